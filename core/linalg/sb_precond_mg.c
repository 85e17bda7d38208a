/* sb_precond_mg.c — one symmetric V-cycle (or W-cycle, solver.mg_cycle=w:
 * see second_cycle) of the method's own nested hierarchy as the
 * preconditioner of CG (solver.linear = pcg-mg).
 *
 *   coarse operators  H_l = I_l^T H_{l+1} I_l, Galerkin, recomputed once per
 *                     Newton iteration from the finest Hessian
 *                     (sb_problem_galerkin_hessian: the products the rmtr
 *                     solver's Galerkin coarse models use);
 *   transfers         the method's prolongation I_l and restriction I_l^T
 *                     (sb_problem_prolong / sb_problem_restrict, counted);
 *   smoother          block Gauss–Seidel on the node blocks: forward sweeps
 *                     before the coarse correction, backward sweeps after
 *                     (the adjoint), mg_sweeps of each;
 *   coarsest level    CHOLMOD (analyzed once, factored once per Newton
 *                     iteration);
 *   lagging           solver.mg_lag = k > 1: the coarse levels (Galerkin
 *                     products, their block inverses, the coarsest
 *                     factorization) are rebuilt at every step's first
 *                     Newton iteration and every k-th one after, kept in
 *                     between, while the finest level's smoother always
 *                     uses the current Hessian (PETSc's
 *                     -snes_lag_preconditioner, applied to the coarse
 *                     levels only).  The V-cycle stays symmetric and
 *                     positive definite: a symmetric V-cycle whose coarse
 *                     correction is any SPD operator and whose smoother
 *                     satisfies R^{-1} + R^{-T} - H > 0 is SPD (Vassilevski
 *                     2008, §5.1), and the kept coarse V-cycle is SPD for
 *                     the kept (SPD or shifted) coarse operators.
 *
 * Symmetry and definiteness: with pre-smoother R and post-smoother R^T the
 * V-cycle is a symmetric operator B; B is positive definite when the coarse
 * solve is and the smoother converges in the energy norm, i.e. when
 * R^{-1} + R^{-T} - H is SPD (Xu & Zikatanov, J. AMS 15 (2002), and
 * Vassilevski, Multilevel Block Factorization Preconditioners (2008),
 * §5.1).  For block Gauss–Seidel, R^{-1} = D + L, so R^{-1} + R^{-T} - H = D,
 * the node-block diagonal: SPD whenever H is.  So CG stays valid on every
 * SPD Hessian (Saad, Iterative Methods, §9.2; checked on random vectors in
 * tests/test_krylov.c).
 *
 * Why Gauss–Seidel and not Chebyshev–Jacobi: the node blocks of these
 * shells are strongly coupled (12 Hermite dofs per bhem node, 3 position
 * dofs whose membrane stiffness dwarfs the bending), which a block smoother
 * inverts exactly; Gauss–Seidel needs no eigenvalue estimate (Chebyshev
 * needs lambda_max of D^{-1} H per Newton iteration, and a bad estimate
 * makes the preconditioner indefinite); everything here is sequential, where
 * Chebyshev's only advantage, parallel matrix-vector products, does not
 * count. */
#include "sb_precond.h"
#include "sb_context.h"
#include "sb_linsolve.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct mg_level {
    int n, bs;
    double *b, *x, *t, *e, *w;  /* right side, iterate, residual, correction, scatter scratch */
    double *binv;               /* n * bs inverted node blocks (levels >= 1) */
    double *xw;                 /* W-cycle (levels 1 .. nl-2): the first cycle's iterate */
    /* kd[j]: the entries of column j above its node block are
     * colptr[j] .. colptr[j] + kd[j] - 1, the block's own from there to the
     * diagonal (the column's last entry): the sweeps' loops split once per
     * pattern instead of testing every entry's row (levels >= 1) */
    int *kd;
    const sb_pattern *kfrom;
    /* the penalty band (levels >= 1 of a method with penalty_support): its
     * dofs, their principal submatrix of the level's operator (pattern from
     * the level's, values copied from bpos each set-up), CHOLMOD */
    int ns, band_ok;
    int *band;
    sb_pattern *bpat;
    const sb_pattern *bfrom;    /* the level pattern bpos indexes */
    long *bpos;
    sb_matrix B;
    sb_linsolve *bls;
    double *bb;
} mg_level;

