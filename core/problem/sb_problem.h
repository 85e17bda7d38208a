/* sb_problem.h — the per-step minimization problem every solver sees.
 *
 *   Phi(x) = 1/(2 dt^2) (x - xhat)^T M (x - xhat)                (inertia, dynamic)
 *          + 1/(2 dt)   (x - x_n)^T (alpha M + beta K_n) (x - x_n) (Rayleigh damping, dynamic)
 *          + E(x)                                                 (method: elastic + external + penalty)
 *   xhat = x_n + dt v_n,  K_n = Hessian of E at x_n (lagged),  DESIGN.md.
 *
 * Quasi-static scenes drop the first two terms.  Constrained dofs are
 * eliminated: they hold their prescribed values, their gradient entries are
 * zero and their Hessian rows/columns are identity.
 *
 * Every evaluation, factorization, solve and transfer made through this
 * interface is counted in the context's statistics (events per level, work
 * units per RMTR paper Eq. 7.3). */
#ifndef SB_PROBLEM_H
#define SB_PROBLEM_H

#include "sb_method.h"
#include "sb_linsolve.h"

struct sb_context;
typedef struct sb_problem sb_problem;

int  sb_problem_create(struct sb_context *ctx, const sb_method_type *mt, void *method_state,
                       const sb_scene *scene, sb_problem **out);
/* Rebuild every level from the method's current discretization after it
 * adapted its mesh (sb_method.h adapt); SB_OK or an error status. */
int  sb_problem_rebuild(sb_problem *p);
void sb_problem_free(sb_problem *p);

int  sb_problem_levels(const sb_problem *p);
int  sb_problem_n(const sb_problem *p, int level);
int  sb_problem_finest(const sb_problem *p);
/* The step of the run under way (sb_problem_begin_step; 0 before the first).
 * Solvers keep no state across steps, so that a run resumed at a step
 * boundary computes what an uninterrupted one does: what depends on the
 * step (RMTR's first-step nested start) asks here. */
int  sb_problem_step(const sb_problem *p);
int  sb_problem_has_hierarchy(const sb_problem *p);
struct sb_context *sb_problem_context(sb_problem *p);
const sb_method_type *sb_problem_method_type(const sb_problem *p);
void *sb_problem_method_state(sb_problem *p);

/* Start a step: passes step data to the method, builds xhat and the lagged
 * damping matrix on every level, and writes into x0 (finest level) the initial
 * iterate: x_n with constrained dofs at their new prescribed values. */
int  sb_problem_begin_step(sb_problem *p, const sb_step_info *si,
                           const double *x_n, const double *v_n, double *x0);

/* Optional predictor for moving boundaries: replace the elimination start x0
 * (x_n with jumped constrained values) by the linear elastic lifting of the
 * boundary increment when that is admissible and not worse (sb_problem.c). */
/* A linear solve with the finest level's Hessian as the problem holds it
 * (assembled, constrained): s = -H^{-1} g by a solver's own linear path
 * (sb_solver_type.linear_solve); SB_OK, SB_ERR_UNSUPPORTED (no path of its
 * own: CHOLMOD is used) or another status (then nothing is used). */
typedef int (*sb_linear_solve_fn)(void *state, sb_problem *p, const double *g, double *s);
/* solve NULL: CHOLMOD (sb_problem_factor / sb_problem_solve) */
int  sb_problem_lift(sb_problem *p, const double *x_n, double *x0, sb_linear_solve_fn solve, void *state);

/* The force scale of the current step (run.stop=scaled, docs/trust.md):
 * ||grad E|| over the free dofs of the method's energy alone (elastic +
 * external + penalty; no inertia, no damping) at the reference
 * configuration of the finest level, with the step's loads and boundary
 * data as set by sb_problem_begin_step.  For dead loads on an elimination
 * method this is the norm of the applied forces.  One gradient evaluation,
 * counted.  SB_OK, SB_NONFINITE (F = inf) or an error. */
int  sb_problem_force_scale(sb_problem *p, double *F);

/* E(x) of the method alone on the finest level (elastic + external +
 * penalty: no inertia, no damping, constrained dofs as in x), with the
 * current step's data; one energy evaluation, counted.  SB_OK, SB_NONFINITE
 * or an error. */
int  sb_problem_method_energy(sb_problem *p, const double *x, double *e);

/* f = Phi(x) at `level`; g and H optional (H: the level's Hessian matrix,
 * sb_problem_hessian()).  Returns SB_OK or SB_NONFINITE. */
