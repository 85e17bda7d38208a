/* sb_record.h — what one run produced, written to one HDF5 file (plus an
 * XDMF sidecar for the final surface), and read back by the report. */
#ifndef SB_RECORD_H
#define SB_RECORD_H

#include "sb_scene.h"
#include "sb_params.h"
#include "sb_stats.h"
#include "sb_material_state.h"
#include "sb_blob.h"
#include "sb_impulse.h"
#include <stdio.h>

/* Interruptions a run came through (--resume), accumulated over resumes and
 * written as root attributes of every record (all zero for a run that ran
 * in one process). */
typedef struct sb_resume_log {
    int count;                 /* resumes */
    char steps[256];           /* the completed step each resume started after, "1,3" */
    double setup_seconds;      /* set-up time of the resumed processes (in seconds_total) */
    double lost_seconds;       /* time an interrupted process spent past its last step boundary
                                  (discarded, not in seconds_total) */
    char builds[256];          /* build ids of the interrupted processes that differ from this one */
} sb_resume_log;

/* A step boundary a run can resume from: a checkpoint's /resume group. */
typedef struct sb_resume_point {
    int step;                  /* steps completed (0: the start) */
    int n_x;
    double *x, *v;             /* state at the end of `step` */
    double seconds;            /* seconds_total at the boundary */
    /* adaptive methods (sb_method.h save_mesh): the discretization at the
     * boundary (/resume/mesh_ints, /resume/mesh_doubles); has_mesh 0: none */
    int has_mesh;
    sb_blob mesh;
    /* contact.model = "impulse": the response's counts at the boundary
     * (/resume/impulse_counts), so that a resumed run's counts cover every
     * step; has_impulse 0: none (or a checkpoint of an older build) */
    int has_impulse;
    sb_impulse_stats impulse;
    /* statistics at the boundary: event counts and seconds per level, work
     * units, not_posdef; history records of steps 1..step (n_iters, n_steps) */
    sb_stats stats;
} sb_resume_point;

/* Validation of a run against its scene's expected probe values, separate
 * from solver convergence (docs/trust.md "Validation"). */
enum { SB_VALIDATION_NONE = 0,     /* nothing to check, or the run stopped before the final step */
       SB_VALIDATION_PASSED = 1,   /* every expected value within its tolerance */
       SB_VALIDATION_FAILED = 2 };
const char *sb_validation_name(int v);   /* "none", "passed", "failed" */

/* One expected value of one probe, judged (/probes/checks). */
typedef struct sb_check_row {
    int probe;                 /* probe index */
    int component;             /* 0,1,2 = x,y,z; 3 = norm; -1 = vector (sb_probe_check) */
    double expected[3];        /* in [0] unless component -1 */
    double measured[3];        /* the displacement component(s) at the final step, alike */
    double rel_error;          /* |measured - expected| / |expected| (vector: Euclidean norms) */
    double signed_error;       /* measured / expected - 1 (vector: along the expected vector):
                                  < 0 smaller than expected (too stiff), > 0 larger (too soft) */
    double tol;
    int passed;                /* rel_error <= tol */
} sb_check_row;

/* The method's own triangle surface at every step (sb_record_mesh.c), for
 * methods whose `surface` op gives triangles (linear_fem, adaptive_sqrt3):
 * each topology version (triangles, reference positions, grid parameters)
 * is stored once; every step row holds the vertex positions on its
 * version.  Written as /steps/mesh and played by RUN.mesh.xdmf, a
 * temporal collection whose grids change their point and cell counts with
 * the mesh (docs/recorded_figures.md). */
