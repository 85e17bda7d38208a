/* sb_sparse.h — symmetric sparsity pattern built once from element DOF lists,
 * with a precomputed scatter map per element, and matrices on that pattern.
 *
 * Storage: compressed sparse column, upper triangle (row <= col), sorted row
 * indices: exactly CHOLMOD's stype = +1 layout, so a matrix's value array is
 * handed to CHOLMOD without copying. */
#ifndef SB_SPARSE_H
#define SB_SPARSE_H

#include "sb_common.h"

typedef struct sb_pattern_builder sb_pattern_builder;

typedef struct sb_pattern {
    int n;              /* matrix dimension */
    long nnz;           /* stored entries (upper triangle) */
    long *colptr;       /* n+1 */
    int *rowind;        /* nnz */
    long *diag;         /* n: position of (i,i) */
    /* element scatter maps: element e has m_e = elem_ndof[e] dofs, and for
     * every ordered local pair (a,b) with dof[a] <= dof[b] (both >= 0) an
     * entry (a*m_e + b, position).  Repeated dofs inside an element (periodic
     * identification) are handled: both (a,b) and (b,a) then land on the
     * diagonal. */
    int n_elems;
    int *elem_ndof;     /* n_elems */
    long *elem_off;     /* n_elems+1, into map_local/map_pos */
    int *map_local;     /* a*m+b */
    long *map_pos;      /* position in values */
    long *elem_dof_off; /* n_elems+1, into elem_dofs */
    int *elem_dofs;     /* dof lists (-1 = no dof) */
} sb_pattern;

sb_pattern_builder *sb_pattern_builder_new(int n);
/* Add element e (elements must be added in order 0,1,2,...); dofs < 0 are skipped. */
int sb_pattern_builder_add(sb_pattern_builder *pb, int ndof, const int *dofs);
/* Finish: builds the pattern; frees the builder. */
int sb_pattern_builder_finish(sb_pattern_builder *pb, sb_pattern **out);
void sb_pattern_free(sb_pattern *p);

typedef struct sb_matrix {
    const sb_pattern *pat;
    double *val;        /* nnz (may be owned by a CHOLMOD sparse object) */
    int owns_val;
} sb_matrix;

int  sb_matrix_init(sb_matrix *A, const sb_pattern *pat);   /* allocates val */
void sb_matrix_free(sb_matrix *A);
void sb_matrix_zero(sb_matrix *A);
/* Add a dense m x m (row-major, symmetric) element matrix of element e. */
void sb_matrix_add_element(sb_matrix *A, int e, const double *Ke);
/* Add a value at global (i,j) (any order); returns SB_ERR_INTERNAL if not in pattern. */
int  sb_matrix_add(sb_matrix *A, int i, int j, double v);
/* y = A x (A symmetric, upper stored). */
void sb_matrix_symv(const sb_matrix *A, const double *x, double *y);
/* A += alpha B (same pattern). */
void sb_matrix_axpy(sb_matrix *A, double alpha, const sb_matrix *B);
/* max |A_ij| (for norms) and Frobenius norm. */
double sb_matrix_norm_max(const sb_matrix *A);

/* small dense vector helpers */
double sb_dot(int n, const double *a, const double *b);
double sb_norm2(int n, const double *a);
void   sb_axpy(int n, double alpha, const double *x, double *y);   /* y += alpha x */
void   sb_copy(int n, const double *x, double *y);
void   sb_scal(int n, double alpha, double *x);
int    sb_all_finite(int n, const double *x);

#endif
