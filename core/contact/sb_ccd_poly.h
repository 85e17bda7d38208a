/* sb_ccd_poly.h — the polynomial core shared by the continuous collision
 * tests of core/contact (sb_ccd.c: point-triangle, sb_ccd_ee.c: edge-edge
 * and point-edge).  Internal to core/contact. */
#ifndef SB_CCD_POLY_H
#define SB_CCD_POLY_H

/* real roots in [0, 1] of c3 t^3 + c2 t^2 + c1 t + c0, ascending; their
 * count, or -1 when all coefficients are below `zero` (identically zero) */
int sb_ccd_roots01(double c3, double c2, double c1, double c0, double zero, double r[3]);

/* f(t) = ((e1 + t de1) x (e2 + t de2)) . (w + t dw) = k[3] t^3 + ... + k[0];
 * returns the configuration's length scale L (f is a volume, L^3) */
double sb_ccd_coplanar_cubic(const double e1[3], const double de1[3], const double e2[3], const double de2[3],
                             const double w[3], const double dw[3], double k[4]);

#endif
