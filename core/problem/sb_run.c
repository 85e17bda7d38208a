/* sb_run.c — one run, end to end: scene -> method -> problem -> solver ->
 * record (sb_run.h).  sb_run_execute() runs its phases in order, each a
 * function of its own:
 *
 *   resolve_request   scene, method, solver, parameters; refuse what cannot work
 *   sb_run_resolve_res, sb_run_check_memory (sb_run_limits.c)
 *                     the resolution used; refuse what cannot fit in memory
 *   sb_run_prepare_output (sb_run_output.c)
 *                     where the record and its checkpoint go: checked, locked
 *   prepare_run       method -> problem -> solver, work vectors, record identity
 *   check_reference   the scene's reference file, if any, is usable (docs/trust.md)
 *   start_or_resume   step 1, a checkpoint's last completed step, or nothing to do
 *   run_steps         the time / load steps; a converged step must be physical
 *   finish_run        probes and validation, penalty, samples, error, material,
 *                     record, summary
 *
 * A phase returns RUN_GO_ON to continue or the exit code to stop with.  All
 * statistics come from the core wrappers (sb_problem.c). */
#include "sb_run_state.h"
#include "sb_contact.h"
#include "sb_sysinfo.h"
#include "sb_surface.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { RUN_GO_ON = -1 };

static void run_cleanup(run_state *R)
{
    if (R->ss_allocated) R->stype->free(R->ss);
    free(R->ss);
    sb_problem_free(R->prob);
    if (R->ms_created) R->mt->destroy(R->ms);
    free(R->ms);
    free(R->x); free(R->xn); free(R->v); free(R->xref);
    sb_resume_point_free(&R->bp);
    free(R->rec.probe_traj); free(R->rec.probe_expected); free(R->rec.probe_rel_error);
    free(R->rec.sample_st); free(R->rec.sample_ref); free(R->rec.sample_pos); free(R->rec.tris);
    free(R->rec.checks);
    free(R->rec.sample_traj);
    sb_mesh_series_free(&R->mesh_series);
    free(R->probe_names);
    if (R->scene_loaded) sb_scene_free(&R->scene);
    sb_context_free(&R->ctx);
    sb_output_lock_release(&R->lock);
}

/* run.perturb: each dof of the start gets an offset uniform in [-a, a], from
 * a SplitMix64 stream seeded by run.seed (Steele, Lea & Flood 2014; local
 * state, so runs with the same seed are bit-identical).  Round-off-sized
 * offsets sample how much a count on a nonconvex scene owes to round-off.
 * Kept instead of a gsl_rng (issue 31): the committed perturbed-start records
 * (results/rmtr/runs/rmtrd-SCENE-lL-p1e-10-sN.h5) were drawn from this
 * stream, and GSL has no SplitMix64; a new stream uses sb_rng_for_run
 * (sb_gsl.h) and records its generator's name. */
static void perturb_start(int n, double *x, double a, unsigned long long seed)
{
    if (!(a > 0)) return;
    unsigned long long z = seed;
    for (int i = 0; i < n; i++) {
        z += 0x9E3779B97F4A7C15ull;
        unsigned long long w = z;
        w = (w ^ (w >> 30)) * 0xBF58476D1CE4E5B9ull;
        w = (w ^ (w >> 27)) * 0x94D049BB133111EBull;
        w ^= w >> 31;
        double u = (double)(w >> 11) * 0x1.0p-53;        /* uniform in [0, 1) */
        x[i] += a * (2.0 * u - 1.0);
    }
}


