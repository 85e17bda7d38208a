/* sb_obstacle.h — geometry of one scene obstacle (docs/contact.md): its
 * rigid pose at a step, the distance of a point to it with exact gradient
 * and Hessian, and the time of impact of a point moving on a segment.
 *
 * Distances.  Analytic solids (sphere, plane = half-space, box, capsule) use
 * the signed distance phi to the solid, positive outside: a point with
 * phi <= 0 is inside (infeasible).  A triangle mesh is a surface: the
 * distance of a point to each triangle is unsigned, and the barrier sums
 * over the triangles within reach (IPC, Li et al. 2020, §4: one barrier per
 * point–triangle pair); crossing the surface is excluded by continuous
 * collision detection (the step filter), not by a sign. */
#ifndef SB_OBSTACLE_H
#define SB_OBSTACLE_H

#include "sb_scene.h"

/* x_world = c + R (y - c) + t, y in the obstacle's rest frame */
typedef struct sb_pose {
    double R[9];      /* row-major */
    double c[3], t[3];
} sb_pose;

/* The pose of obstacle o at motion factor f (sb_obstacle_motion_factor). */
void sb_pose_at(const sb_obstacle_spec *o, double f, sb_pose *P);
void sb_pose_apply(const sb_pose *P, const double y[3], double x[3]);
void sb_pose_inverse(const sb_pose *P, const double x[3], double y[3]);
/* world vector v from a rest-frame vector u: v = R u */
void sb_pose_rotate(const sb_pose *P, const double u[3], double v[3]);

/* Signed distance of the world point x to analytic obstacle o in pose P,
 * with gradient g (3) and Hessian H (3x3 row-major) when non-NULL (exact;
 * the box's Hessian is that of the region x lies in, the other shapes are
 * smooth outside their solid). */
double sb_obstacle_phi(const sb_obstacle_spec *o, const sb_pose *P, const double x[3], double *g, double *H);

/* Unsigned distance of x (rest frame of the mesh) to triangle (a, b, c),
 * gradient and Hessian w.r.t. x (exact in the region of the closest
 * feature: face, edge or vertex). */
double sb_point_triangle_distance(const double x[3], const double a[3], const double b[3], const double c[3],
                                  double *g, double *H);

/* Time of impact t in [0, 1] at which the point x + t d (world) first
 * touches the solid of analytic obstacle o in pose P (closed form); returns
 * 2 (no impact in [0, 1]) otherwise.  x must be outside (phi > 0). */
double sb_obstacle_toi(const sb_obstacle_spec *o, const sb_pose *P, const double x[3], const double d[3]);

/* Continuous collision of a point against a triangle, all four moving
 * linearly from time 0 to 1 (p0 -> p1, a0 -> a1, ...): the first time in
 * [0, 1] at which the point lies on the triangle (closed triangle), or 2 when
 * it does not.  The coplanarity condition is the cubic
 * ((b-a) x (c-a)) . (p-a) = 0 (solved with gsl_poly_solve_cubic, and as a
 * quadratic or linear equation when its leading coefficients vanish); a
 * motion that stays coplanar throughout is handled in the plane by the
 * point's crossings of the three edges (sb_ccd.c). */
double sb_ccd_point_triangle(const double p0[3], const double p1[3], const double a0[3], const double a1[3],
                             const double b0[3], const double b1[3], const double c0[3], const double c1[3]);

#endif
