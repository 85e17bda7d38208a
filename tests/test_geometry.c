/* test_geometry.c — domain maps, charts and composite (s,t) -> X: exact
 * derivatives against central finite differences, unmap o map = id, L-shape
 * notch, named parts, sample grid, bounding box / diameter, rotations. */
#include <math.h>
#include <string.h>

#include "sb_geometry.h"
#include "sb_test.h"

#define PI 3.14159265358979323846

static sb_domain rect(void)
{
    sb_domain d;
    memset(&d, 0, sizeof d);
    d.kind = SB_DOMAIN_RECTANGLE;
    d.origin[0] = -0.3; d.origin[1] = 0.2;
    d.size[0] = 1.7;    d.size[1] = 0.9;
    return d;
}

static sb_domain lshape(int corner)
{
    sb_domain d = rect();
    d.kind = SB_DOMAIN_L_SHAPE;
    d.notch[0] = 0.51; d.notch[1] = 0.3;
    d.notch_corner = corner;
    return d;
}

static sb_domain annulus(double r_in, double r_out, double th0, double th1)
{
    sb_domain d;
    memset(&d, 0, sizeof d);
    d.kind = SB_DOMAIN_ANNULUS_SECTOR;
    d.center[0] = 0.4; d.center[1] = -1.1;
    d.r_in = r_in; d.r_out = r_out;
    d.theta[0] = th0; d.theta[1] = th1;
    return d;
}

/* central differences of a jet-valued map: first derivatives from x, second
 * from the exact first derivatives (both O(h^2)) */
static void check_jet2_fd(sb_test_state *T, const sb_domain *d, double s, double t)
{
    const double h = 1e-5;
    sb_jet2 J, a, b;
    sb_domain_map(d, s, t, &J);
    sb_domain_map(d, s + h, t, &a);
    sb_domain_map(d, s - h, t, &b);
    for (int k = 0; k < 2; k++) {
        CHECK_NEAR(J.d1[k], (a.x[k] - b.x[k]) / (2 * h), 1e-8);
        CHECK_NEAR(J.d11[k], (a.d1[k] - b.d1[k]) / (2 * h), 1e-7);
        CHECK_NEAR(J.d12[k], (a.d2[k] - b.d2[k]) / (2 * h), 1e-7);
    }
    sb_domain_map(d, s, t + h, &a);
    sb_domain_map(d, s, t - h, &b);
    for (int k = 0; k < 2; k++) {
        CHECK_NEAR(J.d2[k], (a.x[k] - b.x[k]) / (2 * h), 1e-8);
        CHECK_NEAR(J.d22[k], (a.d2[k] - b.d2[k]) / (2 * h), 1e-7);
        CHECK_NEAR(J.d12[k], (a.d1[k] - b.d1[k]) / (2 * h), 1e-7);
    }
}

SB_TEST(domain_map_derivatives)
{
    sb_domain ds[3] = { rect(), lshape(SB_CORNER_11), annulus(0.5, 1.3, 0.2, 2.9) };
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 5; k++) check_jet2_fd(T, &ds[i], 0.1 + 0.2 * k, 0.85 - 0.17 * k);
}

