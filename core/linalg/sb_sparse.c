/* sb_sparse.c — block sparsity pattern from element node lists, scatter maps,
 * symmetric matrices on the pattern (CSC, upper triangle; CHOLMOD stype=+1). */
#include "sb_sparse.h"

#include <math.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

struct sb_pattern_builder {
    int n_nodes, bs;
    int n_elems;
    long *off;          /* n_elems+1 */
    int *nodes;
    size_t cap_e, cap_n;
    int lazy_maps;      /* sb_pattern_builder_lazy_maps */
};

void sb_pattern_builder_lazy_maps(sb_pattern_builder *pb)
{
    if (pb) pb->lazy_maps = 1;
}

sb_pattern_builder *sb_pattern_builder_new(int n_nodes, int bs)
{
    /* the dimension bs * n_nodes is an int (CHOLMOD's int interface) */
    if (n_nodes < 0 || bs < 1 || n_nodes > INT_MAX / bs) return NULL;
    sb_pattern_builder *pb = calloc(1, sizeof *pb);
    if (!pb) return NULL;
    pb->n_nodes = n_nodes;
    pb->bs = bs;
    pb->cap_e = 64;
    pb->cap_n = 1024;
    pb->off = malloc(pb->cap_e * sizeof *pb->off);
    pb->nodes = malloc(pb->cap_n * sizeof *pb->nodes);
    if (!pb->off || !pb->nodes) {
        free(pb->off);
        free(pb->nodes);
        free(pb);
        return NULL;
    }
    pb->off[0] = 0;
    return pb;
}

