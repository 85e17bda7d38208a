/* newton.c — the Newton family: line-search Newton (backtracking Armijo),
 * damped Newton (constant step, no globalization) and the linearized solve
 * (one Newton step per time step, Baraff–Witkin), sharing one direction
 * computation.  RMTR paper §7.4.1 describes all three as comparison solvers. */
#include "sb_solver.h"
#include "sb_context.h"
#include "sb_trs.h"
#include "sb_krylov.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* solver.linear and the Krylov paths' options (docs/solvers.md "Linear
 * solvers"), shared by lsnewton and damped */
#define KRYLOV_PARAMS(RTOL_DEF, RTOL_HELP, MAXIT_DEF)                                                                  \
    { "cg_rtol", SB_PARAM_REAL, RTOL_DEF, -1, 0.5, NULL, RTOL_HELP },                                                  \
    { "cg_max_iter", SB_PARAM_INT, MAXIT_DEF, 1, 1000000000, NULL, "Krylov paths: CG iteration cap per linear solve" }, \
    { "mg_sweeps", SB_PARAM_INT, 1, 1, 20, NULL,                                                                       \
      "pcg-mg: block Gauss-Seidel sweeps before (forward) and after (backward) the coarse correction" },               \
    { "mg_lag", SB_PARAM_INT, 1, 1, 1000000, NULL, MG_LAG_HELP },                                                      \
    { "mg_cycle", SB_PARAM_CHOICE, 0, 0, 0, sb_mg_cycle_names, SB_MG_CYCLE_HELP },                                     \
    { "amg_strength", SB_PARAM_REAL, 0.5, 0, 0.99, NULL,                                                               \
      "pcg-amg: BoomerAMG strength threshold (0.5: hypre's advice for 3-D problems; hypre's default 0.25)" },            \
    { "cg_noise_floor", SB_PARAM_INT, 0, 0, 1, NULL, SB_NOISE_FLOOR_HELP },                                          \
    { "cg_xstop", SB_PARAM_INT, 1, 0, 1, NULL, SB_CG_XSTOP_HELP }
#define MG_LAG_HELP "pcg-mg: rebuild the coarse levels (Galerkin products, coarsest factorization) at each step's " \
    "first Newton iteration and every mg_lag-th one after; 1: every iteration"
#define LINEAR_HELP "linear solver of the Newton step: cholmod (sparse Cholesky), pcg-jacobi (CG, node-block Jacobi), " \
    "pcg-mg (CG, one V-cycle of the method's hierarchy), pcg-amg (CG, hypre BoomerAMG)"
#define EW_HELP "Krylov paths: stop CG at ||H d + g|| <= cg_rtol ||g||; -1: Eisenstat-Walker forcing terms (choice 2)"

static const sb_param_def lsnewton_params[] = {
    { "c1", SB_PARAM_REAL, 1e-4, 1e-12, 0.5, NULL, "Armijo sufficient-decrease constant (Nocedal & Wright Alg. 3.1)" },
    { "backtrack", SB_PARAM_REAL, 0.5, 0.01, 0.99, NULL, "step contraction factor" },
    { "max_backtracks", SB_PARAM_INT, 50, 1, 1000, NULL, "line-search trials before failure" },
    { "shift0", SB_PARAM_REAL, 1e-8, 1e-300, 1, NULL,
      "first diagonal shift, relative to max|H_ij|, when H is not positive definite" },
    { "shift_factor", SB_PARAM_REAL, 10, 1.1, 1e6, NULL, "shift growth per failed factorization" },
    { "max_shifts", SB_PARAM_INT, 40, 1, 1000, NULL, "shifted factorizations before failure" },
    { "linear", SB_PARAM_CHOICE, 0, 0, 0, sb_linear_names, LINEAR_HELP },
    KRYLOV_PARAMS(-1, EW_HELP, 1000),
    { NULL, 0, 0, 0, 0, NULL, NULL }
};