typedef struct sb_mesh_topo {
    int nv, nt;
    int *tri;                  /* 3 nt, into the version's vertices */
    double *ref;               /* 3 nv: reference positions (m) */
    double *st;                /* 2 nv: grid parameters (s,t) */
} sb_mesh_topo;
typedef struct sb_mesh_series {
    int n_topo, cap_topo;
    sb_mesh_topo *topo;
    int rows, cap_rows;        /* rows 0 .. rows-1 filled: row k = after step k (0 = the start) */
    int *row_topo;             /* the topology version of each row */
    double **row_pos;          /* 3 nv of its version per row (m) */
    long points;               /* positions stored so far */
} sb_mesh_series;
/* Row `row` (<= s->rows: appended, or a row replaced) of the surface
 * (nv vertices, nt triangles): a new topology version when tri, ref or st
 * differ from the last version's.  SB_OK or SB_ERR_NOMEM. */
int  sb_mesh_series_put(sb_mesh_series *s, int row, int nv, int nt, const int *tri, const double *ref,
                        const double *st, const double *pos);
void sb_mesh_series_free(sb_mesh_series *s);
/* Rows 0 .. rows-1 of /steps/mesh of the record PATH into s (s freed
 * first); SB_ERR_INPUT with a sentence when it has none or too few rows. */
int  sb_record_read_mesh_series(const char *path, int rows, sb_mesh_series *s, char *err, size_t errlen);
/* 1 when the record PATH holds /steps/mesh (0: none, or unreadable) and
 * *rows its rows */
int  sb_record_has_mesh_series(const char *path, int *rows);
/* The method's surface of row `step` of /steps/mesh: vertices (current,
 * reference, st) and triangles into one sb_mesh_topo plus pos (3 nv);
 * caller frees topo->tri/ref/st and *pos. */
int  sb_record_read_step_mesh(const char *path, int step, sb_mesh_topo *topo, double **pos, char *err,
                              size_t errlen);

/* room for the checksums of SB_SCENE_MAX_OBSTACLES meshes with long names */
#define SB_RECORD_MESH_SUMS_LEN 8192

