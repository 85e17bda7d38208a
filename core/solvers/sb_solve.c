/* sb_solve.c — the one outer loop shared by every solver: iterate, record,
 * test convergence (RMTR paper Eq. 7.1, with optional relative terms). */
#include "sb_solver.h"
#include "sb_context.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const sb_param_def sb_solve_params[] = {
    { "gtol", SB_PARAM_REAL, 1e-7, 0, 1e10, NULL, "stop when ||g|| < gtol (RMTR paper Eq. 7.1)" },
    { "gtol_rel", SB_PARAM_REAL, 1e-9, 0, 1, NULL,
      "also stop when ||g|| < gtol_rel ||g_0|| (scale-free extension of Eq. 7.1; 0 = paper rule)" },
    { "ftol", SB_PARAM_REAL, 1e-12, 0, 1e10, NULL, "|f_{i-1} - f_i| < ftol once Delta > delta_big (Eq. 7.1)" },
    { "xtol", SB_PARAM_REAL, 1e-12, 0, 1e10, NULL, "||x_{i-1} - x_i|| < xtol once Delta > delta_big (Eq. 7.1)" },
    { "delta_big", SB_PARAM_REAL, 1e15, 0, 1e300, NULL,
      "radius above which the f/x tests of Eq. 7.1 apply (Newton solvers: after full unshifted steps)" },
    { "stall_iter", SB_PARAM_INT, 10, 0, 1e9, NULL,
      "stop (reason stalled, not converged) after this many iterations in a row that accepted a step below xtol "
      "changing f by less than ftol, or rejected one with a radius below xtol (0 = never)" },
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

sb_reason sb_solve_step(const sb_solver_type *type, void *state, sb_problem *p, const sb_paramset *ps,
                        int step, double *x, int *iterations, double *f_out, double *gnorm_out)
{
    sb_context *ctx = sb_problem_context(p);
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F);
    const double gtol = sb_param(ps, "run.gtol"), gtol_rel = sb_param(ps, "run.gtol_rel");
    const double ftol = sb_param(ps, "run.ftol"), xtol = sb_param(ps, "run.xtol");
    const double delta_big = sb_param(ps, "run.delta_big"), diverge = sb_param(ps, "run.diverge");
    const int max_iter = sb_param_int(ps, "run.max_iter"), stall_iter = sb_param_int(ps, "run.stall_iter");
    int stalled = 0;

    double *x0 = malloc((size_t)n * sizeof *x0);
    if (!x0) return SB_REASON_LINEAR_SOLVER;
    sb_copy(n, x, x0);
    const double x0max = max_abs_diff(n, x0, NULL);

    sb_iterate_info info;
    memset(&info, 0, sizeof info);
    info.level = F;
    sb_reason reason = SB_REASON_NONE;
    int it = 0;
    int rc = type->set(state, p, x, &info);
    if (rc < 0) reason = SB_REASON_LINEAR_SOLVER;
    else if (info.fail) reason = info.fail;
    else if (rc == SB_NONFINITE || !isfinite(info.f)) reason = SB_REASON_NONFINITE;
    const double g0 = info.gnorm;
    const double gstop = fmax(gtol, gtol_rel * g0);
    if (!reason && info.gnorm < gstop) reason = SB_REASON_GRAD_TOL;
    {
        sb_iter_record r0 = { step, 0, F, info.f, info.gnorm, info.delta, 0, 0, 0, 1, 0, reason };
        sb_stats_push_iter(&ctx->stats, &r0);
    }
    while (!reason) {
        if (it >= max_iter) { reason = SB_REASON_MAX_ITER; break; }
        memset(&info, 0, sizeof info);
        info.level = F;
        rc = type->iterate(state, p, x, &info);
        it++;
        if (rc < 0) reason = SB_REASON_LINEAR_SOLVER;
        else if (info.fail) reason = info.fail;
        else if (rc == SB_NONFINITE || !isfinite(info.f) || !isfinite(info.gnorm)) reason = SB_REASON_NONFINITE;
        else if (info.level != F) {
            /* an iteration on a coarser level (RMTR's nested start): x moves only
             * when the start reaches the finest level; only a failure or the cap
             * ends the step, convergence is tested on the finest level */
        }
        else if (info.gnorm < gstop) reason = SB_REASON_GRAD_TOL;
        else if (type->flags & SB_SOLVER_SINGLE_STEP) reason = SB_REASON_SINGLE_STEP;
        else if (max_abs_diff(n, x, x0) > diverge * (1.0 + x0max)) reason = SB_REASON_DIVERGED;
        else if (info.accepted && info.delta > delta_big) {
            /* Newton solvers report delta = inf for a full unshifted Newton step */
            if (fabs(info.df) < ftol) reason = SB_REASON_F_TOL;
            else if (info.step_norm < xtol) reason = SB_REASON_X_TOL;
        }
        if (!reason && info.level == F) {
            /* the limiting accuracy: steps and changes of f at round-off while the
             * radius shrinks (Eq. 7.1's f/x tests need a big radius) */
            const int tiny = info.accepted ? info.step_norm < xtol && fabs(info.df) < ftol : info.delta < xtol;
            stalled = tiny ? stalled + 1 : 0;
            if (stall_iter > 0 && stalled >= stall_iter) reason = SB_REASON_STALLED;
        }
        sb_iter_record r = { step, it, info.level, info.f, info.gnorm, info.delta, info.rho, info.step_norm,
                             info.shift, info.accepted, info.linear_iters, reason };
        sb_stats_push_iter(&ctx->stats, &r);
        if (ctx->monitor) ctx->monitor(ctx->monitor_data, &r);
    }
    free(x0);
    *iterations = it;
    *f_out = info.f;
    *gnorm_out = info.gnorm;
    return reason;
}