static const sb_param_def damped_params[] = {
    { "alpha", SB_PARAM_REAL, 0.3, 1e-6, 1, NULL, "constant step length (RMTR paper §7.4.1: 0.3)" },
    { "linear", SB_PARAM_CHOICE, 0, 0, 0, sb_linear_names, LINEAR_HELP },
    KRYLOV_PARAMS(-1, EW_HELP, 1000),
    { NULL, 0, 0, 0, 0, NULL, NULL }
};

static const char *const linear_choices[] = { "cholmod", "pcg", "pcg-jacobi", "pcg-mg", "pcg-amg", NULL };

/* The linear solve of the linearized step: CHOLMOD (default) or, as the
 * sqrt3 paper (Bender & Deul §4.2.5, Baraff & Witkin) does, preconditioned CG
 * on the eliminated system (constrained rows are identity: the "modified"
 * PCG's filtering).  CG stops at ||r|| <= cg_rtol ||g||; the step is judged
 * by the same backward-error test as the direct solve (sb_solve.c), so a
 * loose cg_rtol is recorded as a linear-solver failure, never hidden. */
static const sb_param_def linearized_params[] = {
    { "linear", SB_PARAM_CHOICE, 0, 0, 0, linear_choices,
      "linear solver of the single step: cholmod (sparse Cholesky), pcg (preconditioned CG, sqrt3 paper Eq. 21, "
      "preconditioner cg_precond), pcg-jacobi, pcg-mg, pcg-amg (as lsnewton's)" },
    { "cg_rtol", SB_PARAM_REAL, 1e-10, 1e-16, 0.5, NULL, "linear=pcg*: stop at ||r|| <= cg_rtol ||g||" },
    { "cg_max_iter", SB_PARAM_INT, 10000, 1, 1000000000, NULL, "linear=pcg*: iteration cap" },
    { "cg_precond", SB_PARAM_CHOICE, 2, 0, 0, sb_trs_precond_names,
      "linear=pcg: preconditioner (none, jacobi, block = 3x3 node blocks, sgs, schwarz)" },
    { "mg_sweeps", SB_PARAM_INT, 1, 1, 20, NULL,
      "pcg-mg: block Gauss-Seidel sweeps before (forward) and after (backward) the coarse correction" },
    { "mg_lag", SB_PARAM_INT, 1, 1, 1000000, NULL, MG_LAG_HELP },
    { "mg_cycle", SB_PARAM_CHOICE, 0, 0, 0, sb_mg_cycle_names, SB_MG_CYCLE_HELP },
    { "amg_strength", SB_PARAM_REAL, 0.5, 0, 0.99, NULL,
      "pcg-amg: BoomerAMG strength threshold (0.5: hypre's advice for 3-D problems; hypre's default 0.25)" },
    { NULL, 0, 0, 0, 0, NULL, NULL }
};

typedef enum { KIND_LS, KIND_DAMPED, KIND_LINEARIZED } newton_kind;

typedef struct newton_state {
    newton_kind kind;
    int n, F;
    double c1, backtrack, shift0, shift_factor, alpha;
    int max_backtracks, max_shifts;
    int pcg, cg_max_iter;              /* linearized with linear=pcg */
    sb_trs cg;
    /* solver.linear = pcg-jacobi | pcg-mg | pcg-amg (sb_krylov.h) */
    int krylov;
    sb_krylov kr;
    double cg_rtol;                    /* < 0: Eisenstat–Walker forcing */
    double eta, gprev;                 /* the last forcing term and the ||g|| it was computed at */
    double snorm, sprev;               /* the last two steps' norms (0: none yet this step) */
    sb_noise_floor noise;              /* the forcing's floor at the gradient's rounding level */
    int xstop;                         /* solver.cg_xstop */
    double zcorr;                      /* ||M^-1 r|| of a solve the correction test stopped (else 0) */
    double *g, *gt, *d, *xt;
    double f, gnorm;
} newton_state;

static int alloc_common(newton_state *s, sb_problem *p, newton_kind kind)
{
    s->kind = kind;
    s->F = sb_problem_finest(p);
    s->n = sb_problem_n(p, s->F);
    s->g = malloc((size_t)s->n * sizeof(double));
    s->gt = malloc((size_t)s->n * sizeof(double));
    s->d = malloc((size_t)s->n * sizeof(double));
    s->xt = malloc((size_t)s->n * sizeof(double));
    return s->g && s->gt && s->d && s->xt ? SB_OK : SB_ERR_NOMEM;
}

