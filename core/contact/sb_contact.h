/* sb_contact.h — contact against a scene's obstacles as a term of the
 * incremental potential (docs/contact.md):
 *
 *   Phi_c(x) = sum_p sum_o kappa a_p b(d_o(x_p))                 (IPC barrier, Li et al. 2020 Eq. 6)
 *            + sum_(p,o) mu_o lambda_po f0(|T_po^T (x_p - x_p^n - delta_po)|)  (lagged friction, IPC §5 Eq. 14-16)
 *
 * over the method's sample points x_p = sum_a w_a q_a (sb_contact_points.h),
 * with b(d) = -(d - dhat)^2 ln(d / dhat) for 0 < d < dhat (0 beyond).  One
 * object per level of a run; no global state.  The step filter
 * sb_contact_step_bound limits a trial step so that no sample point reaches
 * an obstacle along it. */
#ifndef SB_CONTACT_H
#define SB_CONTACT_H

#include "sb_scene.h"
#include "sb_sparse.h"
#include "sb_contact_points.h"

#include <stddef.h>

typedef struct sb_contact sb_contact;

/* Takes ownership of *pts (left zeroed). */
int  sb_contact_create(const sb_scene *sc, sb_contact_points *pts, sb_contact **out);
void sb_contact_free(sb_contact *c);
int  sb_contact_n_points(const sb_contact *c);

/* Obstacle poses of step `step` (the energy's) and of step - 1, and the
 * friction data lagged at x_n (normal forces, tangent bases, obstacle
 * slip); dt = 0 (quasi-static) switches friction off. */
int  sb_contact_begin_step(sb_contact *c, int step, double dt, const double *x_n);

/* f += Phi_c(x); g += its gradient and H += its Hessian when non-NULL
 * (H on the method's pattern).  SB_NONFINITE (f = inf) when a sample point
 * is inside an analytic obstacle or on a mesh triangle. */
int  sb_contact_energy(sb_contact *c, const double *x, double *f, double *g, sb_matrix *H);

/* The largest alpha in [0, 1] for which x + alpha d keeps every sample
 * point outside every obstacle: filter * (first time of impact) when a
 * point would reach one, else 1 (closed form for analytic obstacles,
 * point–triangle CCD for meshes). */
double sb_contact_step_bound(sb_contact *c, const double *x, const double *d);

/* A moving obstacle against the sample points at the start of a step
 * (docs/contact.md "Moving obstacles"): the point (index, world position
 * at x_n, grid parameter) that the obstacle's motion over step `step`
 * touches first, the fraction of the step at which it does (0: inside at
 * the start), and whether the point ends inside the obstacle's new pose.
 * sb_contact_sweep_check returns the number of points touched (0: none,
 * hit->point = -1). */
typedef struct sb_contact_sweep_hit {
    int point, obstacle;
    double when;
    double x[3], st[2];
    int ends_inside;
} sb_contact_sweep_hit;
int  sb_contact_sweep_check(const sb_contact *c, int step, const double *x_n, sb_contact_sweep_hit *hit);
/* Sample points of x inside an analytic obstacle (or on a mesh triangle)
 * in the poses of step `step` (0: the scene's start): their number, the
 * first in *hit. */
int  sb_contact_inside_check(const sb_contact *c, int step, const double *x, sb_contact_sweep_hit *hit);

typedef struct sb_contact_report {
    int points;              /* sample points */
    int active;              /* points within dhat of an obstacle (barrier active) */
    int inside;              /* points inside an analytic obstacle or on a mesh triangle */
    double min_distance;     /* smallest distance of a sample point to an obstacle (m) */
    /* between the sample points (issue 37): the sample triangles into which
     * an analytic obstacle's solid reaches deeper than dhat (or which a
     * capsule's axis pierces) although their three corners are outside it
     * (an obstacle crossing the cloth between the points); -1 when the
     * method does not triangulate its points (not checked); the first such
     * obstacle (-1: none) */
    int between;
    int between_obstacle;
    /* self-contact (zero / INFINITY without) */
    int self_pairs;          /* candidate pairs of the step */
    int self_active;         /* candidate pairs within dhat */
    double self_min_distance;/* smallest distance of a candidate pair (m) */
    int self_crossings;      /* sample edges crossing a non-incident sample triangle (-1: out of memory) */
    double self_max_move;    /* largest distance of a sample point from its step-start position (m) */
} sb_contact_report;
void sb_contact_measure(sb_contact *c, const double *x, sb_contact_report *r);

/* Self-contact (docs/contact.md "Self-contact", sb_self.h): set up from the
 * triangles of the sample points at the reference state xref;
 * SB_ERR_UNSUPPORTED with a sentence in why when it cannot be honoured.
 * Afterwards the energy, the step filter and the measurement include it. */
struct sb_self;
int  sb_contact_self_setup(sb_contact *c, const double *xref, char *why, size_t why_size);
struct sb_self *sb_contact_self(sb_contact *c);
const sb_contact_points *sb_contact_points_of(const sb_contact *c);
/* The Hessian's pattern was replaced (forget cached positions). */
void sb_contact_pattern_changed(sb_contact *c);
/* After a change of mesh (adaptation): push the sample points that are
 * inside an obstacle or closer than target out to target, moving the free
 * vertices of their combinations (fixed: per dof, may be NULL); obstacle
 * poses of step `step`.  *moved = pushes (a point pushed in two passes
 * counts twice); returns the points still closer than target (sb_contact.c). */
int  sb_contact_separate(sb_contact *c, int step, double *x, const unsigned char *fixed, double target, int *moved);

/* IPC barrier b(d) and its first two derivatives (Li et al. 2020 Eq. 6). */
double sb_barrier(double d, double dhat, double *db, double *ddb);
/* IPC friction mollifier f0(y) with eps (Li et al. 2020 Eq. 16) and f1 = f0', f1' */
double sb_friction_f0(double y, double eps, double *f1, double *df1);

#endif
