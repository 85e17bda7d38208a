/* sb_elem_point.c — the fast Kirchhoff–Love kernel per element: the
 * quadrature points (jet, strains, section law, the 15 x 15 local Hessian K
 * and its Z rows), the gradient, the products and the scatter into the
 * element matrix.  What it exploits is listed in sb_shell_elem.c's header.
 *
 * Compiled once per vector width (Makefile VEC_SRC; SB_VEC_FN names the
 * exported functions, sb_shell_isa.c dispatches on the batch's width):
 * every sum over the basis or the points is either lane-wise (one output
 * entry per lane, the same operations in the same order at any width) or
 * taken in explicit 2-lane vectors (the jet), and contraction into FMA is
 * off, so all widths give the same bits (tests/test_shell_fast.c,
 * vector_widths_same_bits).  The scalar code in between gains the VEX
 * encoding's three-operand form in the AVX2 and AVX-512 builds. */
#include "sb_shell_batch.h"

#include <math.h>
#include <string.h>

/* D = dA blockdiag(T, T)^T C6 blockdiag(T, T): the material-frame section
 * tangent in covariant strain components (a congruence: PSD stays PSD).
 * Fully unrolled (constant indices, no index arithmetic in the loops) and
 * the upper triangle only (D symmetric); every entry is the same expression
 * in the same order as before, so the bits are unchanged. */
static void congruence6(const double *C6, const double *T, double dA, double D[6][6])
{
    double CT[6][6];
#pragma GCC unroll 6
    for (int i = 0; i < 6; i++)
#pragma GCC unroll 6
        for (int j = 0; j < 6; j++) {
            const int jb = j < 3 ? 0 : 3, jj = j - jb;
            CT[i][j] = C6[6 * i + jb] * T[jj] + C6[6 * i + jb + 1] * T[3 + jj] + C6[6 * i + jb + 2] * T[6 + jj];
        }
#pragma GCC unroll 6
    for (int i = 0; i < 6; i++)
#pragma GCC unroll 6
        for (int j = i; j < 6; j++) {
            const int ib = i < 3 ? 0 : 3, ii = i - ib;
            D[i][j] = D[j][i] = dA * (T[ii] * CT[ib][j] + T[3 + ii] * CT[ib + 1][j] + T[6 + ii] * CT[ib + 2][j]);
        }
}

/* x-slot parts of J = d(A, B)/dy (rows A11 A22 A12 B0 B1 B2; slots x_,1
 * x_,2); the v-slot part of bending row i is n/2 in slot bslot[i] */
static void jacobian_x(const double *x1, const double *x2, double gv[3][3], double Jx[6][2][3])
{
    for (int d = 0; d < 3; d++) {
        Jx[0][0][d] = x1[d];       Jx[0][1][d] = 0.0;
        Jx[1][0][d] = 0.0;         Jx[1][1][d] = x2[d];
        Jx[2][0][d] = 0.5 * x2[d]; Jx[2][1][d] = 0.5 * x1[d];
    }
    for (int i = 0; i < 3; i++) {
        double t1[3], t2[3];
        cross3(x2, gv[i], t1);
        cross3(gv[i], x1, t2);
        for (int d = 0; d < 3; d++) {
            Jx[3 + i][0][d] = 0.5 * t1[d];
            Jx[3 + i][1][d] = 0.5 * t2[d];
        }
    }
}

/* K = J^T D J in the local jet, the blocks on and above the block diagonal
 * (slot s <= t), exploiting J's sparsity: the x-slot rows that touch slot s
 * are s (A11 for x_,1, A22 for x_,2), 2 (A12) and the bending rows 3..5 —
 * row 1 - s is zero in slot s and is skipped (a zero term of each sum: the
 * other terms keep their order, so the bits are those of the full sums).
 * Fully unrolled: constant indices only. */