const char *const sb_mg_cycle_names[] = { "v", "w", NULL };

int sb_mg_cycle_kind(const char *name)
{
    return name && strcmp(name, "w") == 0 ? SB_MG_CYCLE_W : SB_MG_CYCLE_V;
}

typedef struct mg_state {
    int nl, sweeps, cycle;
    int lag, since, step;       /* solver.mg_lag; setups since the coarse levels were built, and in which step */
    double coarse_shift;        /* shift of the coarsest factorization (0 unless indefinite) */
    mg_level lv[SB_MAX_LEVELS];
} mg_state;

static void band_free(mg_level *L)
{
    sb_linsolve_free(L->bls);
    sb_matrix_free(&L->B);
    sb_pattern_free(L->bpat);
    free(L->band); free(L->bpos); free(L->bb);
    L->bls = NULL, L->bpat = NULL, L->band = NULL, L->bpos = NULL, L->bb = NULL, L->ns = 0;
}

static void mg_free(void *st)
{
    mg_state *m = st;
    for (int l = 0; l < SB_MAX_LEVELS; l++) {
        mg_level *L = &m->lv[l];
        band_free(L);
        free(L->b); free(L->x); free(L->t); free(L->e); free(L->w); free(L->binv); free(L->xw); free(L->kd);
        memset(L, 0, sizeof *L);
    }
}

static int band_build(mg_level *L, sb_problem *p, int l);

static int mg_alloc(void *st, sb_problem *p, int level, const sb_precond_opts *o)
{
    mg_state *m = st;
    sb_context *ctx = sb_problem_context(p);
    const sb_method_type *mt = sb_problem_method_type(p);
    if (!(mt->flags & SB_METHOD_HIERARCHY) || mt->adapt)
        return sb_error(ctx, SB_ERR_UNSUPPORTED, "solver.linear=pcg-mg needs a method with a fixed level hierarchy "
                        "(prolongation and restriction), but method %s has none: use pcg-jacobi, pcg-amg or cholmod",
                        mt->name);
    if (level < 1 || !sb_problem_has_hierarchy(p))
        return sb_error(ctx, SB_ERR_INPUT, "solver.linear=pcg-mg needs at least 2 levels (one V-cycle over the "
                        "method's hierarchy), but --levels is %d", level + 1);
    m->nl = level + 1;
    m->sweeps = o && o->mg_sweeps > 0 ? o->mg_sweeps : 1;
    m->cycle = o && o->mg_cycle == SB_MG_CYCLE_W ? SB_MG_CYCLE_W : SB_MG_CYCLE_V;
    m->lag = o && o->mg_lag > 1 ? o->mg_lag : 1;
    m->since = 0;
    m->step = -1;
    for (int l = 0; l < m->nl; l++) {
        mg_level *L = &m->lv[l];
        L->n = sb_problem_n(p, l);
        L->bs = sb_problem_block_size(p, l);
        if (L->bs < 1 || L->bs > 12 || L->n % L->bs) L->bs = 1;
        const size_t n = (size_t)L->n;
        L->b = malloc(n * sizeof(double));
        L->x = malloc(n * sizeof(double));
        L->t = malloc(n * sizeof(double));
        L->e = malloc(n * sizeof(double));
        L->w = malloc(n * sizeof(double));
        if (l > 0) L->binv = malloc(n * (size_t)L->bs * sizeof(double));
        if (l > 0) L->kd = malloc(n * sizeof(int));
        const int w = m->cycle == SB_MG_CYCLE_W && l > 0 && l < m->nl - 1;
        if (w) L->xw = malloc(n * sizeof(double));
        if (!L->b || !L->x || !L->t || !L->e || !L->w || (l > 0 && (!L->binv || !L->kd)) || (w && !L->xw)) {
            mg_free(m);
            return sb_error(ctx, SB_ERR_NOMEM, "out of memory (pcg-mg workspaces, level %d)", l);
        }
    }
    /* the symbolic Galerkin products, once per run; a hierarchy whose
     * products do not fit the coarse patterns is refused here */
    for (int lc = m->nl - 2; lc >= 0; lc--) {
        int rc = sb_problem_galerkin_prepare_lean(p, lc);
        if (rc) {
            mg_free(m);
            char msg[sizeof ctx->err];
            snprintf(msg, sizeof msg, "%s", ctx->err);
            return sb_error(ctx, rc, "solver.linear=pcg-mg: %s", msg);
        }
    }
    /* the penalty band of every level but the coarsest (solved exactly) */
    for (int l = 1; l < m->nl; l++) {
        int rc = band_build(&m->lv[l], p, l);
        if (rc) {
            mg_free(m);
            return rc;
        }
    }
    return SB_OK;
}

