/* test_a3_adapt.c — adaptive_sqrt3's adaptation (a3_adapt.c): a curved state
 * refines, a flat one coarsens back to the base mesh exactly; total mass is
 * conserved; vertices that stay keep their state; adapting a fully curved
 * sheet again and again reaches the full-resolution mesh (method.adaptive =
 * 0), whose pattern it then equals; a run changes its dofs and counts its
 * adaptations and analyses. */
#include "sb_test.h"
#include "run_json.h"
#include "../methods/adaptive_sqrt3/a3.h"
#include "sb_context.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *SCENE =
    "{\"name\": \"t\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1.5]},"
    " \"geometry\": {\"type\": \"plane\"}, \"material\": {\"model\": \"stvk\", \"young\": 1e6, \"poisson\": 0.33,"
    " \"thickness\": 0.001, \"density\": 0.1}, \"loads\": [{\"type\": \"gravity\", \"acceleration\": [0, -9.81, -5]}],"
    " \"boundary\": [{\"type\": \"fixed\", \"at\": [0, 1.5]}],"
    " \"time\": {\"mode\": \"dynamic\", \"dt\": 0.005, \"steps\": 40}, \"probes\": [{\"name\": \"p\", \"at\": [0.5, 0]}]}";

typedef struct am { sb_scene scene; sb_paramset ps; a3_state *S; } am;

static int am_create(am *m, int res, const char *const *sets)
{
    char err[1024];
    memset(m, 0, sizeof *m);
    if (sb_scene_parse_string(SCENE, "inline.json", &m->scene, err, sizeof err)) return SB_ERR_INPUT;
    sb_paramset_init(&m->ps);
    sb_paramset_add(&m->ps, "method", sb_method_adaptive_sqrt3.params);
    for (int i = 0; sets && sets[i]; i++)
        if (sb_paramset_set(&m->ps, sets[i], err, sizeof err)) { printf("    %s\n", err); return SB_ERR_INPUT; }
    m->S = calloc(1, sb_method_adaptive_sqrt3.state_size);
    sb_method_config cfg = { res, 1, &m->ps, NULL, 0 };
    int rc = sb_method_adaptive_sqrt3.create(m->S, &m->scene, &cfg);
    if (rc) { free(m->S); m->S = NULL; }
    return rc;
}

static void am_free(am *m)
{
    if (m->S) { sb_method_adaptive_sqrt3.destroy(m->S); free(m->S); }
    sb_scene_free(&m->scene);
}

/* the sheet rolled about the s axis with curvature kappa (1/m) */
static void rolled(const a3_state *S, double kappa, double *x)
{
    for (int v = 0; v < S->nv; v++) {
        const double X = S->x_ref[3 * v], Y = S->x_ref[3 * v + 1], R = 1 / kappa;
        x[3 * v] = R * sin(X / R);
        x[3 * v + 1] = Y;
        x[3 * v + 2] = R * (1 - cos(X / R));
    }
}

static double total_mass(const a3_state *S)
{
    double m = 0;
    for (int v = 0; v < S->nv; v++) m += S->mass[v];
    return m;
}

static int cmp(const void *x, const void *y)
{
    const double *a = x, *b = y;
    for (int i = 0; i < 4; i++) {
        if (a[i] < b[i] - 1e-12) return -1;
        if (a[i] > b[i] + 1e-12) return 1;
    }
    return 0;
}