int  sb_problem_eval(sb_problem *p, int level, const double *x, double *f, double *g, sb_matrix *H);
sb_matrix *sb_problem_hessian(sb_problem *p, int level);
/* The element scatter maps of a level's pattern, built at the first need:
 * before reading a level's matrix by elements (sb_matrix_get_element,
 * rmtr's Schwarz smoother); the problem's own assemblies call it. */
int sb_problem_element_maps(sb_problem *p, int level);
/* Factor the level's Hessian (as last assembled) + shift I.  SB_NOT_POSDEF is an outcome. */
int  sb_problem_factor(sb_problem *p, int level, double shift);
int  sb_problem_solve(sb_problem *p, int level, const double *b, double *x);
/* The level's direct solver (NULL before its first factorization): its
 * analysis's figures (sb_linsolve_supernodes) for benches. */
const sb_linsolve *sb_problem_linsolve(const sb_problem *p, int level);
/* y = H x with the level's Hessian as last assembled. */
void sb_problem_hess_mult(sb_problem *p, int level, const double *x, double *y);
/* d = diag(H) of the last assembly on the level */
void sb_problem_hess_diag(const sb_problem *p, int level, double *d);
/* dofs per node, and the bs x bs diagonal node blocks of H (n * bs values, row-major per node) */
int  sb_problem_block_size(const sb_problem *p, int level);
void sb_problem_hess_block_diag(const sb_problem *p, int level, double *B);

/* Zero the constrained entries of a correction / gradient-like vector. */
void sb_problem_constrain(const sb_problem *p, int level, double *v);
/* Overwrite constrained entries of an iterate with prescribed values. */
void sb_problem_impose(const sb_problem *p, int level, double *x);
/* Euclidean norm over free dofs. */
double sb_problem_norm(const sb_problem *p, int level, const double *v);
/* The rounding level of the computed gradient at x (sb_noise.c): the ||g||
 * below which no solve can drive the computed gradient — the evaluation's
 * rounding, measured from two gradient evaluations (counted) at x perturbed
 * by a few units in the last place (g the gradient at x, H =
 * sb_problem_hessian its Hessian there), and H dx, dx the rounding of the
 * state to doubles.  *rounding (optional): the evaluation's part alone, 0
 * when the differences are H's, not the rounding's (H not the Hessian of g:
 * a PSD projection).  w_x, w_g, w_h: n-vector workspaces; w_h ends holding
 * a vector of the level's size and kind (*noise = its norm).  SB_OK,
 * SB_NONFINITE or an error. */
int sb_problem_gradient_noise(sb_problem *p, int level, const double *x, const double *g, double *w_x, double *w_g,
                              double *w_h, double *noise, double *rounding);

/* Transfers (counted); lc is the coarse level. */
int  sb_problem_prolong(sb_problem *p, int lc, const double *xc, double *xf);
int  sb_problem_restrict(sb_problem *p, int lc, const double *gf, double *gc);
int  sb_problem_project(sb_problem *p, int lc, const double *xf, double *xc);

/* H_lc := I^T H_{lc+1} I (Galerkin coarse Hessian, sb_galerkin.h) from the
 * Hessian of level lc+1 as last assembled or set, on the free dofs; the
 * constrained dofs of level lc get identity rows.  Counted as the event
 * "galerkin" on level lc. */
int  sb_problem_galerkin_hessian(sb_problem *p, int lc);
/* Set-up of the above (prolongation matrix, symbolic product), done by the
 * first call; SB_ERR_UNSUPPORTED (with a message) when I^T H I does not fit
 * the coarse level's sparsity pattern. */
int  sb_problem_galerkin_prepare(sb_problem *p, int lc);
/* The same in the lean form (sb_galerkin_create_lean: no index of the fine
 * pattern's lower part; other round-off): pcg-mg's.  Whichever form a level
 * was prepared in first is kept (the rmtr solver prepares the indexed one). */
int  sb_problem_galerkin_prepare_lean(sb_problem *p, int lc);

/* Contact (docs/contact.md).  The step filter: the largest alpha in [0, 1]
 * such that x + alpha d keeps every contact sample point of the level
 * outside every obstacle (1 when the scene has no obstacles); solvers scale
 * their trial steps by it.  Counted as the event "collide". */
int    sb_problem_has_contact(const sb_problem *p);
/* max |x(st(f)) - p(f)| of the finest level's sliding pins at x (sb_pin.h),
 * their number in *n_pins (0: none, and 0 is returned) */
