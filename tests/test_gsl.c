/* test_gsl.c — the GSL error policy and the sb_gsl wrappers (sb_gsl.c):
 * a GSL error never aborts and becomes the suite's status in the calling
 * context; quantiles, random streams and Brent's root against known values. */
#include "sb_test.h"
#include "sb_context.h"
#include "sb_gsl.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_log.h>
#include <math.h>
#include <string.h>

static double no_root(double x, void *data) { (void)data; return 1.0 + x * x; }
static double cubic(double x, void *data) { (void)data; return x * x * x - 2.0; }
static double nan_inside(double x, void *data) { (void)data; return x < 0.3 ? -1.0 : x < 0.7 ? NAN : 1.0; }

/* GSL's default handler aborts; a context installs the policy of sb_gsl.h,
 * after which GSL calls with bad input return codes that the context maps
 * (were the default handler still in place, this binary would abort here
 * and the suite would count it as crashed). */
SB_TEST(context_turns_gsl_errors_into_status)
{
    gsl_set_error_handler(NULL);                 /* GSL's default: abort() */
    sb_context ctx;
    CHECK_EQ_INT(sb_context_init(&ctx), SB_OK);
    gsl_error_handler_t *h = gsl_set_error_handler(NULL);
    CHECK(h != NULL);                            /* the context installed one */
    gsl_set_error_handler(h);

    /* a bracket without a sign change: GSL_EINVAL -> SB_ERR_INPUT, with a sentence */
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    CHECK(s != NULL);
    gsl_function F = { no_root, NULL };
    int rc = gsl_root_fsolver_set(s, &F, -1.0, 1.0);
    gsl_root_fsolver_free(s);
    CHECK_EQ_INT(rc, GSL_EINVAL);
    CHECK_EQ_INT(sb_gsl_error(&ctx, rc, "bracket"), SB_ERR_INPUT);
    CHECK_EQ_INT(ctx.status, SB_ERR_INPUT);
    CHECK_MSG(strstr(ctx.err, "bracket: GSL error 4") != NULL, "message: %s", ctx.err);

    /* a domain error of a special function: log(-1) */
    gsl_sf_result r;
    rc = gsl_sf_log_e(-1.0, &r);
    CHECK_EQ_INT(rc, GSL_EDOM);
    CHECK_EQ_INT(sb_gsl_error(&ctx, rc, "log"), SB_ERR_INPUT);
    /* success records nothing */
    ctx.err[0] = '\0';
    CHECK_EQ_INT(sb_gsl_error(&ctx, GSL_SUCCESS, "ok"), SB_OK);
    CHECK_EQ_INT((int)strlen(ctx.err), 0);
    sb_context_free(&ctx);
}

SB_TEST(status_mapping)
{
    CHECK_EQ_INT(sb_gsl_status(GSL_SUCCESS), SB_OK);
    CHECK_EQ_INT(sb_gsl_status(GSL_ENOMEM), SB_ERR_NOMEM);
    CHECK_EQ_INT(sb_gsl_status(GSL_EDOM), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_gsl_status(GSL_EBADTOL), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_gsl_status(GSL_EUNIMPL), SB_ERR_UNSUPPORTED);
    CHECK_EQ_INT(sb_gsl_status(GSL_EBADFUNC), SB_NONFINITE);
    CHECK_EQ_INT(sb_gsl_status(GSL_EOVRFLW), SB_NONFINITE);
    CHECK_EQ_INT(sb_gsl_status(GSL_ESING), SB_NOT_POSDEF);
    CHECK_EQ_INT(sb_gsl_status(GSL_EMAXITER), SB_NOT_CONVERGED);
    CHECK_EQ_INT(sb_gsl_status(GSL_ENOPROG), SB_NOT_CONVERGED);
    CHECK_EQ_INT(sb_gsl_status(GSL_ESANITY), SB_ERR_INTERNAL);
    CHECK_EQ_INT(sb_gsl_status(12345), SB_ERR_INTERNAL);
}

/* Brent's root: cube root of 2 to round-off; each failure is a status */
SB_TEST(root_brent_outcomes)
{
    double x = 0.0;
    int it = 0;
    CHECK_EQ_INT(sb_root_brent(cubic, NULL, 2.0, 0.0, 0.0, 1e-15, 100, &x, &it), SB_OK);
    CHECK_NEAR(x, cbrt(2.0), 4e-15);
    CHECK(it > 0 && it < 100);
    CHECK_EQ_INT(sb_root_brent(no_root, NULL, -1.0, 1.0, 0.0, 1e-12, 100, &x, &it), SB_ERR_INPUT);
    CHECK_EQ_INT(it, 0);
    CHECK_EQ_INT(sb_root_brent(cubic, NULL, 0.0, 2.0, -1.0, 1e-12, 100, &x, &it), SB_ERR_INPUT);   /* bad tol */
    CHECK_EQ_INT(sb_root_brent(nan_inside, NULL, 0.0, 1.0, 0.0, 1e-12, 100, &x, &it), SB_NONFINITE);
    x = -1.0;
    CHECK_EQ_INT(sb_root_brent(cubic, NULL, 0.0, 2.0, 0.0, 1e-15, 2, &x, &it), SB_NOT_CONVERGED);
    CHECK_EQ_INT(it, 2);
    CHECK(x >= 0.0 && x <= 2.0);                  /* the estimate so far */
    CHECK_EQ_INT(sb_root_brent(NULL, NULL, 0.0, 1.0, 0.0, 1e-12, 100, &x, &it), SB_ERR_INPUT);
}

