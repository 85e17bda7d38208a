/* sb_study.h — studies: scenes x methods x solvers x resolutions x
 * parameters as one JSON file (docs/study.md), run by `shellbench sweep
 * --study FILE` and turned into work-precision diagrams, performance
 * profiles and a method-selection table by `shellbench report --study FILE`
 * (from the records only, never by re-running).
 *
 *   sb_study_load    parse and validate: every error FILE:LINE:COL, before any run
 *   sb_study_plan    the runs: per scene and method the resolution nearest each dofs target
 *   sb_study_sweep   run what is not recorded yet (resumable), refusals recorded
 *   sb_study_report  the Markdown report and its figures
 *
 * A study of kind "dt_stability" (RMTR paper Fig. 10) is planned one
 * bisection over dt at a time: sb_study_dt.c. */
#ifndef SB_STUDY_H
#define SB_STUDY_H

#include "sb_method.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <stdio.h>

#define SB_STUDY_MAX_SCENES 32
#define SB_STUDY_MAX_METHODS 16
#define SB_STUDY_MAX_SOLVERS 16
#define SB_STUDY_MAX_RES 12
#define SB_STUDY_MAX_SETS 24
#define SB_STUDY_MAX_SEEDS 16
#define SB_STUDY_MAX_TARGETS 6
#define SB_STUDY_MAX_RULES 64
#define SB_STUDY_MAX_VARY 4       /* varied parameters */
#define SB_STUDY_MAX_VALUES 8     /* values per varied parameter */
#define SB_STUDY_SET_LEN 320

typedef enum { SB_STUDY_ACCURACY, SB_STUDY_DT_STABILITY } sb_study_kind;
typedef enum { SB_SOLUTION_UNIQUE, SB_SOLUTION_MULTIPLE } sb_solution_kind;
/* the error a scene is ranked by */
typedef enum { SB_ERRKIND_PROBE, SB_ERRKIND_FIELD_RMS, SB_ERRKIND_FIELD_MAX, SB_ERRKIND_NONE } sb_error_kind;

/* "key=value" assignments with the JSON pointer each came from */
typedef struct sb_study_sets {
    int n;
    char kv[SB_STUDY_MAX_SETS][SB_STUDY_SET_LEN];
} sb_study_sets;

typedef struct sb_study_scene {
    char name[SB_NAME_LEN];          /* the scene's name */
    char arg[512];                   /* as written in the study (name or path) */
    char path[512];                  /* resolved scene file */
    sb_scene *scene;                 /* loaded (owned) */
    sb_solution_kind solution;
    sb_error_kind error;             /* what the diagrams rank by */
    char reference[1024];            /* reference record path ("" = none / analytic probes) */
    double perturb;                  /* multiple: run.perturb of the extra starts */
    int n_seeds;
    long seeds[SB_STUDY_MAX_SEEDS];  /* multiple: one extra start per seed */
} sb_study_scene;

typedef struct sb_study_method {
    char name[SB_NAME_LEN];
    const sb_method_type *type;
    sb_study_sets sets;
} sb_study_method;

typedef struct sb_study_solver {
    char name[SB_NAME_LEN];
    const sb_solver_type *type;
    int levels;
    char linear[SB_NAME_LEN];   /* "linear": solver.linear of this entry ("" none: the
                                   study's, default cholmod); part of its label and records' names */
    sb_study_sets sets;
} sb_study_solver;

/* A rule applies to the runs it matches (-1 = any): extra parameters, its
 * own resolutions / dofs targets, or "skip" with the reason. */
typedef struct sb_study_rule {
    int scene, method, solver;
    long levels;                      /* > 0: only solver entries with this level count */
    sb_study_sets sets;
    int n_res;                        /* > 0: own resolutions */
    long res[SB_STUDY_MAX_RES];
    int n_dofs;                       /* > 0: own dofs targets */
    long dofs[SB_STUDY_MAX_RES];
    char skip[256];                   /* non-empty: not run, with this reason */
} sb_study_rule;

/* dt_stability: bisection over dt in log scale (RMTR paper Fig. 10) */
typedef struct sb_study_dt {
    double dt_max, dt_min;           /* the cap (paper: 1 s) and the smallest dt tried */
    double descent;                  /* after a failure at dt_max: probe dt_max / descent^k down to dt_min
                                        until one converges (default dt_max / dt_min: dt_min at once) */
    int bisections;                  /* halvings of the log-interval after the first failure */
    int steps;                       /* time steps of every run (the horizon is steps * dt) */
    int max_iter;                    /* iteration cap per step */
} sb_study_dt;

