/* sb_solve.c — the one outer loop shared by every solver: iterate, record,
 * test convergence (RMTR paper Eq. 7.1, with optional relative terms). */
#include "sb_solver.h"
#include "sb_context.h"
#include "sb_shell.h"   /* sb_vector_choices (run.vectors) */

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const stop_names[] = { "scaled", "paper", NULL };
static const char *const supernode_names[] = { "cholmod", "wide", NULL };

const sb_param_def sb_solve_params[] = {
    { "stop", SB_PARAM_CHOICE, SB_STOP_SCALED, 0, 0, stop_names,
      "stopping rule: scaled (||g|| <= gtol_rel times the step's force scale, or a correction below the "
      "round-off of x; docs/trust.md) or paper (RMTR paper Eq. 7.1: absolute gtol, f/x tests once Delta > "
      "delta_big; the rule of the committed paper reproductions)" },
    { "gtol", SB_PARAM_REAL, 1e-7, 0, 1e10, NULL,
      "stop when ||g|| < gtol (RMTR paper Eq. 7.1; with stop=scaled only when set explicitly)" },
    { "gtol_rel", SB_PARAM_REAL, 1e-9, 0, 1, NULL,
      "stop when ||g|| <= gtol_rel F; stop=scaled: F = min(||g_0||, force scale of the step), stop=paper: "
      "F = ||g_0|| (scale-free extension of Eq. 7.1; 0 = off)" },
    { "xtol_rel", SB_PARAM_REAL, 1e-12, 0, 1e-3, NULL,
      "stop=scaled: the limiting accuracy, a correction not limited by a radius or line search below "
      "xtol_rel ||x|| (converged, roundoff_limit); also the size of a stalled step" },
    { "ftol", SB_PARAM_REAL, 1e-12, 0, 1e10, NULL, "stop=paper: |f_{i-1} - f_i| < ftol once Delta > delta_big (Eq. 7.1)" },
    { "xtol", SB_PARAM_REAL, 1e-12, 0, 1e10, NULL, "stop=paper: ||x_{i-1} - x_i|| < xtol once Delta > delta_big (Eq. 7.1)" },
    { "delta_big", SB_PARAM_REAL, 1e15, 0, 1e300, NULL,
      "stop=paper: radius above which the f/x tests of Eq. 7.1 apply (Newton solvers: after full unshifted steps)" },
    { "stall_iter", SB_PARAM_INT, 10, 0, 1e9, NULL,
      "stop (reason stalled, not converged) after this many iterations in a row whose accepted steps (or, when "
      "rejected, radii) are at round-off (stop=scaled: below xtol_rel ||x||; stop=paper: steps below xtol "
      "changing f by less than ftol, radii below xtol) (0 = never)" },
    { "single_step_rtol", SB_PARAM_REAL, 0.5, 0, 1e300, NULL,
      "single-step solvers (linearized): the step counts as converged only when it leaves ||g|| <= "
      "single_step_rtol max(||g_0||, force scale) (else single_step_residual)" },
    { "strain_max", SB_PARAM_REAL, 1.0, 0, 1e300, NULL,
      "a step whose state strains the material beyond this Green-Lagrange strain (max |E_ij| at the "
      "midsurface) is not converged (reason strain_bound; methods with material_state; 0 = no bound)" },
    { "penalty_tol", SB_PARAM_REAL, 5e-2, 0, 1e300, NULL,
      "a run whose penalty-imposed constraints are violated by more than penalty_tol times the displacement "
      "scale at its end is not converged (reason penalty_violated; methods with penalty constraints; 0 = recorded, "
      "not judged)" },
    { "contact_unresolved_max", SB_PARAM_INT, 0, -1, 1e9, NULL,
      "contact.model = impulse: a run in which more than this many steps ended with a collision the response "
      "left unresolved is not converged at its end (reason contact_unresolved; the run goes on to its last "
      "step; -1 = recorded, not judged)" },
    { "max_iter", SB_PARAM_INT, 10000, 1, 1e9, NULL, "iteration cap per step" },
    { "diverge", SB_PARAM_REAL, 1e6, 1, 1e300, NULL,
      "diverged when max|x - x_0| exceeds diverge * (1 + max|x_0|)" },
    { "checkpoint", SB_PARAM_REAL, 300, 0, 1e9, NULL,
      "seconds between checkpoints: the record so far (status unfinished) is written to OUT.partial while the "
      "run goes on, and removed once OUT is written; a killed run leaves it (0 = never)" },
    { "perturb", SB_PARAM_REAL, 0, 0, 1e10, NULL,
      "add to every dof of the start an offset uniform in [-perturb, perturb] (the dofs' units: m for control "
      "points), to sample how counts on a nonconvex scene spread under round-off-sized changes (0 = none)" },
    { "seed", SB_PARAM_INT, 1, 0, 2147483647, NULL, "seed of run.perturb's random offsets" },
    { "max_memory", SB_PARAM_REAL, 0, 0, 1e9, NULL,
      "GB (1e9 bytes) a run may take: one whose estimate (discretization, matrices, Cholesky factor, record) exceeds "
      "it is refused before any work (0 = the machine's physical memory)" },
    { "lifting", SB_PARAM_INT, 1, 0, 1, NULL,
      "start a step with moving boundaries from the linear lifting of the boundary increment (0 = off)" },
    { "threads", SB_PARAM_INT, 1, 1, 64, NULL,
      "threads assembling energy, gradient and Hessian over elements (rmtr, bhem; OpenMP): the reduction is in "
      "element order, so every count and record is bit-identical for any number (docs/performance.md)" },
    { "vectors", SB_PARAM_CHOICE, 0, 0, 0, sb_vector_choices,
      "vector width of the fast shell kernel (rmtr, bhem): auto = the widest this CPU runs; every width gives "
      "the same bits, only the speed differs (docs/performance.md)" },
    { "supernodes", SB_PARAM_CHOICE, SB_SUPERNODES_CHOLMOD, 0, 0, supernode_names,
      "CHOLMOD's relaxed supernode amalgamation: cholmod (its defaults, nrelax 4/16/48, zrelax 0.8/0.1/0.05) or "
      "wide (16/48/128, 0.9/0.2/0.1: larger dense blocks, a faster numeric factorization at >= 1e5 dofs for a "
      "larger factor; the same factorization up to round-off; docs/scaling.md)" },
    { NULL, 0, 0, 0, 0, NULL, NULL }
};

