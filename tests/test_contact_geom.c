/* test_contact_geom.c — the geometry under contact (docs/contact.md): the
 * IPC barrier and friction mollifier against finite differences; signed
 * distances of every analytic obstacle (also moved and rotated) and the
 * point–triangle distance in each of its regions, gradient and Hessian
 * against central differences; closed-form times of impact against dense
 * sampling of the distance along the segment; point–triangle CCD with its
 * degenerate cases at known times of impact. */
#include <math.h>
#include <string.h>

#include "sb_contact.h"
#include "sb_obstacle.h"
#include "sb_test.h"

SB_TEST(barrier_and_mollifier_derivatives)
{
    const double dhat = 0.01;
    for (double d = 0.0005; d < dhat; d += 0.0013) {
        double db, ddb, h = 1e-7;
        double b = sb_barrier(d, dhat, &db, &ddb);
        double bp, bm, dbp, dbm;
        bp = sb_barrier(d + h, dhat, &dbp, NULL);
        bm = sb_barrier(d - h, dhat, &dbm, NULL);
        CHECK(b > 0);
        CHECK_REL(db, (bp - bm) / (2 * h), 1e-6);
        CHECK_REL(ddb, (dbp - dbm) / (2 * h), 1e-6);
    }
    double db, ddb;
    CHECK(sb_barrier(dhat, dhat, &db, &ddb) == 0 && db == 0 && ddb == 0);
    CHECK(sb_barrier(2 * dhat, dhat, &db, &ddb) == 0);
    /* C2 at dhat from below: b, b' -> 0 */
    double bl = sb_barrier(dhat * (1 - 1e-6), dhat, &db, &ddb);
    CHECK(fabs(bl) < 1e-15 && fabs(db) < 1e-7);
    const double eps = 0.002;
    for (double y = 0.0001; y < 3 * eps; y += 0.00037) {
        double f1, df1, h = 1e-8, f1p, f1m;
        double fp = sb_friction_f0(y + h, eps, &f1p, NULL), fm = sb_friction_f0(y - h, eps, &f1m, NULL);
        sb_friction_f0(y, eps, &f1, &df1);
        CHECK_REL(f1, (fp - fm) / (2 * h), 1e-6);
        if (fabs(y - eps) > 1e-6) CHECK_NEAR(df1, (f1p - f1m) / (2 * h), 1e-4 * (1 / eps));
    }
    /* continuity at eps: f0(eps) = eps, f1(eps) = 1 */
    double f1;
    CHECK_REL(sb_friction_f0(eps * (1 - 1e-12), eps, &f1, NULL), eps, 1e-9);
    CHECK_NEAR(f1, 1.0, 1e-9);
}

static sb_obstacle_spec shape(int kind)
{
    sb_obstacle_spec o;
    memset(&o, 0, sizeof o);
    o.kind = (sb_obstacle_shape)kind;
    double c[3] = { 0.1, -0.2, 0.3 };
    memcpy(o.center, c, sizeof c);
    o.radius = 0.25;
    o.point[2] = 0.05;
    o.normal[0] = 0.6; o.normal[2] = 0.8;
    o.half[0] = 0.3; o.half[1] = 0.2; o.half[2] = 0.1;
    o.a[0] = -0.2; o.a[1] = 0.1; o.a[2] = 0.0;
    o.b[0] = 0.3; o.b[1] = -0.1; o.b[2] = 0.2;
    /* moved: translated and rotated about a skew axis */
    o.translation[0] = 0.05; o.translation[1] = 0.02; o.translation[2] = -0.03;
    o.rot_axis[0] = 1 / sqrt(3.0); o.rot_axis[1] = 1 / sqrt(3.0); o.rot_axis[2] = 1 / sqrt(3.0);
    o.rot_center[0] = 0.1;
    o.rot_angle = 0.4;
    o.moving = 1;
    return o;
}

/* phi's gradient and Hessian against central differences at points
 * around each analytic shape, at rest and moved (f = 0.7) */
