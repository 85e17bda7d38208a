/* test_eigen.c — the eigenvalue estimators of bench_cond (core/linalg/sb_eigen.c)
 * on matrices with a known spectrum: the 1D Laplacian tridiag(-1, 2, -1) of
 * order n, lambda_k = 2 - 2 cos(k pi / (n + 1)), k = 1..n, whose condition
 * number grows like (n+1)^2 (4 (n+1)^2 / pi^2), and a diagonal matrix with a
 * condition number of 1e10 (the range of the RMTR paper's Fig. 9). */
#include "sb_test.h"
#include "sb_common.h"
#include "sb_eigen.h"

#include <stdlib.h>
#include <string.h>

static double lap_eig(int n, int k) { return 2.0 - 2.0 * cos(k * M_PI / (n + 1)); }

static int lap_mult(void *ctx, const double *x, double *y)
{
    int n = *(int *)ctx;
    for (int i = 0; i < n; i++) y[i] = 2 * x[i] - (i > 0 ? x[i - 1] : 0) - (i < n - 1 ? x[i + 1] : 0);
    return SB_OK;
}

/* y = A^-1 x for the 1D Laplacian (Thomas algorithm): shift-invert Lanczos */
static int lap_solve(void *ctx, const double *x, double *y)
{
    int n = *(int *)ctx;
    double *c = malloc((size_t)n * sizeof *c);
    double b = 2.0;
    c[0] = -1.0 / b;
    y[0] = x[0] / b;
    for (int i = 1; i < n; i++) {
        double m = 2.0 + c[i - 1];
        c[i] = -1.0 / m;
        y[i] = (x[i] + y[i - 1]) / m;
    }
    for (int i = n - 2; i >= 0; i--) y[i] -= c[i] * y[i + 1];
    free(c);
    return SB_OK;
}

SB_TEST(dense_laplacian_spectrum)
{
    for (int n = 1; n <= 200; n = n < 10 ? n + 3 : 2 * n) {
        double *A = calloc((size_t)n * n, sizeof *A), *w = malloc((size_t)n * sizeof *w);
        for (int i = 0; i < n; i++) {
            A[i + (size_t)i * n] = 2;
            if (i + 1 < n) A[i + 1 + (size_t)i * n] = A[i + (size_t)(i + 1) * n] = -1;
        }
        CHECK_EQ_INT(sb_eig_dense_sym(n, A, w), SB_OK);
        double err = 0;
        for (int k = 1; k <= n; k++) err = fmax(err, fabs(w[k - 1] - lap_eig(n, k)));
        CHECK_MSG(err <= 1e-13 * 4 * n, "n = %d: max eigenvalue error %.3g", n, err);
        free(A);
        free(w);
    }
}

SB_TEST(dense_cond1_laplacian)
{
    /* ||A||_1 = 4 (n >= 3); A^-1 = (min(i,j) (n+1-max(i,j)))/(n+1), whose
     * largest column sum is the middle column's: sum_i G(i, m) */
    int n = 50;
    double *A = calloc((size_t)n * n, sizeof *A);
    for (int i = 0; i < n; i++) {
        A[i + (size_t)i * n] = 2;
        if (i + 1 < n) A[i + 1 + (size_t)i * n] = A[i + (size_t)(i + 1) * n] = -1;
    }
    double best = 0;
    for (int j = 1; j <= n; j++) {
        double s = 0;
        for (int i = 1; i <= n; i++) s += (double)(i < j ? i : j) * (n + 1 - (i > j ? i : j)) / (n + 1);
        best = fmax(best, s);
    }
    CHECK_REL(sb_cond1_dense_spd(n, A), 4.0 * best, 1e-12);
    /* not positive definite: NAN */
    double B[4] = { 1, 2, 2, 1 };
    CHECK(isnan(sb_cond1_dense_spd(2, B)));
    free(A);
}

SB_TEST(lanczos_laplacian_extremes)
{
    int n = 2000, kmax = 300;
    double *h[4];
    for (int i = 0; i < 4; i++) h[i] = calloc((size_t)kmax, sizeof(double));
    sb_lanczos_result r = { .hist_theta_max = h[0], .hist_res_max = h[1], .hist_theta_min = h[2], .hist_res_min = h[3] };
    /* lambda_max by Lanczos on A: converges (residual bound small) and the
     * bound holds: an eigenvalue lies within res of theta */
    CHECK_EQ_INT(sb_lanczos_extreme(n, lap_mult, &n, kmax, 1e-10, NULL, &r), SB_OK);
    double lmax = lap_eig(n, n);
    /* the top of the Laplacian's spectrum is clustered (gap ~ 3 pi^2/n^2), so
     * the residual bound converges slowly: the bound holds, and the value
     * is far closer than the bound (Ritz values converge like res^2/gap) */
    CHECK_MSG(fabs(r.theta_max - lmax) <= r.res_max + 1e-13, "theta_max %.15g vs %.15g, bound %.3g",
              r.theta_max, lmax, r.res_max);
    CHECK_REL(r.theta_max, lmax, 3e-5);            /* 9.4e-6 after 300 steps */
    CHECK(r.theta_max <= lmax * (1 + 1e-14));   /* Ritz values lie inside the spectrum */
    /* the history is monotone: theta_max grows, theta_min falls (interlacing) */
    int mono = 1;
    for (int k = 1; k < r.steps; k++)
        if (h[0][k] < h[0][k - 1] * (1 - 1e-14) || h[2][k] > h[2][k - 1] * (1 + 1e-14)) mono = 0;
    CHECK(mono);
    /* lambda_min by Lanczos on A^-1 (shift-invert): cond = 4 (n+1)^2/pi^2 ~ 1.8e6 */
    memset(&r, 0, sizeof r);
    CHECK_EQ_INT(sb_lanczos_extreme(n, lap_solve, &n, 60, 1e-12, NULL, &r), SB_OK);
    double lmin = lap_eig(n, 1);
    CHECK_REL(1.0 / r.theta_max, lmin, 1e-10);
    CHECK(1.0 / (r.theta_max + r.res_max) <= lmin * (1 + 1e-10));
    CHECK(r.theta_max - r.res_max <= 0 || 1.0 / (r.theta_max - r.res_max) >= lmin * (1 - 1e-10));
    CHECK_REL(lmax * r.theta_max, lmax / lmin, 1e-10);
    for (int i = 0; i < 4; i++) free(h[i]);
}

