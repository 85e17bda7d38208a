/* sb_obstacle.c — poses, signed distances (with exact derivatives) and
 * closed-form times of impact of the analytic obstacles, and the
 * point–triangle distance of mesh obstacles (sb_obstacle.h). */
#include "sb_obstacle.h"
#include "sb_geometry.h"
#include "sb_self_geom.h"
#include "sb_bridson.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void sb_pose_at(const sb_obstacle_spec *o, double f, sb_pose *P)
{
    /* Rodrigues: R = cos th I + sin th [k]x + (1 - cos th) k k^T, th = f angle
     * (the moving-boundary convention of sb_scene.h: x = c + R(X - c) + f t) */
    const double th = f * o->rot_angle, C = cos(th), S = sin(th), *k = o->rot_axis;
    double *R = P->R;
    R[0] = C + (1 - C) * k[0] * k[0];        R[1] = (1 - C) * k[0] * k[1] - S * k[2]; R[2] = (1 - C) * k[0] * k[2] + S * k[1];
    R[3] = (1 - C) * k[1] * k[0] + S * k[2]; R[4] = C + (1 - C) * k[1] * k[1];        R[5] = (1 - C) * k[1] * k[2] - S * k[0];
    R[6] = (1 - C) * k[2] * k[0] - S * k[1]; R[7] = (1 - C) * k[2] * k[1] + S * k[0]; R[8] = C + (1 - C) * k[2] * k[2];
    for (int i = 0; i < 3; i++) {
        P->c[i] = o->rot_center[i];
        P->t[i] = f * o->translation[i];
    }
}

void sb_pose_rotate(const sb_pose *P, const double u[3], double v[3])
{
    for (int i = 0; i < 3; i++) v[i] = P->R[3 * i] * u[0] + P->R[3 * i + 1] * u[1] + P->R[3 * i + 2] * u[2];
}

void sb_pose_apply(const sb_pose *P, const double y[3], double x[3])
{
    double u[3] = { y[0] - P->c[0], y[1] - P->c[1], y[2] - P->c[2] }, v[3];
    sb_pose_rotate(P, u, v);
    for (int i = 0; i < 3; i++) x[i] = P->c[i] + v[i] + P->t[i];
}

void sb_pose_inverse(const sb_pose *P, const double x[3], double y[3])
{
    double u[3] = { x[0] - P->c[0] - P->t[0], x[1] - P->c[1] - P->t[1], x[2] - P->c[2] - P->t[2] };
    for (int i = 0; i < 3; i++) y[i] = P->c[i] + P->R[i] * u[0] + P->R[3 + i] * u[1] + P->R[6 + i] * u[2];
}

/* g = w/r, H = (Pm - g g^T)/r with Pm the projector of the free directions
 * (identity for a point, I - e e^T for a line): the derivatives of r = |Pm y|. */
static double radial(const double w[3], const double *Pm, double *g, double *H)
{
    double r = sqrt(dot3(w, w));
    if (g)
        for (int i = 0; i < 3; i++) g[i] = r > 0 ? w[i] / r : 0.0;
    if (H)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                H[3 * i + j] = r > 0 ? ((Pm ? Pm[3 * i + j] : (double)(i == j)) - g[i] * g[j]) / r : 0.0;
    return r;
}

/* the rest-frame derivatives g, H mapped to the world: R g, R H R^T */
static void to_world(const sb_pose *P, double *g, double *H)
{
    if (g) {
        double u[3] = { g[0], g[1], g[2] };
        sb_pose_rotate(P, u, g);
    }
    if (H) {
        double T[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double s = 0;
                for (int k = 0; k < 3; k++) s += P->R[3 * i + k] * H[3 * k + j];
                T[3 * i + j] = s;
            }
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double s = 0;
                for (int k = 0; k < 3; k++) s += T[3 * i + k] * P->R[3 * j + k];
                H[3 * i + j] = s;
            }
    }
}

