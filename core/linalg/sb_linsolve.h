/* sb_linsolve.h — sparse Cholesky through CHOLMOD: analyze once per pattern,
 * numeric factorization (optionally shifted, A + beta I) per iteration, solves
 * into preallocated workspace.  Counting (events, flops, nnz(L)) is done here. */
#ifndef SB_LINSOLVE_H
#define SB_LINSOLVE_H

#include "sb_sparse.h"
#include "sb_stats.h"

struct sb_context;
typedef struct sb_linsolve sb_linsolve;

/* run.supernodes: CHOLMOD's relaxed supernode amalgamation (issue 42) */
enum { SB_SUPERNODES_CHOLMOD = 0, SB_SUPERNODES_WIDE = 1 };
/* Stored entries of a supernodal factor per nonzero of L, as measured
 * (chol_factor_entries / chol_nnz_l of plate and trampoline runs at
 * 1e4-1e6 dofs): what the memory estimate counts for each choice. */
double sb_linsolve_fill(int supernodes);

/* Creates the solver for the matrix H (its values are used in place, not
 * copied: assemble into H, then factor) and performs the symbolic analysis. */
int  sb_linsolve_create(struct sb_context *ctx, int level, sb_matrix *H, sb_linsolve **out);
void sb_linsolve_free(sb_linsolve *ls);
/* Factor (A + shift I).  Returns SB_OK, SB_NOT_POSDEF (recorded, not an
 * error: the factor is unusable), or a negative error. */
int  sb_linsolve_factor(sb_linsolve *ls, double shift);
/* x = (A + shift I)^{-1} b with the last successful factor.  x may equal b. */
int  sb_linsolve_solve(sb_linsolve *ls, const double *b, double *x);
/* figures of the last analysis/factorization */
double sb_linsolve_flops(const sb_linsolve *ls);
double sb_linsolve_nnz_l(const sb_linsolve *ls);

/* The supernodes of the analysis (issue 42: what bounds the factorization's
 * rate), binned by their column count k: bin b holds 2^b <= k < 2^(b+1)
 * (the last bin everything wider).  Per bin: supernodes, columns, the
 * dense flops of their factorization (potrf k^3/3 + trsm (m-k) k^2 + the
 * update (m-k)^2 k they send to their ancestors, m = the supernode's rows
 * with its diagonal block) and the flop-weighted mean k and m.  Returns
 * SB_OK, or SB_ERR_INPUT when the factor is not supernodal. */
#define SB_SN_BINS 12
typedef struct sb_supernode_bins {
    long supernodes[SB_SN_BINS], columns[SB_SN_BINS];
    double flops[SB_SN_BINS];
    double mean_k[SB_SN_BINS], mean_m[SB_SN_BINS];   /* flop-weighted */
    long n_super;
    double flops_total;
} sb_supernode_bins;
int sb_linsolve_supernodes(const sb_linsolve *ls, sb_supernode_bins *b);

#endif
