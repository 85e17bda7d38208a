/* sb_run_state.h — internal to the run (sb_run*.c): the state of one run
 * from request to record, and the helpers its phases share.  Not part of
 * the public interface (sb_run.h is). */
#ifndef SB_RUN_STATE_H
#define SB_RUN_STATE_H

#include "sb_context.h"
#include "sb_output.h"
#include "sb_problem.h"
#include "sb_record.h"
#include "sb_run.h"
#include "sb_solver.h"

#include <stdio.h>

/* the live progress line (sb_run_progress.c) */
typedef struct sb_run_progress {
    int on, tty, shown;                /* shown: a line is on the terminal now */
    double interval, last;             /* seconds between updates, time of the last */
    long iterations;                   /* outer iterations (finest level) so far in this process */
    const char *prefix;
} sb_run_progress;

typedef struct run_state {
    sb_context ctx;
    sb_scene scene;
    int scene_loaded;
    const sb_method_type *mt;
    const sb_solver_type *stype;
    void *ms, *ss;
    int ms_created, ss_allocated;
    sb_problem *prob;
    double *x, *xn, *v, *xref;
    sb_run rec;
    char (*probe_names)[SB_NAME_LEN];
    int n_grid;                        /* sample grid per side */
    int res;                           /* the resolution used: --res, else the scene's */
    int res_t;                         /* elements along t (--res NxM, "resolution": [N, M]); 0: as res */
    double mem_estimate;               /* bytes (sb_memory.h), 0 before the estimate */
    sb_output_lock lock;               /* OUT.lock while the run writes OUT */
    /* checkpoints (run.checkpoint): the record so far, written to
     * partial_path every checkpoint_every seconds by the loop's monitor */
    FILE *err;
    double t_start, checkpoint_every, checkpoint_last;
    int checkpoint_failed;
    /* rec->material is of x as it is now (set by the step's judgement, cleared
     * when a step begins): the final record reuses it instead of evaluating
     * the material at every quadrature point again (issue 42: the two
     * evaluations were 8 % of a 1.2e6-dof bhem/rmtr run) */
    int material_current;
    int checkpoints_on;                /* run.checkpoint > 0 and a record path */
    sb_run_progress progress;
    char partial_path[1100];
    /* the last completed step: the resume point the checkpoints carry */
    sb_resume_point bp;
    /* --resume: the analyze events of the checkpoint's boundary; this
     * process's repeat of a symbolic factorization done before is set-up
     * (sb_run_fold_resume_setup) */
    int resumed;
    int resume_folded;                 /* 1 once an adaptive mesh changed in the resumed process: no more folding */
    sb_event_stat analyze_at_resume[SB_MAX_LEVELS];
    /* the method's own triangles per step (methods whose surface op gives
     * triangles; sb_run_record_mesh): rec.mesh points here while kept */
    int tri_surface;
    sb_mesh_series mesh_series;
    /* contact sample points pushed out of obstacles after adaptations
     * (sb_run_adapt, sb_problem_contact_separate) */
    int contact_separated;
    /* obstacles crossing the cloth between its sample points (issue 37,
     * sb_run_contact.c): the first step and obstacle, the sample spacing */
    int between_init, between_first_step, between_obstacle;
    double contact_spacing;
} run_state;


/* ---- sizes (sb_run_limits.c): -1 to go on, else the exit code ---------- */
/* R->res from --res or the scene; refuses a resolution out of range. */
int    sb_run_resolve_res(run_state *R, const sb_run_request *req);
/* The memory estimate of the method's estimate op against the limit. */
int    sb_run_check_memory(run_state *R, int levels);
/* The same for a method without one, after its create(). */
int    sb_run_check_created(run_state *R);

/* ---- output (sb_run_output.c): -1 to go on, else the exit code ---------- */
/* The record path (*out_path, NULL for none), checked, its directory made
 * and locked; checkpoints on when run.checkpoint > 0. */
int    sb_run_prepare_output(run_state *R, const sb_run_request *req, int levels, const char **out_path,
                             char *auto_path, size_t len);

/* ---- results (sb_run_results.c) ----------------------------------------- */
/* Sample grid (n x n in (s,t), points inside the domain) and its triangles. */
int    sb_run_build_samples(run_state *R);
/* Load and motion factors of `step` (1-based). */
void   sb_run_step_info(const sb_scene *sc, int step, sb_step_info *si);
/* Relative error of a probe's displacement u against its expected value. */
double sb_run_probe_rel_error(const sb_probe *p, const double u[3]);
/* Probe positions of the current state into trajectory slot `step_slot`. */
int    sb_run_record_probes(run_state *R, int step_slot);
/* The method's triangle surface of the current state into row `step_slot`
 * of the mesh series (rec.mesh), and its triangle count into *n_tris (0
 * for a method without a triangle surface).  The series is dropped, with a
 * note, once it would exceed 2^22 stored positions (about 100 MB).
 * SB_OK, or an error status (the surface op failed, out of memory). */
