/* test_patch_ccd.c — the dynamic ray–patch intersection of BHEM §5.2
 * (core/contact/sb_patch_ccd.h) against cases with known times of impact:
 * a flat patch moving onto a static point (exact time), a static flat patch
 * and a moving point, a curved patch z = c u(1-u) v(1-v) translating
 * through a static point (t = z_p - z(u_p, v_p) over the speed), an oblique
 * point against that moving curved patch (reference by bisection on the
 * scalar height function), a tilting patch, grazing just above
 * and just below the crest, a point passing beside the patch, a point that
 * starts on the surface, and the Eq. 27 time interval. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sb_patch_ccd.h"
#include "sb_test.h"

/* control points of the graph z = c * u(1-u) * v(1-v) over [0,1]^2, shifted by dz:
 * u(1-u) has Bernstein coefficients (0, 1/3, 1/3, 0); x = u, y = v are linear */
static void curved_patch(double c, double dz, double *P)
{
    static const double b[4] = { 0, 1.0 / 3, 1.0 / 3, 0 };
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *p = P + 3 * (i + 4 * j);
            p[0] = i / 3.0;
            p[1] = j / 3.0;
            p[2] = c * b[i] * b[j] + dz;
        }
}

static double curved_z(double c, double u, double v) { return c * u * (1 - u) * v * (1 - v); }

static int ccd(const double *P0, const double *P1, const double p0[3], const double p1[3], sb_ccd_hit *h)
{
    sb_patch_ccd_ws *ws = sb_patch_ccd_ws_new();
    int rc = sb_patch_ccd(P0, P1, p0, p1, 1e-9, ws, h);
    sb_patch_ccd_ws_free(ws);
    return rc;
}

SB_TEST(flat_patch_onto_static_point)
{
    double P0[SB_BEZ_N], P1[SB_BEZ_N];
    curved_patch(0.0, 0.0, P0);   /* the plane z = 0 ... */
    curved_patch(0.0, 1.0, P1);   /* ... moving to z = 1 */
    const double pts[][3] = { { 0.5, 0.5, 0.25 }, { 0.1, 0.9, 0.7 }, { 0.0, 0.0, 0.5 }, { 1.0, 0.3, 1.0 } };
    for (int k = 0; k < 4; k++) {
        sb_ccd_hit h;
        CHECK_EQ_INT(ccd(P0, P1, pts[k], pts[k], &h), 1);
        CHECK_NEAR(h.t, pts[k][2], 1e-8);
        CHECK_NEAR(h.u, pts[k][0], 1e-6);
        CHECK_NEAR(h.v, pts[k][1], 1e-6);
    }
    /* above the final position: no hit; below the start: none either */
    const double up[3] = { 0.5, 0.5, 1.2 }, down[3] = { 0.5, 0.5, -0.1 };
    sb_ccd_hit h;
    CHECK_EQ_INT(ccd(P0, P1, up, up, &h), 0);
    CHECK_EQ_INT(ccd(P0, P1, down, down, &h), 0);
}

SB_TEST(static_patch_moving_point)
{
    double P[SB_BEZ_N];
    curved_patch(0.0, 0.0, P);
    const double a[3] = { 0.3, 0.6, 1.0 }, b[3] = { 0.5, 0.2, -3.0 };   /* crosses z = 0 at t = 1/4 */
    sb_ccd_hit h;
    CHECK_EQ_INT(ccd(P, P, a, b, &h), 1);
    CHECK_NEAR(h.t, 0.25, 1e-8);
    CHECK_NEAR(h.u, 0.35, 1e-6);
    CHECK_NEAR(h.v, 0.5, 1e-6);
    /* beside the patch (x > 1 throughout): a miss */
    const double c[3] = { 1.2, 0.5, 1.0 }, d[3] = { 1.1, 0.5, -1.0 };
    CHECK_EQ_INT(ccd(P, P, c, d, &h), 0);
    /* a point starting on the surface: t = 0 */
    const double e[3] = { 0.4, 0.4, 0.0 }, f[3] = { 0.4, 0.4, -1.0 };
    CHECK_EQ_INT(ccd(P, P, e, f, &h), 1);
    CHECK_NEAR(h.t, 0.0, 1e-8);
}

