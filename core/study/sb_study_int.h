/* sb_study_int.h — internal to core/study: the dof counts of methods at
 * given resolutions (sb_study_dofs.c). */
#ifndef SB_STUDY_INT_H
#define SB_STUDY_INT_H

#include "sb_run.h"
#include "sb_study.h"

#include <sys/types.h>

/* Set-ups already done: (scene, method, levels, res) -> dofs or refusal. */
typedef struct sb_dofs_entry {
    int scene, method, levels, res;
    long dofs;                /* 0: refused */
    char why[1400];
} sb_dofs_entry;

typedef struct sb_dofs_cache {
    int n, cap;
    sb_dofs_entry *e;
} sb_dofs_cache;

void sb_dofs_cache_init(sb_dofs_cache *c);
void sb_dofs_cache_free(sb_dofs_cache *c);

/* Dofs of method m on scene i at resolution res with `levels` levels (the
 * finest level), by setting the method up with the study's method.*
 * parameters.  0 with *dofs; 1 when the method refuses (why: its sentence);
 * < 0 on an internal error (why). */
int sb_study_dofs_at(const sb_study *st, sb_dofs_cache *c, int i, int m, int levels, int res, long *dofs,
                     char *why, size_t len);
/* The accepted resolution whose dof count is nearest to `target` in ratio
 * (|log(dofs/target)| smallest; ties to the smaller).  1 when no resolution
 * up to 4096 is accepted near it (why). */
int sb_study_res_for_dofs(const sb_study *st, sb_dofs_cache *c, int i, int m, int levels, long target, int *res,
                          long *dofs, char *why, size_t len);

int sb_study_n_variants(const sb_study *st);
/* Whether solver s can run method m at all; why when not (may be NULL). */
int sb_study_applicable(const sb_study *st, int m, int s, char *why, size_t len);
/* Whether rule k matches scene i, method m, solver s (-1 = any of them). */
int sb_study_rule_matches(const sb_study *st, int k, int i, int m, int s);

/* ---- sweep (sb_study_sweep.c) ------------------------------------------ */
/* SB_OK when the record at r->out is the planned run's: the same scene
 * (name and problem), method, solver, resolution and levels; else an error
 * with one sentence naming the file and the first difference
 * (sb_study_records.c). */
int sb_study_record_check(const sb_study *st, const sb_plan_run *r, char *why, size_t len);
/* 1 when the run has a record or a refusal marker already. */
int sb_study_run_done(const sb_plan_run *r);
/* Run plan->runs[queue[0..nq)] in child processes, o->jobs at a time;
 * *failed counts internal errors.  Returns 0 or an exit code. */
int sb_study_run_queue(const sb_study *st, const sb_plan *plan, const int *queue, int nq, const sb_sweep_options *o,
                       FILE *out, FILE *err, int *failed);
/* One run in a child process (messages into OUT.log); the child's pid, or -1. */
/* Before the first run: every record of the queue, its log, refusal note
 * and lock file can be written (new or regular files, not symbolic links,
 * in a directory that is writable or can be made).  0, or -1 with a
 * sentence on err (sb_study_sweep.c; also the MPI scheduler's). */
int sb_study_check_outputs(const sb_plan *plan, const int *queue, int nq, FILE *err);
pid_t sb_study_start_child(const sb_study *st, const sb_plan_run *r, FILE *err);
/* What a finished child (exit code) leaves: OUT.refused for a refusal, its
 * log shown (and removed unless it failed); the outcome's word. */
const char *sb_study_finish_child(const sb_plan_run *r, int code, FILE *err);

/* ---- distributed sweeps (sb_sweep_order.c, sb_sweep_mpi.c, sb_sweep_slurm.c) ---- */
/* Sort queue[0..nq) by expected seconds, longest first (ties in plan
 * order): from the study's records of the same configuration at other
 * resolutions or starts, scaled by (dofs / recorded dofs)^1.5, else from
 * c dofs^1.5 with c the median over every record of the study (1e-5 s
 * without records).  expected (may be NULL) receives the estimates in the
 * new order. */
void sb_study_order_longest_first(const sb_study *st, const sb_plan *plan, int *queue, int nq, double *expected);
/* The sweep over MPI ranks (rank 0 schedules and runs too).  In the
 * ordinary binary (no MPI): exec BUILD/shellbench-mpi with `sweep` and the
 * command's arguments, or a sentence and SB_EXIT_INPUT when there is none. */
int  sb_study_sweep_mpi(const sb_study *st, const sb_sweep_options *o, int argc, char **argv, FILE *out, FILE *err);
/* The runnable runs of the plan, in plan order: task k of a job array is
 * runs[task[k]]; returns the count (task: plan->n entries). */
int  sb_study_tasks(const sb_plan *plan, int *task);
/* `--emit slurm`: an sbatch job-array script for the runs not yet recorded. */
int  sb_study_emit_slurm(const sb_study *st, const char *study_file, const char *path, FILE *out, FILE *err);
/* `--task K`: run task K (sb_study_tasks) unless recorded. */
int  sb_study_run_task(const sb_study *st, int task, FILE *out, FILE *err);

/* ---- dt stability (sb_study_dt.c) -------------------------------------- */
/* The scene of run r at its dt: written once as RECORDS/scenes/SCENE-dtX.json
 * (time.dt, time.steps and the ramps in seconds of the original); its path
 * into buf. */
int sb_study_dt_scene(const sb_study *st, const sb_plan_run *r, char *buf, size_t len, FILE *err);
int sb_study_dt_sweep(const sb_study *st, const sb_sweep_options *o, FILE *out, FILE *err);
int sb_study_dt_report(const sb_study *st, const sb_study_report_options *o, FILE *err);

#endif
