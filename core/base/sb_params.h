/* sb_params.h — declared, validated, recorded parameters.
 *
 * Every component (problem/stepper, solver, trust-region subproblem solver,
 * method) declares its parameters in a constant table.  A run collects the
 * tables of the components it uses into one sb_paramset, applies overrides
 * from the command line (`--set solver.eta1=0.2`) and writes every resolved
 * value into the run's record.  Unknown keys and out-of-range values are
 * input errors that name the key and what is wrong. */
#ifndef SB_PARAMS_H
#define SB_PARAMS_H

#include "sb_common.h"

typedef enum { SB_PARAM_REAL, SB_PARAM_INT, SB_PARAM_CHOICE } sb_param_kind;

typedef struct sb_param_def {
    const char *name;          /* without component prefix, e.g. "eta1" */
    sb_param_kind kind;
    double def;                /* default (for CHOICE: index into choices) */
    double lo, hi;             /* inclusive valid range (REAL/INT) */
    const char *const *choices;/* NULL-terminated names (CHOICE) */
    const char *help;          /* one line, with the paper reference */
} sb_param_def;
/* A table ends with an entry whose name is NULL. */

#define SB_PARAMSET_MAX 128

typedef struct sb_param_value {
    char key[SB_NAME_LEN];     /* "prefix.name" */
    const sb_param_def *def;
    double value;
    int overridden;            /* 1 when set by the user */
} sb_param_value;

typedef struct sb_paramset {
    int n;
    sb_param_value v[SB_PARAMSET_MAX];
} sb_paramset;

void sb_paramset_init(sb_paramset *ps);
/* Register a component's table under `prefix` ("solver", "trs", "method", "run"). */
int sb_paramset_add(sb_paramset *ps, const char *prefix, const sb_param_def *defs);
/* Apply "key=value"; on error writes a sentence into err (size errlen). */
int sb_paramset_set(sb_paramset *ps, const char *assignment, char *err, size_t errlen);
/* Look up a resolved value; aborts the lookup with SB_ERR_INTERNAL if the key
 * was never declared (a programming error, caught by tests). */
double sb_param(const sb_paramset *ps, const char *key);
int sb_param_int(const sb_paramset *ps, const char *key);
/* The value of key if ps (may be NULL) declares it, else def: for a
 * component that reads another's parameter and may run without it (a
 * method created by a test or a tool without the run's table: run.threads). */
int sb_param_int_or(const sb_paramset *ps, const char *key, int def);
/* Name of a CHOICE value. */
const char *sb_param_choice(const sb_paramset *ps, const char *key);
/* Formats a value for printing/recording ("0.1", "dogleg"). */
void sb_param_format(const sb_param_value *pv, char *buf, size_t len);

#endif