/* Scene, method and solver, whether they fit together, and the parameters. */
static int resolve_request(run_state *R, const sb_run_request *req, int *levels)
{
    FILE *err = R->err;
    char path[1024], msg[2048], e1[256];
    if (sb_scene_resolve(req->scene, path, sizeof path)) {
        fprintf(err, "shellbench: scene \"%s\" not found (neither a file nor a name in bench/scenes; try `shellbench list scenes`)\n",
                sb_escape_copy(req->scene, e1, sizeof e1));
        return SB_EXIT_INPUT;
    }
    if (sb_scene_load(path, &R->scene, msg, sizeof msg)) {
        fprintf(err, "%s\n", msg);
        return SB_EXIT_INPUT;
    }
    R->scene_loaded = 1;

    R->mt = sb_method_find(req->method);
    R->stype = sb_solver_find(req->solver);
    if (!R->mt || !R->stype) {
        fprintf(err, "shellbench: unknown %s \"%s\" (see `shellbench list %s`)\n", !R->mt ? "method" : "solver",
                sb_escape_copy(!R->mt ? req->method : req->solver, e1, sizeof e1), !R->mt ? "methods" : "solvers");
        return SB_EXIT_INPUT;
    }
    *levels = req->levels > 0 ? req->levels : 1;
    int rc = sb_run_combination_check(R->mt, R->stype, *levels, msg, sizeof msg);
    if (!rc) rc = sb_run_scene_methods_check(&R->scene, msg, sizeof msg);
    if (!rc) rc = sb_run_scene_method_check(&R->scene, R->mt, msg, sizeof msg);
    if (!rc) {
        /* the scene's settings for this method first, the command line's --set after (it wins) */
        const sb_scene_method *sm = sb_scene_method_find(&R->scene, R->mt->name);
        const int n_scene = sm ? sm->n_sets : 0;
        const char **sets = malloc((size_t)(n_scene + req->n_sets + 1) * sizeof *sets);
        if (!sets) return SB_EXIT_INTERNAL;
        for (int k = 0; k < n_scene; k++) sets[k] = sm->sets[k];
        for (int k = 0; k < req->n_sets; k++) sets[n_scene + k] = req->sets[k];
        rc = sb_run_paramset(&R->ctx.params, R->mt, R->stype, n_scene + req->n_sets, sets, msg, sizeof msg);
        free(sets);
    }
    if (rc) {
        fprintf(err, "shellbench: %s\n", msg);
        return rc == SB_ERR_INTERNAL ? SB_EXIT_INTERNAL : SB_EXIT_INPUT;
    }
    return RUN_GO_ON;
}

/* The record's identity: what ran, where, with which build. */
static void record_identity(run_state *R)
{
    const sb_scene *sc = &R->scene;
    sb_run *rec = &R->rec;
    snprintf(rec->scene_name, sizeof rec->scene_name, "%s", sc->name);
    snprintf(rec->scene_path, sizeof rec->scene_path, "%s", sc->path);
    rec->scene_json = sc->json_text;
    snprintf(rec->method, sizeof rec->method, "%s", R->mt->name);
    snprintf(rec->solver, sizeof rec->solver, "%s", R->stype->name);
    if (R->mt->describe) R->mt->describe(R->ms, rec->method_info, sizeof rec->method_info);
    if (R->stype->describe) R->stype->describe(R->ss, rec->solver_info, sizeof rec->solver_info);
    rec->res = R->res;   /* the resolution used, also when --res was absent */
    rec->res_t = R->res_t;
    rec->levels = sb_problem_levels(R->prob);
    rec->n_dofs = R->rec.n_x;
    rec->params = &R->ctx.params;
    sb_sysinfo_build_id(rec->build_id, sizeof rec->build_id);
    sb_sysinfo_cpu_model(rec->cpu_model, sizeof rec->cpu_model);
    rec->n_cores = sb_sysinfo_cores();
    sb_sysinfo_now_iso(rec->started, sizeof rec->started);
    sb_record_mesh_sums(sc, rec->obstacle_meshes, sizeof rec->obstacle_meshes);
    rec->steps_planned = sc->time.steps;
    rec->stats = &R->ctx.stats;
    rec->n_probes = R->mt->eval_points ? sc->n_probes : 0;
    rec->probe_names = R->probe_names;
    for (int p = 0; p < sc->n_probes; p++) {
        snprintf(R->probe_names[p], SB_NAME_LEN, "%s", sc->probes[p].name);
        for (int k = 0; k < 3; k++)
            rec->probe_expected[3 * p + k] = sc->probes[p].has_expected &&
                (sc->probes[p].expected_component < 0 || k == 0) ? sc->probes[p].expected[k] : NAN;
        rec->probe_rel_error[p] = NAN;
    }
    rec->x_final = R->x;
}

/* method -> problem -> solver, the work vectors, the record's identity and
 * the reference state (probes, sample grid), then run.perturb's start. */
