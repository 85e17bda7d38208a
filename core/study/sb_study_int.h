/* sb_study_int.h — internal to core/study: the dof counts of methods at
 * given resolutions (sb_study_dofs.c). */
#ifndef SB_STUDY_INT_H
#define SB_STUDY_INT_H

#include "sb_run.h"
#include "sb_study.h"

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
/* 1 when the run has a record or a refusal marker already. */
int sb_study_run_done(const sb_plan_run *r);
/* Run plan->runs[queue[0..nq)] in child processes, o->jobs at a time;
 * *failed counts internal errors.  Returns 0 or an exit code. */
int sb_study_run_queue(const sb_study *st, const sb_plan *plan, const int *queue, int nq, const sb_sweep_options *o,
                       FILE *out, FILE *err, int *failed);

/* ---- dt stability (sb_study_dt.c) -------------------------------------- */
/* The scene of run r at its dt: written once as RECORDS/scenes/SCENE-dtX.json
 * (time.dt, time.steps and the ramps in seconds of the original); its path
 * into buf. */
int sb_study_dt_scene(const sb_study *st, const sb_plan_run *r, char *buf, size_t len, FILE *err);
int sb_study_dt_sweep(const sb_study *st, const sb_sweep_options *o, FILE *out, FILE *err);
int sb_study_dt_report(const sb_study *st, const sb_study_report_options *o, FILE *err);

#endif