/* the Krylov path of solver.linear, when chosen (refused here, before any
 * work, when the method or the build cannot do it) */
static int krylov_alloc(newton_state *s, sb_problem *p, const sb_paramset *ps)
{
    const int kind = sb_linear_kind(sb_param_choice(ps, "solver.linear"));
    const sb_precond_type *pt = sb_linear_precond(kind);
    if (!pt) return SB_OK;
    s->krylov = 1;
    s->cg_rtol = sb_param(ps, "solver.cg_rtol");
    s->noise.on = s->kind != KIND_LINEARIZED && sb_param_int(ps, "solver.cg_noise_floor");   /* linearized: fixed cg_rtol */
    s->xstop = s->kind != KIND_LINEARIZED && s->cg_rtol < 0.0 && sb_param_int(ps, "solver.cg_xstop");
    s->cg_max_iter = sb_param_int(ps, "solver.cg_max_iter");
    sb_precond_opts o = { .mg_sweeps = sb_param_int(ps, "solver.mg_sweeps"), .mg_lag = sb_param_int(ps, "solver.mg_lag"),
                          .mg_cycle = sb_mg_cycle_kind(sb_param_choice(ps, "solver.mg_cycle")),
                          .amg_strength = sb_param(ps, "solver.amg_strength") };
    return sb_krylov_alloc(&s->kr, p, s->F, pt, &o);
}

static int lsnewton_alloc(void *st, sb_problem *p, const sb_paramset *ps)
{
    newton_state *s = st;
    s->c1 = sb_param(ps, "solver.c1");
    s->backtrack = sb_param(ps, "solver.backtrack");
    s->max_backtracks = sb_param_int(ps, "solver.max_backtracks");
    s->shift0 = sb_param(ps, "solver.shift0");
    s->shift_factor = sb_param(ps, "solver.shift_factor");
    s->max_shifts = sb_param_int(ps, "solver.max_shifts");
    int rc = alloc_common(s, p, KIND_LS);
    return rc ? rc : krylov_alloc(s, p, ps);
}

static int damped_alloc(void *st, sb_problem *p, const sb_paramset *ps)
{
    newton_state *s = st;
    s->alpha = sb_param(ps, "solver.alpha");
    int rc = alloc_common(s, p, KIND_DAMPED);
    return rc ? rc : krylov_alloc(s, p, ps);
}

static int linearized_alloc(void *st, sb_problem *p, const sb_paramset *ps)
{
    newton_state *s = st;
    int rc = alloc_common(s, p, KIND_LINEARIZED);
    if (rc) return rc;
    if ((rc = krylov_alloc(s, p, ps))) return rc;
    s->pcg = sb_linear_kind(sb_param_choice(ps, "solver.linear")) == SB_LINEAR_PCG_LEGACY;
    if (!s->pcg) return SB_OK;
    s->cg_max_iter = sb_param_int(ps, "solver.cg_max_iter");
    if ((rc = sb_trs_alloc(&s->cg, &sb_trs_stcg, s->n))) return rc;
    sb_trs_set_cg_rtol(&s->cg, sb_param(ps, "solver.cg_rtol"));
    sb_trs_set_cg_precond(&s->cg, sb_param_int(ps, "solver.cg_precond"));
    return SB_OK;
}

static void linearized_describe(const void *st, char *buf, size_t len)
{
    const newton_state *s = st;
    if (s->krylov) sb_krylov_describe(&s->kr, buf, len);
    else snprintf(buf, len, "%s", s->pcg ? "linear solve: preconditioned CG (sqrt3 paper §4.2.5)" : "linear solve: CHOLMOD");
}

/* lsnewton and damped: nothing is said for the direct path (its records
 * stay as they were); the Krylov paths name themselves */
static void newton_describe(const void *st, char *buf, size_t len)
{
    const newton_state *s = st;
    if (s->krylov) sb_krylov_describe(&s->kr, buf, len);
    else if (len) buf[0] = 0;
}

