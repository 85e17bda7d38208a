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

/* DOFs come in blocks of bs per node (3 for positions, 12 for a Hermite node
 * x, x_,1, x_,2, x_,12): dof = bs*node + c.  An element is a list of k nodes;
 * its dense element matrix is (bs k) x (bs k), row-major, local dof index
 * bs*a + c — for bs = 3 exactly the shell kernel's 3*I + c. */
typedef struct sb_pattern {
    int n;              /* matrix dimension = bs * n_nodes */
    int bs;             /* dofs per node */
    long nnz;           /* stored entries (upper triangle) */
    long *colptr;       /* n+1 */
    int *rowind;        /* nnz */
    long *diag;         /* n: position of (i,i) */
    /* element scatter maps.  For element e with nodes nd[0..k), the ordered
     * local node pairs (a,b) in loop order a-major, b-minor that satisfy
     * nd[a] >= 0, nd[b] >= 0 and nd[a] <= nd[b] each own one entry o: the
     * block's first row in column c = bs*nd[b] + j is at position
     * colptr[c] + o of the value array, the same o for every j (node
     * nd[a]'s rank among the neighbour nodes of nd[b], times bs).  o is
     * below the longest column's length, so it is stored in map_width = 1,
     * 2 or 4 bytes, the fewest that hold every column (1 for every method
     * here: linear_fem's scalar pattern with edge directors, 231 blocks a
     * triangle, took 80 MB at 261,251 dofs in 4 bytes; bs positions of 8
     * bytes each once took a third of its memory, docs/solvers.md
     * "Memory").  nd[a] < nd[b]: full bs x bs block;
     * nd[a] == nd[b] (the diagonal block, also for a repeated node —
     * periodic identification — where both orders are kept): upper triangle
     * i <= j. */
    int n_elems;
    long *elem_node_off;/* n_elems+1, into elem_nodes */
    int *elem_nodes;    /* node lists (-1 = no node) */
    long *elem_map_off; /* n_elems+1, into map (NULL until sb_pattern_ensure_maps for a lazy pattern) */
    void *map;          /* block row offsets within their columns (sb_offset_get) */
    int map_width;      /* bytes an entry of map: 1, 2 or 4 */
} sb_pattern;

sb_pattern_builder *sb_pattern_builder_new(int n_nodes, int bs);
/* Add the next element (elements numbered in order of addition); nodes < 0 are skipped. */
int sb_pattern_builder_add(sb_pattern_builder *pb, int k, const int *nodes);
/* Finish: builds the pattern and the scatter maps; frees the builder (also on error). */
int sb_pattern_builder_finish(sb_pattern_builder *pb, sb_pattern **out);
/* finish without the element scatter maps: sb_pattern_ensure_maps builds
 * them before the first sb_matrix_add_element / get_element on the pattern
 * (a coarse level whose matrices are Galerkin products never needs them:
 * 924 bytes a linear_fem triangle) */
void sb_pattern_builder_lazy_maps(sb_pattern_builder *pb);
int  sb_pattern_ensure_maps(sb_pattern *p);     /* SB_OK when built (or already there) */
void sb_pattern_free(sb_pattern *p);
/* position of entry (i, j) (any order) in the value array, -1 if not in the pattern */
long sb_pattern_find(const sb_pattern *p, int i, int j);
/* Offsets within the pattern's columns held in w = 1, 2 or 4 bytes an
 * entry (the scatter maps, a mass matrix by its nonzeros): the fewest bytes
 * that hold every offset, i.e. the longest column's length (0 when it
 * exceeds 2^31 - 1), and entry i of such an array. */
int sb_pattern_offset_width(const sb_pattern *p);
static inline __attribute__((always_inline)) long sb_offset_get(const void *a, int w, long i)
{
    return w == 1 ? ((const unsigned char *)a)[i] : w == 2 ? ((const unsigned short *)a)[i] : ((const int *)a)[i];
}
static inline void sb_offset_set(void *a, int w, long i, long o)
{
    if (w == 1) ((unsigned char *)a)[i] = (unsigned char)o;
    else if (w == 2) ((unsigned short *)a)[i] = (unsigned short)o;
    else ((int *)a)[i] = (int)o;
}
/* nodes of element e: *k and pointer */
const int *sb_pattern_elem_nodes(const sb_pattern *p, int e, int *k);

typedef struct sb_matrix {
    const sb_pattern *pat;
    double *val;        /* nnz (may be owned by a CHOLMOD sparse object) */
    int owns_val;
} sb_matrix;

int  sb_matrix_init(sb_matrix *A, const sb_pattern *pat);   /* allocates val */
void sb_matrix_free(sb_matrix *A);
void sb_matrix_zero(sb_matrix *A);
/* Add the dense (bs k) x (bs k) row-major symmetric element matrix of element e. */
void sb_matrix_add_element(sb_matrix *A, int e, const double *Ke);
/* The dense (bs k) x (bs k) row-major submatrix of A on the dofs of element e
 * (the inverse of sb_matrix_add_element's scatter, read from the assembled A). */
void sb_matrix_get_element(const sb_matrix *A, int e, double *Ke);
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
