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
    int threads, max_n, max_terms, chunk;
    size_t slot;        /* doubles per slot */
    double *buf;        /* 2 buffers x chunk slots */
};

/* elements per chunk and thread: enough to balance the dynamic schedule,
 * few enough that the two buffers of a 120 x 120 element stay ~4 MB */
#define SB_CHUNK_PER_THREAD 4

int sb_assemble_have_threads(void)
{
#ifdef _OPENMP
    return 1;
#else
    return 0;
#endif
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
    A->chunk = threads == 1 ? 1 : SB_CHUNK_PER_THREAD * threads;
    A->slot = (size_t)max_n * max_n + (size_t)max_n + (size_t)max_terms;
    A->buf = malloc(2 * (size_t)A->chunk * A->slot * sizeof *A->buf);
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
    free(A);
}

int sb_assembler_threads(const sb_assembler *A) { return A ? A->threads : 0; }

static sb_elem_out slot_out(const sb_assembler *A, int buffer, int i, int want_ge, int want_Ke)
{
    double *s = A->buf + ((size_t)buffer * A->chunk + (size_t)i) * A->slot;
    sb_elem_out o;
    o.terms = s;
    o.n_terms = 0;
    o.ge = want_ge || want_Ke ? s + A->max_terms : NULL;
    o.Ke = want_Ke ? s + A->max_terms + A->max_n : NULL;
    return o;
}

void sb_assemble(sb_assembler *A, int n_elems, int want_ge, int want_Ke, sb_elem_compute compute,
                 sb_elem_reduce reduce, void *ctx)
{
    if (!A || n_elems < 1) return;
    if (A->threads == 1 || n_elems < 2) {
        for (int e = 0; e < n_elems; e++) {
            sb_elem_out o = slot_out(A, 0, 0, want_ge, want_Ke);
            compute(ctx, 0, e, &o);
            reduce(ctx, e, &o);
        }
        return;
    }
#ifdef _OPENMP
    const int chunk = A->chunk, nchunks = (n_elems + chunk - 1) / chunk;
    /* the outcome of compute(e) lives in its slot's terms/ge/Ke plus
     * n_terms, kept beside the buffers */
    int nt[2][256 * SB_CHUNK_PER_THREAD];
#pragma omp parallel num_threads(A->threads)
    {
        for (int c = 0; c <= nchunks; c++) {
            /* one thread reduces the previous chunk, in element order ... */
#pragma omp single nowait
            if (c > 0) {
                const int b = (c - 1) & 1, e0 = (c - 1) * chunk;
                const int e1 = e0 + chunk < n_elems ? e0 + chunk : n_elems;
                for (int e = e0; e < e1; e++) {
                    sb_elem_out o = slot_out(A, b, e - e0, want_ge, want_Ke);
                    o.n_terms = nt[b][e - e0];
                    reduce(ctx, e, &o);
                }
            }
            /* ... while the others (and then it) compute this one */
            if (c < nchunks) {
                const int b = c & 1, e0 = c * chunk;
                const int e1 = e0 + chunk < n_elems ? e0 + chunk : n_elems;
#pragma omp for schedule(dynamic, 1) nowait
                for (int e = e0; e < e1; e++) {
                    sb_elem_out o = slot_out(A, b, e - e0, want_ge, want_Ke);
                    compute(ctx, omp_get_thread_num(), e, &o);
                    nt[b][e - e0] = o.n_terms;
                }
            }
#pragma omp barrier
        }
    }
#endif
}
