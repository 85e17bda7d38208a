/* sb_assemble.h — element loops for energy, gradient and Hessian on any
 * number of threads, with a reduction in element order, so that every
 * result is bit-identical for any thread count (issue 30).
 *
 * A method splits its assembly into compute(e), which fills the element's
 * energy terms, gradient and matrix into a slot (independent per element:
 * any thread, any order), and reduce(e), which adds a slot into the global
 * energy, gradient and matrix (called for e = 0, 1, 2, ... in order, one
 * call at a time).  With one thread the loop is compute(e); reduce(e), the
 * arithmetic of a plain serial loop.  With T > 1 threads (OpenMP) the
 * elements go in chunks (consecutive elements whose slots fill ~4 MB)
 * through two buffers: while the threads compute chunk c, one of them
 * reduces chunk c - 1, then joins the computing. */
#ifndef SB_ASSEMBLE_H
#define SB_ASSEMBLE_H

#include "sb_common.h"

typedef struct sb_elem_out {
    double *Ke;        /* max_n x max_n element matrix; NULL when no Hessian is assembled */
    double *ge;        /* max_n element gradient; NULL when neither gradient nor Hessian */
    double *terms;     /* energy terms, summed in this order by the reduction (max_terms) */
    int n_terms;
} sb_elem_out;

/* compute must clear what it uses of Ke and ge (it knows the element's
 * dimension) and set n_terms; it runs concurrently on `thread` (0..T-1),
 * which indexes the caller's per-thread scratch. */
typedef void (*sb_elem_compute)(void *ctx, int thread, int e, sb_elem_out *out);
typedef void (*sb_elem_reduce)(void *ctx, int e, const sb_elem_out *out);
/* the dimension of element e (<= max_n); NULL: every element has max_n */
typedef int (*sb_elem_dim)(void *ctx, int e);

typedef struct sb_assembler sb_assembler;

/* threads >= 1; max_n: largest element dimension; max_terms: most energy
 * terms one element adds.  NULL on bad arguments, out of memory, or
 * threads > 1 in a build without OpenMP (see sb_assemble_have_threads). */
sb_assembler *sb_assembler_new(int threads, int max_n, int max_terms);
void sb_assembler_free(sb_assembler *A);
int sb_assembler_threads(const sb_assembler *A);
/* 1 when this build runs assemblies on more than one thread (OpenMP) */
int sb_assemble_have_threads(void);

void sb_assemble(sb_assembler *A, int n_elems, sb_elem_dim dim, int want_ge, int want_Ke, sb_elem_compute compute,
                 sb_elem_reduce reduce, void *ctx);

#endif
