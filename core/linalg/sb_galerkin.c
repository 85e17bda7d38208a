/* sb_galerkin.c — Galerkin coarse Hessians H_c = S^T H_f S (sb_galerkin.h).
 *
 * Column by column of H_c: t = H_f S e_K (the fine Hessian applied to one
 * prolongated coarse basis vector, a sparse accumulation over the columns of
 * H_f that S e_K touches: the upper part of each from the pattern, the lower
 * part from a transposed index kept once per run), then H_c(:,K) = S^T t
 * restricted to rows J <= K.
 * Cost per coarse dof: nnz(S e_K) x (row length of H_f) + nnz(t) x (row
 * length of S), i.e. O(n_f) in total for local operators.
 *
 * The lean form's numeric product runs the same steps on a block of
 * coarse columns at once, the coarse pattern's dofs of one node (bs, e.g.
 * 12 for a Hermite node): each fine column of H_f and each row of S is
 * then read once per block instead of once per coarse column, and the
 * accumulators hold a short dense row per entry (compact lists, no dense
 * vectors of the fine size).  Its symbolic check at creation stays
 * column by column. */
#include "sb_galerkin.h"

#include <stdlib.h>
#include <string.h>

int sb_csr_alloc(sb_csr *A, int nr, int nc, long nnz)
{
    memset(A, 0, sizeof *A);
    A->nr = nr;
    A->nc = nc;
    A->rp = calloc((size_t)nr + 1, sizeof *A->rp);
    A->ci = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *A->ci);
    A->v = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *A->v);
    if (!A->rp || !A->ci || !A->v) {
        sb_csr_free(A);
        return SB_ERR_NOMEM;
    }
    return SB_OK;
}

void sb_csr_free(sb_csr *A)
{
    if (!A) return;
    free(A->rp);
    free(A->ci);
    free(A->v);
    memset(A, 0, sizeof *A);
}

struct sb_galerkin {
    int nf, nc;
    sb_csr S;          /* free fine rows x free coarse columns */
    sb_csr St;         /* its transpose (coarse rows) */
    /* the strictly lower part of the fine pattern by columns (the rows of
     * its upper triangle): column j's upper entries are read from the
     * pattern itself, these give the entries (i, j), i > j, stored in
     * column i of the upper triangle */
    const sb_pattern *fine;
    long *lrp;         /* nf+1 */
    int *lrow;         /*   row i > j of each entry */
    int *loff;         /*   its offset in column i: position colptr[i] + loff */
    const sb_pattern *coarse;
    int lean;          /* sb_galerkin_create_lean: A + A^T, no lower index */
    int *cpos;         /*   lean: position of row J in the current coarse column (-1 none), nc */
    /* lean numeric product by blocks of bs coarse columns (product_block_lean) */
    int bs;            /*   coarse columns per block (0: column by column) */
    int *jpos, *tpos, *upos;          /* nf, nf, nc: position in the block's lists (-1 none) */
    int *jlist;                        /* the block's fine columns (at most maxj) */
    double *sval, *tval, *uval;        /* bs values per list entry: S(j, K), T(i, K), A(J, K) */
    unsigned char *sidx;               /* per fine column j: the block columns b that S(j, K0 + b) reaches */
    int *scount;                       /*   how many (their values first in sval's slots) */
    long *ucur;                        /* per coarse row J > K0: a cursor in column J of Hc */
    const unsigned char *fixed_f, *fixed_c;   /* the caller's arrays, read at every product */
    double *t, *u;     /* dense accumulators: nf, nc */
    int *tlist, *ulist;
    unsigned char *tmark, *umark, *inpat;
};

void sb_galerkin_free(sb_galerkin *G)
{
    if (!G) return;
    sb_csr_free(&G->S);
    sb_csr_free(&G->St);
    free(G->lrp); free(G->lrow); free(G->loff); free(G->cpos);
    free(G->t); free(G->u); free(G->tlist); free(G->ulist);
    free(G->tmark); free(G->umark); free(G->inpat);
    free(G->jpos); free(G->tpos); free(G->upos); free(G->jlist);
    free(G->sval); free(G->tval); free(G->uval); free(G->ucur); free(G->sidx); free(G->scount);
    free(G);
}