/* the smoother's inverted node blocks of level l, from its Hessian as it is */
static void split_columns(mg_level *L, const sb_pattern *pat);

static void mg_block_inverses(mg_level *L, sb_problem *p, int l)
{
    split_columns(L, sb_problem_hessian(p, l)->pat);
    if (L->bs == 1) sb_problem_hess_diag(p, l, L->binv);
    else {
        memset(L->binv, 0, (size_t)L->n * L->bs * sizeof(double));
        sb_problem_hess_block_diag(p, l, L->binv);
    }
    for (int b0 = 0; b0 < L->n; b0 += L->bs) sb_block_inverse_spd(L->bs, L->binv + (size_t)b0 * L->bs);
}

/* The penalty band of level l (issue 38, docs/krylov.md): the method's
 * penalty support, node-aligned.  Its pattern holds every node pair the
 * level's pattern couples; the symbolic analysis is done once (level -1 for
 * the statistics: the finest level's CHOLMOD figures stay the run's). */
static int band_build(mg_level *L, sb_problem *p, int l)
{
    const sb_method_type *mt = sb_problem_method_type(p);
    sb_context *ctx = sb_problem_context(p);
    if (!mt->penalty_support || l < 1) return SB_OK;
    unsigned char *mask = calloc((size_t)L->n, 1);
    int *loc = malloc((size_t)L->n * sizeof *loc);
    if (!mask || !loc) { free(mask); free(loc); return sb_error(ctx, SB_ERR_NOMEM, "out of memory (pcg-mg band)"); }
    (void)mt->penalty_support(sb_problem_method_state(p), l, mask);
    const int bs = L->bs;
    /* whole node blocks */
    for (int b0 = 0; b0 < L->n; b0 += bs) {
        int any = 0;
        for (int c = 0; c < bs; c++) any |= mask[b0 + c];
        for (int c = 0; c < bs; c++) mask[b0 + c] = (unsigned char)any;
    }
    int ns = 0;
    for (int i = 0; i < L->n; i++) loc[i] = mask[i] ? ns++ : -1;
    int rc = SB_OK;
    if (ns == 0 || ns == L->n) goto out;   /* nothing, or the whole level: the band adds nothing */
    const sb_pattern *pat = sb_problem_hessian(p, l)->pat;
    sb_pattern_builder *pb = sb_pattern_builder_new(ns / bs, bs);
    if (!pb) { rc = sb_error(ctx, SB_ERR_NOMEM, "out of memory (pcg-mg band)"); goto out; }
    for (int j = 0; j < L->n && !rc; j += bs) {
        if (loc[j] < 0) continue;
        int nd[2] = { loc[j] / bs, loc[j] / bs };
        rc = sb_pattern_builder_add(pb, 1, nd);
        for (long k = pat->colptr[j]; k < pat->colptr[j + 1] && !rc; k++) {
            const int i = pat->rowind[k];
            if (loc[i] < 0 || i / bs == j / bs || i % bs) continue;
            nd[0] = loc[i] / bs;
            rc = sb_pattern_builder_add(pb, 2, nd);
        }
    }
    {   /* finishing frees the builder, also after an error */
        sb_pattern *bp = NULL;
        const int frc = sb_pattern_builder_finish(pb, &bp);
        if (!rc) rc = frc, L->bpat = bp;
        else sb_pattern_free(bp);
    }
    if (rc) { rc = sb_error(ctx, rc < 0 ? rc : SB_ERR_NOMEM, "pcg-mg: the penalty band's pattern"); goto out; }
    L->ns = ns;
    L->band = malloc((size_t)ns * sizeof *L->band);
    L->bpos = malloc((size_t)L->bpat->nnz * sizeof *L->bpos);
    L->bb = malloc((size_t)ns * sizeof *L->bb);
    if (!L->band || !L->bpos || !L->bb || sb_matrix_init(&L->B, L->bpat)) {
        rc = sb_error(ctx, SB_ERR_NOMEM, "out of memory (pcg-mg band)");
        goto out;
    }
    for (int i = 0; i < L->n; i++)
        if (loc[i] >= 0) L->band[loc[i]] = i;
    L->bfrom = NULL;
    rc = sb_linsolve_create(ctx, -1, &L->B, &L->bls);
out:
    if (rc) band_free(L);
    free(mask);
    free(loc);
    return rc;
}

