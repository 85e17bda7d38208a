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

/* phi_j of RMTR paper Eq. (3.4) and its derivatives on a vector of
 * arguments, as phi_fast / phi_cont in sb_material.c */
static inline void vphi(const sb_material *m, int j, sb_vd u, sb_vd *f, sb_vd *d1, sb_vd *d2)
{
    const sb_denim_params *p = &m->denim;
    if (m->denim_linear[j]) {   /* every alpha = 1: phi = (sum mu) u */
        double s = 0.0;
        for (int i = 0; i < p->d[j]; i++) s += p->mu[j][i];
        *f = s * u;
        *d1 = sb_vbcast(s);
        *d2 = sb_vbcast(0.0);
        return;
    }
    const sb_vd L = sb_vlog1p(u);   /* NaN for u <= -1: outside the domain, as phi_fast */
    sb_vd F = sb_vbcast(0.0), G = F, G1 = F, H = F;
    for (int i = 0; i < p->d[j]; i++) {
        const double al = p->alpha[j][i], mu = p->mu[j][i];
        if (al == 1.0) {   /* exact linear term */
            F += mu * u;
            G1 += mu;
            continue;
        }
        const sb_vd em1 = sb_vexpm1(al * L), pw = em1 + 1.0;
        F += m->denim_mu_over_alpha[j][i] * em1;
        G += mu * pw;
        H += m->denim_mu_alpha_m1[j][i] * pw;
    }
    const sb_vd inv = 1.0 / (1.0 + u);
    sb_vd D1 = G1 + G * inv, D2 = H * inv * inv;
    if (!p->beyond_fit) {   /* linear continuation beyond the joins (phi_cont) */
        const double jh = m->denim_join_hi[j], jl = m->denim_join_lo[j];
        const sb_vi hi = u > jh, lo = u < jl;
        if (isfinite(jh)) {
            F = sb_vselect(hi, m->denim_fj_hi[j] + m->denim_gj_hi[j] * (u - jh), F);
            D1 = sb_vselect(hi, sb_vbcast(m->denim_gj_hi[j]), D1);
            D2 = sb_vselect(hi, sb_vbcast(0.0), D2);
        }
        if (isfinite(jl)) {
            F = sb_vselect(lo, m->denim_fj_lo[j] + m->denim_gj_lo[j] * (u - jl), F);
            D1 = sb_vselect(lo, sb_vbcast(m->denim_gj_lo[j]), D1);
            D2 = sb_vselect(lo, sb_vbcast(0.0), D2);
        }
    }
    *f = F;
    *d1 = D1;
    *d2 = D2;
}

static inline double hsum(sb_vd v)
{
    double s = 0.0;
    for (int l = 0; l < SB_VL; l++) s += v[l];
    return s;
}

static double section_denim(const sb_material *m, const double A[3], const double B[3], double sA[3],
                            double sB[3], double C[36])
{
    const double *k = m->denim.k;
    const int nt = m->n_thick;
    sb_vd E = sb_vbcast(0.0), gA[3], gB[3], caa[4], cab[4], cbb[4];   /* C entries 00 01 11 22 */
    for (int i = 0; i < 3; i++) gA[i] = gB[i] = E;
    for (int i = 0; i < 4; i++) caa[i] = cab[i] = cbb[i] = E;
    for (int g0 = 0; g0 < nt; g0 += SB_VL) {
        /* lanes past the rule: xi = 0, weight 0 (finite values, no contribution) */
        sb_vd xi, wg;
        for (int l = 0; l < SB_VL; l++) {
            const int g = g0 + l;
            xi[l] = g < nt ? m->thick_pt[g] : 0.0;
            wg[l] = g < nt ? m->thick_w[g] : 0.0;
        }
        const sb_vd e0 = A[0] - 2.0 * xi * B[0], e1 = A[1] - 2.0 * xi * B[1], e2 = A[2] - 2.0 * xi * B[2];
        const sb_vd u1 = e0 * e0, u2 = e0 * e1, u3 = e1 * e1, u4 = e2 * e2;
        if (m->denim.beyond_fit) {   /* outside the admissible range: NaN (denim_psi) */
            const sb_vi out = (u1 > m->denim_u_max[0]) | (u2 > m->denim_u_max[1]) | (u2 < m->denim_u_min[1]) |
                              (u3 > m->denim_u_max[2]) | (u4 > m->denim_u_max[3]);
            for (int l = 0; l < SB_VL; l++)
                if (out[l]) {
                    if (sA) sA[0] = sA[1] = sA[2] = NAN;
                    if (sB) sB[0] = sB[1] = sB[2] = NAN;
                    if (C)
                        for (int i = 0; i < 36; i++) C[i] = NAN;
                    return NAN;
                }
        }
        sb_vd f1, f2, f3, f4, g1, g2, g3, g4, h1, h2, h3, h4;
        vphi(m, 0, u1, &f1, &g1, &h1);
        vphi(m, 1, u2, &f2, &g2, &h2);
        vphi(m, 2, u3, &f3, &g3, &h3);
        vphi(m, 3, u4, &f4, &g4, &h4);
        /* RMTR paper Eq. (3.3) and its derivatives (denim_psi) */
        const sb_vd psi = 0.5 * k[0] * f1 + k[1] * f2 + 0.5 * k[2] * f3 + k[3] * f4;
        E += wg * psi;
        if (!sA && !sB && !C) continue;
        const sb_vd s0 = k[0] * g1 * e0 + k[1] * g2 * e1, s1 = k[1] * g2 * e0 + k[2] * g3 * e1,
                    s2 = 2.0 * k[3] * g4 * e2;
        const sb_vd wb = -2.0 * xi * wg;   /* dE/dB = -2 xi3 */
        gA[0] += wg * s0;
        gA[1] += wg * s1;
        gA[2] += wg * s2;
        gB[0] += wb * s0;
        gB[1] += wb * s1;
        gB[2] += wb * s2;
        if (!C) continue;
        const sb_vd c00 = k[0] * (g1 + 2.0 * e0 * e0 * h1) + k[1] * h2 * e1 * e1;
        const sb_vd c01 = k[1] * (g2 + h2 * e0 * e1);
        const sb_vd c11 = k[2] * (g3 + 2.0 * e1 * e1 * h3) + k[1] * h2 * e0 * e0;
        const sb_vd c22 = 2.0 * k[3] * (g4 + 2.0 * e2 * e2 * h4);
        const sb_vd wbb = 4.0 * xi * xi * wg;
        const sb_vd cc[4] = { c00, c01, c11, c22 };
        for (int i = 0; i < 4; i++) {
            caa[i] += wg * cc[i];
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