typedef struct sb_run {
    /* identity */
    char scene_name[SB_NAME_LEN];
    char scene_path[512];
    const char *scene_json;    /* verbatim scene file text */
    char method[SB_NAME_LEN];
    char solver[SB_NAME_LEN];
    char method_info[256];     /* method describe() */
    char solver_info[256];     /* solver describe() (empty when the solver has none) */
    int res, levels;
    int res_t;                 /* elements along t when --res NxM gave them (0: as res) */
    long n_dofs;               /* finest level */
    const sb_paramset *params;
    char build_id[64];         /* git describe */
    char cpu_model[128];
    int n_cores;
    char started[32];          /* ISO 8601 UTC */
    char obstacle_meshes[SB_RECORD_MESH_SUMS_LEN];   /* the mesh obstacles' contents (sb_record_mesh_sums); "" none */
    /* outcome */
    int status;                /* 0 converged, 1 not converged, see exit codes;
                                  SB_STATUS_UNFINISHED in a checkpoint */
    int reason;                /* sb_reason of the last step, or the failing step */
    int steps_planned, steps_done;
    const sb_stats *stats;
    /* probes: trajectory[(step)*(n_probes*3) + p*3 + c], step 0 = reference */
    int n_probes;
    char (*probe_names)[SB_NAME_LEN];
    double *probe_traj;        /* (steps_done+1) * n_probes * 3 */
    double *probe_expected;    /* n_probes * 3 (NaN where none) */
    double *probe_rel_error;   /* n_probes (NaN where none) */
    /* final state */
    int n_x;
    const double *x_final;
    /* sample grid: material points (s,t), reference and final positions */
    int n_samples;
    double *sample_st;         /* 2 * n_samples */
    double *sample_ref;        /* 3 * n_samples */
    double *sample_pos;        /* 3 * n_samples */
    /* surface for output: triangles over the sample grid */
    int n_tris;
    int *tris;                 /* 3 * n_tris, indices into samples */
    /* the sample grid at every step (time series): row k = positions after
     * step k (row 0 = reference), rows 0..steps_done filled; NULL = not kept
     * (written as /steps/sample_pos/NNNNNN, played by the XDMF sidecar) */
    double *sample_traj;       /* (steps_planned + 1) * n_samples * 3 */
    /* the method's own triangles at every step (NULL: a method without a
     * triangle surface, or a series that outgrew its limit) */
    sb_mesh_series *mesh;
    /* where the final state strains the material (methods with material_state) */
    int has_material;
    sb_material_state material;
    /* error against the scene's reference */
    int has_error;
    double error_rms, error_max;   /* relative to the domain diameter (field) */
    double error_probe;            /* max probe relative error (probes) */
    char error_kind[16];           /* "none", "probes", "field" */
    /* constraints imposed by penalty at the final state (methods with
     * penalty_violation; docs/trust.md): the report, the displacement scale
     * max |x - X| over the sample grid, the relative violation
     * max(position, rotation * diameter) / scale and the tolerance */
    int has_penalty;
    double penalty_beta, penalty_position, penalty_rotation;
    double penalty_scale, penalty_relative, penalty_tol;
    /* contact (scenes with obstacles, docs/contact.md): sample points of
     * the finest level; the smallest distance of a sample point to an
     * obstacle over every step's end state, the points within dhat and the
     * points inside an obstacle at the end, and the steps that ended with a
     * point inside (the step filter keeps this 0) */
    int has_contact;
    int contact_points, contact_active, contact_inside, contact_steps_inside;
    double contact_min_distance;
    /* why the run stopped at a moving obstacle that swept through the
     * cloth within a step ("" otherwise; reason obstacle_swept) and what the
     * no-penetration guarantee covers (docs/contact.md "What the guarantee
     * covers"); both "" without obstacles */
    char contact_stop[1024];
    char contact_coverage[1024];
    /* steps whose end had an analytic obstacle crossing a sample triangle
     * with its corners outside (between the points); -1: not checked (the
     * method does not triangulate its points) */
    int has_between, contact_steps_between;
    /* self-contact (contact.self; docs/contact.md): end-of-step figures */
    int has_self, self_pairs, self_active, self_steps_crossing;
    double self_min_distance;
    /* contact.model = "impulse": the collision response's counts summed
     * over the steps this process ran (sb_impulse.h) */
    int has_impulse;
    sb_impulse_stats impulse;
    /* validation (docs/trust.md): every expected value of every probe */
    int validation;            /* SB_VALIDATION_* */
    int n_checks;
    sb_check_row *checks;
    /* Phi_E(x_final) - Phi_E(X): the method's energy (elastic + external +
     * penalty; no inertia) at the final state minus at the reference
     * configuration, both with the last step's loads: comparable across
     * methods, unlike f, which carries the constant -F.X of dead loads */
    int has_potential;
    double potential_change;
    /* the method's energy E(x) (elastic + external + boundary penalty, no
     * inertia) of the final state at the last step's loads: what a local
     * minimum found on a nonconvex scene is compared by (docs/study.md) */
    int has_energy;
    double energy_final;           /* J */
    sb_resume_log resumed;
    /* checkpoints only: the last step boundary, written as /resume (NULL in
     * a final record); its stats' history pointers are not used, the
     * boundary is n_iters / n_steps records into /history */
    const sb_resume_point *resume;
    /* the record's own write (issue 42): when write_event is an event
     * (SB_EV_RECORD of the final record) and write_t0 its start, the seconds
     * from write_t0 to the moment every group is written are added to that
     * event (finest level) and to seconds_total in the file; 0 / 0: none.
     * Closing, checksumming, fsync and renames stay outside the file. */
    int write_event;
    double write_t0;
} sb_run;

/* Call first thing in main() of a program that reads records it did not
 * write: HDF5 (1.10 to at least 1.14, HDFGroup/hdf5#6677) can be left by a
 * malformed file with internal state its at-exit shutdown cannot release
 * ("HDF5: infinite loop closing library", a bounded leak LeakSanitizer
 * reports) although every handle the readers opened is closed.  This turns
 * that shutdown off (H5dont_atexit): files are always closed explicitly, and
 * what HDF5 holds stays reachable until the process ends. */
void sb_record_library_init(void);