double sb_obstacle_phi(const sb_obstacle_spec *o, const sb_pose *P, const double x[3], double *g, double *H)
{
    double y[3], w[3], phi = 0;
    sb_pose_inverse(P, x, y);
    if (H) memset(H, 0, 9 * sizeof *H);
    switch (o->kind) {
    case SB_OBST_SPHERE:   /* phi = |y - c| - r */
        for (int i = 0; i < 3; i++) w[i] = y[i] - o->center[i];
        phi = radial(w, NULL, g, H) - o->radius;
        break;
    case SB_OBST_PLANE:    /* phi = n . (y - p) */
        for (int i = 0; i < 3; i++) w[i] = y[i] - o->point[i];
        phi = dot3(o->normal, w);
        if (g) memcpy(g, o->normal, 3 * sizeof *g);
        break;
    case SB_OBST_CAPSULE: {   /* phi = |y - q(y)| - r, q the closest point of the axis segment */
        double e[3], L2 = 0, Pm[9];
        for (int i = 0; i < 3; i++) { e[i] = o->b[i] - o->a[i]; L2 += e[i] * e[i]; w[i] = y[i] - o->a[i]; }
        double s = dot3(w, e) / L2;
        const double *Pp = NULL;
        if (s <= 0) s = 0;
        else if (s >= 1) s = 1;
        else {
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) Pm[3 * i + j] = (double)(i == j) - e[i] * e[j] / L2;
            Pp = Pm;
        }
        for (int i = 0; i < 3; i++) w[i] -= s * e[i];
        phi = radial(w, Pp, g, H) - o->radius;
        break;
    }
    case SB_OBST_BOX: {       /* q_k = |y_k - c_k| - h_k; outside: phi = |max(q, 0)|, inside: max q_k */
        double q[3], sg[3], Pm[9] = { 0 };
        int out = 0, kmax = 0;
        for (int i = 0; i < 3; i++) {
            double u = y[i] - o->center[i];
            sg[i] = u >= 0 ? 1.0 : -1.0;
            q[i] = fabs(u) - o->half[i];
            if (q[i] > q[kmax]) kmax = i;
            out |= q[i] > 0;
        }
        if (out) {
            for (int i = 0; i < 3; i++) {
                w[i] = q[i] > 0 ? sg[i] * q[i] : 0.0;
                Pm[4 * i] = q[i] > 0 ? 1.0 : 0.0;
            }
            phi = radial(w, Pm, g, H);
        } else {
            phi = q[kmax];
            if (g) { g[0] = g[1] = g[2] = 0; g[kmax] = sg[kmax]; }
        }
        break;
    }
    case SB_OBST_MESH:
        phi = INFINITY;   /* meshes are handled per triangle (sb_point_triangle_distance) */
        if (g) g[0] = g[1] = g[2] = 0;
        break;
    }
    to_world(P, g, H);
    return phi;
}

/* closest point of triangle abc to x (Ericson, Real-Time Collision
 * Detection, §5.1.5), as the feature: 0 face, 1..3 edge ab/bc/ca, 4..6
 * vertex a/b/c */
double sb_point_triangle_distance(const double x[3], const double a[3], const double b[3], const double c[3],
                                  double *g, double *H)
{
    double ab[3], ac[3], ap[3], bp[3], cp[3], w[3];
    for (int i = 0; i < 3; i++) {
        ab[i] = b[i] - a[i]; ac[i] = c[i] - a[i];
        ap[i] = x[i] - a[i]; bp[i] = x[i] - b[i]; cp[i] = x[i] - c[i];
    }
    const double d1 = dot3(ab, ap), d2 = dot3(ac, ap), d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    const double *p0 = NULL, *e = NULL;
    double Pm[9];
    if (d1 <= 0 && d2 <= 0) p0 = a;
    else if (d3 >= 0 && d4 <= d3) p0 = b;
    else if (d6 >= 0 && d5 <= d6) p0 = c;
    else if (vc <= 0 && d1 >= 0 && d3 <= 0) { p0 = a; e = ab; }
    else if (vb <= 0 && d2 >= 0 && d6 <= 0) { p0 = a; e = ac; }
    else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        double bc[3] = { c[0] - b[0], c[1] - b[1], c[2] - b[2] }, L2 = dot3(bc, bc);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) Pm[3 * i + j] = (double)(i == j) - bc[i] * bc[j] / L2;
        for (int i = 0; i < 3; i++) w[i] = bp[i] - dot3(bp, bc) / L2 * bc[i];
        return radial(w, Pm, g, H);
    } else {
        /* face: |n . (x - a)| */
        double n[3] = { ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0] };
        double nn = sqrt(dot3(n, n));
        for (int i = 0; i < 3; i++) n[i] /= nn;
        double s = dot3(n, ap), sg = s >= 0 ? 1.0 : -1.0;
        if (g)
            for (int i = 0; i < 3; i++) g[i] = sg * n[i];
        if (H) memset(H, 0, 9 * sizeof *H);
        return fabs(s);
    }
    if (e) {
        double L2 = dot3(e, e);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) Pm[3 * i + j] = (double)(i == j) - e[i] * e[j] / L2;
        double u[3] = { x[0] - p0[0], x[1] - p0[1], x[2] - p0[2] }, s = dot3(u, e) / L2;
        for (int i = 0; i < 3; i++) w[i] = u[i] - s * e[i];
        return radial(w, Pm, g, H);
    }
    for (int i = 0; i < 3; i++) w[i] = x[i] - p0[i];
    return radial(w, NULL, g, H);
}

