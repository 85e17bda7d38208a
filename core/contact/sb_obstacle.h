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

/* A static world point x against obstacle o moving over a step from
 * motion factor fa to fb (the factor interpolated linearly within the
 * step): the first fraction of the step in [0, 1] at which the obstacle
 * touches x (0 when x is inside its solid at fa), or 2 when it does not.
 * The point's path in the obstacle's rest frame is tested piece by piece
 * (closed-form sb_obstacle_toi, point–triangle CCD for meshes): exact for
 * translations, chords within tol (m) of the path for rotations
 * (sb_obstacle.c).  This is the obstacle's swept volume seen from x. */
double sb_obstacle_sweep(const sb_obstacle_spec *o, double fa, double fb, const double x[3], double tol);

/* The scene's reference surface, sampled at its resolution (res x
 * contact.samples points per side, at most 129 x 129), against the
 * obstacles' poses at step 0: 1 when a point lies inside an analytic
 * obstacle or on a mesh triangle, with a sentence in why naming the
 * obstacle and the point; 0 when none does; -1 out of memory.  Method-free:
 * `shellbench check` and the run's set-up use it (the run then checks the
 * method's own sample points too). */
int sb_obstacles_start_check(const sb_scene *sc, char *why, size_t why_size);

/* How deep the open solid of analytic obstacle o in pose P reaches into
 * the world triangle (xa, xb, xc): > 0 when they overlap (<= 0 otherwise).
 * Sphere: radius minus the centre's distance to the triangle; capsule:
 * radius minus the axis segment's distance, INFINITY when the axis crosses
 * the triangle (pierced); box: the penetration depth of the separating-axis
 * test (Akenine-Möller 2001); plane: minus the lowest corner's distance.
 * Meshes: 0 (not tested).  Used to see an obstacle crossing the cloth
 * between its sample points (docs/contact.md "What the guarantee covers"). */
double sb_obstacle_triangle_depth(const sb_obstacle_spec *o, const sb_pose *P, const double xa[3], const double xb[3],
                                  const double xc[3]);

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
