/* sb_section_denim.c — the denim section law of the fast kernel (RMTR
 * paper Eq. 3.3-3.4 through the thickness, BHEM paper Eq. 6a-7): the
 * thickness points in vectors of SB_VL lanes and the powers
 * (u + 1)^alpha = expm1(alpha log1p(u)) + 1 by sb_vexpm1 / sb_vlog1p
 * (sb_vmath.h) instead of 16 libm calls per point; the admissible range and
 * the linear continuation beyond the fit are those of sb_material.c
 * (denim_psi, phi_cont), applied as lane selects.
 *
 * Compiled once per vector width (Makefile VEC_SRC; SB_VEC_FN names the
 * function): SSE2 (2 lanes, 3 vectors for the usual 6 thickness points),
 * AVX2 (4 lanes, 2 vectors), AVX-512 (8 lanes, 1 vector).  Every thickness
 * point's terms are computed in one lane by the same IEEE operations at any
 * width (sb_vmath.h is lane-wise), and the sums over the thickness points
 * are taken in the order of the 2-lane build: the even points, the odd
 * points, then the two (red2 below), so all widths give the same bits
 * (tests/test_shell_fast.c, vector_widths_same_bits and
 * section_widths_same_bits). */
#include "sb_shell_batch.h"
#include "sb_vmath.h"

#include <math.h>

/* The sum over the thickness points t < nt of per-point values, lane t % SB_VL
 * of P[t / SB_VL], in the summation order of SSE2 vectors accumulated over
 * the groups and added across their 2 lanes: (0 + sum of the even points in
 * order) + (sum of the odd ones); a rule of odd size includes the padding
 * point (weight 0) as SSE2 does. */
static inline double red2(const sb_vd *P, int ng, int nt)
{
#if SB_VL == 2
    (void)nt;
    sb_vd acc = sb_vbcast(0.0);
    for (int g = 0; g < ng; g++) acc += P[g];
    return (0.0 + acc[0]) + acc[1];
#else
    (void)ng;
    double a0 = 0.0, a1 = 0.0;
    for (int t = 0; t < nt; t += 2) {
        a0 += P[t / SB_VL][t % SB_VL];
        a1 += P[(t + 1) / SB_VL][(t + 1) % SB_VL];
    }
    return (0.0 + a0) + a1;
#endif
}

#define NG_MAX ((SB_MAX_THICK + SB_VL - 1) / SB_VL)

/* denim: the thickness points in ng vectors; all logarithms of the section
 * in one batch, then all powers in one batch (sb_vmath.h: the evaluations
 * interleave instead of each waiting out its own chain of latencies) */