SB_TEST(domain_unmap_inverts_map)
{
    sb_domain ds[4] = { rect(), lshape(SB_CORNER_00), annulus(0.5, 1.3, -0.7, 2.9),
                        annulus(0.0, 2.0, 0.0, 2 * PI) };
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k <= 10; k++) {
            double st[2], s = k / 10.0, t = fmod(0.37 * k + 0.05, 1.0);
            sb_jet2 J;
            if (!sb_domain_contains_st(&ds[i], s, t)) continue;
            sb_domain_map(&ds[i], s, t, &J);
            CHECK_EQ_INT(sb_domain_unmap(&ds[i], J.x, st), 0);
            if (ds[i].kind == SB_DOMAIN_ANNULUS_SECTOR && ds[i].r_in == 0 && s == 0) continue; /* centre */
            CHECK_NEAR(st[0], s, 1e-12);
            if (ds[i].kind == SB_DOMAIN_ANNULUS_SECTOR && ds[i].theta[1] - ds[i].theta[0] == 2 * PI && t == 1)
                continue;   /* full circle: t = 1 is t = 0 */
            CHECK_NEAR(st[1], t, 1e-12);
        }
    }
    /* points outside */
    sb_domain a = annulus(0.5, 1.0, 0, PI / 2);
    double xi_out[4][2] = { { 0.4 + 1.2, -1.1 }, { 0.4 + 0.3, -1.1 + 0.1 }, { 0.4 - 0.7, -1.1 + 0.1 },
                            { 0.4 + 0.5, -1.1 - 0.5 } };
    for (int k = 0; k < 4; k++) {
        double st[2];
        CHECK_EQ_INT(sb_domain_unmap(&a, xi_out[k], st), 1);
    }
    /* boundary points (closed domain), including theta0 reached from below */
    double on[2] = { 0.4 + 0.75 * cos(-1e-15), -1.1 + 0.75 * sin(-1e-15) }, st[2];
    CHECK_EQ_INT(sb_domain_unmap(&a, on, st), 0);
    CHECK_NEAR(st[1], 0, 1e-12);
    sb_domain r = rect();
    double corner[2] = { r.origin[0] + r.size[0], r.origin[1] + r.size[1] };
    CHECK_EQ_INT(sb_domain_unmap(&r, corner, st), 0);
    CHECK_NEAR(st[0], 1, 1e-15);
    CHECK_NEAR(st[1], 1, 1e-15);
    double beyond[2] = { corner[0] + 1e-6, corner[1] };
    CHECK_EQ_INT(sb_domain_unmap(&r, beyond, st), 1);
}

SB_TEST(lshape_notch_and_contains)
{
    /* notch 0.51/1.7 = 0.3 in s, 0.3/0.9 = 1/3 in t */
    const int corners[4] = { SB_CORNER_00, SB_CORNER_10, SB_CORNER_11, SB_CORNER_01 };
    const double cs[4] = { 0, 1, 1, 0 }, ct[4] = { 0, 0, 1, 1 };
    for (int c = 0; c < 4; c++) {
        sb_domain d = lshape(corners[c]);
        double s01[2], t01[2];
        CHECK_EQ_INT(sb_domain_notch_st(&d, s01, t01), 1);
        CHECK_NEAR(s01[1] - s01[0], 0.3, 1e-12);
        CHECK_NEAR(t01[1] - t01[0], 1.0 / 3, 1e-12);
        /* the notched corner and a point near it are outside; the opposite corner is inside */
        CHECK(!sb_domain_contains_st(&d, cs[c], ct[c]));
        CHECK(!sb_domain_contains_st(&d, fabs(cs[c] - 0.1), fabs(ct[c] - 0.1)));
        CHECK(sb_domain_contains_st(&d, 1 - cs[c], 1 - ct[c]));
        /* the notch boundary belongs to the domain */
        double sb = cs[c] ? 0.7 : 0.3, tb = ct[c] ? 2.0 / 3 : 1.0 / 3;
        CHECK(sb_domain_contains_st(&d, sb, fabs(ct[c] - 0.05)));
        CHECK(sb_domain_contains_st(&d, fabs(cs[c] - 0.05), tb));
        CHECK(!sb_domain_contains_st(&d, sb + (cs[c] ? 1e-6 : -1e-6), fabs(ct[c] - 0.05)));
        /* xi inside the notch is rejected by unmap */
        sb_jet2 J;
        double st[2];
        sb_domain_map(&d, fabs(cs[c] - 0.1), fabs(ct[c] - 0.1), &J);
        CHECK_EQ_INT(sb_domain_unmap(&d, J.x, st), 1);
    }
    sb_domain r = rect();
    double s01[2], t01[2];
    CHECK_EQ_INT(sb_domain_notch_st(&r, s01, t01), 0);
    CHECK(!sb_domain_contains_st(&r, 1.01, 0.5));
    CHECK(!sb_domain_contains_st(&r, 0.5, -0.01));
    CHECK(sb_domain_contains_st(&r, 1, 0));
}

static sb_chart chart(sb_chart_kind k)
{
    sb_chart c;
    memset(&c, 0, sizeof c);
    c.kind = k;
    c.radius = 2.5;
    c.angle[0] = -0.3; c.angle[1] = 1.1;
    c.length = 3.0;
    c.polar[0] = 0.4; c.polar[1] = 2.0;
    c.azimuth[0] = -1.0; c.azimuth[1] = 2.2;
    return c;
}

