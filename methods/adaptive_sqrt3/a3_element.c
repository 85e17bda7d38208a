/* a3_element.c — the element kernels of adaptive_sqrt3 (model and
 * assumptions in a3.h): the corotational orthotropic membrane triangle
 * (sqrt3 paper Eq. 5-17), the isometric bending edge (Eq. 18-19) and the
 * hybrid Voronoi corner areas of the lumped mass (Alg. 1, Eq. 1). */
#include "sb_vec3.h"
#include "a3.h"

#include <math.h>
#include <string.h>

static inline void sub3(const double *a, const double *b, double *c)
{
    c[0] = a[0] - b[0];
    c[1] = a[1] - b[1];
    c[2] = a[2] - b[2];
}

int a3_tri_init(a3_tri *T, const double *Xa, const double *Xb, const double *Xc, const double w[3],
                const double C[9])
{
    double d1[3], d2[3], N[3], e1[3], e2[3];
    sub3(Xb, Xa, d1);
    sub3(Xc, Xa, d2);
    sb_cross3(d1, d2, N);
    const double an = sqrt(sb_dot3(N, N));
    if (!(an > 1e-14 * sb_dot3(d1, d1)) || !isfinite(an)) return SB_ERR_INPUT;
    for (int c = 0; c < 3; c++) N[c] /= an;
    /* 2D rest frame (Eq. 13, assumption a3.h): the warp direction w in the
     * triangle's plane, e2 = N x e1 */
    const double wn = sb_dot3(w, N);
    for (int c = 0; c < 3; c++) e1[c] = w[c] - wn * N[c];
    const double l1 = sqrt(sb_dot3(e1, e1));
    if (!(l1 > 1e-12)) return SB_ERR_INPUT;
    for (int c = 0; c < 3; c++) e1[c] /= l1;
    sb_cross3(N, e1, e2);
    T->area = 0.5 * an;
    memset(T->x0, 0, sizeof T->x0);
    T->x0[2] = sb_dot3(e1, d1);
    T->x0[3] = sb_dot3(e2, d1);
    T->x0[4] = sb_dot3(e1, d2);
    T->x0[5] = sb_dot3(e2, d2);
    /* shape function derivatives (Eq. 5, Appendix A): [N_b; N_c] = S^-1 (m - m_a),
     * S of Eq. 13 */
    const double s00 = T->x0[2], s01 = T->x0[4], s10 = T->x0[3], s11 = T->x0[5];
    const double det = s00 * s11 - s01 * s10;
    if (!(det > 0.0)) return SB_ERR_INPUT;
    const double G[4] = { s11 / det, -s01 / det, -s10 / det, s00 / det };
    const double dN[3][2] = { { -G[0] - G[2], -G[1] - G[3] }, { G[0], G[1] }, { G[2], G[3] } };
    /* B_e of Eq. 7 (3 x 6): (eps_x, eps_y, gamma_xy) with gamma = 1/2 (du/dy + dv/dx) */
    double B[18] = { 0 };
    for (int i = 0; i < 3; i++) {
        B[0 * 6 + 2 * i] = dN[i][0];
        B[1 * 6 + 2 * i + 1] = dN[i][1];
        B[2 * 6 + 2 * i] = 0.5 * dN[i][1];
        B[2 * 6 + 2 * i + 1] = 0.5 * dN[i][0];
    }
    /* K_e = A_e B^T C B (Eq. 10) */
    double CB[18];
    for (int r = 0; r < 3; r++)
        for (int j = 0; j < 6; j++) CB[r * 6 + j] = C[3 * r] * B[j] + C[3 * r + 1] * B[6 + j] + C[3 * r + 2] * B[12 + j];
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++)
            T->K[6 * i + j] = T->area * (B[i] * CB[j] + B[6 + i] * CB[6 + j] + B[12 + i] * CB[12 + j]);
    /* symmetrize against round-off (C is symmetric, a3_method.c) */
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < i; j++) T->K[6 * i + j] = T->K[6 * j + i] = 0.5 * (T->K[6 * i + j] + T->K[6 * j + i]);
    return SB_OK;
}

