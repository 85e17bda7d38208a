/* sb_bridson.h — the impulse-based collision response of Bridson, Fedkiw &
 * Anderson 2002 ("Robust treatment of collisions, contact and friction for
 * cloth animation", SIGGRAPH; "Bridson" below), as Bender & Deul (paper 003,
 * §6) use it, for any triangle mesh given its positions at t_n and t_{n+1},
 * its vertex masses and its triangles, against a scene's obstacles and
 * (contact.self) itself.  docs/contact.md, "The impulse pipeline".
 *
 * The pipeline of one step (sb_bridson.c), on the average velocity
 * v = (x1 - x0)/dt of the step:
 *   1. proximity (Bridson §7.1-7.2): every point–triangle and edge–edge pair
 *      closer than the thickness h at x0 (and every vertex within h of an
 *      analytic obstacle) gets an inelastic normal impulse that stops the
 *      approach, plus a repulsion that moves the pair apart at
 *      0.1 (h - d)/dt (Bridson's cap on the spring impulse, §7.2), and
 *      Coulomb friction on the relative tangential velocity,
 *      dv_T = -min(mu dv_N / |v_T|, 1) v_T (Bridson §7.2 Eq. for friction);
 *   2. continuous collision detection (Bridson §6.1 / §7.3): point–triangle
 *      and edge–edge pairs along the linear trajectories x0 -> x0 + dt v
 *      (coplanarity cubic), each hit resolved by an inelastic impulse that
 *      leaves the pair 0.1 h apart at t_{n+1}; at most five passes;
 *   3. rigid impact zones (Provot 1997, Bridson §7.4): the vertices of the
 *      pairs still colliding are merged into zones (overlapping zones merge)
 *      that move rigidly with their linear and angular momentum, until no
 *      collision is left.
 * Broad phase: one spatial hash per object (Teschner et al. 2003).
 * Dirichlet vertices have infinite mass (inverse mass 0). */
#ifndef SB_BRIDSON_H
#define SB_BRIDSON_H

#include "sb_scene.h"
#include "sb_impulse.h"

typedef struct sb_bridson_mesh {
    int nv, nt;
    const int *tri;            /* 3 nt vertex indices */
    const double *inv_mass;    /* nv; 0 = infinite mass (prescribed vertex) */
} sb_bridson_mesh;

/* One step of the pipeline: x0 (3 nv, t_n, assumed free of intersections)
 * and x1 (3 nv, the step's result at t1 = t_n + dt), corrected in place.
 * Thickness h = scene contact.dhat, obstacles and contact.self from sc;
 * obstacle poses at the steps round(t1/dt) - 1 and round(t1/dt).
 * Returns SB_OK, SB_ERR_NOMEM, or SB_NONFINITE when x1 is not finite (x1
 * left as is).  A step that ends with a collision left counts in
 * st->unresolved_steps. */
int sb_bridson_respond(const sb_bridson_mesh *m, const sb_scene *sc, double dt, double t1, const double *x0,
                       double *x1, sb_impulse_stats *st);

/* ---- geometry (sb_bridson_geom.c) -------------------------------------- */

/* Closest point of triangle (a, b, c) to p: its barycentric weights w[3]
 * (Ericson 2005, §5.1.5); returns the distance. */
double sb_closest_point_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                                 double w[3]);
/* Closest points p1 + s (q1 - p1), p2 + t (q2 - p2) of two segments, s, t in
 * [0, 1], parallel segments included (Ericson 2005, §5.1.9); returns the
 * distance. */
double sb_closest_segments(const double p1[3], const double q1[3], const double p2[3], const double q2[3],
                           double *s, double *t);
/* Continuous collision of two edges: sb_ccd_edge_edge (sb_self_geom.h,
 * sb_ccd_ee.c), shared with the barrier's self-contact filter. */

/* ---- rigid impact zones (sb_bridson_zone.c) ----------------------------- */

/* The rigid motion of n vertices (positions x0, velocities v, masses m,
 * all finite and positive) with their linear momentum P = sum m v and
 * angular momentum L = sum m (x0 - xc) x v about the centre of mass xc
 * (Bridson §7.4): vc = P / M, omega = I^-1 L (I the inertia tensor at x0;
 * pseudo-inverse on a degenerate, collinear zone).  Writes vc, omega and
 * the new velocities v = vc + (R(omega dt) (x0 - xc) - (x0 - xc))/dt, i.e.
 * the positions xc + dt vc + R (x0 - xc) at t_{n+1}. */
void sb_rigid_zone(int n, const double *x0, double *v, const double *m, double dt, double vc[3], double omega[3]);

#endif