SB_TEST(signed_distance_derivatives)
{
    for (int kind = SB_OBST_SPHERE; kind <= SB_OBST_CAPSULE; kind++)
        for (int moved = 0; moved < 2; moved++) {
            sb_obstacle_spec o = shape(kind);
            sb_pose P;
            sb_pose_at(&o, moved ? 0.7 : 0.0, &P);
            int tested = 0;
            for (int k = 0; k < 60; k++) {
                double x[3] = { 0.1 + 0.7 * sin(1.3 * k), -0.2 + 0.6 * cos(0.7 * k + 1), 0.3 + 0.5 * sin(2.1 * k + 2) };
                double g[3], H[9];
                double phi = sb_obstacle_phi(&o, &P, x, g, H);
                if (!(phi > 0.01)) continue;
                if (kind == SB_OBST_BOX) {
                    /* stay off the region boundaries where the box's Hessian jumps */
                    double y[3];
                    sb_pose_inverse(&P, x, y);
                    int near = 0;
                    for (int i = 0; i < 3; i++) near |= fabs(fabs(y[i] - o.center[i]) - o.half[i]) < 1e-3;
                    if (near) continue;
                }
                tested++;
                const double h = 1e-6;
                for (int i = 0; i < 3; i++) {
                    double xp[3] = { x[0], x[1], x[2] }, xm[3] = { x[0], x[1], x[2] }, gp[3], gm[3];
                    xp[i] += h; xm[i] -= h;
                    double fp = sb_obstacle_phi(&o, &P, xp, gp, NULL), fm = sb_obstacle_phi(&o, &P, xm, gm, NULL);
                    CHECK_NEAR(g[i], (fp - fm) / (2 * h), 1e-7);
                    for (int j = 0; j < 3; j++) CHECK_NEAR(H[3 * i + j], (gp[j] - gm[j]) / (2 * h), 1e-5 * (1 + fabs(H[3 * i + j])));
                }
            }
            CHECK_MSG(tested >= 10, "shape %d: only %d points tested", kind, tested);
        }
}

/* sign and value at known points: inside negative, outside the exact distance */
SB_TEST(signed_distance_values)
{
    sb_obstacle_spec o;
    sb_pose P;
    memset(&o, 0, sizeof o);
    sb_pose_at(&o, 0, &P);
    o.kind = SB_OBST_BOX;
    o.half[0] = o.half[1] = o.half[2] = 1;
    double x1[3] = { 2, 2, 0 }, x2[3] = { 0.5, 0, 0 }, x3[3] = { 0, 0, 3 };
    CHECK_NEAR(sb_obstacle_phi(&o, &P, x1, NULL, NULL), sqrt(2.0), 1e-15);
    CHECK_NEAR(sb_obstacle_phi(&o, &P, x2, NULL, NULL), -0.5, 1e-15);
    CHECK_NEAR(sb_obstacle_phi(&o, &P, x3, NULL, NULL), 2.0, 1e-15);
    o.kind = SB_OBST_CAPSULE;
    o.a[0] = -1; o.b[0] = 1; o.radius = 0.5;
    double x4[3] = { 0, 0, 2 }, x5[3] = { 3, 0, 0 };
    CHECK_NEAR(sb_obstacle_phi(&o, &P, x4, NULL, NULL), 1.5, 1e-15);
    CHECK_NEAR(sb_obstacle_phi(&o, &P, x5, NULL, NULL), 1.5, 1e-15);
    /* a moved sphere: the translation and a rotation about its own centre */
    o.kind = SB_OBST_SPHERE;
    o.radius = 1;
    o.translation[2] = 1;
    o.rot_axis[2] = 1; o.rot_angle = 1; o.moving = 1;
    sb_pose_at(&o, 0.5, &P);
    double x6[3] = { 0, 0, 2.5 };
    CHECK_NEAR(sb_obstacle_phi(&o, &P, x6, NULL, NULL), 1.0, 1e-14);
}

