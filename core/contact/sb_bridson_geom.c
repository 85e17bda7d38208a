/* sb_bridson_geom.c — closest points (point–triangle, segment–segment) and
 * the continuous collision test of two moving edges (sb_bridson.h). */
#include "sb_bridson.h"

#include <gsl/gsl_poly.h>
#include <math.h>

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void sub3(const double a[3], const double b[3], double c[3])
{
    for (int i = 0; i < 3; i++) c[i] = a[i] - b[i];
}
static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static void lerp3(const double a[3], const double b[3], double t, double o[3])
{
    for (int i = 0; i < 3; i++) o[i] = a[i] + t * (b[i] - a[i]);
}
static double clamp01(double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); }

double sb_closest_point_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                                 double w[3])
{
    /* Ericson 2005, Real-Time Collision Detection, §5.1.5: the Voronoi
     * regions of the vertices, edges and face in turn */
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    sub3(b, a, ab); sub3(c, a, ac); sub3(p, a, ap);
    double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) { w[0] = 1; w[1] = 0; w[2] = 0; goto done; }
    sub3(p, b, bp);
    double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) { w[0] = 0; w[1] = 1; w[2] = 0; goto done; }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double v = d1 / (d1 - d3);
        w[0] = 1 - v; w[1] = v; w[2] = 0;
        goto done;
    }
    sub3(p, c, cp);
    double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) { w[0] = 0; w[1] = 0; w[2] = 1; goto done; }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double t = d2 / (d2 - d6);
        w[0] = 1 - t; w[1] = 0; w[2] = t;
        goto done;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        w[0] = 0; w[1] = 1 - t; w[2] = t;
        goto done;
    }
    {
        double den = va + vb + vc;
        if (!(den > 0)) {   /* degenerate triangle: the best of its three edges */
            double best = INFINITY, s, t;
            const double *V[3] = { a, b, c };
            for (int k = 0; k < 3; k++) {
                double dd = sb_closest_segments(p, p, V[k], V[(k + 1) % 3], &s, &t);
                if (dd < best) {
                    best = dd;
                    w[0] = w[1] = w[2] = 0;
                    w[k] = 1 - t;
                    w[(k + 1) % 3] = t;
                }
            }
            return best;
        }
        double v = vb / den, ww = vc / den;
        w[0] = 1 - v - ww; w[1] = v; w[2] = ww;
    }
done:;
    double q[3];
    for (int i = 0; i < 3; i++) q[i] = w[0] * a[i] + w[1] * b[i] + w[2] * c[i] - p[i];
    return sqrt(dot3(q, q));
}

double sb_closest_segments(const double p1[3], const double q1[3], const double p2[3], const double q2[3],
                           double *s_out, double *t_out)
{
    /* Ericson 2005, §5.1.9, with its degenerate (point) and parallel cases */
    double d1[3], d2[3], r[3];
    sub3(q1, p1, d1); sub3(q2, p2, d2); sub3(p1, p2, r);
    const double a = dot3(d1, d1), e = dot3(d2, d2), f = dot3(d2, r);
    const double tiny = 1e-300;
    double s, t;
    if (a <= tiny && e <= tiny) { s = t = 0; }
    else if (a <= tiny) { s = 0; t = clamp01(f / e); }
    else {
        const double c = dot3(d1, r);
        if (e <= tiny) { t = 0; s = clamp01(-c / a); }
        else {
            const double b = dot3(d1, d2), den = a * e - b * b;
            /* parallel (den ~ 0 relative to a e): any s; take 0 */
            s = den > 1e-14 * a * e ? clamp01((b * f - c * e) / den) : 0.0;
            t = (b * s + f) / e;
            if (t < 0) { t = 0; s = clamp01(-c / a); }
            else if (t > 1) { t = 1; s = clamp01((b - c) / a); }
        }
    }
    double x[3];
    for (int i = 0; i < 3; i++) x[i] = p1[i] + s * d1[i] - p2[i] - t * d2[i];
    *s_out = s;
    *t_out = t;
    return sqrt(dot3(x, x));
}

/* segments' distance at time t of the linear motions */
static double seg_dist_at(const double *const P[8], double t)
{
    double x[4][3], s, u;
    for (int k = 0; k < 4; k++) lerp3(P[2 * k], P[2 * k + 1], t, x[k]);
    return sb_closest_segments(x[0], x[1], x[2], x[3], &s, &u);
}

/* real roots in [0, 1] of c3 t^3 + c2 t^2 + c1 t + c0, ascending; -1 when
 * the polynomial is identically zero at the scale `zero` */
static int roots01(double c3, double c2, double c1, double c0, double zero, double r[3])
{
    double S = fmax(fmax(fabs(c3), fabs(c2)), fmax(fabs(c1), fabs(c0))), x[3];
    int n = 0, m = 0;
    if (S <= zero) return -1;
    const double eps = 1e-12 * S;
    if (fabs(c3) > eps) n = gsl_poly_solve_cubic(c2 / c3, c1 / c3, c0 / c3, &x[0], &x[1], &x[2]);
    else if (fabs(c2) > eps || fabs(c1) > eps) n = gsl_poly_solve_quadratic(fabs(c2) > eps ? c2 : 0.0, c1, c0, &x[0], &x[1]);
    else return fabs(c0) > eps ? 0 : -1;
    for (int i = 0; i < n; i++)
        if (x[i] >= -1e-12 && x[i] <= 1 + 1e-12) r[m++] = clamp01(x[i]);
    return m;
}