SB_TEST(chart_derivatives)
{
    const double h = 1e-5;
    sb_domain ds[2] = { rect(), annulus(0.5, 1.3, 0.2, 2.9) };
    for (int kind = 0; kind < 3; kind++) {
        sb_chart c = chart((sb_chart_kind)kind);
        for (int di = 0; di < 2; di++) {
            double lo[2], hi[2];
            sb_domain_bbox(&ds[di], lo, hi);
            for (int p = 0; p < 4; p++) {
                double xi[2] = { lo[0] + (0.15 + 0.2 * p) * (hi[0] - lo[0]),
                                 lo[1] + (0.8 - 0.2 * p) * (hi[1] - lo[1]) };
                sb_jet3 J, a, b;
                sb_chart_eval(&c, &ds[di], xi, &J);
                for (int dir = 0; dir < 2; dir++) {
                    double xp[2] = { xi[0], xi[1] }, xm[2] = { xi[0], xi[1] };
                    xp[dir] += h;
                    xm[dir] -= h;
                    sb_chart_eval(&c, &ds[di], xp, &a);
                    sb_chart_eval(&c, &ds[di], xm, &b);
                    for (int k = 0; k < 3; k++) {
                        double fd = (a.x[k] - b.x[k]) / (2 * h);
                        CHECK_NEAR(dir ? J.d2[k] : J.d1[k], fd, 1e-7);
                        double fd1 = (a.d1[k] - b.d1[k]) / (2 * h), fd2 = (a.d2[k] - b.d2[k]) / (2 * h);
                        CHECK_NEAR(dir ? J.d12[k] : J.d11[k], fd1, 1e-6);
                        CHECK_NEAR(dir ? J.d22[k] : J.d12[k], fd2, 1e-6);
                    }
                }
            }
        }
    }
}

SB_TEST(chart_conventions)
{
    /* Scordelis-Lo quarter: domain = arc length x axial, chart isometric */
    sb_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.domain.kind = SB_DOMAIN_RECTANGLE;
    sc.domain.size[0] = 25 * 40 * PI / 180;
    sc.domain.size[1] = 25;
    sc.chart.kind = SB_CHART_CYLINDER;
    sc.chart.radius = 25;
    sc.chart.angle[1] = 40 * PI / 180;
    sc.chart.length = 25;
    double xi[2] = { 3.0, 7.0 };
    sb_jet3 X;
    sb_chart_eval(&sc.chart, &sc.domain, xi, &X);
    double n1 = sqrt(X.d1[0] * X.d1[0] + X.d1[1] * X.d1[1] + X.d1[2] * X.d1[2]);
    CHECK_NEAR(n1, 1, 1e-14);
    CHECK_NEAR(X.d2[1], 1, 1e-14);
    CHECK_NEAR(X.x[1], 7, 1e-14);
    CHECK_NEAR(hypot(X.x[0], X.x[2]), 25, 1e-12);
    /* crown (phi = 0) at (0, y, R); the free edge at phi = 40 deg */
    sb_geometry_eval_st(&sc, 0, 0.5, &X);
    CHECK_NEAR(X.x[0], 0, 1e-14);
    CHECK_NEAR(X.x[2], 25, 1e-12);
    sb_geometry_eval_st(&sc, 1, 0, &X);
    CHECK_NEAR(X.x[0], 25 * sin(40 * PI / 180), 1e-12);
    CHECK_NEAR(X.x[2], 25 * cos(40 * PI / 180), 1e-12);
    /* outward normal a1 x a2 = (sin phi, 0, cos phi) */
    double nx = X.d1[1] * X.d2[2] - X.d1[2] * X.d2[1], nz = X.d1[0] * X.d2[1] - X.d1[1] * X.d2[0];
    CHECK(nx > 0 && nz > 0);
    /* sphere normal points inwards (documented) */
    sb_chart s = chart(SB_CHART_SPHERE);
    sb_domain r = rect();
    double mid[2] = { 0.5, 0.6 };
    sb_chart_eval(&s, &r, mid, &X);
    double n[3] = { X.d1[1] * X.d2[2] - X.d1[2] * X.d2[1], X.d1[2] * X.d2[0] - X.d1[0] * X.d2[2],
                    X.d1[0] * X.d2[1] - X.d1[1] * X.d2[0] };
    CHECK(n[0] * X.x[0] + n[1] * X.x[1] + n[2] * X.x[2] < 0);
    CHECK_NEAR(sqrt(X.x[0] * X.x[0] + X.x[1] * X.x[1] + X.x[2] * X.x[2]), 2.5, 1e-12);
}