int    sb_run_record_mesh(run_state *R, int step_slot, int *n_tris);
/* The JSON summary (caller frees). */
char  *sb_run_summary_json(run_state *R, const char *out_path);
/* Error against the scene's reference (DESIGN.md "Accuracy").  SB_OK, or
 * SB_ERR_INPUT when the reference file is refused (the sentence on err, no
 * error recorded): the run then exits 2, as check and its start would have.
 * skip_file: the run makes its scene's reference; no file error is taken. */
int    sb_run_compute_error(run_state *R, FILE *err, int allow_unsealed, int skip_file);
/* rec->material of the current state (methods with material_state). */
void   sb_run_record_material(run_state *R);
/* rec->energy_final: the method's energy of the current state (uncounted). */
void   sb_run_record_energy(run_state *R);

/* ---- verdicts beyond the solver's (sb_run_judge.c, docs/trust.md) -------- */
/* A step the solver calls converged is a physical state: finite, and within
 * run.strain_max (methods with material_state; fills rec->material).
 * Returns the step's reason, or SB_REASON_NONFINITE / SB_REASON_STRAIN. */
sb_reason sb_run_judge_step(run_state *R, sb_reason reason);
/* The final state's penalty-imposed constraints (methods with
 * penalty_violation): recorded, and a converged run whose violation exceeds
 * run.penalty_tol times the displacement scale becomes not converged
 * (SB_REASON_PENALTY).  Needs rec->sample_pos of the final state. */
void sb_run_judge_penalty(run_state *R);
/* contact.model = impulse: a run whose response left collisions in more
 * than run.contact_unresolved_max steps is not converged (reason
 * contact_unresolved): its recorded states cross themselves or an obstacle. */
void sb_run_judge_contact(run_state *R);
/* The expected probe values judged (sb_validation.c): rec->checks,
 * rec->validation, probe_rel_error.  SB_OK or SB_ERR_NOMEM. */
int  sb_run_validate(run_state *R);
/* 1 when paths p and q name the same file (directories resolved); a and b
 * (len bytes each) receive the normalized paths. */
int  sb_run_same_path(const char *p, const char *q, char *a, char *b, size_t len);
/* ---- what the contact guarantee covered (sb_run_contact.c) -------------- */
/* Fold the step's end report into rec->contact_steps_between. */
struct sb_contact_report;
void sb_run_contact_between(run_state *R, int step, const struct sb_contact_report *r, double spacing);
/* rec->contact_coverage: a sentence on what the no-penetration guarantee
 * covered (sample points; between them checked or not, crossings found or
 * not, features that could pass unseen); "" without obstacles. */
void sb_run_contact_coverage(run_state *R);

/* rec->potential_change: Phi_E(x) - Phi_E(X) with the last step's data. */
void sb_run_potential_change(run_state *R);

/* ---- checkpoints and resume (sb_run_checkpoint.c) ------------------------ */
int    sb_run_partial_path(const char *out_path, char *buf, size_t len);
void   sb_run_remove_partial(run_state *R);
void   sb_run_write_checkpoint(run_state *R);
void   sb_run_mark_boundary(run_state *R, int step);
/* After a resume: a level's symbolic factorization (analyze) repeated in
 * this process, although the interrupted one had done it, moves from the
 * event counts to the resume log's set-up time, so that every count but
 * checkpoint equals the uninterrupted run's.  Idempotent; called after each step. */
void   sb_run_fold_resume_setup(run_state *R);
/* --resume: steps already done (0: no checkpoint), or -1 on an input error. */
int    sb_run_resume(run_state *R, int quiet);

/* ---- adaptive meshes (sb_run_adapt.c) ------------------------------------ */
/* method.adapt_every of a method with the adapt op (0: it never adapts) */
int    sb_run_adapt_every(const run_state *R);
/* 1 when the method can save and restore its mesh (checkpoints of adaptive runs) */
int    sb_run_adapt_resumable(const run_state *R);
/* For an adaptive method that cannot save its mesh: refuses --resume from
 * a checkpoint and --stop-after-steps, and turns checkpoints off.  -1 to
 * go on, else the exit code. */
int    sb_run_adapt_check(run_state *R, const sb_run_request *req);
/* After the method's discretization changed (an adaptation, or a mesh
 * restored for --resume): the run's vectors re-sized (x, v taken from
 * adapt_state when take_state), the reference, problem and solver rebuilt,
 * the record's dof count updated.  SB_OK or an error status. */
int    sb_run_adapt_follow(run_state *R, int take_state);
/* Before step `step`: the method's adaptation when it is due; on a change
 * the run's vectors, the problem and the solver follow, *n gets the new
 * dof count.  -1 to go on, else the exit code. */
int    sb_run_adapt(run_state *R, int step, int *n);

/* ---- the monitor (sb_run_progress.c) ------------------------------------- */
void   sb_run_progress_init(run_state *R, const sb_run_request *req);
/* Erase the progress line (before any other message on err). */
void   sb_run_progress_clear(run_state *R);
/* sb_context.monitor, after every iteration: a checkpoint when run.checkpoint
 * seconds have passed, then the progress line. */
void   sb_run_monitor(void *data, const sb_iter_record *r);

#endif