typedef struct sb_study {
    char name[SB_NAME_LEN];
    char description[1024];
    char path[512];                  /* the study file */
    sb_study_kind kind;
    char records[512];               /* directory of the records */
    int samples;                     /* sample grid per side */
    int n_targets;
    double targets[SB_STUDY_MAX_TARGETS];
    int n_scenes, n_methods, n_solvers, n_rules;
    sb_study_scene scenes[SB_STUDY_MAX_SCENES];
    sb_study_method methods[SB_STUDY_MAX_METHODS];
    sb_study_solver solvers[SB_STUDY_MAX_SOLVERS];
    sb_study_rule rules[SB_STUDY_MAX_RULES];
    int n_res, n_dofs;               /* exactly one of them > 0 */
    long res[SB_STUDY_MAX_RES], dofs[SB_STUDY_MAX_RES];
    sb_study_sets sets;              /* every run */
    /* varied parameters: every combination is a configuration of its own */
    int n_vary;
    char vary_key[SB_STUDY_MAX_VARY][SB_NAME_LEN];
    int n_values[SB_STUDY_MAX_VARY];
    char vary_value[SB_STUDY_MAX_VARY][SB_STUDY_MAX_VALUES][SB_NAME_LEN];
    sb_study_dt dt;
    int allow_unsealed_reference;    /* --allow-unsealed-reference: the scenes' references may lack a checksum
                                        (set by the command line after sb_study_load; docs/trust.md) */
} sb_study;

/* Parse and validate the study file.  Errors: "FILE:LINE:COL: at /ptr: what"
 * (SB_ERR_INPUT), nothing run.  records_override (may be NULL) replaces the
 * file's "records" directory.  The study is large: allocate it. */
int  sb_study_load(const char *path, const char *records_override, sb_study *st, char *err, size_t errlen);
int  sb_study_parse_string(const char *text, const char *file, const char *records_override, sb_study *st,
                           char *err, size_t errlen);
void sb_study_free(sb_study *st);

/* ---- the plan ------------------------------------------------------------ */

typedef enum {
    SB_PLAN_RUN = 0,          /* to run (or recorded) */
    SB_PLAN_SKIP,             /* a rule says skip */
    SB_PLAN_NOT_APPLICABLE,   /* solver needs what the method lacks */
    SB_PLAN_REFUSED           /* the method refused the scene at set-up */
} sb_plan_state;

typedef struct sb_plan_run {
    int scene, method, solver, variant;
    int res, levels;
    long dofs;                /* at this resolution (0 when refused) */
    int start;                /* 0 = the unperturbed start, k > 0 = seeds[k-1] */
    double dt;                /* dt_stability: the step; 0 = the scene's */
    sb_plan_state state;
    char why[512];            /* skip / not applicable / refused: one sentence */
    char out[1024];           /* record path */
    int n_sets;
    char sets[2 * SB_STUDY_MAX_SETS + SB_STUDY_MAX_VARY + 8][SB_STUDY_SET_LEN];
} sb_plan_run;

typedef struct sb_plan {
    int n, cap;
    sb_plan_run *runs;
    int n_variants;
} sb_plan;

/* Expand the study into runs (accuracy studies; a dt study's first probes).
 * Resolutions for dofs targets are found by setting up the method (no run).
 * Returns SB_OK, or an error with a sentence. */
int  sb_study_plan(const sb_study *st, sb_plan *plan, char *err, size_t errlen);
void sb_plan_free(sb_plan *plan);
/* The configuration label of a run: "tr", "rmtr L2", "tr eta1=0.25" */
void sb_plan_config_label(const sb_study *st, const sb_plan_run *r, char *buf, size_t len);
/* Fill out[] and sets[] of a run from its indices (used by the dt study). */
int  sb_plan_finish_run(const sb_study *st, sb_plan_run *r, char *err, size_t errlen);
/* The refusal marker next to a record: OUT.refused (one sentence). */
void sb_plan_refused_path(const char *out, char *buf, size_t len);

/* ---- sweep ----------------------------------------------------------------- */

typedef struct sb_sweep_options {
    int jobs;                 /* processes at once (>= 1) */
    int max_runs;             /* > 0: stop after this many new runs (resumable) */
    int quiet;
} sb_sweep_options;

/* Run every planned run without a record or refusal marker.  Returns 0 when
 * everything is recorded, 4 when stopped by max_runs, 2/3 on errors. */
int sb_study_sweep(const sb_study *st, const sb_sweep_options *o, FILE *out, FILE *err);
/* One planned run, in this process: the exit code of sb_run_execute;
 * its messages go to err. */
int sb_study_run_one(const sb_study *st, const sb_plan_run *r, FILE *err);

/* ---- report ---------------------------------------------------------------- */

typedef struct sb_study_report_options {
    const char *out_dir;      /* report.md and figures; NULL = the records directory */
    const char *gnuplot;      /* NULL: $SB_GNUPLOT or "gnuplot" */
    int deterministic;        /* leave out wall-clock figures and the machine: the same records
                                 give the same bytes (nightly comparisons, the resume test) */
} sb_study_report_options;

int sb_study_report(const sb_study *st, const sb_study_report_options *o, FILE *err);

/* ---- the CLI commands (core/cli/main.c dispatches to them) ------------------- */
int sb_study_cmd_sweep(int argc, char **argv);
int sb_study_cmd_report(int argc, char **argv);
int sb_study_cmd_reference(int argc, char **argv);
/* 1 when this process was started by an MPI launcher (mpirun, srun):
 * sb_sweep_order.c; a study sweep is then distributed (docs/regression.md). */
int sb_mpi_launched(void);

#endif
