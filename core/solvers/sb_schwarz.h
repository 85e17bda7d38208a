/* sb_schwarz.h — additive Schwarz preconditioner on element patches: the
 * dofs of every element of a level's sparsity pattern form one overlapping
 * block, M^{-1} = sum_e R_e^T A_e^{-1} R_e with A_e = R_e H R_e^T read from the
 * assembled Hessian (Toselli & Widlund, Domain Decomposition Methods, §1.3).
 * Used as the preconditioner of the Steihaug–Toint CG smoother. */
#ifndef SB_SCHWARZ_H
#define SB_SCHWARZ_H
#include "sb_sparse.h"

typedef struct sb_schwarz {
    int n, ne, maxm;
    long *doff;          /* ne+1: offsets into dof and into the packed factors */
    long *foff;          /* ne+1: offsets of the packed lower Cholesky factors */
    int *dof;            /* element dof lists */
    double *fac;         /* packed lower-triangular factors (or inverse diagonals) */
    unsigned char *diag_only;  /* 1: A_e was not positive definite, Jacobi on the patch */
    double *Ke, *t;      /* maxm x maxm and maxm scratch */
} sb_schwarz;

/* Factor the element blocks of H; allocates on the first call (the pattern is fixed). */
int  sb_schwarz_setup(sb_schwarz *S, const sb_matrix *H);
/* z = M^{-1} r */
void sb_schwarz_apply(const sb_schwarz *S, const double *r, double *z);
void sb_schwarz_free(sb_schwarz *S);
#endif
