/* sb_regress_stats.c — the Mann-Whitney U test the nightly regression judges
 * times by (as Google Benchmark's compare tool does).
 *
 * U = #{(i, j): x_i > y_j} + 1/2 #{(i, j): x_i = y_j}  (Mann & Whitney 1947).
 * Under H0 (both samples from one distribution, no ties) every one of the
 * C(n+m, n) rank orders is equally likely, and the number of orders with
 * U = u is the coefficient of q^u of the Gaussian binomial coefficient
 * [n+m choose n]_q = prod_{i=1..n} (1 - q^(m+i)) / (1 - q^i)
 * (Andrews, The Theory of Partitions, Thm 3.1); the exact two-sided p-value
 * is 2 min(P(U <= u), P(U >= u)), capped at 1.  With ties, or samples larger
 * than 50, the normal approximation: mean nm/2, variance
 * nm/12 ((N+1) - sum(t^3 - t) / (N(N-1))) over tie groups of size t
 * (Lehmann, Nonparametrics, 1975, Eq. 1.48), with a continuity correction
 * of 1/2, through gsl_cdf_ugaussian_Q. */
#include "sb_regress.h"

#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>

enum { EXACT_MAX = 50 };

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* P(U <= u) and P(U >= u) under H0 without ties, exactly */
static int exact_tails(int n, int m, double u, double *lo, double *hi)
{
    int top = n * m;
    double *c = calloc((size_t)top + 1, sizeof *c);
    if (!c) return SB_ERR_NOMEM;
    c[0] = 1;
    for (int i = 1; i <= n; i++) {
        for (int k = top; k >= m + i; k--) c[k] -= c[k - (m + i)];   /* times (1 - q^(m+i)) */
        for (int k = i; k <= top; k++) c[k] += c[k - i];             /* over (1 - q^i) */
    }
    double total = 0, below = 0, above = 0;
    for (int k = 0; k <= top; k++) {
        total += c[k];
        if (k <= u + 1e-9) below += c[k];
        if (k >= u - 1e-9) above += c[k];
    }
    free(c);
    *lo = below / total;
    *hi = above / total;
    return SB_OK;
}

int sb_regress_mwu(const double *x, int n, const double *y, int m, sb_mwu *r)
{
    r->u = 0, r->p = 1, r->exact = 0;
    if (n < 1 || m < 1) return SB_ERR_INPUT;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < m; j++) r->u += x[i] > y[j] ? 1.0 : x[i] == y[j] ? 0.5 : 0.0;
    /* tie groups of the pooled sample */
    int N = n + m;
    double *z = malloc((size_t)N * sizeof *z), ties = 0;
    if (!z) return SB_ERR_NOMEM;
    for (int i = 0; i < n; i++) z[i] = x[i];
    for (int j = 0; j < m; j++) z[n + j] = y[j];
    qsort(z, (size_t)N, sizeof *z, cmp_dbl);
    for (int i = 0; i < N;) {
        int k = i;
        while (k < N && z[k] == z[i]) k++;
        double t = k - i;
        ties += t * t * t - t;
        i = k;
    }
    free(z);
    if (ties == 0 && n <= EXACT_MAX && m <= EXACT_MAX) {
        double lo, hi;
        int rc = exact_tails(n, m, r->u, &lo, &hi);
        if (rc) return rc;
        r->p = fmin(1.0, 2 * fmin(lo, hi));
        r->exact = 1;
        return SB_OK;
    }
    double mean = 0.5 * n * m, var = n * (double)m / 12.0 * ((N + 1) - ties / ((double)N * (N - 1)));
    if (!(var > 0)) return SB_OK;   /* every value equal: no evidence of a difference */
    double zz = (fabs(r->u - mean) - 0.5) / sqrt(var);
    r->p = zz <= 0 ? 1.0 : fmin(1.0, 2 * gsl_cdf_ugaussian_Q(zz));
    return SB_OK;
}
