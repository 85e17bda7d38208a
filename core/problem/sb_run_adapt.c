/* sb_run_adapt.c — adaptive meshes in the run (sb_method.h adapt, issue 22):
 * every method.adapt_every steps the method may change its discretization;
 * the run then takes the mapped state, re-sizes its vectors, rebuilds the
 * problem (dofs, pattern, Dirichlet set, mass; the symbolic analysis is
 * redone and counted at the next factorization) and re-allocates the
 * solver.  The time spent is event `adapt`; each step records its dofs.
 * A method may declare method.adaptive too: its runs with adaptive = 0 keep
 * their mesh (no adapt calls, resumable).
 * Checkpoints of an adaptive run carry the method's mesh at the resume
 * point (save_mesh, written as /resume/mesh_*); --resume restores it
 * (restore_mesh) and follows it as after an adaptation, so a resumed run
 * equals an uninterrupted one bit for bit (tests/test_a3_resume.c).  A
 * method without save_mesh / restore_mesh refuses --stop-after-steps and
 * --resume from a checkpoint (--resume with no checkpoint starts at step
 * 1, as study sweeps ask) and writes no checkpoints, with a sentence. */
#include "sb_run_state.h"

#include <stdlib.h>
#include <unistd.h>
#include <string.h>

int sb_run_adapt_every(const run_state *R)
{
    if (!R->mt || !R->mt->adapt || !R->mt->adapt_state) return 0;
    /* a method may also declare method.adaptive; 0 there means a fixed mesh */
    const sb_paramset *ps = &R->ctx.params;
    int every = 0;
    for (int i = 0; i < ps->n; i++) {
        if (strcmp(ps->v[i].key, "method.adaptive") == 0 && ps->v[i].value == 0.0) return 0;
        if (strcmp(ps->v[i].key, "method.adapt_every") == 0) every = (int)ps->v[i].value;
    }
    return every;
}

int sb_run_adapt_resumable(const run_state *R)
{
    return R->mt && R->mt->save_mesh && R->mt->restore_mesh;
}

int sb_run_adapt_check(run_state *R, const sb_run_request *req)
{
    if (sb_run_adapt_every(R) <= 0 || sb_run_adapt_resumable(R)) return -1;
    /* a method that cannot save its mesh: --resume with nothing to resume
     * starts at step 1 (a study sweep asks every run to resume), and a
     * finished record is "nothing to do" as for every method; only a
     * checkpoint to continue from is refused */
    const int has_checkpoint = req->resume && R->partial_path[0] && access(R->partial_path, F_OK) == 0;
    if (has_checkpoint || req->stop_after_steps > 0) {
        fprintf(R->err, "shellbench: method %s adapts its mesh during the run (method.adapt_every = %d) and cannot "
                "save it in a checkpoint (no save_mesh / restore_mesh), so its runs cannot be resumed: %s\n",
                R->mt->name, sb_run_adapt_every(R),
                has_checkpoint ? "remove its checkpoint or run it without --resume" : "run it without --stop-after-steps");
        return SB_EXIT_INPUT;
    }
    if (R->checkpoints_on && !req->quiet)
        fprintf(R->err, "shellbench: note: no checkpoints for the adaptive method %s (it cannot save its mesh)\n",
                R->mt->name);
    R->checkpoints_on = 0;
    return -1;
}

static int grow(double **p, int n)
{
    double *q = realloc(*p, (size_t)(n ? n : 1) * sizeof **p);
    if (!q) return SB_ERR_NOMEM;
    *p = q;
    return SB_OK;
}

int sb_run_adapt_follow(run_state *R, int take_state)
{
    const int F = sb_problem_finest(R->prob);
    const int n = R->mt->n_dofs(R->ms, F);
    int rc = n > 0 ? SB_OK : SB_ERR_INTERNAL;
    if (!rc && (grow(&R->x, n) || grow(&R->xn, n) || grow(&R->v, n) || grow(&R->xref, n) || grow(&R->bp.x, n) ||
                grow(&R->bp.v, n)))
        rc = SB_ERR_NOMEM;
    if (!rc && take_state) rc = R->mt->adapt_state(R->ms, R->x, R->v);
    if (!rc) rc = R->mt->initial(R->ms, F, R->xref);
    if (!rc) rc = sb_problem_rebuild(R->prob);
    if (!rc) {
        /* the solver's vectors have the old size: allocated anew */
        R->stype->free(R->ss);
        memset(R->ss, 0, R->stype->state_size);
        rc = R->stype->alloc(R->ss, R->prob, &R->ctx.params);
    }
    if (!rc) {
        R->rec.n_x = R->rec.n_dofs = n;   /* the record's dofs: the final mesh's (per step: history) */
        R->rec.x_final = R->x;            /* re-allocated above */
    }
    return rc;
}

int sb_run_adapt(run_state *R, int step, int *n_out)
{
    const int every = sb_run_adapt_every(R);
    if (every <= 0 || step <= 1 || (step - 1) % every) return -1;
    sb_stats *stats = &R->ctx.stats;
    const int F = sb_problem_finest(R->prob);
    double t0 = sb_stats_begin(stats);
    int changed = 0, rc = R->mt->adapt(R->ms, R->x, R->v, &changed);
    if (rc == SB_OK && changed) {
        rc = sb_run_adapt_follow(R, 1);
        /* a resumed process's first analysis after a change is the run's own, not a repeat (sb_run_fold_resume_setup) */
        if (R->resumed) R->resume_folded = 1;
        if (!rc && sb_problem_has_contact(R->prob)) {
            /* the new surface (inserted vertices, flips, joins) may put a
             * sample point inside an obstacle the old one kept clear of:
             * pushed out at the state's time t_(step-1) (docs/contact.md) */
            int moved = 0, left = sb_problem_contact_separate(R->prob, step - 1, R->x, &moved);
            if (left < 0) rc = left;
            R->contact_separated += moved;
        }
    }
    sb_stats_event(stats, F, SB_EV_ADAPT, t0);
    if (rc) {
        fprintf(R->err, "shellbench: step %d: adapting the mesh of method %s failed: %s\n", step, R->mt->name,
                R->ctx.err[0] ? R->ctx.err : "(no message)");
        return SB_EXIT_INTERNAL;
    }
    *n_out = sb_problem_n(R->prob, F);
    return -1;
}