/* the sorted (s,t) pairs of a method's pattern blocks */
static int pattern_pairs(const a3_state *S, double **out)
{
    sb_pattern_builder *pb = sb_pattern_builder_new(S->nv, 3);
    sb_method_adaptive_sqrt3.pattern(S, 0, pb);
    sb_pattern *p = NULL;
    sb_pattern_builder_finish(pb, &p);
    long n = 0;
    for (int c = 0; c < p->n; c += 3)
        for (long q = p->colptr[c]; q < p->colptr[c + 1]; q++) n += p->rowind[q] % 3 == 0;
    double *a = malloc(sizeof(double) * 4 * (size_t)n);
    long k = 0;
    for (int c = 0; c < p->n; c += 3)
        for (long q = p->colptr[c]; q < p->colptr[c + 1]; q++) {
            const int r = p->rowind[q];
            if (r % 3) continue;
            const double *u = S->mesh.st + 2 * (r / 3), *w = S->mesh.st + 2 * (c / 3);
            double *e = a + 4 * k++;
            /* order-free key: the smaller point first */
            const int sw = u[0] > w[0] || (u[0] == w[0] && u[1] > w[1]);
            e[0] = sw ? w[0] : u[0]; e[1] = sw ? w[1] : u[1]; e[2] = sw ? u[0] : w[0]; e[3] = sw ? u[1] : w[1];
        }
    sb_pattern_free(p);
    qsort(a, (size_t)n, 4 * sizeof(double), cmp);
    *out = a;
    return (int)n;
}


SB_TEST(test_refine_coarsen_mass)
{
    am m;
    const char *sets[] = { "method.max_generation=4", NULL };
    CHECK(am_create(&m, 4, sets) == SB_OK);
    if (!m.S) return;
    a3_state *S = m.S;
    const int nt0 = S->nt, nv0 = S->nv;
    const double mass0 = total_mass(S);
    CHECK_REL(mass0, 0.1 * 1.5, 1e-13);
    int *tri0 = malloc(sizeof(int) * 3 * nt0);
    memcpy(tri0, S->mesh.tri, sizeof(int) * 3 * nt0);
    /* rolled with curvature 10/m: above every limit of Eq. 23 up to generation 4 (2 + 18 g/4) */
    double *x = malloc(sizeof(double) * S->n_dofs), *v = calloc(S->n_dofs, sizeof(double));
    rolled(S, 10.0, x);
    for (int i = 0; i < S->n_dofs; i++) v[i] = 0.1 * x[i];
    int changed = 0;
    CHECK(a3_adapt(S, x, v, &changed) == SB_OK);
    CHECK(changed);
    printf("    rolled: %d -> %d triangles\n", nt0, S->nt);
    CHECK(S->nt > nt0);
    CHECK_REL(total_mass(S), mass0, 1e-12);
    /* vertices that stay keep their state (base vertices keep their index) */
    double *xn = malloc(sizeof(double) * S->n_dofs), *vn = malloc(sizeof(double) * S->n_dofs);
    CHECK(a3_adapt_state(S, xn, vn) == SB_OK);
    for (int i = 0; i < 3 * nv0; i++) {
        CHECK(xn[i] == x[i]);
        CHECK(vn[i] == v[i]);
    }
    /* inserted vertices lie on the rolled surface's chords: within h^2 kappa of the cylinder */
    double dev = 0;
    for (int i = nv0; i < S->nv; i++) {
        const double R = 0.1, px = xn[3 * i], pz = xn[3 * i + 2];
        dev = fmax(dev, fabs(sqrt(px * px + (pz - R) * (pz - R)) - R));
    }
    CHECK_MSG(dev < 0.25 * 0.25 * 10.0, "inserted vertices %g off the cylinder", dev);
    /* flat again: everything coarsens back to the base mesh, exactly */
    for (int pass = 0; pass < 6 && S->nt > nt0; pass++) {
        double *xf = malloc(sizeof(double) * S->n_dofs), *vf = calloc(S->n_dofs, sizeof(double));
        memcpy(xf, S->x_ref, sizeof(double) * S->n_dofs);
        CHECK(a3_adapt(S, xf, vf, &changed) == SB_OK);
        free(xf);
        free(vf);
        CHECK_REL(total_mass(S), mass0, 1e-12);
    }
    CHECK_EQ_INT(S->nt, nt0);
    CHECK_EQ_INT(S->nv, nv0);
    if (S->nt == nt0) CHECK(!memcmp(tri0, S->mesh.tri, sizeof(int) * 3 * nt0));
    free(tri0); free(x); free(v); free(xn); free(vn);
    am_free(&m);
}

