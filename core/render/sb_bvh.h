/* sb_bvh.h — a bounding-volume hierarchy of axis-aligned boxes over the
 * primitives of a surface (patches or triangles): built once per image by
 * median splits on the longest axis of the box centres, traversed nearest
 * child first. */
#ifndef SB_BVH_H
#define SB_BVH_H

#include "sb_ray.h"

typedef struct sb_bvh_node {
    double lo[3], hi[3];
    int left;        /* inner: index of the first child (the second is left + 1); leaf: -1 */
    int first, count;/* leaf: primitives prim[first .. first + count) */
} sb_bvh_node;

typedef struct sb_bvh {
    int n_nodes, n_prims;
    sb_bvh_node *node;
    int *prim;       /* primitive ids in leaf order */
} sb_bvh;

/* Build over n boxes lo[3 i], hi[3 i]; leaves hold at most leaf_size
 * primitives.  Returns 0 or -1 (out of memory). */
int  sb_bvh_build(sb_bvh *b, int n, const double *lo, const double *hi, int leaf_size);
void sb_bvh_free(sb_bvh *b);

/* Test primitive `prim` against r: on a hit closer than *tmax, lower *tmax
 * and return 1; 0 if no hit, negative on error. */
typedef int (*sb_bvh_hit_fn)(void *ctx, int prim, const sb_ray *r, double *tmax);

/* Visit the primitives whose boxes the ray enters before *tmax, nearest
 * first; any_hit = 1 stops at the first hit (shadow rays).  Returns 1 if some
 * primitive was hit (and *tmax lowered), 0 if none, negative on error. */
int sb_bvh_intersect(const sb_bvh *b, const sb_ray *r, double *tmax, int any_hit, sb_bvh_hit_fn fn, void *ctx);

/* Bounds of everything (the root box); zero box for an empty hierarchy. */
void sb_bvh_bounds(const sb_bvh *b, double lo[3], double hi[3]);

#endif