/* Zero the run and fill the machine/build fields (build_id, cpu_model,
 * n_cores, started = now) from sb_sysinfo.h. */
void sb_run_init(sb_run *run);

/* Layout version written as the root attribute "format_version"; a reader
 * refuses files with a newer version.  The layout is documented in
 * docs/recorded_figures.md. */
#define SB_RECORD_FORMAT_VERSION 5   /* 2: root attribute "checksum" (docs/trust.md); 3: exclusive event
                                        seconds, harness events, CHOLMOD per factorization, peak memory,
                                        per-iteration and per-step seconds by part (issue 42); 4: CPU
                                        seconds of the numeric factorizations (/stats/chol_factorize_cpu);
                                        5: the first factorization after each analysis apart
                                        (/stats/chol_first_factorize_cpu, chol_first_flops) */
#define SB_RECORD_FORMAT_NAME "shellbench-run"
/* Record status of a checkpoint (run.checkpoint): the run was still going. */
#define SB_STATUS_UNFINISHED 2

/* The XDMF sidecar path of an HDF5 record: PATH with a trailing ".h5"
 * replaced by ".xdmf" (".xdmf" appended when PATH does not end in ".h5").
 * Returns SB_OK or SB_ERR_INPUT when buf is too small. */
int sb_record_xdmf_path(const char *h5path, char *buf, size_t len);

/* The time-series sidecar of a record: PATH with ".h5" replaced by
 * ".steps.xdmf" (appended otherwise); SB_OK or SB_ERR_INPUT. */
int sb_record_steps_xdmf_path(const char *h5path, char *buf, size_t len);

/* The mesh time-series sidecar: PATH with ".h5" replaced by ".mesh.xdmf"
 * (appended otherwise); SB_OK or SB_ERR_INPUT. */
int sb_record_mesh_xdmf_path(const char *h5path, char *buf, size_t len);

/* Write atomically: to PATH.tmp.<pid>, then rename. Also writes PATH minus
 * ".h5" plus ".xdmf", and, when the run keeps its time series
 * (sample_traj), PATH minus ".h5" plus ".steps.xdmf" (removed otherwise),
 * and when it keeps its mesh series (mesh), PATH minus ".h5" plus
 * ".mesh.xdmf" (removed otherwise).
 * Returns SB_OK or SB_ERR_IO with a message in err. */
int sb_record_write(const sb_run *run, const char *path, char *err, size_t errlen);

/* A flat summary read back from a record (for reports and comparisons). */
typedef struct sb_record_summary {
    char scene[SB_NAME_LEN], method[SB_NAME_LEN], solver[SB_NAME_LEN];
    long dofs;
    int levels, steps, iterations, status, reason;
    double work_assembly, work_qp, seconds;
    double seconds_event[SB_EV_COUNT];
    /* exclusive seconds per event (format 3, /stats/events_self_seconds) and
     * what no event covers; has_self 0 for older records (then both are 0) */
    int has_self;
    double seconds_self[SB_EV_COUNT], seconds_unattributed;
    int has_error;
    double error_rms, error_max, error_probe;
    char error_kind[16];
    double energy_final;       /* J; NaN when the record has none (written before it was kept) */
    /* convergence history of all iterations (for plots) */
    int n_hist;
    double *hist_gnorm;        /* owned */
    int *hist_step;            /* owned */
    /* added by the recording module */
    int *hist_level;           /* owned; level of each history record */
    int *hist_iter;            /* owned; iteration within its step (0 = start of step) */
    int steps_planned, n_cores;
    char build_id[64], cpu_model[128], started[32];
    char blas_core[64];        /* OpenBLAS kernel set; "unknown" in records written before it was kept */
    char reason_name[32];      /* sb_reason_name(reason) as recorded */
    int resumes;               /* times the run was resumed (0 in records written before resumes existed) */
    char resume_steps[256];    /* after which completed steps, "2,3" */
    int resume_point;          /* a checkpoint: the completed step --resume continues after; -1 otherwise */
    int res;                   /* elements per side (0 in records written before the resolution used was kept) */
    int res_t;                 /* elements along t with --res NxM (0: as res, or not recorded) */
    char overrides[1024];      /* the parameters the run was given (--set), "key=value, key=value"; "" none */
    char validation[16];       /* "passed", "failed", "none"; "" in records written before validation */
    double potential_change;   /* NaN when not recorded */
    double below_reference;    /* /final/material below_reference_area_fraction: share of the area whose
                                * energy is below the reference state's (docs/denim.md); NaN when not recorded */
} sb_record_summary;