/* smallest root in [0, 1] of A t^2 + B t + C (C > 0: starts outside) */
static double first_root(double A, double B, double C)
{
    if (C <= 0) return 0.0;
    if (A == 0) return B < 0 ? -C / B : 2.0;
    double disc = B * B - 4 * A * C;
    if (disc < 0) return 2.0;
    double sq = sqrt(disc);
    /* the numerically stable pair (Press et al., Numerical Recipes §5.6) */
    double q = -0.5 * (B + (B >= 0 ? sq : -sq));
    double r1 = q / A, r2 = q != 0 ? C / q : r1;
    double lo = fmin(r1, r2), hi = fmax(r1, r2), t = lo >= 0 ? lo : hi;
    return t >= 0 && t <= 1 ? t : 2.0;
}

static double toi_sphere(const double y[3], const double d[3], const double c[3], double r)
{
    double w[3] = { y[0] - c[0], y[1] - c[1], y[2] - c[2] };
    return first_root(dot3(d, d), 2 * dot3(w, d), dot3(w, w) - r * r);
}

double sb_obstacle_toi(const sb_obstacle_spec *o, const sb_pose *P, const double x[3], const double d[3])
{
    double y[3], dr[3], x1[3], y1[3];
    sb_pose_inverse(P, x, y);
    for (int i = 0; i < 3; i++) x1[i] = x[i] + d[i];
    sb_pose_inverse(P, x1, y1);
    for (int i = 0; i < 3; i++) dr[i] = y1[i] - y[i];   /* the motion in the rest frame */
    switch (o->kind) {
    case SB_OBST_SPHERE:
        return toi_sphere(y, dr, o->center, o->radius);
    case SB_OBST_PLANE: {
        double w[3] = { y[0] - o->point[0], y[1] - o->point[1], y[2] - o->point[2] };
        double f0 = dot3(o->normal, w), v = dot3(o->normal, dr);
        if (v >= 0) return 2.0;
        double t = f0 / -v;
        return t <= 1 ? fmax(t, 0.0) : 2.0;
    }
    case SB_OBST_BOX: {   /* slabs (Kay & Kajiya) */
        double t0 = 0, t1 = 1;
        for (int i = 0; i < 3; i++) {
            double lo = o->center[i] - o->half[i], hi = o->center[i] + o->half[i];
            if (dr[i] == 0) {
                if (y[i] < lo || y[i] > hi) return 2.0;
                continue;
            }
            double ta = (lo - y[i]) / dr[i], tb = (hi - y[i]) / dr[i];
            if (ta > tb) { double s = ta; ta = tb; tb = s; }
            t0 = fmax(t0, ta);
            t1 = fmin(t1, tb);
            if (t0 > t1) return 2.0;
        }
        return t0;
    }
    case SB_OBST_CAPSULE: {
        /* the end spheres, and the cylinder part: |w_perp(t)|^2 = r^2 with
         * the axial coordinate in [0, L] at that time */
        double t = fmin(toi_sphere(y, dr, o->a, o->radius), toi_sphere(y, dr, o->b, o->radius));
        double e[3], w[3], L2 = 0;
        for (int i = 0; i < 3; i++) { e[i] = o->b[i] - o->a[i]; L2 += e[i] * e[i]; w[i] = y[i] - o->a[i]; }
        double we = dot3(w, e) / L2, de = dot3(dr, e) / L2, wp[3], dp[3];
        for (int i = 0; i < 3; i++) { wp[i] = w[i] - we * e[i]; dp[i] = dr[i] - de * e[i]; }
        double C = dot3(wp, wp) - o->radius * o->radius;   /* C <= 0: within the axis' reach, the caps decide */
        double tc = C > 0 ? first_root(dot3(dp, dp), 2 * dot3(wp, dp), C) : 2.0;
        if (tc <= 1) {
            double s = we + tc * de;
            if (s >= 0 && s <= 1) t = fmin(t, tc);
        }
        return t;
    }
    case SB_OBST_MESH:
        break;
    }
    return 2.0;
}

