/* sb_regress.h — nightly performance regression (docs/regression.md):
 * `shellbench regress` / `make nightly` runs a fixed suite (a study file,
 * bench/nightly/nightly.json) k times, compares every case with a committed
 * baseline (bench/nightly/baseline.json) and gives one verdict per case and
 * an exit code a CI job can act on (0 no regression, 1 regression, 2 input
 * error).
 *
 *   sb_regress_figures   the deterministic figures of one record (counts,
 *                        work units, CHOLMOD nnz and flops, status, energy,
 *                        probes): sb_regress_figures.c
 *   sb_regress_calibrate a fixed amount of work independent of the suite's
 *                        code, timed in the same invocation: sb_regress_calib.c
 *   sb_regress_mwu       Mann-Whitney U test: sb_regress_stats.c
 *   sb_regress_judge     one verdict per case: sb_regress_judge.c
 *   baseline and history files (JSON, CSV): sb_regress_files.c
 *   the runs: sb_regress_run.c; the report (Markdown, PNG): sb_regress_report.c
 */
#ifndef SB_REGRESS_H
#define SB_REGRESS_H

#include "sb_common.h"

#include <stdio.h>

#define SB_REGRESS_MAX_REPEAT 64
#define SB_REGRESS_MAX_PROBES 16
#define SB_REGRESS_ID_LEN 256

/* Deterministic figures of one run: reproducible bit for bit by the same
 * build with the pinned BLAS kernel set (docs/reproducibility.md). */
enum {
    SB_RF_STEPS = 0,       /* steps done */
    SB_RF_ITERATIONS,      /* outer iterations over all steps */
    SB_RF_DOFS,            /* finest-level dofs */
    SB_RF_ENERGY_CALLS,    /* calls of the energy, gradient and Hessian events, all levels */
    SB_RF_GRADIENT_CALLS,
    SB_RF_HESSIAN_CALLS,
    SB_RF_FACTORIZE_CALLS,
    SB_RF_SOLVE_CALLS,
    SB_RF_CG_ITERS,
    SB_RF_COUNT_INT
};
enum {
    SB_RF_WORK_ASSEMBLY = 0, /* RMTR paper Eq. (7.3) */
    SB_RF_WORK_QP,
    SB_RF_CHOL_NNZ,        /* nnz(L), summed over levels */
    SB_RF_CHOL_FLOPS,      /* flops of one factorization, summed over levels */
    SB_RF_MATRIX_NNZ,      /* stored Hessian entries, summed over levels */
    SB_RF_COUNT_EXACT      /* compared exactly (whole numbers or sums of n^l/n^L) */
};

typedef struct sb_regress_figures {
    int status;                          /* record status: 0 converged, 1 not converged */
    char reason[32];                     /* stop reason of the last step */
    long n[SB_RF_COUNT_INT];
    double x[SB_RF_COUNT_EXACT];
    int has_energy;
    double energy;                       /* energy_final, J: within rtol (round-off enters) */
    int n_probes;
    double probe[SB_REGRESS_MAX_PROBES][3]; /* final probe positions, m: within rtol */
} sb_regress_figures;

const char *sb_regress_int_name(int k);     /* "iterations", ... */
const char *sb_regress_exact_name(int k);   /* "work_assembly", ... */

/* Read a record's figures: SB_OK or an error with a sentence naming the file. */
int sb_regress_figures_read(const char *path, sb_regress_figures *f, char *err, size_t errlen);
/* First difference of b against a (the baseline) into what (empty when the
 * figures agree: integers, status and reason exactly, work units, nnz and
 * flops to 1e-12 relative, energy and probes to rtol); returns 1 when they differ. */
int sb_regress_figures_differ(const sb_regress_figures *a, const sb_regress_figures *b, double rtol, char *what,
                              size_t len);

/* ---- timing ------------------------------------------------------------- */

/* CPU seconds of one pass of the calibration kernel: a fixed amount of
 * floating-point and memory work written here, independent of the suite's
 * code, so that a regression of the suite is not normalized away. */
double sb_regress_calibrate(void);
/* Bumped whenever the kernel's work changes: normalized times of baselines
 * made with another version are not compared (1: until 83601fa, the data
 * allocated inside the timed region). */
#define SB_REGRESS_CALIB_VERSION 2

/* Mann-Whitney U test of x (n) against y (m): U of x, two-sided p-value
 * (exact distribution without ties for n, m <= 50 and no ties; else the
 * normal approximation with tie and continuity corrections, gsl_cdf). */
typedef struct sb_mwu {
    double u;        /* U statistic of x: pairs (x_i, y_j) with x_i > y_j, ties 1/2 */
    double p;        /* two-sided */
    int exact;       /* 1: exact distribution */
} sb_mwu;
int sb_regress_mwu(const double *x, int n, const double *y, int m, sb_mwu *r);

/* ---- one case ------------------------------------------------------------ */

