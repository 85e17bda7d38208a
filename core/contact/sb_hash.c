/* sb_hash.c — uniform-grid spatial hash (Teschner et al. 2003; sb_hash.h). */
#include "sb_hash.h"
#include "sb_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Teschner et al. 2003 §4.1: hash(i, j, k) = (i p1 xor j p2 xor k p3) mod n */
static int bucket(const sb_hash *h, long i, long j, long k)
{
    const unsigned long v = ((unsigned long)i * 73856093UL) ^ ((unsigned long)j * 19349663UL) ^
                            ((unsigned long)k * 83492791UL);
    return (int)(v % (unsigned long)h->size);
}

static void cell_range(const sb_hash *h, const double lo[3], const double hi[3], long c0[3], long c1[3])
{
    for (int a = 0; a < 3; a++) {
        c0[a] = (long)floor(lo[a] / h->cell);
        c1[a] = (long)floor(hi[a] / h->cell);
        if (c1[a] - c0[a] > 64) c1[a] = c0[a] + 64;   /* a huge box: cut (never for sample primitives) */
    }
}

int sb_hash_build(sb_hash *h, int n, const double *lo, const double *hi, double cell)
{
    memset(h, 0, sizeof *h);
    h->cell = cell;
    h->n = n;
    long total = 0;
    for (int i = 0; i < n; i++) {
        long c0[3], c1[3];
        cell_range(h, lo + 3 * i, hi + 3 * i, c0, c1);
        total += (c1[0] - c0[0] + 1) * (c1[1] - c0[1] + 1) * (c1[2] - c0[2] + 1);
    }
    h->size = (int)(2 * total + 1);
    h->start = calloc((size_t)h->size + 1, sizeof *h->start);
    h->id = malloc((size_t)(total ? total : 1) * sizeof *h->id);
    h->mark = malloc((size_t)(n ? n : 1) * sizeof *h->mark);
    if (!h->start || !h->id || !h->mark) { sb_hash_free(h); return SB_ERR_NOMEM; }
    for (int i = 0; i < n; i++) h->mark[i] = -1;
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < n; i++) {
            long c0[3], c1[3];
            cell_range(h, lo + 3 * i, hi + 3 * i, c0, c1);
            for (long a = c0[0]; a <= c1[0]; a++)
                for (long b = c0[1]; b <= c1[1]; b++)
                    for (long c = c0[2]; c <= c1[2]; c++) {
                        const int k = bucket(h, a, b, c);
                        if (pass == 0) h->start[k + 1]++;
                        else h->id[h->start[k]++] = i;
                    }
        }
        if (pass == 0)
            for (int k = 0; k < h->size; k++) h->start[k + 1] += h->start[k];
    }
    /* the second pass advanced start[k] to the end of bucket k: shift back */
    for (int k = h->size; k > 0; k--) h->start[k] = h->start[k - 1];
    h->start[0] = 0;
    return SB_OK;
}

void sb_hash_free(sb_hash *h)
{
    free(h->start);
    free(h->id);
    free(h->mark);
    memset(h, 0, sizeof *h);
}

int sb_hash_query(sb_hash *h, const double lo[3], const double hi[3], int (*fn)(void *data, int i), void *data)
{
    long c0[3], c1[3];
    cell_range(h, lo, hi, c0, c1);
    const int stamp = h->stamp++;
    for (long a = c0[0]; a <= c1[0]; a++)
        for (long b = c0[1]; b <= c1[1]; b++)
            for (long c = c0[2]; c <= c1[2]; c++) {
                const int k = bucket(h, a, b, c);
                for (int q = h->start[k]; q < h->start[k + 1]; q++) {
                    const int i = h->id[q];
                    if (h->mark[i] == stamp) continue;
                    h->mark[i] = stamp;
                    int r = fn(data, i);
                    if (r) return r;
                }
            }
    return 0;
}
