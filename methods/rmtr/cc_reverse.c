/* cc_reverse.c — projection of iterates from level l+1 to level l by
 * reverse subdivision (RMTR paper §5.3.2, Appendices B and C), and the
 * restriction-based alternative D^{-1} S^T.
 *
 * Q is assembled once, as a sparse matrix, from local rules:
 *  1. interior coarse vertices of valence n != 3 whose fine one-ring survived
 *     the removal of the outer ghost layer:
 *       v^l = c1 v^{l+1} + c2 sum e^{l+1} + c3 sum f^{l+1}            (5.19)
 *       c1 = n/(n-3), c2 = -4/(n(n-3)), c3 = 1/(n(n-3))               (5.21)
 *  2. ghost points (App. B) and valence-3 vertices (App. C): through any
 *     interior edge (v, w) with w already reconstructed,
 *       v^l = 4 e^{l+1} - w^l - f_I^{l+1} - f_{I+1}^{l+1}             (B.2)
 *  3. corner ghost points: through a face F whose other vertices are known,
 *       v^l = N f^{l+1} - sum_{i=1}^{N-1} v_{I+i}^l                   (B.4)
 * Steps 2 and 3 repeat until every coarse vertex is reconstructed; rows of
 * already reconstructed coarse points are substituted, so Q acts on fine
 * points only.  Every rule inverts an exact subdivision relation, hence
 * Q S = I (tested).  App. C assumes one extraordinary vertex per face; a
 * cage where the rules cannot reach a vertex is reported as an error. */
#include "cc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct rctx {
    const cc_mesh *c;
    const int *vmap;
    cc_row *rows;
    unsigned char *known;
} rctx;

static int fine_v(const rctx *r, int v) { return r->vmap[v]; }
static int fine_e(const rctx *r, int d) { return r->vmap[r->c->nv + d]; }
static int fine_f(const rctx *r, int q) { return r->vmap[r->c->nv + r->c->ne + q]; }

static int rule_519(rctx *r, int v)
{
    const cc_mesh *c = r->c;
    int n = c->val[v];
    if (c->bnd[v] || n == 3 || fine_v(r, v) < 0) return 0;
    for (int p = c->veo[v]; p < c->veo[v + 1]; p++)
        if (fine_e(r, c->ve[p]) < 0) return 0;
    for (int p = c->vfo[v]; p < c->vfo[v + 1]; p++)
        if (fine_f(r, c->vf[p]) < 0) return 0;
    double c1 = (double)n / (n - 3), c2 = -4.0 / (n * (n - 3.0)), c3 = 1.0 / (n * (n - 3.0));  /* (5.21) */
    cc_row *row = &r->rows[v];
    int st = cc_row_add(row, fine_v(r, v), c1);
    for (int p = c->veo[v]; p < c->veo[v + 1]; p++) st |= cc_row_add(row, fine_e(r, c->ve[p]), c2);
    for (int p = c->vfo[v]; p < c->vfo[v + 1]; p++) st |= cc_row_add(row, fine_f(r, c->vf[p]), c3);
    if (st) return -1;
    r->known[v] = 1;
    return 1;
}

static int rule_b2(rctx *r, int v)
{
    const cc_mesh *c = r->c;
    for (int p = c->veo[v]; p < c->veo[v + 1]; p++) {
        int d = c->ve[p], fa = c->ef[2 * d], fb = c->ef[2 * d + 1];
        int w = c->ev[2 * d] == v ? c->ev[2 * d + 1] : c->ev[2 * d];
        if (fb < 0 || !r->known[w] || fine_e(r, d) < 0 || fine_f(r, fa) < 0 || fine_f(r, fb) < 0) continue;
        cc_row *row = &r->rows[v];
        int st = cc_row_add(row, fine_e(r, d), 4.0);                      /* (B.2) */
        st |= cc_row_axpy(row, -1.0, &r->rows[w]);
        st |= cc_row_add(row, fine_f(r, fa), -1.0);
        st |= cc_row_add(row, fine_f(r, fb), -1.0);
        if (st) return -1;
        r->known[v] = 1;
        return 1;
    }
    return 0;
}

static int rule_b4(rctx *r, int v)
{
    const cc_mesh *c = r->c;
    for (int p = c->vfo[v]; p < c->vfo[v + 1]; p++) {
        int q = c->vf[p], ok = fine_f(r, q) >= 0;
        for (int k = 0; k < 4 && ok; k++) {
            int u = c->fv[4 * q + k];
            ok = u == v || r->known[u];
        }
        if (!ok) continue;
        cc_row *row = &r->rows[v];
        int st = cc_row_add(row, fine_f(r, q), 4.0);                      /* (B.4), N = 4 */
        for (int k = 0; k < 4; k++) {
            int u = c->fv[4 * q + k];
            if (u != v) st |= cc_row_axpy(row, -1.0, &r->rows[u]);
        }
        if (st) return -1;
        r->known[v] = 1;
        return 1;
    }
    return 0;
}