/* the lifting's solve (sb_solver_type.linear_solve) on the Krylov paths,
 * to 1e-8 (a start judged by its energy; a capped or indefinite solve
 * leaves the plain start); the direct path says SB_ERR_UNSUPPORTED and the
 * lifting factors with CHOLMOD as before */
static int newton_linear_solve(void *st, sb_problem *p, const double *g, double *s)
{
    newton_state *ns = st;
    return ns->krylov ? sb_krylov_solve_to(&ns->kr, p, g, 1e-8, ns->cg_max_iter, s) : SB_ERR_UNSUPPORTED;
}

static void newton_free(void *st)
{
    newton_state *s = st;
    free(s->g);
    free(s->gt);
    free(s->d);
    free(s->xt);
    if (s->pcg) sb_trs_free(&s->cg);
    if (s->krylov) sb_krylov_free(&s->kr);
}

static int newton_set(void *st, sb_problem *p, const double *x, sb_iterate_info *info)
{
    newton_state *s = st;
    int rc = sb_problem_eval(p, s->F, x, &s->f, s->g, sb_problem_hessian(p, s->F));
    s->gnorm = sb_problem_norm(p, s->F, s->g);
    info->f = s->f;
    info->gnorm = s->gnorm;
    info->delta = INFINITY;
    s->eta = 0.0;          /* Eisenstat–Walker starts afresh each step */
    s->gprev = s->snorm = s->sprev = 0.0;
    sb_noise_floor_reset(&s->noise);
    return rc;
}

/* d ~ -H^{-1} g by preconditioned CG (solver.linear = pcg-*).
 *   tolerance  ||H d + g|| <= eta ||g||, eta the Eisenstat–Walker forcing
 *              term (choice 2) or the fixed cg_rtol (linearized: 1e-10);
 *   indefinite CG meets d^T H d <= 0: lsnewton shifts as its direct path
 *              does (H + tau I, tau from shift0 max|H| grown by shift_factor,
 *              at least twice the curvature CG found, up to max_shifts
 *              solves; Nocedal & Wright Alg. 3.3), damped and linearized
 *              record NOT_POSDEF as theirs do;
 *   the cap    a solve that does not reach its tolerance is recorded
 *              (krylov_status 1): lsnewton uses its d only when it is a
 *              descent direction (the line search then judges it), damped
 *              and linearized stop with linear_solver. */
