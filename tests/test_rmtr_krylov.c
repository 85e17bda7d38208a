/* test_rmtr_krylov.c — the rmtr solver's Krylov acceleration (solver.krylov,
 * issue 38; core/solvers/rmtr.c krylov_iterate, docs/krylov.md):
 *   - off is the plain RMTR path bit for bit (iterations, f, ||g||, work
 *     units, probe positions equal to the last bit);
 *   - auto and always (and auto with krylov_boundary=krylov on the
 *     trampoline) converge to the known minimizer: on the clamped plate
 *     (bhem) the probe is the discrete minimizer of lsnewton + CHOLMOD to
 *     1e-6 relative and the analytic Kirchhoff deflection to the scene's
 *     tolerance; on the trampoline (rmtr method) the probes of TR with exact
 *     (dogleg) Newton steps to 1e-6 m; Krylov steps were taken (CG
 *     iterations counted);
 *   - krylov_boundary=krylov follows an accepted boundary Krylov step by
 *     another Krylov step, the default never does (record history);
 *   - a hierarchy without Galerkin coarse operators is refused before any
 *     work with a sentence naming solver.krylov.
 * No timing is asserted. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <unistd.h>

#include "h5_read.h"
#include "run_json.h"
#include "sb_run.h"
#include "sb_test.h"

/* set: NULL, or one or two --set KEY=VALUE separated by a space; out: the
 * record's path, NULL for none */
static json_t *run_out(const char *scene, const char *method, const char *solver, int res, int levels, const char *set,
                       const char *out, int *exit_code)
{
    sb_run_request req;
    sb_test_request(&req, scene, method, solver, res);
    if (out) req.out = out;
    req.levels = levels;
    req.summary_json = 1;
    char buf[256] = "";
    const char *sets[2] = { NULL, NULL };
    int n = 0;
    if (set) {
        snprintf(buf, sizeof buf, "%s", set);
        char *sp = strchr(buf, ' ');
        if (sp) *sp = '\0';
        sets[n++] = buf;
        if (sp) sets[n++] = sp + 1;
    }
    req.sets = sets;
    req.n_sets = n;
    return sb_test_run_json(&req, exit_code);
}

static json_t *run(const char *scene, const char *method, const char *solver, int res, int levels, const char *set,
                   int *exit_code)
{
    return run_out(scene, method, solver, res, levels, set, NULL, exit_code);
}

/* a column of /history/iterations, NULL when absent */
static double *hist(hid_t f, const char *name, size_t *n)
{
    char path[128];
    snprintf(path, sizeof path, "/history/iterations/%s", name);
    return sb_test_h5_doubles(f, path, n, NULL);
}

static double num(json_t *o, const char *a, const char *b)
{
    json_t *v = json_object_get(o, a);
    if (b) v = json_object_get(v, b);
    return json_number_value(v);
}

static double probe(json_t *r, const char *name, int c)
{
    json_t *pr = json_object_get(json_object_get(r, "probes"), name);
    return json_number_value(json_array_get(json_object_get(pr, "position"), c));
}

static int cg_iters(json_t *r)
{
    return (int)json_integer_value(json_object_get(json_object_get(r, "counts"), "cg_iter"));
}

SB_TEST(krylov_off_is_the_plain_path_bit_for_bit)
{
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/trampoline_1step.json", sb_test_root());
    for (int levels = 2; levels <= 3; levels++) {
        int e0, e1;
        json_t *a = run(scene, "rmtr", "rmtr", 4 << (levels - 1), levels, NULL, &e0);
        json_t *b = run(scene, "rmtr", "rmtr", 4 << (levels - 1), levels, "solver.krylov=off", &e1);
        CHECK(a && b);
        if (a && b) {
            CHECK_EQ_INT(e0, 0);
            CHECK_EQ_INT(e1, 0);
            CHECK_EQ_INT((int)num(a, "iterations", NULL), (int)num(b, "iterations", NULL));
            CHECK(num(a, "f", NULL) == num(b, "f", NULL));
            CHECK(num(a, "gnorm", NULL) == num(b, "gnorm", NULL));
            CHECK(num(a, "work_units", "assembly") == num(b, "work_units", "assembly"));
            CHECK(num(a, "work_units", "qp") == num(b, "work_units", "qp"));
            for (int c = 0; c < 3; c++) CHECK(probe(a, "center", c) == probe(b, "center", c));
            CHECK_EQ_INT(cg_iters(a), cg_iters(b));
        }
        json_decref(a);
        json_decref(b);
    }
}

