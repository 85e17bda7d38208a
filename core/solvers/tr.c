/* tr.c — single-level trust region (RMTR paper Alg. 4.1) with the radius
 * update of Alg. 4.3 (single level: no coarse-correction bound, Delta^{L+1}
 * = infinity), Table 2 parameters, derivatives recomputed only after
 * accepted steps (paper §7.4.2), subproblem by dogleg or Steihaug–Toint CG. */
#include "sb_solver.h"
#include "sb_trs.h"
#include "sb_krylov.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const tr_rho_names[] = { "robust", "paper", NULL };

static const sb_param_def tr_params[] = {
    { "eta1", SB_PARAM_REAL, 0.1, 0, 1, NULL, "accept when rho > eta1 (RMTR paper Table 2)" },
    { "eta2", SB_PARAM_REAL, 0.75, 0, 1, NULL, "enlarge when rho > eta2 (Table 2)" },
    { "gamma1", SB_PARAM_REAL, 0.5, 1e-6, 1, NULL, "shrink factor (Table 2)" },
    { "gamma2", SB_PARAM_REAL, 2.0, 1, 1e6, NULL, "enlarge factor (Table 2)" },
    { "delta0", SB_PARAM_REAL, 1.0, 1e-300, 1e300, NULL, "initial radius of every step (Table 2)" },
    { "delta_min", SB_PARAM_REAL, 1e-300, 0, 1, NULL, "fail when the radius drops below this" },
    { "trs", SB_PARAM_CHOICE, 0, 0, 0, sb_trs_names, "subproblem solver (RMTR paper §7.3: dogleg)" },
    { "indefinite", SB_PARAM_CHOICE, 1, 0, 0, sb_trs_indefinite_names,
      "dogleg on an indefinite Hessian: shift (Newton point of H + tau I) or cauchy (the paper's configuration)" },
    { "cg_precond", SB_PARAM_CHOICE, 0, 0, 0, sb_trs_precond_names, "Steihaug–Toint CG preconditioner (trs = stcg)" },
    { "cg_max_iter", SB_PARAM_INT, 0, 0, 1e9, NULL, "Steihaug–Toint CG iteration cap (0 = n)" },
    { "rho", SB_PARAM_CHOICE, 0, 0, 0, tr_rho_names,
      "ratio (4.2): robust (round-off-sized reductions count as agreement, or are taken from gradients) or paper "
      "(the plain quotient of Eq. 4.2, issue 43)" },
    { "linear", SB_PARAM_CHOICE, 0, 0, 0, sb_linear_names,
      "linear solver of the subproblem: cholmod (the trs choice, as before) or Steihaug–Toint CG preconditioned by "
      "pcg-jacobi (node-block Jacobi), pcg-mg (a V-cycle of the method's hierarchy), pcg-amg (hypre BoomerAMG)" },
    { "cg_rtol", SB_PARAM_REAL, -1, -1, 0.5, NULL,
      "pcg-*: stop CG at ||H s + g|| <= cg_rtol ||g||; -1: Eisenstat-Walker forcing terms (choice 2)" },
    { "mg_sweeps", SB_PARAM_INT, 1, 1, 20, NULL,
      "pcg-mg: block Gauss-Seidel sweeps before (forward) and after (backward) the coarse correction" },
    { "mg_lag", SB_PARAM_INT, 1, 1, 1000000, NULL,
      "pcg-mg: rebuild the coarse levels (Galerkin products, coarsest factorization) at each step's first TR "
      "iteration and every mg_lag-th one after; 1: every iteration" },
    { "mg_cycle", SB_PARAM_CHOICE, 0, 0, 0, sb_mg_cycle_names, SB_MG_CYCLE_HELP },
    { "amg_strength", SB_PARAM_REAL, 0.5, 0, 0.99, NULL,
      "pcg-amg: BoomerAMG strength threshold (0.5: hypre's advice for 3-D problems; hypre's default 0.25)" },
    { "cg_noise_floor", SB_PARAM_INT, 0, 0, 1, NULL, SB_NOISE_FLOOR_HELP },
    { "cg_xstop", SB_PARAM_INT, 1, 0, 1, NULL, SB_CG_XSTOP_HELP },
    { NULL, 0, 0, 0, 0, NULL, NULL }
};