static int krylov_direction(newton_state *s, sb_problem *p, const double *x, sb_iterate_info *info, double *shift_out)
{
    const int n = s->n;
    int rc = sb_krylov_setup(&s->kr, p);
    if (rc < 0) return rc;
    double eta = s->cg_rtol >= 0.0 ? s->cg_rtol : sb_forcing_ew2_steps(s->gnorm, s->gprev, s->snorm, s->sprev, s->eta);
    if (s->cg_rtol < 0.0 && s->kind != KIND_LINEARIZED) {
        /* Kelley's floor on gstop and on the gradient's rounding (d, gt, xt
         * are free until the solve) */
        int rf = sb_noise_floor_apply(&s->noise, &s->kr, rc == SB_OK, p, x, s->g, s->gnorm, info->gstop, s->xt, s->gt,
                                      s->d, &eta);
        if (rf < 0) return rf;
        info->gnoise = s->noise.level;
    }
    if (s->kind == KIND_LINEARIZED) eta = s->cg_rtol;
    s->eta = eta;
    s->gprev = s->gnorm;
    info->linear_rtol = eta;
    sb_krylov_result r;
    double shift = 0.0;
    int iters = 0;
    /* the correction test (solver.cg_xstop): CG need not resolve the step
     * below what the stopping rule can see.  A step stops (roundoff_limit)
     * when its Newton correction is below xstop = run.xtol_rel ||x||; CG's
     * remaining error s* - s = H^{-1} r, estimated by z = M^{-1} r, below
     * xstop / 10 leaves that test's verdict to the part CG has resolved.
     * ASSUMPTION (not in Eisenstat & Walker, who stop on ||r|| alone): ||z||
     * estimates ||H^{-1} r|| for a multigrid M within a small factor
     * (measured against CHOLMOD's exact step in tests/test_krylov.c: at
     * most 1.4x low); the tenth leaves room for it, and for the next
     * iteration's one-CG-iteration correction to pass the test (a half,
     * tried first, left the correction just above xstop and cost the
     * 261,251-dof linear_fem plate a fifth Newton iteration) */
    s->kr.ztol = sb_krylov_xstop_ztol(s->xstop, info->xstop);
    s->zcorr = 0.0;
    if (rc == SB_OK) {
        rc = sb_krylov_solve(&s->kr, p, s->g, INFINITY, eta, s->cg_max_iter, s->d, &r);
        if (rc < 0) return rc;
        iters += r.iters;
    } else r.status = SB_KRYLOV_NEGCURV, r.curvature = 0.0;
    if (r.status == SB_KRYLOV_NEGCURV && s->kind == KIND_LS) {
        double scale = sb_matrix_norm_max(sb_problem_hessian(p, s->F));
        shift = s->shift0 * (scale > 0 ? scale : 1.0);
        for (int k = 0; k < s->max_shifts && r.status == SB_KRYLOV_NEGCURV; k++) {
            /* the Rayleigh quotient CG met bounds lambda_min(H + old shift) from above */
            if (k > 0) shift = fmax(shift * s->shift_factor, shift - 2.0 * r.curvature);
            sb_krylov_shift(&s->kr, p, shift);
            rc = sb_krylov_setup(&s->kr, p);
            if (rc < 0) break;
            if (rc == SB_NOT_POSDEF) { r.status = SB_KRYLOV_NEGCURV; r.curvature = 0.0; continue; }
            rc = sb_krylov_solve(&s->kr, p, s->g, INFINITY, eta, s->cg_max_iter, s->d, &r);
            if (rc < 0) break;
            iters += r.iters;
        }
        sb_krylov_unshift(&s->kr, p);
        if (rc < 0) return rc;
    }
    *shift_out = shift;
    info->shift = shift;
    info->linear_iters = iters;
    info->linear_status = (int)r.status + (shift > 0.0 ? 4 : 0) + (r.by_correction ? 8 : 0);
    if (r.by_correction) s->zcorr = r.znorm;
    if (r.status == SB_KRYLOV_NEGCURV) {
        info->fail = SB_REASON_NOT_POSDEF;
        return SB_OK;
    }
    if (!sb_all_finite(n, s->d)) {
        info->fail = SB_REASON_NONFINITE;
        return SB_OK;
    }
    if (r.status == SB_KRYLOV_CAP && (s->kind != KIND_LS || !(sb_dot(n, s->g, s->d) < 0.0))) {
        info->fail = SB_REASON_LINEAR_SOLVER;
        return SB_OK;
    }
    return SB_OK;
}

/* d = -(H + shift I)^{-1} g.  lsnewton: on a non-positive-definite H the
 * shift grows geometrically from shift0 * max|H_ij| until the factorization
 * succeeds (Nocedal & Wright Alg. 3.3); the others record NOT_POSDEF. */
