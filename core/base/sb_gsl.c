/* sb_gsl.c — GSL's error policy and the small wrappers of sb_gsl.h. */
#include "sb_gsl.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sb_gsl_errors_off(void)
{
    gsl_set_error_handler_off();
}

int sb_gsl_status(int gsl_errno)
{
    switch (gsl_errno) {
    case GSL_SUCCESS:
        return SB_OK;
    case GSL_ENOMEM:
        return SB_ERR_NOMEM;
    case GSL_EDOM: case GSL_EINVAL: case GSL_EFAULT: case GSL_EBADTOL: case GSL_EBADLEN: case GSL_ENOTSQR:
        return SB_ERR_INPUT;
    case GSL_EUNSUP: case GSL_EUNIMPL: case GSL_ECACHE: case GSL_ETABLE:
        return SB_ERR_UNSUPPORTED;
    case GSL_EBADFUNC: case GSL_EOVRFLW: case GSL_ERANGE: case GSL_EZERODIV:
        return SB_NONFINITE;
    case GSL_EFACTOR: case GSL_ESING:
        return SB_NOT_POSDEF;
    case GSL_EMAXITER: case GSL_ETOL: case GSL_ETOLF: case GSL_ETOLX: case GSL_ETOLG: case GSL_ENOPROG:
    case GSL_ENOPROGJ: case GSL_EROUND: case GSL_ELOSS: case GSL_ERUNAWAY: case GSL_EDIVERGE: case GSL_EUNDRFLW:
        return SB_NOT_CONVERGED;
    default:
        return SB_ERR_INTERNAL;
    }
}

int sb_gsl_error(sb_context *ctx, int gsl_errno, const char *what)
{
    const int st = sb_gsl_status(gsl_errno);
    if (st == SB_OK) return SB_OK;
    if (ctx) return sb_error(ctx, st, "%s: GSL error %d (%s)", what, gsl_errno, gsl_strerror(gsl_errno));
    fprintf(stderr, "%s: GSL error %d (%s)\n", what, gsl_errno, gsl_strerror(gsl_errno));
    return st;
}

/* ---- order statistics -------------------------------------------------------- */

int sb_quantiles(const double *x, size_t n, const double *p, size_t np, double *q)
{
    sb_gsl_errors_off();
    if (n == 0 || !x || (np && (!p || !q))) return SB_ERR_INPUT;
    for (size_t k = 0; k < np; k++)
        if (!(p[k] >= 0.0 && p[k] <= 1.0)) return SB_ERR_INPUT;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i])) return SB_ERR_INPUT;
    double *s = malloc(n * sizeof *s);
    if (!s) return SB_ERR_NOMEM;
    memcpy(s, x, n * sizeof *s);
    gsl_sort(s, 1, n);
    for (size_t k = 0; k < np; k++) q[k] = gsl_stats_quantile_from_sorted_data(s, 1, n, p[k]);
    free(s);
    return SB_OK;
}

int sb_median(const double *x, size_t n, double *median)
{
    const double half = 0.5;
    return sb_quantiles(x, n, &half, 1, median);
}

/* ---- random streams ------------------------------------------------------------ */

gsl_rng *sb_rng_alloc(const char *name, unsigned long seed, char *err, size_t errlen)
{
    sb_gsl_errors_off();
    if (err && errlen) err[0] = '\0';
    if (!name || !*name) name = "mt19937";
    const gsl_rng_type *type = NULL;
    for (const gsl_rng_type **t = gsl_rng_types_setup(); *t; t++)
        if (!strcmp((*t)->name, name)) {
            type = *t;
            break;
        }
    if (!type) {
        if (err) snprintf(err, errlen, "random generator \"%s\" is not one of GSL's (e.g. mt19937, ranlxd2)", name);
        return NULL;
    }
    gsl_rng *r = gsl_rng_alloc(type);
    if (!r) {
        if (err) snprintf(err, errlen, "random generator \"%s\": out of memory", name);
        return NULL;
    }
    gsl_rng_set(r, seed);
    return r;
}

gsl_rng *sb_rng_for_run(sb_context *ctx, const char *name)
{
    const double seed = sb_param(&ctx->params, "run.seed");
    if (!(isfinite(seed) && seed >= 0)) {
        sb_error(ctx, SB_ERR_INTERNAL, "random stream: the run has no parameter run.seed");
        return NULL;
    }
    char msg[256];
    gsl_rng *r = sb_rng_alloc(name, (unsigned long)seed, msg, sizeof msg);
    if (!r) sb_error(ctx, strstr(msg, "memory") ? SB_ERR_NOMEM : SB_ERR_INPUT, "%s", msg);
    return r;
}

/* ---- scalar root --------------------------------------------------------------- */

int sb_root_brent(double (*f)(double x, void *data), void *data, double lo, double hi,
                  double epsabs, double epsrel, int max_iter, double *root, int *iters)
{
    sb_gsl_errors_off();
    if (iters) *iters = 0;
    if (!f || !root || max_iter < 1) return SB_ERR_INPUT;
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s) return SB_ERR_NOMEM;
    gsl_function F = { f, data };
    /* gsl_root_fsolver_set: GSL_EINVAL without a sign change, GSL_EBADFUNC for
     * a non-finite f at an end */
    int rc = gsl_root_fsolver_set(s, &F, fmin(lo, hi), fmax(lo, hi));
    int it = 0;
    while (rc == GSL_SUCCESS) {
        if (it == max_iter) {
            rc = GSL_EMAXITER;
            break;
        }
        it++;
        rc = gsl_root_fsolver_iterate(s);
        if (rc != GSL_SUCCESS) break;
        rc = gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), epsabs, epsrel);
        if (rc == GSL_SUCCESS) break;
        if (rc == GSL_CONTINUE) rc = GSL_SUCCESS;
    }
    if (it > 0) *root = gsl_root_fsolver_root(s);
    if (iters) *iters = it;
    gsl_root_fsolver_free(s);
    return sb_gsl_status(rc);
}
