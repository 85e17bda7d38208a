/* sb_hash.c — the broad phase of the impulse pipeline (one spatial hash per
 * object) and of barrier self-contact (Teschner, Heidelberger, Müller, Pomeranets & Gross 2003,
 * "Optimized spatial hashing for collision detection of deformable
 * objects"): primitives (triangles or edges) are entered into every grid
 * cell their bounding box covers, cells hashed by
 *   hash(i, j, k) = (i p1 xor j p2 xor k p3) mod n,  p1 = 73856093,
 *   p2 = 19349663, p3 = 83492791                       (Teschner §4.1)
 * with the cell size near the average edge length (Teschner §5: the best
 * size) and a table of about twice as many entries as there are cell
 * entries.  A box query visits the cells it covers and returns the
 * primitives whose own boxes overlap it (bucket collisions are removed by
 * that test, duplicates by a stamp per primitive).  Primitives that cover
 * more than 64 cells (a large obstacle triangle) are kept in a list that
 * every query scans. */
#include "sb_hash.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { BIG_CELLS = 64, QUERY_CELLS = 4096 };

static unsigned cell_hash(long i, long j, long k, int size)
{
    unsigned long h = ((unsigned long)i * 73856093ul) ^ ((unsigned long)j * 19349663ul) ^ ((unsigned long)k * 83492791ul);
    return (unsigned)(h % (unsigned long)size);
}

static void cell_range(const double *box, double cell, long lo[3], long hi[3], double *count)
{
    *count = 1;
    for (int c = 0; c < 3; c++) {
        lo[c] = (long)floor(box[c] / cell);
        hi[c] = (long)floor(box[3 + c] / cell);
        *count *= (double)(hi[c] - lo[c] + 1);
    }
}

void sb_hash_free(sb_hash *H)
{
    free(H->start); free(H->item); free(H->big); free(H->ids);
    memset(H, 0, sizeof *H);
}

/* *p holds at least need ints (reallocated, its contents dropped, when shorter) */
static int reserve(int **p, int *cap, long need)
{
    if (need < 1) need = 1;
    if (*cap >= need) return 0;
    free(*p);
    *p = malloc((size_t)need * sizeof **p);
    *cap = *p ? (int)need : 0;
    return *p ? 0 : -1;
}

int sb_hash_build(sb_hash *H, int n, const int *ids, const double *boxes, double cell)
{
    H->cell = cell;
    H->n = n;
    H->boxes = boxes;
    H->nbig = 0;
    if (reserve(&H->ids, &H->cap_ids, n)) return -1;
    if (n) memcpy(H->ids, ids, (size_t)n * sizeof *ids);
    long entries = 0;
    for (int k = 0; k < n; k++) {
        long lo[3], hi[3];
        double cnt;
        cell_range(boxes + 6 * ids[k], cell, lo, hi, &cnt);
        if (cnt > BIG_CELLS) H->nbig++;
        else entries += (long)cnt;
    }
    H->size = (int)(2 * entries + 1);
    if (reserve(&H->start, &H->cap_start, (long)H->size + 1) || reserve(&H->item, &H->cap_item, entries) ||
        reserve(&H->big, &H->cap_big, H->nbig))
        return -1;
    memset(H->start, 0, ((size_t)H->size + 1) * sizeof *H->start);
    /* counting sort of the (cell hash, primitive) entries */
    H->nbig = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (int k = 0; k < n; k++) {
            long lo[3], hi[3];
            double cnt;
            cell_range(boxes + 6 * ids[k], cell, lo, hi, &cnt);
            if (cnt > BIG_CELLS) {
                if (pass == 0) H->big[H->nbig++] = ids[k];
                continue;
            }
            for (long i = lo[0]; i <= hi[0]; i++)
                for (long j = lo[1]; j <= hi[1]; j++)
                    for (long l = lo[2]; l <= hi[2]; l++) {
                        unsigned b = cell_hash(i, j, l, H->size);
                        if (pass == 0) H->start[b + 1]++;
                        else H->item[H->start[b]++] = ids[k];
                    }
        }
        if (pass == 0)
            for (int b = 0; b < H->size; b++) H->start[b + 1] += H->start[b];
    }
    for (int b = H->size; b > 0; b--) H->start[b] = H->start[b - 1];   /* undo the fill's shift */
    H->start[0] = 0;
    return 0;
}

static int overlap(const double *a, const double *b)
{
    for (int c = 0; c < 3; c++)
        if (a[c] > b[3 + c] || b[c] > a[3 + c]) return 0;
    return 1;
}

static int push(sb_idlist *L, int id)
{
    if (L->n == L->cap) {
        int cap = L->cap ? 2 * L->cap : 64;
        int *v = realloc(L->v, (size_t)cap * sizeof *v);
        if (!v) return -1;
        L->v = v;
        L->cap = cap;
    }
    L->v[L->n++] = id;
    return 0;
}

int sb_hash_query(const sb_hash *H, const double *box, int *stamp, int mark, sb_idlist *out)
{
    out->n = 0;
    long lo[3], hi[3];
    double cnt;
    cell_range(box, H->cell, lo, hi, &cnt);
    for (int k = 0; k < H->nbig; k++) {
        int id = H->big[k];
        if (stamp[id] != mark && overlap(box, H->boxes + 6 * id)) {
            stamp[id] = mark;
            if (push(out, id)) return -1;
        }
    }
    if (cnt > QUERY_CELLS) {   /* a huge query box: every primitive */
        for (int k = 0; k < H->n; k++) {
            int id = H->ids[k];
            if (stamp[id] != mark && overlap(box, H->boxes + 6 * id)) {
                stamp[id] = mark;
                if (push(out, id)) return -1;
            }
        }
        return 0;
    }
    for (long i = lo[0]; i <= hi[0]; i++)
        for (long j = lo[1]; j <= hi[1]; j++)
            for (long l = lo[2]; l <= hi[2]; l++) {
                unsigned b = cell_hash(i, j, l, H->size);
                for (int e = H->start[b]; e < H->start[b + 1]; e++) {
                    int id = H->item[e];
                    if (stamp[id] != mark && overlap(box, H->boxes + 6 * id)) {
                        stamp[id] = mark;
                        if (push(out, id)) return -1;
                    }
                }
            }
    return 0;
}

int sb_hash_visit(const sb_hash *H, const double *box, int *stamp, int mark, sb_idlist *scratch,
                  int (*fn)(void *data, int id), void *data)
{
    if (sb_hash_query(H, box, stamp, mark, scratch)) return -1;
    for (int k = 0; k < scratch->n; k++) {
        const int r = fn(data, scratch->v[k]);
        if (r) return r;
    }
    return 0;
}