SB_TEST(test_adaptive_reaches_full_pattern)
{
    am a, f;
    const char *sa[] = { "method.max_generation=4", "method.curv_base=0", "method.curv_max=0", NULL };
    const char *sf[] = { "method.max_generation=4", "method.adaptive=0", NULL };
    CHECK(am_create(&a, 2, sa) == SB_OK);
    CHECK(am_create(&f, 2, sf) == SB_OK);
    if (!a.S || !f.S) return;
    for (int pass = 0; pass < 12; pass++) {
        double *x = malloc(sizeof(double) * a.S->n_dofs), *v = calloc(a.S->n_dofs, sizeof(double));
        rolled(a.S, 3.0, x);
        int changed = 0;
        CHECK(a3_adapt(a.S, x, v, &changed) == SB_OK);
        free(x);
        free(v);
        if (!changed) break;
    }
    printf("    adaptive %d triangles, full resolution %d\n", a.S->nt, f.S->nt);
    CHECK_EQ_INT(a.S->nt, f.S->nt);
    CHECK_EQ_INT(a.S->nv, f.S->nv);
    double *pa = NULL, *pf = NULL;
    const int na = pattern_pairs(a.S, &pa), nf = pattern_pairs(f.S, &pf);
    CHECK_EQ_INT(na, nf);
    int same = na == nf;
    for (int k = 0; same && k < 4 * na; k++) same = fabs(pa[k] - pf[k]) < 1e-12;
    CHECK_MSG(same, "the adapted pattern differs from the full-resolution one built from scratch");
    free(pa);
    free(pf);
    am_free(&a);
    am_free(&f);
}

/* a short run: the hanging sheet folds, the mesh adapts, everything is counted */
SB_TEST(test_adaptive_run)
{
    char path[256];
    snprintf(path, sizeof path, "/tmp/sb_test_a3_adapt_%d.json", (int)getpid());
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (!fp) return;
    fputs(SCENE, fp);
    fclose(fp);
    const char *sets[] = { "method.max_generation=4", "method.curv_base=0.01", "method.curv_max=0.1", "run.single_step_rtol=1e300", NULL };
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = path;
    rq.method = "adaptive_sqrt3";
    rq.solver = "linearized";
    rq.res = 4;
    rq.out = "none";
    rq.quiet = 1;
    rq.n_sets = 4;
    rq.sets = sets;
    int code = -1;
    json_t *o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 0);
    if (o) {
        json_t *c = json_object_get(o, "counts");
        const long ad = (long)json_integer_value(json_object_get(c, "adapt"));
        const long an = (long)json_integer_value(json_object_get(c, "analyze"));
        const long dofs = (long)json_integer_value(json_object_get(o, "dofs"));
        printf("    40 steps: %ld adaptations, %ld analyses, final %ld dofs (base 3 x 25)\n", ad, an, dofs);
        CHECK_EQ_INT(ad, 7);
        CHECK(an > 1 && dofs != 75);
        json_decref(o);
    }
    remove(path);
}

