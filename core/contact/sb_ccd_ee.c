/* sb_ccd_ee.c — continuous collision detection of an edge against an edge
 * and of a point against an edge, all vertices moving linearly over t in
 * [0, 1] (sb_self_geom.h).
 *
 * Edge–edge (Provot 1997; Bridson, Fedkiw & Anderson 2002 §4): the two
 * lines are coplanar when the cubic
 *   f(t) = ((a1 - a0) x (b1 - b0)) . (b0 - a0)
 * vanishes; at each root in [0, 1], in increasing order, the closed
 * segments are tested for contact (distance below 1e-9 of the
 * configuration's length scale: touching counts).  When f vanishes
 * identically (edges that stay parallel, or move within one plane), the
 * segments first meet at t = 0 or when an endpoint of one reaches the
 * other (two segments in a plane that start apart first touch at an
 * endpoint), so the answer is the first of the four point–edge times.
 *
 * Point–edge: the point is on the segment's line when c(t) = (v - u) x
 * (p - u) = 0, three quadratics; the roots of the component with the
 * largest coefficients are tested for the other two and for the segment's
 * parameter in [0, 1].  A point that stays on the line throughout enters
 * the segment when its parameter s(t) = (p - u).(v - u) / |v - u|^2 crosses
 * 0 or 1 (quadratic conditions). */
#include "sb_self_geom.h"
#include "sb_ccd_poly.h"

#include <math.h>

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
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

/* coefficients (c2, c1, c0) of the quadratic through g(0), g(1/2), g(1) */
static void quad_coef(const double g[3], double c[3])
{
    c[0] = 2 * g[0] - 4 * g[1] + 2 * g[2];
    c[1] = -3 * g[0] + 4 * g[1] - g[2];
    c[2] = g[0];
}

double sb_ccd_point_edge(const double p[3], const double pe[3], const double u[3], const double ue[3],
                         const double v[3], const double ve[3])
{
    double L = 0;
    for (int i = 0; i < 3; i++)
        L = fmax(L, fmax(fmax(fabs(v[i] - u[i]), fabs(p[i] - u[i])),
                         fmax(fabs(ve[i] - ue[i]), fabs(pe[i] - ue[i]))));
    if (!(L > 0)) return 0.0;
    /* c(t) and the dot products at t = 0, 1/2, 1 (each a quadratic in t) */
    double cs[3][3], ns[3], ls[3];
    for (int s = 0; s < 3; s++) {
        double t = 0.5 * s, a[3], b[3], q[3], d[3], w[3];
        lerp3(u, ue, t, a); lerp3(v, ve, t, b); lerp3(p, pe, t, q);
        for (int i = 0; i < 3; i++) { d[i] = b[i] - a[i]; w[i] = q[i] - a[i]; }
        double c[3];
        cross3(d, w, c);
        for (int i = 0; i < 3; i++) cs[i][s] = c[i];
        ns[s] = dot3(w, d);
        ls[s] = dot3(d, d);
    }
    const double zero = 1e-13 * L * L, tol = 1e-9 * L * L;
    int best_k = -1;
    double best_S = 0, C[3][3];
    for (int k = 0; k < 3; k++) {
        quad_coef(cs[k], C[k]);
        double S = fmax(fabs(C[k][0]), fmax(fabs(C[k][1]), fabs(C[k][2])));
        if (S > best_S) { best_S = S; best_k = k; }
    }
    if (best_k >= 0 && best_S > zero) {
        double r[3];
        const int m = sb_ccd_roots01(0.0, C[best_k][0], C[best_k][1], C[best_k][2], zero, r);
        for (int i = 0; i < m; i++) {
            double a[3], b[3], q[3], d[3], w[3], c[3];
            lerp3(u, ue, r[i], a); lerp3(v, ve, r[i], b); lerp3(p, pe, r[i], q);
            for (int j = 0; j < 3; j++) { d[j] = b[j] - a[j]; w[j] = q[j] - a[j]; }
            cross3(d, w, c);
            const double dd = dot3(d, d), s = dd > 0 ? dot3(w, d) / dd : -1;
            if (sqrt(dot3(c, c)) <= tol && s >= -1e-10 && s <= 1 + 1e-10) return r[i];
        }
        return 2.0;
    }
    /* on the line throughout: 0 <= n(t) <= l(t) */
    if (ns[0] >= 0 && ns[0] <= ls[0]) return 0.0;
    double Cn[3], Cl[3], r[3], best = 2.0;
    quad_coef(ns, Cn);
    quad_coef(ls, Cl);
    int m = sb_ccd_roots01(0.0, Cn[0], Cn[1], Cn[2], zero, r);
    for (int i = 0; i < m; i++) best = fmin(best, r[i]);
    m = sb_ccd_roots01(0.0, Cn[0] - Cl[0], Cn[1] - Cl[1], Cn[2] - Cl[2], zero, r);
    for (int i = 0; i < m; i++) best = fmin(best, r[i]);
    return best;
}

double sb_ccd_edge_edge(const double a0[3], const double a0e[3], const double a1[3], const double a1e[3],
                        const double b0[3], const double b0e[3], const double b1[3], const double b1e[3])
{
    double ea[3], eb[3], w[3], dea[3], deb[3], dw[3];
    for (int i = 0; i < 3; i++) {
        ea[i] = a1[i] - a0[i];
        eb[i] = b1[i] - b0[i];
        w[i] = b0[i] - a0[i];
        dea[i] = (a1e[i] - a0e[i]) - ea[i];
        deb[i] = (b1e[i] - b0e[i]) - eb[i];
        dw[i] = (b0e[i] - a0e[i]) - w[i];
    }
    /* f(t) = ((ea + t dea) x (eb + t deb)) . (w + t dw) */
    double k[4];
    const double L = sb_ccd_coplanar_cubic(ea, dea, eb, deb, w, dw, k);
    if (!(L > 0)) return 0.0;
    if (sb_self_segment_distance(a0, a1, b0, b1) <= 1e-9 * L) return 0.0;
    double r[3];
    const int m = sb_ccd_roots01(k[3], k[2], k[1], k[0], 1e-13 * L * L * L, r);
    if (m >= 0) {
        for (int i = 0; i < m; i++) {
            double p[3], q[3], s[3], t[3];
            lerp3(a0, a0e, r[i], p); lerp3(a1, a1e, r[i], q); lerp3(b0, b0e, r[i], s); lerp3(b1, b1e, r[i], t);
            if (sb_self_segment_distance(p, q, s, t) <= 1e-9 * L) return r[i];
        }
        return 2.0;
    }
    /* identically coplanar: the first endpoint to reach the other segment */
    double best = sb_ccd_point_edge(a0, a0e, b0, b0e, b1, b1e);
    best = fmin(best, sb_ccd_point_edge(a1, a1e, b0, b0e, b1, b1e));
    best = fmin(best, sb_ccd_point_edge(b0, b0e, a0, a0e, a1, a1e));
    best = fmin(best, sb_ccd_point_edge(b1, b1e, a0, a0e, a1, a1e));
    return best;
}
