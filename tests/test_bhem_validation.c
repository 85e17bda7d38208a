/* test_bhem_validation.c — BHEM against analytic references through the
 * real run path (sb_run_execute = `shellbench run`) and the CLI binary:
 * clamped and simply supported square plates (<= 8x8 patches, within 1 %),
 * Scordelis–Lo roof (8x8 patches, within 1.5 % of 0.3006, linear regime). */
#include "sb_test.h"
#include "sb_run.h"
#include "sb_method.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Runs a scene of bench/bhem/scenes and returns the parsed summary (or NULL). */
static json_t *run_scene(sb_test_state *T, const char *scene, const char *solver, int res,
                         int n_sets, const char *const *sets, int *exit_code)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/bench/bhem/scenes/%s.json", sb_test_root(), scene);
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = path;
    rq.method = "bhem";
    rq.solver = solver;
    rq.res = res;
    rq.levels = 1;
    rq.out = "none";
    rq.quiet = 1;
    rq.n_sets = n_sets;
    rq.sets = sets;
    char *js = NULL;
    FILE *devnull = fopen("/dev/null", "w");
    *exit_code = sb_run_execute(&rq, devnull ? devnull : stdout, stderr, &js);
    if (devnull) fclose(devnull);
    CHECK_MSG(js != NULL, "%s: no summary (exit %d)", scene, *exit_code);
    if (!js) return NULL;
    json_error_t err;
    json_t *o = json_loads(js, 0, &err);
    free(js);
    return o;
}

static double probe_field(json_t *o, const char *probe, const char *key)
{
    json_t *p = json_object_get(json_object_get(o, "probes"), probe);
    json_t *v = json_object_get(p, key);
    return json_is_number(v) ? json_number_value(v) : NAN;
}

static void check_probe(sb_test_state *T, const char *scene, int res, const char *probe, double tol,
                        int n_sets, const char *const *sets)
{
    CHECK_MSG(sb_method_find("bhem") != NULL, "method bhem is not registered (core/problem/sb_registry.c: &sb_method_bhem)");
    if (!sb_method_find("bhem")) return;
    int code;
    json_t *o = run_scene(T, scene, "lsnewton", res, n_sets, sets, &code);
    if (!o) return;
    CHECK_EQ_INT(code, SB_EXIT_CONVERGED);
    double rel = probe_field(o, probe, "rel_error");
    CHECK_MSG(rel <= tol, "%s at --res %d: probe %s relative error %.4g > %.4g", scene, res, probe, rel, tol);
    printf("    %s --res %d: %s rel_error %.3e\n", scene, res, probe, rel);
    json_decref(o);
}

SB_TEST(test_plate_clamped) { check_probe(T, "plate_clamped", 8, "center", 0.01, 0, NULL); }
SB_TEST(test_plate_simply_supported) { check_probe(T, "plate_simply_supported", 8, "center", 0.01, 0, NULL); }

/* The roof's gradient cannot go below ~1e-6 (round-off of Y h = 1e8 N/m
 * membrane forces) while the scaled load starts at |g| ~ 0.04: gtol 1e-5. */
SB_TEST(test_scordelis_lo)
{
    static const char *const sets[] = { "run.gtol=1e-5" };
    check_probe(T, "scordelis_lo_linear", 8, "free_edge_mid", 0.015, 1, sets);
}

/* Roll-up under an end moment at M/M_max = 0.25: tip on the exact circular
 * arc (tip rotation m L / B = pi/2), within 1 % (8 patches along the strip). */
SB_TEST(test_rollup_quarter)
{
    static const char *const sets[] = { "method.cells_t=1" };
    check_probe(T, "rollup_quarter", 8, "tip", 0.01, 1, sets);
}

/* Heavy cantilever at Gamma = 5: H/W within 2 % of the master curve
 * (../shared/reference/cantilever_master_curve.csv, log-interpolated). */
SB_TEST(test_cantilever_gamma5)
{
    static const char *const sets[] = { "method.cells_t=1" };
    const double master = 0.5861695;   /* H/W at Gamma = 5 */
    CHECK(sb_method_find("bhem") != NULL);
    if (!sb_method_find("bhem")) return;
    int code;
    json_t *o = run_scene(T, "cantilever_G5", "lsnewton", 8, 1, sets, &code);
    if (!o) return;
    CHECK_EQ_INT(code, SB_EXIT_CONVERGED);
    json_t *u = json_object_get(json_object_get(json_object_get(o, "probes"), "tip"), "displacement");
    double ux = json_number_value(json_array_get(u, 0)), uz = json_number_value(json_array_get(u, 2));
    double hw = -uz / (1.0 + ux);
    printf("    cantilever Gamma = 5, 8x1 patches: H/W = %.5f (master curve %.5f, %+.2f %%)\n", hw, master,
           100 * (hw / master - 1));
    CHECK_REL(hw, master, 0.02);
    json_decref(o);
}

/* The CLI contract: exit code 0 and a JSON summary on stdout. */
SB_TEST(test_cli_summary)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s run --scene %s/bench/bhem/scenes/plate_clamped.json --method bhem --solver tr "
             "--res 4 --out none --summary json 2>/dev/null", sb_test_bin(), sb_test_root());
    FILE *p = popen(cmd, "r");
    CHECK(p != NULL);
    if (!p) return;
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, p);
    buf[n] = 0;
    int st = pclose(p);
    CHECK_MSG(WIFEXITED(st) && WEXITSTATUS(st) == 0, "exit status %d, output: %.300s", st, buf);
    json_error_t err;
    json_t *o = json_loads(buf, 0, &err);
    CHECK_MSG(o != NULL, "summary is not JSON: %.300s", buf);
    if (!o) return;
    CHECK(strcmp(json_string_value(json_object_get(o, "method")), "bhem") == 0);
    CHECK_EQ_INT(json_integer_value(json_object_get(o, "dofs")), 12 * 25);
    CHECK(probe_field(o, "center", "rel_error") < 0.01);
    json_decref(o);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_plate_clamped), SB_CASE(test_plate_simply_supported), SB_CASE(test_scordelis_lo),
        SB_CASE(test_rollup_quarter), SB_CASE(test_cantilever_gamma5), SB_CASE(test_cli_summary), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
