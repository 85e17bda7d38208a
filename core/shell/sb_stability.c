/* sb_stability.c — is the material law convex in the strain at a state?
 *
 * The section tangent C = d2e/d(A,B)2 of sb_shell_section (membrane strain
 * A, bending strain B, energy per reference area integrated through the
 * thickness) is positive definite for a stable (convex) law.  The RMTR
 * paper's denim fit (Eq. 3.3-3.4, Table 1, with our mu_j1 assumption) is
 * not convex everywhere: its membrane tangent is indefinite for uniaxial
 * strains |E11| in (0.0265, 0.083), |E22| in (0.0055, 0.065) and |E12| in
 * (0.0175, 0.0305) (tests/test_stability.c checks the intervals), so where a scene strains the cloth that far the discrete
 * minimization can localize the strain into single elements.  This file
 * reports it; it changes nothing that a solver sees. */
#include "sb_shell.h"
#include "sb_material_state.h"

#include <math.h>
#include <string.h>

extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
                   double *w, double *work, const int *lwork, int *info);

/* smallest eigenvalue of a symmetric n x n matrix (n <= 6) over its largest |eigenvalue| */
static int rel_min_eig(int n, const double *S, double *out)
{
    double a[36], lam[6], work[64];
    int lwork = 64, info = 0;
    memcpy(a, S, (size_t)n * n * sizeof *a);
    dsyev_("N", "U", &n, a, &n, lam, work, &lwork, &info);
    if (info != 0) return SB_NONFINITE;
    double big = fmax(fabs(lam[0]), fabs(lam[n - 1]));
    *out = big > 0 ? lam[0] / big : 0.0;
    return SB_OK;
}

int sb_shell_section_stability(const sb_material *m, const double A[3], const double B[3],
                               double *rel_min_membrane, double *rel_min_section)
{
    if (!m || !A || !B || !rel_min_membrane || !rel_min_section || !(m->thickness > 0)) return SB_ERR_INPUT;
    for (int i = 0; i < 3; i++)
        if (!isfinite(A[i]) || !isfinite(B[i])) return SB_NONFINITE;
    double C[36], CAA[9];
    sb_shell_section(m, A, B, NULL, NULL, C);
    for (int i = 0; i < 36; i++)
        if (!isfinite(C[i])) return SB_NONFINITE;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) CAA[3 * i + j] = C[6 * i + j];
    /* D C D with D = diag(1, 1, 1, s, s, s): for a quadratic law CBB = (tau^2/3) CAA,
     * so s = sqrt(3)/tau gives both blocks the same scale */
    const double s = sqrt(3.0) / m->thickness;
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) C[6 * i + j] *= (i >= 3 ? s : 1.0) * (j >= 3 ? s : 1.0);
    int rc = rel_min_eig(3, CAA, rel_min_membrane);
    if (!rc) rc = rel_min_eig(6, C, rel_min_section);
    return rc;
}

void sb_material_state_init(sb_material_state *ms)
{
    memset(ms, 0, sizeof *ms);
    ms->min_rel_eig = INFINITY;
}

int sb_material_state_add_strains(sb_material_state *ms, const sb_material *m, double dA, const double A[3],
                                  const double B[3])
{
    double lm, ls;
    int rc;
    if (m->kind == SB_MAT_STVK && ms->const_tangent_of == (const void *)m) {
        /* StVK: psi is quadratic in E (sb_material.c stvk_psi, BHEM paper
         * Eq. 8), so the section tangent C does not depend on (A, B) and its
         * eigenvalues are those of the first point, bit for bit (issue 42:
         * two LAPACK eigenproblems per point were half of a 1e6-dof plate
         * run's harness time); the strains are still checked finite */
        for (int i = 0; i < 3; i++)
            if (!isfinite(A[i]) || !isfinite(B[i])) return SB_NONFINITE;
        lm = ms->const_tangent_lm;
        ls = ms->const_tangent_ls;
    } else {
        rc = sb_shell_section_stability(m, A, B, &lm, &ls);
        if (rc) return rc;
        if (m->kind == SB_MAT_STVK) {
            ms->const_tangent_of = m;
            ms->const_tangent_lm = lm;
            ms->const_tangent_ls = ls;
        }
    }
    /* ASSUMPTION: a relative eigenvalue below -1e-9 is negative (round-off
     * of a 3 x 3 or 6 x 6 dsyev is near 1e-15 relative) */
    const double tol = -1e-9;
    ms->points++;
    ms->area += dA;
    if (lm < tol) {
        ms->soft_membrane++;
        ms->soft_area += dA;
    }
    ms->soft_section += ls < tol;
    if (lm < ms->min_rel_eig) ms->min_rel_eig = lm;
    for (int i = 0; i < 3; i++) ms->max_strain[i] = fmax(ms->max_strain[i], fabs(A[i]));
    return SB_OK;
}

int sb_material_state_add(sb_material_state *ms, const sb_material *m, const sb_shell_ref *r,
                          const sb_shell_basis *b, const double *q, sb_shell_work *w)
{
    double A[3], B[3];
    int rc = sb_shell_strains(r, b, q, w, A, B);
    return rc ? rc : sb_material_state_add_strains(ms, m, r->dA, A, B);
}
