/* sb_linsolve.c — CHOLMOD wrapper: analyze once per pattern, factorize
 * A + shift I per iteration (cholmod_factorize_p), solve into preallocated
 * workspaces (cholmod_solve2), count events, flops and nnz(L). */
#include "sb_linsolve.h"
#include "sb_context.h"
#include "sb_params.h"

#include <cholmod.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* CHOLMOD without its own threads (issue 42).  Debian's CHOLMOD 3 (SuiteSparse
 * 5) runs loops of its supernodal factorization (clearing its maps, zeroing
 * and assembling supernodes) as OpenMP regions with a compiled-in
 * num_threads(CHOLMOD_OMP_NUM_THREADS) = 4, whatever OMP_NUM_THREADS says.  On
 * the 2-core machine, with one BLAS thread doing the dense work and other
 * work beside it, half the factorization's time went into waking and waiting
 * for those threads (futex calls in the profile): a 199,692-dof bhem plate
 * factored in 15-17 s with them and in 8 s without.  The loops touch
 * disjoint entries, so the factor is the same bit for bit.  Inside every
 * CHOLMOD call the OpenMP regions are made inactive (max-active-levels 0),
 * and restored after, so run.threads still threads the assembly. */
static int cholmod_threads_off(void)
{
#ifdef _OPENMP
    const int m = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
    return m;
#else
    return 0;
#endif
}

static void cholmod_threads_on(int m)
{
#ifdef _OPENMP
    omp_set_max_active_levels(m);
#else
    (void)m;
#endif
}

struct sb_linsolve {
    sb_context *ctx;
    int level;
    cholmod_sparse *A;       /* pattern + values (values aliased by `mat`) */
    cholmod_factor *L;
    cholmod_dense *B, *X, *Y, *E;  /* solve2 workspaces (X, Y, E reused) */
    int factored;
    int factorized_once;      /* a numeric factorization was attempted since the analysis */
    double flops, lnz;
};

int sb_linsolve_create(sb_context *ctx, int level, sb_matrix *H, sb_linsolve **out)
{
    const sb_pattern *pat = H->pat;
    cholmod_common *cm = ctx->cholmod;
    *out = NULL;
    if (pat->nnz > INT_MAX)   /* cholmod_* (not cholmod_l_*) indexes entries with int */
        return sb_error(ctx, SB_ERR_INPUT, "a %d x %d matrix of %ld entries exceeds the %d entries of CHOLMOD's int "
                        "interface", pat->n, pat->n, pat->nnz, INT_MAX);
    sb_linsolve *ls = calloc(1, sizeof *ls);
    if (!ls) return SB_ERR_NOMEM;
    ls->ctx = ctx;
    ls->level = level;
    /* pattern-only allocation; the values are H's array (aliased, see free) */
    ls->A = cholmod_allocate_sparse((size_t)pat->n, (size_t)pat->n, (size_t)pat->nnz,
                                    1, 1, 1, CHOLMOD_PATTERN, cm);
    ls->B = cholmod_zeros((size_t)pat->n, 1, CHOLMOD_REAL, cm);
    if (!ls->A || !ls->B) {
        sb_linsolve_free(ls);
        return sb_error(ctx, SB_ERR_NOMEM, "cannot allocate a %d x %d sparse matrix (%ld entries)",
                        pat->n, pat->n, pat->nnz);
    }
    /* CHOLMOD default index type for cholmod_* (int) routines */
    int *Ap = ls->A->p, *Ai = ls->A->i;
    for (int c = 0; c <= pat->n; c++) Ap[c] = (int)pat->colptr[c];
    memcpy(Ai, pat->rowind, (size_t)pat->nnz * sizeof *Ai);
    ls->A->xtype = CHOLMOD_REAL;
    ls->A->x = H->val;

    if (sb_param_int_or(&ctx->params, "run.supernodes", SB_SUPERNODES_CHOLMOD) == SB_SUPERNODES_WIDE) {
        /* ASSUMPTION (measured, docs/scaling.md): wider relaxed amalgamation
         * than CHOLMOD's defaults (nrelax 4/16/48, zrelax 0.8/0.1/0.05)
         * merges more of a 2-D mesh's small supernodes, so the numeric
         * factorization runs more of its flops in larger DGEMM/DSYRK
         * blocks, for the stored zeros of the merged blocks */
        cm->nrelax[0] = 16, cm->nrelax[1] = 48, cm->nrelax[2] = 128;
        cm->zrelax[0] = 0.9, cm->zrelax[1] = 0.2, cm->zrelax[2] = 0.1;
    }
    double t0 = sb_stats_begin(&ctx->stats);
    int omp_levels = cholmod_threads_off();
    ls->L = cholmod_analyze(ls->A, cm);       /* fill-reducing ordering, symbolic, once */
    cholmod_threads_on(omp_levels);
    sb_stats_event(&ctx->stats, level, SB_EV_ANALYZE, t0);
    if (!ls->L || cm->status < CHOLMOD_OK) {
        sb_linsolve_free(ls);
        return sb_error(ctx, SB_ERR_INTERNAL, "CHOLMOD analyze failed (status %d) on level %d", cm->status, level);
    }
    ls->flops = cm->fl;
    ls->lnz = cm->lnz;
    ctx->stats.peak_rss_analyzed = sb_peak_rss();   /* issue 42: set-up plus the symbolic factor */
    if (level >= 0 && level < SB_MAX_LEVELS) {
        ctx->stats.chol_flops[level] = cm->fl;
        ctx->stats.chol_nnz_l[level] = cm->lnz;
        ctx->stats.matrix_nnz[level] = pat->nnz;
    }
    *out = ls;
    return SB_OK;
}

