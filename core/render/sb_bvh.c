/* sb_bvh.c — bounding-volume hierarchy (sb_bvh.h). */
#include "sb_bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct build_ctx {
    sb_bvh *b;
    const double *lo, *hi;
    double *cen;     /* 3 n box centres */
    int leaf_size;
} build_ctx;

/* qsort needs a comparator without context: sort (key, id) pairs instead */
typedef struct key_id { double key; int id; } key_id;
static int cmp_key(const void *a, const void *b)
{
    const double x = ((const key_id *)a)->key, y = ((const key_id *)b)->key;
    return x < y ? -1 : x > y ? 1 : ((const key_id *)a)->id - ((const key_id *)b)->id;
}

static int build(build_ctx *C, int node, int first, int count, key_id *tmp)
{
    sb_bvh *b = C->b;
    sb_bvh_node *N = &b->node[node];
    for (int c = 0; c < 3; c++) { N->lo[c] = INFINITY; N->hi[c] = -INFINITY; }
    double clo[3] = { INFINITY, INFINITY, INFINITY }, chi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int k = first; k < first + count; k++) {
        const int p = b->prim[k];
        for (int c = 0; c < 3; c++) {
            N->lo[c] = fmin(N->lo[c], C->lo[3 * p + c]);
            N->hi[c] = fmax(N->hi[c], C->hi[3 * p + c]);
            clo[c] = fmin(clo[c], C->cen[3 * p + c]);
            chi[c] = fmax(chi[c], C->cen[3 * p + c]);
        }
    }
    N->first = first;
    N->count = count;
    N->left = -1;
    if (count <= C->leaf_size) return 0;
    int axis = 0;
    for (int c = 1; c < 3; c++)
        if (chi[c] - clo[c] > chi[axis] - clo[axis]) axis = c;
    for (int k = 0; k < count; k++) {
        tmp[k].id = b->prim[first + k];
        tmp[k].key = C->cen[3 * tmp[k].id + axis];
    }
    qsort(tmp, (size_t)count, sizeof *tmp, cmp_key);
    for (int k = 0; k < count; k++) b->prim[first + k] = tmp[k].id;
    const int half = count / 2;
    const int left = b->n_nodes;
    b->n_nodes += 2;
    N->left = left;   /* N stays valid: the node array is allocated once */
    N->count = 0;
    if (build(C, left, first, half, tmp)) return -1;
    return build(C, left + 1, first + half, count - half, tmp);
}

int sb_bvh_build(sb_bvh *b, int n, const double *lo, const double *hi, int leaf_size)
{

    memset(b, 0, sizeof *b);
    if (n <= 0) return 0;
    b->node = malloc((size_t)(2 * n) * sizeof *b->node);
    b->prim = malloc((size_t)n * sizeof *b->prim);
    double *cen = malloc((size_t)n * 3 * sizeof *cen);
    key_id *tmp = malloc((size_t)n * sizeof *tmp);
    if (!b->node || !b->prim || !cen || !tmp) {
        free(cen);
        free(tmp);
        sb_bvh_free(b);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        b->prim[i] = i;
        for (int c = 0; c < 3; c++) cen[3 * i + c] = 0.5 * (lo[3 * i + c] + hi[3 * i + c]);
    }
    b->n_prims = n;
    b->n_nodes = 1;
    build_ctx C = { b, lo, hi, cen, leaf_size < 1 ? 1 : leaf_size };
    int rc = build(&C, 0, 0, n, tmp);
    free(cen);
    free(tmp);
    if (rc) sb_bvh_free(b);
    return rc;
}

void sb_bvh_free(sb_bvh *b)
{
    free(b->node);
    free(b->prim);
    memset(b, 0, sizeof *b);
}

void sb_bvh_bounds(const sb_bvh *b, double lo[3], double hi[3])
{
    for (int c = 0; c < 3; c++) lo[c] = hi[c] = 0.0;
    if (b->n_nodes > 0)
        for (int c = 0; c < 3; c++) {
            lo[c] = b->node[0].lo[c];
            hi[c] = b->node[0].hi[c];
        }
}

int sb_bvh_intersect(const sb_bvh *b, const sb_ray *r, double *tmax, int any_hit, sb_bvh_hit_fn fn, void *ctx)
{
    if (b->n_nodes == 0) return 0;
    int stack[128], sp = 0, hit = 0;
    double t0, t1;
    if (!sb_ray_box(r, b->node[0].lo, b->node[0].hi, *tmax, &t0, &t1)) return 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const sb_bvh_node *N = &b->node[stack[--sp]];
        if (N->left < 0) {
            for (int k = N->first; k < N->first + N->count; k++) {
                int rc = fn(ctx, b->prim[k], r, tmax);
                if (rc < 0) return rc;
                if (rc > 0) {
                    hit = 1;
                    if (any_hit) return 1;
                }
            }
            continue;
        }
        double a0, a1, b0, b1;
        const int ha = sb_ray_box(r, b->node[N->left].lo, b->node[N->left].hi, *tmax, &a0, &a1);
        const int hb = sb_ray_box(r, b->node[N->left + 1].lo, b->node[N->left + 1].hi, *tmax, &b0, &b1);
        if (sp + 2 > (int)(sizeof stack / sizeof *stack)) return -1;   /* depth > 64: cannot happen for median splits */
        /* push the farther child first so the nearer is visited first */
        if (ha && hb) {
            if (a0 <= b0) { stack[sp++] = N->left + 1; stack[sp++] = N->left; }
            else { stack[sp++] = N->left; stack[sp++] = N->left + 1; }
        } else if (ha) stack[sp++] = N->left;
        else if (hb) stack[sp++] = N->left + 1;
    }
    return hit;
}