SB_TEST(curved_patch_translating)
{
    const double c = 2.0;
    double P0[SB_BEZ_N], P1[SB_BEZ_N];
    curved_patch(c, 0.0, P0);
    curved_patch(c, 0.5, P1);   /* speed 0.5 in z */
    const double pts[][2] = { { 0.5, 0.5 }, { 0.2, 0.7 }, { 0.9, 0.1 }, { 0.35, 0.45 } };
    for (int k = 0; k < 4; k++) {
        const double zs = curved_z(c, pts[k][0], pts[k][1]);
        const double p[3] = { pts[k][0], pts[k][1], zs + 0.3 };
        sb_ccd_hit h;
        CHECK_EQ_INT(ccd(P0, P1, p, p, &h), 1);
        CHECK_NEAR(h.t, 0.6, 1e-8);   /* 0.3 / 0.5 */
        CHECK_NEAR(h.u, pts[k][0], 1e-6);
        CHECK_NEAR(h.v, pts[k][1], 1e-6);
    }
}

/* height of the point over the moving curved patch: g(t) = p_z(t) - z(p_x(t), p_y(t)) - dz t */
static double gap(double c, double dz, const double a[3], const double b[3], double t)
{
    double x = a[0] + t * (b[0] - a[0]), y = a[1] + t * (b[1] - a[1]), z = a[2] + t * (b[2] - a[2]);
    return z - curved_z(c, x, y) - dz * t;
}

SB_TEST(oblique_point_moving_curved_patch)
{
    const double c = 3.0, dz = 0.4;
    double P0[SB_BEZ_N], P1[SB_BEZ_N];
    curved_patch(c, 0.0, P0);
    curved_patch(c, dz, P1);
    const double a[3] = { 0.1, 0.2, 0.5 }, b[3] = { 0.8, 0.7, 0.1 };
    /* reference: the first sign change of g on a fine grid, then bisection */
    double lo = 0, hi = 0;
    for (int i = 1; i <= 100000; i++)
        if (gap(c, dz, a, b, i * 1e-5) <= 0) { lo = (i - 1) * 1e-5; hi = i * 1e-5; break; }
    CHECK(hi > 0);
    for (int it = 0; it < 80; it++) {
        double m = 0.5 * (lo + hi);
        if (gap(c, dz, a, b, m) > 0) lo = m; else hi = m;
    }
    sb_ccd_hit h;
    CHECK_EQ_INT(ccd(P0, P1, a, b, &h), 1);
    CHECK_NEAR(h.t, lo, 1e-7);
    CHECK_NEAR(h.u, a[0] + lo * (b[0] - a[0]), 1e-6);
    CHECK_NEAR(h.v, a[1] + lo * (b[1] - a[1]), 1e-6);
}

SB_TEST(grazing_the_crest)
{
    /* static crest at z = c/16 at (0.5, 0.5); a horizontal path over it */
    const double c = 1.6, top = c / 16;
    double P[SB_BEZ_N];
    curved_patch(c, 0.0, P);
    sb_ccd_hit h;
    const double a1[3] = { -0.5, 0.5, top + 1e-4 }, b1[3] = { 1.5, 0.5, top + 1e-4 };
    CHECK_EQ_INT(ccd(P, P, a1, b1, &h), 0);   /* passes 1e-4 above */
    const double a2[3] = { -0.5, 0.5, top - 1e-4 }, b2[3] = { 1.5, 0.5, top - 1e-4 };
    CHECK_EQ_INT(ccd(P, P, a2, b2, &h), 1);   /* cuts the crest: enters where z(u, 1/2) = top - 1e-4 */
    /* z(u, 1/2) = (c/4) u (1-u) = top - 1e-4  ->  u = (1 - sqrt(1 - 16 (top - 1e-4)/c)) / 2 */
    const double u = 0.5 * (1 - sqrt(1 - 16 * (top - 1e-4) / c));
    CHECK_NEAR(h.t, (u + 0.5) / 2.0, 1e-7);
    /* touching exactly (within eps): a hit at the crest's time */
    const double a3[3] = { -0.5, 0.5, top }, b3[3] = { 1.5, 0.5, top };
    CHECK_EQ_INT(ccd(P, P, a3, b3, &h), 1);
    CHECK_NEAR(h.t, 0.5, 1e-3);
}