/* The clamped plate (bhem, Kirchhoff reference in the scene): the V-cycle
 * preconditioner is nearly exact there, so always reaches the minimizer in
 * a few Krylov steps. */
SB_TEST(krylov_reaches_the_minimizer_of_the_clamped_plate)
{
    static const char *const modes[] = { "solver.krylov=auto", "solver.krylov=always" };
    for (int levels = 2; levels <= 3; levels++) {
        int ec;
        json_t *ref = run("plate_clamped", "bhem", "lsnewton", 8, levels, NULL, &ec);
        CHECK(ref && ec == 0);
        if (!ref) continue;
        const double z0 = probe(ref, "center", 2);
        for (int m = 0; m < 2; m++) {
            json_t *r = run("plate_clamped", "bhem", "rmtr", 8, levels, modes[m], &ec);
            CHECK_MSG(r && ec == 0, "%s levels %d: exit %d", modes[m], levels, ec);
            if (!r) continue;
            const double z = probe(r, "center", 2);
            CHECK_MSG(fabs(z - z0) <= 1e-6 * fabs(z0), "%s levels %d: center %.10g, lsnewton %.10g", modes[m], levels, z,
                      z0);
            CHECK(strcmp(json_string_value(json_object_get(r, "validation")), "passed") == 0);
            CHECK_MSG(cg_iters(r) > 0, "%s levels %d: no Krylov iterations", modes[m], levels);
            CHECK(strstr(json_string_value(json_object_get(r, "solver_info")), "Krylov acceleration") != NULL);
            printf("    plate_clamped levels %d %-22s iterations %2d, CG iterations %3d, center %.9g (lsnewton %.9g)\n",
                   levels, modes[m], (int)num(r, "iterations", NULL), cg_iters(r), z, z0);
            json_decref(r);
        }
        json_decref(ref);
    }
}

/* The trampoline's first step on the subdivision hierarchy (penalty
 * boundary conditions, nonconvex start): the same minimizer as TR with
 * exact Newton steps. */
SB_TEST(krylov_reaches_the_minimizer_of_the_trampoline)
{
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/trampoline_1step.json", sb_test_root());
    static const char *const modes[] = { "solver.krylov=auto", "solver.krylov=always",
                                         "solver.krylov=auto solver.krylov_boundary=krylov" };
    int ec;
    json_t *ref = run(scene, "rmtr", "tr", 8, 2, NULL, &ec);
    CHECK(ref && ec == 0);
    if (!ref) return;
    for (int m = 0; m < 3; m++) {
        json_t *r = run(scene, "rmtr", "rmtr", 8, 2, modes[m], &ec);
        CHECK_MSG(r && ec == 0, "%s: exit %d", modes[m], ec);
        if (!r) continue;
        for (int c = 0; c < 3; c++) {
            CHECK_NEAR(probe(r, "center", c), probe(ref, "center", c), 1e-6);
            CHECK_NEAR(probe(r, "quarter", c), probe(ref, "quarter", c), 1e-6);
        }
        if (m == 1) CHECK(cg_iters(r) > 0);
        printf("    trampoline 363 dofs %-48s iterations %2d, CG iterations %4d\n", modes[m],
               (int)num(r, "iterations", NULL), cg_iters(r));
        json_decref(r);
    }
    json_decref(ref);
}

