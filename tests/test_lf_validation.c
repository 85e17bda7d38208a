/* test_lf_validation.c — linear_fem against analytic references through the
 * run path (sb_run_execute = `shellbench run`) and the CLI: clamped and
 * simply supported plates (with the second-order convergence of the edge
 * directors on alternate and jittered meshes), Scordelis–Lo (linear regime),
 * the heavy cantilever at Gamma = 5, the roll-up under an end moment, and the
 * refusal of a bc the model cannot impose. */
#include "sb_test.h"
#include "sb_run.h"
#include "run_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* one run of `method`; returns the summary (caller decrefs) */
static json_t *run_method(sb_test_state *T, const char *method, const char *scene, int res, int n_sets,
                          const char *const *sets, int *code)
{
    char path[1024];
    if (scene[0] == '/') snprintf(path, sizeof path, "%s", scene);
    else if (strchr(scene, '/')) snprintf(path, sizeof path, "%s/%s", sb_test_root(), scene);
    else snprintf(path, sizeof path, "%s/bench/scenes/%s.json", sb_test_root(), scene);
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = path;
    rq.method = method;
    rq.solver = "lsnewton";
    rq.res = res;
    rq.levels = 1;
    rq.out = "none";
    rq.quiet = 1;
    rq.n_sets = n_sets;
    rq.sets = sets;
    json_t *o = sb_test_run_json(&rq, code);
    CHECK_MSG(o != NULL, "%s --res %d: no summary (exit %d)", scene, res, *code);
    return o;
}

static json_t *run(sb_test_state *T, const char *scene, int res, int n_sets, const char *const *sets, int *code)
{
    return run_method(T, "linear_fem", scene, res, n_sets, sets, code);
}

static double probe(json_t *o, const char *name, const char *key, int comp)
{
    json_t *v = json_object_get(json_object_get(json_object_get(o, "probes"), name), key);
    if (comp >= 0) v = json_array_get(v, (size_t)comp);
    return json_is_number(v) ? json_number_value(v) : NAN;
}

/* relative error of probe `name` at --res res */
static double rel_error(sb_test_state *T, const char *scene, int res, const char *name, int n_sets,
                        const char *const *sets)
{
    int code;
    json_t *o = run(T, scene, res, n_sets, sets, &code);
    if (!o) return NAN;
    CHECK_EQ_INT(code, SB_EXIT_CONVERGED);
    const double e = probe(o, name, "rel_error", -1);
    json_decref(o);
    return e;
}

SB_TEST(test_plate_clamped)
{
    const double e16 = rel_error(T, "plate_clamped", 16, "center", 0, NULL);
    const double e32 = rel_error(T, "plate_clamped", 32, "center", 0, NULL);
    printf("    plate_clamped: error %.3e (16), %.3e (32), order %.2f\n", e16, e32, log2(e16 / e32));
    CHECK_MSG(e32 < 0.03, "clamped plate at --res 32: error %.3g", e32);
    CHECK_MSG(log2(e16 / e32) > 1.8, "clamped plate: order %.2f", log2(e16 / e32));
}

SB_TEST(test_plate_simply_supported)
{
    const double e8 = rel_error(T, "plate_simply_supported", 8, "center", 0, NULL);
    const double e16 = rel_error(T, "plate_simply_supported", 16, "center", 0, NULL);
    printf("    plate_simply_supported: error %.3e (8), %.3e (16), order %.2f\n", e8, e16, log2(e8 / e16));
    CHECK_MSG(e16 < 0.015, "simply supported plate at --res 16: error %.3g", e16);
    CHECK_MSG(log2(e8 / e16) > 1.8, "simply supported plate: order %.2f", log2(e8 / e16));
}

/* edge directors converge on irregular meshes too (the Morley property) */
SB_TEST(test_plate_jitter)
{
    static const char *const sets[] = { "method.mesh=jitter" };
    const double e16 = rel_error(T, "plate_simply_supported", 16, "center", 1, sets);
    const double e32 = rel_error(T, "plate_simply_supported", 32, "center", 1, sets);
    printf("    plate_simply_supported, jitter 0.3: error %.3e (16), %.3e (32)\n", e16, e32);
    CHECK_MSG(e32 < 0.01 && e32 < 0.5 * e16, "jittered simply supported plate: %.3g (16), %.3g (32)", e16, e32);
}

