/* sb_eigen.h — extreme eigenvalues of symmetric matrices, for measuring
 * condition numbers (RMTR paper §7.1, Fig. 9; issue 43).
 *
 * Dense: every eigenvalue by LAPACK's divide and conquer (dsyevd), exact to
 * round-off (|lambda - lambda_computed| <= c n eps ||A||_2).
 *
 * Sparse: the Lanczos process with full reorthogonalization on an operator
 * y = op(x) (A x, or A^-1 x by a factorization for the smallest eigenvalue:
 * shift-invert with shift 0).  After k steps the Ritz values theta_j of the
 * tridiagonal T_k lie inside the spectrum of op, and for each Ritz pair
 * (theta, V y) the residual ||op V y - theta V y|| = |beta_{k+1} y_k| bounds
 * the distance from theta to the nearest eigenvalue of op (symmetric
 * matrices: Parlett, The Symmetric Eigenvalue Problem, Thm. 4.5.1 /
 * Saad, Numerical Methods for Large Eigenvalue Problems, §6.6).  Each step's
 * extreme Ritz values and their residual bounds are kept, so a caller can
 * show the convergence, not only the last number. */
#ifndef SB_EIGEN_H
#define SB_EIGEN_H

/* All eigenvalues of the symmetric n x n matrix A (column-major, full
 * storage; destroyed), ascending, into w[n].  SB_OK or SB_ERR_*. */
int sb_eig_dense_sym(int n, double *A, double *w);
/* The same with the orthonormal eigenvectors: column j of A is that of w[j]. */
int sb_eig_dense_sym_vec(int n, double *A, double *w);

/* 1-norm condition number ||A||_1 ||A^-1||_1 of a symmetric positive
 * definite A (column-major, full; destroyed) by Cholesky and the explicit
 * inverse (dpotrf + dpotri); NAN when A is not positive definite. */
double sb_cond1_dense_spd(int n, double *A);

typedef int (*sb_eig_op)(void *ctx, const double *x, double *y);

typedef struct sb_lanczos_result {
    int steps;            /* Lanczos steps taken */
    double theta_max;     /* largest Ritz value of op after `steps` */
    double res_max;       /* its residual bound |beta_{k+1} y_k| */
    double theta_min;     /* smallest Ritz value of op */
    double res_min;
    /* per step k = 1..steps (arrays of length kmax, owned by the caller or NULL) */
    double *hist_theta_max, *hist_res_max, *hist_theta_min, *hist_res_min;
    /* optional (length n, owned by the caller, or NULL): on return the unit
     * Ritz vectors V_k y of theta_max and theta_min, whose residuals
     * ||op v - theta v|| are res_max and res_min (issue 43: which energy term
     * an extreme eigenvector of H lives in, by its Rayleigh quotient per term) */
    double *vec_max, *vec_min;
} sb_lanczos_result;

/* Lanczos with full (twice) reorthogonalization from the start vector v0
 * (NULL: a fixed pseudo-random vector).  Stops after kmax steps, on an
 * invariant subspace (beta ~ 0), or once both extreme Ritz values have a
 * residual bound <= rtol |theta| (rtol 0: run all kmax steps).  Memory n kmax
 * doubles.  SB_OK, or the op's error code. */
int sb_lanczos_extreme(int n, sb_eig_op op, void *ctx, int kmax, double rtol, const double *v0,
                       sb_lanczos_result *res);

#endif
