/* test_study_error.c — errors at matched material points (core/record/
 * sb_record_reference.c): every registered method maps the grid parameter
 * (s,t) to the material point xi = sb_domain_map(s,t); two different
 * discretizations of the same exact surface differ by round-off; a
 * reference record of another scene, another problem, another sample grid,
 * an unfinished or an unconverged run is refused with a sentence. */
#include "sb_test.h"
#include "sb_context.h"
#include "sb_geometry.h"
#include "sb_method.h"
#include "sb_record.h"
#include "sb_reference.h"
#include "sb_run.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char tmpdir[256];

/* the n x n sample grid of a run (points inside the domain) */
static int grid(const sb_scene *sc, int n, double *st)
{
    int m = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double s = (double)i / (n - 1), t = (double)j / (n - 1);
            if (!sb_domain_contains_st(&sc->domain, s, t)) continue;
            st[2 * m] = s, st[2 * m + 1] = t, m++;
        }
    return m;
}

/* positions of method mt's reference state at res, mapped by A (3x3, applied
 * to every 3-vector of the dof vector: positions and derivatives alike), at
 * the points st.  Returns 0, or 1 when the method refuses the scene. */
static int sample(const sb_method_type *mt, const sb_scene *sc, int res, const double A[9], int np, const double *st,
                  double *pos)
{
    sb_context ctx;
    if (sb_context_init(&ctx)) return -1;
    sb_paramset_add(&ctx.params, "method", mt->params);
    void *ms = calloc(1, mt->state_size);
    sb_method_config cfg = { .res = res, .levels = 1, .params = &ctx.params, .ctx = &ctx, .res_t = 0 };
    int rc = mt->create(ms, sc, &cfg);
    if (rc == SB_OK) {
        int F = mt->n_levels(ms) - 1, n = mt->n_dofs(ms, F);
        double *x = malloc((size_t)n * sizeof *x);
        mt->initial(ms, F, x);
        for (int b = 0; b + 2 < n; b += 3) {
            double v[3] = { x[b], x[b + 1], x[b + 2] };
            for (int r = 0; r < 3; r++) x[b + r] = A[3 * r] * v[0] + A[3 * r + 1] * v[1] + A[3 * r + 2] * v[2];
        }
        rc = mt->eval_points(ms, F, x, np, st, pos);
        free(x);
    } else {
        rc = 1;
    }
    mt->destroy(ms);
    free(ms);
    sb_context_free(&ctx);
    return rc;
}

static int load(const char *name, sb_scene *sc)
{
    char path[1024], err[2048];
    if (sb_scene_resolve(name, path, sizeof path)) return -1;
    return sb_scene_load(path, sc, err, sizeof err);
}

/* The methods' (s,t) are the scene's: on plane charts the reference surface
 * at (s,t) is chart(sb_domain_map(s,t)) to round-off (rectangle, L-shape);
 * on the cylinder it converges to it. */
SB_TEST(every_method_samples_the_material_point_of_the_scene)
{
    static const double I[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    const char *plane[] = { "trampoline", "reentrant_corner" };
    double st[2 * 441], pos[3 * 441], pos2[3 * 441];
    int tested = 0;
    for (int k = 0; k < sb_method_count(); k++) {
        const sb_method_type *mt = sb_method_at(k);
        if (mt->flags & SB_METHOD_TEST_FIXTURE || !mt->eval_points) continue;
        for (int s = 0; s < 2; s++) {
            sb_scene sc;
            CHECK(load(plane[s], &sc) == 0);
            int np = grid(&sc, 21, st), res = 10;   /* the L-shape's 0.3 m notch needs a multiple of 10 for some methods */
            if (sample(mt, &sc, res, I, np, st, pos) == 0) {
                double worst = 0, diam = sb_domain_diameter(&sc.domain);
                for (int p = 0; p < np; p++) {
                    sb_jet3 X;
                    sb_geometry_eval_st(&sc, st[2 * p], st[2 * p + 1], &X);
                    for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(pos[3 * p + c] - X.x[c]));
                }
                CHECK_MSG(worst <= 1e-13 * diam, "method %s on %s: the reference surface at (s,t) is %.3g m from "
                          "chart(domain_map(s,t))", mt->name, sc.name, worst);
                tested++;
            }
            sb_scene_free(&sc);
        }
        /* cylinder (Scordelis-Lo roof): converges to the chart */
        sb_scene sc;
        CHECK(load("scordelis_lo", &sc) == 0);
        int np = grid(&sc, 21, st);
        double e[2] = { 0, 0 };
        int ok = 1;
        for (int r = 0; r < 2 && ok; r++) {
            ok = sample(mt, &sc, r ? 16 : 8, I, np, st, r ? pos2 : pos) == 0;
            for (int p = 0; ok && p < np; p++) {
                sb_jet3 X;
                sb_geometry_eval_st(&sc, st[2 * p], st[2 * p + 1], &X);
                for (int c = 0; c < 3; c++) e[r] = fmax(e[r], fabs((r ? pos2 : pos)[3 * p + c] - X.x[c]));
            }
        }
        if (ok) CHECK_MSG(e[1] < 0.5 * e[0] || e[1] < 1e-12, "method %s: reference-surface error on the cylinder %.3g "
                          "at res 8, %.3g at res 16 (a parametrization other than the scene's would not converge)",
                          mt->name, e[0], e[1]);
        sb_scene_free(&sc);
    }
    CHECK(tested >= 2);
}