static int direction(newton_state *s, sb_problem *p, const double *x, sb_iterate_info *info)
{
    double shift = 0.0;
    int rc;
    if (s->krylov) {
        rc = krylov_direction(s, p, x, info, &shift);
        if (rc < 0 || info->fail) return rc < 0 ? rc : SB_OK;
        goto judge;
    }
    if (s->pcg) {
        /* CG from 0 on H d = -g without a radius; negative curvature means
         * H is not positive definite (recorded as such) */
        sb_trs_result r;
        memset(&r, 0, sizeof r);
        rc = sb_trs_solve(&s->cg, p, s->F, s->g, INFINITY, 1, s->cg_max_iter, s->d, &r);
        if (rc < 0) return rc;
        info->shift = 0.0;
        if (r.boundary) {
            info->fail = SB_REASON_NOT_POSDEF;
            return SB_OK;
        }
        info->linear_iters = r.iters;
        if (!sb_all_finite(s->n, s->d)) {
            info->fail = SB_REASON_NONFINITE;
            return SB_OK;
        }
        rc = SB_OK;
        goto judge;
    }
    rc = sb_problem_factor(p, s->F, 0.0);
    if (rc == SB_NOT_POSDEF && s->kind == KIND_LS) {
        double scale = sb_matrix_norm_max(sb_problem_hessian(p, s->F));
        shift = s->shift0 * (scale > 0 ? scale : 1.0);
        for (int k = 0; k < s->max_shifts; k++) {
            rc = sb_problem_factor(p, s->F, shift);
            if (rc != SB_NOT_POSDEF) break;
            shift *= s->shift_factor;
        }
    }
    info->shift = shift;
    if (rc == SB_NOT_POSDEF) {
        info->fail = SB_REASON_NOT_POSDEF;
        return SB_OK;
    }
    if (rc < 0) return rc;
    for (int i = 0; i < s->n; i++) s->xt[i] = -s->g[i];
    rc = sb_problem_solve(p, s->F, s->xt, s->d);
    if (rc == SB_NONFINITE) info->fail = SB_REASON_NONFINITE;
    info->linear_iters = 1;
judge:
    if (rc == SB_OK && shift == 0.0 && !(s->krylov && (info->linear_status & 7) != SB_KRYLOV_CONVERGED)) {
        /* the unshifted Newton correction (limiting-accuracy test, sb_solve.c);
         * a CG solve stopped by the correction test adds its estimated
         * remaining error, so that the test sees a bound, not the truncation */
        info->has_correction = 1;
        info->correction = sb_norm2(s->n, s->d) + (s->krylov ? s->zcorr : 0.0);
    }
    if (rc == SB_OK && s->kind == KIND_LINEARIZED) {
        /* the linearized solver's step is judged by its linear solve: the
         * normwise backward error ||H d + g|| / (||H||_F ||d|| + ||g||)
         * (Higham, Accuracy and Stability of Numerical Algorithms, Thm. 7.1);
         * xt is free scratch here */
        const sb_matrix *H = sb_problem_hessian(p, s->F);
        sb_problem_hess_mult(p, s->F, s->d, s->xt);
        double r2 = 0.0, h2 = 0.0;
        for (int i = 0; i < s->n; i++) r2 += (s->xt[i] + s->g[i]) * (s->xt[i] + s->g[i]);
        for (int c = 0; c < H->pat->n; c++)
            for (long q = H->pat->colptr[c]; q < H->pat->colptr[c + 1]; q++)
                h2 += (H->pat->rowind[q] != c ? 2.0 : 1.0) * H->val[q] * H->val[q];
        double den = sqrt(h2) * sb_norm2(s->n, s->d) + sb_norm2(s->n, s->g);
        info->linear_residual = den > 0.0 ? sqrt(r2) / den : 0.0;
    }
    return rc < 0 ? rc : SB_OK;
}

