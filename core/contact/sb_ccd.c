/* sb_ccd.c — continuous collision detection of a point against a triangle,
 * all four moving linearly over t in [0, 1] (sb_obstacle.h).
 *
 * The point lies in the triangle's plane when the cubic
 *   f(t) = ((b - a) x (c - a)) . (p - a) = c3 t^3 + c2 t^2 + c1 t + c0
 * vanishes (Provot 1997; Bridson, Fedkiw & Anderson 2002, §4); at each root
 * in [0, 1], in increasing order, the point is tested against the closed
 * triangle.  Degenerate cases (unit tests in tests/test_contact_ccd.c):
 *  - vanishing leading coefficients (a static triangle gives a linear f; a
 *    point moving parallel to a static plane a constant one): the cubic is
 *    solved as the polynomial of its true degree (relative threshold 1e-12);
 *  - f identically zero (the motion stays in the plane): the point enters
 *    the closed triangle when it crosses one of its edges, a quadratic
 *    condition in the plane ((v - u) x (p - u)) . n = 0 per edge, or it is
 *    inside at t = 0;
 *  - touching (a root where the point is on an edge or vertex) counts as a
 *    contact: barycentric tolerance 1e-10. */
#include "sb_obstacle.h"
#include "sb_ccd_poly.h"

#include <gsl/gsl_poly.h>
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

/* is p in the closed triangle abc (p assumed in or next to its plane)? */
static int in_triangle(const double p[3], const double a[3], const double b[3], const double c[3])
{
    double v0[3], v1[3], v2[3];
    for (int i = 0; i < 3; i++) { v0[i] = b[i] - a[i]; v1[i] = c[i] - a[i]; v2[i] = p[i] - a[i]; }
    double d00 = dot3(v0, v0), d01 = dot3(v0, v1), d11 = dot3(v1, v1), d20 = dot3(v2, v0), d21 = dot3(v2, v1);
    double den = d00 * d11 - d01 * d01;
    if (!(den > 0)) return 0;
    double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den, u = 1 - v - w;
    const double tol = 1e-10;
    return u >= -tol && v >= -tol && w >= -tol;
}

/* real roots in [0, 1] of c3 t^3 + c2 t^2 + c1 t + c0, ascending; their
 * count, or -1 when all coefficients are below `zero` (identically zero) */
int sb_ccd_roots01(double c3, double c2, double c1, double c0, double zero, double r[3])
{
    double S = fmax(fmax(fabs(c3), fabs(c2)), fmax(fabs(c1), fabs(c0)));
    double x[3];
    int n = 0, m = 0;
    if (S <= zero) return -1;                                /* identically zero (round-off of the scale) */
    const double eps = 1e-12 * S;
    if (fabs(c3) > eps) n = gsl_poly_solve_cubic(c2 / c3, c1 / c3, c0 / c3, &x[0], &x[1], &x[2]);
    else if (fabs(c2) > eps || fabs(c1) > eps) n = gsl_poly_solve_quadratic(fabs(c2) > eps ? c2 : 0.0, c1, c0, &x[0], &x[1]);
    else return fabs(c0) > eps ? 0 : -1;                     /* a nonzero constant: never; ~0: always */
    for (int i = 0; i < n; i++)
        if (x[i] >= 0 && x[i] <= 1) r[m++] = x[i];
    return m;                                                /* gsl returns roots ascending */
}

