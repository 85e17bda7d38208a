/* test_solvers.c — every outer solver on standard problems with known
 * minimizers, through the same code path as `shellbench run`. */
#include "sb_test.h"
#include "sb_run.h"
#include "sb_trs.h"

#include <jansson.h>
#include <stdlib.h>
#include <string.h>

typedef struct outcome {
    int exit_code;
    double f, gnorm;
    long iterations;
    char reason[64];
} outcome;

static outcome run(const char *method, const char *solver, int nsets, const char *const *sets)
{
    outcome o;
    memset(&o, 0, sizeof o);
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/fixture_static.json", sb_test_root());
    sb_run_request req;
    memset(&req, 0, sizeof req);
    req.scene = scene;
    req.method = method;
    req.solver = solver;
    req.out = "none";
    req.quiet = 1;
    req.n_sets = nsets;
    req.sets = sets;
    char *js = NULL;
    FILE *devnull = fopen("/dev/null", "w");
    o.exit_code = sb_run_execute(&req, devnull, stderr, &js);
    fclose(devnull);
    o.f = NAN;
    if (js) {
        json_error_t e;
        json_t *root = json_loads(js, 0, &e);
        if (root) {
            o.f = json_number_value(json_object_get(root, "f"));
            o.gnorm = json_number_value(json_object_get(root, "gnorm"));
            o.iterations = (long)json_integer_value(json_object_get(root, "iterations"));
            snprintf(o.reason, sizeof o.reason, "%s", json_string_value(json_object_get(root, "reason")));
            json_decref(root);
        }
        free(js);
    }
    return o;
}

