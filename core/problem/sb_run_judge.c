/* sb_run_judge.c — what a run claims beyond its solver's stopping rule
 * (docs/trust.md): a step the solver calls converged must be a physical
 * state — finite, and straining the material no more than run.strain_max —
 * or the step is recorded with the reason that says why it is not. */
#include "sb_run_state.h"

#include <math.h>

sb_reason sb_run_judge_step(run_state *R, sb_reason reason)
{
    if (!sb_reason_converged(reason)) return reason;
    const int F = sb_problem_finest(R->prob), n = sb_problem_n(R->prob, F);
    if (!sb_all_finite(n, R->x)) return SB_REASON_NONFINITE;
    const double strain_max = sb_param(&R->ctx.params, "run.strain_max");
    if (!(strain_max > 0) || !R->mt->material_state) return reason;
    sb_material_state *m = &R->rec.material;
    R->rec.has_material = R->mt->material_state(R->ms, F, R->x, m) == SB_OK;
    /* a state the material law cannot even evaluate is not admissible */
    if (!R->rec.has_material) return SB_REASON_STRAIN;
    for (int k = 0; k < 3; k++)
        if (!(m->max_strain[k] <= strain_max)) return SB_REASON_STRAIN;
    return reason;
}
