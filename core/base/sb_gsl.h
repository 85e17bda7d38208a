/* sb_gsl.h — the suite's door to GSL, the GNU Scientific Library (Galassi et
 * al., GNU Scientific Library Reference Manual, 3rd ed.): its error policy
 * and a few small wrappers that reports, studies and mesh generators share.
 *
 * Error policy.  GSL's default error handler prints a message and calls
 * abort(), which would turn bad input or a numerical failure into a crash.
 * GSL has exactly one handler per process (gsl_set_error_handler, a global
 * function pointer without user data), so it cannot know which run's
 * context an error belongs to, and a handler that records the error would
 * need global mutable state, which the suite does not have.  The policy is
 * therefore:
 *   1. GSL's handler is switched off (gsl_set_error_handler_off): a failing
 *      GSL function only returns its error code (or NULL).  sb_context_init
 *      does this for every run, and every sb_gsl entry point does it again
 *      (idempotent, it stores the same null pointer), so a tool that calls
 *      the wrappers without a context is covered too.
 *   2. Every caller checks the GSL return code where it calls GSL and maps it
 *      to the suite's status codes in its own context: sb_gsl_status() gives
 *      the status (bad input -> SB_ERR_INPUT, no memory -> SB_ERR_NOMEM, a
 *      numerical failure -> a positive, recorded outcome), sb_gsl_error()
 *      also writes the sentence into the context's message.  That is the
 *      "one handler per context": the mapping runs in the calling context.
 * Code that calls gsl_* directly follows the same rule: check the code, map
 * it with sb_gsl_status/sb_gsl_error, never rely on GSL's handler.
 *
 * Not in inner loops: the wrappers allocate and check; a GSL routine per
 * quadrature point or per element is not the place for them (the shell
 * kernel keeps its inlined numerics, see sb_material.c). */
#ifndef SB_GSL_H
#define SB_GSL_H

#include "sb_context.h"

#include <gsl/gsl_rng.h>
#include <stddef.h>

/* Install the error policy above (gsl_set_error_handler_off).  Idempotent. */
void sb_gsl_errors_off(void);

/* The suite's status for a GSL error code (GSL_SUCCESS -> SB_OK):
 *   GSL_ENOMEM                                   -> SB_ERR_NOMEM
 *   GSL_EDOM, EINVAL, EFAULT, EBADTOL, EBADLEN, ENOTSQR -> SB_ERR_INPUT
 *   GSL_EUNSUP, EUNIMPL, ECACHE, ETABLE           -> SB_ERR_UNSUPPORTED
 *   GSL_EBADFUNC, EOVRFLW, ERANGE, EZERODIV       -> SB_NONFINITE (outcome)
 *   GSL_EFACTOR, ESING                            -> SB_NOT_POSDEF (outcome)
 *   GSL_EMAXITER, ETOL*, ENOPROG*, EROUND, ELOSS, ERUNAWAY, EDIVERGE,
 *   EUNDRFLW                                      -> SB_NOT_CONVERGED (outcome)
 *   anything else (EFAILED, ESANITY, ...)          -> SB_ERR_INTERNAL
 * A caller that knows better maps itself (gsl_linalg_cholesky_decomp1, for
 * one, says "not positive definite" with GSL_EDOM). */
int sb_gsl_status(int gsl_errno);

/* Records "WHAT: GSL error N (gsl_strerror text)" in ctx with the mapped
 * status and returns that status (SB_OK, with nothing recorded, for
 * GSL_SUCCESS).  ctx == NULL: the sentence goes to stderr. */
int sb_gsl_error(sb_context *ctx, int gsl_errno, const char *what);

/* ---- order statistics (gsl_sort + gsl_stats) ------------------------------ */

/* q[k] = the p[k]-quantile of x[0..n-1] (x is not modified), GSL's rule
 * gsl_stats_quantile_from_sorted_data: linear interpolation between order
 * statistics at position (n-1) p (Hyndman & Fan 1996, definition 7; the
 * median of an even count is the mean of the middle two).  SB_ERR_INPUT for
 * n = 0, a p outside [0, 1] or a non-finite x (a failed run's figure is not
 * a sample: filter it first); SB_ERR_NOMEM. */
int sb_quantiles(const double *x, size_t n, const double *p, size_t np, double *q);
int sb_median(const double *x, size_t n, double *median);

/* ---- random streams (gsl_rng) --------------------------------------------- */

/* A GSL generator by name ("mt19937", "ranlxd2", ... — gsl_rng_types_setup;
 * NULL or "" = "mt19937", Matsumoto & Nishimura 1998), seeded with
 * gsl_rng_set(r, seed).  A run that draws from it records the generator's
 * name (gsl_rng_name(r)) beside its seed, so that the stream can be
 * reproduced.  NULL with a sentence in err for an unknown name or no memory.
 * Free with gsl_rng_free. */
gsl_rng *sb_rng_alloc(const char *name, unsigned long seed, char *err, size_t errlen);

/* The same seeded from the run's parameter run.seed (ctx->params); NULL with
 * the error recorded in ctx. */
gsl_rng *sb_rng_for_run(sb_context *ctx, const char *name);

/* ---- scalar root (gsl_root_fsolver_brent) ----------------------------------- */

/* A root of f in [lo, hi] by Brent's method (Brent 1973, ch. 4), where f(lo)
 * and f(hi) differ in sign, stopped when the bracket [a, b] satisfies
 * |b - a| < epsabs + epsrel min(|a|, |b|) (gsl_root_test_interval) or after
 * max_iter iterations.  *root is GSL's best estimate; *iters (optional) the
 * iterations taken.  Returns SB_OK, SB_ERR_INPUT (no sign change, a bad
 * tolerance), SB_NONFINITE (f gave NaN or Inf) or SB_NOT_CONVERGED (max_iter
 * reached: *root is the estimate so far). */
int sb_root_brent(double (*f)(double x, void *data), void *data, double lo, double hi,
                  double epsabs, double epsrel, int max_iter, double *root, int *iters);

#endif
