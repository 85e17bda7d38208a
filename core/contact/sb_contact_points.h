/* sb_contact_points.h — contact sample points of a discretization
 * (docs/contact.md): point p sits at x_p = sum_a w_a (x[dof_a], x[dof_a+1],
 * x[dof_a+2]) — the method's basis x(xi) = sum_I N_I(xi) q_I evaluated at a
 * fixed material point (weights N_I(xi_p), dof_a the first dof of the 3-vector
 * q_I), or a triangle vertex (one term, weight 1).  All terms of one point
 * must lie in one element of the method's sparsity pattern (the barrier's
 * Hessian couples them).  area is the reference area the point stands for
 * (the barrier is a surface integral, sampled). */
#ifndef SB_CONTACT_POINTS_H
#define SB_CONTACT_POINTS_H

typedef struct sb_contact_points {
    int n;              /* points */
    int *off;           /* n+1: terms of point p are off[p] .. off[p+1]-1 */
    int *dof;           /* first dof of the 3-vector of each term */
    double *w;          /* weight of each term */
    double *area;       /* n: reference area per point (m^2) */
    double *st;         /* 2n: grid parameter (s, t) of each point (for messages and records) */
    int cap_p, cap_t;
    /* The surface between the points (self-contact, docs/contact.md): nt
     * triangles of point indices (3 nt), consistently oriented, or nt = 0 when
     * the method does not triangulate its points. */
    int nt, cap_tri;
    int *tri;
} sb_contact_points;

/* Append one point with k terms; SB_OK or SB_ERR_NOMEM. */
int  sb_contact_points_add(sb_contact_points *cp, int k, const int *dof, const double *w, double area, double s,
                           double t);
/* Append triangle (a, b, c) of point indices; SB_OK or SB_ERR_NOMEM. */
int  sb_contact_points_add_tri(sb_contact_points *cp, int a, int b, int c);
/* Triangulate a (ns+1) x (nt+1) grid of points, map[j (ns+1) + i] = the
 * index of grid point (i, j) or -1 (absent): every cell with four points
 * gives two triangles, counter-clockwise in (i, j), its diagonal alternating
 * with the parity of i + j (no directional bias). */
int  sb_contact_grid_triangles(sb_contact_points *cp, const int *map, int ns, int nt);
void sb_contact_points_free(sb_contact_points *cp);
/* x_p of point p from the dof vector x */
void sb_contact_points_eval(const sb_contact_points *cp, int p, const double *x, double xp[3]);

#endif
