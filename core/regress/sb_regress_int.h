/* sb_regress_int.h — internal to core/regress: running the suite
 * (sb_regress_run.c) for the command (core/cli/sb_cli_regress.c). */
#ifndef SB_REGRESS_INT_H
#define SB_REGRESS_INT_H

#include "sb_regress.h"
#include "sb_study.h"

#define SB_REGRESS_MAX_SETS 16

typedef struct sb_regress_run_options {
    int repeat;               /* rounds (k samples per case) */
    int jobs;                 /* runs at once */
    int quiet;
    int n_sets;               /* extra parameters of every run (--set) */
    const char *sets[SB_REGRESS_MAX_SETS];
    int n_only;               /* > 0: only the cases with these ids (a confirmation) */
    const char *const *only;
} sb_regress_run_options;

/* Run every case of the suite `repeat` times (plus one calibration pass per
 * round) into now (empty on entry).  Returns 0, SB_EXIT_INPUT when the plan
 * or a run is refused as input (a message on err), SB_EXIT_INTERNAL. */
int sb_regress_measure(const sb_study *st, const sb_regress_run_options *o, sb_regress_set *now, FILE *out, FILE *err);

#endif
