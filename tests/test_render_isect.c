/* test_render_isect.c — the ray–patch algorithms of the BHEM paper's §5.1
 * (subdivision, subdivision + Newton, Bézier clipping) against each other
 * and against an analytic plane and cylinder: hit points, the first hit of
 * rays that cross a surface twice, grazing rays that hit and that miss, rays
 * from inside; the Bézier forms of bhem's Hermite patches and rmtr's
 * B-spline faces against their methods' own evaluation; the BVH world with
 * patches, triangles and obstacles. */
#include "sb_test.h"
#include "sb_render_world.h"
#include "sb_method.h"
#include "../methods/bhem/bhem.h"
#include "../methods/rmtr/cc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static double rnd(unsigned long long *st)   /* uniform in [0, 1) */
{
    *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*st >> 11) / 9007199254740992.0;
}

/* every algorithm, the textbook (depth-first, all roots) clipping too */
enum { NK = 4 };
static const sb_isect_kind KINDS[NK] = { SB_ISECT_SUBDIVISION, SB_ISECT_NEWTON, SB_ISECT_CLIPPING, SB_ISECT_CLIPPING_DFS };

/* ---- Bézier basics ---------------------------------------------------------- */

static void random_patch(unsigned long long *st, double *P)
{
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            P[3 * (i + 4 * j)] = i / 3.0 + 0.1 * (rnd(st) - 0.5);
            P[3 * (i + 4 * j) + 1] = j / 3.0 + 0.1 * (rnd(st) - 0.5);
            P[3 * (i + 4 * j) + 2] = 0.3 * (rnd(st) - 0.5);
        }
}

SB_TEST(bezier_eval_split_and_derivative_bounds)
{
    unsigned long long st = 7;
    double P[SB_BEZ_N], S[SB_BEZ_N];
    random_patch(&st, P);
    for (int k = 0; k < 20; k++) {
        const double u = rnd(&st), v = rnd(&st);
        double W[6][16], x[3], xu[3], xv[3], y[3] = { 0, 0, 0 }, yu[3] = { 0, 0, 0 }, yv[3] = { 0, 0, 0 };
        sb_bezier_basis(u, v, W);
        sb_bezier_eval(P, u, v, x, xu, xv);
        for (int I = 0; I < 16; I++)
            for (int c = 0; c < 3; c++) {
                y[c] += W[0][I] * P[3 * I + c];
                yu[c] += W[1][I] * P[3 * I + c];
                yv[c] += W[2][I] * P[3 * I + c];
            }
        for (int c = 0; c < 3; c++) {
            CHECK_NEAR(x[c], y[c], 1e-14);
            CHECK_NEAR(xu[c], yu[c], 1e-13);
            CHECK_NEAR(xv[c], yv[c], 1e-13);
        }
        /* derivative of the basis by finite differences */
        double Wp[6][16], Wm[6][16], h = 1e-6;
        sb_bezier_basis(u + h, v, Wp);
        sb_bezier_basis(u - h, v, Wm);
        for (int I = 0; I < 16; I++) {
            CHECK_NEAR(W[1][I], (Wp[0][I] - Wm[0][I]) / (2 * h), 1e-8);
            CHECK_NEAR(W[3][I], (Wp[1][I] - Wm[1][I]) / (2 * h), 1e-7);
            CHECK_NEAR(W[4][I], (Wp[2][I] - Wm[2][I]) / (2 * h), 1e-7);
        }
        /* a sub-patch is the same surface */
        const double u0 = 0.7 * rnd(&st), u1 = u0 + 0.01 + 0.29 * rnd(&st), v0 = 0.7 * rnd(&st), v1 = v0 + 0.3 * rnd(&st) + 1e-3;
        sb_bezier_sub(P, u0, u1, v0, v1, S);
        const double a = rnd(&st), b = rnd(&st);
        double p[3], q[3];
        sb_bezier_eval(S, a, b, p, NULL, NULL);
        sb_bezier_eval(P, u0 + a * (u1 - u0), v0 + b * (v1 - v0), q, NULL, NULL);
        for (int c = 0; c < 3; c++) CHECK_NEAR(p[c], q[c], 1e-13);
        /* the derivative bounds bound */
        double L[2], M[3];
        sb_bezier_derivative_bounds(P, L, M);
        CHECK(sqrt(xu[0] * xu[0] + xu[1] * xu[1] + xu[2] * xu[2]) <= L[0] + 1e-12);
        CHECK(sqrt(xv[0] * xv[0] + xv[1] * xv[1] + xv[2] * xv[2]) <= L[1] + 1e-12);
        double nuu = 0, nuv = 0, nvv = 0;
        for (int c = 0; c < 3; c++) {
            double s3 = 0, s4 = 0, s5 = 0;
            for (int I = 0; I < 16; I++) { s3 += W[3][I] * P[3 * I + c]; s4 += W[4][I] * P[3 * I + c]; s5 += W[5][I] * P[3 * I + c]; }
            nuu += s3 * s3; nuv += s4 * s4; nvv += s5 * s5;
        }
        CHECK(sqrt(nuu) <= M[0] + 1e-12);
        CHECK(sqrt(nuv) <= M[1] + 1e-12);
        CHECK(sqrt(nvv) <= M[2] + 1e-12);
    }
}