int sb_pattern_builder_add(sb_pattern_builder *pb, int k, const int *nodes)
{
    if (!pb || k < 0) return SB_ERR_INTERNAL;
    for (int a = 0; a < k; a++)
        if (nodes[a] >= pb->n_nodes) return SB_ERR_INTERNAL;
    if ((size_t)pb->n_elems + 2 > pb->cap_e) {
        size_t nc = pb->cap_e * 2;
        long *o = realloc(pb->off, nc * sizeof *o);
        if (!o) return SB_ERR_NOMEM;
        pb->off = o;
        pb->cap_e = nc;
    }
    size_t need = (size_t)pb->off[pb->n_elems] + (size_t)k;
    if (need > pb->cap_n) {
        size_t nc = pb->cap_n;
        while (nc < need) nc *= 2;
        int *q = realloc(pb->nodes, nc * sizeof *q);
        if (!q) return SB_ERR_NOMEM;
        pb->nodes = q;
        pb->cap_n = nc;
    }
    memcpy(pb->nodes + pb->off[pb->n_elems], nodes, (size_t)k * sizeof *nodes);
    pb->n_elems++;
    pb->off[pb->n_elems] = (long)need;
    return SB_OK;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

static void builder_free(sb_pattern_builder *pb)
{
    if (!pb) return;
    free(pb->off);
    free(pb->nodes);
    free(pb);
}

/* position of row r in column c (binary search), -1 if absent */
static long find_pos(const sb_pattern *p, int r, int c)
{
    long lo = p->colptr[c], hi = p->colptr[c + 1] - 1;
    while (lo <= hi) {
        long mid = (lo + hi) / 2;
        int v = p->rowind[mid];
        if (v == r) return mid;
        if (v < r) lo = mid + 1;
        else hi = mid - 1;
    }
    return -1;
}

long sb_pattern_find(const sb_pattern *p, int i, int j)
{
    if (i > j) { int t = i; i = j; j = t; }
    if (i < 0 || j >= p->n) return -1;
    return find_pos(p, i, j);
}

int sb_pattern_builder_finish(sb_pattern_builder *pb, sb_pattern **out)
{
    *out = NULL;
    if (!pb) return SB_ERR_INTERNAL;
    const int nn = pb->n_nodes, bs = pb->bs, ne = pb->n_elems;
    int rc = SB_ERR_NOMEM;
    sb_pattern *p = calloc(1, sizeof *p);
    long *inc_off = calloc((size_t)nn + 1, sizeof *inc_off);
    int *inc = NULL, *mark = NULL, *nbr = NULL;
    long *ncount = NULL;
    if (!p || !inc_off) goto fail;

    /* node -> element incidence (CSR) */
    for (int e = 0; e < ne; e++)
        for (long q = pb->off[e]; q < pb->off[e + 1]; q++)
            if (pb->nodes[q] >= 0) inc_off[pb->nodes[q] + 1]++;
    for (int i = 0; i < nn; i++) inc_off[i + 1] += inc_off[i];
    inc = malloc((size_t)(inc_off[nn] ? inc_off[nn] : 1) * sizeof *inc);
    long *fill = calloc((size_t)nn + 1, sizeof *fill);
    if (!inc || !fill) { free(fill); goto fail; }
    for (int e = 0; e < ne; e++)
        for (long q = pb->off[e]; q < pb->off[e + 1]; q++) {
            int v = pb->nodes[q];
            if (v >= 0) inc[inc_off[v] + fill[v]++] = e;
        }
    free(fill);

    /* node-level upper pattern: for node column J, neighbours I <= J */
    mark = malloc((size_t)(nn ? nn : 1) * sizeof *mark);
    ncount = calloc((size_t)nn + 1, sizeof *ncount);
    if (!mark || !ncount) goto fail;
    for (int i = 0; i < nn; i++) mark[i] = -1;
    size_t cap = 1024, used = 0;
    nbr = malloc(cap * sizeof *nbr);
    if (!nbr) goto fail;
    for (int J = 0; J < nn; J++) {
        size_t start = used;
        for (long q = inc_off[J]; q < inc_off[J + 1]; q++) {
            int e = inc[q];
            for (long r = pb->off[e]; r < pb->off[e + 1]; r++) {
                int I = pb->nodes[r];
                if (I < 0 || I > J || mark[I] == J) continue;
                mark[I] = J;
                if (used == cap) {
                    cap *= 2;
                    int *t = realloc(nbr, cap * sizeof *t);
                    if (!t) goto fail;
                    nbr = t;
                }
                nbr[used++] = I;
            }
        }
        if (mark[J] != J) {            /* isolated node: keep its diagonal block */
            if (used == cap) {
                cap *= 2;
                int *t = realloc(nbr, cap * sizeof *t);
                if (!t) goto fail;
                nbr = t;
            }
            nbr[used++] = J;
            mark[J] = J;
        }
        qsort(nbr + start, used - start, sizeof *nbr, cmp_int);
        ncount[J + 1] = (long)used;
    }

    /* scalar CSC upper pattern */
    p->n = nn * bs;
    p->bs = bs;
    p->colptr = malloc(((size_t)p->n + 1) * sizeof *p->colptr);
    p->diag = malloc((size_t)(p->n ? p->n : 1) * sizeof *p->diag);
    if (!p->colptr || !p->diag) goto fail;
    long nnz = 0;
    p->colptr[0] = 0;
    for (int J = 0; J < nn; J++) {
        long nI = ncount[J + 1] - ncount[J];          /* includes J itself */
        for (int c = 0; c < bs; c++) {
            nnz += (nI - 1) * bs + (c + 1);
            p->colptr[J * bs + c + 1] = nnz;
        }
    }
    p->nnz = nnz;
    p->rowind = malloc((size_t)(nnz ? nnz : 1) * sizeof *p->rowind);
    if (!p->rowind) goto fail;
    for (int J = 0; J < nn; J++)
        for (int c = 0; c < bs; c++) {
            int col = J * bs + c;
            long pos = p->colptr[col];
            for (long q = ncount[J]; q < ncount[J + 1]; q++) {
                int I = nbr[q];
                int rmax = (I == J) ? c : bs - 1;
                for (int r = 0; r <= rmax; r++) p->rowind[pos++] = I * bs + r;
            }
            p->diag[col] = pos - 1;
        }

    /* element node lists and scatter maps */
    p->n_elems = ne;
    p->elem_node_off = malloc(((size_t)ne + 1) * sizeof *p->elem_node_off);
    p->elem_nodes = malloc((size_t)(pb->off[ne] ? pb->off[ne] : 1) * sizeof *p->elem_nodes);
    if (!p->elem_node_off || !p->elem_nodes) goto fail;
    memcpy(p->elem_node_off, pb->off, ((size_t)ne + 1) * sizeof *pb->off);
    memcpy(p->elem_nodes, pb->nodes, (size_t)pb->off[ne] * sizeof *pb->nodes);
    if (!pb->lazy_maps && (rc = sb_pattern_ensure_maps(p)) != SB_OK) goto fail;
    *out = p;
    p = NULL;
    rc = SB_OK;
fail:
    free(inc_off);
    free(inc);
    free(mark);
    free(ncount);
    free(nbr);
    builder_free(pb);
    sb_pattern_free(p);
    return rc;
}

int sb_pattern_offset_width(const sb_pattern *p)
{
    long maxcol = 0;   /* every offset lies below the longest column's length */
    for (int c = 0; c < p->n; c++)
        if (p->colptr[c + 1] - p->colptr[c] > maxcol) maxcol = p->colptr[c + 1] - p->colptr[c];
    return maxcol <= 256 ? 1 : maxcol <= 65536 ? 2 : maxcol <= INT_MAX ? 4 : 0;
}

int sb_pattern_ensure_maps(sb_pattern *p)
{
    if (p->map) return SB_OK;
    const int ne = p->n_elems, bs = p->bs;
    const long *off = p->elem_node_off;
    const int *nodes = p->elem_nodes;
    const int w = sb_pattern_offset_width(p);
    if (!w) return SB_ERR_INTERNAL;
    long *moff = malloc(((size_t)ne + 1) * sizeof *moff);
    if (!moff) return SB_ERR_NOMEM;
    long nmap = 0;
    moff[0] = 0;
    for (int e = 0; e < ne; e++) {
        const int *nd = nodes + off[e];
        int k = (int)(off[e + 1] - off[e]);
        for (int a = 0; a < k; a++)
            for (int b = 0; b < k; b++)
                if (nd[a] >= 0 && nd[b] >= 0 && nd[a] <= nd[b]) nmap++;
        moff[e + 1] = nmap;
    }
    unsigned char *map = malloc((size_t)(nmap ? nmap : 1) * (size_t)w);
    if (!map) { free(moff); return SB_ERR_NOMEM; }
    long m = 0;
    for (int e = 0; e < ne; e++) {
        const int *nd = nodes + off[e];
        int k = (int)(off[e + 1] - off[e]);
        for (int a = 0; a < k; a++)
            for (int b = 0; b < k; b++) {
                if (nd[a] < 0 || nd[b] < 0 || nd[a] > nd[b]) continue;
                /* one offset per block: in every column of node nd[b] the
                 * rows of node nd[a] start at the same place (its rank among
                 * the column's neighbour nodes times bs) */
                const int c0 = nd[b] * bs;
                const long o = find_pos(p, nd[a] * bs, c0) - p->colptr[c0];
                /* checked in every column of the block: its row there
                 * (a column's rows are distinct, so one look suffices) */
                for (int j = 0; j < bs; j++)
                    if (o < 0 || o >= p->colptr[c0 + j + 1] - p->colptr[c0 + j] ||
                        p->rowind[p->colptr[c0 + j] + o] != nd[a] * bs) {
                        free(moff);
                        free(map);
                        return SB_ERR_INTERNAL;
                    }
                sb_offset_set(map, w, m++, o);
            }
    }
    p->elem_map_off = moff;
    p->map = map;
    p->map_width = w;
    return SB_OK;
}

void sb_pattern_free(sb_pattern *p)
{
    if (!p) return;
    free(p->colptr);
    free(p->rowind);
    free(p->diag);
    free(p->elem_node_off);
    free(p->elem_nodes);
    free(p->elem_map_off);
    free(p->map);
    free(p);
}

const int *sb_pattern_elem_nodes(const sb_pattern *p, int e, int *k)
{
    *k = (int)(p->elem_node_off[e + 1] - p->elem_node_off[e]);
    return p->elem_nodes + p->elem_node_off[e];
}

int sb_matrix_init(sb_matrix *A, const sb_pattern *pat)
{
    A->pat = pat;
    A->val = calloc((size_t)(pat->nnz ? pat->nnz : 1), sizeof *A->val);
    A->owns_val = 1;
    return A->val ? SB_OK : SB_ERR_NOMEM;
}

void sb_matrix_free(sb_matrix *A)
{
    if (A->owns_val) free(A->val);
    A->val = NULL;
    A->owns_val = 0;
}

void sb_matrix_zero(sb_matrix *A) { memset(A->val, 0, (size_t)A->pat->nnz * sizeof *A->val); }

static inline __attribute__((always_inline)) void add_element_w(sb_matrix *A, int e, const double *Ke, int w)
{
    const sb_pattern *p = A->pat;
    const int bs = p->bs;
    const int *nd = p->elem_nodes + p->elem_node_off[e];
    const int k = (int)(p->elem_node_off[e + 1] - p->elem_node_off[e]);
    const int m = bs * k;
    const void *map = p->map;
    long mi = p->elem_map_off[e];
    const long *cp = p->colptr;
    double *val = A->val;
    for (int a = 0; a < k; a++) {
        if (nd[a] < 0) continue;
        for (int b = 0; b < k; b++) {
            if (nd[b] < 0 || nd[a] > nd[b]) continue;
            const double *blk = Ke + (size_t)(bs * a) * m + bs * b;
            const long *col = cp + (size_t)nd[b] * bs;
            const long o = sb_offset_get(map, w, mi++);
            if (nd[a] < nd[b]) {
                for (int j = 0; j < bs; j++) {
                    double *dst = val + col[j] + o;
                    for (int i = 0; i < bs; i++) dst[i] += blk[(size_t)i * m + j];
                }
            } else {
                for (int j = 0; j < bs; j++) {
                    double *dst = val + col[j] + o;
                    for (int i = 0; i <= j; i++) dst[i] += blk[(size_t)i * m + j];
                }
            }
        }
    }
}

/* bs = 1 (linear_fem with edge directors): every block is one entry, the
 * diagonal ones included, so the scatter needs no block loops and no
 * separate diagonal case */
static inline __attribute__((always_inline)) void add_element_scalar(sb_matrix *A, int e, const double *Ke, int w)
{
    const sb_pattern *p = A->pat;
    const int *nd = p->elem_nodes + p->elem_node_off[e];
    const int k = (int)(p->elem_node_off[e + 1] - p->elem_node_off[e]);
    const void *map = p->map;
    long mi = p->elem_map_off[e];
    const long *cp = p->colptr;
    double *val = A->val;
    for (int a = 0; a < k; a++) {
        const int na = nd[a];
        if (na < 0) continue;
        const double *row = Ke + (size_t)a * k;
        for (int b = 0; b < k; b++) {
            const int nb = nd[b];
            if (nb < 0 || na > nb) continue;
            val[cp[nb] + sb_offset_get(map, w, mi++)] += row[b];
        }
    }
}

void sb_matrix_add_element(sb_matrix *A, int e, const double *Ke)
{
    if (A->pat->bs == 1) {
        if (A->pat->map_width == 1) add_element_scalar(A, e, Ke, 1);
        else if (A->pat->map_width == 2) add_element_scalar(A, e, Ke, 2);
        else add_element_scalar(A, e, Ke, 4);
        return;
    }
    switch (A->pat->map_width) {   /* one copy of the loop per width */
    case 1: add_element_w(A, e, Ke, 1); break;
    case 2: add_element_w(A, e, Ke, 2); break;
    default: add_element_w(A, e, Ke, 4); break;
    }
}

void sb_matrix_get_element(const sb_matrix *A, int e, double *Ke)
{
    const sb_pattern *p = A->pat;
    const int bs = p->bs;
    const int *nd = p->elem_nodes + p->elem_node_off[e];
    const int k = (int)(p->elem_node_off[e + 1] - p->elem_node_off[e]);
    const int m = bs * k;
    long mi = p->elem_map_off[e];
    const long *cp = p->colptr;
    const double *val = A->val;
    memset(Ke, 0, (size_t)m * m * sizeof *Ke);
    for (int a = 0; a < k; a++) {
        if (nd[a] < 0) continue;
        for (int b = 0; b < k; b++) {
            if (nd[b] < 0 || nd[a] > nd[b]) continue;
            const long *col = cp + (size_t)nd[b] * bs;
            const long o = sb_offset_get(p->map, p->map_width, mi++);
            for (int j = 0; j < bs; j++) {
                const double *src = val + col[j] + o;
                for (int i = 0; i < bs; i++) {
                    /* the diagonal block stores its upper triangle only */
                    const double v = nd[a] < nd[b] || i <= j ? src[i] : val[col[i] + o + j];
                    Ke[(size_t)(bs * a + i) * m + bs * b + j] = v;
                    Ke[(size_t)(bs * b + j) * m + bs * a + i] = v;
                }
            }
        }
    }
}

int sb_matrix_add(sb_matrix *A, int i, int j, double v)
{
    if (i > j) { int t = i; i = j; j = t; }
    if (i < 0 || j >= A->pat->n) return SB_ERR_INTERNAL;
    long pos = find_pos(A->pat, i, j);
    if (pos < 0) return SB_ERR_INTERNAL;
    A->val[pos] += v;
    return SB_OK;
}

void sb_matrix_symv(const sb_matrix *A, const double *x, double *y)
{
    const sb_pattern *p = A->pat;
    memset(y, 0, (size_t)p->n * sizeof *y);
    for (int c = 0; c < p->n; c++) {
        double xc = x[c], acc = 0.0;
        long end = p->colptr[c + 1] - 1;          /* last entry is the diagonal */
        for (long q = p->colptr[c]; q < end; q++) {
            int r = p->rowind[q];
            double v = A->val[q];
            y[r] += v * xc;
            acc += v * x[r];
        }
        y[c] += acc + A->val[end] * xc;
    }
}

void sb_matrix_axpy(sb_matrix *A, double alpha, const sb_matrix *B)
{
    sb_axpy((int)A->pat->nnz, alpha, B->val, A->val);
}

double sb_matrix_norm_max(const sb_matrix *A)
{
    double m = 0.0;
    for (long q = 0; q < A->pat->nnz; q++) {
        double v = fabs(A->val[q]);
        if (v > m) m = v;
    }
    return m;
}

double sb_dot(int n, const double *a, const double *b)
{
    double s = 0.0;
    for (int i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

double sb_norm2(int n, const double *a) { return sqrt(sb_dot(n, a, a)); }

void sb_axpy(int n, double alpha, const double *x, double *y)
{
    for (int i = 0; i < n; i++) y[i] += alpha * x[i];
}

void sb_copy(int n, const double *x, double *y) { memmove(y, x, (size_t)n * sizeof *x); }

void sb_scal(int n, double alpha, double *x)
{
    for (int i = 0; i < n; i++) x[i] *= alpha;
}

int sb_all_finite(int n, const double *x)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i])) return 0;
    return 1;
}