/* B = S without explicit zeros */
static int copy_nonzeros(const sb_csr *S, sb_csr *B)
{
    int rc = sb_csr_alloc(B, S->nr, S->nc, S->rp[S->nr]);
    if (rc) return rc;
    long k = 0;
    for (int i = 0; i < S->nr; i++) {
        for (long q = S->rp[i]; q < S->rp[i + 1]; q++) {
            if (S->v[q] == 0.0) continue;
            B->ci[k] = S->ci[q];
            B->v[k++] = S->v[q];
        }
        B->rp[i + 1] = k;
    }
    return SB_OK;
}

static int transpose(const sb_csr *A, sb_csr *T)
{
    int rc = sb_csr_alloc(T, A->nc, A->nr, A->rp[A->nr]);
    if (rc) return rc;
    for (long q = 0; q < A->rp[A->nr]; q++) T->rp[A->ci[q] + 1]++;
    for (int j = 0; j < A->nc; j++) T->rp[j + 1] += T->rp[j];
    long *next = malloc((size_t)(A->nc > 0 ? A->nc : 1) * sizeof *next);
    if (!next) return SB_ERR_NOMEM;
    memcpy(next, T->rp, (size_t)A->nc * sizeof *next);
    for (int i = 0; i < A->nr; i++)
        for (long q = A->rp[i]; q < A->rp[i + 1]; q++) {
            long d = next[A->ci[q]]++;
            T->ci[d] = i;
            T->v[d] = A->v[q];
        }
    free(next);
    return SB_OK;
}

/* The strictly lower part of an upper-triangle CSC pattern, by columns: for
 * every stored (j, i) with j < i (column i, row j), the entry (i, j) under
 * column j, with its offset in column i.  Together with the pattern's own
 * columns this is full symmetric access at 8 bytes per off-diagonal entry
 * (a full row index with 8-byte positions took 24 bytes per stored entry:
 * 3 times the Hessian's values; docs/solvers.md, "Memory"). */
static int lower_columns(sb_galerkin *G, const sb_pattern *P)
{
    const int n = P->n;
    G->lrp = calloc((size_t)n + 1, sizeof *G->lrp);
    if (!G->lrp) return SB_ERR_NOMEM;
    for (int i = 0; i < n; i++)
        for (long k = P->colptr[i]; k < P->colptr[i + 1]; k++)
            if (P->rowind[k] != i) G->lrp[P->rowind[k] + 1]++;
    for (int j = 0; j < n; j++) G->lrp[j + 1] += G->lrp[j];
    const long nl = G->lrp[n];
    G->lrow = malloc((size_t)(nl > 0 ? nl : 1) * sizeof *G->lrow);
    G->loff = malloc((size_t)(nl > 0 ? nl : 1) * sizeof *G->loff);
    long *next = malloc((size_t)(n > 0 ? n : 1) * sizeof *next);
    if (!G->lrow || !G->loff || !next) {
        free(next);
        return SB_ERR_NOMEM;
    }
    memcpy(next, G->lrp, (size_t)n * sizeof *next);
    /* columns i in increasing order: each lower column's rows come sorted */
    for (int i = 0; i < n; i++)
        for (long k = P->colptr[i]; k < P->colptr[i + 1]; k++) {
            const int j = P->rowind[k];
            if (j == i) continue;
            const long d = next[j]++;
            G->lrow[d] = i;
            G->loff[d] = (int)(k - P->colptr[i]);   /* < column length <= n */
        }
    free(next);
    return SB_OK;
}

static int product_column(sb_galerkin *G, int K, const double *hv, double *hc);
static int product_column_lean(sb_galerkin *G, int K, const double *hv, double *hc);

static int create(const sb_csr *S, const sb_pattern *fine, const sb_pattern *coarse, const unsigned char *fixed_f,
                  const unsigned char *fixed_c, int lean, sb_galerkin **out);
static int block_prepare(sb_galerkin *G);

int sb_galerkin_create(const sb_csr *S, const sb_pattern *fine, const sb_pattern *coarse,
                       const unsigned char *fixed_f, const unsigned char *fixed_c, sb_galerkin **out)
{
    return create(S, fine, coarse, fixed_f, fixed_c, 0, out);
}

int sb_galerkin_create_lean(const sb_csr *S, const sb_pattern *fine, const sb_pattern *coarse,
                            const unsigned char *fixed_f, const unsigned char *fixed_c, sb_galerkin **out)
{
    return create(S, fine, coarse, fixed_f, fixed_c, 1, out);
}

