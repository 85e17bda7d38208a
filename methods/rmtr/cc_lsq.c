/* cc_lsq.c — least-squares projection (RMTR paper (5.17)–(5.18)):
 *   q^l = (S^T S)^{-1} S^T q^{l+1},
 * the Moore–Penrose pseudo-inverse of S_l^{l+1}.  S^T S is formed and
 * factored once with CHOLMOD (own cholmod_common, so the object does not
 * depend on a run context); each application is one sparse product and one
 * solve with preallocated workspace (cholmod_solve2).  Kept for comparison
 * with reverse subdivision (paper Table 8). */
#include "cc.h"

#include <cholmod.h>
#include <stdlib.h>
#include <string.h>

struct cc_lsq {
    cholmod_common cm;
    cholmod_factor *L;
    const cc_csr *S;        /* borrowed: must outlive the projection */
    cholmod_dense *B, *X, *Y, *E;
    double *tmp;            /* 3 nc */
};

void cc_lsq_free(cc_lsq *P)
{
    if (!P) return;
    cholmod_free_factor(&P->L, &P->cm);
    cholmod_free_dense(&P->B, &P->cm);
    cholmod_free_dense(&P->X, &P->cm);
    cholmod_free_dense(&P->Y, &P->cm);
    cholmod_free_dense(&P->E, &P->cm);
    cholmod_finish(&P->cm);
    free(P->tmp);
    free(P);
}

int cc_lsq_create(const cc_csr *S, cc_lsq **out, cc_err *e)
{
    *out = NULL;
    cc_lsq *P = calloc(1, sizeof *P);
    if (!P) return cc_fail(e, SB_ERR_NOMEM, "out of memory (least-squares projection)");
    cholmod_start(&P->cm);
    P->cm.print = 0;
    P->S = S;
    int nc = S->nc, nf = S->nr;
    long nnz = S->rp[nf];
    /* S^T as a CHOLMOD matrix: the CSR of S is the CSC of S^T */
    cholmod_sparse *At = cholmod_allocate_sparse((size_t)nc, (size_t)nf, (size_t)nnz, 1, 1, 0, CHOLMOD_REAL, &P->cm);
    cholmod_sparse *AAt = NULL, *N = NULL;
    int st = At ? SB_OK : SB_ERR_NOMEM;
    if (!st) {
        memcpy(At->p, S->rp, (size_t)(nf + 1) * sizeof(int));
        memcpy(At->i, S->ci, (size_t)nnz * sizeof(int));
        memcpy(At->x, S->v, (size_t)nnz * sizeof(double));
        AAt = cholmod_aat(At, NULL, 0, 1, &P->cm);                      /* S^T S */
        N = AAt ? cholmod_copy(AAt, 1, 1, &P->cm) : NULL;               /* upper, symmetric */
        if (!N) st = SB_ERR_NOMEM;
    }
    if (!st) {
        P->L = cholmod_analyze(N, &P->cm);
        if (!P->L || !cholmod_factorize(N, P->L, &P->cm) || P->cm.status != CHOLMOD_OK)
            st = cc_fail(e, SB_ERR_INTERNAL, "S^T S is not positive definite (CHOLMOD status %d)", P->cm.status);
    } else {
        cc_fail(e, st, "out of memory forming S^T S");
    }
    cholmod_free_sparse(&At, &P->cm);
    cholmod_free_sparse(&AAt, &P->cm);
    cholmod_free_sparse(&N, &P->cm);
    if (!st) {
        P->B = cholmod_allocate_dense((size_t)nc, 3, (size_t)nc, CHOLMOD_REAL, &P->cm);
        P->tmp = malloc((size_t)3 * nc * sizeof *P->tmp);
        if (!P->B || !P->tmp) st = cc_fail(e, SB_ERR_NOMEM, "out of memory (least-squares projection)");
    }
    if (st) {
        cc_lsq_free(P);
        return st;
    }
    *out = P;
    return SB_OK;
}

int cc_lsq_apply(cc_lsq *P, int dim, const double *qf, double *qc)
{
    int nc = P->S->nc;
    if (dim < 1 || dim > 3) return SB_ERR_INPUT;
    cc_csr_apply_t(P->S, dim, qf, P->tmp);                                /* S^T q^{l+1} */
    P->B->ncol = (size_t)dim;
    double *b = P->B->x;
    for (int i = 0; i < nc; i++)
        for (int c = 0; c < dim; c++) b[(size_t)c * nc + i] = P->tmp[dim * i + c];
    if (!cholmod_solve2(CHOLMOD_A, P->L, P->B, NULL, &P->X, NULL, &P->Y, &P->E, &P->cm))
        return SB_ERR_INTERNAL;
    const double *x = P->X->x;
    for (int i = 0; i < nc; i++)
        for (int c = 0; c < dim; c++) qc[dim * i + c] = x[(size_t)c * nc + i];
    return SB_OK;
}