static double max_abs_diff(int n, const double *a, const double *b)
{
    double m = 0.0;
    for (int i = 0; i < n; i++) {
        double d = fabs(a[i] - (b ? b[i] : 0.0));
        if (d > m) m = d;
    }
    return m;
}

/* Whether the user set a parameter on the command line (an explicit gtol
 * is honoured by the scaled rule as an absolute tolerance). */
/* Inclusive seconds so far of the parts an iteration record keeps: assembly
 * (energy, gradient, hessian), analyze, factorize, solve, collide. */
static void iter_seconds(const sb_stats *st, double out[6])
{
    out[0] = sb_stats_event_total(st, SB_EV_ENERGY).seconds + sb_stats_event_total(st, SB_EV_GRADIENT).seconds +
             sb_stats_event_total(st, SB_EV_HESSIAN).seconds;
    out[1] = sb_stats_event_total(st, SB_EV_ANALYZE).seconds;
    out[2] = sb_stats_event_total(st, SB_EV_FACTORIZE).seconds;
    out[3] = sb_stats_event_total(st, SB_EV_SOLVE).seconds;
    out[4] = sb_stats_event_total(st, SB_EV_COLLIDE).seconds;
    out[5] = 0.0;
}

static int overridden(const sb_paramset *ps, const char *key)
{
    for (int i = 0; i < ps->n; i++)
        if (strcmp(ps->v[i].key, key) == 0) return ps->v[i].overridden;
    return 0;
}

sb_reason sb_solve_step(const sb_solver_type *type, void *state, sb_problem *p, const sb_paramset *ps,
                        int step, double *x, int *iterations, double *f_out, double *gnorm_out)
{
    sb_step_outcome o;
    sb_reason r = sb_solve_step_ex(type, state, p, ps, step, x, &o);
    *iterations = o.iterations;
    *f_out = o.f;
    *gnorm_out = o.gnorm;
    return r;
}

