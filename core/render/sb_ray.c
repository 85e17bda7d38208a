/* sb_ray.c — ray set-up, ray–box and ray–triangle tests (sb_ray.h). */
#include "sb_ray.h"

#include <math.h>

int sb_ray_init(sb_ray *r, const double o[3], const double d[3], double tmin, double tmax)
{
    const double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(n > 0.0) || !isfinite(n)) return -1;
    for (int c = 0; c < 3; c++) {
        r->o[c] = o[c];
        r->d[c] = d[c] / n;
        r->inv[c] = 1.0 / r->d[c];   /* +-inf for 0 (IEEE), handled in sb_ray_box */
    }
    r->tmin = tmin;
    r->tmax = tmax;
    return 0;
}

int sb_ray_box(const sb_ray *r, const double lo[3], const double hi[3], double tmax, double *t0, double *t1)
{
    double a = r->tmin, b = tmax;
    for (int c = 0; c < 3; c++) {
        if (r->d[c] == 0.0) {
            /* parallel to the slab: inside it or never */
            if (r->o[c] < lo[c] || r->o[c] > hi[c]) return 0;
            continue;
        }
        double ta = (lo[c] - r->o[c]) * r->inv[c], tb = (hi[c] - r->o[c]) * r->inv[c];
        if (ta > tb) { double s = ta; ta = tb; tb = s; }
        if (ta > a) a = ta;
        if (tb < b) b = tb;
        if (a > b) return 0;
    }
    *t0 = a;
    *t1 = b;
    return 1;
}

int sb_ray_triangle(const sb_ray *r, const double a[3], const double b[3], const double c[3], double tmax,
                    double *t, double *b1, double *b2)
{
    double e1[3], e2[3], p[3], q[3], s[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
        s[k] = r->o[k] - a[k];
    }
    p[0] = r->d[1] * e2[2] - r->d[2] * e2[1];
    p[1] = r->d[2] * e2[0] - r->d[0] * e2[2];
    p[2] = r->d[0] * e2[1] - r->d[1] * e2[0];
    const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det == 0.0 || !isfinite(det)) return 0;
    const double id = 1.0 / det;
    const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * id;
    if (u < 0.0 || u > 1.0) return 0;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    const double v = (r->d[0] * q[0] + r->d[1] * q[1] + r->d[2] * q[2]) * id;
    if (v < 0.0 || u + v > 1.0) return 0;
    const double tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * id;
    if (!(tt > r->tmin && tt < tmax)) return 0;
    *t = tt;
    *b1 = u;
    *b2 = v;
    return 1;
}
