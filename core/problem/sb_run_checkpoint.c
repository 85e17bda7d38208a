/* sb_run_checkpoint.c — checkpoints of a run under way (OUT.partial), the
 * resume point at each step boundary, and --resume (sb_run_state.h). */
#include "sb_run_state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The path of a run's checkpoint: OUT.partial (its XDMF sidecar
 * OUT.partial.xdmf), so that globs for *.h5 and a sweep's resume never take
 * it for a finished record. */
int sb_run_partial_path(const char *out_path, char *buf, size_t len)
{
    return snprintf(buf, len, "%s.partial", out_path) >= (int)len ? -1 : 0;
}

/* Once the record is written, its checkpoint (this run's, or a stale one of
 * an earlier interrupted run to the same path) has served. */
void sb_run_remove_partial(run_state *R)
{
    char x[1200];
    if (!R->partial_path[0]) return;
    unlink(R->partial_path);
    if (sb_record_xdmf_path(R->partial_path, x, sizeof x) == SB_OK) unlink(x);
    if (sb_record_steps_xdmf_path(R->partial_path, x, sizeof x) == SB_OK) unlink(x);
    if (sb_record_mesh_xdmf_path(R->partial_path, x, sizeof x) == SB_OK) unlink(x);
}

/* Write the record so far (steps done, the iteration history including the
 * current step's, x and the sample positions now) as a checkpoint with
 * status SB_STATUS_UNFINISHED.  A failed write is a warning, once, and ends
 * the checkpoints; it never stops the run. */
void sb_run_write_checkpoint(run_state *R)
{
    sb_run *rec = &R->rec;
    sb_stats *stats = &R->ctx.stats;
    const int F = sb_problem_finest(R->prob);
    double t0 = sb_stats_begin(&R->ctx.stats);
    const int status = rec->status, reason = rec->reason;
    rec->status = SB_STATUS_UNFINISHED;
    rec->reason = SB_REASON_CHECKPOINT;
    rec->resume = &R->bp;
    if (R->mt->eval_points)
        R->mt->eval_points(R->ms, F, R->x, rec->n_samples, rec->sample_st, rec->sample_pos);
    /* /final/material only of a judged state (a step's end): a checkpoint
     * written between iterations is a resume point, and `inspect` computes
     * the material state of its x itself.  Evaluating the law's convexity
     * at every quadrature point there cost 5 s a checkpoint at 1e6 dofs of
     * the subdivision method (issue 42) */
    const int has_material = rec->has_material;
    if (!R->material_current) rec->has_material = 0;
    stats->seconds_total = t0 - R->t_start;
    char msg[2048];
    if (sb_record_write(rec, R->partial_path, msg, sizeof msg)) {
        fprintf(R->err, "shellbench: warning: no more checkpoints: %s\n", msg);
        R->checkpoint_failed = 1;
    }
    rec->has_material = has_material;
    rec->status = status;
    rec->reason = reason;
    rec->resume = NULL;
    sb_stats_event(stats, F, SB_EV_CHECKPOINT, t0);
    R->checkpoint_last = sb_now();
}

/* The end of step `step` (0: the start) as the resume point: x, v and a
 * snapshot of the statistics (history pointers left out: the boundary is
 * n_iters / n_steps records into the live history). */
void sb_run_mark_boundary(run_state *R, int step)
{
    sb_resume_point *b = &R->bp;
    b->step = step;
    b->n_x = R->rec.n_x;
    sb_copy(b->n_x, R->x, b->x);
    sb_copy(b->n_x, R->v, b->v);
    b->stats = R->ctx.stats;
    b->stats.iters = NULL;
    b->stats.steps = NULL;
    b->stats.cap_iters = b->stats.cap_steps = 0;
    b->seconds = sb_now() - R->t_start;
    b->has_impulse = R->rec.has_impulse;
    b->impulse = R->rec.impulse;
    /* an adaptive method's mesh at the boundary: the next step may adapt
     * before a checkpoint is written (checkpoints are also written mid-step) */
    sb_blob_free(&b->mesh);
    b->has_mesh = 0;
    if (sb_run_adapt_every(R) > 0 && sb_run_adapt_resumable(R)) {
        if (R->mt->save_mesh(R->ms, &b->mesh) == SB_OK) {
            b->has_mesh = 1;
        } else {
            sb_blob_free(&b->mesh);
            if (R->checkpoints_on && !R->checkpoint_failed)
                fprintf(R->err, "shellbench: warning: no more checkpoints: method %s could not save its mesh: %s\n",
                        R->mt->name, R->ctx.err[0] ? R->ctx.err : "(no message)");
            R->checkpoint_failed = 1;
        }
    }
}

