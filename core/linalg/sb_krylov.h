/* sb_krylov.h — preconditioned conjugate gradients on the Hessian of one
 * level (solver.linear = pcg-jacobi | pcg-mg | pcg-amg, docs/solvers.md),
 * with the preconditioner as a constant type (sb_precond.h), workspaces
 * allocated once per run, and Steihaug–Toint truncation when a trust-region
 * radius is given.  CG iterations (and the seconds of the solves, the
 * preconditioner's set-up included) are counted here, once. */
#ifndef SB_KRYLOV_H
#define SB_KRYLOV_H

#include "sb_precond.h"

/* What one solve found (the per-iteration record keeps status and rtol). */
typedef enum {
    SB_KRYLOV_CONVERGED = 0,   /* ||H s + g|| <= rtol ||g|| */
    SB_KRYLOV_CAP = 1,         /* the iteration cap came first: s is inexact beyond rtol */
    SB_KRYLOV_NEGCURV = 2,     /* d^T H d <= 0 met (H not positive definite along d) */
    SB_KRYLOV_BOUNDARY = 3     /* ended on the trust-region boundary (Steihaug–Toint) */
} sb_krylov_status;

typedef struct sb_krylov_result {
    sb_krylov_status status;
    int iters;
    int precond_restart;   /* the preconditioner gave r^T M^{-1} r <= 0: CG restarted without it */
    double curvature;      /* d^T H d / d^T d where negative curvature was met */
    double relres;         /* ||H s + g|| / ||g|| at the end (the recursive residual) */
    double snorm;          /* ||s|| */
    double pred;           /* -(g^T s + s^T H s / 2) */
    double znorm;          /* ||M^{-1} r|| at the end when ztol was set (0 otherwise) */
    int by_correction;     /* stopped by ztol (status CONVERGED) */
} sb_krylov_result;

typedef struct sb_krylov {
    int n, level;
    const sb_precond_type *type;
    void *pstate;
    double *r, *z, *d, *Hd, *diag0;
    int shifted;           /* the level's Hessian holds diag0 + shift */
    /* > 0: CG also stops (CONVERGED, by_correction) after an iteration whose
     * preconditioned residual z = M^{-1} r has ||z|| <= ztol.  z is the
     * preconditioner's estimate of the iterate's remaining error s* - s =
     * H^{-1} r, so the caller sets ztol below the smallest correction it
     * can use (solver.cg_xstop: a tenth of run.xtol_rel ||x||); set per solve
     * by the caller, 0 by sb_krylov_alloc */
    double ztol;
} sb_krylov;

/* solver.cg_xstop of lsnewton, damped and tr (newton.c, tr.c): the ztol of
 * a solve, a tenth of xstop = run.xtol_rel ||x|| (sb_iterate_info.xstop;
 * why a tenth: newton.c krylov_direction), 0 when the test is off or the
 * stopping rule has no xstop */
static inline double sb_krylov_xstop_ztol(int on, double xstop) { return on && xstop > 0.0 ? 0.1 * xstop : 0.0; }

#define SB_CG_XSTOP_HELP                                                                                               \
    "Krylov paths with Eisenstat-Walker forcing, run.stop=scaled: 1 stops CG also when its preconditioned residual "   \
    "||M^-1 r|| (the estimate of the step's remaining error) is below run.xtol_rel ||x|| / 10 (run.xtol_rel ||x||: "  \
    "the smallest correction the stopping rule resolves); the correction the roundoff_limit test sees is then "        \
    "||s|| + ||M^-1 r||; 0: the forcing terms alone"

/* Workspaces and the preconditioner's alloc (which refuses what cannot work
 * with a sentence in the context). */
int  sb_krylov_alloc(sb_krylov *k, sb_problem *p, int level, const sb_precond_type *type, const sb_precond_opts *o);
void sb_krylov_free(sb_krylov *k);
/* The preconditioner of the level's Hessian as last assembled (or shifted):
 * once per Newton iteration.  SB_OK, SB_NOT_POSDEF or an error. */