/* The four points stay coplanar: in 2D two segments first touch when an end
 * point of one reaches the other segment; the end point p crosses the line
 * of segment (u, v) where ((v - u) x (p - u)) . n = 0, a quadratic in t
 * (sampled exactly at t = 0, 1/2, 1), then the crossing must lie on the
 * segment.  Collinear motions (no plane normal) use the end points'
 * coincidences along the line instead. */
static double coplanar_ee(const double *const P[8], double L, double tol)
{
    if (seg_dist_at(P, 0) <= tol) return 0.0;
    /* a reference normal: the largest normal of the triples through the
       first point at t = 0, 1/4, ..., 1 (the common plane may move, e.g. of
       parallel edges; g below changes sign where the in-plane order flips or
       where the plane turns through the points' line, and every root is
       checked by the segments' distance) */
    double x[4][3], n[3] = { 0, 0, 0 }, e[3];
    for (int q = 0; q <= 4; q++) {
        for (int k = 0; k < 4; k++) lerp3(P[2 * k], P[2 * k + 1], 0.25 * q, x[k]);
        for (int k = 1; k < 4; k++)
            for (int j = k + 1; j < 4; j++) {
                double a[3], b[3], c[3];
                sub3(x[k], x[0], a); sub3(x[j], x[0], b);
                cross3(a, b, c);
                if (dot3(c, c) > dot3(n, n)) for (int i = 0; i < 3; i++) n[i] = c[i];
            }
    }
    for (int k = 0; k < 4; k++) lerp3(P[2 * k], P[2 * k + 1], 0.5, x[k]);
    double best = 2.0;
    if (dot3(n, n) > 1e-24 * L * L * L * L) {
        for (int pe = 0; pe < 2; pe++)          /* end points of edge pe against edge 1 - pe */
            for (int q = 0; q < 2; q++) {
                const double *const *Pp = P + 4 * pe + 2 * q, *const *U = P + 4 * (1 - pe), *const *V = U + 2;
                double g[3];
                for (int s = 0; s < 3; s++) {
                    double t = 0.5 * s, u[3], v[3], p[3], d[3], w[3], c[3];
                    lerp3(U[0], U[1], t, u); lerp3(V[0], V[1], t, v); lerp3(Pp[0], Pp[1], t, p);
                    sub3(v, u, d); sub3(p, u, w);
                    cross3(d, w, c);
                    g[s] = dot3(c, n);
                }
                double qa = 2 * g[0] - 4 * g[1] + 2 * g[2], qb = -3 * g[0] + 4 * g[1] - g[2], r[3];
                int m = roots01(0.0, qa, qb, g[0], 1e-13 * L * L * sqrt(dot3(n, n)), r);
                for (int i = 0; i < m; i++)
                    if (r[i] < best && seg_dist_at(P, r[i]) <= tol) best = r[i];
            }
        return best;
    }
    /* collinear: the times an end point passes another along the line */
    sub3(x[1], x[0], e);
    if (dot3(e, e) <= 0) sub3(x[3], x[2], e);
    if (dot3(e, e) <= 0) return 2.0;
    for (int i = 0; i < 2; i++)
        for (int j = 2; j < 4; j++) {
            double a = 0, b = 0;   /* ((p_i - p_j)(t)) . e = a + b t */
            for (int c = 0; c < 3; c++) {
                double d0 = P[2 * i][c] - P[2 * j][c], d1 = P[2 * i + 1][c] - P[2 * j + 1][c];
                a += d0 * e[c];
                b += (d1 - d0) * e[c];
            }
            if (b == 0) continue;
            double t = -a / b;
            if (t >= 0 && t <= 1 && t < best && seg_dist_at(P, t) <= tol) best = t;
        }
    return best;
}

double sb_bridson_ccd_edge_edge(const double a0[3], const double a1[3], const double b0[3], const double b1[3],
                        const double c0[3], const double c1[3], const double d0[3], const double d1[3])
{
    /* f(t) = ((b - a) x (d - c)) . (c - a), all relative to a:
     * e1 = b - a, e2 = d - c, w = c - a, each linear in t */
    double e1[3], e2[3], w[3], de1[3], de2[3], dw[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = b0[i] - a0[i];
        e2[i] = d0[i] - c0[i];
        w[i] = c0[i] - a0[i];
        de1[i] = (b1[i] - a1[i]) - e1[i];
        de2[i] = (d1[i] - c1[i]) - e2[i];
        dw[i] = (c1[i] - a1[i]) - w[i];
    }
    double n0[3], m1[3], m2[3], n2[3], nm[3];
    cross3(e1, e2, n0);
    cross3(e1, de2, m1);
    cross3(de1, e2, m2);
    cross3(de1, de2, n2);
    for (int i = 0; i < 3; i++) nm[i] = m1[i] + m2[i];
    double k3 = dot3(n2, dw), k2 = dot3(nm, dw) + dot3(n2, w), k1 = dot3(n0, dw) + dot3(nm, w), k0 = dot3(n0, w);
    double L = 0;
    for (int i = 0; i < 3; i++)
        L = fmax(L, fmax(fmax(fabs(e1[i]), fabs(e2[i])), fmax(fmax(fabs(w[i]), fabs(de1[i])), fmax(fabs(de2[i]), fabs(dw[i])))));
    if (!(L > 0)) return 0.0;                               /* four coincident points */
    const double tol = 1e-9 * L;
    const double *const P[8] = { a0, a1, b0, b1, c0, c1, d0, d1 };
    double r[3];
    int m = roots01(k3, k2, k1, k0, 1e-13 * L * L * L, r);
    if (m < 0) return coplanar_ee(P, L, tol);
    for (int i = 0; i < m; i++)
        if (seg_dist_at(P, r[i]) <= tol) return r[i];
    return 2.0;
}
