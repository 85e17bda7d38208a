/* sb_trs.h — trust-region subproblem (QP) solvers, as their own small type
 * (GSL trs style):  min m(s) = g^T s + 1/2 s^T H s  subject to ||s|| <= Delta,
 * with H the level's Hessian as last assembled by sb_problem_eval(). */
#ifndef SB_TRS_H
#define SB_TRS_H

#include "sb_problem.h"

typedef struct sb_trs_result {
    double pred;        /* predicted reduction m(0) - m(s) >= 0 */
    double snorm;       /* ||s|| */
    int iters;          /* CG iterations, or 1 for a direct solve */
    int boundary;       /* 1 when the step lies on the trust-region boundary */
    int posdef;         /* dogleg: 1 when H factored (Newton point available) */
    int newton;         /* 1 when s is the (possibly truncated) Newton step, not limited by the
                           radius: dogleg's interior Newton point, ST-CG's interior end on its
                           residual or iteration cap (the limiting-accuracy test, docs/trust.md) */
} sb_trs_result;

enum { SB_TRS_SAME_H = 1 << 1 };

typedef struct sb_trs_type {
    const char *name;
    size_t state_size;
    int  (*alloc)(void *state, int n);
    void (*free)(void *state);
    /* fresh = 1 when H or g changed since the last call on this state (a
     * direct method then refactors; otherwise cached factors/points are
     * reused); fresh = 1 | SB_TRS_SAME_H when only g changed (the factor or
     * preconditioner of H is kept). */
    int  (*solve)(void *state, sb_problem *p, int level, const double *g, double delta,
                  int fresh, int max_iter, double *s, sb_trs_result *r);
} sb_trs_type;

extern const sb_trs_type sb_trs_dogleg;   /* Nocedal & Wright §4.1; sparse direct Newton point */
extern const sb_trs_type sb_trs_stcg;     /* Steihaug–Toint truncated CG */

extern const char *const sb_trs_names[];  /* "dogleg", "stcg", NULL */
extern const char *const sb_trs_indefinite_names[];  /* "cauchy", "shift", NULL */
extern const char *const sb_trs_precond_names[];  /* ST-CG preconditioners, indexed as sb_trs_set_cg_precond */
const sb_trs_type *sb_trs_by_index(int i);

/* A TRS instance: type + state. */
typedef struct sb_trs {
    const sb_trs_type *type;
    void *state;
} sb_trs;

int  sb_trs_alloc(sb_trs *t, const sb_trs_type *type, int n);
/* Steihaug–Toint CG stopping on the residual: rtol < 0 (default) uses the
 * forcing term min(0.5, sqrt||g||) of inexact Newton methods; rtol >= 0 stops
 * at ||r|| <= rtol ||g|| (0: run all max_iter iterations, as a smoother). */
void sb_trs_set_cg_rtol(sb_trs *t, double rtol);
/* Preconditioner of Steihaug–Toint CG (index into sb_trs_precond_names): 0
 * none, 1 Jacobi, 2 node-block Jacobi, 3 symmetric block Gauss–Seidel, 4
 * additive Schwarz on element patches.  The trust region stays Euclidean. */
void sb_trs_set_cg_precond(sb_trs *t, int precond);
/* Dogleg on an indefinite H: 0 (default, paper) Cauchy point; 1 Newton point
 * of a shifted, positive definite H + tau I. */
void sb_trs_set_shift_indefinite(sb_trs *t, int on);
void sb_trs_free(sb_trs *t);
/* Solve and count one QP work unit on `level` (RMTR paper Eq. 7.3). */
int  sb_trs_solve(sb_trs *t, sb_problem *p, int level, const double *g, double delta, int fresh,
                  int max_iter, double *s, sb_trs_result *r);

/* Trust-region ratio rho = (f - f_trial) / pred (RMTR paper Eq. 4.2, 4.11),
 * -inf for a failed or non-finite trial.  When the actual and the predicted
 * reduction are both below the round-off of f (100 eps |f|), the ratio carries
 * no information and is taken as 1 (Conn, Gould & Toint, Trust-Region Methods,
 * §17.4.2): otherwise the radius collapses at the limiting accuracy. */
double sb_tr_ratio(int trial_status, double f, double f_trial, double pred);

/* Near the limiting accuracy the difference f - f_trial is mostly round-off
 * (an energy summed over thousands of elements carries far more than the
 * 100 eps |f| above).  When the predicted reduction is below 1e4 eps |f|
 * (sb_tr_ared_unreliable), the actual reduction is taken from gradients,
 * ared = -(g + g_trial)^T s / 2 (trapezoid rule, exact for a quadratic, error
 * O(||s||^3); Conn, Gould & Toint, Trust-Region Methods, §17.4.2), and
 * sb_tr_ratio_grad returns ared / pred. */
int sb_tr_ared_unreliable(double f, double f_trial, double pred);
double sb_tr_ratio_grad(int n, const double *g, const double *g_trial, const double *s, double pred);

#endif