/* full resolution keeps its mesh: stopped and resumed equals uninterrupted */
SB_TEST(test_resume_full_resolution)
{
    char path[256], out1[256], out2[256];
    snprintf(path, sizeof path, "/tmp/sb_test_a3_res_%d.json", (int)getpid());
    snprintf(out1, sizeof out1, "/tmp/sb_test_a3_res1_%d.h5", (int)getpid());
    snprintf(out2, sizeof out2, "/tmp/sb_test_a3_res2_%d.h5", (int)getpid());
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (!fp) return;
    fputs(SCENE, fp);
    fclose(fp);
    const char *sets[] = { "method.max_generation=2", "method.adaptive=0", "run.single_step_rtol=1e300", NULL };
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = path;
    rq.method = "adaptive_sqrt3";
    rq.solver = "linearized";
    rq.res = 4;
    rq.quiet = 1;
    rq.n_sets = 3;
    rq.sets = sets;
    int code = -1;
    double z[2][3] = { { 0 } };
    rq.out = out1;
    json_t *o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 0);
    if (o) {
        json_t *d = json_object_get(json_object_get(json_object_get(o, "probes"), "p"), "position");
        for (int c = 0; c < 3; c++) z[0][c] = json_number_value(json_array_get(d, c));
        json_decref(o);
    }
    rq.out = out2;
    rq.stop_after_steps = 13;
    o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 4);
    if (o) json_decref(o);
    rq.stop_after_steps = 0;
    rq.resume = 1;
    o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 0);
    if (o) {
        json_t *d = json_object_get(json_object_get(json_object_get(o, "probes"), "p"), "position");
        for (int c = 0; c < 3; c++) z[1][c] = json_number_value(json_array_get(d, c));
        json_decref(o);
    }
    for (int c = 0; c < 3; c++) CHECK(z[0][c] == z[1][c]);
    CHECK(fabs(z[0][2]) > 1e-4);
    /* adaptive runs resume too: tests/test_a3_resume.c */
    remove(path);
    for (int k = 0; k < 2; k++) {
        char side[300];
        const char *o5 = k ? out2 : out1;
        remove(o5);
        snprintf(side, sizeof side, "%.*s.xdmf", (int)strlen(o5) - 3, o5);
        remove(side);
        snprintf(side, sizeof side, "%.*s.steps.xdmf", (int)strlen(o5) - 3, o5);
        remove(side);
        snprintf(side, sizeof side, "%.*s.mesh.xdmf", (int)strlen(o5) - 3, o5);
        remove(side);
    }
}

/* Eq. 22's |c| is the mean-curvature normal's length, kappa_1 + kappa_2 =
 * 2H (Meyer et al.): 2/R on a sphere of radius R, 1/R on a cylinder.  So a
 * sphere's cap exceeds every Eq. 23 limit below 2/R (the cloth over a
 * sphere of radius 0.15 m: 13.3 /m, results/sqrt3_report.md). */
SB_TEST(test_curvature_sphere_and_cylinder)
{
    am m;
    const char *sets[] = { "method.max_generation=4", NULL };
    CHECK(am_create(&m, 24, sets) == SB_OK);
    if (!m.S) return;
    a3_state *S = m.S;
    double *x = malloc(sizeof(double) * S->n_dofs), *c = malloc(sizeof(double) * S->nv);
    const double R = 2.0;
    /* the sheet projected vertically onto the sphere of radius R through its centre */
    for (int v = 0; v < S->nv; v++) {
        const double u = S->x_ref[3 * v] - 0.5, w = S->x_ref[3 * v + 1] - 0.75;
        x[3 * v] = u, x[3 * v + 1] = w, x[3 * v + 2] = R - sqrt(R * R - u * u - w * w);
    }
    CHECK(a3_curvature(S, x, c) == SB_OK);
    double mean = 0, dev = 0;
    int n = 0;
    for (int v = 0; v < S->nv; v++) {
        if (S->mesh.vflag[v] & SB_MESH_V_BOUNDARY) { CHECK(c[v] == 0.0); continue; }
        mean += c[v], n++;
        dev = fmax(dev, fabs(c[v] - 2.0 / R));
    }
    mean /= n;
    printf("    sphere R = %g: mean |c| %.5f (2/R = %g), largest deviation %.3g over %d interior vertices\n", R, mean,
           2.0 / R, dev, n);
    CHECK_REL(mean, 2.0 / R, 0.02);
    CHECK_MSG(dev < 0.1 * 2.0 / R, "largest deviation %g from 2/R", dev);
    /* the cylinder of radius 1/kappa: |c| = kappa */
    rolled(S, 0.5, x);
    CHECK(a3_curvature(S, x, c) == SB_OK);
    mean = 0, n = 0, dev = 0;
    for (int v = 0; v < S->nv; v++)
        if (!(S->mesh.vflag[v] & SB_MESH_V_BOUNDARY)) mean += c[v], n++, dev = fmax(dev, fabs(c[v] - 0.5));
    mean /= n;
    printf("    cylinder R = 2: mean |c| %.5f (1/R = 0.5), largest deviation %.3g\n", mean, dev);
    CHECK_REL(mean, 0.5, 0.02);
    CHECK_MSG(dev < 0.05, "largest deviation %g from 1/R", dev);
    /* flat: zero */
    CHECK(a3_curvature(S, S->x_ref, c) == SB_OK);
    for (int v = 0; v < S->nv; v++) CHECK_MSG(fabs(c[v]) < 1e-9, "flat sheet: |c| = %g at vertex %d", c[v], v);
    free(x); free(c);
    am_free(&m);
}