SB_TEST(test_scordelis_lo)
{
    static const char *const sets[] = { "run.gtol=1e-5" };
    const double e = rel_error(T, "bench/bhem/scenes/scordelis_lo_linear.json", 32, "free_edge_mid", 1, sets);
    printf("    scordelis_lo_linear --res 32: error %.3e\n", e);
    CHECK_MSG(e < 0.015, "Scordelis-Lo at --res 32: error %.3g", e);
}

/* heavy cantilever at Gamma = 5: H/W within 1 % of the master curve */
SB_TEST(test_cantilever_gamma5)
{
    static const char *const sets[] = { "method.cells_t=2" };
    const double master = 0.5861695;
    int code;
    json_t *o = run(T, "bench/bhem/scenes/cantilever_G5.json", 16, 1, sets, &code);
    if (!o) return;
    CHECK_EQ_INT(code, SB_EXIT_CONVERGED);
    const double ux = probe(o, "tip", "displacement", 0), uz = probe(o, "tip", "displacement", 2);
    const double hw = -uz / (1.0 + ux);
    printf("    cantilever Gamma = 5, 16 x 2 cells: H/W = %.5f (master curve %.5f)\n", hw, master);
    CHECK_REL(hw, master, 0.01);
    json_decref(o);
}

/* roll-up to a quarter of the ring: tip on the exact arc within 0.1 % */
SB_TEST(test_rollup_quarter)
{
    static const char *const sets[] = { "method.cells_t=1" };
    const double e = rel_error(T, "bench/bhem/scenes/rollup_quarter.json", 16, "tip", 1, sets);
    printf("    rollup_quarter 16 x 1: tip error %.3e\n", e);
    CHECK_MSG(e < 1e-3, "roll-up quarter: tip error %.3g", e);
}

/* the full ring closes with averaged directors (README: edge directors lose
 * the planar path near closure under this end-moment potential) */
SB_TEST(test_rollup_full_average)
{
    static const char *const sets[] = { "method.cells_t=1", "method.director=average" };
    const double e = rel_error(T, "bench/bhem/scenes/rollup_full.json", 16, "tip", 2, sets);
    printf("    rollup_full 16 x 1, averaged directors: tip error %.3e\n", e);
    CHECK_MSG(e < 0.01, "ring closure: tip error %.3g", e);
}

/* The crossed mesh on a wide annulus sector (issue 21): the annulus_open
 * setup over 240 deg at --res 8 (30-deg cells) failed its line search at the
 * first iteration (inverted centre triangles, test_mesh.c); it converges to
 * bhem's end deflection (0.0307 at --res 8) within 1 %. */
SB_TEST(test_crossed_wide_sector)
{
    char src[1024];
    snprintf(src, sizeof src, "%s/tests/scenes/annulus_open.json", sb_test_root());
    FILE *in = fopen(src, "r");
    CHECK(in != NULL);
    if (!in) return;
    char text[4096];
    size_t n = fread(text, 1, sizeof text - 1, in);
    text[n] = 0;
    fclose(in);
    /* 359.9 -> 240, the probe on the new end's mid-line */
    char *th = strstr(text, "\"theta\""), *at = strstr(text, "0.749998857675");
    CHECK(th && at);
    if (th) th = strstr(th, "359.9");
    if (!th || !at) return;
    const char *path = "/tmp/sb_test_lf_sector240.json";
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fwrite(text, 1, (size_t)(th - text), f);
    fputs("240", f);
    char *rest = th + 5, *close = strchr(at, ']');
    fwrite(rest, 1, (size_t)(at - rest), f);
    fputs("-0.3761330528695933, -0.6488635654272782", f);
    fputs(close, f);
    fclose(f);
    const char *sets[] = { "method.mesh=crossed" };
    int code;
    json_t *o = run(T, path, 8, 1, sets, &code);
    if (o) {
        CHECK_EQ_INT(code, SB_EXIT_CONVERGED);
        const double w = probe(o, "end_mid", "displacement", 2);
        printf("    240-deg sector, 8 x 8 crossed: end deflection %.5g (bhem --res 8: 0.03072)\n", w);
        CHECK_MSG(fabs(w - 0.03072) < 0.01 * 0.03072, "end deflection %g", w);
        json_decref(o);
    }
    remove(path);
}