SB_TEST(point_triangle_distance_regions)
{
    const double a[3] = { 0, 0, 0 }, b[3] = { 1, 0, 0.2 }, c[3] = { 0.2, 1, -0.1 };
    /* face, three edges, three vertices */
    const double pts[7][3] = { { 0.3, 0.3, 0.5 }, { 0.5, -0.4, 0.3 }, { 0.8, 0.8, 0.1 }, { -0.4, 0.5, 0.2 },
                               { -0.3, -0.3, 0.2 }, { 1.4, -0.2, 0.4 }, { 0.2, 1.5, 0.3 } };
    for (int k = 0; k < 7; k++) {
        double g[3], H[9];
        double d = sb_point_triangle_distance(pts[k], a, b, c, g, H);
        CHECK(d > 0);
        const double h = 1e-6;
        for (int i = 0; i < 3; i++) {
            double xp[3] = { pts[k][0], pts[k][1], pts[k][2] }, xm[3] = { pts[k][0], pts[k][1], pts[k][2] }, gp[3], gm[3];
            xp[i] += h; xm[i] -= h;
            double fp = sb_point_triangle_distance(xp, a, b, c, gp, NULL), fm = sb_point_triangle_distance(xm, a, b, c, gm, NULL);
            CHECK_NEAR(g[i], (fp - fm) / (2 * h), 1e-7);
            for (int j = 0; j < 3; j++) CHECK_NEAR(H[3 * i + j], (gp[j] - gm[j]) / (2 * h), 1e-5);
        }
    }
    /* vertex region: the distance to the vertex itself */
    CHECK_NEAR(sb_point_triangle_distance(pts[4], a, b, c, NULL, NULL), sqrt(0.09 + 0.09 + 0.04), 1e-15);
}

/* the closed-form time of impact equals the first sign change of phi along
 * the segment (dense sampling, then bisection) */
SB_TEST(time_of_impact_closed_form)
{
    int hits = 0, misses = 0;
    for (int kind = SB_OBST_SPHERE; kind <= SB_OBST_CAPSULE; kind++) {
        sb_obstacle_spec o = shape(kind);
        sb_pose P;
        sb_pose_at(&o, 0.3, &P);
        for (int k = 0; k < 200; k++) {
            double x[3] = { 0.1 + 0.9 * sin(1.7 * k), -0.2 + 0.9 * cos(0.9 * k + 1), 0.3 + 0.9 * sin(2.3 * k + 2) };
            if (!(sb_obstacle_phi(&o, &P, x, NULL, NULL) > 1e-3)) continue;
            double tgt[3] = { 0.1 + 0.2 * sin(k), -0.2 + 0.2 * cos(k), 0.3 + 0.1 * sin(3.0 * k) };
            double d[3] = { 1.3 * (tgt[0] - x[0]), 1.3 * (tgt[1] - x[1]), 1.3 * (tgt[2] - x[2]) };
            if (k % 3 == 0) { d[0] = -d[1]; d[1] = d[0]; }   /* some that pass by */
            double t = sb_obstacle_toi(&o, &P, x, d), ts = 2.0;
            const int N = 4000;
            for (int s = 1; s <= N; s++) {
                double y[3] = { x[0] + d[0] * s / N, x[1] + d[1] * s / N, x[2] + d[2] * s / N };
                if (sb_obstacle_phi(&o, &P, y, NULL, NULL) <= 0) {
                    double lo = (s - 1.0) / N, hi = (double)s / N;
                    for (int it = 0; it < 60; it++) {
                        double mid = 0.5 * (lo + hi);
                        double z[3] = { x[0] + d[0] * mid, x[1] + d[1] * mid, x[2] + d[2] * mid };
                        if (sb_obstacle_phi(&o, &P, z, NULL, NULL) <= 0) hi = mid; else lo = mid;
                    }
                    ts = hi;
                    break;
                }
            }
            if (t <= 1) {
                /* on the surface at t, and no earlier sample inside (a grazing
                 * impact may be shorter than the sampling's spacing) */
                hits++;
                double z[3] = { x[0] + d[0] * t, x[1] + d[1] * t, x[2] + d[2] * t };
                CHECK_MSG(fabs(sb_obstacle_phi(&o, &P, z, NULL, NULL)) < 1e-10, "shape %d case %d: phi(toi) = %g", kind,
                          k, sb_obstacle_phi(&o, &P, z, NULL, NULL));
                CHECK_MSG(ts >= t - 1e-9, "shape %d case %d: toi %.12g after the sampled impact %.12g", kind, k, t, ts);
            } else {
                misses++;
                CHECK_MSG(ts > 1, "shape %d case %d: no toi but an impact at %.12g", kind, k, ts);
            }
        }
    }
    CHECK(hits > 100 && misses > 20);
}

