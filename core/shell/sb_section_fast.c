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
 * - denim (RMTR paper Eq. 3.3-3.4): sb_section_denim.c, the thickness
 *   points in vectors, at the vector width of the caller's batch.
 * Other laws fall back to sb_shell_section. */
#include "sb_shell_batch.h"

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

double sb_section_fast_isa(sb_shell_isa isa, const sb_material *m, const double A[3], const double B[3],
                           double sA[3], double sB[3], double C[36])
{
    if (!m || !A || !B || m->n_thick < 1 || m->n_thick > 8) return NAN;
    switch (m->kind) {
    case SB_MAT_STVK: return section_stvk(m, A, B, sA, sB, C);
    case SB_MAT_DENIM: return sb_section_denim_isa(isa, m, A, B, sA, sB, C);
    }
    return sb_shell_section(m, A, B, sA, sB, C);
}

double sb_shell_section_fast(const sb_material *m, const double A[3], const double B[3], double sA[3],
                             double sB[3], double C[36])
{
    return sb_section_fast_isa(sb_shell_isa_best(), m, A, B, sA, sB, C);
}