/* The stopping rules (docs/trust.md):
 *   paper   RMTR paper Eq. (7.1): ||g|| < max(gtol, gtol_rel ||g_0||), or, once
 *           Delta > delta_big (Newton: an unshifted step), |df| < ftol or
 *           ||s|| < xtol; the committed paper reproductions ran with it.
 *   scaled  ||g|| <= gtol_rel F with F = min(||g_0||, force scale of the step
 *           (sb_problem_force_scale); ||g_0|| when that is 0: no applied
 *           forces, only prescribed motion), so that the relative test is bounded by
 *           the applied forces and accepts no state whose own imbalance is
 *           huge; or the limiting accuracy: a correction the solver's model
 *           asked for without a radius or line search limiting it, below
 *           xtol_rel ||x|| (roundoff_limit).  gtol applies only when set.
 * Both: stalled (not converged) after stall_iter round-off steps in a row,
 * diverged, the iteration cap; a single-step solver's step is judged by its
 * linear residual and by ||g|| after it (single_step_rtol). */
sb_reason sb_solve_step_ex(const sb_solver_type *type, void *state, sb_problem *p, const sb_paramset *ps,
                           int step, double *x, sb_step_outcome *out)
{
    sb_context *ctx = sb_problem_context(p);
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F);
    const int scaled = sb_param_int(ps, "run.stop") == SB_STOP_SCALED;
    const double gtol = sb_param(ps, "run.gtol"), gtol_rel = sb_param(ps, "run.gtol_rel");
    const double ftol = sb_param(ps, "run.ftol"), xtol = sb_param(ps, "run.xtol");
    const double xtol_rel = sb_param(ps, "run.xtol_rel");
    const double delta_big = sb_param(ps, "run.delta_big"), diverge = sb_param(ps, "run.diverge");
    const int max_iter = sb_param_int(ps, "run.max_iter"), stall_iter = sb_param_int(ps, "run.stall_iter");
    const double single_rtol = sb_param(ps, "run.single_step_rtol");
    const int single = (type->flags & SB_SOLVER_SINGLE_STEP) != 0;
    int stalled = 0;

    memset(out, 0, sizeof *out);
    out->force_scale = NAN;
    double *x0 = malloc((size_t)n * sizeof *x0);
    if (!x0) return out->reason = SB_REASON_LINEAR_SOLVER;
    sb_copy(n, x, x0);
    const double x0max = max_abs_diff(n, x0, NULL);

    sb_reason reason = SB_REASON_NONE;
    double fscale = INFINITY;
    sb_iterate_info info;
    memset(&info, 0, sizeof info);
    info.level = F;
    int it = 0;
    int rc = type->set(state, p, x, &info);
    if (scaled && rc >= 0) {
        /* after set(): a method's first evaluation of a step may set state
         * from the point it is given (bhem's end-moment angle branch), which
         * must be the step's start, not the reference configuration */
        int rs = sb_problem_force_scale(p, &fscale);
        if (rs < 0) rc = rs;
        out->force_scale = rs == SB_OK ? fscale : INFINITY;
        if (rs != SB_OK) fscale = INFINITY;
    }
    if (rc < 0) reason = SB_REASON_LINEAR_SOLVER;
    else if (info.fail) reason = info.fail;
    else if (rc == SB_NONFINITE || !isfinite(info.f) || !isfinite(info.gnorm)) reason = SB_REASON_NONFINITE;
    const double g0 = info.gnorm;
    double gstop;
    if (scaled) {
        /* no applied forces at all (only prescribed motion): the step's own
         * imbalance is the scale (physical states: run.strain_max guards) */
        gstop = gtol_rel * (fscale > 0 ? fmin(g0, fscale) : g0);
        if (overridden(ps, "run.gtol")) gstop = fmax(gstop, gtol);
    } else {
        gstop = fmax(gtol, gtol_rel * g0);
    }
    out->g0 = g0;
    out->gstop = gstop;
    /* scaled: <= so that a step with nothing to do (g = F = 0) is solved */
