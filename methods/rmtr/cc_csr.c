/* cc_csr.c — small row-compressed matrices for the subdivision operators
 * (S, Q, scaled restriction) and a sparse row accumulator used at set-up. */
#include "cc.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cc_fail(cc_err *e, int status, const char *fmt, ...)
{
    if (e) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(e->msg, sizeof e->msg, fmt, ap);
        va_end(ap);
    }
    return status;
}

int cc_csr_init(cc_csr *A, int nr, int nc, long cap)
{
    memset(A, 0, sizeof *A);
    if (nr < 0 || nc < 0) return SB_ERR_INPUT;
    if (cap < 16) cap = 16;
    A->nr = nr;
    A->nc = nc;
    A->rp = calloc((size_t)nr + 1, sizeof *A->rp);
    A->ci = malloc((size_t)cap * sizeof *A->ci);
    A->v = malloc((size_t)cap * sizeof *A->v);
    A->cap = cap;
    if (!A->rp || !A->ci || !A->v) {
        cc_csr_free(A);
        return SB_ERR_NOMEM;
    }
    return SB_OK;
}

void cc_csr_free(cc_csr *A)
{
    free(A->rp);
    free(A->ci);
    free(A->v);
    memset(A, 0, sizeof *A);
}

int cc_csr_row(cc_csr *A, int row, int n, const int *cols, const double *vals)
{
    if (row < 0 || row >= A->nr) return SB_ERR_INTERNAL;
    long start = A->rp[row];
    if (start + n > A->cap) {
        long cap = 2 * A->cap + n;
        int *ci = realloc(A->ci, (size_t)cap * sizeof *ci);
        if (!ci) return SB_ERR_NOMEM;
        A->ci = ci;
        double *v = realloc(A->v, (size_t)cap * sizeof *v);
        if (!v) return SB_ERR_NOMEM;
        A->v = v;
        A->cap = cap;
    }
    int m = 0;
    for (int a = 0; a < n; a++) {
        if (cols[a] < 0 || cols[a] >= A->nc) return SB_ERR_INTERNAL;
        /* insertion into the sorted row, summing duplicates */
        int p = m;
        while (p > 0 && A->ci[start + p - 1] > cols[a]) p--;
        if (p > 0 && A->ci[start + p - 1] == cols[a]) {
            A->v[start + p - 1] += vals[a];
            continue;
        }
        memmove(A->ci + start + p + 1, A->ci + start + p, (size_t)(m - p) * sizeof *A->ci);
        memmove(A->v + start + p + 1, A->v + start + p, (size_t)(m - p) * sizeof *A->v);
        A->ci[start + p] = cols[a];
        A->v[start + p] = vals[a];
        m++;
    }
    A->rp[row + 1] = (int)(start + m);
    return SB_OK;
}

void cc_csr_apply(const cc_csr *A, int dim, const double *x, double *y)
{
    for (int i = 0; i < A->nr; i++) {
        double acc[3] = { 0, 0, 0 };
        for (int p = A->rp[i]; p < A->rp[i + 1]; p++)
            for (int c = 0; c < dim; c++) acc[c] += A->v[p] * x[dim * A->ci[p] + c];
        for (int c = 0; c < dim; c++) y[dim * i + c] = acc[c];
    }
}

void cc_csr_apply_t(const cc_csr *A, int dim, const double *x, double *y)
{
    memset(y, 0, (size_t)A->nc * (size_t)dim * sizeof *y);
    for (int i = 0; i < A->nr; i++)
        for (int p = A->rp[i]; p < A->rp[i + 1]; p++)
            for (int c = 0; c < dim; c++) y[dim * A->ci[p] + c] += A->v[p] * x[dim * i + c];
}

int cc_csr_select_rows(const cc_csr *A, int n, const int *rows, cc_csr *B)
{
    long nnz = 0;
    for (int r = 0; r < n; r++) nnz += A->rp[rows[r] + 1] - A->rp[rows[r]];
    int st = cc_csr_init(B, n, A->nc, nnz);
    if (st) return st;
    for (int r = 0; r < n; r++) {
        int i = rows[r];
        st = cc_csr_row(B, r, A->rp[i + 1] - A->rp[i], A->ci + A->rp[i], A->v + A->rp[i]);
        if (st) return st;
    }
    return SB_OK;
}

double cc_csr_get(const cc_csr *A, int i, int j)
{
    for (int p = A->rp[i]; p < A->rp[i + 1]; p++)
        if (A->ci[p] == j) return A->v[p];
    return 0.0;
}

int cc_row_add(cc_row *r, int col, double val)
{
    for (int a = 0; a < r->n; a++)
        if (r->c[a] == col) {
            r->v[a] += val;
            return SB_OK;
        }
    if (r->n == r->cap) {
        int cap = r->cap ? 2 * r->cap : 16;
        int *c = realloc(r->c, (size_t)cap * sizeof *c);
        if (!c) return SB_ERR_NOMEM;
        r->c = c;
        double *v = realloc(r->v, (size_t)cap * sizeof *v);
        if (!v) return SB_ERR_NOMEM;
        r->v = v;
        r->cap = cap;
    }
    r->c[r->n] = col;
    r->v[r->n++] = val;
    return SB_OK;
}

int cc_row_axpy(cc_row *r, double a, const cc_row *x)
{
    for (int i = 0; i < x->n; i++) {
        int st = cc_row_add(r, x->c[i], a * x->v[i]);
        if (st) return st;
    }
    return SB_OK;
}

void cc_row_free(cc_row *r)
{
    free(r->c);
    free(r->v);
    memset(r, 0, sizeof *r);
}
