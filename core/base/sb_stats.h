/* sb_stats.h — statistics of one run: events per level, work units, CHOLMOD
 * figures and per-iteration / per-step history.
 *
 * Counting is done only by the core wrappers (sb_problem_*, sb_linsolve_*),
 * never inside a method or solver plugin, so every method and solver is
 * measured the same way (PETSc-style events counted at one call site). */
#ifndef SB_STATS_H
#define SB_STATS_H

#include "sb_common.h"

typedef enum {
    SB_EV_ENERGY = 0,   /* energy-only evaluation                     */
    SB_EV_GRADIENT,     /* energy + gradient                           */
    SB_EV_HESSIAN,      /* energy + gradient + Hessian (an "assembly") */
    SB_EV_ANALYZE,      /* symbolic factorization (once per pattern)   */
    SB_EV_FACTORIZE,    /* numeric factorization                       */
    SB_EV_SOLVE,        /* triangular solves                           */
    SB_EV_CG_ITER,      /* one Steihaug–Toint CG iteration             */
    SB_EV_QP,           /* one trust-region subproblem solve           */
    SB_EV_TRANSFER,     /* prolongation / restriction / projection     */
    SB_EV_ADAPT,
    SB_EV_COLLIDE,
    SB_EV_RECORD,       /* recording (harness overhead)                */
    SB_EV_GALERKIN,     /* Galerkin coarse Hessian I^T H I             */
    SB_EV_CHECKPOINT,   /* a checkpoint written (run.checkpoint, --stop-after-steps): how many
                           depends on wall-clock time and interruptions, unlike every other count */
    /* harness parts (issue 42), so that every second of seconds_total is attributed */
    SB_EV_SETUP,        /* set-up: scene, method, problem (pattern, symbolic analysis), solver, samples */
    SB_EV_SAMPLES,      /* probes, sample grid, the method's triangles, material state, validation */
    SB_EV_ERROR,        /* error against the scene's reference */
    SB_EV_PROGRESS,     /* the live progress line */
    SB_EV_SOLVER,       /* a step's own work outside every other event: the outer solver's vector
                           operations, line searches and bookkeeping, the step's set-up (one per step) */
    SB_EV_COUNT
} sb_event;

const char *sb_event_name(sb_event e);

typedef struct sb_event_stat {
    long count;
    double seconds;      /* inclusive: wall time between the event's start and end */
    double self;         /* exclusive: seconds minus the events timed inside it (sb_stats_begin) */
} sb_event_stat;

/* Open events (sb_stats_begin) nest at most this deep; deeper ones are
 * timed as leaves. */
#define SB_STATS_DEPTH 16

/* One outer iteration (TR iteration, V-cycle, Newton iteration). */
typedef struct sb_iter_record {
    int step;            /* time / load step */
    int iter;            /* iteration within the step */
    int level;           /* level the record refers to (finest for outer iterations) */
    double f;            /* objective after the iteration */
    double gnorm;        /* ||g|| after the iteration (free dofs) */
    double delta;        /* trust-region radius (0 when not applicable) */
    double rho;          /* TR ratio, or line-search step length */
    double step_norm;    /* ||x_{i} - x_{i-1}|| */
    double shift;        /* Hessian diagonal shift used (lsnewton) */
    int accepted;
    int linear_iters;    /* CG iterations (or 1 for a direct solve) */
    int reason;          /* sb_reason when the step ended here, else 0 */
    /* seconds of this iteration (issue 42; 0 for a step's iteration-0 record):
     * wall time, and the events' inclusive seconds inside it */
    double seconds;
    double seconds_assembly;   /* energy + gradient + hessian (contact terms included) */
    double seconds_analyze, seconds_factorize, seconds_solve;
    double seconds_contact;    /* collide */
    /* Krylov linear solves (solver.linear = pcg-*, docs/solvers.md): the
     * relative tolerance asked of the solve (the Eisenstat–Walker forcing
     * term, or the fixed cg_rtol; 0 for a direct solve) and how it ended
     * (sb_krylov_status: 0 converged or direct, 1 iteration cap, 2 negative
     * curvature, 3 trust-region boundary; + 4 when a shift was needed) */
    double krylov_rtol;
    int krylov_status;
} sb_iter_record;

/* One time / load step. */
typedef struct sb_step_record {
    int step;
    double t;
    int iterations;
    int reason;          /* sb_reason */
    double f;
    double gnorm;
    double seconds;
    double work_assembly;/* work units spent in this step */
    double work_qp;
    double force_scale;  /* run.stop=scaled: the step's force scale (sb_solve.h), NaN otherwise */
    double gstop;        /* the gradient threshold the step's stopping rule used */
    double gnoise;       /* the computed gradient's rounding level the Krylov forcing measured (0: none) */
    int dofs;            /* dofs of the finest level in this step (adaptive meshes change it) */
    int triangles;       /* triangles of the method's own surface in this step (triangle methods:
                            linear_fem, adaptive_sqrt3); 0 for methods whose surface is not triangles */
    /* issue 42: the step's exclusive event seconds (sb_event_stat.self) by
     * part, from its start to the end of its recording, and the process's
     * peak resident memory at its end */
    double seconds_assembly;   /* energy + gradient + hessian */
    double seconds_analyze, seconds_factorize, seconds_solve;
    double seconds_contact, seconds_adapt, seconds_record, seconds_checkpoint;
    double peak_rss;           /* bytes (VmHWM) */
} sb_step_record;