/* ---- a static point against an obstacle moving over a step -------------- */

/* The obstacle moves from factor fa to fb; seen from its rest frame the
 * static world point x travels on y(f) = c + R(f angle)^T (x - c - f t)
 * (sb_pose_inverse).  For a translation y is linear in f and one segment is
 * exact.  With a rotation y is followed by chords of n pieces; a chord of a
 * C2 curve over a piece of length h deviates from it by at most
 * h^2/8 max|y''| (linear interpolation error), and
 * |y''| <= th^2 |x - c - f t| + 2 th |t| (th = angle, t = translation), so
 * n is chosen to keep that below tol (at most 4096 pieces). */
static int sweep_pieces(const sb_obstacle_spec *o, double fa, double fb, const double x[3], double tol)
{
    const double th = fabs(o->rot_angle), df = fabs(fb - fa);
    if (th == 0 || df == 0) return 1;
    const double tn = sqrt(dot3(o->translation, o->translation));
    double u = 0;
    for (int i = 0; i < 3; i++) u += (x[i] - o->rot_center[i]) * (x[i] - o->rot_center[i]);
    u = sqrt(u) + tn;   /* |x - c - f t| <= |x - c| + |t| for f in [0, 1] */
    const double ypp = th * th * u + 2 * th * tn;
    double n = ceil(df * sqrt(ypp / (8 * tol)));
    if (!(n >= 1)) n = 1;
    return n > 4096 ? 4096 : (int)n;
}

double sb_obstacle_sweep(const sb_obstacle_spec *o, double fa, double fb, const double x[3], double tol)
{
    if (fa == fb) return 2.0;
    sb_pose rest, P;
    sb_pose_at(o, 0.0, &rest);   /* identity: the rest frame */
    const int n = sweep_pieces(o, fa, fb, x, tol);
    double y0[3], y1[3];
    sb_pose_at(o, fa, &P);
    sb_pose_inverse(&P, x, y0);
    if (o->kind != SB_OBST_MESH && sb_obstacle_phi(o, &rest, y0, NULL, NULL) <= 0) return 0.0;
    for (int k = 0; k < n; k++) {
        sb_pose_at(o, fa + (fb - fa) * (k + 1) / n, &P);
        sb_pose_inverse(&P, x, y1);
        double d[3] = { y1[0] - y0[0], y1[1] - y0[1], y1[2] - y0[2] }, t = 2.0;
        if (o->kind != SB_OBST_MESH) {
            t = sb_obstacle_toi(o, &rest, y0, d);
        } else {
            double lo[3], hi[3];
            for (int i = 0; i < 3; i++) { lo[i] = fmin(y0[i], y1[i]); hi[i] = fmax(y0[i], y1[i]); }
            for (int f = 0; f < o->nt; f++) {
                const double *a = o->verts + 3 * o->tris[3 * f], *b = o->verts + 3 * o->tris[3 * f + 1],
                             *c = o->verts + 3 * o->tris[3 * f + 2];
                int sep = 0;
                for (int i = 0; i < 3; i++)
                    sep |= hi[i] < fmin(a[i], fmin(b[i], c[i])) || lo[i] > fmax(a[i], fmax(b[i], c[i]));
                if (!sep) t = fmin(t, sb_ccd_point_triangle(y0, y1, a, a, b, b, c, c));
            }
        }
        if (t <= 1) return (k + t) / n;
        memcpy(y0, y1, sizeof y0);
    }
    return 2.0;
}

/* ---- the scene's reference surface against the obstacles at the start ---- */

/* y within the bounding box of triangle (a, b, c) (closed): only then can it lie on it */
static int in_tri_box(const double y[3], const double a[3], const double b[3], const double c[3])
{
    for (int i = 0; i < 3; i++)
        if (y[i] < fmin(a[i], fmin(b[i], c[i])) || y[i] > fmax(a[i], fmax(b[i], c[i]))) return 0;
    return 1;
}