/* "a,b" + ",c" into a fixed buffer (kept whole or left as it was) */
static void list_append(char *buf, size_t len, const char *item)
{
    size_t u = strlen(buf);
    if (u + strlen(item) + 2 <= len) snprintf(buf + u, len - u, "%s%s", u ? "," : "", item);
}

/* --resume: continue from the resume point of OUT.partial.  No checkpoint:
 * the run starts at step 1 (0).  A checkpoint of another run, or an
 * unreadable one, is an input error (-1) and stays untouched.  Statistics
 * become the checkpoint's at its boundary (set-up of this process is in
 * the resume log, not in the event counts, so the counts equal those of an
 * uninterrupted run); seconds_total goes on from the boundary. */
int sb_run_resume(run_state *R, int quiet)
{
    sb_run *rec = &R->rec;
    if (access(R->partial_path, F_OK) != 0) {
        if (!quiet) sb_escape_print(R->err, "shellbench: no checkpoint %s: starting at step 1", R->partial_path);
        return 0;
    }
    sb_resume_point rp;
    sb_resume_log log;
    double ck_seconds = 0, setup = sb_now() - R->t_start;
    char ck_build[64] = "", msg[2048];
    if (sb_record_read_resume(R->partial_path, rec, &rp, &ck_seconds, ck_build, sizeof ck_build, &log, rec->probe_traj,
                              msg, sizeof msg)) {
        fprintf(R->err, "shellbench: %s\n", msg);
        return -1;
    }
    sb_stats *st = &R->ctx.stats;
    memcpy(st->ev, rp.stats.ev, sizeof st->ev);
    st->work_assembly = rp.stats.work_assembly;
    st->work_qp = rp.stats.work_qp;
    st->not_posdef = rp.stats.not_posdef;
    memcpy(st->chol_flops_sum, rp.stats.chol_flops_sum, sizeof st->chol_flops_sum);
    memcpy(st->chol_nnz_l_sum, rp.stats.chol_nnz_l_sum, sizeof st->chol_nnz_l_sum);
    memcpy(st->chol_factorize_cpu, rp.stats.chol_factorize_cpu, sizeof st->chol_factorize_cpu);
    memcpy(st->chol_first_cpu, rp.stats.chol_first_cpu, sizeof st->chol_first_cpu);
    memcpy(st->chol_first_flops, rp.stats.chol_first_flops, sizeof st->chol_first_flops);
    st->n_iters = st->n_steps = 0;
    int bad = 0;
    for (size_t i = 0; i < rp.stats.n_iters && !bad; i++) bad = sb_stats_push_iter(st, &rp.stats.iters[i]);
    for (size_t i = 0; i < rp.stats.n_steps && !bad; i++) bad = sb_stats_push_step(st, &rp.stats.steps[i]);
    if (bad) {
        sb_resume_point_free(&rp);
        fprintf(R->err, "shellbench: out of memory\n");
        return -1;
    }
    /* an adaptive run: the mesh of the resume point, followed as after an
     * adaptation (sb_run_adapt.c), before the state of that mesh is taken */
    if (rp.has_mesh || sb_run_adapt_every(R) > 0) {
        int rc = SB_OK;
        if (!rp.has_mesh) {
            sb_escape_print(R->err, "shellbench: cannot resume from %s: it holds no mesh of the adaptive method %s (/resume/mesh_ints; "
                    "written by a build that did not keep it); move it away to start the run afresh", R->partial_path,
                    R->mt->name);
            rc = SB_ERR_INPUT;
        } else if (!sb_run_adapt_resumable(R)) {
            sb_escape_print(R->err, "shellbench: cannot resume from %s: it holds a mesh, which method %s cannot restore",
                    R->partial_path, R->mt->name);
            rc = SB_ERR_INPUT;
        } else if ((rc = R->mt->restore_mesh(R->ms, &rp.mesh)) != SB_OK) {
            sb_escape_print(R->err, "shellbench: cannot resume from %s: its mesh (/resume/mesh_ints): %s", R->partial_path,
                    R->ctx.err[0] ? R->ctx.err : "not restorable");
        } else if ((rc = sb_run_adapt_follow(R, 0)) != SB_OK) {
            sb_escape_print(R->err, "shellbench: resuming from %s: following the restored mesh failed: %s", R->partial_path,
                    R->ctx.err[0] ? R->ctx.err : "(no message)");
        } else if (rp.n_x != R->rec.n_x) {
            sb_escape_print(R->err, "shellbench: cannot resume from %s: /resume/x has %d dofs, its restored mesh %d",
                    R->partial_path, rp.n_x, R->rec.n_x);
            rc = SB_ERR_INPUT;
        }
        if (rc) {
            sb_resume_point_free(&rp);
            return -1;
        }
    }
    sb_copy(rp.n_x, rp.x, R->x);
    sb_copy(rp.n_x, rp.v, R->v);
    /* the method's triangles per step so far; a checkpoint without them gives a record without them */
    if (rec->mesh && sb_record_read_mesh_series(R->partial_path, rp.step + 1, rec->mesh, msg, sizeof msg)) {
        sb_mesh_series_free(rec->mesh);
        rec->mesh = NULL;
    }
    /* the time series so far; a checkpoint without it (older build) gives a
     * record without one */
    if (rec->sample_traj && sb_record_read_sample_traj(R->partial_path, rp.step, rec->n_samples, rec->sample_traj,
                                                       msg, sizeof msg)) {
        free(rec->sample_traj);
        rec->sample_traj = NULL;
    }
    rec->steps_done = rp.step;
    rec->reason = rp.step > 0 ? rp.stats.steps[rp.step - 1].reason : SB_REASON_NONE;
    if (rp.has_impulse) {   /* the counts go on from the boundary */
        rec->has_impulse = 1;
        rec->impulse = rp.impulse;
    }
    char item[32];
    snprintf(item, sizeof item, "%d", rp.step);
    rec->resumed = log;
    rec->resumed.count++;
    list_append(rec->resumed.steps, sizeof rec->resumed.steps, item);
    /* this process's set-up includes reading the checkpoint (and restoring
     * a mesh), so that no second of it is left unattributed (issue 42) */
    setup = sb_now() - R->t_start;
    rec->resumed.setup_seconds += setup;
    rec->resumed.lost_seconds += fmax(ck_seconds - rp.seconds, 0.0);
    if (strcmp(ck_build, rec->build_id) && !strstr(rec->resumed.builds, ck_build)) {
        list_append(rec->resumed.builds, sizeof rec->resumed.builds, ck_build);
        fprintf(R->err, "shellbench: warning: resuming a checkpoint of build %s with build %s (recorded in resume_builds)\n",
                ck_build, rec->build_id);
    }
    R->t_start -= rp.seconds;   /* seconds_total: the boundary's, then this process's */
    R->resumed = 1;
    for (int l = 0; l < SB_MAX_LEVELS; l++) R->analyze_at_resume[l] = st->ev[l][SB_EV_ANALYZE];
    /* iterations as `report` counts them: the steps' outer iterations (the
     * history also holds each step's iteration-0 record and coarse levels') */
    long its = 0;
    for (int i = 0; i < rp.step && (size_t)i < rp.stats.n_steps; i++) its += rp.stats.steps[i].iterations;
    if (!quiet)
        sb_escape_print(R->err, "shellbench: resuming %s after step %d of %d (%ld iterations done)", R->partial_path,
                rp.step, rec->steps_planned, its);
    sb_resume_point_free(&rp);
    sb_run_mark_boundary(R, rec->steps_done);
    return rec->steps_done;
}

void sb_run_fold_resume_setup(run_state *R)
{
    /* not after an adaptive mesh changed in this process: the analyses from
     * then on are the run's own (sb_run_adapt sets resume_folded) */
    if (!R->resumed || R->resume_folded) return;
    for (int l = 0; l < SB_MAX_LEVELS; l++) {
        sb_event_stat *ev = &R->ctx.stats.ev[l][SB_EV_ANALYZE];
        const sb_event_stat *b = &R->analyze_at_resume[l];
        if (b->count > 0 && ev->count > b->count) {
            R->rec.resumed.setup_seconds += ev->seconds - b->seconds;
            *ev = *b;
        }
    }
}
