/* sb_geometry.h — domain map (grid parameter -> material coordinates) and
 * charts (material coordinates -> reference surface in R^3), each with first
 * and second derivatives, plus the composite used by structured methods. */
#ifndef SB_GEOMETRY_H
#define SB_GEOMETRY_H

#include "sb_scene.h"

/* Derivatives of a map F(u,v) -> R^d: val[d], du[d], dv[d], duu[d], duv[d], dvv[d]. */
typedef struct sb_jet3 { double x[3], d1[3], d2[3], d11[3], d12[3], d22[3]; } sb_jet3;
typedef struct sb_jet2 { double x[2], d1[2], d2[2], d11[2], d12[2], d22[2]; } sb_jet2;

/* (s,t) in [0,1]^2 -> xi, with derivatives. */
void sb_domain_map(const sb_domain *d, double s, double t, sb_jet2 *out);
/* xi -> (s,t); returns 0 when xi lies in the (closed) domain, 1 otherwise. */
int  sb_domain_unmap(const sb_domain *d, const double xi[2], double st[2]);
/* Is the grid point (s,t) inside the domain (L-shape: outside the notch)?
 * Points on the boundary count as inside. */
int  sb_domain_contains_st(const sb_domain *d, double s, double t);
/* Bounding box in xi: [lo0, hi0] x [lo1, hi1]. */
void sb_domain_bbox(const sb_domain *d, double lo[2], double hi[2]);
/* Diameter of the reference surface's domain (for relative errors). */
double sb_domain_diameter(const sb_domain *d);
/* L-shape notch rectangle in (s,t): [s0,s1]x[t0,t1]; returns 0 if no notch. */
int  sb_domain_notch_st(const sb_domain *d, double s01[2], double t01[2]);

/* xi -> X (reference surface), with derivatives w.r.t. xi.  Conventions in
 * sb_chart.c: a_3 = a_1 x a_2 is +e_z (plane), outward (cylinder), inward
 * (sphere). */
void sb_chart_eval(const sb_chart *c, const sb_domain *d, const double xi[2], sb_jet3 *out);

/* Composite (s,t) -> X with derivatives w.r.t. (s,t) (chain rule, exact). */
void sb_geometry_eval_st(const sb_scene *sc, double s, double t, sb_jet3 *out);

/* Named boundary part lookup, fills `part` (edge segment in (s,t)).  Returns
 * SB_ERR_INPUT when the name does not exist for this domain kind. */
int sb_domain_edge_part(const sb_domain *d, const char *name, sb_part *part);
/* NULL-terminated list of the edge part names valid for a domain kind:
 * rectangle left/right/bottom/top, L-shape the same plus notch_s/notch_t,
 * annulus sector inner/outer/start/end. */
const char *const *sb_domain_part_names(sb_domain_kind kind);

/* Does grid point (s,t) lie on the part (within tol in (s,t))? */
int sb_part_contains_st(const sb_part *p, double s, double t, double tol);

/* Sample grid of material points inside the domain for error metrics:
 * n x n in (s,t) excluding points in the L-shape notch; returns count,
 * writes up to max points into st (2 per point).  The nodes are
 * (i/(n-1), j/(n-1)), i,j = 0..n-1 (boundary included; notch boundary counts
 * as inside), row by row in t; n = 1 gives the centre (0.5, 0.5).  The count
 * returned is the full count even when it exceeds max. */
int sb_domain_sample_grid(const sb_domain *d, int n, double *st, int max);

/* Rotation matrix for angle about unit axis (Rodrigues). */
void sb_rotation(const double axis[3], double angle, double R[9]);

#endif