static int newton_iterate(void *st, sb_problem *p, double *x, sb_iterate_info *info)
{
    newton_state *s = st;
    const int n = s->n;
    info->delta = 0.0;
    int rc = direction(s, p, x, info);
    if (rc < 0 || info->fail) {
        info->f = s->f;
        info->gnorm = s->gnorm;
        return rc;
    }
    double alpha = s->kind == KIND_DAMPED ? s->alpha : 1.0;
    /* contact step filter (docs/contact.md): no sample point may reach an
     * obstacle along the step; 1 without obstacles */
    alpha = fmin(alpha, sb_problem_step_bound(p, s->F, x, s->d));
    double fold = s->f;
    /* the linearized solver evaluates the gradient only, to report the
     * residual its single step leaves */
    sb_matrix *H = s->kind == KIND_LINEARIZED ? NULL : sb_problem_hessian(p, s->F);
    if (s->kind == KIND_LS) {
        /* backtracking Armijo: f(x + a d) <= f(x) + c1 a g^T d (Nocedal & Wright
         * Alg. 3.1); a trial point with finite energy but non-finite
         * derivatives is backtracked from as well */
        double slope = sb_dot(n, s->g, s->d);
        int ok = 0;
        if (slope < 0.0) {
            for (int k = 0; k < s->max_backtracks && !ok; k++, alpha *= s->backtrack) {
                for (int i = 0; i < n; i++) s->xt[i] = x[i] + alpha * s->d[i];
                double ft;
                rc = sb_problem_eval(p, s->F, s->xt, &ft, NULL, NULL);
                if (rc < 0) return rc;
                if (rc == SB_OK && isfinite(ft) && !(ft <= s->f + s->c1 * alpha * slope) &&
                    (s->krylov ? sb_krylov_f_noise(s->f, ft, -alpha * slope)
                               : sb_tr_ared_unreliable(s->f, ft, -alpha * slope) &&
                                 fabs(ft - s->f) <= 1e4 * DBL_EPSILON * fmax(fabs(s->f), fabs(ft)))) {
                    /* the decrease asked for, and the change of f found, are both
                     * below the round-off of f: decide by the gradients,
                     * ared = -(g + g_trial)^T s / 2 (as tr does, sb_trs.h; Conn,
                     * Gould & Toint §17.4.2) */
                    rc = sb_problem_eval(p, s->F, s->xt, &ft, s->gt, H);
                    if (rc < 0) return rc;
                    if (rc != SB_OK) continue;
                    double ared = -0.5 * alpha * (sb_dot(n, s->g, s->d) + sb_dot(n, s->gt, s->d));
                    if (ared >= -s->c1 * alpha * slope) { ok = 1; s->f = ft; break; }
                    continue;
                }
                if (!(rc == SB_OK && isfinite(ft) && ft <= s->f + s->c1 * alpha * slope)) continue;
                rc = sb_problem_eval(p, s->F, s->xt, &ft, s->gt, H);
                if (rc < 0) return rc;
                if (rc == SB_OK) { ok = 1; s->f = ft; break; }
            }
        }
        if (!ok) {
            /* restore the derivatives at x if a rejected trial overwrote H */
            double f0;
            rc = sb_problem_eval(p, s->F, x, &f0, s->g, H);
            if (rc < 0) return rc;
            info->fail = SB_REASON_LINESEARCH;
            info->f = s->f;
            info->gnorm = s->gnorm;
            return SB_OK;
        }
        sb_copy(n, s->xt, x);
        double *sw = s->g; s->g = s->gt; s->gt = sw;
    } else {
        sb_axpy(n, alpha, s->d, x);
        rc = sb_problem_eval(p, s->F, x, &s->f, s->g, H);
        if (rc < 0) return rc;
        if (rc == SB_NONFINITE) info->fail = SB_REASON_NONFINITE;
    }
    s->gnorm = sb_problem_norm(p, s->F, s->g);
    info->rho = alpha;
    info->accepted = 1;
    /* "Newton regime" for the stagnation tests of Eq. (7.1): an unshifted
     * Newton direction plays the role of Delta > delta_big (a shortened step
     * near the limiting accuracy must still be able to stop on f/x) */
    info->delta = (info->shift == 0.0 && s->kind != KIND_DAMPED) ? INFINITY : 0.0;
    info->df = fold - s->f;
    info->step_norm = alpha * sb_norm2(n, s->d);
    s->sprev = s->snorm;
    s->snorm = info->step_norm;
    info->f = s->f;
    info->gnorm = s->gnorm;
    return SB_OK;
}

const sb_solver_type sb_solver_lsnewton = {
    "lsnewton", "Newton with backtracking Armijo line search; shifted Hessian when indefinite",
    sizeof(newton_state), lsnewton_params, 0, lsnewton_alloc, newton_set, newton_iterate, newton_free, newton_describe,
    newton_linear_solve,
};

const sb_solver_type sb_solver_damped = {
    "damped", "Newton with constant step 0.3 and no globalization (may diverge: recorded)",
    sizeof(newton_state), damped_params, 0, damped_alloc, newton_set, newton_iterate, newton_free, newton_describe,
    newton_linear_solve,
};

const sb_solver_type sb_solver_linearized = {
    "linearized", "one Newton step per time step from x_n (Baraff–Witkin linearized implicit Euler)",
    sizeof(newton_state), linearized_params, SB_SOLVER_SINGLE_STEP, linearized_alloc, newton_set, newton_iterate, newton_free,
    linearized_describe, NULL,   /* no lifting: one Newton step from x_n */
};
