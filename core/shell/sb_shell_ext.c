/* sb_shell_ext.c — external potential of one quadrature point: gravity and
 * pressure, with gradient and (follower pressure only) Hessian.
 *
 * Gravity (RMTR paper Eq. 3.2, potential term rho g^T r integrated through the
 * thickness; BHEM paper §3.4 f_grav): areal density rho (kg/m^2), dead load,
 *     E = - rho (g . x) dA.
 * Dead pressure (follower = 0): force p N dA on the reference normal N,
 *     E = - p (N . x) dA                         (linear; no Hessian).
 * Follower pressure (follower = 1): force p n da on the deformed normal
 * (BHEM paper §3.4 f_press = p n).  It is made conservative through the
 * enclosed-volume potential E = -p V with
 *     V = 1/3 int x . (x_,1 x x_,2) dxi1 dxi2,
 * whose first variation is int dx . (x_,1 x x_,2) dxi (= p n da) plus boundary
 * terms that vanish on closed surfaces and on fixed boundaries.  ASSUMPTION,
 * stated for users: on an open surface with free edges the potential depends on
 * the origin and adds edge forces; scenes with free-edged follower pressure are
 * then only approximately the paper's load (no scene in the suite uses one). */
#include "sb_shell.h"

#include <math.h>

static inline void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

double sb_shell_external(const sb_material *m, const sb_shell_ref *r, const sb_shell_basis *b,
                         const double *q, const double gvec[3], double pressure, int follower,
                         double *grad, double *hess)
{
    if (!m || !r || !b || !q || !b->N || b->k < 1 || b->k > SB_SHELL_MAX_BASIS) return NAN;
    if (follower && (!b->N1 || !b->N2)) return NAN;
    const int k = b->k;
    double x[3] = { 0, 0, 0 }, x1[3] = { 0, 0, 0 }, x2[3] = { 0, 0, 0 };
    for (int I = 0; I < k; I++)
        for (int c = 0; c < 3; c++) {
            x[c] += b->N[I] * q[3 * I + c];
            if (follower) {
                x1[c] += b->N1[I] * q[3 * I + c];
                x2[c] += b->N2[I] * q[3 * I + c];
            }
        }

    /* dead part: E = -(f . x) dA with f = rho g (+ p N when not follower) */
    double f[3] = { 0, 0, 0 };
    if (gvec)
        for (int c = 0; c < 3; c++) f[c] = m->density * gvec[c];
    if (!follower && pressure != 0.0)
        for (int c = 0; c < 3; c++) f[c] += pressure * r->normal[c];
    for (int c = 0; c < 3; c++) f[c] *= r->dA;
    double e = -(f[0] * x[0] + f[1] * x[1] + f[2] * x[2]);
    if (grad)
        for (int I = 0; I < k; I++)
            for (int c = 0; c < 3; c++) grad[3 * I + c] -= b->N[I] * f[c];

    if (!follower || pressure == 0.0) return e;

    /* follower: E = s x . (x1 x x2), s = -p w / 3 (w = parameter-domain weight) */
    const double s = -pressure * r->weight / 3.0;
    double c12[3], c2x[3], cx1[3];
    cross3(x1, x2, c12);
    cross3(x2, x, c2x);
    cross3(x, x1, cx1);
    e += s * (x[0] * c12[0] + x[1] * c12[1] + x[2] * c12[2]);
    if (grad)
        for (int I = 0; I < k; I++)
            for (int c = 0; c < 3; c++)
                grad[3 * I + c] += s * (b->N[I] * c12[c] + b->N1[I] * c2x[c] + b->N2[I] * cx1[c]);
    if (hess) {
        /* trilinear T(x, x1, x2): blocks (x,x1) = -[x2], (x,x2) = [x1], (x1,x2) = -[x];
         * the (t,s) block is the transpose of (s,t) and diagonal blocks vanish. */
        const double *vs[3] = { x2, x1, x };   /* vector in the skew block of pair p */
        const double sg[3] = { -1.0, 1.0, -1.0 };
        const int pa[3] = { 0, 0, 1 }, pb[3] = { 1, 2, 2 };
        const double *Wt[3] = { b->N, b->N1, b->N2 };
        const int n3 = 3 * k;
        for (int p = 0; p < 3; p++) {
            const double *vv = vs[p];
            /* S = [vv]_x; the sign sg[p] goes into c1, c2 */
            const double S[9] = { 0, -vv[2], vv[1], vv[2], 0, -vv[0], -vv[1], vv[0], 0 };
            const double *wa = Wt[pa[p]], *wb = Wt[pb[p]];
            for (int I = 0; I < k; I++)
                for (int J = 0; J < k; J++) {
                    /* d2E/dq_I dq_J += s sg (wa_I wb_J S + wb_I wa_J S^T) */
                    const double c1 = s * sg[p] * wa[I] * wb[J], c2 = s * sg[p] * wb[I] * wa[J];
                    if (c1 == 0.0 && c2 == 0.0) continue;
                    double *h = hess + (size_t)(3 * I) * n3 + 3 * J;
                    for (int a = 0; a < 3; a++)
                        for (int d = 0; d < 3; d++)
                            h[(size_t)a * n3 + d] += c1 * S[3 * a + d] + c2 * S[3 * d + a];
                }
        }
    }
    return e;
}
