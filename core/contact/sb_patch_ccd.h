/* sb_patch_ccd.h — continuous collision detection of a moving point against
 * a moving bicubic Bézier patch: the dynamic ray–patch intersection of the
 * BHEM paper (Ni, Chen et al.) §5.2, Eq. (25)-(28).
 *
 * The patch moves linearly over the step, control points
 * p_ij(t) = P0_ij + t (P1_ij - P0_ij) (Eq. 25, time normalized to [0, 1]), the
 * point on x(t) = p0 + t (p1 - p0) (Eq. 26).  In the point's frame the patch
 * has control points c_ij(t) = p_ij(t) - x(t), also linear in t, and a
 * collision at t is the origin lying on the patch.  Necessary condition
 * (convex hull, Eq. 27): the origin lies in the AABB of the c_ij(t); per axis
 * it is a union of half-lines in t (Eq. 28), so the feasible times form
 * [0,1] minus at most six open gaps, whose earliest and latest points bound
 * the region's time interval (the paper's "greedy" solution of Eq. 27).
 *
 * Search (the divide-and-conquer of §5.1 on (u, v, t)): regions (a
 * parameter box and a time interval) sit in a min-heap on their earliest
 * feasible time; a popped region is split in time when its control points
 * move more over its interval than its patch is large, else by De Casteljau
 * into four in (u, v); a region whose swept box is smaller than eps is a hit
 * at its earliest time.  Newton acceleration (§5.1, last paragraph, for
 * Eq. 25 = Eq. 26): each popped region first tries Newton's method on
 * F(u, v, t) = x(u, v, t) - x_p(t) from its centre; a root inside the region
 * lowers the bound tau_opt, and every region that cannot enter before it is
 * dropped.  The heap order makes the first hit the earliest one (to eps). */
#ifndef SB_PATCH_CCD_H
#define SB_PATCH_CCD_H

#include "sb_bezier.h"

typedef struct sb_ccd_hit { double t, u, v; } sb_ccd_hit;

typedef struct sb_patch_ccd_counts {
    long calls, hits;
    long regions;        /* regions taken from the heap */
    long newton;         /* Newton solves started */
    long newton_roots;   /* ... that found a root inside their region */
    long budget;         /* searches stopped by the region budget (reported as a hit at the bound) */
} sb_patch_ccd_counts;

typedef struct sb_patch_ccd_ws sb_patch_ccd_ws;
sb_patch_ccd_ws *sb_patch_ccd_ws_new(void);
void sb_patch_ccd_ws_free(sb_patch_ccd_ws *ws);
sb_patch_ccd_counts *sb_patch_ccd_ws_counts(sb_patch_ccd_ws *ws);

/* First time t in [0, 1] at which the point p0 -> p1 lies on the patch
 * P0 -> P1 (SB_BEZ_N doubles each), to within eps (world units: the point
 * is within about eps of the surface point x(u, v, t), and no earlier time
 * brings it closer than that).  Returns 1 (hit filled), 0 (none) or -1 (out
 * of memory). */
int sb_patch_ccd(const double *P0, const double *P1, const double p0[3], const double p1[3], double eps,
                 sb_patch_ccd_ws *ws, sb_ccd_hit *hit);

/* Interval [*t0, *t1] of [0, 1] over which the origin can lie in the AABB of
 * the control points Ca + s (Cb - Ca) inflated by tol (Eq. 27-28); returns 0
 * when empty.  Exposed for the tests. */
int sb_patch_ccd_times(const double *Ca, const double *Cb, double tol, double *t0, double *t1);

#endif