static int create(const sb_csr *S, const sb_pattern *fine, const sb_pattern *coarse, const unsigned char *fixed_f,
                  const unsigned char *fixed_c, int lean, sb_galerkin **out)
{
    *out = NULL;
    if (S->nr != fine->n || S->nc != coarse->n) return SB_ERR_INPUT;
    sb_galerkin *G = calloc(1, sizeof *G);
    if (!G) return SB_ERR_NOMEM;
    G->nf = fine->n;
    G->nc = coarse->n;
    G->coarse = coarse;
    G->fixed_f = fixed_f;
    G->fixed_c = fixed_c;
    int rc = copy_nonzeros(S, &G->S);
    if (!rc) rc = transpose(&G->S, &G->St);
    G->fine = fine;
    G->lean = lean;
    if (!rc && !lean) rc = lower_columns(G, fine);
    if (!rc && lean) {
        G->cpos = malloc((size_t)(G->nc > 0 ? G->nc : 1) * sizeof *G->cpos);
        if (!G->cpos) rc = SB_ERR_NOMEM;
        else for (int J = 0; J < G->nc; J++) G->cpos[J] = -1;
    }
    if (!rc) {
        G->t = calloc((size_t)G->nf, sizeof *G->t);
        G->u = calloc((size_t)G->nc, sizeof *G->u);
        G->tlist = malloc((size_t)G->nf * sizeof *G->tlist);
        G->ulist = malloc((size_t)G->nc * sizeof *G->ulist);
        G->tmark = calloc((size_t)G->nf, 1);
        G->umark = calloc((size_t)G->nc, 1);
        G->inpat = calloc((size_t)G->nc, 1);
        if (!G->t || !G->u || !G->tlist || !G->ulist || !G->tmark || !G->umark || !G->inpat) rc = SB_ERR_NOMEM;
    }
    /* the product's structure (all dofs free) must fit the coarse pattern */
    for (int K = 0; K < G->nc && !rc; K++) {
        const unsigned char *ff = G->fixed_f, *fc = G->fixed_c;
        G->fixed_f = G->fixed_c = NULL;
        if (lean ? product_column_lean(G, K, NULL, NULL) : product_column(G, K, NULL, NULL)) rc = SB_ERR_UNSUPPORTED;
        G->fixed_f = ff;
        G->fixed_c = fc;
    }
    if (!rc && lean) rc = block_prepare(G);
    if (rc) {
        sb_galerkin_free(G);
        return rc;
    }
    *out = G;
    return SB_OK;
}

/* t = Hf S e_K on the free fine dofs (the list of its rows in G->tlist, the
 * count returned): the stored upper part of each column j of Hf that S e_K
 * touches, and (indexed form) its lower part from the transposed index; the
 * lean form reads the upper part only, with the diagonal halved (B = U -
 * D/2).  hv == NULL: symbolic (every stored entry counts 1). */
static int gather_t(sb_galerkin *G, int K, const double *hv)
{
    const sb_pattern *F = G->fine;
    const unsigned char *ff = G->fixed_f;
    int nt = 0;
    for (long q = G->St.rp[K]; q < G->St.rp[K + 1]; q++) {
        const int j = G->St.ci[q];
        const double s = G->St.v[q];
        if (ff && ff[j]) continue;
        const long end = F->colptr[j + 1] - 1;   /* the diagonal closes each column */
        for (long r = F->colptr[j]; r <= end; r++) {
            const int i = F->rowind[r];
            if (!G->tmark[i]) {
                G->tmark[i] = 1;
                G->tlist[nt++] = i;
            }
            const double w = G->lean && r == end ? 0.5 : 1.0;   /* 1.0 * h is h exactly */
            G->t[i] += hv ? w * hv[r] * s : 1.0;
        }
        if (G->lean) continue;
        for (long r = G->lrp[j]; r < G->lrp[j + 1]; r++) {
            const int i = G->lrow[r];
            if (!G->tmark[i]) {
                G->tmark[i] = 1;
                G->tlist[nt++] = i;
            }
            G->t[i] += hv ? hv[F->colptr[i] + G->loff[r]] * s : 1.0;
        }
    }
    return nt;
}

/* u = S^T t on the free coarse dofs, rows J <= K only when upper (the list in
 * G->ulist, the count returned); t is cleared on the way. */