#define GRAD_OK(g) (scaled ? (g) <= gstop : (g) < gstop)
    if (!reason && GRAD_OK(info.gnorm)) reason = SB_REASON_GRAD_TOL;
    {
        sb_iter_record r0 = { step, 0, F, info.f, info.gnorm, info.delta, 0, 0, 0, 1, 0, reason, 0, 0, 0, 0, 0, 0, 0, 0 };
        sb_stats_push_iter(&ctx->stats, &r0);
    }
    while (!reason) {
        if (it >= max_iter) { reason = SB_REASON_MAX_ITER; break; }
        memset(&info, 0, sizeof info);
        info.level = F;
        info.gstop = gstop;
        info.xstop = scaled ? xtol_rel * sb_norm2(n, x) : 0.0;
        double ev0[6], ev1[6], ti0 = sb_now();
        iter_seconds(&ctx->stats, ev0);
        rc = type->iterate(state, p, x, &info);
        if (info.gnoise > 0.0) out->gnoise = info.gnoise;
        iter_seconds(&ctx->stats, ev1);
        const double ti1 = sb_now();
        it++;
        const int finite = isfinite(info.f) && isfinite(info.gnorm);
        const double xnorm = scaled ? sb_norm2(n, x) : 0.0;
        if (rc < 0) reason = SB_REASON_LINEAR_SOLVER;
        /* a failure at a non-finite state is that state's (pressure 1e308: ||g|| = inf) */
        else if (info.fail) reason = !finite && info.fail != SB_REASON_LINEAR_SOLVER ? SB_REASON_NONFINITE : info.fail;
        else if (rc == SB_NONFINITE || !finite) reason = SB_REASON_NONFINITE;
        else if (info.level != F) {
            /* an iteration on a coarser level (RMTR's nested start): x moves only
             * when the start reaches the finest level; only a failure or the cap
             * ends the step, convergence is tested on the finest level */
        }
        else if (GRAD_OK(info.gnorm)) reason = SB_REASON_GRAD_TOL;
        else if (single) {
            /* one Newton step by design: judged, not assumed (docs/trust.md) */
            double scale = scaled && isfinite(fscale) ? fmax(g0, fscale) : g0;
            if (!(info.linear_residual <= 1e-8)) reason = SB_REASON_LINEAR_SOLVER;
            else if (info.gnorm > single_rtol * scale) reason = SB_REASON_SINGLE_STEP_RESIDUAL;
            else reason = SB_REASON_SINGLE_STEP;
        }
        else if (max_abs_diff(n, x, x0) > diverge * (1.0 + x0max)) reason = SB_REASON_DIVERGED;
        else if (scaled) {
            if (info.has_correction && info.correction <= xtol_rel * xnorm) reason = SB_REASON_ROUNDOFF;
        }
        else if (info.accepted && info.delta > delta_big) {
            /* Newton solvers report delta = inf for a full unshifted Newton step */
            if (fabs(info.df) < ftol) reason = SB_REASON_F_TOL;
            else if (info.step_norm < xtol) reason = SB_REASON_X_TOL;
        }
        if (!reason && info.level == F) {
            /* the limiting accuracy: steps and changes of f at round-off while the
             * radius shrinks (Eq. 7.1's f/x tests need a big radius) */
            int tiny;
            if (scaled) tiny = (info.accepted ? info.step_norm : info.delta) <= xtol_rel * xnorm;
            else tiny = info.accepted ? info.step_norm < xtol && fabs(info.df) < ftol : info.delta < xtol;
            stalled = tiny ? stalled + 1 : 0;
            if (stall_iter > 0 && stalled >= stall_iter) reason = SB_REASON_STALLED;
        }
        sb_iter_record r = { step, it, info.level, info.f, info.gnorm, info.delta, info.rho, info.step_norm,
                             info.shift, info.accepted, info.linear_iters, reason, ti1 - ti0, ev1[0] - ev0[0],
                             ev1[1] - ev0[1], ev1[2] - ev0[2], ev1[3] - ev0[3], ev1[4] - ev0[4],
                             info.linear_rtol, info.linear_status };
        sb_stats_push_iter(&ctx->stats, &r);
        if (ctx->monitor) ctx->monitor(ctx->monitor_data, &r);
    }
#undef GRAD_OK
    free(x0);
    out->reason = reason;
    out->iterations = it;
    out->f = info.f;
    out->gnorm = info.gnorm;
    return reason;
}