/* Limits that cannot work are refused before any work with a sentence
 * naming the key (issue 40): decreasing Eq. 23 limits, a coarsening limit
 * at or above the refinement limit, and more generations than the fully
 * refined base mesh fits in memory (the estimate op, which runs first). */
SB_TEST(test_limits_refused)
{
    am m;
    static const struct { const char *set, *key; } bad[] = {
        { "method.curv_max=1", "method.curv_max" },
        { "method.coarsen_fraction=1", "method.coarsen_fraction" },
    };
    for (int k = 0; k < 2; k++) {
        const char *sets[] = { bad[k].set, NULL };
        CHECK_EQ_INT(am_create(&m, 4, sets), SB_ERR_INPUT);
        CHECK(m.S == NULL);
        am_free(&m);
    }
    /* the same through the estimate op (before create), and the sentence */
    sb_scene sc;
    char err[1024];
    CHECK(sb_scene_parse_string(SCENE, "inline.json", &sc, err, sizeof err) == SB_OK);
    static const struct { const char *set; int res, ok; const char *key; } cases[] = {
        { "method.curv_max=1", 4, 0, "method.curv_max = 1 is below method.curv_base = 2" },
        { "method.coarsen_fraction=1", 4, 0, "method.coarsen_fraction = 1" },
        { "method.max_generation=20", 64, 0, "method.max_generation = 20" },
        { "method.max_generation=6", 64, 1, NULL },
        { "method.coarsen_fraction=0.99", 4, 1, NULL },
        { "method.curv_max=2", 4, 1, NULL },
    };
    for (int k = 0; k < 6; k++) {
        sb_context ctx;
        CHECK(sb_context_init(&ctx) == SB_OK);
        sb_paramset_add(&ctx.params, "method", sb_method_adaptive_sqrt3.params);
        CHECK(sb_paramset_set(&ctx.params, cases[k].set, err, sizeof err) == SB_OK);
        sb_method_config cfg = { cases[k].res, 1, &ctx.params, &ctx, 0 };
        sb_method_size sz;
        const int rc = sb_method_adaptive_sqrt3.estimate(&sc, &cfg, &sz);
        if (cases[k].ok) CHECK_MSG(rc == SB_OK, "%s: refused: %s", cases[k].set, ctx.err);
        else {
            CHECK_EQ_INT(rc, SB_ERR_INPUT);
            CHECK_MSG(strstr(ctx.err, cases[k].key) != NULL, "%s: the sentence does not name the key: %s",
                      cases[k].set, ctx.err);
            printf("    %s: %s\n", cases[k].set, ctx.err);
        }
        sb_context_free(&ctx);
    }
    sb_scene_free(&sc);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_refine_coarsen_mass),
        SB_CASE(test_adaptive_reaches_full_pattern),
        SB_CASE(test_adaptive_run),
        SB_CASE(test_resume_full_resolution),
        SB_CASE(test_curvature_sphere_and_cylinder),
        SB_CASE(test_limits_refused),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