/* x = A X with a rotation and a shear: every method represents it exactly;
 * two methods (and resolutions) then differ at round-off. */
SB_TEST(two_discretizations_of_one_exact_surface_differ_at_round_off)
{
    const double c = cos(0.7), s = sin(0.7);
    const double A[9] = { c, -s, 0.3, s, c, 0.1, 0.2, -0.4, 1 };   /* rotation about z, then shear into z */
    static const char *scenes[] = { "trampoline", "reentrant_corner" };
    double st[2 * 441], pa[3 * 441], pb[3 * 441];
    int pairs = 0;
    for (int q = 0; q < 2; q++) {
        sb_scene sc;
        CHECK(load(scenes[q], &sc) == 0);
        int np = grid(&sc, 21, st);
        double diam = sb_domain_diameter(&sc.domain);
        for (int a = 0; a < sb_method_count(); a++)
            for (int b = 0; b < sb_method_count(); b++) {
                const sb_method_type *ma = sb_method_at(a), *mb = sb_method_at(b);
                if ((ma->flags | mb->flags) & SB_METHOD_TEST_FIXTURE) continue;
                if (sample(ma, &sc, 10, A, np, st, pa) || sample(mb, &sc, 20, A, np, st, pb)) continue;
                double rms, mx;
                sb_field_error(np, pa, pb, diam, &rms, &mx);
                CHECK_MSG(mx < 1e-14 && rms <= mx, "%s res 10 against %s res 20 on %s: max %.3g, rms %.3g", ma->name,
                          mb->name, sc.name, mx, rms);
                /* and both are the exact surface */
                double worst = 0;
                for (int p = 0; p < np; p++) {
                    sb_jet3 X;
                    sb_geometry_eval_st(&sc, st[2 * p], st[2 * p + 1], &X);
                    for (int r = 0; r < 3; r++)
                        worst = fmax(worst, fabs(pa[3 * p + r] - (A[3 * r] * X.x[0] + A[3 * r + 1] * X.x[1] + A[3 * r + 2] * X.x[2])));
                }
                CHECK(worst < 1e-14 * diam);
                pairs++;
            }
        sb_scene_free(&sc);
    }
    CHECK(pairs >= 4);
}

static int run(const char *scene, const char *out, int samples, const char *set1, const char *set2, int stop)
{
    /* rmtr at res 4 holds its clamped edges by a penalty to 3-8 % of the
     * displacement (docs/trust.md): these tests are about references, not
     * about that verdict, so the run records the violation without judging */
    const char *sets[3] = { "run.penalty_tol=0", set1, set2 };
    sb_run_request q;
    memset(&q, 0, sizeof q);
    q.scene = scene, q.method = "rmtr", q.solver = "tr", q.res = 4, q.levels = 1, q.out = out, q.quiet = 1;
    q.sample_n = samples, q.sets = sets, q.n_sets = set2 ? 3 : set1 ? 2 : 1, q.stop_after_steps = stop;
    FILE *devnull = fopen("/dev/null", "w");
    int rc = sb_run_execute(&q, devnull, devnull, NULL);
    fclose(devnull);
    return rc;
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    return strdup(buf);
}