/* ---- the analytic plane ------------------------------------------------------ */

/* a plane patch with a non-affine parametrization: every control point in
 * z = a x + b y + c */
static void plane_patch(double *P, double a, double b, double c)
{
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const double x = i / 3.0 + (i == 1 ? 0.12 : i == 2 ? -0.05 : 0.0) + 0.04 * j * (3 - j);
            const double y = j / 3.0 + (j == 1 ? -0.08 : 0.0) + 0.03 * i;
            P[3 * (i + 4 * j)] = x;
            P[3 * (i + 4 * j) + 1] = y;
            P[3 * (i + 4 * j) + 2] = a * x + b * y + c;
        }
}

/* hit with each algorithm; returns the number that hit, t[k] per algorithm */
static int hit_all(sb_test_state *T, sb_bezier_ws *ws, const double *P, const sb_ray *r, double eps, double t[NK],
                   double x[NK][3])
{
    int n = 0;
    for (int k = 0; k < NK; k++) {
        sb_patch_hit h;
        int rc = sb_bezier_intersect(KINDS[k], P, NULL, NULL, r, INFINITY, eps, ws, &h);
        CHECK(rc >= 0);
        t[k] = rc > 0 ? h.t : NAN;
        if (rc > 0) {
            n++;
            sb_bezier_eval(P, h.u, h.v, x[k], NULL, NULL);
            CHECK_MSG(h.u >= 0 && h.u <= 1 && h.v >= 0 && h.v <= 1, "%s: (u,v) = (%g,%g) outside the patch",
                      sb_isect_names[k], h.u, h.v);
        }
    }
    return n;
}

SB_TEST(plane_hits_match_the_analytic_plane)
{
    const double a = 0.3, b = -0.2, c = 0.1, eps = 1e-7;
    double P[SB_BEZ_N];
    plane_patch(P, a, b, c);
    sb_bezier_ws *ws = sb_bezier_ws_new();
    unsigned long long st = 11;
    int hits = 0, misses = 0;
    for (int k = 0; k < 60; k++) {
        /* a point inside the patch and a direction from above, some grazing */
        const double u = 0.05 + 0.9 * rnd(&st), v = 0.05 + 0.9 * rnd(&st);
        double x[3];
        sb_bezier_eval(P, u, v, x, NULL, NULL);
        const double n[3] = { -a, -b, 1 };
        const double graze = k < 20 ? 1e-3 : 0.2 + rnd(&st);   /* elevation of the ray above the plane (rad) */
        const double az = 2 * M_PI * rnd(&st);
        double tan1[3] = { 1, 0, a }, tan2[3] = { 0, 1, b }, d[3];
        for (int q = 0; q < 3; q++) d[q] = -(cos(az) * tan1[q] + sin(az) * tan2[q]) * cos(graze) / sqrt(1 + a * a) - sin(graze) * n[q] / sqrt(a * a + b * b + 1);
        double o[3];
        for (int q = 0; q < 3; q++) o[q] = x[q] - 2.0 * d[q];
        sb_ray r;
        sb_ray_init(&r, o, d, 0.0, INFINITY);
        /* analytic: ((o + t d) - x).n = 0 */
        double on = 0, dn = 0;
        for (int q = 0; q < 3; q++) { on += (o[q] - x[q]) * n[q]; dn += r.d[q] * n[q]; }
        const double t_exact = -on / dn;
        double t[NK], xh[NK][3];
        int nh = hit_all(T, ws, P, &r, eps, t, xh);
        if (nh) hits++;
        CHECK_MSG(nh == NK, "ray %d (grazing %g): %d of %d algorithms hit", k, graze, nh, NK);
        for (int m = 0; m < NK && nh == NK; m++) {
            /* subdivision stops at the first box smaller than eps that the ray
             * enters: along a ray at angle theta to the surface, t is then
             * within eps / sin(theta), the point within eps of the surface */
            const double tt = (KINDS[m] == SB_ISECT_SUBDIVISION ? 2.0 / sin(graze) : 1.0) * 3 * eps;
            CHECK_MSG(fabs(t[m] - t_exact) <= tt, "%s, ray %d: t %.12g, exact %.12g", sb_isect_names[m], k, t[m], t_exact);
            for (int q = 0; q < 3; q++) CHECK_NEAR(xh[m][q], o[q] + t_exact * r.d[q], tt);
            double dn2 = 0;
            for (int q = 0; q < 3; q++) dn2 += (xh[m][q] - x[q]) * n[q];
            CHECK_NEAR(dn2 / sqrt(a * a + b * b + 1), 0.0, 1e-12);   /* x(u,v) is on the plane */
        }
        /* the same ray lifted just off the plane by 1e-4 along its normal, running parallel: no hit */
        double o2[3], d2[3];
        for (int q = 0; q < 3; q++) {
            d2[q] = cos(az) * tan1[q] + sin(az) * tan2[q];
            o2[q] = x[q] + 1e-4 * n[q] - 2.0 * d2[q];
        }
        sb_ray_init(&r, o2, d2, 0.0, INFINITY);
        nh = hit_all(T, ws, P, &r, eps, t, xh);
        if (nh == 0) misses++;
        CHECK_MSG(nh == 0, "parallel ray %d above the plane: %d algorithms report a hit", k, nh);
    }
    CHECK_EQ_INT(hits, 60);
    CHECK_EQ_INT(misses, 60);
    CHECK_EQ_INT(sb_bezier_ws_counts(ws)->budget, 0);
    sb_bezier_ws_free(ws);
}