/* the coplanar motion: entry time into the closed triangle through an edge */
static double coplanar(const double *P[2], const double *A[2], const double *B[2], const double *C[2], double L)
{
    double p[3], a[3], b[3], c[3], n[3], e1[3], e2[3];
    lerp3(P[0], P[1], 0, p); lerp3(A[0], A[1], 0, a); lerp3(B[0], B[1], 0, b); lerp3(C[0], C[1], 0, c);
    if (in_triangle(p, a, b, c)) return 0.0;
    /* the plane's normal at mid-motion (the triangle is not degenerate there
       unless it collapses, when there is no entry to find) */
    lerp3(A[0], A[1], 0.5, a); lerp3(B[0], B[1], 0.5, b); lerp3(C[0], C[1], 0.5, c);
    for (int i = 0; i < 3; i++) { e1[i] = b[i] - a[i]; e2[i] = c[i] - a[i]; }
    cross3(e1, e2, n);
    if (!(dot3(n, n) > 0)) return 2.0;
    const double zero = 1e-13 * L * L * sqrt(dot3(n, n));
    const double **V[3] = { A, B, C };
    double best = 2.0;
    for (int k = 0; k < 3; k++) {
        const double **U0 = V[k], **U1 = V[(k + 1) % 3];
        double g[3];
        for (int s = 0; s < 3; s++) {   /* g(t) = ((v - u) x (p - u)) . n at t = 0, 1/2, 1 */
            double t = 0.5 * s, u[3], v[3], q[3], d[3], w[3], x[3];
            lerp3(U0[0], U0[1], t, u); lerp3(U1[0], U1[1], t, v); lerp3(P[0], P[1], t, q);
            for (int i = 0; i < 3; i++) { d[i] = v[i] - u[i]; w[i] = q[i] - u[i]; }
            cross3(d, w, x);
            g[s] = dot3(x, n);
        }
        double qa = 2 * g[0] - 4 * g[1] + 2 * g[2], qb = -3 * g[0] + 4 * g[1] - g[2], r[3];
        int m = sb_ccd_roots01(0.0, qa, qb, g[0], zero, r);
        for (int i = 0; i < m; i++) {
            double u[3], v[3], q[3], d[3], w[3];
            lerp3(U0[0], U0[1], r[i], u); lerp3(U1[0], U1[1], r[i], v); lerp3(P[0], P[1], r[i], q);
            for (int j = 0; j < 3; j++) { d[j] = v[j] - u[j]; w[j] = q[j] - u[j]; }
            double L2 = dot3(d, d), s = L2 > 0 ? dot3(w, d) / L2 : -1;
            if (s >= -1e-10 && s <= 1 + 1e-10 && r[i] < best) best = r[i];
        }
    }
    return best;
}

/* The coplanarity cubic of three vectors moving linearly over t in [0, 1]:
 * f(t) = ((e1 + t de1) x (e2 + t de2)) . (w + t dw) = k[3] t^3 + k[2] t^2 +
 * k[1] t + k[0] (Provot 1997; Bridson, Fedkiw & Anderson 2002, §4: a point
 * and a triangle, or two edges, are coplanar at its roots).  Returns the
 * length scale L of the configuration (the largest component of the six
 * vectors; f is a volume, L^3). */
double sb_ccd_coplanar_cubic(const double e1[3], const double de1[3], const double e2[3], const double de2[3],
                             const double w[3], const double dw[3], double k[4])
{
    double n0[3], nm1[3], nm2[3], n2[3], nm[3];
    cross3(e1, e2, n0);
    cross3(e1, de2, nm1);
    cross3(de1, e2, nm2);
    cross3(de1, de2, n2);
    for (int i = 0; i < 3; i++) nm[i] = nm1[i] + nm2[i];
    k[3] = dot3(n2, dw);
    k[2] = dot3(nm, dw) + dot3(n2, w);
    k[1] = dot3(n0, dw) + dot3(nm, w);
    k[0] = dot3(n0, w);
    double L = 0;
    for (int i = 0; i < 3; i++)
        L = fmax(L, fmax(fmax(fabs(e1[i]), fabs(e2[i])), fmax(fmax(fabs(w[i]), fabs(de1[i])), fmax(fabs(de2[i]), fabs(dw[i])))));
    return L;
}

double sb_ccd_point_triangle(const double p0[3], const double p1[3], const double a0[3], const double a1[3],
                             const double b0[3], const double b1[3], const double c0[3], const double c1[3])
{
    double e1[3], e2[3], w[3], de1[3], de2[3], dw[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = b0[i] - a0[i];
        e2[i] = c0[i] - a0[i];
        w[i] = p0[i] - a0[i];
        de1[i] = (b1[i] - a1[i]) - e1[i];
        de2[i] = (c1[i] - a1[i]) - e2[i];
        dw[i] = (p1[i] - a1[i]) - w[i];
    }
    double k[4];
    const double L = sb_ccd_coplanar_cubic(e1, de1, e2, de2, w, dw, k);
    double r[3];
    int m = sb_ccd_roots01(k[3], k[2], k[1], k[0], 1e-13 * L * L * L, r);
    const double *P[2] = { p0, p1 }, *A[2] = { a0, a1 }, *B[2] = { b0, b1 }, *C[2] = { c0, c1 };
    if (m < 0) return coplanar(P, A, B, C, L);
    for (int i = 0; i < m; i++) {
        double p[3], a[3], b[3], c[3];
        lerp3(p0, p1, r[i], p); lerp3(a0, a1, r[i], a); lerp3(b0, b1, r[i], b); lerp3(c0, c1, r[i], c);
        if (in_triangle(p, a, b, c)) return r[i];
    }
    return 2.0;
}