SB_TEST(a_reference_that_does_not_fit_is_refused_with_a_sentence)
{
    char ref[400], other[400], coarse[400], unconv[400], part[400], err[2048];
    snprintf(ref, sizeof ref, "%s/ref.h5", tmpdir);
    snprintf(other, sizeof other, "%s/other.h5", tmpdir);
    snprintf(coarse, sizeof coarse, "%s/coarse.h5", tmpdir);
    snprintf(unconv, sizeof unconv, "%s/unconv.h5", tmpdir);
    snprintf(part, sizeof part, "%s/part.h5", tmpdir);
    CHECK_EQ_INT(run("tests/scenes/trampoline_1step.json", ref, 0, NULL, NULL, 0), 0);
    CHECK_EQ_INT(run("tests/scenes/drooping_1step.json", other, 0, NULL, NULL, 0), 0);
    CHECK_EQ_INT(run("tests/scenes/trampoline_1step.json", coarse, 11, NULL, NULL, 0), 0);
    CHECK_EQ_INT(run("tests/scenes/trampoline_1step.json", unconv, 0, "run.max_iter=1", NULL, 0), 1);
    char *text = slurp("tests/scenes/trampoline_1step.json");
    CHECK(text != NULL);
    if (!text) return;
    sb_scene sc;
    CHECK(sb_scene_parse_string(text, "tests/scenes/trampoline_1step.json", &sc, err, sizeof err) == 0);
    double st[2 * 441];
    int np = grid(&sc, 21, st);
    sb_refrec r;
    /* fits */
    CHECK_MSG(sb_refrec_load(ref, sc.name, text, np, st, &r, err, sizeof err) == 0, "%s", err);
    CHECK(r.n == np && strcmp(r.method, "rmtr") == 0 && isfinite(r.energy));
    sb_refrec_free(&r);
    /* a description or a probe more does not change the problem */
    char *t2 = malloc(strlen(text) + 64);
    const char *d = strstr(text, "\"description\": \"");
    snprintf(t2, strlen(text) + 64, "%.*sX%s", (int)(d - text + 16), text, d + 16);
    CHECK(sb_refrec_load(ref, sc.name, t2, np, st, &r, err, sizeof err) == 0);
    sb_refrec_free(&r);
    /* another scene */
    CHECK(sb_refrec_load(other, sc.name, text, np, st, &r, err, sizeof err) == SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "computed for scene \"drooping_1step\" with another problem") != NULL, "%s", err);
    /* a copy of the scene under another name keeps its reference (as `check`
     * says: the problem decides, not the name) */
    const char *nm = strstr(text, "\"trampoline_1step\"");
    CHECK(nm != NULL);
    if (nm) {
        snprintf(t2, strlen(text) + 64, "%.*s\"my_copy\"%s", (int)(nm - text), text, nm + strlen("\"trampoline_1step\""));
        CHECK_MSG(sb_refrec_load(ref, "my_copy", t2, np, st, &r, err, sizeof err) == 0, "%s", err);
        sb_refrec_free(&r);
    }
    /* the same name, another problem (gravity) */
    const char *g = strstr(text, "-9.81");
    snprintf(t2, strlen(text) + 64, "%.*s-1.62%s", (int)(g - text), text, g + 5);
    CHECK(sb_refrec_load(ref, sc.name, t2, np, st, &r, err, sizeof err) == SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "another problem (/loads differs") != NULL, "%s", err);
    /* another sample grid */
    CHECK(sb_refrec_load(coarse, sc.name, text, np, st, &r, err, sizeof err) == SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "samples 121 material points, the run 441") != NULL, "%s", err);
    double st2[2 * 441];
    memcpy(st2, st, sizeof st2);
    st2[2 * 7] += 1e-3;
    CHECK(sb_refrec_load(ref, sc.name, text, np, st2, &r, err, sizeof err) == SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "sample point 7") != NULL, "%s", err);
    /* a run that did not converge */
    CHECK(sb_refrec_load(unconv, sc.name, text, np, st, &r, err, sizeof err) == SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "did not converge") != NULL, "%s", err);
    /* an unfinished run's checkpoint (drooping_1step has one step: use the
     * 5-step fixture scene) */
    char part_file[420];
    snprintf(part_file, sizeof part_file, "%s.partial", part);
    const char *sets[] = { "run.checkpoint=1e-9" };
    sb_run_request q;
    memset(&q, 0, sizeof q);
    q.scene = "tests/scenes/membrane_dynamic.json", q.method = "fixture_membrane", q.solver = "tr", q.res = 4, q.out = part;
    q.quiet = 1, q.stop_after_steps = 1, q.sets = sets, q.n_sets = 1;
    FILE *devnull = fopen("/dev/null", "w");
    CHECK_EQ_INT(sb_run_execute(&q, devnull, devnull, NULL), SB_EXIT_STOPPED);
    fclose(devnull);
    char *mtext = slurp("tests/scenes/membrane_dynamic.json");
    sb_scene ms;
    CHECK(mtext && sb_scene_parse_string(mtext, "m", &ms, err, sizeof err) == 0);
    int mp = grid(&ms, 21, st);
    CHECK(sb_refrec_load(part_file, ms.name, mtext, mp, st, &r, err, sizeof err) == SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "checkpoint of an unfinished run") != NULL, "%s", err);
    /* no file */
    CHECK(sb_refrec_load("/nonexistent.h5", sc.name, text, np, st, &r, err, sizeof err) != 0);
    CHECK_MSG(strstr(err, "reference /nonexistent.h5 refused") == err, "%s", err);
    sb_scene_free(&ms);
    sb_scene_free(&sc);
    free(mtext);
    free(t2);
    free(text);
}

