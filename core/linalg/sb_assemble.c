/* sb_assemble.c — element loops with a deterministic reduction (see
 * sb_assemble.h).  Bit-identity for any thread count holds by
 * construction: compute(e) depends on e only (each thread has its own
 * scratch), and reduce(e) runs in element order on one thread at a time,
 * so every global sum sees the same operands in the same order. */
#include "sb_assemble.h"

#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

struct sb_assembler {
    int threads, max_n, max_terms;
    size_t budget;      /* doubles per buffer */
    double *buf;        /* 2 buffers */
    size_t *off;        /* per element: its slot's offset in its chunk's buffer */
    int *chunk;         /* chunk boundaries: elements [chunk[c], chunk[c+1]) */
    int *nt;            /* per element: energy terms written by compute */
    int cap;            /* elements off/chunk/nt hold */
};

/* a buffer of ~4 MB: chunks of ~200 shell elements, so that the threads
 * meet at a barrier a few times per assembly, not per element */
#define SB_ASSEMBLE_BUDGET (512 * 1024)

int sb_assemble_have_threads(void)
{
#ifdef _OPENMP
    return 1;
#else
    return 0;
#endif
}

static size_t slot_size(const sb_assembler *A, int n, int want_Ke)
{
    return (want_Ke ? (size_t)n * n : 0) + (size_t)n + (size_t)A->max_terms;
}

sb_assembler *sb_assembler_new(int threads, int max_n, int max_terms)
{
    if (threads < 1 || threads > 256 || max_n < 1 || max_terms < 1) return NULL;
    if (threads > 1 && !sb_assemble_have_threads()) return NULL;
    sb_assembler *A = calloc(1, sizeof *A);
    if (!A) return NULL;
    A->threads = threads;
    A->max_n = max_n;
    A->max_terms = max_terms;
    if (threads == 1) {
        A->budget = slot_size(A, max_n, 1);
    } else {
        A->budget = SB_ASSEMBLE_BUDGET;
        if (A->budget < (size_t)threads * slot_size(A, max_n, 1)) A->budget = (size_t)threads * slot_size(A, max_n, 1);
    }
    A->buf = malloc(2 * A->budget * sizeof *A->buf);
    if (!A->buf) {
        free(A);
        return NULL;
    }
    return A;
}

void sb_assembler_free(sb_assembler *A)
{
    if (!A) return;
    free(A->buf);
    free(A->off);
    free(A->chunk);
    free(A->nt);
    free(A);
}

int sb_assembler_threads(const sb_assembler *A) { return A ? A->threads : 0; }

static sb_elem_out slot_out(const sb_assembler *A, double *s, int n, int want_ge, int want_Ke)
{
    sb_elem_out o;
    o.terms = s;
    o.n_terms = 0;
    o.ge = want_ge || want_Ke ? s + A->max_terms : NULL;
    o.Ke = want_Ke ? s + A->max_terms + n : NULL;
    return o;
}

void sb_assemble(sb_assembler *A, int n_elems, sb_elem_dim dim, int want_ge, int want_Ke, sb_elem_compute compute,
                 sb_elem_reduce reduce, void *ctx)
{
    if (!A || n_elems < 1) return;
    if (A->threads == 1 || n_elems < 2) {
        for (int e = 0; e < n_elems; e++) {
            sb_elem_out o = slot_out(A, A->buf, A->max_n, want_ge, want_Ke);
            compute(ctx, 0, e, &o);
            reduce(ctx, e, &o);
        }
        return;
    }
#ifdef _OPENMP
    if (n_elems > A->cap) {   /* first assembly of this size: the tables, once */
        size_t *off = realloc(A->off, (size_t)n_elems * sizeof *off);
        if (off) A->off = off;
        int *ch = realloc(A->chunk, ((size_t)n_elems + 1) * sizeof *ch);
        if (ch) A->chunk = ch;
        int *nt = realloc(A->nt, (size_t)n_elems * sizeof *nt);
        if (nt) A->nt = nt;
        if (!off || !ch || !nt) {   /* out of memory: the serial loop needs no tables */
            for (int e = 0; e < n_elems; e++) {
                sb_elem_out o = slot_out(A, A->buf, A->max_n, want_ge, want_Ke);
                compute(ctx, 0, e, &o);
                reduce(ctx, e, &o);
            }
            return;
        }
        A->cap = n_elems;
    }
    /* chunks: consecutive elements whose slots fill one buffer */
    int nchunks = 0;
    size_t used = 0;
    A->chunk[0] = 0;
    for (int e = 0; e < n_elems; e++) {
        const int n = dim ? dim(ctx, e) : A->max_n;
        const size_t sz = (slot_size(A, n, want_Ke) + 7) / 8 * 8;   /* 64-byte multiples */
        if (used + sz > A->budget) {
            A->chunk[++nchunks] = e;
            used = 0;
        }
        A->off[e] = used;
        used += sz;
    }
    A->chunk[++nchunks] = n_elems;
#pragma omp parallel num_threads(A->threads)
    {
        for (int c = 0; c <= nchunks; c++) {
            /* one thread reduces the previous chunk, in element order ... */
#pragma omp single nowait
            if (c > 0) {
                double *b = A->buf + (size_t)((c - 1) & 1) * A->budget;
                for (int e = A->chunk[c - 1]; e < A->chunk[c]; e++) {
                    const int n = dim ? dim(ctx, e) : A->max_n;
                    sb_elem_out o = slot_out(A, b + A->off[e], n, want_ge, want_Ke);
                    o.n_terms = A->nt[e];
                    reduce(ctx, e, &o);
                }
            }
            /* ... while the others (and then it) compute this one */
            if (c < nchunks) {
                double *b = A->buf + (size_t)(c & 1) * A->budget;
                const int e0 = A->chunk[c], e1 = A->chunk[c + 1];
#pragma omp for schedule(dynamic, 4) nowait
                for (int e = e0; e < e1; e++) {
                    const int n = dim ? dim(ctx, e) : A->max_n;
                    sb_elem_out o = slot_out(A, b + A->off[e], n, want_ge, want_Ke);
                    compute(ctx, omp_get_thread_num(), e, &o);
                    A->nt[e] = o.n_terms;
                }
            }
#pragma omp barrier
        }
    }
#else
    (void)dim;
#endif
}