int sb_obstacles_start_check(const sb_scene *sc, char *why, size_t why_size)
{
    static const char *const kinds[] = { "sphere", "plane", "box", "capsule", "mesh" };
    if (why_size) why[0] = '\0';
    if (sc->n_obstacles == 0) return 0;
    /* the sample density of the scene's resolution (n samples per element
     * side), at most 129 x 129 points */
    int n = (sc->default_res > 0 ? sc->default_res : 8) * (sc->contact.samples > 0 ? sc->contact.samples : 1) + 1;
    if (n > 129) n = 129;
    if (n < 2) n = 2;
    double *st = malloc((size_t)2 * n * n * sizeof *st);
    if (!st) return -1;
    const int np = sb_domain_sample_grid(&sc->domain, n, st, n * n);
    int found = 0;
    for (int o = 0; o < sc->n_obstacles && !found; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        sb_pose P;
        sb_pose_at(ob, sb_obstacle_motion_factor(sc, ob, 0), &P);
        double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
        for (int v = 0; ob->kind == SB_OBST_MESH && v < ob->nv; v++)
            for (int i = 0; i < 3; i++) {
                lo[i] = fmin(lo[i], ob->verts[3 * v + i]);
                hi[i] = fmax(hi[i], ob->verts[3 * v + i]);
            }
        for (int k = 0; k < np && k < n * n && !found; k++) {
            sb_jet3 J;
            sb_geometry_eval_st(sc, st[2 * k], st[2 * k + 1], &J);
            double d;
            if (ob->kind != SB_OBST_MESH) d = sb_obstacle_phi(ob, &P, J.x, NULL, NULL);
            else {
                double y[3];
                sb_pose_inverse(&P, J.x, y);
                d = INFINITY;
                int out = 0;   /* outside the mesh's bounding box: on none of its triangles */
                for (int i = 0; i < 3; i++) out |= y[i] < lo[i] || y[i] > hi[i];
                for (int f = 0; f < ob->nt && d > 0 && !out; f++)
                    if (in_tri_box(y, ob->verts + 3 * ob->tris[3 * f], ob->verts + 3 * ob->tris[3 * f + 1],
                                   ob->verts + 3 * ob->tris[3 * f + 2]))
                        d = fmin(d, sb_point_triangle_distance(y, ob->verts + 3 * ob->tris[3 * f],
                                                               ob->verts + 3 * ob->tris[3 * f + 1],
                                                               ob->verts + 3 * ob->tris[3 * f + 2], NULL, NULL));
            }
            if (d <= 0) {
                sb_jet2 xi;
                sb_domain_map(&sc->domain, st[2 * k], st[2 * k + 1], &xi);
                char e[SB_NAME_LEN * 4 + 8];
                snprintf(why, why_size,
                         "the cloth starts inside obstacle \"%s\" (%s): the reference surface's point at material "
                         "coordinates (%.4g, %.4g) (s = %.4g, t = %.4g), (%.4g, %.4g, %.4g) m, is %s it at the "
                         "start; contact cannot start from there (infinite barrier energy, no side to push to).  "
                         "Move the obstacle or the cloth apart",
                         sb_escape_copy(ob->name, e, sizeof e), kinds[ob->kind], xi.x[0], xi.x[1], st[2 * k],
                         st[2 * k + 1], J.x[0], J.x[1], J.x[2],
                         ob->kind == SB_OBST_MESH ? "on a triangle of" : "inside");
                found = 1;
            }
        }
    }
    free(st);
    return found;
}

/* ---- a cloth triangle against an analytic solid ---------------------------- */

/* Triangle (a, b, c) (rest frame) against the axis-aligned box |y - m| <= h:
 * the separating-axis test of Akenine-Möller (2001, "Fast 3D triangle-box
 * overlap testing"): 3 box axes, the triangle's normal, 9 edge x axis
 * products.  Returns, over the axes (each normalized), the smallest of the
 * two translations along it that separate the projections: <= 0 when an
 * axis separates them, else the penetration depth (the shortest
 * translation that separates the two convex polytopes is along one of
 * these axes). */
