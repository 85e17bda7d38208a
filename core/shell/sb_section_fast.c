/* sb_section_fast.c — the shell section law for the fast kernel: the same
 * through-thickness integral as sb_shell_section (sb_shell.c; BHEM paper
 * Eq. 6a-7, RMTR paper Eq. 3.2),
 *     e = sum_g w_g psi(A - 2 xi_g B),
 * with derivatives sA, sB and the 6 x 6 tangent C, evaluated faster:
 *
 * - StVK: psi(E) = E^T Cm E / 2 is quadratic, so with the moments
 *   m0 = sum w_g, m1 = sum w_g xi_g, m2 = sum w_g xi_g^2 of the rule
 *       e = m0 psi(A) - 2 m1 A^T Cm B + 4 m2 psi(B),
 *       sA = Cm (m0 A - 2 m1 B),  sB = Cm (4 m2 B - 2 m1 A),
 *       C = [m0 Cm, -2 m1 Cm; -2 m1 Cm, 4 m2 Cm]
 *   (exact for any rule that integrates quadratics, e.g. 2 Gauss points:
 *   m0 = h, m1 = 0, m2 = h^3/12, i.e. BHEM paper Eq. 7).
 * - denim (RMTR paper Eq. 3.3-3.4): the thickness points in vectors of
 *   SB_VL lanes and the powers (u + 1)^alpha = expm1(alpha log1p(u)) + 1 by
 *   sb_vexpm1 / sb_vlog1p (sb_vmath.h) instead of 16 libm calls per point;
 *   the admissible range and the linear continuation beyond the fit are
 *   those of sb_material.c (denim_psi, phi_cont), applied as lane selects.
 * Other laws fall back to sb_shell_section. */
#include "sb_shell.h"
#include "sb_vmath.h"

#include <math.h>
#include <string.h>

static double section_stvk(const sb_material *m, const double A[3], const double B[3], double sA[3], double sB[3],
                           double C[36])
{
    double m0 = 0.0, m1 = 0.0, m2 = 0.0;
    for (int g = 0; g < m->n_thick; g++) {
        const double xi = m->thick_pt[g], wg = m->thick_w[g];
        m0 += wg;
        m1 += wg * xi;
        m2 += wg * xi * xi;
    }
    /* Cm: d2psi of stvk_psi (sb_material.c), BHEM paper Eq. 8 */
    const double la = m->lambda, mu = m->mu, c0 = la + 2.0 * mu, c2 = 4.0 * mu;
    const double CA[3] = { c0 * A[0] + la * A[1], la * A[0] + c0 * A[1], c2 * A[2] };
    const double CB[3] = { c0 * B[0] + la * B[1], la * B[0] + c0 * B[1], c2 * B[2] };
    const double AA = A[0] * CA[0] + A[1] * CA[1] + A[2] * CA[2];
    const double AB = A[0] * CB[0] + A[1] * CB[1] + A[2] * CB[2];
    const double BB = B[0] * CB[0] + B[1] * CB[1] + B[2] * CB[2];
    const double e = 0.5 * m0 * AA - 2.0 * m1 * AB + 2.0 * m2 * BB;
    if (sA)
        for (int i = 0; i < 3; i++) sA[i] = m0 * CA[i] - 2.0 * m1 * CB[i];
    if (sB)
        for (int i = 0; i < 3; i++) sB[i] = 4.0 * m2 * CB[i] - 2.0 * m1 * CA[i];
    if (C) {
        const double Cm[9] = { c0, la, 0.0, la, c0, 0.0, 0.0, 0.0, c2 };
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                C[6 * i + j] = m0 * Cm[3 * i + j];
                C[6 * i + 3 + j] = C[6 * (3 + j) + i] = -2.0 * m1 * Cm[3 * i + j];
                C[6 * (3 + i) + 3 + j] = 4.0 * m2 * Cm[3 * i + j];
            }
    }
    return e;
}

static inline double hsum(sb_vd v)
{
    double s = 0.0;
    for (int l = 0; l < SB_VL; l++) s += v[l];
    return s;
}