/* ---- the analytic cylinder ----------------------------------------------------- */

/* x^2 + z^2 = R^2 (axis e_y, the scene chart's cylinder): arc [p0, p1] in
 * angle phi (x = R sin phi, z = R cos phi), y in [y0, y1]; cubic arcs with
 * the tangent length (4/3) tan(dphi/4) R */
static void cylinder_patch(double *P, double R, double p0, double p1, double y0, double y1)
{
    const double k = 4.0 / 3.0 * tan((p1 - p0) / 4.0);
    double arc[4][2] = { { R * sin(p0), R * cos(p0) }, { 0, 0 }, { 0, 0 }, { R * sin(p1), R * cos(p1) } };
    arc[1][0] = arc[0][0] + k * R * cos(p0);
    arc[1][1] = arc[0][1] - k * R * sin(p0);
    arc[2][0] = arc[3][0] - k * R * cos(p1);
    arc[2][1] = arc[3][1] + k * R * sin(p1);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            P[3 * (i + 4 * j)] = arc[i][0];
            P[3 * (i + 4 * j) + 1] = y0 + (y1 - y0) * j / 3.0;
            P[3 * (i + 4 * j) + 2] = arc[i][1];
        }
}

/* entry parameter of the ray into the cylinder (t > tmin), NAN if none */
static double cylinder_entry(const sb_ray *r, double R, double *t_far)
{
    const double A = r->d[0] * r->d[0] + r->d[2] * r->d[2], B = r->o[0] * r->d[0] + r->o[2] * r->d[2];
    const double C = r->o[0] * r->o[0] + r->o[2] * r->o[2] - R * R, disc = B * B - A * C;
    if (disc < 0 || A == 0) return NAN;
    const double t0 = (-B - sqrt(disc)) / A, t1 = (-B + sqrt(disc)) / A;
    if (t_far) *t_far = t1;
    return t0 > r->tmin ? t0 : t1 > r->tmin ? t1 : NAN;
}

#define NCYL 8
typedef struct cyl { double P[NCYL][SB_BEZ_N]; double R; } cyl;

static void make_cylinder(cyl *C, double R)
{
    C->R = R;
    for (int k = 0; k < NCYL; k++) cylinder_patch(C->P[k], R, 2 * M_PI * k / NCYL, 2 * M_PI * (k + 1) / NCYL, -1.0, 1.0);
}

/* the first hit over all patches with one algorithm */
static double cyl_first(const cyl *C, sb_isect_kind kind, const sb_ray *r, double eps, sb_bezier_ws *ws, double x[3])
{
    double best = INFINITY;
    for (int k = 0; k < NCYL; k++) {
        sb_patch_hit h;
        if (sb_bezier_intersect(kind, C->P[k], NULL, NULL, r, best, eps, ws, &h) > 0) {
            best = h.t;
            sb_bezier_eval(C->P[k], h.u, h.v, x, NULL, NULL);
        }
    }
    return isfinite(best) ? best : NAN;
}

