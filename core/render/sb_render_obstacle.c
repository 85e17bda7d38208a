/* sb_render_obstacle.c — rays against the analytic obstacles the renderer
 * draws (sphere, box in any orientation, capsule, a bounded square of a
 * plane); mesh obstacles are triangles in a BVH (sb_render_world.c). */
#include "sb_render_world.h"

#include <math.h>
#include <string.h>

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void normalize3(double a[3])
{
    const double l = sqrt(dot3(a, a));
    if (l > 0) for (int c = 0; c < 3; c++) a[c] /= l;
}

/* Entry t of the ray into the ball |x - c| <= rad: the smaller root of
 * |o + t d - c|^2 = rad^2 (|d| = 1); 0 when the origin is inside or it misses. */
static int ball_entry(const double c[3], double rad, const sb_ray *r, double tmax, double *t)
{
    const double oc[3] = { r->o[0] - c[0], r->o[1] - c[1], r->o[2] - c[2] };
    const double b = dot3(oc, r->d), q = dot3(oc, oc) - rad * rad;
    if (q <= 0) return 0;   /* origin inside */
    const double disc = b * b - q;
    if (disc < 0) return 0;
    const double t0 = -b - sqrt(disc);
    if (!(t0 > r->tmin && t0 < tmax)) return 0;
    *t = t0;
    return 1;
}

static int hit_box(const sb_obstacle *ob, const sb_ray *r, double tmax, double *t, double n[3])
{
    double m[3];
    for (int c = 0; c < 3; c++) m[c] = 0.5 * (ob->lo[c] + ob->hi[c]);
    sb_ray lr = *r;
    if (ob->rotated) {
        /* the ray in the box's frame: y = m + R^T (x - m), direction R^T d */
        double o[3], d[3];
        for (int i = 0; i < 3; i++) {
            o[i] = m[i];
            d[i] = 0;
            for (int k = 0; k < 3; k++) {
                o[i] += ob->R[3 * k + i] * (r->o[k] - m[k]);
                d[i] += ob->R[3 * k + i] * r->d[k];
            }
        }
        if (sb_ray_init(&lr, o, d, r->tmin, r->tmax)) return 0;
    }
    double t0, t1;
    if (!sb_ray_box(&lr, ob->lo, ob->hi, tmax, &t0, &t1) || !(t0 > r->tmin)) return 0;   /* or origin inside */
    /* the face whose plane the entry point is nearest */
    double p[3], nl[3] = { 0, 0, 0 }, best = INFINITY;
    for (int c = 0; c < 3; c++) p[c] = lr.o[c] + t0 * lr.d[c];
    for (int c = 0; c < 3; c++) {
        const double dl = fabs(p[c] - ob->lo[c]), dh = fabs(p[c] - ob->hi[c]);
        if (dl < best) { best = dl; nl[0] = nl[1] = nl[2] = 0; nl[c] = -1; }
        if (dh < best) { best = dh; nl[0] = nl[1] = nl[2] = 0; nl[c] = 1; }
    }
    if (ob->rotated)
        for (int i = 0; i < 3; i++) n[i] = ob->R[3 * i] * nl[0] + ob->R[3 * i + 1] * nl[1] + ob->R[3 * i + 2] * nl[2];
    else
        memcpy(n, nl, sizeof nl);
    *t = t0;
    return 1;
}

/* The capsule is the union of the balls at its ends and the finite cylinder
 * between them; from outside, the first entry into a union of convex solids
 * is the smallest of their entries.  The cylinder's flat ends lie inside the
 * balls, so only its lateral surface is tested: with e = b - a, w = o - a,
 * |w + t d|^2 |e|^2 - ((w + t d).e)^2 = rad^2 |e|^2 is the quadratic
 * A t^2 + 2 B t + C = 0 of the infinite cylinder (Quilez, "ray-capsule
 * intersection"), accepted where the axial coordinate is within [0, |e|^2]. */