static int scatter_u(sb_galerkin *G, int K, int nt, const double *hv, int upper)
{
    const unsigned char *ff = G->fixed_f, *fc = G->fixed_c;
    int nu = 0;
    for (int a = 0; a < nt; a++) {
        const int i = G->tlist[a];
        const double ti = G->t[i];
        G->t[i] = 0.0;
        G->tmark[i] = 0;
        if (ff && ff[i]) continue;
        for (long q = G->S.rp[i]; q < G->S.rp[i + 1]; q++) {
            const int J = G->S.ci[q];
            if ((upper && J > K) || (fc && fc[J])) continue;
            if (!G->umark[J]) {
                G->umark[J] = 1;
                G->ulist[nu++] = J;
            }
            G->u[J] += hv ? G->S.v[q] * ti : 1.0;
        }
    }
    return nu;
}

/* Column K of S^T Hf S (rows J <= K) into Hc's pattern column; hv == NULL:
 * symbolic (every stored entry of Hf and S counts as nonzero).  Returns 1
 * when the column has a nonzero outside the pattern. */
static int product_column(sb_galerkin *G, int K, const double *hv, double *hc)
{
    const sb_pattern *C = G->coarse;
    int outside = 0;
    const int nu = scatter_u(G, K, gather_t(G, K, hv), hv, 1);
    for (long k = C->colptr[K]; k < C->colptr[K + 1]; k++) {
        const int J = C->rowind[k];
        if (hc) hc[k] = G->u[J];
        G->inpat[J] = 1;
    }
    for (int a = 0; a < nu; a++) {
        const int J = G->ulist[a];
        if (!G->inpat[J] && G->u[J] != 0.0) outside = 1;
        G->u[J] = 0.0;
        G->umark[J] = 0;
    }
    for (long k = C->colptr[K]; k < C->colptr[K + 1]; k++) G->inpat[C->rowind[k]] = 0;
    return outside;
}

/* Lean column K: u = A(:, K) = S^T B S e_K over every coarse row J (B = U -
 * D/2, read by the stored columns of Hf), added to Hc = A + A^T: u[J] to
 * (J, K) for J < K, to (K, J) for J > K (row K of column J: a binary search
 * in the sorted column), 2 u[K] to the diagonal.  hv == NULL: symbolic.
 * Returns 1 when an entry falls outside Hc's pattern. */
static int product_column_lean(sb_galerkin *G, int K, const double *hv, double *hc)
{
    const sb_pattern *C = G->coarse;
    int outside = 0;
    const int nu = scatter_u(G, K, gather_t(G, K, hv), hv, 0);   /* u = A(:, K), every row J */
    for (long k = C->colptr[K]; k < C->colptr[K + 1]; k++) G->cpos[C->rowind[k]] = (int)(k - C->colptr[K]);
    for (int a = 0; a < nu; a++) {
        const int J = G->ulist[a];
        const double v = G->u[J];
        G->u[J] = 0.0;
        G->umark[J] = 0;
        long at = -1;
        if (J <= K) {
            if (G->cpos[J] >= 0) at = C->colptr[K] + G->cpos[J];
        } else {
            long lo = C->colptr[J], hi = C->colptr[J + 1] - 1;   /* row K in column J (sorted) */
            while (lo <= hi) {
                const long mid = lo + (hi - lo) / 2;
                if (C->rowind[mid] < K) lo = mid + 1;
                else if (C->rowind[mid] > K) hi = mid - 1;
                else { at = mid; break; }
            }
        }
        if (at < 0) {
            if (v != 0.0) outside = 1;
            continue;
        }
        if (hc) hc[at] += J == K ? 2.0 * v : v;
    }
    for (long k = C->colptr[K]; k < C->colptr[K + 1]; k++) G->cpos[C->rowind[k]] = -1;
    return outside;
}

/* ---- the lean product by blocks of coarse columns ---------------------------- */

/* The lists' longest lengths over the blocks (every dof free: the fixed
 * masks only shorten them), the lists allocated to them, and the dense
 * accumulators of the column-by-column symbolic check released.  Blocks
 * of fewer than 4 columns gain nothing (linear_fem's patterns, one dof a
 * node: measured 1.5 x slower by blocks of 1): those keep the column by
 * column product (G->bs = 0). */