SB_TEST(cylinder_first_hits_match_the_analytic_cylinder)
{
    cyl C;
    make_cylinder(&C, 1.0);
    /* radial error of the cubic 45-degree arcs */
    double rmax = 0;
    for (int i = 0; i <= 100; i++) {
        double x[3];
        sb_bezier_eval(C.P[0], i / 100.0, 0.5, x, NULL, NULL);
        rmax = fmax(rmax, fabs(hypot(x[0], x[2]) - 1.0));
    }
    CHECK_MSG(rmax < 2e-5, "arc approximation error %g", rmax);
    const double eps = 1e-7, tol = 4 * rmax + 3 * eps;
    sb_bezier_ws *ws = sb_bezier_ws_new();
    unsigned long long st = 5;
    for (int k = 0; k < 40; k++) {
        /* from outside through the cylinder: two crossings, the first counts */
        const double ang = 2 * M_PI * rnd(&st), off = 0.9 * (2 * rnd(&st) - 1), y = 0.8 * (2 * rnd(&st) - 1);
        const double o[3] = { 3 * cos(ang) - off * sin(ang), y, 3 * sin(ang) + off * cos(ang) };
        const double d[3] = { -cos(ang), 0.2 * (rnd(&st) - 0.5) - 0.3 * y, -sin(ang) };
        sb_ray r;
        sb_ray_init(&r, o, d, 0.0, INFINITY);
        double tfar, te = cylinder_entry(&r, 1.0, &tfar);
        for (int m = 0; m < NK; m++) {
            double x[3];
            double t = cyl_first(&C, KINDS[m], &r, eps, ws, x);
            if (!isfinite(te) || fabs(o[1] + tfar * r.d[1]) > 1.0) continue;   /* not two crossings inside y in [-1,1] */
            CHECK_MSG(fabs(t - te) <= tol * 10, "%s ray %d: first hit t %.10g, analytic entry %.10g (far %.10g)",
                      sb_isect_names[m], k, t, te, tfar);
            CHECK(t < tfar - 0.1);
            CHECK_NEAR(hypot(x[0], x[2]), 1.0, 4 * rmax + 3 * eps);
        }
    }
    /* from inside: the only crossing ahead */
    for (int k = 0; k < 10; k++) {
        const double o[3] = { 0.3 * (rnd(&st) - 0.5), 0.2, 0.3 * (rnd(&st) - 0.5) };
        const double a = 2 * M_PI * rnd(&st), d[3] = { cos(a), 0.1, sin(a) };
        sb_ray r;
        sb_ray_init(&r, o, d, 0.0, INFINITY);
        const double te = cylinder_entry(&r, 1.0, NULL);
        for (int m = 0; m < NK; m++) {
            double x[3];
            CHECK_NEAR(cyl_first(&C, KINDS[m], &r, eps, ws, x), te, 10 * tol);
        }
    }
    CHECK_EQ_INT(sb_bezier_ws_counts(ws)->budget, 0);
    sb_bezier_ws_free(ws);
}

SB_TEST(grazing_cylinder_rays_agree)
{
    /* rays at distance R (1 -+ delta) from the axis: just inside they cross
     * twice close together (the first counts), just outside they miss */
    cyl C;
    make_cylinder(&C, 1.0);
    const double eps = 1e-8;
    sb_bezier_ws *ws = sb_bezier_ws_new();
    unsigned long long st = 3;
    for (int k = 0; k < 24; k++) {
        const double ang = 2 * M_PI * rnd(&st), delta = k % 2 ? 2e-3 : -2e-3;
        const double off = 1.0 + delta;
        const double o[3] = { 3 * cos(ang) - off * sin(ang), 0.1, 3 * sin(ang) + off * cos(ang) };
        const double d[3] = { -cos(ang), 0, -sin(ang) };
        sb_ray r;
        sb_ray_init(&r, o, d, 0.0, INFINITY);
        double t[NK], x[NK][3], tfar;
        for (int m = 0; m < NK; m++) t[m] = cyl_first(&C, KINDS[m], &r, eps, ws, x[m]);
        /* the patches are the cylinder to within 2e-5 R: well inside the 2e-3 band */
        if (delta > 0) {
            for (int m = 0; m < NK; m++) CHECK_MSG(isnan(t[m]), "%s: grazing ray outside hits at t %g", sb_isect_names[m], t[m]);
            continue;
        }
        const double te = cylinder_entry(&r, 1.0, &tfar);
        for (int m = 0; m < NK; m++) {
            CHECK_MSG(isfinite(t[m]), "%s: grazing ray %d inside misses", sb_isect_names[m], k);
            /* the two crossings are 2 sqrt(2 delta) R apart: the first one */
            CHECK_MSG(fabs(t[m] - te) < 0.2 * (tfar - te), "%s ray %d: t %.9g, entry %.9g, exit %.9g", sb_isect_names[m], k,
                      t[m], te, tfar);
            CHECK_NEAR(t[m], t[0], 10 * eps + 1e-7);
        }
    }
    CHECK_EQ_INT(sb_bezier_ws_counts(ws)->budget, 0);
    sb_bezier_ws_free(ws);
}

