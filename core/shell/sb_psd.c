/* sb_psd.c — per-element positive-semidefinite projection of a symmetric
 * matrix: eigenvalues below zero are clamped to zero (LAPACK dsyev).
 *
 * The projection is applied as a correction, H <- H - sum_{lambda_j < 0}
 * lambda_j v_j v_j^T, so that a matrix that is already PSD comes back
 * bit-for-bit unchanged, and the cost beyond the eigen-decomposition is
 * proportional to the number of negative eigenvalues. */
#include "sb_shell.h"
#include "sb_simd.h"

#include <math.h>
#include <string.h>

extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
                   double *w, double *work, const int *lwork, int *info);

/* eigenvalues (n) + eigenvector copy (n*n) + LAPACK work ((NB+2) n with NB = 32) */
size_t sb_psd_work_size(int n)
{
    if (n < 1) return 0;
    return (size_t)n + (size_t)n * (size_t)n + 34u * (size_t)n;
}

int sb_psd_project(int n, double *H, double *work)
{
    if (n < 1 || !H || !work) return SB_ERR_INPUT;
    const size_t nn = (size_t)n * (size_t)n;
    for (size_t i = 0; i < nn; i++)
        if (!isfinite(H[i])) return SB_NONFINITE;
    double *lam = work, *Vm = work + n, *lw = Vm + nn;
    int lwork = 34 * n, info = 0;
    /* H is symmetric, so row-major and column-major views coincide. */
    memcpy(Vm, H, nn * sizeof *H);
    dsyev_("V", "U", &n, Vm, &n, lam, lw, &lwork, &info);
    if (info < 0) return SB_ERR_INTERNAL;
    if (info > 0) return SB_NONFINITE;   /* QR iteration failed: treated like a non-finite Hessian */
    /* eigenvalues ascending: the negative ones come first; column j of Vm
     * (column-major) is v_j, i.e. v_j[i] = Vm[j*n + i] */
    for (int j = 0; j < n && lam[j] < 0.0; j++) {
        const double *vj = Vm + (size_t)j * n;
        const double l = lam[j];
        for (int a = 0; a < n; a++) {
            const double s = -l * vj[a];
            double *row = H + (size_t)a * n;
            for (int b = 0; b < n; b++) row[b] += s * vj[b];
        }
    }
    return SB_OK;
}

/* Semidefiniteness test by LDL^T with diagonal pivoting (the pivoted
 * Cholesky of Higham, "Accuracy and Stability of Numerical Algorithms",
 * §10.3): at step j the largest remaining diagonal is the pivot; a PSD
 * matrix has its largest entries on the diagonal, so once that pivot is
 * below the tolerance the Schur complement left must be within it too.
 * Only the lower triangle is read and updated.  The tolerance covers the
 * round-off of the rigid-body null space every element Hessian has. */
int sb_psd_check(int n, const double *H, double *work)
{
    if (n < 1 || n > SB_PSD_CHECK_MAX_N || !H || !work) return 0;
    double *A = work, dmax = 0.0, col[SB_PSD_CHECK_MAX_N];
    const size_t nn = (size_t)n * (size_t)n;
    for (size_t i = 0; i < nn; i++)
        if (!isfinite(H[i])) return 0;
    memcpy(A, H, nn * sizeof *A);
    for (int i = 0; i < n; i++) dmax = fmax(dmax, fabs(A[(size_t)i * n + i]));
    const double tol = 64.0 * n * 2.220446049250313e-16 * dmax;
#define AT(i, k) A[(size_t)(i) * n + (k)]   /* lower triangle, i >= k */
    for (int j = 0; j < n; j++) {
        int p = j;
        for (int i = j + 1; i < n; i++)
            if (AT(i, i) > AT(p, p)) p = i;
        const double piv = AT(p, p);
        if (!(piv > tol)) {
            /* the rest must be ~0: every remaining entry within the tolerance */
            for (int i = j; i < n; i++)
                for (int k = j; k <= i; k++)
                    if (!(fabs(AT(i, k)) <= tol)) return 0;
            return 1;
        }
        if (p != j) {   /* symmetric swap of j and p in the trailing lower triangle */
            double t = AT(j, j);
            AT(j, j) = AT(p, p);
            AT(p, p) = t;
            for (int k = j + 1; k < p; k++) {
                t = AT(k, j);
                AT(k, j) = AT(p, k);
                AT(p, k) = t;
            }
            for (int i = p + 1; i < n; i++) {
                t = AT(i, j);
                AT(i, j) = AT(i, p);
                AT(i, p) = t;
            }
        }
        /* Schur complement: A_ik -= A_ij A_kj / A_jj for j < k <= i */
        for (int k = j + 1; k < n; k++) col[k] = AT(k, j);
        for (int i = j + 1; i < n; i++) {
            const double lij = col[i] / piv;
            double *ai = &AT(i, 0);
            int k = j + 1;
            const sb_vd lv = sb_vbcast(lij);
            for (; k + SB_VL <= i + 1; k += SB_VL) sb_vstore(ai + k, sb_vload(ai + k) - lv * sb_vload(col + k));
            for (; k <= i; k++) ai[k] -= lij * col[k];
        }
    }
#undef AT
    return 1;
}
