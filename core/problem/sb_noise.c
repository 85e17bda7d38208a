/* sb_noise.c — the rounding level of the computed gradient (sb_problem.h).
 *
 * The gradient a run computes is g~(x) = g(x) + e(x), e the rounding of the
 * element kernels and of the assembly, so ||g~|| cannot be driven below about
 * ||e||: Newton with an exact solve stalls there (the limiting accuracy,
 * Kelley 1995 §5.4; the "noise level" of Moré & Wild, SIAM J. Sci. Comput. 33
 * (2011) 1292-1314).  The level is measured, not modelled: at x + delta, delta
 * a few units in the last place of x on the free dofs (signs from a fixed
 * hash of the dof index: no random state), the computed gradient changes by
 * H delta + O(||delta||^2) plus the difference of two rounding samples, so
 *
 *     nu(delta) = ||g~(x + delta) - g~(x) - H delta|| / sqrt(2)
 *
 * estimates ||e|| when H is the Hessian of the gradient (the two samples
 * taken as independent, hence sqrt(2)).  A matrix that is not the Hessian
 * (an element-wise PSD projection, lagged contact or friction data) adds
 * (H - grad^2 E) delta, which doubles with delta while rounding does not:
 * the level is measured at delta and 2 delta, and nu(2 delta) > 1.5 nu(delta)
 * means the difference is the model's, not the rounding's: no level (0).
 * ASSUMPTION: the rounding at x + delta is as large as at x and not
 * correlated with it.  Checked against the ||g|| at which lsnewton + cholmod
 * stalls (docs/solvers.md "The gradient's rounding level"): the measured
 * level is 0.75-1.5 of it on the clamped plate with linear_fem, bhem
 * and the subdivision method (tests/test_krylov.c asserts a factor 3).
 * However well g is computed, x itself is a vector of doubles: the
 * minimizer rounded to them is off by up to half an ulp a dof, which leaves
 * H dx in the gradient (on the clamped plate at res 16 with linear_fem this
 * is the whole floor: the evaluation's rounding is 1e-17 there, the stalled
 * ||g|| 1.8e-10).  The level returned is ||e / sqrt(2)-sample + H dx||, dx
 * with the rms of half-ulp rounding (ulp / sqrt(12)) and signs from a second
 * hash.
 * Cost: two gradient evaluations (counted as such) and three products with H. */
#include "sb_problem.h"

#include <float.h>
#include <math.h>

/* delta_i = +-k eps max(|x_i|, 1e-3 ||x||_inf) on the free dofs; 0 on the
 * constrained ones (their values are the boundary data) */
static void perturbation(const sb_problem *p, int level, int n, const double *x, double xinf, double k, double *delta)
{
    const double floor_x = 1e-3 * xinf;
    for (int i = 0; i < n; i++) {
        const unsigned h = (unsigned)i * 2654435761u;   /* Knuth's multiplicative hash */
        const double sign = (h >> 16) & 1u ? 1.0 : -1.0;
        delta[i] = sign * k * DBL_EPSILON * fmax(fabs(x[i]), floor_x);
    }
    sb_problem_constrain(p, level, delta);
}

/* nu(delta) for delta = perturbation(k); w_x, w_g, w_h: n-vectors */
static int level_at(sb_problem *p, int level, int n, const double *x, const double *g, double xinf, double k,
                    double *w_x, double *w_g, double *w_h, double *nu)
{
    perturbation(p, level, n, x, xinf, k, w_h);
    for (int i = 0; i < n; i++) w_x[i] = x[i] + w_h[i];
    sb_problem_hess_mult(p, level, w_h, w_g);            /* H delta */
    double f;
    int rc = sb_problem_eval(p, level, w_x, &f, w_h, NULL);
    if (rc) return rc;
    for (int i = 0; i < n; i++) w_h[i] -= g[i] + w_g[i];
    *nu = sb_problem_norm(p, level, w_h) / sqrt(2.0);
    return isfinite(*nu) ? SB_OK : SB_NONFINITE;
}

int sb_problem_gradient_noise(sb_problem *p, int level, const double *x, const double *g, double *w_x, double *w_g,
                              double *w_h, double *noise, double *rounding)
{
    const int n = sb_problem_n(p, level);
    double xinf = 0.0;
    for (int i = 0; i < n; i++) xinf = fmax(xinf, fabs(x[i]));
    *noise = 0.0;
    if (rounding) *rounding = 0.0;
    double nu1, nu2;
    int rc = level_at(p, level, n, x, g, xinf, 4.0, w_x, w_g, w_h, &nu1);
    if (rc) return rc;
    rc = level_at(p, level, n, x, g, xinf, 8.0, w_x, w_g, w_h, &nu2);
    if (rc) return rc;
    /* w_h: the difference of two rounding samples (sqrt(2) e), or the
     * model's difference, which is dropped */
    const double keep = nu2 <= 1.5 * nu1 ? 1.0 / sqrt(2.0) : 0.0;
    if (rounding) *rounding = keep > 0.0 ? nu2 : 0.0;
    /* the representable state: x* rounded to doubles is off by up to half
     * an ulp a dof (uniform: rms ulp / sqrt(12)), which leaves H dx in the
     * gradient however well it is computed */
    for (int i = 0; i < n; i++) {
        const unsigned h = (unsigned)i * 2246822519u;
        const double a = fabs(x[i]);
        w_x[i] = ((h >> 15) & 1u ? 1.0 : -1.0) * (nextafter(a, INFINITY) - a) / sqrt(12.0);
    }
    sb_problem_constrain(p, level, w_x);
    sb_problem_hess_mult(p, level, w_x, w_g);
    for (int i = 0; i < n; i++) w_h[i] = keep * w_h[i] + w_g[i];
    *noise = sb_problem_norm(p, level, w_h);
    return isfinite(*noise) ? SB_OK : SB_NONFINITE;
}