SB_TEST(algorithms_agree_on_a_random_wavy_patch)
{
    /* a folded patch: rays can cross it up to several times */
    sb_bezier_ws *ws = sb_bezier_ws_new();
    unsigned long long st = 17;
    int hits = 0;
    for (int p = 0; p < 6; p++) {
        double P[SB_BEZ_N];
        random_patch(&st, P);
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++) P[3 * (i + 4 * j) + 2] += (i == 1 || i == 2 ? 0.6 : -0.2) * (p % 2 ? 1 : -1);
        for (int k = 0; k < 30; k++) {
            const double o[3] = { rnd(&st), rnd(&st), 2.0 };
            const double d[3] = { 0.8 * (rnd(&st) - 0.5), 0.8 * (rnd(&st) - 0.5), -1 };
            sb_ray r;
            sb_ray_init(&r, o, d, 0.0, INFINITY);
            double t[NK], x[NK][3];
            int n = hit_all(T, ws, P, &r, 1e-8, t, x);
            CHECK_MSG(n == 0 || n == NK, "patch %d ray %d: %d of %d hit", p, k, n, NK);
            if (n == NK) {
                hits++;
                for (int m = 1; m < NK; m++) CHECK_NEAR(t[m], t[0], 3e-8);
                for (int m = 0; m < NK; m++)
                    for (int q = 0; q < 3; q++) CHECK_NEAR(x[m][q], o[q] + t[m] * r.d[q], 3e-8);
            }
        }
    }
    CHECK(hits > 50);
    sb_bezier_ws_free(ws);
}

/* ---- methods' Bézier forms ------------------------------------------------------ */

static const char *CYL_SCENE =
    "{\"name\": \"cyl\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [4.18879020478639, 3]},"
    " \"geometry\": {\"type\": \"cylinder\", \"radius\": 2.0, \"angle\": [-60, 60], \"length\": 3.0},"
    " \"material\": {\"model\": \"stvk\", \"young\": 1e6, \"poisson\": 0.3, \"thickness\": 0.01, \"density\": 1},"
    " \"boundary\": [{\"type\": \"fixed\", \"on\": [\"bottom\"]}], \"loads\": [], \"time\": {\"mode\": \"quasi_static\", \"steps\": 1}}";

/* rebuild a method on the inline scene, surface of its reference state */
static int method_surface(const char *name, const char *json, int res, sb_scene *sc, void **state, sb_surface *s,
                          double **x)
{
    char err[512];
    if (sb_scene_parse_string(json, "inline.json", sc, err, sizeof err)) { printf("    %s\n", err); return -1; }
    const sb_method_type *mt = sb_method_find(name);
    sb_paramset ps;
    sb_paramset_init(&ps);
    sb_paramset_add(&ps, "method", mt->params);
    *state = calloc(1, mt->state_size);
    sb_method_config cfg = { res, 1, &ps, NULL, 0 };
    if (mt->create(*state, sc, &cfg)) return -1;
    const int n = mt->n_dofs(*state, 0);
    *x = malloc((size_t)n * sizeof **x);
    mt->initial(*state, 0, *x);
    /* a smooth deformation so that current and reference differ */
    for (int i = 0; i < n; i++) (*x)[i] *= 1.0 + 0.01 * sin(0.37 * i);
    memset(s, 0, sizeof *s);
    return mt->surface(*state, 0, *x, s);
}

/* the Bézier surface at (u,v) of patch e against eval_points at the (s,t)
 * its patch_st box gives (affine on these uniform grids) */
static void check_against_eval(sb_test_state *T, const char *name, const sb_surface *s, void *state, const double *x)
{
    const sb_method_type *mt = sb_method_find(name);
    unsigned long long st = 9;
    CHECK(s->patch_st != NULL);
    for (int k = 0; k < 40 && s->patch_st; k++) {
        const int e = (int)(rnd(&st) * s->n_patches);
        const double u = rnd(&st), v = rnd(&st), *b = s->patch_st + 4 * e;
        double pos[3], stp[2] = { b[0] + u * (b[1] - b[0]), b[2] + v * (b[3] - b[2]) };
        CHECK(mt->eval_points(state, 0, x, 1, stp, pos) == 0);
        double y[3];
        sb_bezier_eval(s->patch + (size_t)e * SB_BEZ_N, u, v, y, NULL, NULL);
        for (int c = 0; c < 3; c++)
            CHECK_MSG(fabs(y[c] - pos[c]) < 1e-11, "%s patch %d at (%g,%g): %.15g vs %.15g", name, e, u, v, y[c], pos[c]);
    }
}