typedef struct tr_state {
    int n, F;
    double eta1, eta2, gamma1, gamma2, delta0, delta_min;
    int cg_max;
    int rho_paper;     /* solver.rho = paper: Eq. (4.2) as a plain quotient */
    sb_trs trs;
    double *g, *gt, *s, *xt;
    double f, delta, gnorm;
    int fresh;
    /* solver.linear = pcg-*: Steihaug–Toint CG with a preconditioner of
     * sb_precond.h instead of the trs choice (sb_krylov.h) */
    int krylov;
    sb_krylov kr;
    double cg_rtol, eta, gprev;
    sb_noise_floor noise;   /* the forcing's floor at the gradient's rounding level */
    int xstop;              /* solver.cg_xstop */
    double zcorr;           /* ||M^-1 r|| of a solve the correction test stopped (else 0) */
} tr_state;

static int tr_alloc(void *st, sb_problem *p, const sb_paramset *ps)
{
    tr_state *t = st;
    t->F = sb_problem_finest(p);
    t->n = sb_problem_n(p, t->F);
    t->eta1 = sb_param(ps, "solver.eta1");
    t->eta2 = sb_param(ps, "solver.eta2");
    t->gamma1 = sb_param(ps, "solver.gamma1");
    t->gamma2 = sb_param(ps, "solver.gamma2");
    t->delta0 = sb_param(ps, "solver.delta0");
    t->delta_min = sb_param(ps, "solver.delta_min");
    t->cg_max = sb_param_int(ps, "solver.cg_max_iter");
    t->rho_paper = sb_param_int(ps, "solver.rho") == 1;
    t->g = malloc((size_t)t->n * sizeof(double));
    t->gt = malloc((size_t)t->n * sizeof(double));
    t->s = malloc((size_t)t->n * sizeof(double));
    t->xt = malloc((size_t)t->n * sizeof(double));
    if (!t->g || !t->gt || !t->s || !t->xt) return SB_ERR_NOMEM;
    int rc = sb_trs_alloc(&t->trs, sb_trs_by_index(sb_param_int(ps, "solver.trs")), t->n);
    if (rc == SB_OK) {
        sb_trs_set_shift_indefinite(&t->trs, sb_param_int(ps, "solver.indefinite"));
        sb_trs_set_cg_precond(&t->trs, sb_param_int(ps, "solver.cg_precond"));
    }
    const sb_precond_type *pt = sb_linear_precond(sb_linear_kind(sb_param_choice(ps, "solver.linear")));
    if (rc == SB_OK && pt) {
        t->krylov = 1;
        t->cg_rtol = sb_param(ps, "solver.cg_rtol");
        t->noise.on = sb_param_int(ps, "solver.cg_noise_floor");
        t->xstop = t->cg_rtol < 0.0 && sb_param_int(ps, "solver.cg_xstop");
        sb_precond_opts o = { .mg_sweeps = sb_param_int(ps, "solver.mg_sweeps"),
                              .mg_lag = sb_param_int(ps, "solver.mg_lag"),
                              .mg_cycle = sb_mg_cycle_kind(sb_param_choice(ps, "solver.mg_cycle")),
                              .amg_strength = sb_param(ps, "solver.amg_strength") };
        rc = sb_krylov_alloc(&t->kr, p, t->F, pt, &o);
    }
    return rc;
}

/* the lifting's solve (sb_solver_type.linear_solve): on the Krylov paths
 * PCG to 1e-8 without a radius (a start judged by its energy; capped or
 * indefinite: the plain start); the direct path says SB_ERR_UNSUPPORTED and
 * the lifting factors with CHOLMOD */
static int tr_linear_solve(void *st, sb_problem *p, const double *g, double *s)
{
    tr_state *t = st;
    return t->krylov ? sb_krylov_solve_to(&t->kr, p, g, 1e-8, t->cg_max, s) : SB_ERR_UNSUPPORTED;
}