#define NG_MAX ((SB_MAX_THICK + SB_VL - 1) / SB_VL)

/* denim: the thickness points in ng vectors; all logarithms of the section
 * in one batch, then all powers in one batch (sb_vmath.h: the evaluations
 * interleave instead of each waiting out its own chain of latencies) */
static double section_denim(const sb_material *m, const double A[3], const double B[3], double sA[3],
                            double sB[3], double C[36])
{
    const double *k = m->denim.k;
    const sb_denim_params *p = &m->denim;
    const int nt = m->n_thick, ng = (nt + SB_VL - 1) / SB_VL;
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
                if (out[l]) {
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
    /* RMTR paper Eq. (3.3), its derivatives (denim_psi), through the thickness */
    sb_vd E = sb_vbcast(0.0), gA[3], gB[3], caa[4], cab[4], cbb[4];   /* C entries 00 01 11 22 */
    for (int i = 0; i < 3; i++) gA[i] = gB[i] = E;
    for (int i = 0; i < 4; i++) caa[i] = cab[i] = cbb[i] = E;
    for (int g = 0; g < ng; g++) {
        const sb_vd psi = 0.5 * k[0] * F[0][g] + k[1] * F[1][g] + 0.5 * k[2] * F[2][g] + k[3] * F[3][g];
        E += wg[g] * psi;
        if (!sA && !sB && !C) continue;
        const sb_vd g1 = D1[0][g], g2 = D1[1][g], g3 = D1[2][g], g4 = D1[3][g];
        const sb_vd s0 = k[0] * g1 * e0[g] + k[1] * g2 * e1[g], s1 = k[1] * g2 * e0[g] + k[2] * g3 * e1[g],
                    s2 = 2.0 * k[3] * g4 * e2[g];
        const sb_vd wb = -2.0 * xi[g] * wg[g];   /* dE/dB = -2 xi3 */
        gA[0] += wg[g] * s0;
        gA[1] += wg[g] * s1;
        gA[2] += wg[g] * s2;
        gB[0] += wb * s0;
        gB[1] += wb * s1;
        gB[2] += wb * s2;
        if (!C) continue;
        const sb_vd h1 = D2[0][g], h2 = D2[1][g], h3 = D2[2][g], h4 = D2[3][g];
        const sb_vd c00 = k[0] * (g1 + 2.0 * e0[g] * e0[g] * h1) + k[1] * h2 * e1[g] * e1[g];
        const sb_vd c01 = k[1] * (g2 + h2 * e0[g] * e1[g]);
        const sb_vd c11 = k[2] * (g3 + 2.0 * e1[g] * e1[g] * h3) + k[1] * h2 * e0[g] * e0[g];
        const sb_vd c22 = 2.0 * k[3] * (g4 + 2.0 * e2[g] * e2[g] * h4);
        const sb_vd wbb = 4.0 * xi[g] * xi[g] * wg[g];
        const sb_vd cc[4] = { c00, c01, c11, c22 };
        for (int i = 0; i < 4; i++) {
            caa[i] += wg[g] * cc[i];
            cab[i] += wb * cc[i];
            cbb[i] += wbb * cc[i];
        }
    }
    if (sA)
        for (int i = 0; i < 3; i++) sA[i] = hsum(gA[i]);
    if (sB)
        for (int i = 0; i < 3; i++) sB[i] = hsum(gB[i]);
    if (C) {
        double a[4], ab[4], b[4];
        for (int i = 0; i < 4; i++) {
            a[i] = hsum(caa[i]);
            ab[i] = hsum(cab[i]);
            b[i] = hsum(cbb[i]);
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
    return hsum(E);
}

double sb_shell_section_fast(const sb_material *m, const double A[3], const double B[3], double sA[3],
                             double sB[3], double C[36])
{
    if (!m || !A || !B || m->n_thick < 1 || m->n_thick > 8) return NAN;
    switch (m->kind) {
    case SB_MAT_STVK: return section_stvk(m, A, B, sA, sB, C);
    case SB_MAT_DENIM: return section_denim(m, A, B, sA, sB, C);
    }
    return sb_shell_section(m, A, B, sA, sB, C);
}