SB_TEST(bhem_and_rmtr_patches_are_their_surfaces)
{
    const char *names[2] = { "bhem", "rmtr" };
    for (int m = 0; m < 2; m++) {
        sb_scene sc;
        void *state = NULL;
        double *x = NULL;
        sb_surface s;
        const sb_method_type *mt = sb_method_find(names[m]);
        int rc = method_surface(names[m], CYL_SCENE, 4, &sc, &state, &s, &x);
        CHECK_MSG(rc == 0, "%s: surface op failed", names[m]);
        if (rc == 0) {
            CHECK_EQ_INT(s.n_patches, 16);
            CHECK(s.patch_ref != NULL);
            check_against_eval(T, names[m], &s, state, x);
            /* the reference patches are the chart's cylinder, u along s (the angle) */
            double p[3], pu[3], pv[3];
            sb_bezier_eval(s.patch_ref + 5 * SB_BEZ_N, 0.3, 0.6, p, pu, pv);
            /* bhem interpolates the chart (30-degree patches: 3e-4 R); rmtr's limit
             * surface of a cage through the chart points lies inside it */
            CHECK_NEAR(hypot(p[0], p[2]), 2.0, m == 0 ? 1e-3 : 0.2);
            CHECK(pu[0] * p[2] - pu[2] * p[0] > 0);   /* d phi / du > 0 */
            CHECK(pv[1] > 0);
        }
        sb_surface_free(&s);
        if (state) { mt->destroy(state); free(state); }
        free(x);
        sb_scene_free(&sc);
    }
}

SB_TEST(bhem_cylinder_hits_the_analytic_cylinder)
{
    sb_scene sc;
    void *state = NULL;
    double *x = NULL;
    sb_surface s;
    CHECK(method_surface("bhem", CYL_SCENE, 6, &sc, &state, &s, &x) == 0);
    /* the reference patches: Hermite interpolant of the R = 2 cylinder */
    sb_render_options o;
    sb_render_options_default(&o);
    o.ground = 0;
    char err[256];
    memcpy(s.patch, s.patch_ref, (size_t)s.n_patches * SB_BEZ_N * sizeof(double));
    unsigned long long st = 21;
    for (int m = 0; m < NK; m++) {
        o.isect = KINDS[m];
        sb_world w;
        CHECK(sb_world_build(&w, &s, NULL, &o, err, sizeof err) == 0);
        for (int k = 0; k < 30; k++) {
            const double phi = (-50 + 100 * rnd(&st)) * M_PI / 180, y = 0.3 + 2.4 * rnd(&st);
            /* from above the roof, aimed at a point of it */
            const double tgt[3] = { 2 * sin(phi), y, 2 * cos(phi) }, o3[3] = { 0.3, 1.5, 6.0 };
            double d[3];
            for (int c = 0; c < 3; c++) d[c] = tgt[c] - o3[c];
            sb_ray r;
            sb_ray_init(&r, o3, d, 0.0, INFINITY);
            sb_hit h;
            CHECK(sb_world_intersect(&w, &r, INFINITY, 0, &h) == 1);
            CHECK_EQ_INT(h.kind, SB_HIT_PATCH);
            CHECK_NEAR(h.t, cylinder_entry(&r, 2.0, NULL), 2e-3);   /* oblique rays: t error = radial / cos */
            CHECK_NEAR(hypot(h.p[0], h.p[2]), 2.0, 2e-4);           /* Hermite interpolant of 20-degree arcs */
            CHECK_NEAR(hypot(h.n[0], h.n[2]), 1.0, 1e-3);   /* the normal is radial */
        }
        sb_world_free(&w);
    }
    sb_surface_free(&s);
    sb_method_find("bhem")->destroy(state);
    free(state);
    free(x);
    sb_scene_free(&sc);
}

/* ---- the world: triangles, obstacles, the BVH ---------------------------------- */