int  sb_record_read_summary(const char *path, sb_record_summary *s, char *err, size_t errlen);
/* The name of a record's status: "converged" (0), "not converged" (1),
 * "unfinished" (SB_STATUS_UNFINISHED, a checkpoint), "failed" (< 0),
 * "unknown" otherwise. */
const char *sb_record_status_name(int status);
void sb_record_summary_free(sb_record_summary *s);
/* Read the sampled final positions (for reference-run errors). */
int  sb_record_read_samples(const char *path, int *n, double **st, double **pos,
                            char *err, size_t errlen);

/* What it takes to rebuild a record's discretization and state (for
 * `shellbench inspect`): the scene text, method, resolution, levels, the
 * method.* parameters as "key=value" assignments, and the final (or, in a
 * checkpoint, the current) DOF vector. */
#define SB_RECORD_MAX_SETS 64
typedef struct sb_record_setup {
    char scene[SB_NAME_LEN], method[SB_NAME_LEN], solver[SB_NAME_LEN];
    char scene_path[512];
    char *scene_json;          /* owned */
    int res, levels, status, steps_done;
    int res_t;                 /* 0 in records without --res NxM */
    int n_sets;
    char sets[SB_RECORD_MAX_SETS][320];
    char linear[32];           /* solver.linear when the record has one ("" otherwise: cholmod) */
    int n_x;
    double *x;                 /* owned */
} sb_record_setup;

/* Read the resume point of the checkpoint PATH for the run `expect` (its
 * identity filled in, params resolved): refuses, with a sentence naming the
 * file and the field, a checkpoint of another scene text, method, solver,
 * resolution, level count, dof count or parameter value (run.checkpoint may
 * differ), and one without a /resume group.  A checkpoint that holds the
 * method's mesh (rp->has_mesh, adaptive methods) is not held to
 * expect->n_dofs: the caller restores the mesh and checks rp->n_x.  On success rp owns x, v and
 * stats.iters / stats.steps (sb_resume_point_free), `ckpt_seconds` is the
 * checkpoint's seconds_total, `ckpt_build` its build id, `log` its resume
 * log, and probe_traj receives rows 0..step of its probe trajectory
 * (expect->n_probes probes; the caller's buffer). */
int  sb_record_read_resume(const char *path, const sb_run *expect, sb_resume_point *rp, double *ckpt_seconds,
                           char *ckpt_build, size_t build_len, sb_resume_log *log, double *probe_traj,
                           char *err, size_t errlen);
void sb_resume_point_free(sb_resume_point *rp);

int  sb_record_read_setup(const char *path, sb_record_setup *s, char *err, size_t errlen);
/* The same without the final state (x NULL, n_x 0): what a digest, which
 * drops /final/x, still holds of the run's identity */
int  sb_record_read_identity(const char *path, sb_record_setup *s, char *err, size_t errlen);

/* Rewrite the finished record at path in place as a digest: without /steps,
 * /final/displacement, sample_ref and triangles (and /final/x with
 * drop_state), marked by the root attribute "digest", sealed
 * (sb_record_digest.c).  *already = 1 (and nothing written) for a digest;
 * SB_ERR_INPUT for a checkpoint or anything unreadable as a record. */
int  sb_record_digest(const char *path, int drop_state, int *already, char *err, size_t errlen);
/* 1 when the record keeps its final state /final/x (what render and inspect
 * rebuild from), 0 for a digest made with drop_state, < 0 when unreadable */