/* the band's values from the level's operator as it is; a band that is not
 * positive definite (an indefinite Hessian) is left out of this set-up's
 * cycles, which then stay those of the plain smoother */
static int band_factor(mg_level *L, const sb_matrix *H)
{
    if (!L->ns) return SB_OK;
    if (L->bfrom != H->pat) {   /* positions in the level's pattern (built once per pattern) */
        for (int jc = 0; jc < L->ns; jc++)
            for (long k = L->bpat->colptr[jc]; k < L->bpat->colptr[jc + 1]; k++)
                L->bpos[k] = sb_pattern_find(H->pat, L->band[L->bpat->rowind[k]], L->band[jc]);
        L->bfrom = H->pat;
    }
    for (long k = 0; k < L->bpat->nnz; k++) L->B.val[k] = L->bpos[k] >= 0 ? H->val[L->bpos[k]] : 0.0;
    const int rc = sb_linsolve_factor(L->bls, 0.0);
    L->band_ok = rc == SB_OK;
    return rc == SB_NOT_POSDEF ? SB_OK : rc;
}

/* x += Z B^{-1} Z^T (b - H x): the exact band solve (a symmetric
 * multiplicative subspace correction of the smoother) */
static int band_solve(mg_level *L, const sb_matrix *H)
{
    if (!L->ns || !L->band_ok) return SB_OK;
    sb_matrix_symv(H, L->x, L->t);
    for (int k = 0; k < L->ns; k++) L->bb[k] = L->b[L->band[k]] - L->t[L->band[k]];
    int rc = sb_linsolve_solve(L->bls, L->bb, L->bb);
    if (rc) return rc;
    for (int k = 0; k < L->ns; k++) L->x[L->band[k]] += L->bb[k];
    return SB_OK;
}

static int mg_setup(void *st, sb_problem *p)
{
    mg_state *m = st;
    const int F = m->nl - 1, step = sb_problem_step(p);
    mg_block_inverses(&m->lv[F], p, F);          /* the finest level: always the current Hessian */
    int brc = band_factor(&m->lv[F], sb_problem_hessian(p, F));
    if (brc) return brc;
    if (m->lag > 1 && m->step == step && m->since > 0 && m->since < m->lag) {
        m->since++;                              /* the coarse levels as built (solver.mg_lag) */
        return SB_OK;
    }
    m->since = 1;
    m->step = step;
    for (int lc = m->nl - 2; lc >= 0; lc--) {
        int rc = sb_problem_galerkin_hessian(p, lc);
        if (rc) return rc;
    }
    for (int l = 1; l < F; l++) {
        mg_block_inverses(&m->lv[l], p, l);
        if ((brc = band_factor(&m->lv[l], sb_problem_hessian(p, l)))) return brc;
    }
    /* the coarsest level by CHOLMOD; a Galerkin operator of an indefinite
     * Hessian may be indefinite: then the shift of the direct path (1e-8
     * max|H| grown 10x, Nocedal & Wright Alg. 3.3) keeps the V-cycle SPD */
    m->coarse_shift = 0.0;
    int rc = sb_problem_factor(p, 0, 0.0);
    if (rc == SB_NOT_POSDEF) {
        double scale = sb_matrix_norm_max(sb_problem_hessian(p, 0));
        double tau = 1e-8 * (scale > 0 ? scale : 1.0);
        for (int k = 0; k < 40 && rc == SB_NOT_POSDEF; k++, tau *= 10) {
            rc = sb_problem_factor(p, 0, tau);
            m->coarse_shift = tau;
        }
    }
    return rc;
}

/* The smoother: block Gauss–Seidel over the node blocks.  H is upper CSC
 * (sb_sparse.h): the strictly lower part of row j is column j above its
 * node block.
 *
 * kd of level L's pattern (once per pattern): the rows of a column are
 * sorted and its last entry is the diagonal (sb_sparse.h) */