SB_TEST(tilting_patch)
{
    /* a patch that tilts while its control points move linearly (Eq. 25):
     * z = t (x - 0.25), point static at (0.75, 0.5, 0.2): z_patch = 0.5 t, hit at t = 0.4 */
    double P0[SB_BEZ_N], P1[SB_BEZ_N];
    curved_patch(0.0, 0.0, P0);
    curved_patch(0.0, 0.0, P1);
    for (int i = 0; i < 16; i++) P1[3 * i + 2] = P1[3 * i] - 0.25;
    const double p[3] = { 0.75, 0.5, 0.2 };
    sb_ccd_hit h;
    CHECK_EQ_INT(ccd(P0, P1, p, p, &h), 1);
    CHECK_NEAR(h.t, 0.4, 1e-8);
    /* the point at x = 0.1 is passed by the other side going down: z = t (0.1 - 0.25) = -0.15 t,
     * point at z = -0.1: t = 2/3 */
    const double q[3] = { 0.1, 0.5, -0.1 };
    CHECK_EQ_INT(ccd(P0, P1, q, q, &h), 1);
    CHECK_NEAR(h.t, 2.0 / 3.0, 1e-8);
}

SB_TEST(time_interval_eq27)
{
    /* a flat patch at z = 0 moving to z = 1 and the origin shifted: feasible exactly at z_p */
    double P0[SB_BEZ_N], P1[SB_BEZ_N], C0[SB_BEZ_N], C1[SB_BEZ_N];
    curved_patch(0.0, 0.0, P0);
    curved_patch(0.0, 1.0, P1);
    const double p[3] = { 0.5, 0.5, 0.3 };
    for (int i = 0; i < 16; i++)
        for (int k = 0; k < 3; k++) {
            C0[3 * i + k] = P0[3 * i + k] - p[k];
            C1[3 * i + k] = P1[3 * i + k] - p[k];
        }
    double t0, t1;
    CHECK_EQ_INT(sb_patch_ccd_times(C0, C1, 0.0, &t0, &t1), 1);
    CHECK_NEAR(t0, 0.3, 1e-14);
    CHECK_NEAR(t1, 0.3, 1e-14);
    CHECK_EQ_INT(sb_patch_ccd_times(C0, C1, 0.1, &t0, &t1), 1);
    CHECK_NEAR(t0, 0.2, 1e-14);
    CHECK_NEAR(t1, 0.4, 1e-14);
    /* outside in x: never feasible */
    for (int i = 0; i < 16; i++) { C0[3 * i] -= 2.0; C1[3 * i] -= 2.0; }
    CHECK_EQ_INT(sb_patch_ccd_times(C0, C1, 0.0, &t0, &t1), 0);
}

SB_TEST(newton_accelerates)
{
    /* with Newton the curved case needs far fewer regions than the 1e-9 tolerance would by halving */
    double P0[SB_BEZ_N], P1[SB_BEZ_N];
    curved_patch(2.0, 0.0, P0);
    curved_patch(2.0, 0.5, P1);
    const double p[3] = { 0.2, 0.7, curved_z(2.0, 0.2, 0.7) + 0.3 };
    sb_patch_ccd_ws *ws = sb_patch_ccd_ws_new();
    sb_ccd_hit h;
    CHECK_EQ_INT(sb_patch_ccd(P0, P1, p, p, 1e-9, ws, &h), 1);
    const sb_patch_ccd_counts *k = sb_patch_ccd_ws_counts(ws);
    CHECK(k->newton_roots >= 1);
    CHECK_MSG(k->regions < 200, "regions %ld", k->regions);
    CHECK_EQ_INT(k->budget, 0);
    sb_patch_ccd_ws_free(ws);
}

static const sb_test_case cases[] = {
    SB_CASE(flat_patch_onto_static_point), SB_CASE(static_patch_moving_point), SB_CASE(curved_patch_translating),
    SB_CASE(oblique_point_moving_curved_patch), SB_CASE(grazing_the_crest), SB_CASE(tilting_patch),
    SB_CASE(time_interval_eq27), SB_CASE(newton_accelerates), SB_END
};

int main(int argc, char **argv) { return sb_test_main(argc, argv, cases); }