int  sb_krylov_setup(sb_krylov *k, sb_problem *p);
/* Replace the level's Hessian by H + shift I in place (the diagonal kept,
 * so sb_krylov_unshift restores the same bits); set up again after it. */
int  sb_krylov_shift(sb_krylov *k, sb_problem *p, double shift);
void sb_krylov_unshift(sb_krylov *k, sb_problem *p);
/* s ~ -H^{-1} g from s = 0 by PCG: stops at ||r|| <= rtol ||g||, at
 * max_iter iterations, at negative curvature (to the boundary when delta is
 * finite, else where it was met), or on the boundary ||s|| = delta
 * (Steihaug 1983, Toint 1981; Nocedal & Wright Alg. 7.2; the trust region is
 * Euclidean, as sb_trs.c's). */
int  sb_krylov_solve(sb_krylov *k, sb_problem *p, const double *g, double delta, double rtol, int max_iter,
                     double *s, sb_krylov_result *res);
void sb_krylov_describe(const sb_krylov *k, char *buf, size_t len);
/* Set up and solve s = -H^{-1} g to rtol without a radius: SB_OK only when
 * CG reached rtol (capped or negative curvature: SB_NOT_POSDEF). */
int  sb_krylov_solve_to(sb_krylov *k, sb_problem *p, const double *g, double rtol, int max_iter, double *s);

/* Eisenstat & Walker (1996), choice 2, with their safeguards:
 *   eta_k = gamma (||g_k|| / ||g_{k-1}||)^alpha,  gamma = 0.9, alpha = 2,
 *   eta_k = max(eta_k, gamma eta_{k-1}^alpha)  when gamma eta_{k-1}^alpha > 0.1,
 *   eta_k = min(eta_k, eta_max = 0.9),  eta_0 = 0.5,
 * and a floor of 1e-10 (below it CG meets its round-off).  gprev <= 0:
 * the first iteration of a step. */
double sb_forcing_ew2(double gnorm, double gprev, double eta_prev);

/* The same with progress measured by the smaller of two ratios:
 * ||g_k|| / ||g_{k-1}|| and ||s_{k-1}|| / ||s_{k-2}||, the norms of the last
 * two steps taken (snorm, sprev; sprev <= 0: not known yet).  Assumption
 * (not in Eisenstat & Walker): their analysis needs a progress measure
 * equivalent to the error near the solution, and the Newton step is one
 * (s_k ~ -e_k); the gradient is not once it reaches its round-off floor
 * (about 1e-5 at 2.5e5 dofs on the denim trampoline), where its ratio sits
 * near 1 and choice 2 returns eta_max: one CG iteration a Newton iteration,
 * each removing about half of the remaining correction (12 Newton
 * iterations where the direct solve needs 3; docs/solvers.md, "Inexact
 * Newton").  The smaller ratio never loosens the
 * choice-2 term; the safeguard on eta_{k-1} still bounds how fast it falls. */
double sb_forcing_ew2_steps(double gnorm, double gprev, double snorm, double sprev, double eta_prev);

/* Kelley's safeguard against oversolving in the last Newton iterations
 * (C. T. Kelley, Iterative Methods for Linear and Nonlinear Equations,
 * SIAM 1995, Eq. (6.20)): eta = min(eta_max, max(eta, 0.5 gstop / ||g||)),
 * gstop the gradient norm the step stops at, so that a solve never asks for
 * a residual far below it (at ||g|| = 2 gstop it asks for gstop / 4, not
 * the choice-2 term's eta^2-driven 1e-8).  gstop <= 0 or the fixed
 * cg_rtol: eta unchanged. */
double sb_forcing_floor(double eta, double gnorm, double gstop);