static void split_columns(mg_level *L, const sb_pattern *pat)
{
    if (L->kfrom == pat) return;
    for (int b0 = 0; b0 < L->n; b0 += L->bs)
        for (int j = b0; j < b0 + L->bs; j++) {
            long k = pat->colptr[j];
            while (k < pat->colptr[j + 1] && pat->rowind[k] < b0) k++;
            L->kd[j] = (int)(k - pat->colptr[j]);
        }
    L->kfrom = pat;
}

/* y_block = binv_block v (bs x bs, row-major) */
static inline void block_apply(const double *A, int bs, const double *v, double *y)
{
    for (int i = 0; i < bs; i++) {
        double s = 0.0;
        for (int j = 0; j < bs; j++) s += A[i * bs + j] * v[j];
        y[i] = s;
    }
}

/* one node block of the forward sweep: v = t - (rows of the block, columns
 * before it) y, then y_block = binv v */
static inline void gs_forward_block(const mg_level *L, const sb_matrix *H, int b0, const double *t, double *y,
                                    double *v)
{
    const long *cp = H->pat->colptr;
    const int *ri = H->pat->rowind;
    const double *val = H->val;
    const int bs = L->bs;
    for (int j = b0; j < b0 + bs; j++) {
        double s = t[j];
        for (long k = cp[j], ke = cp[j] + L->kd[j]; k < ke; k++) s -= val[k] * y[ri[k]];
        v[j - b0] = s;
    }
    block_apply(L->binv + (size_t)b0 * bs, bs, v, y + b0);
}

static void gs_forward(const mg_level *L, const sb_matrix *H, const double *t, double *y)
{
    double v[12];
    for (int b0 = 0; b0 < L->n; b0 += L->bs) gs_forward_block(L, H, b0, t, y, v);
}

/* w_i += H_ij y_j for the node block's columns j (b0 .. b0+bs-1) and the
 * rows i above the block: a finished block's share of the later rows'
 * sums in a backward sweep */
static inline void scatter_above(const mg_level *L, const sb_matrix *H, int b0, const double *y, double *w)
{
    const long *cp = H->pat->colptr;
    const int *ri = H->pat->rowind;
    const double *val = H->val;
    for (int j = b0; j < b0 + L->bs; j++) {
        const double yj = y[j];
        for (long k = cp[j], ke = cp[j] + L->kd[j]; k < ke; k++) w[ri[k]] += val[k] * yj;
    }
}

/* backward sweep from zero: (D + U) y = t; the finished blocks' columns are
 * scattered into w (w_i = sum_{j later} H_ij y_j) */
static void gs_backward(const mg_level *L, const sb_matrix *H, const double *t, double *y, double *w)
{
    const int n = L->n, bs = L->bs;
    double v[12];
    memset(w, 0, (size_t)n * sizeof *w);
    for (int b0 = n - bs; b0 >= 0; b0 -= bs) {
        for (int j = b0; j < b0 + bs; j++) v[j - b0] = t[j] - w[j];
        block_apply(L->binv + (size_t)b0 * bs, bs, v, y + b0);
        scatter_above(L, H, b0, y, w);
    }
}

/* The forward sweep from zero and its residual in one pass over H:
 * (D' + L) y = t (D' the inverse of binv: D, the node-block diagonal, for
 * SPD blocks), then r = t - H y = (D' - D) y - U y (U the strictly upper
 * block part), each column's entries read for the sweep and, still in
 * cache, scattered into r once y's block is known.  The same y and r as
 * gs_forward + residual in half the passes over the matrix (the smoother's
 * sweeps and residuals, not the arithmetic, are what a V-cycle pays: it
 * reads 12 bytes an entry for 2 flops). */