/* a diagonal matrix with eigenvalues 1e-6 .. 1e4 (condition number 1e10) */
static int diag_mult(void *ctx, const double *x, double *y)
{
    const double *d = ctx;
    int n = (int)d[0];
    for (int i = 0; i < n; i++) y[i] = d[1 + i] * x[i];
    return SB_OK;
}
static int diag_solve(void *ctx, const double *x, double *y)
{
    const double *d = ctx;
    int n = (int)d[0];
    for (int i = 0; i < n; i++) y[i] = x[i] / d[1 + i];
    return SB_OK;
}

SB_TEST(lanczos_ill_conditioned_diagonal)
{
    int n = 3000;
    double *d = malloc((size_t)(n + 1) * sizeof *d);
    d[0] = n;
    for (int i = 0; i < n; i++) d[1 + i] = pow(10.0, -6.0 + 10.0 * i / (n - 1));
    sb_lanczos_result r;
    memset(&r, 0, sizeof r);
    CHECK_EQ_INT(sb_lanczos_extreme(n, diag_mult, d, 200, 1e-10, NULL, &r), SB_OK);
    CHECK_REL(r.theta_max, 1e4, 1e-9);
    memset(&r, 0, sizeof r);
    CHECK_EQ_INT(sb_lanczos_extreme(n, diag_solve, d, 200, 1e-10, NULL, &r), SB_OK);
    CHECK_REL(1.0 / r.theta_max, 1e-6, 1e-9);
    /* plain Lanczos on A does not find lambda_min = 1e-6 in 200 steps (the
     * reason bench_cond uses shift-invert): its smallest Ritz value stays far
     * above, and its residual bound says so */
    memset(&r, 0, sizeof r);
    CHECK_EQ_INT(sb_lanczos_extreme(n, diag_mult, d, 50, 0, NULL, &r), SB_OK);
    CHECK(r.theta_min > 1e-5);
    CHECK(r.res_min > 1e-3 * r.theta_min);
    free(d);
}

/* The Ritz vectors: unit vectors whose residual ||A v - theta v|| is the
 * reported bound, and (diagonal A, well separated ends) the extreme unit
 * coordinate vectors; NULL outputs are left alone */
SB_TEST(lanczos_ritz_vectors)
{
    int n = 400;
    double *d = malloc((size_t)(n + 1) * sizeof *d), *vmax = malloc((size_t)n * sizeof *vmax);
    double *vmin = malloc((size_t)n * sizeof *vmin), *w = malloc((size_t)n * sizeof *w);
    d[0] = n;
    for (int i = 0; i < n; i++) d[1 + i] = 1.0 + i;          /* 1 .. 400 */
    d[1 + 0] = 0.01;                                          /* lambda_min well separated */
    d[1 + n - 1] = 1e3;                                       /* lambda_max well separated */
    sb_lanczos_result r;
    memset(&r, 0, sizeof r);
    r.vec_max = vmax;
    r.vec_min = vmin;
    CHECK_EQ_INT(sb_lanczos_extreme(n, diag_mult, d, 120, 0, NULL, &r), SB_OK);
    CHECK_REL(r.theta_max, 1e3, 1e-12);
    for (int side = 0; side < 2; side++) {
        const double *v = side ? vmin : vmax, th = side ? r.theta_min : r.theta_max, rb = side ? r.res_min : r.res_max;
        double nv = 0, nr = 0;
        diag_mult(d, v, w);
        for (int i = 0; i < n; i++) { nv += v[i] * v[i]; nr += (w[i] - th * v[i]) * (w[i] - th * v[i]); }
        CHECK_REL(nv, 1.0, 1e-10);
        /* the computed residual equals the bound Lanczos reports (to round-off) */
        CHECK_MSG(fabs(sqrt(nr) - rb) <= 1e-8 * fabs(d[n]) + 1e-6 * rb, "side %d: residual %.3g, bound %.3g", side,
                  sqrt(nr), rb);
    }
    CHECK(fabs(vmax[n - 1]) > 1 - 1e-10);                     /* e_n */
    /* the smallest end converges more slowly (relative gap 0.99 / 1e3): still
     * mostly on e_1 */
    CHECK(fabs(vmin[0]) > 0.99);
    free(d); free(vmax); free(vmin); free(w);
}

static const sb_test_case cases[] = {
    SB_CASE(dense_laplacian_spectrum),
    SB_CASE(dense_cond1_laplacian),
    SB_CASE(lanczos_laplacian_extremes),
    SB_CASE(lanczos_ill_conditioned_diagonal),
    SB_CASE(lanczos_ritz_vectors),
    SB_END
};

int main(int argc, char **argv) { return sb_test_main(argc, argv, cases); }