static void jtdj(double Jx[6][2][3], const double *n, double D[6][6], double K[15][15])
{
    /* DJx[r][s][d] = sum_q D[r][q] Jx[q][s][d], q over s, 2, 3, 4, 5 */
    double DJx[6][2][3];
#pragma GCC unroll 6
    for (int rr = 0; rr < 6; rr++)
#pragma GCC unroll 2
        for (int s = 0; s < 2; s++)
#pragma GCC unroll 3
            for (int d = 0; d < 3; d++)
                DJx[rr][s][d] = D[rr][s] * Jx[s][s][d] + D[rr][2] * Jx[2][s][d] + D[rr][3] * Jx[3][s][d] +
                                D[rr][4] * Jx[4][s][d] + D[rr][5] * Jx[5][s][d];
    /* (x, x) blocks: sum_r Jx[r][s][c] DJx[r][t][d], r over s, 2, 3, 4, 5 */
#pragma GCC unroll 2
    for (int s = 0; s < 2; s++)
#pragma GCC unroll 2
        for (int tt = s; tt < 2; tt++)
#pragma GCC unroll 3
            for (int cc = 0; cc < 3; cc++)
#pragma GCC unroll 3
                for (int d = 0; d < 3; d++)
                    K[3 * s + cc][3 * tt + d] = Jx[s][s][cc] * DJx[s][tt][d] + Jx[2][s][cc] * DJx[2][tt][d] +
                                                Jx[3][s][cc] * DJx[3][tt][d] + Jx[4][s][cc] * DJx[4][tt][d] +
                                                Jx[5][s][cc] * DJx[5][tt][d];
    /* (x, v_i) blocks: (sum_r Jx[r][s][c] D[r][3+i]) n_d / 2 */
#pragma GCC unroll 2
    for (int s = 0; s < 2; s++)
#pragma GCC unroll 3
        for (int i = 0; i < 3; i++)
#pragma GCC unroll 3
            for (int cc = 0; cc < 3; cc++) {
                const double u = Jx[s][s][cc] * D[s][3 + i] + Jx[2][s][cc] * D[2][3 + i] +
                                 Jx[3][s][cc] * D[3][3 + i] + Jx[4][s][cc] * D[4][3 + i] +
                                 Jx[5][s][cc] * D[5][3 + i];
#pragma GCC unroll 3
                for (int d = 0; d < 3; d++) K[3 * s + cc][3 * bslot[i] + d] = 0.5 * u * n[d];
            }
    /* (v_i, v_j) blocks: D[3+i][3+j] n_c n_d / 4 */
#pragma GCC unroll 3
    for (int i = 0; i < 3; i++)
#pragma GCC unroll 3
        for (int j = 0; j < 3; j++) {
            const int si = bslot[i], sj = bslot[j];
            if (sj < si) continue;
#pragma GCC unroll 3
            for (int cc = 0; cc < 3; cc++)
#pragma GCC unroll 3
                for (int d = 0; d < 3; d++) K[3 * si + cc][3 * sj + d] = 0.25 * D[3 + i][3 + j] * n[cc] * n[d];
        }
}

/* [s00 s01; s01 s11] <- its positive semidefinite part (kept when it is
 * PSD): S+ = lp v v^T = lp (S - lm I) / (lp - lm) with lp >= lm its
 * eigenvalues, 0 when lp <= 0 */
static inline void psd_part2(double *s00, double *s11, double *s01)
{
    const double a = *s00, b = *s11, c = *s01;
    if (a >= 0.0 && b >= 0.0 && a * b - c * c >= 0.0) return;
    const double mean = 0.5 * (a + b), rad = sqrt(0.25 * (a - b) * (a - b) + c * c);
    const double lp = mean + rad, lm = mean - rad;
    if (lp <= 0.0) {
        *s00 = *s11 = *s01 = 0.0;
    } else {
        const double f = lp / (lp - lm);
        *s00 = f * (a - lm);
        *s11 = f * (b - lm);
        *s01 = f * c;
    }
}

/* ---- one quadrature point ---------------------------------------------------- */

/* Energy of point p; fills Gt rows (gradient de/dy) and, with hess, the Z
 * rows of the point.  Wt rows of the point must be in place. */