static int prepare_run(run_state *R, int levels)
{
    FILE *err = R->err;
    sb_paramset *ps = &R->ctx.params;
    int rc;
    R->ms = calloc(1, R->mt->state_size);
    if (!R->ms) goto nomem;
    sb_method_config cfg = { R->res, levels, ps, &R->ctx, R->res_t };
    rc = R->mt->create(R->ms, &R->scene, &cfg);
    R->ms_created = 1;
    if (rc) {
        fprintf(err, "shellbench: method %s on scene %s: %s\n", R->mt->name, R->scene.name,
                R->ctx.err[0] ? R->ctx.err : "set-up failed");
        return rc == SB_ERR_INPUT || rc == SB_ERR_UNSUPPORTED ? SB_EXIT_INPUT : SB_EXIT_INTERNAL;
    }
    if ((rc = sb_run_check_created(R)) != RUN_GO_ON) return rc;
    rc = sb_problem_create(&R->ctx, R->mt, R->ms, &R->scene, &R->prob);
    if (rc) {
        fprintf(err, "shellbench: %s\n", R->ctx.err);
        return rc == SB_ERR_UNSUPPORTED || rc == SB_ERR_INPUT ? SB_EXIT_INPUT : SB_EXIT_INTERNAL;
    }
    R->ss = calloc(1, R->stype->state_size);
    if (!R->ss) goto nomem;
    rc = R->stype->alloc(R->ss, R->prob, ps);
    R->ss_allocated = 1;
    if (rc) {
        fprintf(err, "shellbench: solver %s: %s\n", R->stype->name, R->ctx.err[0] ? R->ctx.err : "allocation failed");
        return rc == SB_ERR_UNSUPPORTED || rc == SB_ERR_INPUT ? SB_EXIT_INPUT : SB_EXIT_INTERNAL;
    }

    const int F = sb_problem_finest(R->prob), n = sb_problem_n(R->prob, F);
    const sb_scene *sc = &R->scene;
    const size_t np = (size_t)(sc->n_probes ? sc->n_probes : 1);
    R->x = malloc((size_t)n * sizeof(double));
    R->xn = malloc((size_t)n * sizeof(double));
    R->v = calloc((size_t)n, sizeof(double));
    R->xref = malloc((size_t)n * sizeof(double));
    R->bp.x = malloc((size_t)n * sizeof(double));
    R->bp.v = malloc((size_t)n * sizeof(double));
    R->rec.probe_traj = calloc(((size_t)sc->time.steps + 1) * np * 3, sizeof(double));
    R->rec.probe_expected = malloc(np * 3 * sizeof(double));
    R->rec.probe_rel_error = malloc(np * sizeof(double));
    R->probe_names = calloc(np, sizeof *R->probe_names);
    if (!R->x || !R->xn || !R->v || !R->xref || !R->bp.x || !R->bp.v || !R->rec.probe_traj || !R->rec.probe_expected ||
        !R->rec.probe_rel_error || !R->probe_names || sb_run_build_samples(R))
        goto nomem;
    /* the sample grid of every step (the record's time series), unless it
     * would exceed 2^22 points (about 100 MB) */
    if (R->mt->eval_points && ((size_t)sc->time.steps + 1) * (size_t)R->rec.n_samples <= ((size_t)1 << 22) &&
        !(R->rec.sample_traj = malloc(((size_t)sc->time.steps + 1) * ((size_t)R->rec.n_samples ? (size_t)R->rec.n_samples : 1) * 3 * sizeof(double))))
        goto nomem;
    R->mt->initial(R->ms, F, R->x);
    sb_copy(n, R->x, R->xref);
    R->rec.n_x = n;
    record_identity(R);
    sb_run *rec = &R->rec;
    if (R->mt->eval_points) {
        if (sb_run_record_probes(R, 0) ||
            R->mt->eval_points(R->ms, F, R->x, rec->n_samples, rec->sample_st, rec->sample_ref)) {
            fprintf(err, "shellbench: method %s cannot evaluate the probes / sample grid of scene %s\n", R->mt->name, sc->name);
            return SB_EXIT_INTERNAL;
        }
    } else {
        rec->n_samples = 0;
        rec->n_tris = 0;
    }
    /* the method's own triangles (linear_fem, adaptive_sqrt3): counted every
     * step, and kept per step when the run writes a record (rec.mesh) */
    if (R->mt->surface) {
        sb_surface s0;
        memset(&s0, 0, sizeof s0);
        R->tri_surface = R->mt->surface(R->ms, F, R->x, &s0) == SB_OK && s0.n_patches == 0 && s0.n_tris > 0 && s0.vert;
        sb_surface_free(&s0);
        if (R->tri_surface && R->partial_path[0]) rec->mesh = &R->mesh_series;
        int nt0;
        if (sb_run_record_mesh(R, 0, &nt0)) {
            fprintf(err, "shellbench: method %s cannot give its triangle surface on scene %s\n", R->mt->name, sc->name);
            return SB_EXIT_INTERNAL;
        }
    }
    /* run.perturb: the start, perturbed (the reference state, probes and
     * sample grid above are the unperturbed ones) */
    perturb_start(n, R->x, sb_param(ps, "run.perturb"), (unsigned long long)sb_param_int(ps, "run.seed"));
    /* the method's contact sample points at the start against the obstacles
     * (either contact model): a point inside is refused before any work */
    char why[1024];
    const int inside = sb_problem_contact_start_check(R->prob, R->x, why, sizeof why);
    if (inside < 0) {
        fprintf(err, "shellbench: %s\n", R->ctx.err);
        return SB_EXIT_INTERNAL;
    }
    if (inside > 0) {
        fprintf(err, "shellbench: scene %s: %s\n", sc->name, why);
        return SB_EXIT_INPUT;
    }
    return RUN_GO_ON;
nomem:
    fprintf(err, "shellbench: out of memory\n");
    return SB_EXIT_INTERNAL;
}