static double ccd(const double p0[3], const double p1[3], const double a0[3], const double a1[3], const double b0[3],
                  const double b1[3], const double c0[3], const double c1[3])
{
    return sb_ccd_point_triangle(p0, p1, a0, a1, b0, b1, c0, c1);
}

SB_TEST(ccd_point_triangle_degenerate_cases)
{
    const double a[3] = { 0, 0, 0 }, b[3] = { 1, 0, 0 }, c[3] = { 0, 1, 0 };
    /* static triangle (f linear): a point falling through the face at t = 0.25 */
    {
        double p0[3] = { 0.2, 0.2, 1 }, p1[3] = { 0.2, 0.2, -3 };
        CHECK_NEAR(ccd(p0, p1, a, a, b, b, c, c), 0.25, 1e-14);
    }
    /* the same line of motion outside the triangle: no impact */
    {
        double p0[3] = { 0.8, 0.8, 1 }, p1[3] = { 0.8, 0.8, -3 };
        CHECK(ccd(p0, p1, a, a, b, b, c, c) > 1);
    }
    /* touching an edge and a vertex exactly (closed triangle) */
    {
        double p0[3] = { 0.5, 0.5, 1 }, p1[3] = { 0.5, 0.5, -1 };
        CHECK_NEAR(ccd(p0, p1, a, a, b, b, c, c), 0.5, 1e-14);
        double q0[3] = { 1, 0, 2 }, q1[3] = { 1, 0, -2 };
        CHECK_NEAR(ccd(q0, q1, a, a, b, b, c, c), 0.5, 1e-14);
    }
    /* parallel to the plane (f constant, nonzero): never */
    {
        double p0[3] = { -1, 0.2, 0.1 }, p1[3] = { 2, 0.2, 0.1 };
        CHECK(ccd(p0, p1, a, a, b, b, c, c) > 1);
    }
    /* coplanar throughout (f identically zero): entry through edge x = 0 at t = 0.5 */
    {
        double p0[3] = { -0.5, 0.25, 0 }, p1[3] = { 0.5, 0.25, 0 };
        CHECK_NEAR(ccd(p0, p1, a, a, b, b, c, c), 0.5, 1e-12);
        double q0[3] = { 0.25, 0.25, 0 };   /* coplanar and inside from the start */
        CHECK_NEAR(ccd(q0, p1, a, a, b, b, c, c), 0.0, 0);
        double r0[3] = { -1, -0.5, 0 }, r1[3] = { 2, -0.5, 0 };   /* coplanar, passing by */
        CHECK(ccd(r0, r1, a, a, b, b, c, c) > 1);
    }
    /* starting on the triangle: impact at 0 */
    {
        double p0[3] = { 0.2, 0.2, 0 }, p1[3] = { 0.2, 0.2, 1 };
        CHECK_NEAR(ccd(p0, p1, a, a, b, b, c, c), 0.0, 0);
    }
    /* moving triangle, static point (quadratic/cubic f): the triangle rises
     * through the point at z = 0.3 while it rotates about x */
    {
        double p[3] = { 0.25, 0.25, 0.3 };
        double a1[3] = { 0, 0, 0.6 }, b1[3] = { 1, 0, 0.6 }, c1[3] = { 0, 1, 0.6 };
        CHECK_NEAR(ccd(p, p, a, a1, b, b1, c, c1), 0.5, 1e-12);
        /* the triangle tilts: c moves up faster -> plane z = 0.6 t + 0.6 t y... */
        double c2[3] = { 0, 1, 1.8 };
        /* z(t) at (x, y) = (0.25, 0.25): 0.6 t + 1.2 t * 0.25 = 0.9 t = 0.3 -> t = 1/3 */
        CHECK_NEAR(ccd(p, p, a, a1, b, b1, c, c2), 1.0 / 3.0, 1e-12);
    }
    /* a genuinely cubic case: all four move; checked against bisection on
     * the signed volume and the inside test */
    {
        double p0[3] = { 0.3, 0.2, 0.5 }, p1[3] = { 0.1, 0.3, -0.6 };
        double a1[3] = { 0.1, -0.1, 0.2 }, b1[3] = { 0.9, 0.2, -0.3 }, c1[3] = { -0.2, 1.1, 0.4 };
        double t = ccd(p0, p1, a, a1, b, b1, c, c1);
        CHECK(t >= 0 && t <= 1);
        /* the signed volume changes sign around t */
        double vol[2];
        for (int s = 0; s < 2; s++) {
            double tt = t + (s ? 1e-7 : -1e-7), P[3], A[3], B[3], C[3], e1[3], e2[3], w[3];
            for (int i = 0; i < 3; i++) {
                P[i] = p0[i] + tt * (p1[i] - p0[i]); A[i] = a[i] + tt * (a1[i] - a[i]);
                B[i] = b[i] + tt * (b1[i] - b[i]); C[i] = c[i] + tt * (c1[i] - c[i]);
                e1[i] = B[i] - A[i]; e2[i] = C[i] - A[i]; w[i] = P[i] - A[i];
            }
            vol[s] = (e1[1] * e2[2] - e1[2] * e2[1]) * w[0] + (e1[2] * e2[0] - e1[0] * e2[2]) * w[1] +
                     (e1[0] * e2[1] - e1[1] * e2[0]) * w[2];
        }
        CHECK(vol[0] * vol[1] < 0);
    }
}