static void tr_free(void *st)
{
    tr_state *t = st;
    sb_trs_free(&t->trs);
    if (t->krylov) sb_krylov_free(&t->kr);
    free(t->g);
    free(t->gt);
    free(t->s);
    free(t->xt);
}

static int tr_set(void *st, sb_problem *p, const double *x, sb_iterate_info *info)
{
    tr_state *t = st;
    t->delta = t->delta0;
    int rc = sb_problem_eval(p, t->F, x, &t->f, t->g, sb_problem_hessian(p, t->F));
    t->gnorm = sb_problem_norm(p, t->F, t->g);
    t->fresh = 1;
    t->eta = t->gprev = 0.0;   /* Eisenstat–Walker starts afresh each step */
    sb_noise_floor_reset(&t->noise);
    info->f = t->f;
    info->gnorm = t->gnorm;
    info->delta = t->delta;
    return rc;
}

/* The subproblem by preconditioned Steihaug–Toint CG (solver.linear =
 * pcg-*): the preconditioner is set up once per Hessian (after accepted
 * steps), the tolerance is the Eisenstat–Walker forcing term of the
 * current ||g|| (kept while steps are rejected), negative curvature ends
 * the step on the boundary (Steihaug–Toint), and a solve that reaches its
 * cap is a truncated step judged by the ratio test like any other
 * (recorded as krylov_status 1). */
static int tr_krylov_step(tr_state *t, sb_problem *p, const double *x, sb_trs_result *r, sb_iterate_info *info)
{
    if (t->fresh) {
        int rc = sb_krylov_setup(&t->kr, p);
        if (rc < 0) return rc;
        /* SB_NOT_POSDEF (AMG set-up on an indefinite H): CG runs with the
         * preconditioner as it is and restarts without it if it misbehaves */
        if (t->cg_rtol >= 0.0) t->eta = t->cg_rtol;
        else {
            /* Kelley's floor on gstop and on the gradient's rounding (s, gt,
             * xt are free until the solve) */
            t->eta = sb_forcing_ew2(t->gnorm, t->gprev, t->eta);
            int rf = sb_noise_floor_apply(&t->noise, &t->kr, rc == SB_OK, p, x, t->g, t->gnorm, info->gstop, t->xt,
                                          t->gt, t->s, &t->eta);
            if (rf < 0) return rf;
        }
        t->gprev = t->gnorm;
    }
    double t0 = sb_now();
    sb_krylov_result kr;
    /* the correction test, as lsnewton's (newton.c krylov_direction) */
    t->kr.ztol = sb_krylov_xstop_ztol(t->xstop, info->xstop);
    int rc = sb_krylov_solve(&t->kr, p, t->g, t->delta, t->eta, t->cg_max, t->s, &kr);
    sb_problem_count_qp(p, t->F, sb_now() - t0);
    if (rc < 0) return rc;
    memset(r, 0, sizeof *r);
    r->pred = kr.pred;
    r->snorm = kr.snorm;
    r->iters = kr.iters;
    r->boundary = kr.status == SB_KRYLOV_BOUNDARY;
    r->newton = kr.status == SB_KRYLOV_CONVERGED;
    info->linear_rtol = t->eta;
    info->gnoise = t->noise.level;
    info->linear_status = (int)kr.status + (kr.by_correction ? 8 : 0);
    t->zcorr = kr.by_correction ? kr.znorm : 0.0;
    return SB_OK;
}

static void tr_describe(const void *st, char *buf, size_t len)
{
    const tr_state *t = st;
    if (t->krylov) sb_krylov_describe(&t->kr, buf, len);
    else if (len) buf[0] = 0;
}

/* Alg. 4.3, lines 2 and 7 with delta = infinity on the finest level. */
static double radius_update(const tr_state *t, double rho, double delta)
{
    if (rho < t->eta1) return t->gamma1 * delta;
    if (rho > t->eta2) return fmin(t->gamma2 * delta, 1e300);   /* finite, else unbounded as in the paper */
    return delta;
}

