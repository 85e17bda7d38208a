/* sb_run_judge.c — what a run claims beyond its solver's stopping rule
 * (docs/trust.md): a step the solver calls converged must be a physical
 * state — finite, and straining the material no more than run.strain_max —
 * or the step is recorded with the reason that says why it is not. */
#include "sb_run_state.h"

#include "sb_geometry.h"

#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

sb_reason sb_run_judge_step(run_state *R, sb_reason reason)
{
    if (!sb_reason_converged(reason)) return reason;
    const int F = sb_problem_finest(R->prob), n = sb_problem_n(R->prob, F);
    if (!sb_all_finite(n, R->x)) return SB_REASON_NONFINITE;
    const double strain_max = sb_param(&R->ctx.params, "run.strain_max");
    if (!(strain_max > 0) || !R->mt->material_state) return reason;
    sb_material_state *m = &R->rec.material;
    R->rec.has_material = R->mt->material_state(R->ms, F, R->x, m) == SB_OK;
    R->material_current = R->rec.has_material;
    /* a state the material law cannot even evaluate is not admissible */
    if (!R->rec.has_material) return SB_REASON_STRAIN;
    for (int k = 0; k < 3; k++)
        if (!(m->max_strain[k] <= strain_max)) return SB_REASON_STRAIN;
    return reason;
}

/* The relative violation of penalty constraints: position errors and
 * rotation errors converted to a displacement over the domain's diameter
 * (ASSUMPTION: the lever arm of a clamp's rotation error is at most the
 * diameter), over the displacement scale max |x - X| of the sample grid.
 * A zero scale with a zero violation is 0; with a violation, infinite. */
void sb_run_judge_penalty(run_state *R)
{
    sb_run *rec = &R->rec;
    rec->has_penalty = 0;
    sb_penalty_report pr;
    memset(&pr, 0, sizeof pr);
    const int F = sb_problem_finest(R->prob);
    int rc = R->mt->penalty_violation ? R->mt->penalty_violation(R->ms, F, R->x, &pr) : SB_OK;
    if (rc < 0) return;
    /* sliding pins (sb_pin.h) are penalty constraints too, whatever the method */
    int n_pins = 0;
    const double pin_v = sb_problem_pin_violation(R->prob, R->x, &n_pins);
    if (n_pins) {
        pr.points += n_pins;
        pr.position_max = fmax(pr.position_max, pin_v);
    }
    if (pr.points == 0) return;
    double u = 0.0;
    for (int i = 0; i < rec->n_samples; i++) {
        const double *a = rec->sample_pos + 3 * i, *b = rec->sample_ref + 3 * i;
        u = fmax(u, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
    }
    const double v = fmax(pr.position_max, pr.rotation_max * sb_domain_diameter(&R->scene.domain));
    rec->has_penalty = 1;
    rec->penalty_beta = pr.beta;
    rec->penalty_position = pr.position_max;
    rec->penalty_rotation = pr.rotation_max;
    rec->penalty_scale = u;
    rec->penalty_relative = rc == SB_NONFINITE ? INFINITY : v == 0.0 ? 0.0 : u > 0.0 ? v / u : INFINITY;
    rec->penalty_tol = sb_param(&R->ctx.params, "run.penalty_tol");
    if (rec->status == 0 && rec->penalty_tol > 0 && !(rec->penalty_relative <= rec->penalty_tol)) {
        rec->status = 1;
        rec->reason = SB_REASON_PENALTY;
    }
}

void sb_run_judge_contact(run_state *R)
{
    sb_run *rec = &R->rec;
    if (!rec->has_impulse || rec->status != 0) return;
    const double allowed = sb_param(&R->ctx.params, "run.contact_unresolved_max");
    if (allowed < 0 || (double)rec->impulse.unresolved_steps <= allowed) return;
    rec->status = 1;
    rec->reason = SB_REASON_CONTACT_UNRESOLVED;
}

/* Phi_E(x_final) - Phi_E(X) (sb_record.h): the method's energy at the final
 * state and at the reference configuration, both with the last step's loads
 * and boundary data (the problem's current step).  Two energy evaluations,
 * counted.  Not for scenes with end moments: their potential -m theta is
 * multivalued (theta counts turns, and a method tracks it along the run's
 * path), so at X it is not defined by the final step's data alone. */
void sb_run_potential_change(run_state *R)
{
    sb_run *rec = &R->rec;
    rec->has_potential = 0;
    if (rec->steps_done < 1) return;
    for (int i = 0; i < R->scene.n_loads; i++)
        if (R->scene.loads[i].kind == SB_LOAD_END_MOMENT) return;
    double e1, e0;
    if (sb_problem_method_energy(R->prob, R->x, &e1) != SB_OK) return;
    if (sb_problem_method_energy(R->prob, R->xref, &e0) != SB_OK) return;
    rec->has_potential = 1;
    rec->potential_change = e1 - e0;
    /* E(x) is also the record's energy_final (sb_run_record_energy uses it
     * instead of a third evaluation: one pass over the elements less at the
     * end of a run, issue 42's harness share) */
    rec->has_energy = 1;
    rec->energy_final = e1;
}

/* "dir/name" with dir made absolute (realpath) when it exists */
static void normalize(const char *path, char *out, size_t len)
{
    char tmp[4096], tmp2[4096], dir[PATH_MAX];
    snprintf(tmp, sizeof tmp, "%s", path);
    snprintf(tmp2, sizeof tmp2, "%s", path);
    const char *base = basename(tmp2);
    if (realpath(dirname(tmp), dir)) snprintf(out, len, "%s/%s", dir, base);
    else snprintf(out, len, "%s", path);
}

int sb_run_same_path(const char *p, const char *q, char *a, char *b, size_t len)
{
    normalize(p, a, len);
    normalize(q, b, len);
    return strcmp(a, b) == 0;
}

int sb_run_recorded_exit(int status, const char *validation, int strict)
{
    if (status != 0) return SB_EXIT_NOT_CONVERGED;
    if (strict && validation && !strcmp(validation, "failed")) return SB_EXIT_VALIDATION;
    return SB_EXIT_CONVERGED;
}