/* R_p = P^T R of the current triangle (Eq. 11, 12, 14, 15), 3 x 2 row-major.
 * 0, or -1 when the triangle is degenerate. */
static int corot_frame(const a3_tri *T, const double *q, double Rp[6])
{
    double d1[3], d2[3], n[3], px[3], py[3];
    sub3(q + 3, q, d1);
    sub3(q + 6, q, d2);
    const double l1 = sqrt(sb_dot3(d1, d1));
    if (!(l1 > 0.0) || !isfinite(l1)) return -1;
    for (int c = 0; c < 3; c++) px[c] = d1[c] / l1;        /* Eq. 11 */
    sb_cross3(d1, d2, n);
    sb_cross3(n, px, py);
    const double ly = sqrt(sb_dot3(py, py));
    if (!(ly > 0.0) || !isfinite(ly)) return -1;
    for (int c = 0; c < 3; c++) py[c] /= ly;
    /* T (Eq. 14) in the plane (P x, Eq. 12): columns (l1, 0) and (px.d2, py.d2) */
    const double t00 = l1, t01 = sb_dot3(px, d2), t11 = sb_dot3(py, d2);
    /* F = T S^-1 */
    const double s00 = T->x0[2], s01 = T->x0[4], s10 = T->x0[3], s11 = T->x0[5];
    const double det = s00 * s11 - s01 * s10;
    const double g00 = s11 / det, g01 = -s01 / det, g10 = -s10 / det, g11 = s00 / det;
    const double F00 = t00 * g00 + t01 * g10, F01 = t00 * g01 + t01 * g11;
    const double F10 = t11 * g10, F11 = t11 * g11;
    /* 2D polar decomposition [29]: the rotation R maximizing tr(R^T F) */
    const double cs = F00 + F11, sn = F10 - F01, r = hypot(cs, sn);
    if (!(r > 0.0)) return -1;
    const double c = cs / r, s = sn / r;
    /* R_p = P^T R (Eq. 15): columns c px + s py and -s px + c py */
    for (int k = 0; k < 3; k++) {
        Rp[2 * k] = c * px[k] + s * py[k];
        Rp[2 * k + 1] = -s * px[k] + c * py[k];
    }
    return 0;
}

double a3_membrane(const a3_tri *T, const double *q, const double *Rp_fixed, double *Rp_out, double *g, double *H)
{
    double Rp[6];
    if (Rp_fixed)
        memcpy(Rp, Rp_fixed, sizeof Rp);
    else if (corot_frame(T, q, Rp))
        return NAN;
    if (Rp_out) memcpy(Rp_out, Rp, sizeof Rp);
    /* u = R_p^T x - x0bar (Fig. 2(c)), with x relative to corner a: the
     * translation is in the kernel of K_e */
    double u[6], Ku[6];
    for (int i = 0; i < 3; i++) {
        double d[3];
        sub3(q + 3 * i, q, d);
        u[2 * i] = Rp[0] * d[0] + Rp[2] * d[1] + Rp[4] * d[2] - T->x0[2 * i];
        u[2 * i + 1] = Rp[1] * d[0] + Rp[3] * d[1] + Rp[5] * d[2] - T->x0[2 * i + 1];
    }
    double E = 0.0;
    for (int i = 0; i < 6; i++) {
        double s = 0.0;
        for (int j = 0; j < 6; j++) s += T->K[6 * i + j] * u[j];
        Ku[i] = s;
        E += 0.5 * u[i] * s;
    }
    /* -f_e = R_p K_e (R_p^T x - x0bar) (Eq. 16-17) */
    if (g)
        for (int i = 0; i < 3; i++)
            for (int c = 0; c < 3; c++) g[3 * i + c] += Rp[2 * c] * Ku[2 * i] + Rp[2 * c + 1] * Ku[2 * i + 1];
    /* K_e^R = R_p K_e R_p^T (Eq. 16) */
    if (H)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double k00 = T->K[6 * (2 * i) + 2 * j], k01 = T->K[6 * (2 * i) + 2 * j + 1];
                const double k10 = T->K[6 * (2 * i + 1) + 2 * j], k11 = T->K[6 * (2 * i + 1) + 2 * j + 1];
                for (int c = 0; c < 3; c++) {
                    const double a0 = Rp[2 * c] * k00 + Rp[2 * c + 1] * k10;
                    const double a1 = Rp[2 * c] * k01 + Rp[2 * c + 1] * k11;
                    for (int d = 0; d < 3; d++) H[(3 * i + c) * 9 + 3 * j + d] += a0 * Rp[2 * d] + a1 * Rp[2 * d + 1];
                }
            }
    return E;
}