/* A full annulus clamped on `start` and loaded on `end` (issue 21): the mesh
 * layer merged the seam and linear_fem refused the scene ("the part has no
 * boundary edge in the mesh").  The seam now stays open, as in bhem: the slit
 * annulus is the limit of the 359.9-degree sector, and its end deflection
 * approaches bhem's under refinement (+8 % at --res 8, +2 % at 16). */
SB_TEST(test_slit_annulus)
{
    int code;
    json_t *a = run(T, "tests/scenes/annulus_slit.json", 8, 0, NULL, &code);
    json_t *b = run(T, "tests/scenes/annulus_open.json", 8, 0, NULL, &code);
    json_t *c = run(T, "tests/scenes/annulus_slit.json", 16, 0, NULL, &code);
    json_t *h = run_method(T, "bhem", "tests/scenes/annulus_slit.json", 8, 0, NULL, &code);
    if (a && b && c && h) {
        CHECK(strcmp(json_string_value(json_object_get(a, "status")), "converged") == 0);
        const char *info = json_string_value(json_object_get(a, "method_info"));
        CHECK_MSG(info && strstr(info, "slit"), "method_info: %s", info ? info : "?");
        const double wa = probe(a, "end_mid", "displacement", 2), wb = probe(b, "end_mid", "displacement", 2);
        const double wc = probe(c, "end_mid", "displacement", 2), wh = probe(h, "end_mid", "displacement", 2);
        printf("    end deflection: slit %.5g (--res 8), %.5g (16); 359.9 deg %.5g; bhem %.5g\n", wa, wc, wb, wh);
        CHECK_MSG(wa > 0.01, "slit annulus: w = %g", wa);
        CHECK_MSG(fabs(wa - wb) < 1e-3 * wb, "slit %g, open sector %g", wa, wb);
        CHECK_MSG(fabs(wc - wh) < fabs(wa - wh) / 2 && fabs(wc - wh) < 0.03 * wh, "--res 8 %g, 16 %g, bhem %g", wa, wc, wh);
    }
    json_decref(a); json_decref(b); json_decref(c); json_decref(h);
}

/* a bc the model cannot impose is refused before any work, exit 2, one sentence */
SB_TEST(test_refusal)
{
    const char *path = "/tmp/sb_test_lf_refusal.json";
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fputs("{\"name\": \"clamped_point\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1]},"
          " \"material\": {\"model\": \"stvk\", \"young\": 1e5, \"poisson\": 0.3, \"thickness\": 0.01, \"density\": 1},"
          " \"boundary\": [{\"type\": \"clamped\", \"at\": [0, 0]}], \"loads\": [{\"type\": \"gravity\", \"acceleration\": [0, 0, -1]}],"
          " \"time\": {\"mode\": \"quasi_static\", \"steps\": 1}}", f);
    fclose(f);
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s run --scene %s --method linear_fem --solver lsnewton --res 4 --out none 2>&1", sb_test_bin(), path);
    FILE *p = popen(cmd, "r");
    CHECK(p != NULL);
    if (!p) return;
    char buf[4096];
    size_t n = fread(buf, 1, sizeof buf - 1, p);
    buf[n] = 0;
    int st = pclose(p);
    CHECK_MSG(WIFEXITED(st) && WEXITSTATUS(st) == 2, "exit %d: %s", WEXITSTATUS(st), buf);
    CHECK_MSG(strstr(buf, "boundary[0]") && strstr(buf, "clamped") && strstr(buf, "linear_fem") && !strstr(buf, "step 1"),
              "message: %s", buf);
    remove(path);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_plate_clamped), SB_CASE(test_plate_simply_supported), SB_CASE(test_plate_jitter),
        SB_CASE(test_scordelis_lo), SB_CASE(test_cantilever_gamma5), SB_CASE(test_rollup_quarter),
        SB_CASE(test_rollup_full_average), SB_CASE(test_crossed_wide_sector), SB_CASE(test_slit_annulus), SB_CASE(test_refusal), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