/* extended Rosenbrock: unique minimizer (1,...,1) with f* = 0 */
SB_TEST(rosenbrock_tr_dogleg)
{
    const char *sets[] = { "method.n=20" };
    outcome o = run("fixture_rosenbrock", "tr", 1, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK(o.f < 1e-14);
    CHECK(o.gnorm < 1e-7);
}

/* the paper's ratio (Eq. 4.2 as a plain quotient, solver.rho=paper, issue 43) with the paper's dogleg:
 * it converges where the gradient test is reachable; a bad choice is an input error */
SB_TEST(rosenbrock_tr_paper_ratio)
{
    const char *sets[] = { "method.n=20", "solver.rho=paper", "solver.indefinite=cauchy", "run.stall_iter=0" };
    outcome o = run("fixture_rosenbrock", "tr", 4, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK(o.f < 1e-14);
    CHECK(o.gnorm < 1e-7);
    const char *bad[] = { "solver.rho=exact" };
    CHECK_EQ_INT(run("fixture_rosenbrock", "tr", 1, bad).exit_code, 2);
}

SB_TEST(rosenbrock_tr_stcg)
{
    const char *sets[] = { "method.n=20", "solver.trs=stcg" };
    outcome o = run("fixture_rosenbrock", "tr", 2, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK(o.f < 1e-14);
}

SB_TEST(rosenbrock_lsnewton)
{
    const char *sets[] = { "method.n=20" };
    outcome o = run("fixture_rosenbrock", "lsnewton", 1, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK(o.f < 1e-14);
    CHECK(o.iterations < 100);
}

/* quadratic: f* = -1/2 b^T x* with b = A x*, x*_i = 1 + i/n (see fixture) */
static double quad_fstar(int n, double cond)
{
    double f = 0;
    for (int i = 0; i < n; i++) {
        double d = pow(cond, (double)i / (n - 1)), xs = 1.0 + (double)i / n;
        double Ax = d * xs;
        if (i > 0) Ax += 0.25 * sqrt(d * pow(cond, (double)(i - 1) / (n - 1))) * (1.0 + (double)(i - 1) / n);
        if (i + 1 < n) Ax += 0.25 * sqrt(d * pow(cond, (double)(i + 1) / (n - 1))) * (1.0 + (double)(i + 1) / n);
        f -= 0.5 * Ax * xs;
    }
    return f;
}

SB_TEST(quadratic_convex_all_newton_solvers_one_step)
{
    const char *sets[] = { "method.n=50", "method.cond=100" };
    double fs = quad_fstar(50, 100);
    const char *solvers[] = { "lsnewton", "linearized", "tr" };
    for (int k = 0; k < 3; k++) {
        outcome o = run("fixture_quadratic", solvers[k], 2, sets);
        CHECK_EQ_INT(o.exit_code, 0);
        CHECK_REL(o.f, fs, 1e-12);
        if (k < 2) CHECK_EQ_INT(o.iterations, 1);   /* Newton is exact on a quadratic */
    }
}

SB_TEST(quadratic_ill_conditioned_1e10)
{
    const char *sets[] = { "method.n=200", "method.cond=1e10" };
    double fs = quad_fstar(200, 1e10);
    outcome o = run("fixture_quadratic", "lsnewton", 2, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK_REL(o.f, fs, 1e-10);
    /* trust region with dogleg: the radius must grow until the Newton point fits */
    o = run("fixture_quadratic", "tr", 2, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK_REL(o.f, fs, 1e-10);
}

SB_TEST(quadratic_damped_converges_linearly)
{
    const char *sets[] = { "method.n=20", "method.cond=10" };
    outcome o = run("fixture_quadratic", "damped", 2, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK_REL(o.f, quad_fstar(20, 10), 1e-10);
    /* error contracts by (1 - 0.3) per step: about 45-60 steps to 1e-7 */
    CHECK(o.iterations > 20 && o.iterations < 100);
}

/* saddle: started next to the saddle (0,0), f = 0 there; minimizers have f = -1/4 */
SB_TEST(saddle_tr_escapes)
{
    outcome o = run("fixture_saddle", "tr", 0, NULL);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK_NEAR(o.f, -0.25, 1e-12);
}

SB_TEST(saddle_tr_cauchy_escapes)
{
    const char *sets[] = { "solver.indefinite=cauchy" };   /* the paper's dogleg */
    outcome o = run("fixture_saddle", "tr", 1, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK_NEAR(o.f, -0.25, 1e-12);
}

/* the trust-region ratio at the limiting accuracy (sb_tr_ratio) */
SB_TEST(tr_ratio_roundoff)
{
    CHECK_NEAR(sb_tr_ratio(SB_OK, 1.0, 1.0 - 2e-16, 1e-16), 1.0, 0);        /* both below round-off: 1 */
    CHECK_NEAR(sb_tr_ratio(SB_OK, 1.0, 0.5, 1.0), 0.5, 1e-15);              /* ordinary ratio */
    CHECK(sb_tr_ratio(SB_OK, 1.0, 1.0 + 1e-3, 1e-16) < 0);                  /* real increase: rejected */
    CHECK(isinf(sb_tr_ratio(SB_NONFINITE, 1.0, 0.0, 1.0)));
    CHECK(isinf(sb_tr_ratio(SB_OK, 1.0, NAN, 1.0)));
    CHECK(isinf(sb_tr_ratio(SB_OK, 1.0, 0.5, 0.0)));                        /* no predicted decrease */
}

SB_TEST(saddle_tr_stcg_escapes)
{
    const char *sets[] = { "solver.trs=stcg" };
    outcome o = run("fixture_saddle", "tr", 1, sets);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK_NEAR(o.f, -0.25, 1e-12);
}

SB_TEST(saddle_lsnewton_shifts_and_escapes)
{
    outcome o = run("fixture_saddle", "lsnewton", 0, NULL);
    CHECK_EQ_INT(o.exit_code, 0);
    CHECK_NEAR(o.f, -0.25, 1e-12);
}

SB_TEST(saddle_damped_records_not_posdef)
{
    /* plain Newton on an indefinite Hessian: a recorded outcome, exit 1 */
    outcome o = run("fixture_saddle", "damped", 0, NULL);
    CHECK_EQ_INT(o.exit_code, 1);
    CHECK(strcmp(o.reason, "not_posdef") == 0);
}

SB_TEST(max_iter_is_recorded)
{
    const char *sets[] = { "method.n=20", "run.max_iter=3" };
    outcome o = run("fixture_rosenbrock", "tr", 2, sets);
    CHECK_EQ_INT(o.exit_code, 1);
    CHECK(strcmp(o.reason, "max_iter") == 0);
    CHECK_EQ_INT(o.iterations, 3);
}

SB_TEST(bad_parameter_is_input_error)
{
    const char *bad1[] = { "solver.eta1=2" };
    CHECK_EQ_INT(run("fixture_rosenbrock", "tr", 1, bad1).exit_code, 2);
    const char *bad2[] = { "solver.nonsense=1" };
    CHECK_EQ_INT(run("fixture_rosenbrock", "tr", 1, bad2).exit_code, 2);
    const char *bad3[] = { "solver.trs=cholesky" };
    CHECK_EQ_INT(run("fixture_rosenbrock", "tr", 1, bad3).exit_code, 2);
    const char *bad4[] = { "method.n=7" };   /* Rosenbrock needs an even dimension */
    CHECK_EQ_INT(run("fixture_rosenbrock", "tr", 1, bad4).exit_code, 2);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(rosenbrock_tr_dogleg), SB_CASE(rosenbrock_tr_paper_ratio), SB_CASE(rosenbrock_tr_stcg), SB_CASE(rosenbrock_lsnewton),
        SB_CASE(quadratic_convex_all_newton_solvers_one_step), SB_CASE(quadratic_ill_conditioned_1e10),
        SB_CASE(quadratic_damped_converges_linearly), SB_CASE(saddle_tr_escapes), SB_CASE(saddle_tr_cauchy_escapes), SB_CASE(tr_ratio_roundoff), SB_CASE(saddle_tr_stcg_escapes),
        SB_CASE(saddle_lsnewton_shifts_and_escapes), SB_CASE(saddle_damped_records_not_posdef),
        SB_CASE(max_iter_is_recorded), SB_CASE(bad_parameter_is_input_error), SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
