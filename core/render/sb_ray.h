/* sb_ray.h — rays and the two elementary tests every renderable shape is
 * built from: the slab test against an axis-aligned box (BHEM paper Eq. 24)
 * and the ray–triangle test (Möller & Trumbore 1997). */
#ifndef SB_RAY_H
#define SB_RAY_H

/* x(t) = o + t d with |d| = 1, so t is a distance; hits count in (tmin, tmax). */
typedef struct sb_ray {
    double o[3], d[3];
    double inv[3];          /* 1/d (+-inf for a zero component) */
    double tmin, tmax;
} sb_ray;

/* d is normalized here; returns -1 (ray untouched) for a zero or non-finite d. */
int sb_ray_init(sb_ray *r, const double o[3], const double d[3], double tmin, double tmax);

/* Interval [t0, t1] of the ray inside the box, clipped to [r->tmin, tmax];
 * returns 1 if it is not empty.  Boxes of zero thickness (a flat patch) are
 * hit.  Eq. (24) of the BHEM paper solved for tau. */
int sb_ray_box(const sb_ray *r, const double lo[3], const double hi[3], double tmax, double *t0, double *t1);

/* Ray against triangle (a, b, c): returns 1 and t, barycentrics (b1, b2) of
 * b and c when hit with r->tmin < t < tmax. */
int sb_ray_triangle(const sb_ray *r, const double a[3], const double b[3], const double c[3], double tmax,
                    double *t, double *b1, double *b2);

#endif
