/* sb_precond_jacobi.c — node-block Jacobi: M = blockdiag(H_II), one bs x bs
 * block per node (3 for positions, 12 for a Hermite node), inverted once per
 * Newton iteration by Cholesky.  An indefinite node block is replaced by
 * diag(|a_ii|), so M stays SPD (CG stays valid; the indefiniteness of H
 * itself is detected by CG's curvature test, sb_krylov.c). */
#include "sb_precond.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Inverse of the symmetric bs x bs block A (row-major) in place through
 * Cholesky (bs <= 12); returns 0, A unchanged, when A is not positive
 * definite (the trust-region CG's block preconditioners and node-block
 * Jacobi share it). */
int sb_spd_block_inverse(int bs, double *A)
{
    double L[144], Li[144];
    for (int i = 0; i < bs; i++)
        for (int j = 0; j <= i; j++) {
            double v = A[i * bs + j];
            for (int k = 0; k < j; k++) v -= L[i * bs + k] * L[j * bs + k];
            if (i == j) {
                if (!(v > 0.0)) return 0;
                L[i * bs + i] = sqrt(v);
            } else L[i * bs + j] = v / L[j * bs + j];
        }
    /* Li = L^{-1} (lower triangular), A^{-1} = Li^T Li */
    for (int j = 0; j < bs; j++)
        for (int i = 0; i < bs; i++) {
            if (i < j) { Li[i * bs + j] = 0.0; continue; }
            double v = i == j ? 1.0 : 0.0;
            for (int k = j; k < i; k++) v -= L[i * bs + k] * Li[k * bs + j];
            Li[i * bs + j] = v / L[i * bs + i];
        }
    for (int i = 0; i < bs; i++)
        for (int j = 0; j < bs; j++) {
            double v = 0.0;
            for (int k = i > j ? i : j; k < bs; k++) v += Li[k * bs + i] * Li[k * bs + j];
            A[i * bs + j] = v;
        }
    return 1;
}

int sb_block_inverse_spd(int bs, double *A)
{
    double d[12];
    for (int i = 0; i < bs; i++) d[i] = A[i * bs + i];
    if (sb_spd_block_inverse(bs, A)) return 1;
    memset(A, 0, (size_t)bs * bs * sizeof *A);
    for (int i = 0; i < bs; i++) A[i * bs + i] = d[i] != 0.0 && isfinite(d[i]) ? 1.0 / fabs(d[i]) : 1.0;
    return 0;
}

typedef struct jacobi_state {
    int level, n, bs;
    double *binv;      /* n * bs: the inverted node blocks, row-major per node */
} jacobi_state;

static int jacobi_alloc(void *st, sb_problem *p, int level, const sb_precond_opts *o)
{
    (void)o;
    jacobi_state *s = st;
    s->level = level;
    s->n = sb_problem_n(p, level);
    s->bs = sb_problem_block_size(p, level);
    if (s->bs < 1 || s->bs > 12 || s->n % s->bs) s->bs = 1;
    s->binv = malloc((size_t)s->n * (size_t)s->bs * sizeof *s->binv);
    return s->binv ? SB_OK : SB_ERR_NOMEM;
}

static int jacobi_setup(void *st, sb_problem *p)
{
    jacobi_state *s = st;
    const int n = s->n, bs = s->bs;
    if (bs == 1) sb_problem_hess_diag(p, s->level, s->binv);
    else {
        memset(s->binv, 0, (size_t)n * bs * sizeof *s->binv);
        sb_problem_hess_block_diag(p, s->level, s->binv);
    }
    for (int b0 = 0; b0 < n; b0 += bs) sb_block_inverse_spd(bs, s->binv + (size_t)b0 * bs);
    return SB_OK;
}

static int jacobi_apply(void *st, sb_problem *p, const double *r, double *z)
{
    (void)p;
    const jacobi_state *s = st;
    const int n = s->n, bs = s->bs;
    for (int b0 = 0; b0 < n; b0 += bs) {
        const double *A = s->binv + (size_t)b0 * bs;
        for (int i = 0; i < bs; i++) {
            double v = 0.0;
            for (int j = 0; j < bs; j++) v += A[i * bs + j] * r[b0 + j];
            z[b0 + i] = v;
        }
    }
    return SB_OK;
}

static void jacobi_free(void *st)
{
    jacobi_state *s = st;
    free(s->binv);
    s->binv = NULL;
}

static void jacobi_describe(const void *st, char *buf, size_t len)
{
    const jacobi_state *s = st;
    snprintf(buf, len, "node-block Jacobi (%dx%d blocks)", s->bs, s->bs);
}

const sb_precond_type sb_precond_jacobi = {
    "pcg-jacobi", sizeof(jacobi_state), jacobi_alloc, jacobi_setup, jacobi_apply, jacobi_free, jacobi_describe,
};