static int block_prepare(sb_galerkin *G)
{
    const sb_pattern *F = G->fine;
    const int nf = G->nf, nc = G->nc;
    G->bs = G->coarse->bs >= 4 && G->coarse->bs <= 16 ? G->coarse->bs : 0;
    if (!G->bs) return SB_OK;
    G->jpos = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *G->jpos);
    G->tpos = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *G->tpos);
    G->upos = malloc((size_t)(nc > 0 ? nc : 1) * sizeof *G->upos);
    if (!G->jpos || !G->tpos || !G->upos) return SB_ERR_NOMEM;
    for (int i = 0; i < nf; i++) G->jpos[i] = G->tpos[i] = -1;
    for (int J = 0; J < nc; J++) G->upos[J] = -1;
    int *jl = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *jl);
    if (!jl) return SB_ERR_NOMEM;
    int maxj = 1, maxt = 1, maxu = 1;
    for (int K0 = 0; K0 < nc; K0 += G->bs) {
        const int K1 = K0 + G->bs < nc ? K0 + G->bs : nc;
        int nj = 0, nt = 0, nu = 0;
        for (long q = G->St.rp[K0]; q < G->St.rp[K1]; q++)
            if (G->jpos[G->St.ci[q]] < 0) G->jpos[jl[nj] = G->St.ci[q]] = nj, nj++;
        for (int a = 0; a < nj; a++)
            for (long r = F->colptr[jl[a]]; r < F->colptr[jl[a] + 1]; r++)
                if (G->tpos[F->rowind[r]] < 0) G->tpos[G->tlist[nt] = F->rowind[r]] = nt, nt++;
        for (int a = 0; a < nt; a++)
            for (long q = G->S.rp[G->tlist[a]]; q < G->S.rp[G->tlist[a] + 1]; q++)
                if (G->upos[G->S.ci[q]] < 0) G->upos[G->ulist[nu] = G->S.ci[q]] = nu, nu++;
        for (int a = 0; a < nj; a++) G->jpos[jl[a]] = -1;
        for (int a = 0; a < nt; a++) G->tpos[G->tlist[a]] = -1;
        for (int a = 0; a < nu; a++) G->upos[G->ulist[a]] = -1;
        if (nj > maxj) maxj = nj;
        if (nt > maxt) maxt = nt;
        if (nu > maxu) maxu = nu;
    }
    free(jl);
    const size_t b = (size_t)G->bs;
    G->jlist = malloc((size_t)maxj * sizeof *G->jlist);
    G->sval = malloc((size_t)maxj * b * sizeof *G->sval);
    G->sidx = malloc((size_t)maxj * b);
    G->scount = malloc((size_t)maxj * sizeof *G->scount);
    G->tval = malloc((size_t)maxt * b * sizeof *G->tval);
    G->uval = malloc((size_t)maxu * b * sizeof *G->uval);
    G->ucur = malloc((size_t)maxu * sizeof *G->ucur);
    if (!G->jlist || !G->sval || !G->sidx || !G->scount || !G->tval || !G->uval || !G->ucur) return SB_ERR_NOMEM;
    free(G->t); free(G->u); free(G->tmark); free(G->umark); free(G->inpat);
    G->t = G->u = NULL;
    G->tmark = G->umark = G->inpat = NULL;
    return SB_OK;
}

/* u += a t over the block's columns (a length the compiler knows for the
 * usual block sizes, so that it vectorizes) */
static inline void block_axpy(double *restrict u, double a, const double *restrict t, int B)
{
    switch (B) {
    case 12: for (int b = 0; b < 12; b++) u[b] += a * t[b]; break;
    case 3: for (int b = 0; b < 3; b++) u[b] += a * t[b]; break;
    default: for (int b = 0; b < B; b++) u[b] += a * t[b]; break;
    }
}

/* Columns K0 .. K0+B-1 of Hc = A + A^T (product_column_lean's sums, run
 * for the block at once): the block's fine columns j, each with the
 * columns b that S(j, K0 + b) reaches (fixed coarse columns and fixed fine
 * dofs left out; a node's columns of one displacement component reach the
 * same fine dofs and the others none, so the list holds no zeros); T = B_f
 * S reading each column j of the stored upper triangle once (diagonal
 * halved); A = S^T T reading each row of S once; then A(J, K) added to
 * (J, K) for J <= K (2 A on the diagonal) and to (K, J) for J > K (a
 * cursor per J walks column J's sorted rows from K0 on).  A nonzero can
 * fall outside Hc's pattern only where the all-free structure does, which
 * creation has ruled out; entries of the block's union that a column does
 * not reach are exact zeros. */
