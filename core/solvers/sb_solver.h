/* sb_solver.h — outer nonlinear solvers (GSL multimin style):
 * alloc / set / iterate / free behind a constant type table, with the loop,
 * convergence test (RMTR paper Eq. 7.1) and recording in one core file
 * (sb_solve.c). */
#ifndef SB_SOLVER_H
#define SB_SOLVER_H

#include "sb_problem.h"

enum {
    SB_SOLVER_NEEDS_HIERARCHY = 1u << 0, /* needs method prolong/restrict/project */
    SB_SOLVER_SINGLE_STEP = 1u << 1,     /* one iteration per step by design (linearized) */
    SB_SOLVER_TRUST_REGION = 1u << 2     /* reports a radius; (7.1) f/x tests gated by Delta */
};

/* What one iteration reports to the core loop. */
typedef struct sb_iterate_info {
    double f;            /* objective at the (possibly unchanged) iterate */
    double gnorm;        /* ||g|| over free dofs at the iterate */
    double delta;        /* trust-region radius after the update (TR solvers) */
    double rho;          /* TR ratio, or line-search step length */
    double step_norm;    /* ||x_new - x_old|| (0 when rejected) */
    double df;           /* f_old - f_new (0 when rejected) */
    double shift;        /* diagonal shift that made the factorization succeed */
    int accepted;
    int linear_iters;
    int level;           /* level of the reported quantities */
    sb_reason fail;      /* set by the solver on a failure it cannot recover from */
    /* the correction the solver's model asked for at the iterate, when no
     * trust-region radius or line search limited it: the norm of the
     * unshifted Newton direction (Newton family), of an interior dogleg
     * Newton point or Steihaug–Toint step (tr), of a V-cycle correction
     * inside its radius (rmtr).  run.stop=scaled stops (roundoff_limit) when
     * it is below run.xtol_rel ||x||: no representable change is left. */
    int has_correction;
    double correction;
    /* single-step solvers: normwise backward error of the linear solve,
     * ||H d + g|| / (||H||_F ||d|| + ||g||) (0 when not computed) */
    double linear_residual;
    /* Krylov linear solves: the relative tolerance asked and the outcome
     * (sb_iter_record.krylov_rtol / krylov_status) */
    double linear_rtol;
    int linear_status;
    /* in: the step's gradient threshold (sb_solve sets it before each
     * iterate; 0 when not known): the Krylov paths' forcing never asks
     * for a residual far below it (sb_forcing_floor) */
    double gstop;
    /* in: run.xtol_rel ||x|| under run.stop=scaled (the smallest correction
     * the stopping rule resolves: roundoff_limit), else 0: the Newton
     * family's Krylov paths stop CG once the remaining correction is well
     * below it (solver.cg_xstop, sb_krylov.h) */
    double xstop;
    /* out: the computed gradient's rounding level the Krylov forcing floor
     * measured this step (sb_noise_floor; 0: not measured) */
    double gnoise;
} sb_iterate_info;

typedef struct sb_solver_type {
    const char *name;
    const char *description;
    size_t state_size;
    const sb_param_def *params;          /* "solver.*" parameters, may be NULL */
    unsigned flags;
    /* allocate workspaces for `p` (sizes are fixed for the run) */
    int  (*alloc)(void *state, sb_problem *p, const sb_paramset *ps);
    /* start a solve from x (finest level); fills info with f, ||g|| at x */
    int  (*set)(void *state, sb_problem *p, const double *x, sb_iterate_info *info);
    /* one outer iteration; updates x in place */
    int  (*iterate)(void *state, sb_problem *p, double *x, sb_iterate_info *info);
    void (*free)(void *state);
    /* optional: one line on the configuration actually used (after alloc) */
    void (*describe)(const void *state, char *buf, size_t len);
    /* optional: s = -H^{-1} g with the finest Hessian as the problem holds
     * it, by the solver's own linear path (after alloc); the lifting of
     * boundary motion solves with it (sb_problem_lift; NULL: CHOLMOD) */
    int (*linear_solve)(void *state, sb_problem *p, const double *g, double *s);
} sb_solver_type;

const sb_solver_type *sb_solver_find(const char *name);
int sb_solver_count(void);
const sb_solver_type *sb_solver_at(int i);

/* Parameters of the core loop (prefix "run."), RMTR paper Eq. (7.1). */
extern const sb_param_def sb_solve_params[];

/* Solve the current step's problem from x (in/out).  Runs the loop, pushes
 * per-iteration records, returns the reason the loop stopped. */
sb_reason sb_solve_step(const sb_solver_type *type, void *state, sb_problem *p,
                        const sb_paramset *ps, int step, double *x, int *iterations,
                        double *f_out, double *gnorm_out);

/* What a step's loop found, with the scales it judged by (docs/trust.md). */
typedef struct sb_step_outcome {
    sb_reason reason;
    int iterations;
    double f, gnorm;      /* at the end of the step */
    double g0;            /* ||g|| at the step's start */
    double force_scale;   /* run.stop=scaled: ||grad E|| of the method's energy at the reference
                             configuration with this step's loads and boundary data (NaN otherwise) */
    double gstop;         /* the gradient threshold the step used */
    double gnoise;        /* the gradient's rounding level the solver measured (0: none) */
} sb_step_outcome;

/* sb_solve_step with the outcome's scales. */
sb_reason sb_solve_step_ex(const sb_solver_type *type, void *state, sb_problem *p,
                           const sb_paramset *ps, int step, double *x, sb_step_outcome *out);

/* The stopping rules of run.stop (sb_solve_params). */
enum { SB_STOP_SCALED = 0, SB_STOP_PAPER = 1 };

#endif