static double point(const sb_material *m, const sb_shell_ref *r, int p, int kp, int need_g, int need_h,
                    sb_hess_kind kind, sb_shell_batch *w)
{
    const double *Wp = w->Wt + (size_t)5 * p * kp;
    /* 1. the jet y[s][c] = sum_I W_s^I q_I,c: dot products over I in 2-lane
     * vectors at every width (the even and the odd I summed apart, then
     * added), so that the sums have one order in every build */
    double y[5][3];
    for (int s = 0; s < 5; s++) {
        sb_v2d a0 = { 0.0, 0.0 }, a1 = a0, a2 = a0;
        const double *ws = Wp + (size_t)s * kp;
        for (int I = 0; I < kp; I += 2) {
            const sb_v2d wv = sb_v2load(ws + I);
            a0 += wv * sb_v2load(w->qd + I);
            a1 += wv * sb_v2load(w->qd + kp + I);
            a2 += wv * sb_v2load(w->qd + 2 * kp + I);
        }
        double t0 = 0, t1 = 0, t2 = 0;
        for (int l = 0; l < 2; l++) {
            t0 += a0[l];
            t1 += a1[l];
            t2 += a2[l];
        }
        y[s][0] = t0;
        y[s][1] = t1;
        y[s][2] = t2;
    }
    /* 2. strains (BHEM paper Eq. 4a, 5, 6a; sb_shell.c local_strains) */
    const double *x1 = y[S_X1], *x2 = y[S_X2];
    const double *v[3] = { y[S_X11], y[S_X22], y[S_X12] };
    double c[3], n[3];
    cross3(x1, x2, c);
    const double rho = sqrt(dot3(c, c)), irho = 1.0 / rho;
    for (int i = 0; i < 3; i++) n[i] = c[i] * irho;
    const double A[3] = { 0.5 * (dot3(x1, x1) - r->abar[0]), 0.5 * (dot3(x2, x2) - r->abar[1]),
                          0.5 * (dot3(x1, x2) - r->abar[2]) };
    const double fv[3] = { dot3(v[0], n), dot3(v[1], n), dot3(v[2], n) };
    const double B[3] = { 0.5 * (fv[0] - r->bbar[0]), 0.5 * (fv[1] - r->bbar[1]), 0.5 * (fv[2] - r->bbar[2]) };
    const double *T = r->T;
    double TA[3], TB[3];
    for (int i = 0; i < 3; i++) {
        TA[i] = T[3 * i] * A[0] + T[3 * i + 1] * A[1] + T[3 * i + 2] * A[2];
        TB[i] = T[3 * i] * B[0] + T[3 * i + 1] * B[1] + T[3 * i + 2] * B[2];
    }
    /* 3. through the thickness (BHEM paper Eq. 6a, 7) */
    double sA[3], sB[3], C6[36];
    const double dA = r->dA;
    const double e = dA * sb_section_fast_isa(w->isa, m, TA, TB, need_g ? sA : NULL, need_g ? sB : NULL,
                                                need_h ? C6 : NULL);
    if (!need_g) return e;

    /* 4a. covariant generalized forces nA = dA T^T sA, nB = dA T^T sB */
    double nA[3], nB[3];
    for (int i = 0; i < 3; i++) {
        nA[i] = dA * (T[i] * sA[0] + T[3 + i] * sA[1] + T[6 + i] * sA[2]);
        nB[i] = dA * (T[i] * sB[0] + T[3 + i] * sB[1] + T[6 + i] * sB[2]);
    }
    /* P v_i / |c| and V = sum nB_i/2 v_i, gV = P V / |c| */
    double gv[3][3], V[3], gV[3];
    for (int i = 0; i < 3; i++)
        for (int d = 0; d < 3; d++) gv[i][d] = (v[i][d] - fv[i] * n[d]) * irho;
    for (int d = 0; d < 3; d++) {
        V[d] = 0.5 * (nB[0] * v[0][d] + nB[1] * v[1][d] + nB[2] * v[2][d]);
        gV[d] = 0.5 * (nB[0] * gv[0][d] + nB[1] * gv[1][d] + nB[2] * gv[2][d]);
    }
    /* 4b. local gradient de/dy, stored as the point's rows of Gt */
    double *G = w->Gt + (size_t)15 * p, t[3];
    for (int d = 0; d < 3; d++) {
        G[3 * S_X1 + d] = nA[0] * x1[d] + 0.5 * nA[2] * x2[d];
        G[3 * S_X2 + d] = nA[1] * x2[d] + 0.5 * nA[2] * x1[d];
        for (int i = 0; i < 3; i++) G[3 * bslot[i] + d] = 0.5 * nB[i] * n[d];
    }
    cross3(x2, gV, t);
    for (int d = 0; d < 3; d++) G[3 * S_X1 + d] += t[d];
    cross3(gV, x1, t);
    for (int d = 0; d < 3; d++) G[3 * S_X2 + d] += t[d];
    if (!need_h) return e;

    /* 4c. K = J^T D J + membrane and bending second derivatives (15 x 15) */
    if (kind == SB_HESS_PSD) sb_elem_psd_part(6, C6);   /* section tangent in the material frame */
    double D[6][6], Jx[6][2][3], K[15][15];
    congruence6(C6, T, dA, D);
    jacobian_x(x1, x2, gv, Jx);
    jtdj(Jx, n, D, K);
    double *kd = w->keep ? w->kd + (size_t)KD * p : NULL;
    if (kd) {   /* what the strain-space projection takes away from J^T D J */
        kd[KD - 1] = sb_elem_pos_def(6, C6);
        kd[48] = 0.0;
        if (kd[KD - 1] == 0.0) {
            /* C6 - C6+ = sum_l lam_l v_l v_l^T over its negative eigenvalues,
             * so J^T (D - D+) J = -sum_l u_l u_l^T with
             * u_l = sqrt(-lam_l dA) J^T blockdiag(T, T)^T v_l: one rank-1
             * term per clamped eigenvalue (ΔD has rank 1-2) instead of the
             * full 5-slot J^T ΔD J */
            double lam[6], vec[36];
            const int nn = sb_elem_neg_eig(6, C6, lam, vec);
            kd[48] = nn;
            for (int l = 0; l < nn; l++) {
                const double *vl = vec + 6 * l, f = sqrt(-lam[l] * dA);
                double wv[6];
                for (int i = 0; i < 3; i++) {
                    wv[i] = f * (T[i] * vl[0] + T[3 + i] * vl[1] + T[6 + i] * vl[2]);
                    wv[3 + i] = f * (T[i] * vl[3] + T[3 + i] * vl[4] + T[6 + i] * vl[5]);
                }
                double *u = kd + 49 + 15 * l;
                for (int sx = 0; sx < 2; sx++)
                    for (int d = 0; d < 3; d++)
                        u[3 * sx + d] = Jx[sx][sx][d] * wv[sx] + Jx[2][sx][d] * wv[2] + Jx[3][sx][d] * wv[3] +
                                        Jx[4][sx][d] * wv[4] + Jx[5][sx][d] * wv[5];
                for (int i = 0; i < 3; i++)
                    for (int d = 0; d < 3; d++) u[3 * bslot[i] + d] = 0.5 * wv[3 + i] * n[d];
            }
        }
    }
    /* only the blocks on and above the block diagonal (slot s <= t) are
     * formed from here on; the Z product below reads the others by symmetry */
    /* membrane second derivatives (BHEM paper Eq. 51-53); kind PSD: the PSD
     * part of the 2 x 2 stress resultant S = [nA0, nA2/2; nA2/2, nA1] */
    double s00 = nA[0], s11 = nA[1], s01 = 0.5 * nA[2];
    if (kd) {   /* the PSD difference: S - S+ on the diagonal blocks, below the bending terms */
        double t00 = s00, t11 = s11, t01 = s01;
        psd_part2(&t00, &t11, &t01);
        for (int i = 0; i < 27; i++) kd[i] = 0.0;
        for (int d = 0; d < 3; d++) {
            kd[4 * d] = s00 - t00;             /* B11 += (S - S+)_00 I */
            kd[9 + 4 * d] = s01 - t01;         /* B12 */
            kd[18 + 4 * d] = s11 - t11;        /* B22 */
        }
    }
    if (kind == SB_HESS_PSD) psd_part2(&s00, &s11, &s01);
    for (int d = 0; d < 3; d++) {
        K[3 * S_X1 + d][3 * S_X1 + d] += s00;
        K[3 * S_X2 + d][3 * S_X2 + d] += s11;
        K[3 * S_X1 + d][3 * S_X2 + d] += s01;
    }
    /* bending second derivatives (EXACT only; sb_shell.c step 4c) */
    if (kind == SB_HESS_EXACT) {
        const double fV = dot3(V, n), ir2 = irho * irho;
        double Hc[9], X1[9], X2[9], P[9], M1[9], M2[9], S[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double id = i == j ? 1.0 : 0.0;
                Hc[3 * i + j] = (-(V[i] * n[j] + n[i] * V[j]) - fV * (id - 3.0 * n[i] * n[j])) * ir2;
                P[3 * i + j] = (id - n[i] * n[j]) * irho;
            }
        skew3(x1, X1);
        skew3(x2, X2);
        mul33(X2, Hc, M1);
        mul33(M1, X2, M2);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) K[3 * S_X1 + a][3 * S_X1 + b] -= M2[3 * a + b];
        if (kd)
            for (int i = 0; i < 9; i++) kd[i] -= M2[i];
        mul33(M1, X1, M2);
        skew3(gV, S);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                K[3 * S_X1 + a][3 * S_X2 + b] += M2[3 * a + b] - S[3 * a + b];
            }
        if (kd)
            for (int i = 0; i < 9; i++) kd[9 + i] += M2[i] - S[i];
        mul33(X1, Hc, M1);
        mul33(M1, X1, M2);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) K[3 * S_X2 + a][3 * S_X2 + b] -= M2[3 * a + b];
        if (kd)
            for (int i = 0; i < 9; i++) kd[18 + i] -= M2[i];
        mul33(X2, P, M1);
        mul33(X1, P, M2);
        if (kd) {   /* (x1, mu) = X2 P/|c|, (x2, mu) = -X1 P/|c|, mu = sum_i nB_i/2 v_i */
            for (int i = 0; i < 9; i++) {
                kd[27 + i] = M1[i];
                kd[36 + i] = -M2[i];
            }
            for (int i = 0; i < 3; i++) kd[45 + i] = 0.5 * nB[i];
        }
        for (int i = 0; i < 3; i++) {
            const int sv = bslot[i];
            const double h = 0.5 * nB[i];
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    K[3 * S_X1 + a][3 * sv + b] += h * M1[3 * a + b];
                    K[3 * S_X2 + a][3 * sv + b] -= h * M2[3 * a + b];
                }
        }
    }

    /* Z^cd rows of the point (sb_elem_tile.c) */
    SB_VEC_FN(sb_elem_zrows)(K, Wp, kp, w->Z + (size_t)5 * p * kp, (size_t)5 * w->nqmax * kp);
    return e;
}