typedef struct sb_stats {
    int n_levels;
    long n_dofs[SB_MAX_LEVELS];
    sb_event_stat ev[SB_MAX_LEVELS][SB_EV_COUNT];
    /* work units, RMTR paper Eq. (7.3): a call on level l costs n^l / n^L */
    double work_assembly;
    double work_qp;
    /* CHOLMOD per level: flops of one numeric factorization, nnz(L) */
    double chol_flops[SB_MAX_LEVELS];
    double chol_nnz_l[SB_MAX_LEVELS];
    long matrix_nnz[SB_MAX_LEVELS];   /* stored entries of the upper triangle */
    long not_posdef;                  /* factorizations that met an indefinite matrix */
    /* CHOLMOD per numeric factorization (issue 42): flops and nnz(L) of the
     * analysis summed over the level's factorizations, and the stored
     * entries (supernodal: with the zeros supernodes keep) of the last one */
    double chol_flops_sum[SB_MAX_LEVELS];
    double chol_nnz_l_sum[SB_MAX_LEVELS];
    double chol_factor_entries[SB_MAX_LEVELS];
    /* process CPU seconds inside the level's numeric factorizations
     * (CLOCK_PROCESS_CPUTIME_ID, every thread of the process): with
     * chol_flops_sum the achieved rate per CPU second, which other processes
     * on the machine do not change the way they change wall seconds (format 4) */
    double chol_factorize_cpu[SB_MAX_LEVELS];
    /* the first numeric factorization after each symbolic analysis, apart
     * (format 5): its CPU seconds and flops.  In it CHOLMOD allocates the
     * factor's values and the kernel hands the pages over (first touch: on
     * this project's VM 1.7 s per GB on huge pages, docs/scaling.md), so the
     * factorizations' steady rate is (flops_sum - first_flops) / (cpu -
     * first_cpu) */
    double chol_first_cpu[SB_MAX_LEVELS];
    double chol_first_flops[SB_MAX_LEVELS];
    /* memory (issue 42), bytes: the run.max_memory estimate, the process's
     * peak resident size after set-up and at the end (VmHWM) */
    double mem_estimate, peak_rss_setup, peak_rss;
    double peak_rss_analyzed;         /* right after the last symbolic analysis (0: none) */
    /* VmHWM when the run began, before set-up: the process's own start
     * (about 20 MB) for `run` and for a sweep's child whose peak was reset
     * (sb_peak_rss_reset); the sweep's footprint when it was not, so that a
     * report can tell a run's own peak from an inherited one (issue 42) */
    double peak_rss_start;
    /* events open now (sb_stats_begin): start time and inclusive seconds of
     * the events closed inside each */
    int depth;
    double open_t0[SB_STATS_DEPTH], open_child[SB_STATS_DEPTH];
    /* history (growable; amortized allocation, never per inner iteration) */
    sb_iter_record *iters; size_t n_iters, cap_iters;
    sb_step_record *steps; size_t n_steps, cap_steps;
    double seconds_total;
} sb_stats;

void sb_stats_init(sb_stats *s);
void sb_stats_free(sb_stats *s);
void sb_stats_reset(sb_stats *s);     /* keep dof counts, clear the rest */
int  sb_stats_push_iter(sb_stats *s, const sb_iter_record *r);
int  sb_stats_push_step(sb_stats *s, const sb_step_record *r);
/* Sum over levels of one event. */
sb_event_stat sb_stats_event_total(const sb_stats *s, sb_event e);

/* Monotonic clock in seconds (CLOCK_MONOTONIC). */
double sb_now(void);
/* CPU seconds of the whole process, every thread (CLOCK_PROCESS_CPUTIME_ID). */
double sb_cpu_now(void);

/* Timer helper used by the core wrappers:
 *   double t0 = sb_stats_begin(s); ...; sb_stats_event(s, level, SB_EV_X, t0);
 * An event begun with sb_stats_begin gets exclusive seconds (self): its
 * inclusive seconds minus those of the events closed inside it.  An event
 * timed from a plain sb_now() is a leaf (self = seconds) inside the
 * innermost open event.  An event begun and never closed (an error path)
 * is dropped when an enclosing one closes: its time stays the enclosing
 * event's own. */
double sb_stats_begin(sb_stats *s);
void sb_stats_event(sb_stats *s, int level, sb_event e, double t0);
/* Close every open event without counting it (top of a run's phase). */
void sb_stats_close_all(sb_stats *s);
/* Sum over levels of the exclusive seconds of one event. */
double sb_stats_self_total(const sb_stats *s, sb_event e);
/* The process's peak resident size in bytes (VmHWM of /proc/self/status,
 * else getrusage's ru_maxrss), 0 when unknown. */
double sb_peak_rss(void);
/* Start a new peak: the high-water mark VmHWM becomes the current resident
 * size (Linux >= 4.0, /proc/self/clear_refs "5").  A sweep's run is a forked
 * child, which starts with its parent's resident pages and peak (the plan
 * sets methods up at every size, up to 1.2 GB at 1e6 dofs): without this
 * its peak_rss is the parent's (issue 42).  0 on success, -1 when the
 * kernel does not allow it (the peak then includes the parent's). */
int sb_peak_rss_reset(void);
/* Give the heap's free pages back to the system (glibc malloc_trim), so that
 * a process that forks runs after a large transient set-up (the plan) does
 * not hand its freed but resident pages to every child.  No-op elsewhere. */
void sb_release_free_memory(void);

#endif