/* The forcing floor's second bound: the computed gradient's rounding e
 * (sb_problem_gradient_noise), below which no residual changes the state a
 * step ends with, so that a Newton iteration never solves more accurately
 * than it can use (the clamped plate's last Newton iteration asked 6e-9 of
 * CG, 59 of its 94 iterations, for a gradient that stalls at 2.5e-9 anyway).
 * What matters is the correction, not the residual: the rounding of a stiff
 * penalty (the subdivision method's boundary band) is large in ||.|| and
 * moves x by nothing, while a soft mode's residual below it still moves x.
 * So the two are compared after the preconditioner, M^{-1} ~ H^{-1}:
 *     eta >= min(eta_max, 0.5 ||M^{-1} e|| / ||M^{-1} g||)
 * (with Kelley's gstop floor).  e is measured at most once a step (two
 * gradient evaluations), at the first iteration whose forcing term is below
 * 0.1 — the fast local phase, where the floor can bind; ||M^{-1} e|| is kept
 * for the step and ||M^{-1} g|| costs one preconditioner application an
 * iteration from then on.  Steps that never get there pay nothing.  Off by
 * default: measured, it saves 10 % on the plate and costs 5 % on the
 * trampoline (docs/solvers.md).  No
 * preconditioner (its set-up failed: an indefinite H) or
 * solver.cg_noise_floor = 0: Kelley's floor alone. */
typedef struct sb_noise_floor {
    int on;          /* solver.cg_noise_floor */
    int measured;    /* this step */
    double level;    /* ||e|| (0: not measured, or not the rounding's) */
    double zeta;     /* ||M^{-1} e|| at the measurement (0: none) */
} sb_noise_floor;
#define SB_NOISE_FLOOR_HELP "1: Krylov paths with Eisenstat-Walker forcing never ask for a residual whose correction is " \
    "below that of the computed gradient's rounding, measured once a step (two gradient evaluations); 0 (default): " \
    "Kelley's floor alone"
void sb_noise_floor_reset(sb_noise_floor *nf);
/* eta after both floors; x, g: the iterate and its gradient, the level's
 * Hessian assembled at x and k's preconditioner set up for it (have_m = 0:
 * not); w_x, w_g, w_h: n-vector workspaces (k's own are used too) */
int sb_noise_floor_apply(sb_noise_floor *nf, sb_krylov *k, int have_m, sb_problem *p, const double *x, const double *g,
                         double gnorm, double gstop, double *w_x, double *w_g, double *w_h, double *eta);

/* The round-off test of the Krylov paths' line search and trust-region
 * ratio: an inexact Newton step leaves a residual in the stiff (membrane)
 * directions whose Newton correction changes f by far less than the
 * round-off of an energy summed over thousands of elements, which is well
 * above the 1e4 eps |f| of the direct paths (sb_tr_ared_unreliable; on
 * scordelis_lo, bhem res 4: corrections of 1e-14 J against |f| = 1.2e-3 J,
 * and lsnewton stalled).  1 when the predicted and the actual change are
 * both below 1e7 eps |f|: the decrease is then decided from gradients, the
 * trapezoid rule (Conn, Gould & Toint §17.4.2), as the direct paths do
 * below 1e4 eps |f|. */
int sb_krylov_f_noise(double f, double f_trial, double pred);

/* The choices of solver.linear (lsnewton, tr, damped) and its index. */
enum { SB_LINEAR_CHOLMOD = 0, SB_LINEAR_PCG_LEGACY, SB_LINEAR_PCG_JACOBI, SB_LINEAR_PCG_MG, SB_LINEAR_PCG_AMG };
extern const char *const sb_linear_names[];        /* cholmod, pcg-jacobi, pcg-mg, pcg-amg */
/* the SB_LINEAR_* of a choice name; -1 when unknown */
int sb_linear_kind(const char *name);
/* the preconditioner type of a Krylov kind, NULL for cholmod / legacy */
const sb_precond_type *sb_linear_precond(int kind);

#endif