/* ---- the element ------------------------------------------------------------------ */

/* H (3k x 3k) += sign * the element matrix of the products in w->Hc: entry
 * (3I+c, 3J+d) is H^cd[I][J] for c < d, H^dc[J][I] for c > d and H^cc at
 * (min, max) on the diagonal pairs, so the result is exactly symmetric.
 * With store (sb_shell_element_into, sign 1) every entry is written once
 * and not read: 0.0 + x is what h += x gives on a zeroed matrix (the same
 * bits, also for x = -0).  sign and store are constants at every call, so
 * each instance compiles to its own branch-free loop. */
static inline void scatter(int k, int kp, const sb_shell_batch *w, double *hess, double sign, int store)
{
    const int n3 = 3 * k;
    const double *H[3][3];
    for (int pr = 0; pr < 6; pr++) H[pc[pr]][pd[pr]] = w->Hc + (size_t)pr * kp * kp;
#define SB_PUT(i, x) h[i] = (store ? 0.0 : h[i]) + sign * (x)
    for (int I = 0; I < k; I++) {
        double *row0 = hess + (size_t)(3 * I) * n3;
        for (int J = 0; J < k; J++) {
            const size_t ij = (size_t)I * kp + J, ji = (size_t)J * kp + I, dg = I <= J ? ij : ji;
            double *h = row0 + 3 * J;
            SB_PUT(0, H[0][0][dg]);
            SB_PUT(1, H[0][1][ij]);
            SB_PUT(2, H[0][2][ij]);
            h += n3;
            SB_PUT(0, H[0][1][ji]);
            SB_PUT(1, H[1][1][dg]);
            SB_PUT(2, H[1][2][ij]);
            h += n3;
            SB_PUT(0, H[0][2][ji]);
            SB_PUT(1, H[1][2][ji]);
            SB_PUT(2, H[2][2][dg]);
        }
    }
#undef SB_PUT
}

