/* sb_regress_int.h — internal to core/regress: running the suite
 * (sb_regress_run.c) for the command (core/cli/sb_cli_regress.c). */
#ifndef SB_REGRESS_INT_H
#define SB_REGRESS_INT_H

#include "sb_regress.h"
#include "sb_study.h"
#include "sb_output.h"

#define SB_REGRESS_MAX_SETS 16

struct rusage;

/* Where the measurement's times come from.  The command uses the real one
 * (sb_regress_clock_real: the calibration kernel, and each run's CPU time
 * from its process's rusage); the harness's own tests give known samples
 * instead, so that "same", "slower" and "faster" are decided on known data
 * rather than on the times of a shared machine (tests/test_regress.c). */
typedef struct sb_regress_clock {
    /* CPU seconds of one calibration pass (round `round`, from 0) */
    double (*calibrate)(void *ctx, int round);
    /* CPU seconds of a finished run of case `id`, repeat `rep` (from 0);
     * ru is its process's resource usage */
    double (*run_seconds)(void *ctx, const char *id, int rep, const struct rusage *ru);
    void *ctx;
} sb_regress_clock;

/* The real clock (no context). */
const sb_regress_clock *sb_regress_clock_real(void);

typedef struct sb_regress_run_options {
    int repeat;               /* rounds (k samples per case) */
    int jobs;                 /* runs at once */
    int quiet;
    int n_sets;               /* extra parameters of every run (--set) */
    const char *sets[SB_REGRESS_MAX_SETS];
    int n_only;               /* > 0: only the cases with these ids (a confirmation) */
    const char *const *only;
    const sb_regress_clock *clock; /* NULL: sb_regress_clock_real() */
} sb_regress_run_options;

/* Run every case of the suite `repeat` times (plus one calibration pass per
 * round) into now (empty on entry).  Returns 0, SB_EXIT_INPUT when the plan
 * or a run is refused as input (a message on err), SB_EXIT_INTERNAL. */
int sb_regress_measure(const sb_study *st, const sb_regress_run_options *o, sb_regress_set *now, FILE *out, FILE *err);

/* Before any run: the suite's records directory can be written, every
 * history plot and picture the report will draw into dir and every record
 * RECORDS/repK/ID (K = 1..repeat) is a new path or a regular file (not a
 * symbolic link, FIFO, directory: sb_output_check), and no lock file there
 * is anything but a regular file; then the invocation takes the lock
 * RECORDS.lock (one invocation at a time on these records) and removes the
 * lock files a killed invocation's runs left under RECORDS (a live
 * writer's is an error).  SB_OK with *lock held (release it at the end),
 * or SB_ERR_INPUT with a sentence. */
int sb_regress_prepare_outputs(const sb_study *st, int repeat, const char *dir, sb_output_lock *lock, char *err,
                               size_t errlen);

/* A timing verdict (slower, faster) of now is confirmed by measuring the
 * case again (o->repeat fresh repeats with their own calibration) and
 * judging the new samples against base: it stands only when both
 * measurements agree, else the case is "same" (a passing disturbance must
 * strike twice).  The cases keep the confirming samples; *regressions is
 * updated.  Returns what sb_regress_measure returns. */
int sb_regress_confirm(const sb_study *st, const sb_regress_run_options *o, sb_regress_set *now,
                       const sb_regress_set *base, const sb_regress_rules *rules, int *regressions, FILE *out,
                       FILE *err);

#endif