typedef enum {
    SB_VERDICT_SAME = 0,
    SB_VERDICT_FASTER,
    SB_VERDICT_SLOWER,     /* regression */
    SB_VERDICT_CHANGED,    /* deterministic figures differ: regression until the baseline is updated */
    SB_VERDICT_FAILED,     /* no record (internal error, crash): regression */
    SB_VERDICT_NEW,        /* not in the baseline */
    SB_VERDICT_COUNT
} sb_verdict;
const char *sb_verdict_name(sb_verdict v);
int sb_verdict_is_regression(sb_verdict v);

typedef struct sb_regress_case {
    char id[SB_REGRESS_ID_LEN];          /* the record's path under the suite's records dir */
    int ok;                              /* figures read (at least one repeat recorded) */
    int crashed;                         /* a repeat left no readable record */
    char failure[512];                   /* why (crashed), or the repeats' disagreement */
    sb_regress_figures fig;
    int n_rep;
    double cpu[SB_REGRESS_MAX_REPEAT];   /* CPU seconds of each repeat (rusage of its process) */
    double wall[SB_REGRESS_MAX_REPEAT];  /* the record's seconds_total */
    double norm[SB_REGRESS_MAX_REPEAT];  /* cpu / calibration median */
    /* judged */
    sb_verdict verdict;
    double ratio;                        /* median norm now / baseline */
    double p;                            /* Mann-Whitney two-sided p */
    char detail[512];
} sb_regress_case;

/* Provenance of a set of measurements (baseline or this invocation). */
typedef struct sb_regress_prov {
    char build[64], date[32], host[128], cpu[128], blas_core[64], suite[512];
    int repeat;
    double calib[SB_REGRESS_MAX_REPEAT]; /* CPU seconds of each calibration pass */
    int n_calib;
    double calib_median;
    double load_max;                     /* largest 1-minute load average seen at the start of a round
                                            (/proc/loadavg; NaN: not known) */
    int cores;                           /* online processors */
    int calib_version;                   /* SB_REGRESS_CALIB_VERSION of the kernel used */
} sb_regress_prov;

typedef struct sb_regress_set {
    sb_regress_prov prov;
    int n, cap;
    sb_regress_case *c;
} sb_regress_set;

void sb_regress_set_free(sb_regress_set *s);
sb_regress_case *sb_regress_set_add(sb_regress_set *s, const char *id);
const sb_regress_case *sb_regress_set_find(const sb_regress_set *s, const char *id);

/* Judging (sb_regress_judge.c). */
typedef struct sb_regress_rules {
    double alpha;        /* significance of the U test (default 0.05) */
    double min_effect;   /* smallest relative change of the median called a change (default 0.10) */
    double min_seconds;  /* smallest change of a run's CPU seconds called a change (default 0.01): the
                            median now times |ratio - 1|; below it the kernel's CPU-time accounting
                            and a process's start-up move runs of a few hundredths of a second */
    double rtol;         /* relative tolerance of energies and probes (default 1e-9) */
} sb_regress_rules;
void sb_regress_rules_default(sb_regress_rules *r);
/* Judge every case of now against base (NULL: every case is new); returns
 * the number of regressions. */
int sb_regress_judge(sb_regress_set *now, const sb_regress_set *base, const sb_regress_rules *rules);

/* ---- files (sb_regress_files.c) ---------------------------------------- */
int sb_regress_baseline_write(const sb_regress_set *s, const char *path, char *err, size_t errlen);
int sb_regress_baseline_read(const char *path, sb_regress_set *s, char *err, size_t errlen);
/* Append one line per case to the history CSV (header when new). */
int sb_regress_history_append(const sb_regress_set *s, const char *path, char *err, size_t errlen);

/* ---- the report (sb_regress_report.c) ---------------------------------- */
void sb_regress_markdown(FILE *out, const sb_regress_set *now, const sb_regress_set *base,
                         const sb_regress_rules *rules, const char *baseline_path);
/* One PNG per case of its history (normalized CPU time median, min..max,
 * per stored run) into dir/history-<case>.png; warnings into err. */
int sb_regress_history_plots(const char *history, const sb_regress_set *now, const char *dir, const char *gnuplot,
                             FILE *err);

/* The paths of case id's history plot (ext "png" or "svg") and of the
 * picture of its scene, in dir. */
void sb_regress_plot_path(const char *dir, const char *id, const char *ext, char *buf, size_t len);
void sb_regress_picture_path(const char *dir, const char *id, char *buf, size_t len);

/* Pictures (sb_regress_pictures.c): for each scene one representative case
 * (its first converged case) drawn from RECORDS/rep1/ID into
 * dir/final-SCENE.png, and a "Final states" section into md linking them
 * (relative to dir).  0, or -1 when a picture could not be drawn (warnings
 * into err; the others are still shown). */
int sb_regress_pictures(FILE *md, const sb_regress_set *now, const char *records, const char *dir, FILE *err);

/* ---- the command (core/cli/sb_cli_regress.c) ---------------------------- */
int sb_cli_regress(int argc, char **argv);

#endif