/* solver.krylov_boundary (docs/krylov.md): on drooping at 2 levels, where
 * Krylov steps end on the trust-region boundary, the default (vcycle) never
 * follows an accepted boundary Krylov step by another Krylov step, and
 * krylov does (the record's history: krylov_rtol > 0 marks a Krylov step,
 * krylov_status 3 the boundary); both converge. */
SB_TEST(krylov_boundary_chooses_the_step_after_a_boundary_step)
{
    static const char *const modes[] = { "solver.krylov=auto", "solver.krylov=auto solver.krylov_boundary=krylov" };
    int follows[2] = { -1, -1 };
    for (int m = 0; m < 2; m++) {
        char path[96];
        snprintf(path, sizeof path, "/tmp/sb_rmtr_kb%ld_%d.h5", (long)getpid(), m);
        int ec;
        json_t *r = run_out("drooping", "rmtr", "rmtr", 8, 2, modes[m], path, &ec);
        CHECK_MSG(r && ec == 0, "%s: exit %d", modes[m], ec);
        json_decref(r);
        hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
        CHECK(f >= 0);
        if (f < 0) continue;
        size_t n1, n2, n3, n4;
        double *kr = hist(f, "krylov_rtol", &n1), *ks = hist(f, "krylov_status", &n2);
        double *acc = hist(f, "accepted", &n3), *st = hist(f, "step", &n4);
        CHECK(kr && ks && acc && st && n1 == n2 && n1 == n3 && n1 == n4);
        int boundary = 0;
        follows[m] = 0;
        for (size_t i = 0; kr && ks && acc && st && n1 == n2 && n1 == n3 && n1 == n4 && i + 1 < n1; i++)
            if (kr[i] > 0 && ks[i] == 3 && acc[i] > 0 && st[i + 1] == st[i]) {
                boundary++;
                if (kr[i + 1] > 0) follows[m]++;
            }
        CHECK_MSG(boundary > 0, "%s: no accepted boundary Krylov step", modes[m]);
        printf("    drooping 363 dofs %-48s accepted boundary Krylov steps %d, followed by a Krylov step %d\n",
               modes[m], boundary, follows[m]);
        free(kr); free(ks); free(acc); free(st);
        H5Fclose(f);
        remove(path);
    }
    CHECK_MSG(follows[0] == 0, "vcycle: %d boundary steps followed by a Krylov step", follows[0]);
    CHECK_MSG(follows[1] > 0, "krylov: no boundary step followed by a Krylov step");
}

/* The spring-net fixture's coarse patterns cannot hold I^T H I: the V-cycle
 * preconditioner cannot be built, refused before any work. */
SB_TEST(krylov_refused_without_galerkin_operators)
{
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/membrane_dynamic.json", sb_test_root());
    sb_run_request req;
    sb_test_request(&req, scene, "fixture_membrane", "rmtr", 8);
    req.levels = 2;
    const char *sets[1] = { "solver.krylov=auto" };
    req.sets = sets;
    req.n_sets = 1;
    FILE *err = tmpfile();
    FILE *devnull = fopen("/dev/null", "w");
    char *js = NULL;
    int ec = sb_run_execute(&req, devnull, err, &js);
    fclose(devnull);
    free(js);
    char buf[2048] = "";
    rewind(err);
    size_t m = fread(buf, 1, sizeof buf - 1, err);
    buf[m] = 0;
    fclose(err);
    CHECK_MSG(ec == SB_EXIT_INPUT, "exit %d", ec);
    CHECK_MSG(strstr(buf, "solver.krylov=auto needs Galerkin coarse operators") != NULL, "message \"%s\"", buf);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = { SB_CASE(krylov_off_is_the_plain_path_bit_for_bit),
                                          SB_CASE(krylov_reaches_the_minimizer_of_the_clamped_plate),
                                          SB_CASE(krylov_reaches_the_minimizer_of_the_trampoline),
                                          SB_CASE(krylov_boundary_chooses_the_step_after_a_boundary_step),
                                          SB_CASE(krylov_refused_without_galerkin_operators), SB_END };
    return sb_test_main(argc, argv, cases);
}