/* issue 37: the sweep of a moving obstacle against a static point
 * (sb_obstacle_sweep) and a triangle's depth into a solid
 * (sb_obstacle_triangle_depth), on cases with known answers:
 *  - a box translating 0.3 m up through a point 0.02 m above its top: first
 *    touch at 0.02 / 0.3 of the step (exact for translations);
 *  - a sphere (r = 0.1) carried half a turn about z on the unit circle past
 *    the point (0, 1, 0): touch when the centre's chord to the point is r,
 *    f = 1/2 - 2 asin(r/2) / pi (rotation: chords within tol);
 *  - the same sphere passing the origin at distance 1: no touch (2);
 *  - a point already inside at the step's start: 0;
 *  - a mesh (one triangle) moving through the point: the CCD time;
 *  - depths: a triangle 0.05 below a sphere's top (r - d), a capsule whose
 *    axis pierces a triangle (INFINITY), a triangle cutting a box's corner
 *    (the separating-axis depth), a triangle clear of each (<= 0). */
SB_TEST(moving_obstacle_sweep_and_triangle_depth)
{
    sb_obstacle_spec o;
    memset(&o, 0, sizeof o);
    o.kind = SB_OBST_BOX;
    o.center[2] = -0.12;
    o.half[0] = 0.2; o.half[1] = 0.4; o.half[2] = 0.1;
    o.translation[2] = 0.3;
    o.moving = 1;
    const double x0[3] = { 0.05, 0.1, 0.0 };
    CHECK_NEAR(sb_obstacle_sweep(&o, 0.0, 1.0, x0, 1e-5), 0.02 / 0.3, 1e-12);
    CHECK_NEAR(sb_obstacle_sweep(&o, 0.5, 1.0, x0, 1e-5), 0.0, 0.0);    /* inside at f = 0.5 */
    CHECK_NEAR(sb_obstacle_sweep(&o, 0.0, 0.0, x0, 1e-5), 2.0, 0.0);    /* no motion */
    const double x_side[3] = { 0.5, 0.1, 0.0 };
    CHECK_NEAR(sb_obstacle_sweep(&o, 0.0, 1.0, x_side, 1e-5), 2.0, 0.0);

    memset(&o, 0, sizeof o);
    o.kind = SB_OBST_SPHERE;
    o.center[0] = 1;
    o.radius = 0.1;
    o.rot_axis[2] = 1;
    o.rot_angle = M_PI;
    o.moving = 1;
    const double p[3] = { 0, 1, 0 }, tol = 1e-6;
    const double f_exact = 0.5 - 2 * asin(0.05) / M_PI;
    /* chords within tol of the path: the time within tol / speed (speed pi per unit of f) */
    CHECK_NEAR(sb_obstacle_sweep(&o, 0.0, 1.0, p, tol), f_exact, 2 * tol / M_PI + 1e-12);
    const double q[3] = { 0, 0, 0 };
    CHECK_NEAR(sb_obstacle_sweep(&o, 0.0, 1.0, q, tol), 2.0, 0.0);

    /* a one-triangle mesh moving 1 m up through a point 0.25 above it */
    double verts[9] = { -1, -1, 0, 2, -1, 0, -1, 2, 0 };
    int tris[3] = { 0, 1, 2 };
    memset(&o, 0, sizeof o);
    o.kind = SB_OBST_MESH;
    o.nv = 3; o.nt = 1; o.verts = verts; o.tris = tris;
    o.translation[2] = 1;
    o.moving = 1;
    const double pm[3] = { 0.1, 0.1, 0.25 };
    CHECK_NEAR(sb_obstacle_sweep(&o, 0.0, 1.0, pm, tol), 0.25, 1e-12);

    /* depths */
    sb_pose I;
    memset(&o, 0, sizeof o);
    o.kind = SB_OBST_SPHERE;
    o.radius = 0.5;
    sb_pose_at(&o, 0.0, &I);
    const double ta[3] = { -1, -1, 0.45 }, tb[3] = { 1, -1, 0.45 }, tc[3] = { 0, 1, 0.45 };
    CHECK_NEAR(sb_obstacle_triangle_depth(&o, &I, ta, tb, tc), 0.05, 1e-12);
    const double ua[3] = { -1, -1, 0.55 }, ub[3] = { 1, -1, 0.55 }, uc[3] = { 0, 1, 0.55 };
    CHECK(sb_obstacle_triangle_depth(&o, &I, ua, ub, uc) <= 0);
    o.kind = SB_OBST_CAPSULE;
    o.radius = 0.002;
    o.a[2] = -1; o.b[2] = 0.5;
    CHECK(isinf(sb_obstacle_triangle_depth(&o, &I, ta, tb, tc)));
    o.b[2] = 0.4;   /* the tip 0.05 below the triangle: clear */
    CHECK(sb_obstacle_triangle_depth(&o, &I, ta, tb, tc) <= 0);
    o.b[2] = 0.449;   /* the cap 1 mm below, reaching 1 mm into it */
    CHECK_NEAR(sb_obstacle_triangle_depth(&o, &I, ta, tb, tc), 0.001, 1e-12);
    o.kind = SB_OBST_BOX;
    o.half[0] = o.half[1] = o.half[2] = 0.5;
    /* a horizontal triangle at z = 0.45 over the box's top face: 0.05 deep */
    CHECK_NEAR(sb_obstacle_triangle_depth(&o, &I, ta, tb, tc), 0.05, 1e-12);
    CHECK(sb_obstacle_triangle_depth(&o, &I, ua, ub, uc) <= 0);
    /* a steep triangle cutting the box's edge x = y... at (0.5, *, 0.5): the
       plane x + z = 0.9 leaves the corner region 0.1 / sqrt(2) deep */
    const double va[3] = { 0.9, -2, 0 }, vb[3] = { 0.9, 2, 0 }, vc[3] = { -0.1, 0, 1 };
    CHECK_NEAR(sb_obstacle_triangle_depth(&o, &I, va, vb, vc), 0.1 / sqrt(2.0), 1e-12);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(barrier_and_mollifier_derivatives), SB_CASE(signed_distance_derivatives),
        SB_CASE(signed_distance_values), SB_CASE(point_triangle_distance_regions),
        SB_CASE(time_of_impact_closed_form), SB_CASE(ccd_point_triangle_degenerate_cases),
        SB_CASE(moving_obstacle_sweep_and_triangle_depth), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