/* sign = 1 (the element) and -1 (the PSD difference) as constants: h += x
 * instead of h += 1.0 * x, the same bits */
void SB_VEC_FN(sb_elem_scatter)(int k, int kp, const sb_shell_batch *w, double *hess, double sign)
{
    if (sign == 1.0)
        scatter(k, kp, w, hess, 1.0, 0);
    else if (sign == -1.0)
        scatter(k, kp, w, hess, -1.0, 0);
    else
        scatter(k, kp, w, hess, sign, 0);
}

double SB_VEC_FN(sb_elem_element)(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,
                                  const double *q, double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w)
{
    if (!m || !r || !b || !q || !w || nq < 1 || nq > w->nqmax || m->n_thick < 1 || m->n_thick > 8) return NAN;
    const int k = b[0].k;
    if (k < 1 || k > w->kmax) return NAN;
    for (int p = 0; p < nq; p++)
        if (b[p].k != k || !b[p].N1 || !b[p].N2 || !b[p].N11 || !b[p].N12 || !b[p].N22) return NAN;
    const int kp = sb_elem_round_up(k, KPAD), need_g = grad || hess, need_h = hess != NULL;

    /* control values by component, zero padded */
    for (int cc = 0; cc < 3; cc++) {
        double *qc = w->qd + (size_t)cc * kp;
        for (int I = 0; I < k; I++) qc[I] = q[3 * I + cc];
        for (int I = k; I < kp; I++) qc[I] = 0.0;
    }
    double e = 0.0;
    for (int p = 0; p < nq; p++) {
        const double *src[5] = { b[p].N1, b[p].N2, b[p].N11, b[p].N12, b[p].N22 };
        for (int s = 0; s < 5; s++) {
            double *row = w->Wt + (size_t)(5 * p + s) * kp;
            memcpy(row, src[s], sizeof(double) * k);
            for (int I = k; I < kp; I++) row[I] = 0.0;
            if (hess && sb_elem_wants_broadcast(w)) {
                double *rb = w->Wb + (size_t)2 * (5 * p + s) * kp;
                for (int I = 0; I < kp; I++) sb_store_pair(rb + 2 * I, row[I]);
            }
        }
        e += point(m, &r[p], p, kp, need_g, need_h, kind, w);
    }
    if (!need_g) return e;

    /* gradient: g_I,c += sum_r Wt[r][I] Gt[r][c] */
    if (grad) {
        const int R = 5 * nq;
        for (int I = 0; I < kp; I += SB_VL) {
            sb_vd g0 = sb_vbcast(0.0), g1 = g0, g2 = g0;
            for (int rr = 0; rr < R; rr++) {
                const sb_vd wv = sb_vload(w->Wt + (size_t)rr * kp + I);
                const double *G = w->Gt + 3 * rr;
                g0 += wv * G[0];
                g1 += wv * G[1];
                g2 += wv * G[2];
            }
            sb_vstore(w->gd + I, g0);
            sb_vstore(w->gd + kp + I, g1);
            sb_vstore(w->gd + 2 * kp + I, g2);
        }
        for (int I = 0; I < k; I++)
            for (int cc = 0; cc < 3; cc++) grad[3 * I + cc] += w->gd[(size_t)cc * kp + I];
    }
    if (!hess) return e;
    SB_VEC_FN(sb_elem_products)(5 * nq, kp, w);
    if (w->store)
        scatter(k, kp, w, hess, 1.0, 1);
    else
        scatter(k, kp, w, hess, 1.0, 0);
    return e;
}

