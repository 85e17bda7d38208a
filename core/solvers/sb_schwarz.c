/* sb_schwarz.c — additive Schwarz on element patches (see sb_schwarz.h). */
#include "sb_schwarz.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sb_schwarz_free(sb_schwarz *S)
{
    free(S->doff); free(S->foff); free(S->dof); free(S->fac); free(S->diag_only);
    free(S->Ke); free(S->t);
    memset(S, 0, sizeof *S);
}

static int schwarz_alloc(sb_schwarz *S, const sb_pattern *pat)
{
    const int bs = pat->bs;
    S->n = pat->n;
    S->ne = pat->n_elems;
    S->doff = malloc(((size_t)S->ne + 1) * sizeof(long));
    S->foff = malloc(((size_t)S->ne + 1) * sizeof(long));
    S->diag_only = calloc((size_t)S->ne + 1, 1);
    if (!S->doff || !S->foff || !S->diag_only) return SB_ERR_NOMEM;
    S->doff[0] = S->foff[0] = 0;
    S->maxm = 0;
    for (int e = 0; e < S->ne; e++) {
        const int m = bs * (int)(pat->elem_node_off[e + 1] - pat->elem_node_off[e]);
        if (m > S->maxm) S->maxm = m;
        S->doff[e + 1] = S->doff[e] + m;
        S->foff[e + 1] = S->foff[e] + (long)m * (m + 1) / 2;
    }
    S->dof = malloc((size_t)S->doff[S->ne] * sizeof(int));
    S->fac = malloc((size_t)S->foff[S->ne] * sizeof(double));
    S->Ke = malloc((size_t)S->maxm * S->maxm * sizeof(double));
    S->t = malloc((size_t)S->maxm * sizeof(double));
    if (!S->dof || !S->fac || !S->Ke || !S->t) return SB_ERR_NOMEM;
    for (int e = 0; e < S->ne; e++) {
        int k;
        const int *nd = sb_pattern_elem_nodes(pat, e, &k);
        int *d = S->dof + S->doff[e];
        /* a missing node (-1) keeps its rows: they are zero in Ke, and the
         * factorization below gives them a unit pivot */
        for (int a = 0; a < k; a++)
            for (int c = 0; c < bs; c++) d[bs * a + c] = nd[a] < 0 ? -1 : bs * nd[a] + c;
    }
    return SB_OK;
}

/* packed lower Cholesky of the m x m row-major A; 0 when not positive definite */
static int chol_packed(int m, const double *A, double *L)
{
    for (int i = 0; i < m; i++) {
        double *Li = L + (long)i * (i + 1) / 2;
        for (int j = 0; j <= i; j++) {
            const double *Lj = L + (long)j * (j + 1) / 2;
            double v = A[(size_t)i * m + j];
            for (int k = 0; k < j; k++) v -= Li[k] * Lj[k];
            if (i == j) {
                if (!(v > 0.0)) return 0;
                Li[i] = sqrt(v);
            } else Li[j] = v / Lj[j];
        }
    }
    return 1;
}

int sb_schwarz_setup(sb_schwarz *S, const sb_matrix *H)
{
    if (!S->dof) {
        int rc = schwarz_alloc(S, H->pat);
        if (rc) return rc;
    }
    for (int e = 0; e < S->ne; e++) {
        const int m = (int)(S->doff[e + 1] - S->doff[e]);
        const int *d = S->dof + S->doff[e];
        double *L = S->fac + S->foff[e];
        sb_matrix_get_element(H, e, S->Ke);
        for (int i = 0; i < m; i++)
            if (d[i] < 0) S->Ke[(size_t)i * m + i] = 1.0;
        S->diag_only[e] = !chol_packed(m, S->Ke, L);
        if (S->diag_only[e])   /* an indefinite patch: |diagonal| scaling on it */
            for (int i = 0; i < m; i++) {
                double a = fabs(S->Ke[(size_t)i * m + i]);
                L[i] = a > 0 ? 1.0 / a : 0.0;
            }
    }
    return SB_OK;
}

void sb_schwarz_apply(const sb_schwarz *S, const double *r, double *z)
{
    double *t = S->t;
    memset(z, 0, (size_t)S->n * sizeof *z);
    for (int e = 0; e < S->ne; e++) {
        const int m = (int)(S->doff[e + 1] - S->doff[e]);
        const int *d = S->dof + S->doff[e];
        const double *L = S->fac + S->foff[e];
        if (S->diag_only[e]) {
            for (int i = 0; i < m; i++)
                if (d[i] >= 0) z[d[i]] += L[i] * r[d[i]];
            continue;
        }
        for (int i = 0; i < m; i++) {                 /* L y = R_e r */
            const double *Li = L + (long)i * (i + 1) / 2;
            double v = d[i] >= 0 ? r[d[i]] : 0.0;
            for (int k = 0; k < i; k++) v -= Li[k] * t[k];
            t[i] = v / Li[i];
        }
        for (int i = m - 1; i >= 0; i--) {            /* L^T x = y */
            double v = t[i];
            for (int k = i + 1; k < m; k++) v -= L[(long)k * (k + 1) / 2 + i] * t[k];
            t[i] = v / L[(long)i * (i + 1) / 2 + i];
        }
        for (int i = 0; i < m; i++)
            if (d[i] >= 0) z[d[i]] += t[i];
    }
}
