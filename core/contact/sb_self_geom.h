/* sb_self_geom.h — geometry of self-contact between the primitives of the
 * sampled surface (docs/contact.md "Self-contact"): typed squared distances
 * of point–triangle and edge–edge pairs with exact gradient and Hessian,
 * IPC's edge–edge mollifier, edge–edge and point–edge continuous collision
 * detection, and the static segment–triangle intersection test.
 *
 * A pair has four vertices x0..x3 (12 coordinates): point–triangle
 * (p, t0, t1, t2) or edge–edge (a0, a1, b0, b1).  Its distance type (IPC, Li
 * et al. 2020 §4.2 and its supplement: the closest features) is fixed by
 * sb_pt_type / sb_ee_type at the current state; the typed squared distance
 * is then a smooth function of the 12 coordinates whose derivatives are
 * exact within the type's region. */
#ifndef SB_SELF_GEOM_H
#define SB_SELF_GEOM_H

typedef enum sb_dist_type {
    /* point–triangle (p, t0, t1, t2) */
    SB_PT_P_T0, SB_PT_P_T1, SB_PT_P_T2,        /* point–vertex */
    SB_PT_P_E01, SB_PT_P_E12, SB_PT_P_E20,     /* point–edge */
    SB_PT_P_T,                                 /* point–face */
    /* edge–edge (a0, a1, b0, b1) */
    SB_EE_A0B0, SB_EE_A0B1, SB_EE_A1B0, SB_EE_A1B1,  /* endpoint–endpoint */
    SB_EE_A_B0, SB_EE_A_B1, SB_EE_A0_B, SB_EE_A1_B,  /* edge–endpoint */
    SB_EE_A_B,                                       /* edge–edge interiors */
    SB_DIST_NTYPES
} sb_dist_type;

/* The closest-feature type of point p against triangle (t0, t1, t2). */
sb_dist_type sb_pt_type(const double p[3], const double t0[3], const double t1[3], const double t2[3]);
/* The closest-feature type of segments a0a1 and b0b1 (nearly parallel
 * segments get an endpoint type, never SB_EE_A_B). */
sb_dist_type sb_ee_type(const double a0[3], const double a1[3], const double b0[3], const double b1[3]);

/* Squared distance of type `type` between the four vertices x (12), with
 * gradient g (12) and Hessian H (144, row-major) when non-NULL. */
double sb_typed_dist2(sb_dist_type type, const double x[12], double *g, double *H);

/* IPC's edge–edge mollifier (Li et al. 2020 §4.3, Eq. 17 of the
 * supplement): c = |(a1 - a0) x (b1 - b0)|^2, eps_x = 1e-3 |a1-a0|_rest^2
 * |b1-b0|_rest^2, m = (-c/eps_x + 2) c/eps_x for c < eps_x, 1 beyond; value
 * with gradient g (12) and Hessian H (144) w.r.t. (a0, a1, b0, b1) when
 * non-NULL. */
double sb_ee_mollifier(const double x[12], double eps_x, double *g, double *H);

/* Continuous collision of edges a (a0 -> a0', a1 -> a1') and b moving
 * linearly over t in [0, 1]: the first time at which the closed segments
 * touch, or 2 when they do not (sb_ccd_ee.c). */
double sb_ccd_edge_edge(const double a0[3], const double a0e[3], const double a1[3], const double a1e[3],
                        const double b0[3], const double b0e[3], const double b1[3], const double b1e[3]);
/* Continuous collision of point p (p -> p') against segment u v (u -> u',
 * v -> v'): the first time the point lies on the closed segment, or 2. */
double sb_ccd_point_edge(const double p[3], const double pe[3], const double u[3], const double ue[3],
                         const double v[3], const double ve[3]);

/* Does the closed segment a b cross or touch the closed triangle t0 t1 t2?
 * (static test; a segment lying in the triangle's plane counts when it
 * meets the triangle) */
int sb_segment_triangle_intersect(const double a[3], const double b[3], const double t0[3], const double t1[3],
                                  const double t2[3]);
/* Distance between the closed segments a0a1 and b0b1. */
double sb_self_segment_distance(const double a0[3], const double a1[3], const double b0[3], const double b1[3]);

#endif