int cc_reverse_build(const cc_mesh *c, const cc_mesh *f, const int *vmap, cc_csr *Q, cc_err *e)
{
    memset(Q, 0, sizeof *Q);
    rctx r = { c, vmap, calloc((size_t)c->nv, sizeof(cc_row)), calloc((size_t)c->nv, 1) };
    int st = (!r.rows || !r.known) ? SB_ERR_NOMEM : SB_OK;
    for (int v = 0; v < c->nv && !st; v++)
        if (rule_519(&r, v) < 0) st = SB_ERR_NOMEM;
    for (int progress = 1; progress && !st;) {
        progress = 0;
        for (int v = 0; v < c->nv && !st; v++) {
            if (r.known[v]) continue;
            int k = rule_b2(&r, v);
            if (k == 0) k = rule_b4(&r, v);
            if (k < 0) st = SB_ERR_NOMEM;
            progress |= k > 0;
        }
    }
    int missing = -1;
    for (int v = 0; v < c->nv && !st && missing < 0; v++)
        if (!r.known[v]) missing = v;
    if (missing >= 0)
        st = cc_fail(e, SB_ERR_UNSUPPORTED, "reverse subdivision cannot reconstruct coarse vertex %d "
                     "(valence %d%s); App. C needs at most one extraordinary vertex per face",
                     missing, c->val[missing], c->bnd[missing] ? ", boundary" : "");
    long nnz = 0;
    for (int v = 0; v < c->nv && !st; v++) nnz += r.rows[v].n;
    if (!st) st = cc_csr_init(Q, c->nv, f->nv, nnz);
    for (int v = 0; v < c->nv && !st; v++) {
        cc_row *row = &r.rows[v];
        int m = 0;
        for (int a = 0; a < row->n; a++)          /* drop exact cancellations */
            if (fabs(row->v[a]) > 1e-14) {
                row->c[m] = row->c[a];
                row->v[m++] = row->v[a];
            }
        st = cc_csr_row(Q, v, m, row->c, row->v);
    }
    for (int v = 0; r.rows && v < c->nv; v++) cc_row_free(&r.rows[v]);
    free(r.rows);
    free(r.known);
    if (st) {
        cc_csr_free(Q);
        if (st == SB_ERR_NOMEM) cc_fail(e, st, "out of memory assembling reverse subdivision");
    }
    return st;
}

/* P = D^{-1} S^T with D = diag(S^T 1): every coarse point becomes the
 * weighted mean of the fine points it influences.  Keeps constants
 * (P S 1 = 1) but not general iterates (P S != I); the "restrict" choice of
 * the method's "projection" parameter. */
int cc_restrict_scaled_build(const cc_csr *S, cc_csr *P, cc_err *e)
{
    memset(P, 0, sizeof *P);
    int nc = S->nc, nf = S->nr;
    long nnz = S->rp[nf];
    int *cnt = calloc((size_t)nc + 1, sizeof *cnt), *fill = calloc((size_t)nc, sizeof *fill);
    int *ci = malloc((size_t)(nnz ? nnz : 1) * sizeof *ci);
    double *val = malloc((size_t)(nnz ? nnz : 1) * sizeof *val);
    int st = (!cnt || !fill || !ci || !val) ? SB_ERR_NOMEM : SB_OK;
    if (!st) {
        for (long p = 0; p < nnz; p++) cnt[S->ci[p] + 1]++;
        for (int j = 0; j < nc; j++) cnt[j + 1] += cnt[j];
        for (int i = 0; i < nf; i++)
            for (int p = S->rp[i]; p < S->rp[i + 1]; p++) {
                int j = S->ci[p];
                ci[cnt[j] + fill[j]] = i;
                val[cnt[j] + fill[j]++] = S->v[p];
            }
        st = cc_csr_init(P, nc, nf, nnz);
    }
    for (int j = 0; j < nc && !st; j++) {
        double sum = 0;
        for (int p = cnt[j]; p < cnt[j + 1]; p++) sum += val[p];
        if (!(sum > 0)) {
            st = cc_fail(e, SB_ERR_INTERNAL, "coarse vertex %d influences no fine vertex", j);
            break;
        }
        for (int p = cnt[j]; p < cnt[j + 1]; p++) val[p] /= sum;
        st = cc_csr_row(P, j, cnt[j + 1] - cnt[j], ci + cnt[j], val + cnt[j]);
    }
    free(cnt); free(fill); free(ci); free(val);
    if (st) {
        cc_csr_free(P);
        if (st == SB_ERR_NOMEM) cc_fail(e, st, "out of memory assembling the scaled restriction");
    }
    return st;
}
