/* sb_galerkin.h — the Galerkin coarse Hessian H_c = R H_f I = I^T H_f I of a
 * nested hierarchy (second-order consistent coarse models; Gratton,
 * Sartenaer & Toint 2008, §2: "Galerkin models").
 *
 * I is the dof-level prolongation (fine rows, coarse columns) as a row-
 * compressed matrix, built once per level pair: by the method
 * (sb_method_type.prolong_matrix) or, when a method has none, by probing its
 * prolong() with unit vectors at set-up.  The symbolic work (I^T, the
 * transposed index of the fine pattern's strictly lower part) is done once
 * in sb_galerkin_create(); sb_galerkin_product() allocates nothing. */
#ifndef SB_GALERKIN_H
#define SB_GALERKIN_H

#include "sb_sparse.h"

typedef struct sb_csr {
    int nr, nc;
    long *rp;       /* nr+1 */
    int *ci;        /* column indices */
    double *v;
} sb_csr;

int  sb_csr_alloc(sb_csr *A, int nr, int nc, long nnz);   /* rp zeroed */
void sb_csr_free(sb_csr *A);

typedef struct sb_galerkin sb_galerkin;

/* S: prolongation, S->nr = fine->n, S->nc = coarse->n (copied).  Rows of
 * fixed fine dofs and columns of fixed coarse dofs are left out of every
 * product: the product is the Hessian on the free dofs only.  fixed_f /
 * fixed_c (may be NULL) are kept as pointers and read at each product, so
 * they may change between products.  SB_ERR_UNSUPPORTED when the
 * structure of S^T Hf S (fine pattern, all dofs free) does not fit the
 * coarse pattern. */
int  sb_galerkin_create(const sb_csr *S, const sb_pattern *fine, const sb_pattern *coarse,
                        const unsigned char *fixed_f, const unsigned char *fixed_c, sb_galerkin **out);
/* The same product in the lean form (issue 38, pcg-mg): with the fine
 * Hessian's stored upper triangle U, B = U - D/2 (D its diagonal) gives
 * Hf = B + B^T and Hc = A + A^T, A = S^T B S, which reads Hf by stored
 * columns only: no index of the fine pattern's lower part (8 bytes per
 * off-diagonal entry, about a fifth of pcg-mg's peak at 1e6 dofs).  Equal
 * to sb_galerkin_create's product up to round-off (the sums run in another
 * order), so the rmtr solver's Galerkin models keep the indexed form that
 * its committed counts were made with.  Its numeric product runs by blocks
 * of the coarse pattern's bs columns (one node's dofs), each fine column
 * and each row of S read once per block (blocks of 4 or more columns;
 * bhem's 12: its products 1.6 x faster, docs/solvers.md). */
int  sb_galerkin_create_lean(const sb_csr *S, const sb_pattern *fine, const sb_pattern *coarse,
                             const unsigned char *fixed_f, const unsigned char *fixed_c, sb_galerkin **out);
/* Hc = S^T Hf S on Hc's pattern (upper triangle); entries of fixed coarse
 * rows / columns are zero.  SB_ERR_UNSUPPORTED when a nonzero of the product
 * falls outside the coarse pattern (Hc then holds the in-pattern part; the
 * lean form has ruled that out at creation). */
int  sb_galerkin_product(sb_galerkin *G, const sb_matrix *Hf, sb_matrix *Hc);
void sb_galerkin_free(sb_galerkin *G);

#endif
