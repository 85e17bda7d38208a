/* bhem_basis.c — bicubic Hermite shape functions and the patch quadrature
 * rule (BHEM paper App. A). */
#include "bhem.h"

#include <math.h>

/* BHEM Eq. (31): f(th) = 2th^3 - 3th^2 + 1, g(th) = th^3 - 2th^2 + th, and
 *   w_{0,0} = f(th), w_{1,0} = f(1-th), w_{0,1} = g(th), w_{1,1} = -g(1-th).
 * First derivatives: Eq. (34), f' = 6th^2 - 6th, g' = 3th^2 - 4th + 1,
 *   w'_{1,0} = -f'(1-th), w'_{1,1} = g'(1-th).
 * Second derivatives (not printed in the paper; needed for the curvature
 * b_ab = a_a,b . a_3): f'' = 12th - 6, g'' = 6th - 4,
 *   w''_{1,0} = f''(1-th), w''_{1,1} = -g''(1-th). */
void bhem_hermite_1d(int p, int r, double th, double *w, double *dw, double *ddw)
{
    double u = p ? 1.0 - th : th;
    double val, d1, d2;
    if (r == 0) {
        val = (2.0 * u - 3.0) * u * u + 1.0;   /* f(u) */
        d1 = 6.0 * u * u - 6.0 * u;            /* f'(u) */
        d2 = 12.0 * u - 6.0;                   /* f''(u) */
        if (p) d1 = -d1;                       /* chain rule du/dth = -1 */
    } else {
        val = ((u - 2.0) * u + 1.0) * u;       /* g(u) */
        d1 = (3.0 * u - 4.0) * u + 1.0;        /* g'(u) */
        d2 = 6.0 * u - 4.0;                    /* g''(u) */
        if (p) { val = -val; d2 = -d2; }       /* -g(1-th): sign, d1 sign cancels */
    }
    if (w) *w = val;
    if (dw) *dw = d1;
    if (ddw) *ddw = d2;
}

/* BHEM Eq. (15): w_{pq,rs}(th1,th2) = w_{p,r}(th1) w_{q,s}(th2); derivatives
 * w.r.t. s = s_min + hs th1 carry 1/hs (Eq. 32-33). */
void bhem_basis_eval(double th1, double th2, double hs, double ht,
                     double *N, double *N1, double *N2, double *N11, double *N12, double *N22)
{
    double a[2][2][3], b[2][2][3];   /* [p][r][deriv order] */
    for (int p = 0; p < 2; p++)
        for (int r = 0; r < 2; r++) {
            bhem_hermite_1d(p, r, th1, &a[p][r][0], &a[p][r][1], &a[p][r][2]);
            bhem_hermite_1d(p, r, th2, &b[p][r][0], &b[p][r][1], &b[p][r][2]);
        }
    double is = 1.0 / hs, it = 1.0 / ht;
    for (int q = 0; q < 2; q++)
        for (int p = 0; p < 2; p++)
            for (int s = 0; s < 2; s++)
                for (int r = 0; r < 2; r++) {
                    int I = 4 * (p + 2 * q) + (r + 2 * s);
                    const double *A = a[p][r], *B = b[q][s];
                    if (N) N[I] = A[0] * B[0];
                    if (N1) N1[I] = A[1] * B[0] * is;
                    if (N2) N2[I] = A[0] * B[1] * it;
                    if (N11) N11[I] = A[2] * B[0] * is * is;
                    if (N12) N12[I] = A[1] * B[1] * is * it;
                    if (N22) N22[I] = A[0] * B[2] * it * it;
                }
}

/* BHEM App. A, Eq. (37)-(38): 4-point Gauss–Legendre on [0,1],
 * th = 1/2 -+ 1/2 sqrt(3/7 -+ 2/7 sqrt(6/5)); inner weights (18+sqrt30)/72,
 * outer (18-sqrt30)/72 (per unit length; the patch size enters separately).
 * The paper's closed form is kept rather than GSL's table (issue 31): the
 * nodes and outer weights are bit-identical to gsl_integration_glfixed_point
 * on [0, 1], the inner weight is 1 ulp larger (0.3260725774312731 against
 * ...305), and BHEM's reported figures were computed with it;
 * tests/test_bhem_basis.c checks the rule against GSL's to 2 ulp.  Per
 * quadrature point nothing of GSL is called: the rule is built once. */
void bhem_gauss_rule(double x[BHEM_NQ1], double w[BHEM_NQ1])
{
    double a = sqrt(3.0 / 7.0 - 2.0 / 7.0 * sqrt(6.0 / 5.0));  /* inner */
    double b = sqrt(3.0 / 7.0 + 2.0 / 7.0 * sqrt(6.0 / 5.0));  /* outer */
    double wi = (18.0 + sqrt(30.0)) / 72.0, wo = (18.0 - sqrt(30.0)) / 72.0;
    x[0] = 0.5 - 0.5 * b; w[0] = wo;
    x[1] = 0.5 - 0.5 * a; w[1] = wi;
    x[2] = 0.5 + 0.5 * a; w[2] = wi;
    x[3] = 0.5 + 0.5 * b; w[3] = wo;
}