/* A scene that points at a reference computes the field error in the run. */
SB_TEST(a_run_against_its_reference_record_has_a_field_error)
{
    char ref[400], scene[400], out[400], err[2048];
    snprintf(ref, sizeof ref, "%s/ref2.h5", tmpdir);
    CHECK_EQ_INT(run("tests/scenes/trampoline_1step.json", ref, 0, NULL, NULL, 0), 0);
    char *text = slurp("tests/scenes/trampoline_1step.json");
    CHECK(text != NULL);
    if (!text) return;
    /* the same scene pointing at the record */
    char *r = strstr(text, "\"reference\": {");
    char *end = strchr(r, '}');
    snprintf(scene, sizeof scene, "%s/tramp.json", tmpdir);
    FILE *f = fopen(scene, "w");
    fprintf(f, "%.*s\"reference\": {\"type\": \"file\", \"file\": \"ref2.h5\"}%s", (int)(r - text), text, end + 1);
    fclose(f);
    snprintf(out, sizeof out, "%s/same.h5", tmpdir);
    CHECK_EQ_INT(run(scene, out, 0, NULL, NULL, 0), 0);
    sb_record_summary s;
    CHECK(sb_record_read_summary(out, &s, err, sizeof err) == 0);
    CHECK(s.has_error && strcmp(s.error_kind, "field") == 0);
    CHECK_MSG(s.error_rms < 1e-15 && s.error_max < 1e-15, "the same run against itself: %.3g %.3g", s.error_rms, s.error_max);
    sb_record_summary_free(&s);
    free(text);
}

/* shellbench reference: the record, its self-check at half the resolution,
 * the provenance; an existing reference is not replaced without --force; a
 * run that does not converge leaves no reference */
SB_TEST(the_reference_command_writes_a_record_its_check_and_provenance)
{
    char cmd[1500], p[600];
    snprintf(cmd, sizeof cmd, "%s reference tests/scenes/trampoline_1step.json --method rmtr --solver tr --res 4 --set run.penalty_tol=0 "
             "--out %s/refs/t.h5 > %s/refout.txt 2>&1", sb_test_bin(), tmpdir, tmpdir);
    CHECK_EQ_INT(WEXITSTATUS(system(cmd)), 0);
    snprintf(p, sizeof p, "%s/refs/t.h5", tmpdir);
    CHECK(access(p, F_OK) == 0);
    snprintf(p, sizeof p, "%s/refs/t-check.h5", tmpdir);
    CHECK(access(p, F_OK) == 0);
    snprintf(p, sizeof p, "%s/refs/t.json", tmpdir);
    char *j = slurp(p);
    CHECK(j && strstr(j, "\"self_check\"") && strstr(j, "\"res\": 2") && strstr(j, "\"rms\": ") && !strstr(j, "\"rms\": null") &&
          strstr(j, "\"run.gtol=1e-8\""));
    free(j);
    snprintf(p, sizeof p, "%s/refout.txt", tmpdir);
    j = slurp(p);
    CHECK(j && strstr(j, "point the scene at it: \"reference\": {\"type\": \"file\", \"file\": \""));
    free(j);
    CHECK_EQ_INT(WEXITSTATUS(system(cmd)), 2);   /* exists: not replaced */
    snprintf(cmd, sizeof cmd, "%s reference tests/scenes/trampoline_1step.json --method rmtr --solver tr --res 4 --set run.penalty_tol=0 "
             "--set run.max_iter=1 --out %s/refs/u.h5 > /dev/null 2>&1", sb_test_bin(), tmpdir);
    CHECK_EQ_INT(WEXITSTATUS(system(cmd)), 1);
    snprintf(p, sizeof p, "%s/refs/u.h5", tmpdir);
    CHECK(access(p, F_OK) != 0);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_study_err_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    if (chdir(sb_test_root()) != 0) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(every_method_samples_the_material_point_of_the_scene),
        SB_CASE(two_discretizations_of_one_exact_surface_differ_at_round_off),
        SB_CASE(a_reference_that_does_not_fit_is_refused_with_a_sentence),
        SB_CASE(a_run_against_its_reference_record_has_a_field_error),
        SB_CASE(the_reference_command_writes_a_record_its_check_and_provenance), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
