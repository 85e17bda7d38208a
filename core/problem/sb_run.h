/* sb_run.h — one run: scene -> method -> problem -> solver -> record.  The
 * CLI's `run` command is a thin wrapper; tests call this directly, so every
 * solver is exercised through exactly the code path of `shellbench run`. */
#ifndef SB_RUN_H
#define SB_RUN_H

#include "sb_method.h"

#include <stdio.h>

struct sb_solver_type;

typedef struct sb_run_request {
    const char *scene;        /* name or path */
    const char *method;
    const char *solver;
    int res;                  /* 0 = scene/method default; elements along s (or both) */
    int res_t;                /* elements along t (--res NxM); 0 = as res */
    int levels;               /* 0 = 1 */
    const char *out;          /* HDF5 path; NULL = results/runs/<auto>.h5; "none" = no file */
    int summary_json;         /* print the JSON summary on `out_stream` */
    int n_sets;
    const char *const *sets;  /* "key=value" overrides */
    int quiet;                /* no progress lines */
    int sample_n;             /* sample grid per side (0 = 21, else 2..SB_RUN_MAX_SAMPLES) */
    int resume;               /* continue from the last step boundary of OUT.partial */
    int stop_after_steps;     /* > 0: stop after this step with a checkpoint (exit SB_EXIT_STOPPED) */
    int strict;               /* --strict: a converged run whose validation failed exits SB_EXIT_VALIDATION */
    int allow_unsealed_reference;   /* --allow-unsealed-reference: a reference file without a checksum is used */
    int makes_reference;      /* the run computes its scene's reference (`shellbench reference`): the scene's
                                 reference file is neither checked at the start nor a verdict at the end */
    /* a live progress line on err_stream (step, iteration, f, ||g||, radius or
     * step length, elapsed): 0 = when err_stream is a terminal and the run is
     * not quiet, 1 = always (--progress; plain lines, one a second, off a
     * terminal), -1 = never */
    int progress;
    const char *progress_prefix;   /* shown before the line (a sweep's "[3/12, ~2 min left]"), or NULL */
} sb_run_request;

/* --samples: the sample grid per side is 2 to this */
#define SB_RUN_MAX_SAMPLES 2001

/* Exit codes of the CLI contract. */
enum { SB_EXIT_CONVERGED = 0, SB_EXIT_NOT_CONVERGED = 1, SB_EXIT_INPUT = 2, SB_EXIT_INTERNAL = 3,
       SB_EXIT_STOPPED = 4, /* --stop-after-steps: stopped with a resumable checkpoint */
       SB_EXIT_VALIDATION = 5 /* --strict: converged, but an expected probe value is out of tolerance */ };

/* Whether method, solver and level count fit together: SB_OK, or
 * SB_ERR_UNSUPPORTED / SB_ERR_INPUT with a sentence (sb_run_check.c). */
int sb_run_combination_check(const sb_method_type *mt, const struct sb_solver_type *st, int levels, char *err,
                             size_t errlen);
/* The run's parameters: run.*, solver.* and method.* declared, then the
 * "key=value" overrides applied; SB_OK or an error with a sentence. */
/* The scene's "methods" section against the registry: known methods, their
 * own parameters, valid values; SB_OK or SB_ERR_INPUT naming the scene file. */
int sb_run_scene_methods_check(const sb_scene *sc, char *err, size_t errlen);
/* what the scene asks of this method that only some methods honour (a moving
 * bc's "derivative"): SB_OK or SB_ERR_UNSUPPORTED with the sentence */
int sb_run_scene_method_check(const sb_scene *sc, const sb_method_type *mt, char *err, size_t errlen);
int sb_run_paramset(sb_paramset *ps, const sb_method_type *mt, const struct sb_solver_type *st, int n_sets,
                    const char *const *sets, char *err, size_t errlen);

/* Executes the run; returns the exit code.  Messages go to err_stream,
 * the JSON summary (if asked) to out_stream.  When summary is non-NULL it
 * receives the JSON text (caller frees). */
int sb_run_execute(const sb_run_request *req, FILE *out_stream, FILE *err_stream, char **summary);

/* The exit code of a finished run read back from its record (a run that
 * `--resume` finds recorded, a sweep's skipped run): SB_EXIT_CONVERGED or
 * SB_EXIT_NOT_CONVERGED from the recorded status, SB_EXIT_VALIDATION when
 * strict and the recorded validation (sb_record_summary.validation) is
 * "failed" -- the code the original run exited with (sb_run_judge.c). */
int sb_run_recorded_exit(int status, const char *validation, int strict);

/* --res: "N" (N x N elements) or "NxM" (N along s, M along t; 'x', 'X' or
 * the UTF-8 multiplication sign), each a positive integer at most 1000000
 * ("0" alone: the scene's default).  0 or -1 for a malformed value. */
int sb_run_parse_res(const char *text, int *res, int *res_t);

#endif
