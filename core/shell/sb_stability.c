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

/* 1 when the symmetric n x n matrix S (n <= 6) has a Cholesky factor with
 * positive pivots.  A Cholesky factorization that succeeds in floating
 * point is that of S + E with |E| ~ n eps |S| (Higham, Accuracy and
 * Stability of Numerical Algorithms, Thm. 10.3), so S's smallest eigenvalue
 * is then above about -n eps max|lambda|: far above the -1e-9 relative
 * threshold of the material state below. */
static int cholesky_positive(int n, const double *S)
{
    double a[36];
    memcpy(a, S, (size_t)n * n * sizeof *a);
    for (int j = 0; j < n; j++) {
        double d = a[n * j + j];
        for (int k = 0; k < j; k++) d -= a[n * j + k] * a[n * j + k];
        if (!(d > 0)) return 0;
        d = sqrt(d);
        a[n * j + j] = d;
        for (int i = j + 1; i < n; i++) {
            double v = a[n * i + j];
            for (int k = 0; k < j; k++) v -= a[n * i + k] * a[n * j + k];
            a[n * i + j] = v / d;
        }
    }
    return 1;
}

/* The section tangent, scaled (below), and its membrane block. */
static int section_tangents(const sb_material *m, const double A[3], const double B[3], double C[36], double CAA[9])
{
    for (int i = 0; i < 3; i++)
        if (!isfinite(A[i]) || !isfinite(B[i])) return SB_NONFINITE;
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
    return SB_OK;
}

int sb_shell_section_stability(const sb_material *m, const double A[3], const double B[3],
                               double *rel_min_membrane, double *rel_min_section)
{
    if (!m || !A || !B || !rel_min_membrane || !rel_min_section || !(m->thickness > 0)) return SB_ERR_INPUT;
    double C[36], CAA[9];
    int rc = section_tangents(m, A, B, C, CAA);
    if (!rc) rc = rel_min_eig(3, CAA, rel_min_membrane);
    if (!rc) rc = rel_min_eig(6, C, rel_min_section);
    return rc;
}

/* A lower bound of the relative smallest eigenvalue lambda_min / lambda_max
 * of a symmetric positive definite 3 x 3 S (row-major), 0 when S is not
 * positive definite by Sylvester's criterion: lambda_min = det / (lambda_a
 * lambda_b) >= det / e2 (e2 = the sum of the principal 2 x 2 minors, every
 * product of two eigenvalues positive) and lambda_max <= ||S||_F. */
static double rel_min_eig_bound3(const double *S)
{
    const double a = S[0], b = S[4], c = S[8], d = S[1], e = S[2], f = S[5];
    const double m2 = a * b - d * d;
    const double det = a * (b * c - f * f) - d * (d * c - f * e) + e * (d * f - b * e);
    if (!(a > 0) || !(m2 > 0) || !(det > 0)) return 0.0;
    const double e2 = m2 + (a * c - e * e) + (b * c - f * f);
    const double fro = sqrt(a * a + b * b + c * c + 2.0 * (d * d + e * e + f * f));
    return e2 > 0 && fro > 0 ? det / (e2 * fro) : 0.0;
}

/* As sb_shell_section_stability, for the material state: the membrane's
 * relative eigenvalue, and for the section only whether it is soft
 * (relative eigenvalue below tol).  A section tangent that Cholesky proves
 * positive definite skips its 6 x 6 eigenproblem (issue 42: the eigenproblem
 * was half of the per-step physical-state judgement on the denim
 * trampoline); the decision is dsyev's wherever that matters, near zero.
 * The membrane's eigenproblem is skipped where a lower bound (above) shows
 * that its value cannot count: relative eigenvalue >= need (the larger of
 * tol and the state's minimum so far), then *lm = +inf.  The bound is used
 * at half its value and only above 1e-6, where the round-off of det (the
 * smallest eigenvalue then >= 1e-6 of the largest) is far below a half;
 * so the state's minimum and its counts are dsyev's, bit for bit (issue
 * 42: `samples` 4.6 -> 3.6 s on a bounded bhem drape at 1.2e6 dofs, the
 * harness share 3.1 -> 1.9 %, docs/scaling.md). */
static int section_soft(const sb_material *m, const double A[3], const double B[3], double tol, double need,
                        double *lm, int *section_is_soft)
{
    if (!(m->thickness > 0)) return SB_ERR_INPUT;
    double C[36], CAA[9], ls;
    int rc = section_tangents(m, A, B, C, CAA);
    if (!rc) {
        const double bound = rel_min_eig_bound3(CAA);
        if (bound > 1e-6 && 0.5 * bound >= need) *lm = INFINITY;
        else rc = rel_min_eig(3, CAA, lm);
    }
    if (rc) return rc;
    if (cholesky_positive(6, C)) {
        *section_is_soft = 0;
        return SB_OK;
    }
    rc = rel_min_eig(6, C, &ls);
    *section_is_soft = !rc && ls < tol;
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
    /* ASSUMPTION: a relative eigenvalue below -1e-9 is negative (round-off
     * of a 3 x 3 or 6 x 6 dsyev is near 1e-15 relative) */
    const double tol = -1e-9;
    double lm;
    int rc, ss;
    if (m->kind == SB_MAT_STVK && ms->const_tangent_of == (const void *)m) {
        /* StVK: psi is quadratic in E (sb_material.c stvk_psi, BHEM paper
         * Eq. 8), so the section tangent C does not depend on (A, B) and its
         * eigenvalues are those of the first point, bit for bit (issue 42:
         * two LAPACK eigenproblems per point were half of a 1e6-dof plate
         * run's harness time); the strains are still checked finite */
        for (int i = 0; i < 3; i++)
            if (!isfinite(A[i]) || !isfinite(B[i])) return SB_NONFINITE;
        lm = ms->const_tangent_lm;
        ss = ms->const_tangent_soft;
    } else {
        /* StVK's first point is cached for all the others: computed exactly */
        rc = section_soft(m, A, B, tol, m->kind == SB_MAT_STVK ? INFINITY : fmax(tol, ms->min_rel_eig), &lm, &ss);
        if (rc) return rc;
        if (m->kind == SB_MAT_STVK) {
            ms->const_tangent_of = m;
            ms->const_tangent_lm = lm;
            ms->const_tangent_soft = ss;
        }
    }
    ms->points++;
    ms->area += dA;
    if (lm < tol) {
        ms->soft_membrane++;
        ms->soft_area += dA;
    }
    ms->soft_section += ss;
    /* energy below the reference state's (A = B = 0: 0).  A section whose
     * tangent is constant and positive definite (StVK not soft) has a
     * quadratic, nonnegative energy: no evaluation needed */
    if (!(m->kind == SB_MAT_STVK && lm >= tol && !ss) && sb_shell_section(m, A, B, NULL, NULL, NULL) < 0.0) {
        ms->below_reference++;
        ms->below_reference_area += dA;
    }
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
