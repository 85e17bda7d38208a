/* sb_bezier_ray.h — the first intersection of a ray with a bicubic Bézier
 * patch, by the three algorithms the BHEM paper compares in Table 1 (§5.1):
 *
 *   subdivision  midpoint De Casteljau subdivision of the patch; candidate
 *                sub-patches are kept in a min-heap on tau_min, the entry
 *                parameter of the ray into their control-point AABB (Eq. 24);
 *                the first sub-patch popped whose box is smaller than eps
 *                gives the first hit (Fig. 10a).
 *   newton       the same heap, but every popped sub-patch first tries
 *                Newton's method on x(u,v) = o + tau d from its centre; a root
 *                inside the sub-patch updates tau_opt and its neighbourhood
 *                is abandoned while the rest of the sub-patch is split
 *                around it (Fig. 10b); the search ends when the heap's
 *                tau_min reaches tau_opt.
 *   clipping     Bézier clipping (Nishita, Sederberg & Kakimoto 1990): the
 *                patch in a frame of the ray, clipped alternately in u and v
 *                to the parameter interval where the convex hull of its
 *                distances to a line through the ray can vanish, halved when
 *                a clip removes less than 20 %; best first from the same
 *                heap, the search ends when its smallest ray parameter
 *                passes the best root (first-hit pruning).
 *   clipping-dfs the same clipping as NSK90 describe it and most
 *                implementations do it (the BHEM paper does not describe
 *                its own): depth first, every root in (tmin, tmax) found and
 *                the smallest kept; only tmax (the nearest hit on other
 *                patches so far) prunes.  bench/bhem/table1.sh times both.
 *
 * All three search the whole patch and return the smallest t > tmin, so they
 * agree on the first hit (tests/test_render_isect.c); they differ in cost,
 * which the work counters report (bench/bhem/table1.sh). */
#ifndef SB_BEZIER_RAY_H
#define SB_BEZIER_RAY_H

#include "sb_bezier.h"
#include "sb_ray.h"

typedef enum {
    SB_ISECT_SUBDIVISION = 0, SB_ISECT_NEWTON = 1, SB_ISECT_CLIPPING = 2,
    SB_ISECT_CLIPPING_DFS = 3,   /* Bézier clipping depth first, every root (below) */
    SB_ISECT_COUNT
} sb_isect_kind;
extern const char *const sb_isect_names[];   /* "subdivision", "newton", "clipping", "clipping-dfs", NULL */
/* Kind by name; -1 if unknown. */
int sb_isect_find(const char *name);

/* Work done, summed over calls (sb_bezier_ws_counts). */
typedef struct sb_isect_counts {
    long calls;             /* patch tests */
    long hits;
    long regions;           /* sub-patches taken from the heap / stack */
    long splits;            /* De Casteljau sub-patches made */
    long newton;            /* Newton solves started */
    long newton_roots;      /* ... that found a root inside their sub-patch */
    long excluded;          /* roots whose neighbourhood was abandoned */
    long clips;             /* clipping steps */
    long budget;            /* searches stopped by the region budget (should stay 0) */
} sb_isect_counts;

/* Scratch space of one thread: the heap of sub-patches (grows on demand, so
 * no allocation once warmed up). */
typedef struct sb_bezier_ws sb_bezier_ws;
sb_bezier_ws *sb_bezier_ws_new(void);
void sb_bezier_ws_free(sb_bezier_ws *ws);
sb_isect_counts *sb_bezier_ws_counts(sb_bezier_ws *ws);

typedef struct sb_patch_hit { double t, u, v; } sb_patch_hit;

/* First intersection of r with patch P in (r->tmin, tmax), to within eps
 * (world units: the hit point is within eps of the surface point x(u,v) and
 * t within eps of the exact first root).  Returns 1 (hit filled), 0 (no hit)
 * or -1 (out of memory).  lo/hi: the patch's AABB if known, else NULL. */
int sb_bezier_intersect(sb_isect_kind kind, const double *P, const double *lo, const double *hi,
                        const sb_ray *r, double tmax, double eps, sb_bezier_ws *ws, sb_patch_hit *hit);

/* ---- shared by the algorithm files (not for callers) ------------------ */
typedef struct sb_bez_region {
    double P[SB_BEZ_N];     /* the sub-patch (world frame; ray frame for clipping) */
    double u0, u1, v0, v1;  /* its parameter box in the patch */
    double key;             /* tau_min of its box (heap key) */
    int dir;                /* clipping: direction to clip next */
} sb_bez_region;

struct sb_bezier_ws {
    sb_bez_region *pool;
    int *heap, *freel;
    int cap, n_heap, n_free, n_used;
    sb_isect_counts counts;
};

void sb_bez_reset(sb_bezier_ws *ws);
int  sb_bez_new(sb_bezier_ws *ws);                /* a free region index, -1 = out of memory */
void sb_bez_push(sb_bezier_ws *ws, int idx);      /* by pool[idx].key */
int  sb_bez_pop(sb_bezier_ws *ws);                /* smallest key, -1 if empty */
void sb_bez_release(sb_bezier_ws *ws, int idx);

int sb_bezier_clip_intersect(const double *P, const sb_ray *r, double tmax, double eps, sb_bezier_ws *ws,
                             sb_patch_hit *hit);
int sb_bezier_clip_dfs_intersect(const double *P, const sb_ray *r, double tmax, double eps, sb_bezier_ws *ws,
                                 sb_patch_hit *hit);

/* Regions one search may take before it stops with what it has (counts.budget). */
#define SB_BEZ_BUDGET 200000

#endif
