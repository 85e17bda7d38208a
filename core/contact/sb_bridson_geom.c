/* sb_bridson_geom.c — closest points (point–triangle with barycentric
 * weights, segment–segment with parameters) for the proximity impulses
 * (sb_bridson.h); the continuous tests are sb_ccd.c and sb_ccd_ee.c. */
#include "sb_bridson.h"

#include <math.h>

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void sub3(const double a[3], const double b[3], double c[3])
{
    for (int i = 0; i < 3; i++) c[i] = a[i] - b[i];
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