double sb_problem_pin_violation(const sb_problem *p, const double *x, int *n_pins);
/* contact.model = "impulse" (docs/contact.md): whether the run calls the
 * method's impulse_response after every accepted step, and that call on
 * the finest level (x0 at t_n, x1 at t1 corrected in place; timed as event
 * collide, counted into *st).  SB_OK, SB_NONFINITE, or an error (< 0). */
struct sb_impulse_stats;
int    sb_problem_has_impulse(const sb_problem *p);
int    sb_problem_impulse(sb_problem *p, double t1, const double *x0, double *x1, struct sb_impulse_stats *st);
double sb_problem_step_bound(sb_problem *p, int level, const double *x, const double *d);
/* Sample points of the finest level at x: returns their number (0: no
 * contact) and the smallest distance to an obstacle, the points within
 * dhat and the points inside an obstacle. */
/* After an adaptation (sb_run_adapt): push the finest level's sample points
 * that the new mesh put inside an obstacle or closer than dhat/100 out to
 * dhat/100 (obstacle poses of step `step`; sb_contact_separate).  *moved =
 * pushes (sb_contact_separate); returns the points still closer (0 without contact). */
int    sb_problem_contact_separate(sb_problem *p, int step, double *x, int *moved);
int    sb_problem_contact_measure(sb_problem *p, const double *x, double *min_distance, int *active, int *inside);
/* The full report of the finest level's contact at x (sb_contact_measure:
 * also the sample triangles an analytic obstacle crosses between the
 * points) and the sample spacing sqrt(mean area per point) (m); returns
 * 0 (and leaves *r) without contact. */
struct sb_contact_report;
int    sb_problem_contact_report(sb_problem *p, const double *x, struct sb_contact_report *r, double *spacing);

/* Moving obstacles against the finest level's sample points at x_n
 * (docs/contact.md "Obstacles that move through the cloth"): the barrier
 * sees an obstacle at the step's end only, so one whose motion over step
 * `step` sweeps through a sample point is caught here, before the solve.
 * Returns the number of points its motion touches (0 without contact or
 * with contact.model "impulse", whose response sweeps the obstacles
 * itself), with a sentence in why naming the obstacle, the point and what
 * to change. */
int    sb_problem_contact_swept(sb_problem *p, int step, const double *x_n, char *why, size_t why_size);
/* The start x against the obstacles' poses at step 0, with the method's
 * contact sample points of the finest level (both contact models): the
 * number of points inside an analytic obstacle or on a mesh triangle, with
 * a sentence naming the obstacle and the first point in why.  < 0 on error. */
int    sb_problem_contact_start_check(sb_problem *p, const double *x, char *why, size_t why_size);

/* Account one trust-region subproblem (QP) solve on a level: QP work units. */
void sb_problem_count_qp(sb_problem *p, int level, double seconds);
/* The start of a timed part (sb_stats_begin of the run's statistics) and a
 * QP solve counted from it: exclusive seconds too (sb_stats.h). */
double sb_problem_clock(sb_problem *p);
void sb_problem_count_qp_since(sb_problem *p, int level, double t0);
/* Account CG iterations on a level. */
void sb_problem_count_cg(sb_problem *p, int level, int iters);
/* Account a Krylov linear solve or its preconditioner's set-up
 * (solver.linear, sb_krylov.c) as one `cg_iter` event begun at t0 =
 * sb_problem_krylov_begin(p), counting its CG iterations (0 for a set-up). */
double sb_problem_krylov_begin(sb_problem *p);
void sb_problem_count_krylov(sb_problem *p, int level, int iters, double t0);

/* Self-contact (docs/contact.md): 1 once after a level's sparsity pattern
 * was replaced at the start of a step (the solver re-allocates its
 * pattern-bound data), else 0. */
int  sb_problem_take_pattern_change(sb_problem *p);
/* Self-contact figures at x on the finest level: candidate pairs, pairs
 * within dhat, smallest distance, sample edges crossing sample triangles;
 * returns 0 (and leaves them) without self-contact. */
int  sb_problem_self_measure(sb_problem *p, const double *x, int *pairs, int *active, double *min_distance,
                             int *crossings);
/* ... and the largest distance of a sample point from its step-start position */
int  sb_problem_self_measure_ex(sb_problem *p, const double *x, int *pairs, int *active, double *min_distance,
                                int *crossings, double *max_move);

#endif