int  sb_record_keeps_state(const char *path, char *err, size_t errlen);

/* The checksums of the scene's mesh obstacles' contents into buf (""
 * without mesh obstacles), as the record's attribute "obstacle_meshes"
 * holds them (sb_record_obstacles.c). */
void sb_record_mesh_sums(const sb_scene *sc, char *buf, size_t len);
/* The record's "obstacle_meshes" into buf ("" when it has none); SB_OK or
 * an error with a sentence naming the file. */
int  sb_record_read_mesh_sums(const char *path, char *buf, size_t len, char *err, size_t errlen);
/* A scene's `reference: {type: file}` (sb_reference_check.c, docs/trust.md):
 * SB_OK when the scene has none, or when the file is a readable record of a
 * finished, converged run of the same scene (physics compared section by
 * section) on a sample grid of the scene's domain (sample_st NULL: any
 * number of points per side; else exactly the n_samples points given),
 * sealed with a checksum unless allow_unsealed (sb_reference_sealed), whose
 * scene text is the same problem by sb_scene_same_problem too (the test
 * the end of a run and the study reports make, so all give one verdict),
 * and whose obstacle meshes have the contents of this scene's (when it
 * recorded their checksums).  Otherwise SB_ERR_INPUT with one sentence
 * naming the scene, the file and what is wrong. */
int  sb_reference_check(const sb_scene *sc, const double *sample_st, int n_samples, int allow_unsealed, char *err,
                        size_t errlen);
void sb_record_setup_free(sb_record_setup *s);

/* The sample-grid surface of a record at one step (sb_record_steps.c):
 * step -1 = the final state (/final/sample_pos), k >= 0 = after step k
 * (/steps/sample_pos/NNNNNN; records written before it was kept have none). */
typedef struct sb_record_samples {
    int n, n_tris, n_steps;    /* samples, triangles, steps in /steps/sample_pos (0 = none) */
    double *st, *ref, *pos;    /* 2n, 3n, 3n (owned) */
    int *tris;                 /* 3 n_tris (owned) */
} sb_record_samples;
int  sb_record_read_step_samples(const char *path, int step, sb_record_samples *s, char *err, size_t errlen);
void sb_record_samples_free(sb_record_samples *s);
/* Steps 0..step of /steps/sample_pos of the checkpoint PATH into traj (n
 * samples each) for --resume; SB_ERR_INPUT when the file has none. */
int  sb_record_read_sample_traj(const char *path, int step, int n, double *traj, char *err, size_t errlen);

/* Report: Markdown (format "md") or CSV table of the files, and, when
 * png_path is non-NULL, a gnuplot PNG of ||g|| against iteration. */
int sb_report(int n_files, char **files, const char *format, FILE *out,
              const char *png_path, char *err, size_t errlen);

/* Positive warning bits returned by sb_report (the table was written):
 * the plot could not be made (gnuplot missing or failed), or some files
 * could not be read (their rows are left out).  err names the cause. */
enum { SB_REPORT_WARN_PLOT = 1, SB_REPORT_WARN_FILES = 2 };

/* The plot format of a path, from its extension: ".png" (PNG), ".svg"
 * (SVG), ".jpg"/".jpeg" (JPEG); *format (may be NULL) gets "png", "svg" or
 * "jpeg".  SB_OK, or SB_ERR_INPUT with a sentence for any other extension. */
int sb_report_plot_format(const char *path, const char **format, char *err, size_t errlen);

/* sb_report with every option: format "md" (default) or "csv"; plot_path
 * in the format of its extension (sb_report_plot_format); gnuplot is the program
 * to run (NULL: $SB_GNUPLOT, else "gnuplot"). */
typedef struct sb_report_options {
    const char *format;
    const char *plot_path;
    const char *gnuplot;
} sb_report_options;
int sb_report_opts(int n_files, char **files, const sb_report_options *o, FILE *out,
                   char *err, size_t errlen);

#endif
