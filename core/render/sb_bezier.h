/* sb_bezier.h — bicubic Bézier patches (BHEM paper §5, Eq. 22):
 *
 *   x(u,v) = sum_{i,j=0..3} B^i(u) B^j(v) p_ij,   B^i(x) = C(3,i) x^i (1-x)^(3-i),
 *
 * the form every renderable spline surface of the suite is brought into
 * (Hermite patches of bhem, regular Catmull–Clark faces of rmtr).  A patch is
 * 16 control points P[3*(i + 4*j) + c], i along u, j along v.  The surface
 * lies in the convex hull of its control points, hence in their axis-aligned
 * bounding box, which the ray–patch algorithms (sb_bezier_ray.h) build on. */
#ifndef SB_BEZIER_H
#define SB_BEZIER_H

#define SB_BEZ_N 48   /* doubles per patch: 16 control points x 3 */

/* Cubic Bernstein polynomials and their first two derivatives at t. */
void sb_bernstein3(double t, double b[4], double d1[4], double d2[4]);

/* Tensor basis at (u,v): W[r][i + 4j], rows r = N, N_u, N_v, N_uu, N_uv, N_vv
 * (the layout of cc_bspline_patch, so that sb_shell_basis can take it). */
void sb_bezier_basis(double u, double v, double W[6][16]);

/* Position and first derivatives at (u,v) (xu, xv may be NULL). */
void sb_bezier_eval(const double *P, double u, double v, double x[3], double xu[3], double xv[3]);

/* De Casteljau split at u = t (resp. v = t) into the patches over [0,t] (lo)
 * and [t,1] (hi) in that parameter; either output may be NULL, and an output
 * may alias P only if it is the only one requested. */
void sb_bezier_split_u(const double *P, double t, double *lo, double *hi);
void sb_bezier_split_v(const double *P, double t, double *lo, double *hi);

/* The patch over the parameter box [u0,u1] x [v0,v1] of P (0 <= u0 < u1 <= 1),
 * reparametrized to [0,1]^2. */
void sb_bezier_sub(const double *P, double u0, double u1, double v0, double v1, double *out);

/* Axis-aligned bounding box of the control points (BHEM paper Eq. 24). */
void sb_bezier_bounds(const double *P, double lo[3], double hi[3]);

/* Bounds on the derivatives over the whole patch from the control net:
 * |x_u| <= L[0], |x_v| <= L[1], |x_uu| <= M[0], |x_uv| <= M[1], |x_vv| <= M[2]
 * (hodograph control points; the convex-hull property). */
void sb_bezier_derivative_bounds(const double *P, double L[2], double M[3]);

/* One uniform cubic B-spline segment per direction (control points
 * B[3*(a + 4*b) + c]) as a Bézier patch: the exact basis change. */
void sb_bspline_to_bezier(const double *B, double *P);

/* A cubic Hermite segment (values v0, v1 and derivatives d0, d1 w.r.t. the
 * segment parameter) has Bézier points v0, v0 + d0/3, v1 - d1/3, v1; the
 * tensor form of that for a bicubic Hermite patch (BHEM paper Eq. 14-16):
 * corner k = p + 2q at (p,q) carries the value x, the derivatives x_u, x_v
 * and the twist x_uv (all w.r.t. the patch parameters), H[k][kind][c]. */
void sb_hermite_to_bezier(const double H[4][4][3], double *P);

#endif
