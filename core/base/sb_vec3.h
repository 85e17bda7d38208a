/* sb_vec3.h — the two 3-vector products the triangle methods use in their
 * element and mesh code (linear_fem, adaptive_sqrt3), written once. */
#ifndef SB_VEC3_H
#define SB_VEC3_H

static inline double sb_dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* c = a x b (c must not alias a or b) */
static inline void sb_cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

#endif