/* a triangulated sphere (latitude-longitude) of radius R about c */
static int sphere_mesh(sb_surface *s, const double c[3], double R, int nlat, int nlon)
{
    const int nv = (nlat + 1) * nlon, nt = 2 * nlat * nlon;
    if (sb_surface_alloc_tris(s, nv, nt, 0, 0)) return -1;
    for (int i = 0; i <= nlat; i++)
        for (int j = 0; j < nlon; j++) {
            const double th = M_PI * i / nlat, ph = 2 * M_PI * j / nlon;
            double *p = s->vert + 3 * (i * nlon + j);
            p[0] = c[0] + R * sin(th) * cos(ph);
            p[1] = c[1] + R * sin(th) * sin(ph);
            p[2] = c[2] + R * cos(th);
        }
    int t = 0;
    for (int i = 0; i < nlat; i++)
        for (int j = 0; j < nlon; j++) {
            const int a = i * nlon + j, b = i * nlon + (j + 1) % nlon, cc = a + nlon, d = b + nlon;
            int *T = s->tri + 3 * t;
            T[0] = a; T[1] = cc; T[2] = d; T[3] = a; T[4] = d; T[5] = b;
            t += 2;
        }
    return 0;
}

SB_TEST(triangle_world_with_obstacles)
{
    sb_surface s;
    memset(&s, 0, sizeof s);
    const double c[3] = { 0, 0, 0 };
    CHECK(sphere_mesh(&s, c, 1.0, 40, 80) == 0);
    sb_render_options o;
    sb_render_options_default(&o);
    o.ground = 0;
    o.n_obstacles = 2;
    o.obstacles[0].kind = SB_OBSTACLE_SPHERE;
    o.obstacles[0].c[0] = 3;
    o.obstacles[0].r = 0.5;
    o.obstacles[1].kind = SB_OBSTACLE_BOX;
    o.obstacles[1].lo[0] = -0.5; o.obstacles[1].lo[1] = -0.5; o.obstacles[1].lo[2] = -3;
    o.obstacles[1].hi[0] = 0.5; o.obstacles[1].hi[1] = 0.5; o.obstacles[1].hi[2] = -2;
    char err[256];
    sb_world w;
    CHECK(sb_world_build(&w, &s, NULL, &o, err, sizeof err) == 0);
    unsigned long long st = 2;
    const double chord = 1 - cos(M_PI / 40);   /* sagitta of the facets */
    for (int k = 0; k < 40; k++) {
        const double o3[3] = { -4, 0.8 * (rnd(&st) - 0.5), 0.8 * (rnd(&st) - 0.5) }, d[3] = { 1, 0, 0 };
        sb_ray r;
        sb_ray_init(&r, o3, d, 0.0, INFINITY);
        sb_hit h;
        CHECK(sb_world_intersect(&w, &r, INFINITY, 0, &h) == 1);
        CHECK_EQ_INT(h.kind, SB_HIT_TRIANGLE);
        const double te = -o3[0] - sqrt(1 - o3[1] * o3[1] - o3[2] * o3[2]);   /* first crossing */
        CHECK_NEAR(h.t, te, 3 * chord);
        CHECK(h.n[0] < 0);   /* the outward normal faces the ray */
    }
    /* behind the sphere along +x: the ball obstacle; below: the box */
    {
        const double o3[3] = { 2, 0, 0 }, d[3] = { 1, 0, 0 };
        sb_ray r;
        sb_ray_init(&r, o3, d, 0.0, INFINITY);
        sb_hit h;
        CHECK(sb_world_intersect(&w, &r, INFINITY, 0, &h) == 1);
        CHECK_EQ_INT(h.kind, SB_HIT_OBSTACLE);
        CHECK_NEAR(h.t, 0.5, 1e-12);
        CHECK_NEAR(h.n[0], -1.0, 1e-12);
        const double o4[3] = { 0, 0, -1.5 }, d4[3] = { 0, 0, -1 };
        sb_ray_init(&r, o4, d4, 0.0, INFINITY);
        CHECK(sb_world_intersect(&w, &r, INFINITY, 0, &h) == 1);
        CHECK_EQ_INT(h.kind, SB_HIT_OBSTACLE);
        CHECK_NEAR(h.t, 0.5, 1e-12);
        CHECK_NEAR(h.n[2], 1.0, 1e-12);
        /* shadow query: any occluder between */
        const double o5[3] = { 0, 0, 2 };
        sb_ray_init(&r, o5, d4, 0.0, INFINITY);
        CHECK(sb_world_intersect(&w, &r, INFINITY, 1, &h) == 1);
        const double d6[3] = { 0, 0, 1 };
        sb_ray_init(&r, o5, d6, 0.0, INFINITY);
        CHECK(sb_world_intersect(&w, &r, INFINITY, 1, &h) == 0);
    }
    sb_world_free(&w);
    /* curvature of the sphere mesh: H = -1/R with the outward normal */
    double *curv = malloc((size_t)s.n_verts * sizeof *curv), *vn = malloc((size_t)s.n_verts * 3 * sizeof *vn);
    for (int v = 0; v < s.n_verts; v++)
        for (int q = 0; q < 3; q++) vn[3 * v + q] = s.vert[3 * v + q];
    CHECK(sb_field_vertex_curvature(&s, vn, curv) == 0);
    const int v = 20 * 80 + 7;   /* on the equator */
    CHECK_NEAR(curv[v], -1.0, 0.01);
    free(curv);
    free(vn);
    sb_surface_free(&s);
}

