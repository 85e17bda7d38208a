/* sb_self.h — self-contact of the sampled surface as a term of the
 * incremental potential (docs/contact.md "Self-contact"):
 *
 *   Phi_s(x) = sum_(p,T) kappa a_p b(d_pT(x)) + sum_(e,e') kappa a_ee' m_ee'(x) b(d_ee'(x))
 *
 * over point–triangle and edge–edge pairs of the method's sample points
 * and the triangles between them (sb_contact_points.tri) that share no
 * vertex, with IPC's barrier b (Li et al. 2020 Eq. 6) and edge–edge
 * mollifier m (§4.3).  Pairs are those of a per-step candidate set: the
 * pairs within dhat + margin at the start of the step (spatial hash,
 * sb_hash.h); the step filter keeps every sample point within margin/2 of
 * its position at the start of the step, so no other pair can come within
 * dhat during the step, and limits every trial step by continuous collision
 * detection of the candidate pairs.  No global state. */
#ifndef SB_SELF_H
#define SB_SELF_H

#include "sb_contact_points.h"
#include "sb_sparse.h"

#include <stddef.h>

typedef struct sb_self sb_self;

/* Build the edges of pts' triangles and their rest lengths at xref;
 * SB_ERR_UNSUPPORTED with a sentence in why when pts has no triangles or
 * when dhat is not below half the smallest distance between two sample
 * primitives that share no vertex at xref (the rest state would touch
 * itself).  pts must outlive the object. */
int  sb_self_create(const sb_contact_points *pts, const double *xref, double dhat, double kappa, double filter,
                    sb_self **out, char *why, size_t why_size);
void sb_self_free(sb_self *s);

/* The candidate set of a step: pairs within dhat + margin at x0, with
 * margin = max(8 dhat, 4 max_p |xhat_p - x0_p|) (xhat: the inertial
 * prediction x_n + dt v_n, or NULL); x0 is the centre of the step filter's
 * margin.  SB_OK or SB_ERR_NOMEM. */
int  sb_self_begin_step(sb_self *s, const double *x0, const double *xhat);
int  sb_self_n_pairs(const sb_self *s);
/* The four sample points of candidate pair k (point, triangle or edge, edge). */
void sb_self_pair_points(const sb_self *s, int k, int pts[4]);
double sb_self_margin(const sb_self *s);

/* e += Phi_s(x), g += gradient, H += Hessian (upper triangle on H's
 * pattern).  SB_NONFINITE when a pair has distance 0; SB_ERR_INTERNAL when
 * a coupling is outside H's pattern; SB_ERR_NOMEM. */
int  sb_self_energy(sb_self *s, const double *x, double *e, double *g, sb_matrix *H);
/* The largest alpha in [0, 1]: every sample point stays within margin/2 of
 * its step-start position along x + t d, t <= alpha, and filter * (first
 * time of impact of a candidate pair) when one would touch. */
double sb_self_step_bound(sb_self *s, const double *x, const double *d);

typedef struct sb_self_report {
    int pairs;            /* candidate pairs of the step */
    int active;           /* pairs within dhat */
    double min_distance;  /* smallest distance of a candidate pair (m) */
    int crossings;        /* sample edges crossing a sample triangle they do not share a vertex with */
    double max_move;      /* largest distance of a sample point from its step-start position (m) */
} sb_self_report;
/* Figures at x; crossings by an exhaustive hashed test of every edge
 * against every triangle (independent of the candidate set). */
int  sb_self_measure(sb_self *s, const double *x, sb_self_report *r);

#endif