SB_TEST(composite_derivatives)
{
    const double h = 1e-5;
    sb_domain ds[2] = { lshape(SB_CORNER_10), annulus(0.4, 1.2, 0.3, 2.0) };
    for (int kind = 0; kind < 3; kind++) {
        for (int di = 0; di < 2; di++) {
            sb_scene sc;
            memset(&sc, 0, sizeof sc);
            sc.domain = ds[di];
            sc.chart = chart((sb_chart_kind)kind);
            for (int p = 0; p < 3; p++) {
                double s = 0.2 + 0.3 * p, t = 0.7 - 0.25 * p;
                sb_jet3 J, a, b, c, d;
                sb_geometry_eval_st(&sc, s, t, &J);
                sb_geometry_eval_st(&sc, s + h, t, &a);
                sb_geometry_eval_st(&sc, s - h, t, &b);
                sb_geometry_eval_st(&sc, s, t + h, &c);
                sb_geometry_eval_st(&sc, s, t - h, &d);
                for (int k = 0; k < 3; k++) {
                    CHECK_NEAR(J.d1[k], (a.x[k] - b.x[k]) / (2 * h), 1e-7);
                    CHECK_NEAR(J.d2[k], (c.x[k] - d.x[k]) / (2 * h), 1e-7);
                    CHECK_NEAR(J.d11[k], (a.d1[k] - b.d1[k]) / (2 * h), 1e-6);
                    CHECK_NEAR(J.d12[k], (a.d2[k] - b.d2[k]) / (2 * h), 1e-6);
                    CHECK_NEAR(J.d12[k], (c.d1[k] - d.d1[k]) / (2 * h), 1e-6);
                    CHECK_NEAR(J.d22[k], (c.d2[k] - d.d2[k]) / (2 * h), 1e-6);
                }
            }
        }
    }
}

