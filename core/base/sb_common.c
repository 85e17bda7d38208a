/* sb_common.c — names of outcome reasons. */
#include "sb_common.h"

static const char *const reason_names[SB_REASON_COUNT] = {
    [SB_REASON_NONE] = "none",
    [SB_REASON_GRAD_TOL] = "grad_tol",
    [SB_REASON_F_TOL] = "f_tol",
    [SB_REASON_X_TOL] = "x_tol",
    [SB_REASON_SINGLE_STEP] = "single_step",
    [SB_REASON_MAX_ITER] = "max_iter",
    [SB_REASON_NONFINITE] = "nonfinite",
    [SB_REASON_DIVERGED] = "diverged",
    [SB_REASON_NOT_POSDEF] = "not_posdef",
    [SB_REASON_LINESEARCH] = "line_search_failed",
    [SB_REASON_RADIUS] = "radius_collapsed",
    [SB_REASON_LINEAR_SOLVER] = "linear_solver_failed",
    [SB_REASON_STALLED] = "stalled",
    [SB_REASON_CHECKPOINT] = "checkpoint",
    [SB_REASON_ROUNDOFF] = "roundoff_limit",
    [SB_REASON_PENALTY] = "penalty_violated",
    [SB_REASON_STRAIN] = "strain_bound",
    [SB_REASON_SINGLE_STEP_RESIDUAL] = "single_step_residual",
    [SB_REASON_OBSTACLE_SWEPT] = "obstacle_swept",
    [SB_REASON_CONTACT_UNRESOLVED] = "contact_unresolved",
};

const char *sb_reason_name(sb_reason r)
{
    if ((int)r < 0 || r >= SB_REASON_COUNT) return "invalid";
    return reason_names[r];
}

int sb_reason_converged(sb_reason r)
{
    return r == SB_REASON_GRAD_TOL || r == SB_REASON_F_TOL || r == SB_REASON_X_TOL ||
           r == SB_REASON_SINGLE_STEP || r == SB_REASON_ROUNDOFF;
}