/* cot of the angle at P between P->A and P->B */
static double cot_at(const double *P, const double *A, const double *B)
{
    double u[3], v[3], w[3];
    sub3(A, P, u);
    sub3(B, P, v);
    sb_cross3(u, v, w);
    return sb_dot3(u, v) / sqrt(sb_dot3(w, w));
}

void a3_bend_weights(const double *X0, const double *X1, const double *X2, const double *X3, double k[4])
{
    /* Eq. 19 with Fig. 3's labels: c01, c02 the cotangents at x0 in t0
     * (towards x2) and t1 (towards x3), c03, c04 those at x1 (Bergou et al.) */
    const double c01 = cot_at(X0, X1, X2), c02 = cot_at(X0, X1, X3);
    const double c03 = cot_at(X1, X0, X2), c04 = cot_at(X1, X0, X3);
    k[0] = c03 + c04;
    k[1] = c01 + c02;
    k[2] = -c01 - c03;
    k[3] = -c02 - c04;
}

double a3_bend(const a3_edge *e, const double *q12, double *g, double *H)
{
    double s[3] = { 0, 0, 0 };
    for (int i = 0; i < 4; i++)
        for (int c = 0; c < 3; c++) s[c] += e->k[i] * q12[3 * i + c];
    /* E = (k_b/2) x^T Q x, Q = 3/(A_0 + A_1) k^T k (Eq. 18); e->q holds k_b 3/(A_0+A_1) */
    if (g)
        for (int i = 0; i < 4; i++)
            for (int c = 0; c < 3; c++) g[3 * i + c] += e->q * e->k[i] * s[c];
    if (H)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                for (int c = 0; c < 3; c++) H[(3 * i + c) * 12 + 3 * j + c] += e->q * e->k[i] * e->k[j];
    return 0.5 * e->q * sb_dot3(s, s);
}

void a3_voronoi(const double *Xa, const double *Xb, const double *Xc, double A[3])
{
    const double *P[3] = { Xa, Xb, Xc };
    double cot[3], l2[3], n[3], d1[3], d2[3];
    int obtuse = -1;
    for (int i = 0; i < 3; i++) {
        const double *Pi = P[i], *Pj = P[(i + 1) % 3], *Pk = P[(i + 2) % 3];
        sub3(Pj, Pi, d1);
        sub3(Pk, Pi, d2);
        if (sb_dot3(d1, d2) < 0.0) obtuse = i;
        cot[i] = cot_at(Pi, Pj, Pk);
        l2[i] = sb_dot3(d1, d1);            /* |P_{i+1} - P_i|^2 */
    }
    sub3(Xb, Xa, d1);
    sub3(Xc, Xa, d2);
    sb_cross3(d1, d2, n);
    const double At = 0.5 * sqrt(sb_dot3(n, n));
    if (obtuse < 0) {
        /* Eq. 1: A(t, x_i) = 1/8 (|x_k - x_i|^2 cot phi_j + |x_j - x_i|^2 cot phi_k) */
        for (int i = 0; i < 3; i++) {
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            A[i] = (l2[k] * cot[j] + l2[i] * cot[k]) / 8.0;
        }
    } else {
        /* Alg. 1, lines 6-10 */
        for (int i = 0; i < 3; i++) A[i] = i == obtuse ? 0.5 * At : 0.25 * At;
    }
}
