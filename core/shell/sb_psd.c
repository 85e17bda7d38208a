/* sb_psd.c — per-element positive-semidefinite projection of a symmetric
 * matrix: eigenvalues below zero are clamped to zero (LAPACK dsyev).
 *
 * The projection is applied as a correction, H <- H - sum_{lambda_j < 0}
 * lambda_j v_j v_j^T, so that a matrix that is already PSD comes back
 * bit-for-bit unchanged, and the cost beyond the eigen-decomposition is
 * proportional to the number of negative eigenvalues. */
#include "sb_shell.h"

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