void sb_linsolve_free(sb_linsolve *ls)
{
    if (!ls) return;
    cholmod_common *cm = ls->ctx->cholmod;
    cholmod_free_factor(&ls->L, cm);
    if (ls->A) {
        ls->A->x = NULL;                  /* aliased: owned by the caller's matrix */
        ls->A->xtype = CHOLMOD_PATTERN;
    }
    cholmod_free_sparse(&ls->A, cm);
    cholmod_free_dense(&ls->B, cm);
    cholmod_free_dense(&ls->X, cm);
    cholmod_free_dense(&ls->Y, cm);
    cholmod_free_dense(&ls->E, cm);
    free(ls);
}

int sb_linsolve_factor(sb_linsolve *ls, double shift)
{
    cholmod_common *cm = ls->ctx->cholmod;
    double beta[2] = { shift, 0.0 };
    double t0 = sb_stats_begin(&ls->ctx->stats);
    const double cpu0 = sb_cpu_now();
    const int omp_levels = cholmod_threads_off();
    int ok = cholmod_factorize_p(ls->A, beta, NULL, 0, ls->L, cm);
    cholmod_threads_on(omp_levels);
    const double cpu = sb_cpu_now() - cpu0;
    /* status must be read right here: later calls reset it (DESIGN.md) */
    int status = cm->status;
    sb_stats_event(&ls->ctx->stats, ls->level, SB_EV_FACTORIZE, t0);
    if (ls->level >= 0 && ls->level < SB_MAX_LEVELS) {
        /* per factorization (issue 42): the analysis's figures summed, the
         * stored entries of this factor (an indefinite matrix stops CHOLMOD
         * early: its figures are an upper bound) */
        sb_stats *st = &ls->ctx->stats;
        st->chol_flops_sum[ls->level] += ls->flops;
        st->chol_nnz_l_sum[ls->level] += ls->lnz;
        st->chol_factorize_cpu[ls->level] += cpu;
        if (!ls->factorized_once) {   /* the first after this analysis (first touch of the factor) */
            st->chol_first_cpu[ls->level] += cpu;
            st->chol_first_flops[ls->level] += ls->flops;
        }
        st->chol_factor_entries[ls->level] = (double)(ls->L->is_super ? ls->L->xsize : ls->L->nzmax);
    }
    ls->factorized_once = 1;
    if (status == CHOLMOD_NOT_POSDEF) {
        ls->factored = 0;
        ls->ctx->stats.not_posdef++;
        return SB_NOT_POSDEF;
    }
    if (!ok || status < CHOLMOD_OK) {
        ls->factored = 0;
        return sb_error(ls->ctx, SB_ERR_INTERNAL, "CHOLMOD factorize failed (status %d) on level %d",
                        status, ls->level);
    }
    ls->factored = 1;
    return SB_OK;
}

int sb_linsolve_solve(sb_linsolve *ls, const double *b, double *x)
{
    cholmod_common *cm = ls->ctx->cholmod;
    if (!ls->factored) return sb_error(ls->ctx, SB_ERR_INTERNAL, "solve without a valid factorization");
    size_t n = ls->A->nrow;
    double t0 = sb_stats_begin(&ls->ctx->stats);
    memcpy(ls->B->x, b, n * sizeof(double));
    const int omp_levels = cholmod_threads_off();
    int ok = cholmod_solve2(CHOLMOD_A, ls->L, ls->B, NULL, &ls->X, NULL, &ls->Y, &ls->E, cm);
    cholmod_threads_on(omp_levels);
    sb_stats_event(&ls->ctx->stats, ls->level, SB_EV_SOLVE, t0);
    if (!ok || !ls->X) return sb_error(ls->ctx, SB_ERR_INTERNAL, "CHOLMOD solve failed (status %d)", cm->status);
    memcpy(x, ls->X->x, n * sizeof(double));
    return sb_all_finite((int)n, x) ? SB_OK : SB_NONFINITE;
}

double sb_linsolve_flops(const sb_linsolve *ls) { return ls->flops; }

int sb_linsolve_supernodes(const sb_linsolve *ls, sb_supernode_bins *b)
{
    memset(b, 0, sizeof *b);
    const cholmod_factor *L = ls->L;
    if (!L || !L->is_super) return SB_ERR_INPUT;
    const int *super = L->super, *pi = L->pi;
    b->n_super = (long)L->nsuper;
    for (size_t s = 0; s < L->nsuper; s++) {
        const double k = (double)(super[s + 1] - super[s]), m = (double)(pi[s + 1] - pi[s]), r = m - k;
        /* dense Cholesky of the m x k panel and the rank-k update it sends up */
        const double fl = k * k * k / 3.0 + r * k * k + r * r * k;
        int bin = 0;
        for (long w = (long)k; w > 1 && bin < SB_SN_BINS - 1; w >>= 1) bin++;
        b->supernodes[bin]++;
        b->columns[bin] += (long)k;
        b->flops[bin] += fl;
        b->mean_k[bin] += fl * k;
        b->mean_m[bin] += fl * m;
        b->flops_total += fl;
    }
    for (int i = 0; i < SB_SN_BINS; i++)
        if (b->flops[i] > 0) b->mean_k[i] /= b->flops[i], b->mean_m[i] /= b->flops[i];
    return SB_OK;
}
double sb_linsolve_nnz_l(const sb_linsolve *ls) { return ls->lnz; }

double sb_linsolve_fill(int supernodes)
{
    return supernodes == SB_SUPERNODES_WIDE ? 1.45 : 1.3;
}