static void gs_forward_residual(const mg_level *L, const sb_matrix *H, const double *t, double *y, double *r)
{
    const long *cp = H->pat->colptr;
    const int *ri = H->pat->rowind;
    const double *val = H->val;
    const int n = L->n, bs = L->bs;
    double v[12];
    memset(r, 0, (size_t)n * sizeof *r);
    for (int b0 = 0; b0 < n; b0 += bs) {
        gs_forward_block(L, H, b0, t, y, v);
        /* the block's own share of r, v - D y: zero up to round-off unless
         * binv is not D's inverse (a block that is not SPD gets the
         * inverted absolute diagonal, sb_block_inverse_spd) */
        for (int j = b0; j < b0 + bs; j++) r[j] += v[j - b0];
        for (int j = b0; j < b0 + bs; j++) {
            const double yj = y[j];
            const long kb = cp[j] + L->kd[j], dg = cp[j + 1] - 1;
            for (long k = cp[j]; k < kb; k++) r[ri[k]] -= val[k] * yj;
            for (long k = kb; k < dg; k++) {   /* the diagonal block's column j: rows b0 <= i < j */
                const int i = ri[k];
                r[j] -= val[k] * y[i];
                r[i] -= val[k] * yj;
            }
            r[j] -= val[dg] * yj;
        }
    }
}

/* The backward sweep in place, x += (D + U)^{-1} (b - H x), in one pass
 * over H: block by block from the last, its residual from the current x
 * (the earlier blocks' old values read down the block's columns, its own
 * block through the stored upper triangle of the diagonal block, the later
 * blocks' new values from the scatter w), then the new values scattered
 * into w.  The same update as residual + gs_backward + axpy (Gauss–Seidel's
 * two forms), in one pass instead of two. */
static void gs_backward_inplace(const mg_level *L, const sb_matrix *H, const double *b, double *x, double *w)
{
    const long *cp = H->pat->colptr;
    const int *ri = H->pat->rowind;
    const double *val = H->val;
    const int n = L->n, bs = L->bs;
    double v[12], d[12];
    memset(w, 0, (size_t)n * sizeof *w);
    for (int b0 = n - bs; b0 >= 0; b0 -= bs) {
        for (int j = b0; j < b0 + bs; j++) v[j - b0] = b[j] - w[j];
        for (int j = b0; j < b0 + bs; j++) {
            const double xj = x[j];
            const long kb = cp[j] + L->kd[j], dg = cp[j + 1] - 1;
            double s = 0.0;
            for (long k = cp[j]; k < kb; k++) s += val[k] * x[ri[k]];
            v[j - b0] -= s;
            for (long k = kb; k < dg; k++) {   /* the diagonal block's column j: rows b0 <= i < j */
                const int i = ri[k];
                v[j - b0] -= val[k] * x[i];
                v[i - b0] -= val[k] * xj;
            }
            v[j - b0] -= val[dg] * xj;
        }
        block_apply(L->binv + (size_t)b0 * bs, bs, v, d);
        for (int i = 0; i < bs; i++) x[b0 + i] += d[i];
        scatter_above(L, H, b0, x, w);
    }
}

/* t = b - H x */
static void residual(const sb_matrix *H, int n, const double *b, const double *x, double *t)
{
    sb_matrix_symv(H, x, t);
    for (int i = 0; i < n; i++) t[i] = b[i] - t[i];
}

static int vcycle(mg_state *m, sb_problem *p, int l);

/* x_l += I (cycle on level l-1 of I^T t_l): the coarse correction, from the
 * residual in L->t */
static int coarse_correction(mg_state *m, sb_problem *p, int l);

/* The W-cycle's second visit (gamma = 2) of level c (0 < c < nl-1): one more
 * cycle on the residual of the first one's iterate, x_c += B_c (b_c - H_c x_c).
 * Two steps of a symmetric iteration are again symmetric, B_2 = 2 B - B H B =
 * B (2 B^-1 - H) B, and positive definite when the cycle converges in the
 * energy norm (2 B^-1 - H > 0 iff ||I - B H||_H < 1, which the symmetric
 * Gauss-Seidel cycle with an exact coarsest solve satisfies): CG stays valid.
 * Cost: level c is visited 2^(nl-1-c) times with a quarter of the dofs per
 * level, so the coarse levels together cost about one more finest-level
 * cycle (Trottenberg, Oosterlee & Schueller, Multigrid (2001), §2.4). */
static int second_cycle(mg_state *m, sb_problem *p, int c)
{
    mg_level *C = &m->lv[c];
    residual(sb_problem_hessian(p, c), C->n, C->b, C->x, C->t);
    double *sw = C->b;
    C->b = C->t;        /* the residual is the right side of the second cycle */
    C->t = sw;
    sw = C->x;
    C->x = C->xw;       /* the first iterate is kept in xw */
    C->xw = sw;
    int rc = vcycle(m, p, c);
    sb_axpy(C->n, 1.0, C->xw, C->x);
    return rc;
}

