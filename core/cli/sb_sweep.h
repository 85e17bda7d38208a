/* sb_sweep.h — a sweep: the runs of scenes x methods x solvers x
 * resolutions x levels, planned and validated as a whole before the first
 * one starts (an empty list, an unknown name, a scene that does not parse,
 * a resolution out of range or too large for memory, a --set key a run does
 * not know, an output path that cannot be written: one sentence, exit 2,
 * nothing run).  Combinations that cannot work (rmtr without a hierarchy or
 * with one level) are left out of the plan and named.  `sweep` on the
 * command line and study files both go through sb_sweep_validate.
 * docs/cli.md "sweep". */
#ifndef SB_SWEEP_H
#define SB_SWEEP_H

#include "sb_common.h"

#include <stddef.h>

typedef struct sb_sweep_axes {
    int n_scenes;  const char *const *scenes;    /* bundled names or paths */
    int n_methods; const char *const *methods;
    int n_solvers; const char *const *solvers;
    int n_res;     const int *res;               /* 0: the scene's "resolution" */
    int n_levels;  const int *levels;
    int n_sets;    const char *const *sets;      /* "key=value" for every run */
    const char *dir;                             /* where the records go */
    int sample_n;                                /* 0: the run's default */
} sb_sweep_axes;

typedef struct sb_sweep_item {
    const char *scene;                 /* as given (name or path) */
    char scene_name[SB_NAME_LEN];      /* the scene file's "name": the record's */
    const char *method, *solver;
    int res;                           /* the resolution used (the scene's when 0 was given) */
    int levels;
    char out[1200];                    /* DIR/SCENE-METHOD-SOLVER-rRES-lLEVELS.h5 */
} sb_sweep_item;

typedef struct sb_sweep_plan {
    int n;
    sb_sweep_item *items;
    int n_left_out;                    /* impossible (method, solver, levels) combinations, named in left_out */
    char left_out[4096];               /* "method/solver lL: why; ..." */
} sb_sweep_plan;

/* The plan of the axes, every run validated; SB_OK, or SB_ERR_INPUT with
 * one sentence in err (the plan is then empty). */
int  sb_sweep_validate(const sb_sweep_axes *ax, sb_sweep_plan *plan, char *err, size_t errlen);
void sb_sweep_plan_free(sb_sweep_plan *plan);

#endif