SB_TEST(render_a_synthetic_triangle_sheet_to_png)
{
    /* a linear_fem-like surface: an indexed triangle list with reference and
     * grid parameters, uniformly stretched by 2 % along s: strain 0.02 */
    sb_surface s;
    memset(&s, 0, sizeof s);
    const int n = 9;
    CHECK(sb_surface_alloc_tris(&s, n * n, 2 * (n - 1) * (n - 1), 1, 1) == 0);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int v = i + n * j;
            const double a = (double)i / (n - 1), b = (double)j / (n - 1);
            s.vert_st[2 * v] = a; s.vert_st[2 * v + 1] = b;
            s.vert_ref[3 * v] = a; s.vert_ref[3 * v + 1] = b; s.vert_ref[3 * v + 2] = 0;
            s.vert[3 * v] = sqrt(1.04) * a; s.vert[3 * v + 1] = b; s.vert[3 * v + 2] = 0.1 * a * a;
        }
    int t = 0;
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            const int a = i + n * j, b = a + 1, c = a + n, d = c + 1;
            int *T = s.tri + 3 * t;
            T[0] = a; T[1] = b; T[2] = d; T[3] = a; T[4] = d; T[5] = c;
            t += 2;
        }
    sb_material_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.kind = SB_MAT_STVK;
    spec.young = 1e6;
    spec.poisson = 0.3;
    spec.thickness = 1e-3;
    spec.density = 0.1;
    sb_material mat;
    CHECK(sb_material_init(&mat, &spec, 0) == 0);
    sb_render_options o;
    sb_render_options_default(&o);
    o.width = 64;
    o.height = 48;
    o.spp = 2;
    o.color = SB_COLOR_STRAIN;
    snprintf(o.title, sizeof o.title, "synthetic");
    sb_image img;
    sb_render_stats st;
    char err[256];
    CHECK(sb_render_surface(&s, &mat, &o, &img, &st, err, sizeof err) == 0);
    /* E11 = (1.04 + (0.2 a)^2 - 1)/2 in [0.02, 0.04]: the scale lies inside */
    CHECK(st.field_lo >= 0.02 - 1e-9 && st.field_hi <= 0.04 + 1e-9 && st.field_hi > st.field_lo);
    CHECK_NEAR(st.field_min, 0.02, 1e-3);
    CHECK_NEAR(st.field_max, 0.04, 3e-3);   /* constant per triangle: the last column averages */
    CHECK(st.primary_rays == 64L * 48 * 2);
    CHECK(st.tri_tests > 0);
    char path[512];
    snprintf(path, sizeof path, "/tmp/sb_test_render_%d.png", (int)getpid());
    CHECK(sb_image_write_png(&img, path, 0, NULL, NULL, err, sizeof err) == 0);
    FILE *f = fopen(path, "rb");
    unsigned char sig[8] = { 0 };
    CHECK(f && fread(sig, 1, 8, f) == 8);
    if (f) fclose(f);
    CHECK(sig[0] == 137 && sig[1] == 'P' && sig[2] == 'N' && sig[3] == 'G');
    remove(path);
    /* the colours the surface cannot give are refused, with a reason */

    free(s.vert_ref);
    s.vert_ref = NULL;
    CHECK(sb_render_surface(&s, &mat, &o, &img, &st, err, sizeof err) == SB_ERR_INPUT);
    CHECK(strstr(err, "reference") != NULL);
    sb_image_free(&img);
    sb_surface_free(&s);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(bezier_eval_split_and_derivative_bounds), SB_CASE(plane_hits_match_the_analytic_plane),
        SB_CASE(cylinder_first_hits_match_the_analytic_cylinder), SB_CASE(grazing_cylinder_rays_agree),
        SB_CASE(algorithms_agree_on_a_random_wavy_patch), SB_CASE(bhem_and_rmtr_patches_are_their_surfaces),
        SB_CASE(bhem_cylinder_hits_the_analytic_cylinder), SB_CASE(triangle_world_with_obstacles),
        SB_CASE(render_a_synthetic_triangle_sheet_to_png), SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