static int tr_iterate(void *st, sb_problem *p, double *x, sb_iterate_info *info)
{
    tr_state *t = st;
    const int n = t->n;
    sb_trs_result r;
    /* Alg. 4.1 line 2: constrained QP */
    int rc = t->krylov ? tr_krylov_step(t, p, x, &r, info)
                       : sb_trs_solve(&t->trs, p, t->F, t->g, t->delta, t->fresh, t->cg_max, t->s, &r);
    if (rc < 0) return rc;
    t->fresh = 0;
    /* contact step filter (docs/contact.md): a step that would carry a
     * sample point into an obstacle is shortened to tau s, and the model's
     * predicted reduction re-evaluated for it:
     * pred(tau s) = -(tau g^T s + tau^2/2 s^T H s) */
    double tau = sb_problem_step_bound(p, t->F, x, t->s);
    if (tau < 1.0) {
        sb_problem_hess_mult(p, t->F, t->s, t->gt);
        double gs = sb_dot(n, t->g, t->s), sHs = sb_dot(n, t->s, t->gt);
        sb_scal(n, tau, t->s);
        r.pred = -(tau * gs + 0.5 * tau * tau * sHs);
        r.snorm *= tau;
        r.newton = 0;
    }
    for (int i = 0; i < n; i++) t->xt[i] = x[i] + t->s[i];
    double ft;
    rc = sb_problem_eval(p, t->F, t->xt, &ft, NULL, NULL);
    if (rc < 0) return rc;
    /* Alg. 4.1 line 3: rho = actual / predicted reduction (Eq. 4.2) */
    double rho = sb_tr_ratio(rc, t->f, ft, r.pred);
    if (t->rho_paper)   /* Eq. (4.2) exactly: (f(x) - f(x + s)) / (m(0) - m(s)), round-off and all */
        rho = rc == SB_OK && isfinite(ft) && r.pred > 0.0 ? (t->f - ft) / r.pred : -INFINITY;
    else if (rc == SB_OK && (t->krylov ? sb_krylov_f_noise(t->f, ft, r.pred) || sb_tr_ared_unreliable(t->f, ft, r.pred)
                                       : sb_tr_ared_unreliable(t->f, ft, r.pred))) {
        rc = sb_problem_eval(p, t->F, t->xt, &ft, t->gt, NULL);
        if (rc < 0) return rc;
        rho = rc == SB_OK ? sb_tr_ratio_grad(n, t->g, t->gt, t->s, r.pred) : -INFINITY;
    }
    info->linear_iters = r.iters;
    info->rho = rho;
    info->has_correction = r.newton;     /* the Newton step at x, not cut by the radius */
    info->correction = r.snorm + (t->krylov ? t->zcorr : 0.0);   /* + the estimated remaining error */
    if (rho > t->eta1) {
        /* line 5: accept; derivatives are recomputed only here */
        double fnew;
        rc = sb_problem_eval(p, t->F, t->xt, &fnew, t->gt, sb_problem_hessian(p, t->F));
        if (rc < 0) return rc;
        t->fresh = 1;
        if (rc == SB_OK) {
            sb_copy(n, t->xt, x);
            double *sw = t->g; t->g = t->gt; t->gt = sw;
            info->df = t->f - fnew;
            info->step_norm = r.snorm;
            info->accepted = 1;
            t->f = fnew;
            t->gnorm = sb_problem_norm(p, t->F, t->g);
        } else {
            /* finite energy but non-finite derivatives at the trial point:
             * reject it like a failed ratio test and restore H at x (rare) */
            rho = -INFINITY;
            rc = sb_problem_eval(p, t->F, x, &fnew, t->gt, sb_problem_hessian(p, t->F));
            if (rc < 0) return rc;
        }
    }
    t->delta = radius_update(t, rho, t->delta);
    if (t->delta < t->delta_min) info->fail = SB_REASON_RADIUS;
    info->f = t->f;
    info->gnorm = t->gnorm;
    info->delta = t->delta;
    return SB_OK;
}

const sb_solver_type sb_solver_tr = {
    "tr", "single-level trust region, RMTR paper Alg. 4.1 + 4.3 (dogleg or Steihaug–Toint CG)",
    sizeof(tr_state), tr_params, SB_SOLVER_TRUST_REGION, tr_alloc, tr_set, tr_iterate, tr_free, tr_describe,
    tr_linear_solve,
};