static double tri_box_depth(const double a[3], const double b[3], const double c[3], const double m[3], const double h[3])
{
    double v[3][3], e[3][3];
    for (int i = 0; i < 3; i++) { v[0][i] = a[i] - m[i]; v[1][i] = b[i] - m[i]; v[2][i] = c[i] - m[i]; }
    for (int i = 0; i < 3; i++) { e[0][i] = v[1][i] - v[0][i]; e[1][i] = v[2][i] - v[1][i]; e[2][i] = v[0][i] - v[2][i]; }
    double axes[13][3];
    int na = 0;
    for (int k = 0; k < 3; k++) {   /* the box's faces */
        double u[3] = { 0, 0, 0 };
        u[k] = 1;
        memcpy(axes[na++], u, sizeof u);
    }
    double nrm[3] = { e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                      e[0][0] * e[1][1] - e[0][1] * e[1][0] };
    memcpy(axes[na++], nrm, sizeof nrm);
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) {   /* e_j x unit axis k */
            double u[3] = { 0, 0, 0 }, w[3];
            u[k] = 1;
            w[0] = e[j][1] * u[2] - e[j][2] * u[1];
            w[1] = e[j][2] * u[0] - e[j][0] * u[2];
            w[2] = e[j][0] * u[1] - e[j][1] * u[0];
            memcpy(axes[na++], w, sizeof w);
        }
    double depth = INFINITY;
    for (int q = 0; q < na; q++) {
        const double *u = axes[q], un = sqrt(dot3(u, u));
        if (!(un > 1e-12 * (1 + sqrt(dot3(nrm, nrm))))) continue;   /* degenerate axis: no information */
        double lo = INFINITY, hi = -INFINITY;
        for (int k = 0; k < 3; k++) {
            const double p = dot3(v[k], u);
            lo = fmin(lo, p);
            hi = fmax(hi, p);
        }
        const double r = h[0] * fabs(u[0]) + h[1] * fabs(u[1]) + h[2] * fabs(u[2]);
        /* the shorter of the two pushes that separate the projections
           [lo, hi] and [-r, r]: up by r - lo or down by hi + r */
        depth = fmin(depth, fmin(r - lo, hi + r) / un);
        if (depth <= 0) return depth;
    }
    return depth;
}

static double tri_point_distance(const double p[3], const double a[3], const double b[3], const double c[3])
{
    return sb_point_triangle_distance(p, a, b, c, NULL, NULL);
}

double sb_obstacle_triangle_depth(const sb_obstacle_spec *o, const sb_pose *P, const double xa[3], const double xb[3],
                                  const double xc[3])
{
    double a[3], b[3], c[3];
    sb_pose_inverse(P, xa, a);
    sb_pose_inverse(P, xb, b);
    sb_pose_inverse(P, xc, c);
    switch (o->kind) {
    case SB_OBST_SPHERE: {
        for (int i = 0; i < 3; i++)   /* bounding-box cull */
            if (fmin(a[i], fmin(b[i], c[i])) >= o->center[i] + o->radius ||
                fmax(a[i], fmax(b[i], c[i])) <= o->center[i] - o->radius)
                return 0;
        return o->radius - tri_point_distance(o->center, a, b, c);
    }
    case SB_OBST_PLANE: {   /* linear: its minimum over the triangle is at a corner */
        double m = INFINITY;
        const double *v[3] = { a, b, c };
        for (int k = 0; k < 3; k++) {
            double w[3] = { v[k][0] - o->point[0], v[k][1] - o->point[1], v[k][2] - o->point[2] };
            m = fmin(m, dot3(o->normal, w));
        }
        return -m;
    }
    case SB_OBST_BOX:
        return tri_box_depth(a, b, c, o->center, o->half);
    case SB_OBST_CAPSULE: {
        for (int i = 0; i < 3; i++)
            if (fmin(a[i], fmin(b[i], c[i])) >= fmax(o->a[i], o->b[i]) + o->radius ||
                fmax(a[i], fmax(b[i], c[i])) <= fmin(o->a[i], o->b[i]) - o->radius)
                return 0;
        /* the axis segment through the triangle: the capsule pierces it */
        if (sb_segment_triangle_intersect(o->a, o->b, a, b, c)) return INFINITY;
        /* else its distance to the triangle, attained at an end of the
           segment or on an edge of the triangle */
        double d = fmin(tri_point_distance(o->a, a, b, c), tri_point_distance(o->b, a, b, c));
        const double *v[3] = { a, b, c };
        for (int k = 0; k < 3; k++) {
            double s, t;
            d = fmin(d, sb_closest_segments(o->a, o->b, v[k], v[(k + 1) % 3], &s, &t));
        }
        return o->radius - d;
    }
    default:
        return 0;   /* meshes: not tested here */
    }
}
