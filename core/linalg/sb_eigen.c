/* sb_eigen.c — dense symmetric eigenvalues (LAPACK dsyevd), dense 1-norm
 * condition numbers (dpotrf + dpotri), and Lanczos extreme Ritz values with
 * residual bounds (sb_eigen.h).  Used by bench/bench_cond.c for the RMTR
 * paper's Fig. 9 (condition number of H = M/dt^2 + K, §7.1). */
#include "sb_eigen.h"
#include "sb_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* LAPACK (Fortran interface, linked through -llapack) */
extern void dsyevd_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda, double *w,
                    double *work, const int *lwork, int *iwork, const int *liwork, int *info);
extern void dstev_(const char *jobz, const int *n, double *d, double *e, double *z, const int *ldz, double *work,
                   int *info);
extern void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
extern void dpotri_(const char *uplo, const int *n, double *a, const int *lda, int *info);

static int eig_dense(const char *jobz, int n, double *A, double *w)
{
    if (n <= 0) return SB_ERR_INPUT;
    int info = 0, lwork = -1, liwork = -1, iwq = 0;
    double wq = 0;
    dsyevd_(jobz, "U", &n, A, &n, w, &wq, &lwork, &iwq, &liwork, &info);   /* workspace query */
    if (info) return SB_ERR_INTERNAL;
    lwork = (int)wq + 1;
    liwork = iwq > 1 ? iwq : 1;
    double *work = malloc((size_t)lwork * sizeof *work);
    int *iwork = malloc((size_t)liwork * sizeof *iwork);
    if (!work || !iwork) { free(work); free(iwork); return SB_ERR_NOMEM; }
    dsyevd_(jobz, "U", &n, A, &n, w, work, &lwork, iwork, &liwork, &info);
    free(work);
    free(iwork);
    return info ? SB_ERR_INTERNAL : SB_OK;
}

int sb_eig_dense_sym(int n, double *A, double *w) { return eig_dense("N", n, A, w); }

int sb_eig_dense_sym_vec(int n, double *A, double *w) { return eig_dense("V", n, A, w); }

/* ||A||_1 of a full symmetric matrix: the largest absolute column sum */
static double norm1(int n, const double *A)
{
    double m = 0;
    for (int j = 0; j < n; j++) {
        double s = 0;
        for (int i = 0; i < n; i++) s += fabs(A[i + (size_t)j * n]);
        if (s > m) m = s;
    }
    return m;
}

double sb_cond1_dense_spd(int n, double *A)
{
    double a1 = norm1(n, A);
    int info = 0;
    dpotrf_("U", &n, A, &n, &info);
    if (info) return NAN;
    dpotri_("U", &n, A, &n, &info);                /* upper triangle of A^-1 */
    if (info) return NAN;
    for (int j = 0; j < n; j++)                    /* mirror to full storage */
        for (int i = j + 1; i < n; i++) A[i + (size_t)j * n] = A[j + (size_t)i * n];
    return a1 * norm1(n, A);
}

/* Eigenvalues (ascending) and the last components of the eigenvectors of the
 * k x k tridiagonal T = tridiag(b, a, b): the Ritz values and, times
 * beta_{k+1}, their residual bounds. */
static int tridiag_eig(int k, const double *a, const double *b, double *theta, double *last, double *z,
                       double *work)
{
    double *e = work + 2 * k;                      /* dstev destroys d and e */
    memcpy(theta, a, (size_t)k * sizeof *theta);
    if (k > 1) memcpy(e, b, (size_t)(k - 1) * sizeof *e);
    int info = 0;
    dstev_("V", &k, theta, e, z, &k, work, &info);
    if (info) return SB_ERR_INTERNAL;
    for (int j = 0; j < k; j++) last[j] = z[(k - 1) + (size_t)j * k];
    return SB_OK;
}