static void product_block_lean(sb_galerkin *G, int K0, int B, const double *hv, double *hc)
{
    const sb_pattern *F = G->fine, *C = G->coarse;
    const unsigned char *ff = G->fixed_f, *fc = G->fixed_c;
    const size_t bs = (size_t)B;
    int nj = 0;
    for (int b = 0; b < B; b++) {
        const int K = K0 + b;
        if (fc && fc[K]) continue;
        for (long q = G->St.rp[K]; q < G->St.rp[K + 1]; q++) {
            const int j = G->St.ci[q];
            if (ff && ff[j]) continue;
            int p = G->jpos[j];
            if (p < 0) {
                p = G->jpos[j] = nj;
                G->jlist[nj++] = j;
                G->scount[p] = 0;
            }
            const int m = G->scount[p]++;
            G->sidx[(size_t)p * bs + (size_t)m] = (unsigned char)b;
            G->sval[(size_t)p * bs + (size_t)m] = G->St.v[q];
        }
    }
    int nt = 0;
    for (int a = 0; a < nj; a++) {
        const int j = G->jlist[a];
        G->jpos[j] = -1;
        const double *s = G->sval + (size_t)a * bs;
        const unsigned char *sb = G->sidx + (size_t)a * bs;
        const int m = G->scount[a];
        const long end = F->colptr[j + 1] - 1;   /* the diagonal closes each column */
        for (long r = F->colptr[j]; r <= end; r++) {
            const int i = F->rowind[r];
            int p = G->tpos[i];
            if (p < 0) {
                p = G->tpos[i] = nt;
                G->tlist[nt++] = i;
                memset(G->tval + (size_t)p * bs, 0, bs * sizeof *G->tval);
            }
            const double h = r == end ? 0.5 * hv[r] : hv[r];
            double *t = G->tval + (size_t)p * bs;
            for (int k = 0; k < m; k++) t[sb[k]] += h * s[k];
        }
    }
    int nu = 0;
    for (int a = 0; a < nt; a++) {
        const int i = G->tlist[a];
        G->tpos[i] = -1;
        if (ff && ff[i]) continue;
        const double *t = G->tval + (size_t)a * bs;
        for (long q = G->S.rp[i]; q < G->S.rp[i + 1]; q++) {
            const int J = G->S.ci[q];
            if (fc && fc[J]) continue;
            int p = G->upos[J];
            if (p < 0) {
                p = G->upos[J] = nu;
                G->ulist[nu++] = J;
                memset(G->uval + (size_t)p * bs, 0, bs * sizeof *G->uval);
            }
            block_axpy(G->uval + (size_t)p * bs, G->S.v[q], t, B);
        }
    }
    for (int a = 0; a < nu; a++) {   /* the first row >= K0 of column J > K0 */
        const int J = G->ulist[a];
        G->upos[J] = -1;
        if (J <= K0) continue;
        long lo = C->colptr[J], hi = C->colptr[J + 1];
        while (lo < hi) {
            const long mid = lo + (hi - lo) / 2;
            if (C->rowind[mid] < K0) lo = mid + 1;
            else hi = mid;
        }
        G->ucur[a] = lo;
    }
    for (int b = 0; b < B; b++) {
        const int K = K0 + b;
        if (fc && fc[K]) continue;
        const long c0 = C->colptr[K];
        for (long k = c0; k < C->colptr[K + 1]; k++) G->cpos[C->rowind[k]] = (int)(k - c0);
        for (int a = 0; a < nu; a++) {
            const int J = G->ulist[a];
            const double v = G->uval[(size_t)a * bs + (size_t)b];
            if (J <= K) {
                if (G->cpos[J] >= 0) hc[c0 + G->cpos[J]] += J == K ? 2.0 * v : v;
            } else {
                long c = G->ucur[a];
                const long end = C->colptr[J + 1];
                while (c < end && C->rowind[c] < K) c++;
                G->ucur[a] = c;
                if (c < end && C->rowind[c] == K) hc[c] += v;
            }
        }
        for (long k = c0; k < C->colptr[K + 1]; k++) G->cpos[C->rowind[k]] = -1;
    }
}

int sb_galerkin_product(sb_galerkin *G, const sb_matrix *Hf, sb_matrix *Hc)
{
    int outside = 0;
    sb_matrix_zero(Hc);
    if (G->lean && G->bs) {
        for (int K0 = 0; K0 < G->nc; K0 += G->bs)
            product_block_lean(G, K0, K0 + G->bs < G->nc ? G->bs : G->nc - K0, Hf->val, Hc->val);
        return SB_OK;
    }
    for (int K = 0; K < G->nc; K++)
        if (!(G->fixed_c && G->fixed_c[K]))
            outside |= G->lean ? product_column_lean(G, K, Hf->val, Hc->val) : product_column(G, K, Hf->val, Hc->val);
    return outside ? SB_ERR_UNSUPPORTED : SB_OK;
}