/* x_l ~ H_l^{-1} b_l by one cycle (V, or W: see second_cycle) from x_l = 0 */
static int vcycle(mg_state *m, sb_problem *p, int l)
{
    mg_level *L = &m->lv[l];
    if (l == 0) return sb_problem_solve(p, 0, L->b, L->x);
    const sb_matrix *H = sb_problem_hessian(p, l);
    const int n = L->n;
    /* one sweep each way and no penalty band: the sweeps with their
     * residuals fused, two passes over H instead of four */
    const int fused = m->sweeps == 1 && !(L->ns && L->band_ok);
    if (fused) {
        gs_forward_residual(L, H, L->b, L->x, L->t);
        int rc = coarse_correction(m, p, l);
        if (rc) return rc;
        gs_backward_inplace(L, H, L->b, L->x, L->w);
        return SB_OK;
    }
    /* pre-smoothing: forward sweeps */
    gs_forward(L, H, L->b, L->x);
    for (int s = 1; s < m->sweeps; s++) {
        residual(H, n, L->b, L->x, L->t);
        gs_forward(L, H, L->t, L->e);
        sb_axpy(n, 1.0, L->e, L->x);
    }
    /* the penalty band solved exactly after the forward sweeps */
    int rc = band_solve(L, H);
    if (rc) return rc;
    /* coarse correction */
    residual(H, n, L->b, L->x, L->t);
    if ((rc = coarse_correction(m, p, l))) return rc;
    /* the band again before the backward sweeps: the adjoint order */
    if ((rc = band_solve(L, H))) return rc;
    /* post-smoothing: backward sweeps (the adjoint of the pre-smoother) */
    for (int s = 0; s < m->sweeps; s++) {
        residual(H, n, L->b, L->x, L->t);
        gs_backward(L, H, L->t, L->e, L->w);
        sb_axpy(n, 1.0, L->e, L->x);
    }
    return SB_OK;
}

static int coarse_correction(mg_state *m, sb_problem *p, int l)
{
    mg_level *L = &m->lv[l];
    int rc = sb_problem_restrict(p, l - 1, L->t, m->lv[l - 1].b);
    if (!rc) rc = vcycle(m, p, l - 1);
    if (!rc && m->cycle == SB_MG_CYCLE_W && l - 1 > 0) rc = second_cycle(m, p, l - 1);
    if (!rc) rc = sb_problem_prolong(p, l - 1, m->lv[l - 1].x, L->e);
    if (rc) return rc;
    sb_axpy(L->n, 1.0, L->e, L->x);
    return SB_OK;
}

static int mg_apply(void *st, sb_problem *p, const double *r, double *z)
{
    mg_state *m = st;
    mg_level *F = &m->lv[m->nl - 1];
    sb_copy(F->n, r, F->b);
    int rc = vcycle(m, p, m->nl - 1);
    if (rc < 0) return rc;
    sb_copy(F->n, F->x, z);
    return rc;
}

static void mg_describe(const void *st, char *buf, size_t len)
{
    const mg_state *m = st;
    char lag[96] = "";
    if (m->lag > 1) snprintf(lag, sizeof lag, ", coarse levels rebuilt every %d Newton iterations and each step", m->lag);
    char band[96] = "";
    int nb = 0;
    for (int l = 1; l < m->nl; l++) nb += m->lv[l].ns;
    if (nb) snprintf(band, sizeof band, ", the penalty band (%d dofs on the finest level) solved exactly by CHOLMOD",
                     m->lv[m->nl - 1].ns);
    snprintf(buf, len, "%s over %d levels, Galerkin coarse operators, block Gauss-Seidel %d+%d sweeps "
             "(forward/backward)%s, CHOLMOD on the coarsest level (%d dofs)%s",
             m->cycle == SB_MG_CYCLE_W ? "W-cycle" : "V-cycle", m->nl, m->sweeps, m->sweeps, band, m->lv[0].n, lag);
}

const sb_precond_type sb_precond_mg = {
    "pcg-mg", sizeof(mg_state), mg_alloc, mg_setup, mg_apply, mg_free, mg_describe,
};