SB_TEST(part_lookup)
{
    sb_domain r = rect(), a = annulus(0.5, 1, 0, 1);
    sb_part p;
    const char *const *names = sb_domain_part_names(SB_DOMAIN_RECTANGLE);
    int n = 0;
    for (; names[n]; n++) CHECK_EQ_INT(sb_domain_edge_part(&r, names[n], &p), SB_OK);
    CHECK_EQ_INT(n, 4);
    CHECK_EQ_INT(sb_domain_edge_part(&r, "inner", &p), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_domain_edge_part(&r, "notch_s", &p), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_domain_edge_part(&a, "left", &p), SB_ERR_INPUT);
    names = sb_domain_part_names(SB_DOMAIN_ANNULUS_SECTOR);
    for (n = 0; names[n]; n++) CHECK_EQ_INT(sb_domain_edge_part(&a, names[n], &p), SB_OK);
    CHECK_EQ_INT(n, 4);
    /* annulus: inner is s = 0, end is t = 1 */
    sb_domain_edge_part(&a, "inner", &p);
    CHECK(sb_part_contains_st(&p, 0, 0.4, 1e-12) && !sb_part_contains_st(&p, 0.01, 0.4, 1e-3));
    sb_domain_edge_part(&a, "end", &p);
    CHECK(sb_part_contains_st(&p, 0.3, 1, 1e-12) && !sb_part_contains_st(&p, 0.3, 0.9, 1e-3));
    CHECK_EQ_INT(strcmp(p.name, "end"), 0);
    CHECK_EQ_INT(p.kind, SB_PART_EDGE);

    /* L-shape, notch at corner 11 (s in [0.7,1], t in [2/3,1]) */
    sb_domain l = lshape(SB_CORNER_11);
    names = sb_domain_part_names(SB_DOMAIN_L_SHAPE);
    for (n = 0; names[n]; n++) CHECK_EQ_INT(sb_domain_edge_part(&l, names[n], &p), SB_OK);
    CHECK_EQ_INT(n, 6);
    sb_domain_edge_part(&l, "right", &p);      /* clipped: t in [0, 2/3] */
    CHECK(sb_part_contains_st(&p, 1, 0.5, 1e-12) && !sb_part_contains_st(&p, 1, 0.9, 1e-12));
    sb_domain_edge_part(&l, "top", &p);        /* clipped: s in [0, 0.7] */
    CHECK(sb_part_contains_st(&p, 0.6, 1, 1e-12) && !sb_part_contains_st(&p, 0.8, 1, 1e-12));
    sb_domain_edge_part(&l, "left", &p);       /* full */
    CHECK(sb_part_contains_st(&p, 0, 0.0, 1e-12) && sb_part_contains_st(&p, 0, 1.0, 1e-12));
    sb_domain_edge_part(&l, "notch_s", &p);    /* s = 0.7, t in [2/3, 1] */
    CHECK(sb_part_contains_st(&p, 0.7, 0.9, 1e-9) && !sb_part_contains_st(&p, 0.7, 0.5, 1e-9));
    CHECK_NEAR(p.st0[0], 0.7, 1e-12);
    sb_domain_edge_part(&l, "notch_t", &p);    /* t = 2/3, s in [0.7, 1] */
    CHECK(sb_part_contains_st(&p, 0.85, 2.0 / 3, 1e-9) && !sb_part_contains_st(&p, 0.5, 2.0 / 3, 1e-9));
    /* corner 00: left clipped from below, notch_s at s = 0.3 */
    l = lshape(SB_CORNER_00);
    sb_domain_edge_part(&l, "left", &p);
    CHECK(sb_part_contains_st(&p, 0, 0.5, 1e-12) && !sb_part_contains_st(&p, 0, 0.1, 1e-12));
    sb_domain_edge_part(&l, "bottom", &p);
    CHECK(sb_part_contains_st(&p, 0.5, 0, 1e-12) && !sb_part_contains_st(&p, 0.1, 0, 1e-12));
    sb_domain_edge_part(&l, "notch_s", &p);
    CHECK_NEAR(p.st0[0], 0.3, 1e-12);
    CHECK(sb_part_contains_st(&p, 0.3, 0.2, 1e-9) && !sb_part_contains_st(&p, 0.3, 0.5, 1e-9));
    /* a point part */
    memset(&p, 0, sizeof p);
    p.kind = SB_PART_POINT;
    p.st[0] = 0.25; p.st[1] = 0.5;
    CHECK(sb_part_contains_st(&p, 0.25, 0.5 + 1e-10, 1e-9) && !sb_part_contains_st(&p, 0.26, 0.5, 1e-3));
}

SB_TEST(sample_grid)
{
    sb_domain r = rect(), l = lshape(SB_CORNER_11);
    double st[2 * 121];
    CHECK_EQ_INT(sb_domain_sample_grid(&r, 11, st, 121), 121);
    CHECK_NEAR(st[2 * 120], 1, 0);
    CHECK_NEAR(st[2 * 120 + 1], 1, 0);
    /* notch s in (0.7, 1], t in (2/3, 1]: strictly inside for s in {0.8, 0.9, 1}
     * and t in {0.7, 0.8, 0.9, 1} -> 12 points removed */
    int n = sb_domain_sample_grid(&l, 11, st, 121);
    CHECK_EQ_INT(n, 121 - 12);
    for (int i = 0; i < n; i++) CHECK(sb_domain_contains_st(&l, st[2 * i], st[2 * i + 1]));
    CHECK_EQ_INT(sb_domain_sample_grid(&r, 11, st, 5), 121);   /* count beyond max */
    CHECK_EQ_INT(sb_domain_sample_grid(&r, 1, st, 1), 1);
    CHECK_NEAR(st[0], 0.5, 0);
    CHECK_EQ_INT(sb_domain_sample_grid(&r, 0, st, 1), 0);
}