int sb_lanczos_extreme(int n, sb_eig_op op, void *ctx, int kmax, double rtol, const double *v0,
                       sb_lanczos_result *res)
{
    if (n <= 0 || kmax <= 0) return SB_ERR_INPUT;
    if (kmax > n) kmax = n;
    double *V = malloc((size_t)n * (kmax + 1) * sizeof *V);
    double *w = malloc((size_t)n * sizeof *w);
    double *a = malloc((size_t)kmax * sizeof *a), *b = malloc((size_t)kmax * sizeof *b);
    double *theta = malloc((size_t)kmax * sizeof *theta), *last = malloc((size_t)kmax * sizeof *last);
    double *z = malloc((size_t)kmax * kmax * sizeof *z), *work = malloc((size_t)4 * kmax * sizeof *work);
    int rc = SB_OK;
    if (!V || !w || !a || !b || !theta || !last || !z || !work) { rc = SB_ERR_NOMEM; goto out; }
    /* start vector: given, or a fixed pseudo-random one (an LCG: reproducible,
     * and not orthogonal to the extreme eigenvectors by accident) */
    unsigned s = 2463534242u;
    for (int i = 0; i < n; i++) {
        s = s * 1664525u + 1013904223u;
        V[i] = v0 ? v0[i] : (double)(s >> 8) / 16777216.0 - 0.5;
    }
    double nv = 0;
    for (int i = 0; i < n; i++) nv += V[i] * V[i];
    nv = sqrt(nv);
    if (!(nv > 0)) { rc = SB_ERR_INPUT; goto out; }
    for (int i = 0; i < n; i++) V[i] /= nv;
    res->steps = 0;
    for (int k = 0; k < kmax; k++) {
        double *vk = V + (size_t)k * n, *vn = V + (size_t)(k + 1) * n;
        if ((rc = op(ctx, vk, w)) != SB_OK) goto out;
        /* three-term recurrence, then full reorthogonalization against every
         * earlier Lanczos vector, twice ("twice is enough", Parlett §6.9) */
        double ak = 0;                                             /* alpha_k = v_k^T op v_k */
        for (int i = 0; i < n; i++) ak += vk[i] * w[i];
        a[k] = ak;
        for (int pass = 0; pass < 2; pass++)
            for (int j = 0; j <= k; j++) {
                const double *vj = V + (size_t)j * n;
                double c = 0;
                for (int i = 0; i < n; i++) c += vj[i] * w[i];
                for (int i = 0; i < n; i++) w[i] -= c * vj[i];
            }
        double bk = 0;
        for (int i = 0; i < n; i++) bk += w[i] * w[i];
        bk = sqrt(bk);
        if (k < kmax - 1) b[k] = bk;
        if ((rc = tridiag_eig(k + 1, a, b, theta, last, z, work)) != SB_OK) goto out;
        /* Ritz residuals: ||op V y - theta V y|| = beta_{k+1} |y_k| */
        res->steps = k + 1;
        res->theta_min = theta[0];
        res->res_min = bk * fabs(last[0]);
        res->theta_max = theta[k];
        res->res_max = bk * fabs(last[k]);
        if (res->hist_theta_max) {
            res->hist_theta_max[k] = res->theta_max;
            res->hist_res_max[k] = res->res_max;
            res->hist_theta_min[k] = res->theta_min;
            res->hist_res_min[k] = res->res_min;
        }
        double scale = fmax(fabs(theta[0]), fabs(theta[k]));
        if (!(bk > 1e-14 * scale)) break;                          /* invariant subspace: exact */
        if (rtol > 0 && res->res_max <= rtol * fabs(res->theta_max) && res->res_min <= rtol * fabs(res->theta_min))
            break;
        for (int i = 0; i < n; i++) vn[i] = w[i] / bk;
    }
    /* the Ritz vectors V_k y of the extreme Ritz values (z holds the
     * eigenvectors of the last T_k; the Lanczos vectors V_k are orthonormal,
     * so V_k y is a unit vector) */
    for (int side = 0; side < 2 && res->steps > 0; side++) {
        double *out = side ? res->vec_min : res->vec_max;
        if (!out) continue;
        const int k = res->steps, j = side ? 0 : k - 1;
        memset(out, 0, (size_t)n * sizeof *out);
        for (int c = 0; c < k; c++) {
            const double y = z[c + (size_t)j * k], *vc = V + (size_t)c * n;
            for (int i = 0; i < n; i++) out[i] += y * vc[i];
        }
    }
out:
    free(V); free(w); free(a); free(b); free(theta); free(last); free(z); free(work);
    return rc;
}
