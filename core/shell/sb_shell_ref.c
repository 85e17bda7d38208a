/* sb_shell_ref.c — reference quantities of the Kirchhoff–Love kernel at one
 * quadrature point: metric, second fundamental form, area element and the
 * covariant -> local (warp/weft) strain transformation. */
#include "sb_shell.h"

#include <math.h>
#include <string.h>

const char *const sb_hess_kind_names[] = { "exact", "pseudo", "psd", NULL };

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static int ref_fail(sb_shell_ref *r)
{
    double *p = (double *)r;
    for (size_t i = 0; i < sizeof *r / sizeof(double); i++) p[i] = NAN;
    return SB_ERR_INPUT;
}

int sb_shell_ref_init(sb_shell_ref *r, const double X1[3], const double X2[3],
                      const double X11[3], const double X12[3], const double X22[3],
                      double warp_angle, double weight)
{
    if (!r) return SB_ERR_INPUT;
    if (!X1 || !X2 || !X11 || !X12 || !X22) return ref_fail(r);
    for (int c = 0; c < 3; c++)
        if (!isfinite(X1[c]) || !isfinite(X2[c]) || !isfinite(X11[c]) || !isfinite(X12[c]) ||
            !isfinite(X22[c]))
            return ref_fail(r);
    if (!isfinite(warp_angle) || !isfinite(weight)) return ref_fail(r);

    /* first fundamental form abar_ab = X_a . X_b */
    const double a11 = dot3(X1, X1), a22 = dot3(X2, X2), a12 = dot3(X1, X2);
    double c[3];
    cross3(X1, X2, c);
    const double J = sqrt(dot3(c, c));          /* = sqrt(det abar) */
    const double det = a11 * a22 - a12 * a12;
    /* degenerate: tangents (nearly) parallel relative to their lengths */
    if (!(J > 1e-12 * sqrt(a11 * a22)) || !(det > 0)) return ref_fail(r);

    r->abar[0] = a11;
    r->abar[1] = a22;
    r->abar[2] = a12;
    r->ainv[0] = a22 / det;
    r->ainv[1] = a11 / det;
    r->ainv[2] = -a12 / det;
    r->sqrt_a = J;
    r->weight = weight;
    r->dA = weight * J;
    for (int i = 0; i < 3; i++) r->normal[i] = c[i] / J;
    /* second fundamental form bbar_ab = X_,ab . N (BHEM paper Eq. 4a) */
    r->bbar[0] = dot3(X11, r->normal);
    r->bbar[1] = dot3(X22, r->normal);
    r->bbar[2] = dot3(X12, r->normal);

    /* local frame: warp e1 = cos(t) X1/|X1| + sin(t) N x X1/|X1|, weft e2 = N x e1 */
    const double l1 = sqrt(a11);
    double t1[3], t2[3];
    for (int i = 0; i < 3; i++) t1[i] = X1[i] / l1;
    cross3(r->normal, t1, t2);
    const double cw = cos(warp_angle), sw = sin(warp_angle);
    for (int i = 0; i < 3; i++) r->e1[i] = cw * t1[i] + sw * t2[i];
    cross3(r->normal, r->e1, r->e2);

    /* contravariant base vectors abar^a = abar^{ab} X_b and c_ia = e_i . abar^a.
     * Local components E_ij = E_ab (e_i . abar^a)(e_j . abar^b), i.e. with
     * Voigt (E11, E22, E12) on both sides: */
    double g1[3], g2[3];
    for (int i = 0; i < 3; i++) {
        g1[i] = r->ainv[0] * X1[i] + r->ainv[2] * X2[i];
        g2[i] = r->ainv[2] * X1[i] + r->ainv[1] * X2[i];
    }
    const double c10 = dot3(r->e1, g1), c11 = dot3(r->e1, g2);
    const double c20 = dot3(r->e2, g1), c21 = dot3(r->e2, g2);
    double *T = r->T;
    T[0] = c10 * c10;  T[1] = c11 * c11;  T[2] = 2.0 * c10 * c11;
    T[3] = c20 * c20;  T[4] = c21 * c21;  T[5] = 2.0 * c20 * c21;
    T[6] = c10 * c20;  T[7] = c11 * c21;  T[8] = c10 * c21 + c11 * c20;
    return SB_OK;
}

int sb_shell_ref_init_basis(sb_shell_ref *r, const sb_shell_basis *b, const double *Xq,
                            double warp_angle, double weight)
{
    if (!r) return SB_ERR_INPUT;
    if (!b || !Xq || b->k < 1 || b->k > SB_SHELL_MAX_BASIS || !b->N1 || !b->N2 || !b->N11 ||
        !b->N12 || !b->N22)
        return ref_fail(r);
    double X[5][3];
    memset(X, 0, sizeof X);
    const double *W[5] = { b->N1, b->N2, b->N11, b->N12, b->N22 };
    for (int I = 0; I < b->k; I++)
        for (int s = 0; s < 5; s++)
            for (int c = 0; c < 3; c++) X[s][c] += W[s][I] * Xq[3 * I + c];
    return sb_shell_ref_init(r, X[0], X[1], X[2], X[3], X[4], warp_angle, weight);
}