double SB_VEC_FN(sb_section_denim)(SB_SECTION_DENIM_ARGS)
{
    const double *k = m->denim.k;
    const sb_denim_params *p = &m->denim;
    const int nt = m->n_thick, ng = (nt + SB_VL - 1) / SB_VL, nt2 = (nt + 1) / 2 * 2;
    sb_vd xi[NG_MAX] = { 0 }, wg[NG_MAX] = { 0 }, e0[NG_MAX] = { 0 }, e1[NG_MAX] = { 0 }, e2[NG_MAX] = { 0 };
    sb_vd U[4][NG_MAX];
    for (int g = 0; g < ng; g++) {
        /* lanes past the rule: xi = 0, weight 0 (finite values, no contribution) */
        for (int l = 0; l < SB_VL; l++) {
            const int t = g * SB_VL + l;
            xi[g][l] = t < nt ? m->thick_pt[t] : 0.0;
            wg[g][l] = t < nt ? m->thick_w[t] : 0.0;
        }
        e0[g] = A[0] - 2.0 * xi[g] * B[0];
        e1[g] = A[1] - 2.0 * xi[g] * B[1];
        e2[g] = A[2] - 2.0 * xi[g] * B[2];
        U[0][g] = e0[g] * e0[g];
        U[1][g] = e0[g] * e1[g];
        U[2][g] = e1[g] * e1[g];
        U[3][g] = e2[g] * e2[g];
        if (p->beyond_fit) {   /* outside the admissible range: NaN (denim_psi) */
            const sb_vi out = (U[0][g] > m->denim_u_max[0]) | (U[1][g] > m->denim_u_max[1]) |
                              (U[1][g] < m->denim_u_min[1]) | (U[2][g] > m->denim_u_max[2]) |
                              (U[3][g] > m->denim_u_max[3]);
            for (int l = 0; l < SB_VL; l++)
                if (out[l] && g * SB_VL + l < nt2) {   /* the lanes the 2-lane build has */
                    if (sA) sA[0] = sA[1] = sA[2] = NAN;
                    if (sB) sB[0] = sB[1] = sB[2] = NAN;
                    if (C)
                        for (int i = 0; i < 36; i++) C[i] = NAN;
                    return NAN;
                }
        }
    }
    /* L = log1p(u) of every nonlinear phi_j (NaN for u <= -1, as phi_fast) */
    sb_vd Lin[4 * NG_MAX], L[4 * NG_MAX];
    int nl = 0, lofs[4] = { 0, 0, 0, 0 };
    for (int j = 0; j < 4; j++) {
        if (m->denim_linear[j]) continue;
        lofs[j] = nl;
        for (int g = 0; g < ng; g++) Lin[nl++] = U[j][g];
    }
    sb_vlog1p_n(nl, Lin, L);
    /* the powers (u + 1)^alpha - 1 = expm1(alpha L) of every term alpha != 1 */
    sb_vd X[4 * SB_DENIM_MAX_TERMS * NG_MAX], EM[4 * SB_DENIM_MAX_TERMS * NG_MAX];
    int nx = 0;
    for (int j = 0; j < 4; j++) {
        if (m->denim_linear[j]) continue;
        for (int i = 0; i < p->d[j]; i++) {
            if (p->alpha[j][i] == 1.0) continue;
            for (int g = 0; g < ng; g++) X[nx++] = p->alpha[j][i] * L[lofs[j] + g];
        }
    }
    sb_vexpm1_n(nx, X, EM);
    /* phi_j, phi_j', phi_j'' (RMTR paper Eq. 3.4; phi_fast and phi_cont in sb_material.c) */
    sb_vd F[4][NG_MAX], D1[4][NG_MAX], D2[4][NG_MAX];
    int ix = 0;
    for (int j = 0; j < 4; j++) {
        if (m->denim_linear[j]) {   /* every alpha = 1: phi = (sum mu) u */
            double s = 0.0;
            for (int i = 0; i < p->d[j]; i++) s += p->mu[j][i];
            for (int g = 0; g < ng; g++) {
                F[j][g] = s * U[j][g];
                D1[j][g] = sb_vbcast(s);
                D2[j][g] = sb_vbcast(0.0);
            }
            continue;
        }
        for (int g = 0; g < ng; g++) {
            sb_vd Fs = sb_vbcast(0.0), G = Fs, G1 = Fs, H = Fs;
            const sb_vd u = U[j][g];
            int t = ix;
            for (int i = 0; i < p->d[j]; i++) {
                const double al = p->alpha[j][i], mu = p->mu[j][i];
                if (al == 1.0) {   /* exact linear term */
                    Fs += mu * u;
                    G1 += mu;
                    continue;
                }
                const sb_vd em1 = EM[t + g], pw = em1 + 1.0;
                t += ng;
                Fs += m->denim_mu_over_alpha[j][i] * em1;
                G += mu * pw;
                H += m->denim_mu_alpha_m1[j][i] * pw;
            }
            const sb_vd inv = 1.0 / (1.0 + u);
            sb_vd d1 = G1 + G * inv, d2 = H * inv * inv;
            if (!p->beyond_fit) {   /* linear continuation beyond the joins (phi_cont) */
                const double jh = m->denim_join_hi[j], jl = m->denim_join_lo[j];
                if (isfinite(jh)) {
                    const sb_vi hi = u > jh;
                    Fs = sb_vselect(hi, m->denim_fj_hi[j] + m->denim_gj_hi[j] * (u - jh), Fs);
                    d1 = sb_vselect(hi, sb_vbcast(m->denim_gj_hi[j]), d1);
                    d2 = sb_vselect(hi, sb_vbcast(0.0), d2);
                }
                if (isfinite(jl)) {
                    const sb_vi lo = u < jl;
                    Fs = sb_vselect(lo, m->denim_fj_lo[j] + m->denim_gj_lo[j] * (u - jl), Fs);
                    d1 = sb_vselect(lo, sb_vbcast(m->denim_gj_lo[j]), d1);
                    d2 = sb_vselect(lo, sb_vbcast(0.0), d2);
                }
            }
            F[j][g] = Fs;
            D1[j][g] = d1;
            D2[j][g] = d2;
        }
        for (int i = 0; i < p->d[j]; i++) ix += p->alpha[j][i] == 1.0 ? 0 : ng;
    }
    /* RMTR paper Eq. (3.3), its derivatives (denim_psi), per thickness point
     * and weighted; summed through the thickness by red2 */
    sb_vd PE[NG_MAX], PgA[3][NG_MAX], PgB[3][NG_MAX], Paa[4][NG_MAX], Pab[4][NG_MAX], Pbb[4][NG_MAX];
    for (int g = 0; g < ng; g++) {
        const sb_vd psi = 0.5 * k[0] * F[0][g] + k[1] * F[1][g] + 0.5 * k[2] * F[2][g] + k[3] * F[3][g];
        PE[g] = wg[g] * psi;
        if (!sA && !sB && !C) continue;
        const sb_vd g1 = D1[0][g], g2 = D1[1][g], g3 = D1[2][g], g4 = D1[3][g];
        const sb_vd s0 = k[0] * g1 * e0[g] + k[1] * g2 * e1[g], s1 = k[1] * g2 * e0[g] + k[2] * g3 * e1[g],
                    s2 = 2.0 * k[3] * g4 * e2[g];
        const sb_vd wb = -2.0 * xi[g] * wg[g];   /* dE/dB = -2 xi3 */
        PgA[0][g] = wg[g] * s0;
        PgA[1][g] = wg[g] * s1;
        PgA[2][g] = wg[g] * s2;
        PgB[0][g] = wb * s0;
        PgB[1][g] = wb * s1;
        PgB[2][g] = wb * s2;
        if (!C) continue;
        const sb_vd h1 = D2[0][g], h2 = D2[1][g], h3 = D2[2][g], h4 = D2[3][g];
        const sb_vd c00 = k[0] * (g1 + 2.0 * e0[g] * e0[g] * h1) + k[1] * h2 * e1[g] * e1[g];
        const sb_vd c01 = k[1] * (g2 + h2 * e0[g] * e1[g]);
        const sb_vd c11 = k[2] * (g3 + 2.0 * e1[g] * e1[g] * h3) + k[1] * h2 * e0[g] * e0[g];
        const sb_vd c22 = 2.0 * k[3] * (g4 + 2.0 * e2[g] * e2[g] * h4);
        const sb_vd wbb = 4.0 * xi[g] * xi[g] * wg[g];
        const sb_vd cc[4] = { c00, c01, c11, c22 };
        for (int i = 0; i < 4; i++) {
            Paa[i][g] = wg[g] * cc[i];
            Pab[i][g] = wb * cc[i];
            Pbb[i][g] = wbb * cc[i];
        }
    }
    if (sA)
        for (int i = 0; i < 3; i++) sA[i] = red2(PgA[i], ng, nt);
    if (sB)
        for (int i = 0; i < 3; i++) sB[i] = red2(PgB[i], ng, nt);
    if (C) {
        double a[4], ab[4], b[4];
        for (int i = 0; i < 4; i++) {
            a[i] = red2(Paa[i], ng, nt);
            ab[i] = red2(Pab[i], ng, nt);
            b[i] = red2(Pbb[i], ng, nt);
        }
        /* 3 x 3 blocks [c00 c01 0; c01 c11 0; 0 0 c22] */
        const int idx[9] = { 0, 1, -1, 1, 2, -1, -1, -1, 3 };
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const int t = idx[3 * i + j];
                C[6 * i + j] = t < 0 ? 0.0 : a[t];
                C[6 * i + 3 + j] = C[6 * (3 + j) + i] = t < 0 ? 0.0 : ab[t];
                C[6 * (3 + i) + 3 + j] = t < 0 ? 0.0 : b[t];
            }
    }
    return red2(PE, ng, nt);
}