static int hit_capsule(const sb_obstacle *ob, const sb_ray *r, double tmax, double *t, double n[3])
{
    double e[3], w[3];
    for (int c = 0; c < 3; c++) { e[c] = ob->b[c] - ob->a[c]; w[c] = r->o[c] - ob->a[c]; }
    const double ee = dot3(e, e), ed = dot3(e, r->d), ew = dot3(e, w), dw = dot3(r->d, w), ww = dot3(w, w);
    /* origin inside: no hit (distance of o to the segment <= rad) */
    const double s0 = ee > 0 ? fmin(1.0, fmax(0.0, ew / ee)) : 0.0;
    double q0[3];
    for (int c = 0; c < 3; c++) q0[c] = w[c] - s0 * e[c];
    if (dot3(q0, q0) <= ob->r * ob->r) return 0;
    double best = tmax, tt;
    int hit = 0;
    if (ball_entry(ob->a, ob->r, r, best, &tt)) { best = tt; hit = 1; }
    if (ball_entry(ob->b, ob->r, r, best, &tt)) { best = tt; hit = 1; }
    const double A = ee - ed * ed, B = ee * dw - ew * ed, C = ee * ww - ew * ew - ob->r * ob->r * ee;
    if (A > 1e-14 * ee) {
        const double disc = B * B - A * C;
        if (disc >= 0) {
            tt = (-B - sqrt(disc)) / A;
            const double y = ew + tt * ed;
            if (y >= 0 && y <= ee && tt > r->tmin && tt < best) { best = tt; hit = 1; }
        }
    }
    if (!hit) return 0;
    /* normal: from the closest point of the axis segment */
    double p[3];
    for (int c = 0; c < 3; c++) p[c] = r->o[c] + best * r->d[c] - ob->a[c];
    const double s = ee > 0 ? fmin(1.0, fmax(0.0, dot3(p, e) / ee)) : 0.0;
    for (int c = 0; c < 3; c++) n[c] = p[c] - s * e[c];
    normalize3(n);
    *t = best;
    return 1;
}

/* the square |(x - c).u| <= extent, |(x - c).v| <= extent of the plane */
static int hit_plane(const sb_obstacle *ob, const double pu[3], const double pv[3], const sb_ray *r, double tmax,
                     double *t, double n[3])
{
    const double den = dot3(r->d, ob->n);
    if (fabs(den) < 1e-12) return 0;
    const double co[3] = { ob->c[0] - r->o[0], ob->c[1] - r->o[1], ob->c[2] - r->o[2] };
    const double tt = dot3(co, ob->n) / den;
    if (!(tt > r->tmin && tt < tmax)) return 0;
    double q[3];
    for (int c = 0; c < 3; c++) q[c] = r->o[c] + tt * r->d[c] - ob->c[c];
    if (fabs(dot3(q, pu)) > ob->extent || fabs(dot3(q, pv)) > ob->extent) return 0;
    memcpy(n, ob->n, 3 * sizeof *n);
    *t = tt;
    return 1;
}

int sb_ray_obstacle(const sb_obstacle *ob, const double pu[3], const double pv[3], const sb_ray *r, double tmax,
                    double *t, double n[3])
{
    switch (ob->kind) {
    case SB_OBSTACLE_SPHERE:
        if (!ball_entry(ob->c, ob->r, r, tmax, t)) return 0;
        for (int c = 0; c < 3; c++) n[c] = (r->o[c] + *t * r->d[c] - ob->c[c]) / ob->r;
        return 1;
    case SB_OBSTACLE_BOX: return hit_box(ob, r, tmax, t, n);
    case SB_OBSTACLE_CAPSULE: return hit_capsule(ob, r, tmax, t, n);
    case SB_OBSTACLE_PLANE: return hit_plane(ob, pu, pv, r, tmax, t, n);
    case SB_OBSTACLE_MESH: return 0;   /* triangles in the world's mesh BVH */
    }
    return 0;
}