/* The scene's reference file, if any, must be usable before the solve
 * (sb_reference_check): a record of this scene's finished, converged run
 * on this run's sample grid.  Not checked when this run writes that very
 * file (the run that makes the reference). */
static int check_reference(run_state *R, const sb_run_request *req, const char *out_path)
{
    char msg[2048], a[4096], b[4096];
    if (R->scene.reference.kind != SB_REF_FILE) return RUN_GO_ON;
    if (req->makes_reference || (out_path && sb_run_same_path(out_path, R->scene.reference.file, a, b, sizeof a)))
        return RUN_GO_ON;
    if (sb_reference_check(&R->scene, R->rec.sample_st, R->rec.n_samples, req->allow_unsealed_reference, msg,
                           sizeof msg)) {
        fprintf(R->err, "shellbench: %s\n", msg);
        return SB_EXIT_INPUT;
    }
    return RUN_GO_ON;
}

/* The first step to run: 1, or (--resume) the one after the checkpoint's
 * last completed step.  A finished record means nothing to do: its status
 * is the exit code. */
static int start_or_resume(run_state *R, const sb_run_request *req, const char *out_path, int *first_step)
{
    FILE *err = R->err;
    char msg[2048];
    R->rec.status = 0;
    sb_run_mark_boundary(R, 0);
    *first_step = 1;
    if (!req->resume) return RUN_GO_ON;
    if (access(out_path, F_OK) == 0) {
        sb_record_summary done_s;
        if (sb_record_read_summary(out_path, &done_s, msg, sizeof msg) == SB_OK) {
            /* the verdict is the record's: its status and, with --strict, its validation */
            int code = sb_run_recorded_exit(done_s.status, done_s.validation, req->strict);
            if (!req->quiet)
                sb_escape_print(err, "shellbench: %s is already recorded (%s, validation %s): nothing to resume%s", out_path,
                                done_s.reason_name, done_s.validation[0] ? done_s.validation : "not recorded",
                                code == SB_EXIT_VALIDATION ? "; --strict: validation failed, exit 5 as the run that wrote it" : "");
            sb_record_summary_free(&done_s);
            return code;
        }
        sb_escape_print(err, "shellbench: warning: %s exists but is no readable record (%s): running again", out_path, msg);
    }
    int k = sb_run_resume(R, req->quiet);
    if (k < 0) return SB_EXIT_INPUT;
    *first_step = k + 1;
    return RUN_GO_ON;
}

/* The end of set-up: its event (SB_EV_SETUP, from the start of the process;
 * a resumed process's set-up is in the resume log instead, sb_run_resume),
 * the peak resident size so far and the memory estimate. */
