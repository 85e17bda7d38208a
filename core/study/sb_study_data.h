/* sb_study_data.h — a study's records read back for its report: one point
 * per planned run, with its cost, its errors against the scene's reference
 * (computed here from the recorded samples, so a reference made after the
 * runs serves as well) and its energy; and the analysis on top of them
 * (sb_study_wp.c: Pareto fronts, cost to reach an error target, performance
 * profiles, selection). */
#ifndef SB_STUDY_DATA_H
#define SB_STUDY_DATA_H

#include "sb_reference.h"
#include "sb_study_int.h"

typedef enum {
    SB_POINT_RECORDED,        /* a record (converged or not: see status) */
    SB_POINT_REFUSED,         /* refused at set-up (plan) or at run time (OUT.refused) */
    SB_POINT_MISSING,         /* not run yet (or failed without a record) */
    SB_POINT_SKIPPED,         /* a rule skips it */
    SB_POINT_NOT_APPLICABLE
} sb_point_state;

typedef struct sb_study_point {
    int run;                  /* index into the plan */
    int config;               /* method x solver x variant: sb_study_config() */
    sb_point_state state;
    char why[512];
    int status;               /* record status: 0 converged, 1 not */
    char reason[32];
    long dofs;
    int steps, steps_planned, iterations;
    double seconds, work;     /* seconds_total, assembly work units (RMTR paper Eq. 7.3) */
    double err_probe;         /* analytic probes: max relative error; file reference: max probe distance / diameter */
    double err_rms, err_max;  /* field error against the reference record / diameter */
    double error;             /* the one the scene is ranked by (NaN: none) */
    double energy;            /* energy_final (J) */
    double below_reference;   /* share of the area below the reference state's energy (NaN: not recorded) */
    int n_samples;
    double *pos;              /* sampled final positions (owned; for distances between starts) */
    char build[64];
} sb_study_point;

typedef struct sb_study_data {
    const sb_study *st;
    sb_plan plan;
    sb_study_point *pt;       /* plan.n */
    int n_configs;
    /* per scene: its reference record (has_ref) or why there is none */
    int has_ref[SB_STUDY_MAX_SCENES];
    sb_refrec ref[SB_STUDY_MAX_SCENES];
    char ref_why[SB_STUDY_MAX_SCENES][1024];
    /* the reference's self-check (its provenance REF.json, shellbench
     * reference): field RMS / diameter against its run at half the
     * resolution; NaN when there is none */
    double ref_check[SB_STUDY_MAX_SCENES];
    double diameter[SB_STUDY_MAX_SCENES];
} sb_study_data;

/* config id of (method, solver, variant) */
int  sb_study_config(const sb_study *st, int n_variants, int m, int s, int v);
/* a point's cost: 0 seconds, 1 assembly work units */
double sb_point_cost(const sb_study_point *q, int cost);
/* "method/solver L2 key=value" of a config id */
void sb_study_config_label(const sb_study_data *d, int config, char *buf, size_t len);
/* The curve of configuration c on scene i: the recorded, converged runs of
 * the unperturbed start with a finite error and a positive cost, in
 * increasing dofs (ties: cost); point indices into idx (at most d->plan.n).
 * Returns their number. */
int  sb_study_curve(const sb_study_data *d, int i, int c, int cost, int *idx);

/* The cost for configuration c on scene i to reach the error target:
 * sb_wp_cost_to_reach on its curve (INFINITY: never).  *lo / *hi receive the
 * dofs of the bracketing runs (*lo = 0: reached at the coarsest run *hi),
 * *best the smallest error of the curve's finest run (NaN: no curve); any of
 * them may be NULL. */
double sb_study_reach(const sb_study_data *d, int i, int c, int cost, double target, long *lo, long *hi, double *best);
/* 1 when configuration c has a record on scene i */
int sb_study_has_record(const sb_study_data *d, int i, int c);

/* Plan the study and read its records (never runs anything).  Messages on
 * unreadable records go to err as warnings; SB_OK unless the plan fails. */
int  sb_study_data_load(const sb_study *st, sb_study_data *d, FILE *err);
void sb_study_data_free(sb_study_data *d);

/* ---- analysis (sb_study_wp.c): plain arrays, tested on hand-made data ---- */

/* on_front[i] = 1 when no other point has cost <= and error <= with one of
 * them strictly smaller (the Pareto front of "cheaper and more accurate");
 * points with a non-finite cost or error are never on it. */
void sb_wp_pareto(int n, const double *cost, const double *err, int *on_front);

/* The cost at which a curve (points in increasing resolution) reaches the
 * error target and stays below it: the first point from which every finer
 * point has err <= target.  Between that point and the one before, log-log
 * linear interpolation (log cost linear in log error); at the coarsest
 * point its cost (*at_first = 1: reached already there, the true cost may be
 * lower; nothing is extrapolated).  INFINITY when the finest point misses
 * the target.  *from receives the index of the first point below (-1). */
double sb_wp_cost_to_reach(int n, const double *cost, const double *err, double target, int *from, int *at_first);

/* Performance profile (Dolan & More 2002): t[p * ns + s] is the cost of
 * configuration s on problem p (INFINITY: not solved).  ratio[p * ns + s] =
 * t / min_s t (INFINITY when not solved or nobody solved p).  rho_s(tau) is
 * the share of the np problems with ratio <= tau. */
void   sb_profile_ratios(int np, int ns, const double *t, double *ratio);
double sb_profile_rho(int np, int ns, const double *ratio, int s, double tau);

/* Selection: the configurations sorted by cost (ascending, infinite last,
 * ties by index); returns how many have a finite cost. */
int sb_select_order(int n, const double *cost, int *order);

#endif