SB_TEST(bbox_and_diameter)
{
    double lo[2], hi[2];
    sb_domain q = annulus(0.5, 1, 0, PI / 2);
    sb_domain_bbox(&q, lo, hi);
    CHECK_NEAR(lo[0], 0.4, 1e-15);
    CHECK_NEAR(hi[0], 1.4, 1e-15);
    CHECK_NEAR(lo[1], -1.1, 1e-15);
    CHECK_NEAR(hi[1], -0.1, 1e-15);
    CHECK_NEAR(sb_domain_diameter(&q), sqrt(2.0), 1e-14);
    sb_domain r = rect();
    CHECK_NEAR(sb_domain_diameter(&r), hypot(1.7, 0.9), 1e-15);
    sb_domain l = lshape(SB_CORNER_01);
    CHECK_NEAR(sb_domain_diameter(&l), hypot(1.7, 0.9), 1e-15);
    /* brute force over sampled points for a few sectors */
    const double secs[4][4] = { { 0.5, 1, 0.2, 0.5 }, { 0.9, 1, -0.3, 1.0 }, { 0, 2, 0.5, 5.0 },
                                { 0.3, 0.6, 1.0, 3.5 } };
    for (int k = 0; k < 4; k++) {
        sb_domain a = annulus(secs[k][0], secs[k][1], secs[k][2], secs[k][3]);
        double best = 0, blo[2] = { 1e9, 1e9 }, bhi[2] = { -1e9, -1e9 };
        enum { N = 60 };
        double P[4 * N][2];
        int np = 0;
        for (int i = 0; i < N; i++) {   /* boundary: both arcs and both radial edges */
            double f = (double)i / (N - 1);
            sb_jet2 J;
            double sts[4][2] = { { 0, f }, { 1, f }, { f, 0 }, { f, 1 } };
            for (int e = 0; e < 4; e++) {
                sb_domain_map(&a, sts[e][0], sts[e][1], &J);
                P[np][0] = J.x[0];
                P[np][1] = J.x[1];
                for (int c = 0; c < 2; c++) {
                    blo[c] = fmin(blo[c], J.x[c]);
                    bhi[c] = fmax(bhi[c], J.x[c]);
                }
                np++;
            }
        }
        for (int i = 0; i < np; i++)
            for (int j = i + 1; j < np; j++) best = fmax(best, hypot(P[i][0] - P[j][0], P[i][1] - P[j][1]));
        double dia = sb_domain_diameter(&a);
        CHECK(best <= dia * (1 + 1e-12));
        CHECK_REL(best, dia, 2e-3);
        sb_domain_bbox(&a, lo, hi);
        for (int c = 0; c < 2; c++) {
            CHECK(lo[c] <= blo[c] + 1e-12 && hi[c] >= bhi[c] - 1e-12);
            CHECK_NEAR(lo[c], blo[c], 2e-3);
            CHECK_NEAR(hi[c], bhi[c], 2e-3);
        }
    }
}

SB_TEST(rotation)
{
    double R[9], ax[3] = { 0, 0, 2 }, zero[3] = { 0, 0, 0 };
    sb_rotation(ax, PI / 2, R);
    /* e_x -> e_y about +z */
    CHECK_NEAR(R[0], 0, 1e-15);
    CHECK_NEAR(R[3], 1, 1e-15);
    CHECK_NEAR(R[6], 0, 1e-15);
    double g[3] = { 1, -2, 0.5 };
    sb_rotation(g, 0.7, R);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double dot = 0;
            for (int k = 0; k < 3; k++) dot += R[3 * k + i] * R[3 * k + j];
            CHECK_NEAR(dot, i == j, 1e-14);
        }
    double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                 R[2] * (R[3] * R[7] - R[4] * R[6]);
    CHECK_NEAR(det, 1, 1e-14);
    /* the axis is fixed */
    double n = sqrt(1 + 4 + 0.25);
    for (int i = 0; i < 3; i++)
        CHECK_NEAR(R[3 * i] * g[0] + R[3 * i + 1] * g[1] + R[3 * i + 2] * g[2], g[i], 1e-14 * n);
    sb_rotation(zero, 1.0, R);
    for (int i = 0; i < 9; i++) CHECK_NEAR(R[i], i % 4 == 0, 0);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(domain_map_derivatives), SB_CASE(domain_unmap_inverts_map),
        SB_CASE(lshape_notch_and_contains), SB_CASE(chart_derivatives),
        SB_CASE(chart_conventions), SB_CASE(composite_derivatives),
        SB_CASE(part_lookup), SB_CASE(sample_grid),
        SB_CASE(bbox_and_diameter), SB_CASE(rotation), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
