/* seg_tri.h — an independent segment-triangle crossing test for the
 * contact tests (orientation predicates with strict signs: touching is not
 * crossing), to check the suite's own CCD and impulse results against. */
#ifndef SEG_TRI_H
#define SEG_TRI_H

/* the signed volume (times 6) of the tetrahedron abcd */
static inline double tb_orient(const double *a, const double *b, const double *c, const double *d)
{
    double u[3], v[3], w[3];
    for (int i = 0; i < 3; i++) { u[i] = b[i] - a[i]; v[i] = c[i] - a[i]; w[i] = d[i] - a[i]; }
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* the open segment pq crosses the triangle abc */
static inline int tb_seg_tri(const double *p, const double *q, const double *a, const double *b, const double *c)
{
    double s1 = tb_orient(a, b, c, p), s2 = tb_orient(a, b, c, q);
    if (!((s1 > 0 && s2 < 0) || (s1 < 0 && s2 > 0))) return 0;
    double o1 = tb_orient(p, q, a, b), o2 = tb_orient(p, q, b, c), o3 = tb_orient(p, q, c, a);
    return (o1 > 0 && o2 > 0 && o3 > 0) || (o1 < 0 && o2 < 0 && o3 < 0);
}

#endif