static int end_setup(run_state *R)
{
    sb_stats *stats = &R->ctx.stats;
    if (!R->resumed) sb_stats_event(stats, sb_problem_finest(R->prob), SB_EV_SETUP, R->t_start);
    sb_stats_close_all(stats);
    stats->peak_rss_setup = sb_peak_rss();
    stats->mem_estimate = R->mem_estimate;
    return RUN_GO_ON;
}

/* Exclusive seconds so far of the parts a step record keeps (sb_step_record):
 * assembly, analyze, factorize, solve, contact, adapt, record, checkpoint. */
static void step_parts(const sb_stats *s, double out[8])
{
    out[0] = sb_stats_self_total(s, SB_EV_ENERGY) + sb_stats_self_total(s, SB_EV_GRADIENT) +
             sb_stats_self_total(s, SB_EV_HESSIAN);
    out[1] = sb_stats_self_total(s, SB_EV_ANALYZE);
    out[2] = sb_stats_self_total(s, SB_EV_FACTORIZE);
    out[3] = sb_stats_self_total(s, SB_EV_SOLVE);
    out[4] = sb_stats_self_total(s, SB_EV_COLLIDE);
    out[5] = sb_stats_self_total(s, SB_EV_ADAPT);
    out[6] = sb_stats_self_total(s, SB_EV_RECORD);
    out[7] = sb_stats_self_total(s, SB_EV_CHECKPOINT);
}

/* The parts since p0 into the last step record. */
static void step_parts_into(sb_stats *s, const double p0[8])
{
    if (!s->n_steps) return;
    double p[8];
    step_parts(s, p);
    sb_step_record *r = &s->steps[s->n_steps - 1];
    r->seconds_assembly = p[0] - p0[0];
    r->seconds_analyze = p[1] - p0[1];
    r->seconds_factorize = p[2] - p0[2];
    r->seconds_solve = p[3] - p0[3];
    r->seconds_contact = p[4] - p0[4];
    r->seconds_adapt = p[5] - p0[5];
    r->seconds_record = p[6] - p0[6];
    r->seconds_checkpoint = p[7] - p0[7];
}

/* The time / load steps from first_step on; stops at the first step that
 * does not converge (recorded) or after --stop-after-steps. */