/* GSL's quantile rule (Hyndman & Fan definition 7) on hand-checked data */
SB_TEST(quantiles_and_median)
{
    const double x[8] = { 3, 1, 4, 1, 5, 9, 2, 6 };   /* sorted: 1 1 2 3 4 5 6 9 */
    double copy[8];
    memcpy(copy, x, sizeof x);
    const double p[5] = { 0.0, 0.25, 0.5, 0.9, 1.0 };
    double q[5];
    CHECK_EQ_INT(sb_quantiles(x, 8, p, 5, q), SB_OK);
    CHECK_NEAR(q[0], 1.0, 0);
    CHECK_NEAR(q[1], 1.75, 1e-15);   /* position 1.75: 1 + 0.75 (2 - 1) */
    CHECK_NEAR(q[2], 3.5, 1e-15);    /* (3 + 4) / 2 */
    CHECK_NEAR(q[3], 6.9, 1e-14);    /* position 6.3: 6 + 0.3 (9 - 6) */
    CHECK_NEAR(q[4], 9.0, 0);
    CHECK(memcmp(x, copy, sizeof x) == 0);        /* input untouched */
    double med;
    CHECK_EQ_INT(sb_median(x, 7, &med), SB_OK);   /* 3 1 4 1 5 9 2 -> 1 1 2 3 4 5 9 */
    CHECK_NEAR(med, 3.0, 0);
    CHECK_EQ_INT(sb_median(x, 1, &med), SB_OK);
    CHECK_NEAR(med, 3.0, 0);
    const double bad[3] = { 1.0, NAN, 2.0 }, pbad = 1.5;
    CHECK_EQ_INT(sb_median(bad, 3, &med), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_quantiles(x, 8, &pbad, 1, q), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_median(x, 0, &med), SB_ERR_INPUT);
}

/* Random streams: named, seeded, reproducible; the seed comes from run.seed */
SB_TEST(rng_streams)
{
    char err[256];
    gsl_rng *a = sb_rng_alloc("mt19937", 5489, err, sizeof err);
    CHECK(a != NULL);
    if (!a) return;
    /* MT19937 reference output (Matsumoto & Nishimura, init_genrand(5489)) */
    CHECK_EQ_INT((long)gsl_rng_get(a), 3499211612L);
    CHECK(strcmp(gsl_rng_name(a), "mt19937") == 0);
    gsl_rng_free(a);

    gsl_rng *b = sb_rng_alloc(NULL, 7, err, sizeof err), *c = sb_rng_alloc("", 7, err, sizeof err),
            *d = sb_rng_alloc("mt19937", 8, err, sizeof err);
    CHECK(b && c && d);
    if (!b || !c || !d) return;
    CHECK(strcmp(gsl_rng_name(b), "mt19937") == 0);
    int same = 1, differ = 0;
    for (int i = 0; i < 100; i++) {
        unsigned long vb = gsl_rng_get(b), vc = gsl_rng_get(c), vd = gsl_rng_get(d);
        same &= vb == vc;
        differ |= vb != vd;
    }
    CHECK(same);
    CHECK(differ);
    gsl_rng_free(b);
    gsl_rng_free(c);
    gsl_rng_free(d);

    CHECK(sb_rng_alloc("no_such_rng", 1, err, sizeof err) == NULL);
    CHECK_MSG(strstr(err, "no_such_rng") != NULL, "message: %s", err);

    sb_context ctx;
    CHECK_EQ_INT(sb_context_init(&ctx), SB_OK);
    CHECK(sb_rng_for_run(&ctx, "ranlxd2") == NULL);      /* no run parameters declared */
    CHECK_EQ_INT(ctx.status, SB_ERR_INTERNAL);
    static const sb_param_def run_defs[] = {
        { "seed", SB_PARAM_INT, 1, 0, 2147483647, NULL, "seed" },
        { NULL, 0, 0, 0, 0, NULL, NULL }
    };
    CHECK_EQ_INT(sb_paramset_add(&ctx.params, "run", run_defs), SB_OK);
    CHECK_EQ_INT(sb_paramset_set(&ctx.params, "run.seed=8", err, sizeof err), SB_OK);
    gsl_rng *e = sb_rng_for_run(&ctx, "mt19937"), *f = sb_rng_alloc("mt19937", 8, err, sizeof err);
    CHECK(e && f);
    if (e && f) CHECK(gsl_rng_get(e) == gsl_rng_get(f));
    gsl_rng_free(e);
    gsl_rng_free(f);
    CHECK(sb_rng_for_run(&ctx, "no_such_rng") == NULL);
    CHECK_EQ_INT(ctx.status, SB_ERR_INPUT);
    sb_context_free(&ctx);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(context_turns_gsl_errors_into_status), SB_CASE(status_mapping), SB_CASE(root_brent_outcomes),
        SB_CASE(quantiles_and_median), SB_CASE(rng_streams), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
