/* test_a3_adapt.c — adaptive_sqrt3's adaptation (a3_adapt.c): a curved state
 * refines, a flat one coarsens back to the base mesh exactly; total mass is
 * conserved; vertices that stay keep their state; adapting a fully curved
 * sheet again and again reaches the full-resolution mesh (method.adaptive =
 * 0), whose pattern it then equals; a run changes its dofs and counts its
 * adaptations and analyses. */
#include "sb_test.h"
#include "run_json.h"
#include "../methods/adaptive_sqrt3/a3.h"

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

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_refine_coarsen_mass),
        SB_CASE(test_adaptive_reaches_full_pattern),
        SB_CASE(test_adaptive_run),
        SB_CASE(test_resume_full_resolution),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