static int run_steps(run_state *R, const sb_run_request *req, int first_step)
{
    FILE *err = R->err;
    const sb_scene *sc = &R->scene;
    const sb_paramset *ps = &R->ctx.params;
    sb_stats *stats = &R->ctx.stats;
    sb_run *rec = &R->rec;
    const int F = sb_problem_finest(R->prob);
    int n = sb_problem_n(R->prob, F);
    for (int step = first_step; step <= sc->time.steps; step++) {
        R->material_current = 0;   /* x changes from here on */
        sb_stats_close_all(stats);
        double t0 = sb_now(), parts0[8];
        step_parts(stats, parts0);
        double wa0 = stats->work_assembly, wq0 = stats->work_qp;
        int code = sb_run_adapt(R, step, &n);   /* adaptive meshes (sb_method.h adapt) */
        if (code >= 0) return code;
        /* the step's own work outside every other event (SB_EV_SOLVER): its
         * set-up, the solver's vector operations and bookkeeping */
        const double tsolver = sb_stats_begin(stats);
        sb_step_info si;
        sb_run_step_info(sc, step, &si);
        sb_copy(n, R->x, R->xn);
        int rc = sb_problem_begin_step(R->prob, &si, R->xn, R->v, R->x);
        if (rc < 0) {
            fprintf(err, "shellbench: step %d: %s\n", step, R->ctx.err);
            return SB_EXIT_INTERNAL;
        }
        if (sb_problem_take_pattern_change(R->prob)) {
            /* self-contact replaced a sparsity pattern (docs/contact.md): the
               solver's pattern-bound data are allocated anew, as after an
               adaptation */
            R->stype->free(R->ss);
            memset(R->ss, 0, R->stype->state_size);
            if ((rc = R->stype->alloc(R->ss, R->prob, &R->ctx.params))) {
                fprintf(err, "shellbench: step %d: %s\n", step, R->ctx.err);
                return SB_EXIT_INTERNAL;
            }
        }
        /* a moving obstacle that sweeps through the cloth within the step is
         * invisible to the barrier (it sees the step's end only): the run
         * stops here with the reason recorded (docs/contact.md) */
        const int swept = sb_problem_contact_swept(R->prob, step, R->xn, rec->contact_stop, sizeof rec->contact_stop);
        /* lifting of boundary motion; not for the single-step solver, which is
         * by definition one Newton step from x_n */
        if (!swept && sb_param_int(ps, "run.lifting") && !(R->stype->flags & SB_SOLVER_SINGLE_STEP) &&
            (rc = sb_problem_lift(R->prob, R->xn, R->x, R->stype->linear_solve, R->ss)) < 0) {
            fprintf(err, "shellbench: step %d: %s\n", step, R->ctx.err);
            return SB_EXIT_INTERNAL;
        }
        sb_step_outcome o;
        sb_reason reason;
        if (swept) {
            memset(&o, 0, sizeof o);
            o.f = o.gnorm = o.g0 = o.force_scale = o.gstop = NAN;
            o.gnoise = 0.0;
            reason = o.reason = SB_REASON_OBSTACLE_SWEPT;
            sb_copy(n, R->xn, R->x);   /* the state stays at the step's start */
            if (!req->quiet) fprintf(err, "shellbench: %s\n", rec->contact_stop);
        } else
            reason = sb_solve_step_ex(R->stype, R->ss, R->prob, ps, step, R->x, &o);
        const int iters = o.iterations;
        const double f = o.f, gn = o.gnorm;
        sb_run_progress_clear(R);
        if (sb_reason_converged(reason) && sb_problem_has_impulse(R->prob)) {
            /* contact.model = "impulse": the method's collision response on
               the accepted step (docs/contact.md), before v follows */
            rc = sb_problem_impulse(R->prob, si.t, R->xn, R->x, &rec->impulse);
            if (rc < 0) {
                fprintf(err, "shellbench: step %d: %s\n", step, R->ctx.err);
                return SB_EXIT_INTERNAL;
            }
            if (rc == SB_NONFINITE) reason = SB_REASON_NONFINITE;
            rec->has_impulse = 1;
            rec->impulse.counted_steps++;
            /* what the response left between its points (issue 37) */
            sb_contact_report cr;
            double spacing;
            if (sb_problem_contact_report(R->prob, R->x, &cr, &spacing) > 0) sb_run_contact_between(R, step, &cr, spacing);
        }
        if (sc->time.mode == SB_TIME_DYNAMIC)
            for (int i = 0; i < n; i++) R->v[i] = (R->x[i] - R->xn[i]) / sc->time.dt;   /* v_{n+1} = (x - x_n)/dt */
        sb_stats_event(stats, F, SB_EV_SOLVER, tsolver);
        double tr0 = sb_stats_begin(stats);
        /* a converged step must also be a physical state (finite, strains
         * within run.strain_max); the probes and triangles of the step */
        double tsm = sb_stats_begin(stats);
        reason = sb_run_judge_step(R, reason);
        int n_tris = 0;
        if (sb_run_record_mesh(R, step, &n_tris)) {
            fprintf(err, "shellbench: step %d: method %s cannot give its triangle surface\n", step, R->mt->name);
            return SB_EXIT_INTERNAL;
        }
        if (R->mt->eval_points) sb_run_record_probes(R, step);
        sb_stats_event(stats, F, SB_EV_SAMPLES, tsm);
        sb_step_record sr = { step, si.t, iters, reason, f, gn, 0, stats->work_assembly - wa0, stats->work_qp - wq0,
                              o.force_scale, o.gstop, o.gnoise, n, n_tris, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
        sr.seconds = tr0 - t0;
        sr.peak_rss = sb_peak_rss();
        sb_stats_push_step(stats, &sr);
        rec->steps_done = step;
        if (sb_problem_has_contact(R->prob)) {
            /* contact: distances of the step's end state (docs/contact.md) */
            sb_contact_report cr;
            double spacing;
            rec->contact_points = sb_problem_contact_report(R->prob, R->x, &cr, &spacing);
            const double dmin = cr.min_distance;
            const int act = cr.active, ins = cr.inside;
            sb_run_contact_between(R, step, &cr, spacing);
            if (!rec->has_contact || dmin < rec->contact_min_distance) rec->contact_min_distance = dmin;
            rec->has_contact = 1;
            rec->contact_active = act;
            rec->contact_inside = ins;
            rec->contact_steps_inside += ins > 0;
            int pairs, sact, cross;
            double sdmin;
            if (sb_problem_self_measure(R->prob, R->x, &pairs, &sact, &sdmin, &cross)) {
                if (!rec->has_self || sdmin < rec->self_min_distance) rec->self_min_distance = sdmin;
                rec->has_self = 1;
                rec->self_pairs = pairs;
                rec->self_active = sact;
                rec->self_steps_crossing += cross != 0;
            }
        }
        sb_stats_event(stats, F, SB_EV_RECORD, tr0);
        step_parts_into(stats, parts0);
        if (!req->quiet)
            fprintf(err, "step %d/%d: %s after %d iterations, f = %.10g, |g| = %.3g (%.3f s)\n", step, sc->time.steps,
                    sb_reason_name(reason), iters, f, gn, sr.seconds);
        rec->reason = reason;
        sb_run_fold_resume_setup(R);
        if (!sb_reason_converged(reason)) {
            rec->status = 1;
            break;
        }
        /* a resume point; written at once when the last checkpoint is a
         * tenth of run.checkpoint old, so a long step is never lost to a kill
         * (not after the last step: the record itself follows, and a
         * checkpoint there cost 1 % of a 3e5-dof plate's run, issue 42) */
        sb_run_mark_boundary(R, step);
        if (req->stop_after_steps == step && step < sc->time.steps) {
            sb_run_write_checkpoint(R);
            if (R->checkpoint_failed) return SB_EXIT_INTERNAL;
            if (!req->quiet)
                sb_escape_print(err, "shellbench: stopped after step %d of %d as asked; checkpoint %s (continue with --resume)",
                        step, sc->time.steps, R->partial_path);
            return SB_EXIT_STOPPED;
        }
        if (R->checkpoints_on && !R->checkpoint_failed && step < sc->time.steps &&
            sb_now() - R->checkpoint_last >= 0.1 * R->checkpoint_every) {
            sb_run_write_checkpoint(R);
            step_parts_into(stats, parts0);
        }
    }
    stats->seconds_total = sb_now() - R->t_start;
    return RUN_GO_ON;
}

/* Probes, samples, error and material of the final state; the record (its
 * checkpoint removed once it is in place) and the summary. */
static int finish_run(run_state *R, const sb_run_request *req, const char *out_path, FILE *out, char **summary)
{
    FILE *err = R->err;
    const sb_scene *sc = &R->scene;
    sb_stats *stats = &R->ctx.stats;
    sb_run *rec = &R->rec;
    const int F = sb_problem_finest(R->prob);
    char msg[2048];
    sb_stats_close_all(stats);
    double tr0 = sb_stats_begin(stats);
    if (R->mt->eval_points) {
        R->mt->eval_points(R->ms, F, R->x, rec->n_samples, rec->sample_st, rec->sample_pos);
        if (sb_run_validate(R)) {
            fprintf(err, "shellbench: out of memory\n");
            return SB_EXIT_INTERNAL;
        }
        sb_run_judge_penalty(R);
    }
    sb_run_judge_contact(R);
    sb_run_potential_change(R);
    sb_run_contact_coverage(R);
    sb_run_record_material(R);
    sb_run_record_energy(R);
    sb_stats_event(stats, F, SB_EV_SAMPLES, tr0);
    double te0 = sb_stats_begin(stats);
    /* the run that rewrites its scene's reference (`shellbench reference`) is
       measured against the file it replaces, if that can serve: a refusal
       is no verdict on this run (check_reference skipped it too) */
    char pa[4096], pb[4096];
    const int writes_ref = req->makes_reference || (out_path && sc->reference.kind == SB_REF_FILE &&
                                                    sb_run_same_path(out_path, sc->reference.file, pa, pb, sizeof pa));
    const int ref_refused = sb_run_compute_error(R, err, req->allow_unsealed_reference || writes_ref,
                                                 req->makes_reference) != SB_OK && !writes_ref;
    sb_stats_event(stats, F, SB_EV_ERROR, te0);
    stats->peak_rss = sb_peak_rss();
    if (out_path) {
        double tw0 = sb_stats_begin(stats);
        stats->seconds_total = tw0 - R->t_start;
        rec->write_event = SB_EV_RECORD;   /* the record holds its own write (but for closing it, sb_record.h) */
        rec->write_t0 = tw0;
        if (sb_record_write(rec, out_path, msg, sizeof msg)) {
            fprintf(err, "shellbench: %s\n", msg);
            return SB_EXIT_INPUT;
        }
        sb_run_remove_partial(R);   /* the record is in place: the checkpoint has served */
        /* the file cannot hold its own write time: the summary does */
        sb_stats_event(stats, F, SB_EV_RECORD, tw0);
        stats->seconds_total = sb_now() - R->t_start;
    } else {
        stats->seconds_total = sb_now() - R->t_start;
    }
    char *js = sb_run_summary_json(R, out_path);
    if (req->summary_json && js) fprintf(out, "%s\n", js);
    if (summary) *summary = js;
    else free(js);
    if (!req->quiet && !req->summary_json)
        sb_escape_print(err, "%s/%s/%s: %s (%s), validation %s, %ld dofs, %d of %d steps, %.3f s%s%s", sc->name, R->mt->name,
                R->stype->name, rec->status ? "NOT converged" : "converged", sb_reason_name((sb_reason)rec->reason),
                sb_validation_name(rec->validation), rec->n_dofs, rec->steps_done, rec->steps_planned,
                stats->seconds_total, out_path ? ", record " : "", out_path ? out_path : "");
    if (!req->quiet && rec->has_between && rec->contact_steps_between > 0)
        fprintf(err, "shellbench: warning: %s\n", rec->contact_coverage);
    if (!req->quiet && rec->reason == SB_REASON_CONTACT_UNRESOLVED)
        fprintf(err, "shellbench: %ld of %ld steps ended with a collision the impulse response left unresolved "
                     "(run.contact_unresolved_max = %g): the recorded states cross themselves or an obstacle\n",
                rec->impulse.unresolved_steps, rec->impulse.counted_steps,
                sb_param(&R->ctx.params, "run.contact_unresolved_max"));
    if (ref_refused) return SB_EXIT_INPUT;   /* the record is kept, without an error */
    if (rec->status) return SB_EXIT_NOT_CONVERGED;
    if (req->strict && rec->validation == SB_VALIDATION_FAILED) {
        if (!req->quiet) fprintf(err, "shellbench: --strict: validation failed (an expected probe value is out of tolerance)\n");
        return SB_EXIT_VALIDATION;
    }
    return SB_EXIT_CONVERGED;
}

int sb_run_execute(const sb_run_request *req, FILE *out, FILE *err, char **summary)
{
    if (summary) *summary = NULL;
    run_state *R = calloc(1, sizeof *R);
    if (!R) { fprintf(err, "shellbench: out of memory\n"); return SB_EXIT_INTERNAL; }
    if (sb_context_init(&R->ctx)) { free(R); fprintf(err, "shellbench: out of memory\n"); return SB_EXIT_INTERNAL; }
    R->err = err;
    sb_output_lock_init(&R->lock);
    R->t_start = sb_stats_begin(&R->ctx.stats);   /* the set-up event (SB_EV_SETUP), closed by end_setup */
    R->ctx.stats.peak_rss_start = sb_peak_rss();
    sb_run_progress_init(R, req);
    R->ctx.monitor = sb_run_monitor;
    R->ctx.monitor_data = R;
    R->n_grid = req->sample_n > 0 ? req->sample_n : 21;

    int levels = 1, first_step = 1, code;
    const char *out_path = NULL;
    char auto_path[1024];
    if ((code = resolve_request(R, req, &levels)) == RUN_GO_ON &&
        (code = sb_run_resolve_res(R, req)) == RUN_GO_ON &&
        (code = sb_run_check_memory(R, levels)) == RUN_GO_ON &&
        (code = sb_run_prepare_output(R, req, levels, &out_path, auto_path, sizeof auto_path)) == RUN_GO_ON &&
        (code = prepare_run(R, levels)) == RUN_GO_ON &&
        (code = sb_run_adapt_check(R, req)) == RUN_GO_ON &&
        (code = check_reference(R, req, out_path)) == RUN_GO_ON &&
        (code = start_or_resume(R, req, out_path, &first_step)) == RUN_GO_ON &&
        (code = end_setup(R)) == RUN_GO_ON &&
        (code = run_steps(R, req, first_step)) == RUN_GO_ON)
        code = finish_run(R, req, out_path, out, summary);
    sb_run_progress_clear(R);
    run_cleanup(R);
    free(R);
    return code;
}
