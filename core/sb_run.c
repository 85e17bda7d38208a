/* sb_run.c — one run, end to end: scene -> method -> problem -> solver ->
 * record (sb_run.h).  All statistics come from the core wrappers. */
#include "sb_run.h"
#include "sb_context.h"
#include "sb_geometry.h"
#include "sb_record.h"
#include "sb_solver.h"
#include "sb_sysinfo.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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
    /* checkpoints (run.checkpoint): the record so far, written to
     * partial_path every checkpoint_every seconds by the loop's monitor */
    FILE *err;
    double t_start, checkpoint_every, checkpoint_last;
    int checkpoint_failed;
    char partial_path[1100];
    /* the last completed step: the resume point the checkpoints carry */
    sb_resume_point bp;
} run_state;

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
    free(R->probe_names);
    if (R->scene_loaded) sb_scene_free(&R->scene);
    sb_context_free(&R->ctx);
}

static int mkdir_p(const char *path)
{
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s", path);
    for (char *p = tmp + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0777) && errno != EEXIST) return -1;
            *p = '/';
        }
    return 0;
}

/* Sample grid (n x n in (s,t), points inside the domain) and its triangles. */
static int build_samples(run_state *R)
{
    const int n = R->n_grid;
    int *idx = malloc((size_t)n * n * sizeof *idx);
    R->rec.sample_st = malloc((size_t)n * n * 2 * sizeof(double));
    R->rec.tris = malloc((size_t)(n - 1) * (n - 1) * 6 * sizeof(int));
    if (!idx || !R->rec.sample_st || !R->rec.tris) { free(idx); return SB_ERR_NOMEM; }
    int m = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double s = (double)i / (n - 1), t = (double)j / (n - 1);
            idx[j * n + i] = -1;
            if (!sb_domain_contains_st(&R->scene.domain, s, t)) continue;
            R->rec.sample_st[2 * m] = s;
            R->rec.sample_st[2 * m + 1] = t;
            idx[j * n + i] = m++;
        }
    int nt = 0;
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            int a = idx[j * n + i], b = idx[j * n + i + 1], c = idx[(j + 1) * n + i], d = idx[(j + 1) * n + i + 1];
            if (a < 0 || b < 0 || c < 0 || d < 0) continue;
            /* skip cells whose centre is outside (L-shape notch) */
            if (!sb_domain_contains_st(&R->scene.domain, (i + 0.5) / (n - 1), (j + 0.5) / (n - 1))) continue;
            int *T = R->rec.tris + 3 * nt;
            T[0] = a; T[1] = b; T[2] = d; T[3] = a; T[4] = d; T[5] = c;
            nt += 2;
        }
    free(idx);
    R->rec.n_samples = m;
    R->rec.n_tris = nt;
    R->rec.sample_ref = malloc((size_t)(m ? m : 1) * 3 * sizeof(double));
    R->rec.sample_pos = malloc((size_t)(m ? m : 1) * 3 * sizeof(double));
    return R->rec.sample_ref && R->rec.sample_pos ? SB_OK : SB_ERR_NOMEM;
}

static void step_info(const sb_scene *sc, int step, sb_step_info *si)
{
    memset(si, 0, sizeof *si);
    si->step = step;
    si->n_steps = sc->time.steps;
    si->dt = sc->time.mode == SB_TIME_DYNAMIC ? sc->time.dt : 0.0;
    si->t = sc->time.mode == SB_TIME_DYNAMIC ? step * sc->time.dt : (double)step;
    for (int i = 0; i < sc->n_loads; i++) si->load_factor[i] = sb_load_factor(sc, &sc->loads[i], step);
    for (int i = 0; i < sc->n_bcs; i++) si->motion_factor[i] = sb_bc_motion_factor(sc, &sc->bcs[i], step);
}

static double probe_rel_error(const sb_probe *p, const double u[3])
{
    if (!p->has_expected) return NAN;
    if (p->expected_component < 0) {
        double num = 0, den = 0;
        for (int k = 0; k < 3; k++) {
            num += (u[k] - p->expected[k]) * (u[k] - p->expected[k]);
            den += p->expected[k] * p->expected[k];
        }
        return sqrt(num) / fmax(sqrt(den), 1e-300);
    }
    double val = p->expected_component == 3 ? sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) : u[p->expected_component];
    return fabs(val - p->expected[0]) / fmax(fabs(p->expected[0]), 1e-300);
}

static int record_probes(run_state *R, int step_slot)
{
    const sb_scene *sc = &R->scene;
    if (!sc->n_probes || !R->mt->eval_points) return SB_OK;
    double st[2 * SB_SCENE_MAX_PROBES];
    for (int p = 0; p < sc->n_probes; p++) { st[2 * p] = sc->probes[p].st[0]; st[2 * p + 1] = sc->probes[p].st[1]; }
    int F = sb_problem_finest(R->prob);
    return R->mt->eval_points(R->ms, F, R->x, sc->n_probes, st, R->rec.probe_traj + (size_t)step_slot * sc->n_probes * 3);
}

static void json_set_num(json_t *o, const char *k, double v)
{
    json_object_set_new(o, k, isfinite(v) ? json_real(v) : json_null());
}

static char *summary_json(run_state *R, const char *out_path)
{
    const sb_stats *st = &R->ctx.stats;
    json_t *o = json_object();
    json_object_set_new(o, "scene", json_string(R->scene.name));
    json_object_set_new(o, "method", json_string(R->mt->name));
    json_object_set_new(o, "solver", json_string(R->stype->name));
    json_object_set_new(o, "method_info", json_string(R->rec.method_info));
    if (R->rec.solver_info[0]) json_object_set_new(o, "solver_info", json_string(R->rec.solver_info));
    json_object_set_new(o, "dofs", json_integer(R->rec.n_dofs));
    json_object_set_new(o, "levels", json_integer(R->rec.levels));
    json_object_set_new(o, "res", json_integer(R->rec.res));
    json_object_set_new(o, "steps", json_integer(R->rec.steps_done));
    json_object_set_new(o, "steps_planned", json_integer(R->rec.steps_planned));
    json_object_set_new(o, "status", json_string(R->rec.status == 0 ? "converged" : "not_converged"));
    json_object_set_new(o, "reason", json_string(sb_reason_name((sb_reason)R->rec.reason)));
    long iters = 0;
    for (size_t i = 0; i < st->n_steps; i++) iters += st->steps[i].iterations;
    json_object_set_new(o, "iterations", json_integer(iters));
    if (st->n_steps) {
        json_set_num(o, "f", st->steps[st->n_steps - 1].f);
        json_set_num(o, "gnorm", st->steps[st->n_steps - 1].gnorm);
    }
    json_t *wu = json_object();
    json_set_num(wu, "assembly", st->work_assembly);
    json_set_num(wu, "qp", st->work_qp);
    json_object_set_new(o, "work_units", wu);
    json_t *sec = json_object();
    json_set_num(sec, "total", st->seconds_total);
    for (int e = 0; e < SB_EV_COUNT; e++) json_set_num(sec, sb_event_name((sb_event)e), sb_stats_event_total(st, (sb_event)e).seconds);
    json_object_set_new(o, "seconds", sec);
    json_t *cnt = json_object();
    for (int e = 0; e < SB_EV_COUNT; e++) json_object_set_new(cnt, sb_event_name((sb_event)e), json_integer(sb_stats_event_total(st, (sb_event)e).count));
    json_object_set_new(o, "counts", cnt);
    json_t *lin = json_object();
    int F = R->rec.levels - 1;
    json_set_num(lin, "matrix_nnz", (double)st->matrix_nnz[F]);
    json_set_num(lin, "factor_nnz", st->chol_nnz_l[F]);
    json_set_num(lin, "factor_flops", st->chol_flops[F]);
    json_object_set_new(lin, "not_posdef", json_integer(st->not_posdef));
    json_object_set_new(o, "linear_algebra", lin);
    json_t *pr = json_object();
    int last = R->rec.steps_done;
    for (int p = 0; p < R->rec.n_probes; p++) {
        json_t *q = json_object();
        const double *pos = R->rec.probe_traj + ((size_t)last * R->rec.n_probes + p) * 3;
        const double *ref = R->rec.probe_traj + (size_t)p * 3;
        json_object_set_new(q, "position", json_pack("[fff]", pos[0], pos[1], pos[2]));
        json_object_set_new(q, "displacement", json_pack("[fff]", pos[0] - ref[0], pos[1] - ref[1], pos[2] - ref[2]));
        const sb_probe *sp = &R->scene.probes[p];
        if (sp->has_expected) {
            if (sp->expected_component < 0)
                json_object_set_new(q, "expected", json_pack("[fff]", sp->expected[0], sp->expected[1], sp->expected[2]));
            else
                json_set_num(q, "expected", sp->expected[0]);
            static const char *const comp[] = { "x", "y", "z", "norm" };
            json_object_set_new(q, "component", json_string(sp->expected_component < 0 ? "vector" : comp[sp->expected_component]));
            json_set_num(q, "rel_error", R->rec.probe_rel_error[p]);
            json_set_num(q, "tol", sp->tol);
        }
        json_object_set_new(pr, sp->name, q);
    }
    json_object_set_new(o, "probes", pr);
    if (R->rec.has_material) {
        const sb_material_state *m = &R->rec.material;
        json_t *ma = json_object();
        json_object_set_new(ma, "points", json_integer(m->points));
        json_object_set_new(ma, "soft_membrane", json_integer(m->soft_membrane));
        json_object_set_new(ma, "soft_section", json_integer(m->soft_section));
        json_set_num(ma, "soft_area_fraction", m->area > 0 ? m->soft_area / m->area : 0.0);
        json_object_set_new(ma, "max_strain", json_pack("[fff]", m->max_strain[0], m->max_strain[1], m->max_strain[2]));
        json_set_num(ma, "min_rel_eig", m->min_rel_eig);
        json_object_set_new(o, "material", ma);
    } else {
        json_object_set_new(o, "material", json_null());
    }
    if (R->rec.has_error) {
        json_t *er = json_object();
        json_object_set_new(er, "kind", json_string(R->rec.error_kind));
        if (strcmp(R->rec.error_kind, "field") == 0) {
            json_set_num(er, "rms", R->rec.error_rms);
            json_set_num(er, "max", R->rec.error_max);
        } else {
            json_set_num(er, "max_probe_rel", R->rec.error_probe);
        }
        json_object_set_new(o, "error", er);
    } else {
        json_object_set_new(o, "error", json_null());
    }
    json_t *rs = json_object();
    json_object_set_new(rs, "count", json_integer(R->rec.resumed.count));
    json_object_set_new(rs, "after_steps", json_string(R->rec.resumed.steps));
    json_set_num(rs, "setup_seconds", R->rec.resumed.setup_seconds);
    json_set_num(rs, "lost_seconds", R->rec.resumed.lost_seconds);
    json_object_set_new(o, "resumed", rs);
    json_object_set_new(o, "file", out_path ? json_string(out_path) : json_null());
    char *s = json_dumps(o, JSON_INDENT(2) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(12));
    json_decref(o);
    return s;
}

/* error against the scene's reference (DESIGN.md "Accuracy") */
static void compute_error(run_state *R, FILE *err)
{
    const sb_scene *sc = &R->scene;
    sb_run *rec = &R->rec;
    double worst = 0;
    int any = 0;
    for (int p = 0; p < rec->n_probes; p++)
        if (isfinite(rec->probe_rel_error[p])) { any = 1; worst = fmax(worst, rec->probe_rel_error[p]); }
    if (sc->reference.kind == SB_REF_PROBES && any) {
        rec->has_error = 1;
        rec->error_probe = worst;
        snprintf(rec->error_kind, sizeof rec->error_kind, "probes");
    } else if (sc->reference.kind == SB_REF_FILE && rec->n_samples > 0) {
        int n = 0;
        double *st = NULL, *pos = NULL;
        char msg[512];
        if (sb_record_read_samples(sc->reference.file, &n, &st, &pos, msg, sizeof msg)) {
            fprintf(err, "shellbench: warning: reference %s unreadable, no error computed: %s\n", sc->reference.file, msg);
        } else if (n != rec->n_samples) {
            fprintf(err, "shellbench: warning: reference %s has %d sample points, this run %d: no error computed\n",
                    sc->reference.file, n, rec->n_samples);
        } else {
            double diam = sb_domain_diameter(&sc->domain), s2 = 0, mx = 0;
            for (int i = 0; i < n; i++) {
                double d2 = 0;
                for (int k = 0; k < 3; k++) d2 += (rec->sample_pos[3 * i + k] - pos[3 * i + k]) * (rec->sample_pos[3 * i + k] - pos[3 * i + k]);
                s2 += d2;
                mx = fmax(mx, sqrt(d2));
            }
            rec->has_error = 1;
            rec->error_rms = sqrt(s2 / n) / diam;
            rec->error_max = mx / diam;
            snprintf(rec->error_kind, sizeof rec->error_kind, "field");
        }
        free(st);
        free(pos);
    }
    if (!rec->has_error) snprintf(rec->error_kind, sizeof rec->error_kind, "none");
}

/* run.perturb: each dof of the start gets an offset uniform in [-a, a], from
 * a SplitMix64 stream seeded by run.seed (Steele, Lea & Flood 2014; local
 * state, so runs with the same seed are bit-identical).  Round-off-sized
 * offsets sample how much a count on a nonconvex scene owes to round-off. */
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

/* The path of a run's checkpoint: OUT.partial (its XDMF sidecar
 * OUT.partial.xdmf), so that globs for *.h5 and a sweep's resume never take
 * it for a finished record. */
static int partial_path(const char *out_path, char *buf, size_t len)
{
    return snprintf(buf, len, "%s.partial", out_path) >= (int)len ? -1 : 0;
}

/* Once the record is written, its checkpoint (this run's, or a stale one of
 * an earlier interrupted run to the same path) has served. */
static void remove_partial(run_state *R)
{
    char x[1200];
    if (!R->partial_path[0]) return;
    unlink(R->partial_path);
    if (sb_record_xdmf_path(R->partial_path, x, sizeof x) == SB_OK) unlink(x);
}

/* rec->material: where the current state strains the material (methods
 * with material_state); part of the record's time */
static void record_material(run_state *R)
{
    sb_run *rec = &R->rec;
    rec->has_material = R->mt->material_state &&
        R->mt->material_state(R->ms, sb_problem_finest(R->prob), R->x, &rec->material) == SB_OK;
}

/* Write the record so far (steps done, the iteration history including the
 * current step's, x and the sample positions now) as a checkpoint with
 * status SB_STATUS_UNFINISHED.  A failed write is a warning, once, and ends
 * the checkpoints; it never stops the run. */
static void write_checkpoint(run_state *R)
{
    sb_run *rec = &R->rec;
    sb_stats *stats = &R->ctx.stats;
    const int F = sb_problem_finest(R->prob);
    double t0 = sb_now();
    const int status = rec->status, reason = rec->reason;
    rec->status = SB_STATUS_UNFINISHED;
    rec->reason = SB_REASON_CHECKPOINT;
    rec->resume = &R->bp;
    if (R->mt->eval_points)
        R->mt->eval_points(R->ms, F, R->x, rec->n_samples, rec->sample_st, rec->sample_pos);
    record_material(R);
    stats->seconds_total = t0 - R->t_start;
    char msg[2048];
    if (sb_record_write(rec, R->partial_path, msg, sizeof msg)) {
        fprintf(R->err, "shellbench: warning: no more checkpoints: %s\n", msg);
        R->checkpoint_failed = 1;
    }
    rec->status = status;
    rec->reason = reason;
    rec->resume = NULL;
    sb_stats_event(stats, F, SB_EV_RECORD, t0);
    R->checkpoint_last = sb_now();
}

/* The end of step `step` (0: the start) as the resume point: x, v and a
 * snapshot of the statistics (history pointers left out: the boundary is
 * n_iters / n_steps records into the live history). */
static void mark_boundary(run_state *R, int step)
{
    sb_resume_point *b = &R->bp;
    b->step = step;
    b->n_x = R->rec.n_x;
    sb_copy(b->n_x, R->x, b->x);
    sb_copy(b->n_x, R->v, b->v);
    b->stats = R->ctx.stats;
    b->stats.iters = NULL;
    b->stats.steps = NULL;
    b->stats.cap_iters = b->stats.cap_steps = 0;
    b->seconds = sb_now() - R->t_start;
}

/* "a,b" + ",c" into a fixed buffer (kept whole or left as it was) */
static void list_append(char *buf, size_t len, const char *item)
{
    size_t u = strlen(buf);
    if (u + strlen(item) + 2 <= len) snprintf(buf + u, len - u, "%s%s", u ? "," : "", item);
}

/* --resume: continue from the resume point of OUT.partial.  No checkpoint:
 * the run starts at step 1 (0).  A checkpoint of another run, or an
 * unreadable one, is an input error (-1) and stays untouched.  Statistics
 * become the checkpoint's at its boundary (set-up of this process is in
 * the resume log, not in the event counts, so the counts equal those of an
 * uninterrupted run); seconds_total goes on from the boundary. */
static int resume_run(run_state *R, int quiet)
{
    sb_run *rec = &R->rec;
    if (access(R->partial_path, F_OK) != 0) {
        if (!quiet) fprintf(R->err, "shellbench: no checkpoint %s: starting at step 1\n", R->partial_path);
        return 0;
    }
    sb_resume_point rp;
    sb_resume_log log;
    double ck_seconds = 0, setup = sb_now() - R->t_start;
    char ck_build[64] = "", msg[2048];
    if (sb_record_read_resume(R->partial_path, rec, &rp, &ck_seconds, ck_build, sizeof ck_build, &log, rec->probe_traj,
                              msg, sizeof msg)) {
        fprintf(R->err, "shellbench: %s\n", msg);
        return -1;
    }
    sb_stats *st = &R->ctx.stats;
    memcpy(st->ev, rp.stats.ev, sizeof st->ev);
    st->work_assembly = rp.stats.work_assembly;
    st->work_qp = rp.stats.work_qp;
    st->not_posdef = rp.stats.not_posdef;
    st->n_iters = st->n_steps = 0;
    int bad = 0;
    for (size_t i = 0; i < rp.stats.n_iters && !bad; i++) bad = sb_stats_push_iter(st, &rp.stats.iters[i]);
    for (size_t i = 0; i < rp.stats.n_steps && !bad; i++) bad = sb_stats_push_step(st, &rp.stats.steps[i]);
    if (bad) {
        sb_resume_point_free(&rp);
        fprintf(R->err, "shellbench: out of memory\n");
        return -1;
    }
    sb_copy(rp.n_x, rp.x, R->x);
    sb_copy(rp.n_x, rp.v, R->v);
    rec->steps_done = rp.step;
    rec->reason = rp.step > 0 ? rp.stats.steps[rp.step - 1].reason : SB_REASON_NONE;
    char item[32];
    snprintf(item, sizeof item, "%d", rp.step);
    rec->resumed = log;
    rec->resumed.count++;
    list_append(rec->resumed.steps, sizeof rec->resumed.steps, item);
    rec->resumed.setup_seconds += setup;
    rec->resumed.lost_seconds += fmax(ck_seconds - rp.seconds, 0.0);
    if (strcmp(ck_build, rec->build_id) && !strstr(rec->resumed.builds, ck_build)) {
        list_append(rec->resumed.builds, sizeof rec->resumed.builds, ck_build);
        fprintf(R->err, "shellbench: warning: resuming a checkpoint of build %s with build %s (recorded in resume_builds)\n",
                ck_build, rec->build_id);
    }
    R->t_start -= rp.seconds;   /* seconds_total: the boundary's, then this process's */
    if (!quiet)
        fprintf(R->err, "shellbench: resuming %s after step %d of %d (%ld iterations recorded)\n", R->partial_path,
                rp.step, rec->steps_planned, (long)rp.stats.n_iters);
    sb_resume_point_free(&rp);
    mark_boundary(R, rec->steps_done);
    return rec->steps_done;
}

/* sb_context.monitor: after every iteration of the outer loop */
static void checkpoint_monitor(void *data, const sb_iter_record *r)
{
    (void)r;
    run_state *R = data;
    if (!R->checkpoint_failed && sb_now() - R->checkpoint_last >= R->checkpoint_every) write_checkpoint(R);
}

int sb_run_execute(const sb_run_request *req, FILE *out, FILE *err, char **summary)
{
    run_state *R = calloc(1, sizeof *R);
    if (!R) { fprintf(err, "shellbench: out of memory\n"); return SB_EXIT_INTERNAL; }
    int exit_code = SB_EXIT_INTERNAL, rc;
    char path[1024], msg[2048];
    if (summary) *summary = NULL;
    if (sb_context_init(&R->ctx)) { free(R); fprintf(err, "shellbench: out of memory\n"); return SB_EXIT_INTERNAL; }
    R->err = err;
    R->t_start = sb_now();
    R->n_grid = req->sample_n > 1 ? req->sample_n : 21;

    /* scene */
    if (sb_scene_resolve(req->scene, path, sizeof path)) {
        fprintf(err, "shellbench: scene \"%s\" not found (neither a file nor a name in bench/scenes; try `shellbench list scenes`)\n", req->scene);
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    if (sb_scene_load(path, &R->scene, msg, sizeof msg)) {
        fprintf(err, "%s\n", msg);
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    R->scene_loaded = 1;

    /* method and solver, and whether they fit together */
    R->mt = sb_method_find(req->method);
    R->stype = sb_solver_find(req->solver);
    if (!R->mt || !R->stype) {
        fprintf(err, "shellbench: unknown %s \"%s\" (see `shellbench list %s`)\n", !R->mt ? "method" : "solver",
                !R->mt ? req->method : req->solver, !R->mt ? "methods" : "solvers");
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    int levels = req->levels > 0 ? req->levels : 1;
    if ((R->stype->flags & SB_SOLVER_NEEDS_HIERARCHY) && !(R->mt->flags & SB_METHOD_HIERARCHY)) {
        fprintf(err, "shellbench: solver %s needs a level hierarchy (prolongation, restriction, projection), "
                     "but method %s provides none\n", R->stype->name, R->mt->name);
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    if ((R->stype->flags & SB_SOLVER_NEEDS_HIERARCHY) && levels < 2) {
        fprintf(err, "shellbench: solver %s needs at least 2 levels, but --levels is %d\n", R->stype->name, levels);
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    if (levels > 1 && !(R->mt->flags & SB_METHOD_HIERARCHY)) {
        fprintf(err, "shellbench: --levels %d asks for a hierarchy, but method %s has none\n", levels, R->mt->name);
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    if (levels > SB_MAX_LEVELS || req->res < 0) {
        fprintf(err, "shellbench: --levels must be in [1, %d] and --res >= 0\n", SB_MAX_LEVELS);
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    if (!(R->mt->flags & SB_METHOD_POTENTIAL) && !(R->stype->flags & SB_SOLVER_SINGLE_STEP)) {
        fprintf(err, "shellbench: method %s has no energy potential (lagged forces); solver %s needs one: use linearized\n",
                R->mt->name, R->stype->name);
        exit_code = SB_EXIT_INPUT;
        goto done;
    }

    /* parameters: declared tables, then overrides */
    sb_paramset *ps = &R->ctx.params;
    if (sb_paramset_add(ps, "run", sb_solve_params) || sb_paramset_add(ps, "solver", R->stype->params) ||
        sb_paramset_add(ps, "method", R->mt->params)) {
        fprintf(err, "shellbench: internal error: too many parameters\n");
        goto done;
    }
    for (int i = 0; i < req->n_sets; i++)
        if (sb_paramset_set(ps, req->sets[i], msg, sizeof msg)) {
            fprintf(err, "shellbench: %s\n", msg);
            exit_code = SB_EXIT_INPUT;
            goto done;
        }

    /* method -> problem -> solver */
    R->ms = calloc(1, R->mt->state_size);
    if (!R->ms) goto nomem;
    sb_method_config cfg = { req->res, levels, ps, &R->ctx };
    rc = R->mt->create(R->ms, &R->scene, &cfg);
    R->ms_created = 1;
    if (rc) {
        fprintf(err, "shellbench: method %s on scene %s: %s\n", R->mt->name, R->scene.name,
                R->ctx.err[0] ? R->ctx.err : "set-up failed");
        exit_code = rc == SB_ERR_INPUT || rc == SB_ERR_UNSUPPORTED ? SB_EXIT_INPUT : SB_EXIT_INTERNAL;
        goto done;
    }
    rc = sb_problem_create(&R->ctx, R->mt, R->ms, &R->scene, &R->prob);
    if (rc) {
        fprintf(err, "shellbench: %s\n", R->ctx.err);
        exit_code = rc == SB_ERR_UNSUPPORTED || rc == SB_ERR_INPUT ? SB_EXIT_INPUT : SB_EXIT_INTERNAL;
        goto done;
    }
    R->ss = calloc(1, R->stype->state_size);
    if (!R->ss) goto nomem;
    rc = R->stype->alloc(R->ss, R->prob, ps);
    R->ss_allocated = 1;
    if (rc) {
        fprintf(err, "shellbench: solver %s: %s\n", R->stype->name, R->ctx.err[0] ? R->ctx.err : "allocation failed");
        exit_code = rc == SB_ERR_UNSUPPORTED || rc == SB_ERR_INPUT ? SB_EXIT_INPUT : SB_EXIT_INTERNAL;
        goto done;
    }

    const int F = sb_problem_finest(R->prob), n = sb_problem_n(R->prob, F);
    const sb_scene *sc = &R->scene;
    R->x = malloc((size_t)n * sizeof(double));
    R->xn = malloc((size_t)n * sizeof(double));
    R->v = calloc((size_t)n, sizeof(double));
    R->xref = malloc((size_t)n * sizeof(double));
    R->bp.x = malloc((size_t)n * sizeof(double));
    R->bp.v = malloc((size_t)n * sizeof(double));
    R->rec.probe_traj = calloc(((size_t)sc->time.steps + 1) * (sc->n_probes ? sc->n_probes : 1) * 3, sizeof(double));
    R->rec.probe_expected = malloc((size_t)(sc->n_probes ? sc->n_probes : 1) * 3 * sizeof(double));
    R->rec.probe_rel_error = malloc((size_t)(sc->n_probes ? sc->n_probes : 1) * sizeof(double));
    R->probe_names = calloc((size_t)(sc->n_probes ? sc->n_probes : 1), sizeof *R->probe_names);
    if (!R->x || !R->xn || !R->v || !R->xref || !R->bp.x || !R->bp.v || !R->rec.probe_traj || !R->rec.probe_expected ||
        !R->rec.probe_rel_error || !R->probe_names || build_samples(R))
        goto nomem;
    R->mt->initial(R->ms, F, R->x);
    sb_copy(n, R->x, R->xref);

    /* record identity */
    sb_run *rec = &R->rec;
    snprintf(rec->scene_name, sizeof rec->scene_name, "%s", sc->name);
    snprintf(rec->scene_path, sizeof rec->scene_path, "%s", sc->path);
    rec->scene_json = sc->json_text;
    snprintf(rec->method, sizeof rec->method, "%s", R->mt->name);
    snprintf(rec->solver, sizeof rec->solver, "%s", R->stype->name);
    if (R->mt->describe) R->mt->describe(R->ms, rec->method_info, sizeof rec->method_info);
    if (R->stype->describe) R->stype->describe(R->ss, rec->solver_info, sizeof rec->solver_info);
    rec->res = req->res;
    rec->levels = sb_problem_levels(R->prob);
    rec->n_dofs = n;
    rec->params = ps;
    sb_sysinfo_build_id(rec->build_id, sizeof rec->build_id);
    sb_sysinfo_cpu_model(rec->cpu_model, sizeof rec->cpu_model);
    rec->n_cores = sb_sysinfo_cores();
    sb_sysinfo_now_iso(rec->started, sizeof rec->started);
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
    rec->n_x = n;
    rec->x_final = R->x;
    if (R->mt->eval_points) {
        if (record_probes(R, 0) ||
            R->mt->eval_points(R->ms, F, R->x, rec->n_samples, rec->sample_st, rec->sample_ref)) {
            fprintf(err, "shellbench: method %s cannot evaluate the probes / sample grid of scene %s\n", R->mt->name, sc->name);
            exit_code = SB_EXIT_INTERNAL;
            goto done;
        }
    } else {
        rec->n_samples = 0;
        rec->n_tris = 0;
    }

    /* run.perturb: the start, perturbed (the reference state, probes and
     * sample grid above are the unperturbed ones) */
    perturb_start(n, R->x, sb_param(ps, "run.perturb"), (unsigned long long)sb_param_int(ps, "run.seed"));

    /* where the record goes: its directory is made now, so that a run that
     * cannot be recorded fails before it computes anything */
    const char *out_path = NULL;
    char auto_path[1024];
    if (!req->out) {
        snprintf(auto_path, sizeof auto_path, "results/runs/%s-%s-%s-r%d-l%d.h5", sc->name, R->mt->name, R->stype->name,
                 req->res, rec->levels);
        out_path = auto_path;
    } else if (strcmp(req->out, "none") != 0) {
        out_path = req->out;
    }
    if (!out_path && (req->resume || req->stop_after_steps > 0)) {
        fprintf(err, "shellbench: %s needs a record path (--out), not --out none\n",
                req->resume ? "--resume" : "--stop-after-steps");
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    if (out_path && mkdir_p(out_path)) {
        fprintf(err, "shellbench: cannot create the directory of %s: %s\n", out_path, strerror(errno));
        exit_code = SB_EXIT_INPUT;
        goto done;
    }
    R->checkpoint_every = sb_param(ps, "run.checkpoint");
    if (out_path && partial_path(out_path, R->partial_path, sizeof R->partial_path)) R->partial_path[0] = 0;
    if (R->partial_path[0] && R->checkpoint_every > 0) {
        R->checkpoint_last = sb_now();
        R->ctx.monitor = checkpoint_monitor;
        R->ctx.monitor_data = R;
    }

    /* time / load stepping, from the start or from a checkpoint's last step */
    sb_stats *stats = &R->ctx.stats;
    sb_reason reason = SB_REASON_NONE;
    rec->status = 0;
    mark_boundary(R, 0);
    int first_step = 1;
    if (req->resume) {
        if (access(out_path, F_OK) == 0) {
            sb_record_summary done_s;
            if (sb_record_read_summary(out_path, &done_s, msg, sizeof msg) == SB_OK) {
                if (!req->quiet) fprintf(err, "shellbench: %s is already recorded (%s): nothing to resume\n", out_path, done_s.reason_name);
                exit_code = done_s.status == 0 ? SB_EXIT_CONVERGED : SB_EXIT_NOT_CONVERGED;
                sb_record_summary_free(&done_s);
                goto done;
            }
            fprintf(err, "shellbench: warning: %s exists but is no readable record (%s): running again\n", out_path, msg);
        }
        int k = resume_run(R, req->quiet);
        if (k < 0) {
            exit_code = SB_EXIT_INPUT;
            goto done;
        }
        first_step = k + 1;
    }
    for (int step = first_step; step <= sc->time.steps; step++) {
        double t0 = sb_now();
        double wa0 = stats->work_assembly, wq0 = stats->work_qp;
        sb_step_info si;
        step_info(sc, step, &si);
        sb_copy(n, R->x, R->xn);
        rc = sb_problem_begin_step(R->prob, &si, R->xn, R->v, R->x);
        if (rc < 0) {
            fprintf(err, "shellbench: step %d: %s\n", step, R->ctx.err);
            exit_code = SB_EXIT_INTERNAL;
            goto done;
        }
        /* lifting of boundary motion; not for the single-step solver, which is
         * by definition one Newton step from x_n */
        if (sb_param_int(ps, "run.lifting") && !(R->stype->flags & SB_SOLVER_SINGLE_STEP) &&
            (rc = sb_problem_lift(R->prob, R->xn, R->x)) < 0) {
            fprintf(err, "shellbench: step %d: %s\n", step, R->ctx.err);
            exit_code = SB_EXIT_INTERNAL;
            goto done;
        }
        int iters = 0;
        double f = 0, gn = 0;
        reason = sb_solve_step(R->stype, R->ss, R->prob, ps, step, R->x, &iters, &f, &gn);
        if (sc->time.mode == SB_TIME_DYNAMIC)
            for (int i = 0; i < n; i++) R->v[i] = (R->x[i] - R->xn[i]) / sc->time.dt;   /* v_{n+1} = (x - x_n)/dt */
        double tr0 = sb_now();
        sb_step_record sr = { step, si.t, iters, reason, f, gn, 0, stats->work_assembly - wa0, stats->work_qp - wq0 };
        sr.seconds = tr0 - t0;
        sb_stats_push_step(stats, &sr);
        rec->steps_done = step;
        if (R->mt->eval_points) record_probes(R, step);
        sb_stats_event(stats, F, SB_EV_RECORD, tr0);
        if (!req->quiet)
            fprintf(err, "step %d/%d: %s after %d iterations, f = %.10g, |g| = %.3g (%.3f s)\n", step, sc->time.steps,
                    sb_reason_name(reason), iters, f, gn, sr.seconds);
        rec->reason = reason;
        if (!sb_reason_converged(reason)) {
            rec->status = 1;
            break;
        }
        /* a resume point; written at once when the last checkpoint is a
         * tenth of run.checkpoint old, so a long step is never lost to a kill */
        mark_boundary(R, step);
        if (req->stop_after_steps == step && step < sc->time.steps) {
            write_checkpoint(R);
            if (R->checkpoint_failed) {
                exit_code = SB_EXIT_INTERNAL;
                goto done;
            }
            if (!req->quiet)
                fprintf(err, "shellbench: stopped after step %d of %d as asked; checkpoint %s (continue with --resume)\n",
                        step, sc->time.steps, R->partial_path);
            exit_code = SB_EXIT_STOPPED;
            goto done;
        }
        if (R->ctx.monitor && !R->checkpoint_failed && sb_now() - R->checkpoint_last >= 0.1 * R->checkpoint_every)
            write_checkpoint(R);
    }
    stats->seconds_total = sb_now() - R->t_start;

    /* results: probes, samples, error, record */
    double tr0 = sb_now();
    if (R->mt->eval_points) {
        R->mt->eval_points(R->ms, F, R->x, rec->n_samples, rec->sample_st, rec->sample_pos);
        for (int p = 0; p < rec->n_probes; p++) {
            const double *pos = rec->probe_traj + ((size_t)rec->steps_done * rec->n_probes + p) * 3;
            const double *ref = rec->probe_traj + (size_t)p * 3;
            double u[3] = { pos[0] - ref[0], pos[1] - ref[1], pos[2] - ref[2] };
            rec->probe_rel_error[p] = probe_rel_error(&sc->probes[p], u);
        }
    }
    compute_error(R, err);
    record_material(R);
    if (out_path) {
        sb_stats_event(stats, F, SB_EV_RECORD, tr0);
        stats->seconds_total = sb_now() - R->t_start;
        double tw0 = sb_now();
        if (sb_record_write(rec, out_path, msg, sizeof msg)) {
            fprintf(err, "shellbench: %s\n", msg);
            exit_code = SB_EXIT_INPUT;
            goto done;
        }
        remove_partial(R);   /* the record is in place: the checkpoint has served */
        /* the file cannot hold its own write time: the summary does */
        sb_stats_event(stats, F, SB_EV_RECORD, tw0);
        stats->seconds_total = sb_now() - R->t_start;
    } else {
        sb_stats_event(stats, F, SB_EV_RECORD, tr0);
        stats->seconds_total = sb_now() - R->t_start;
    }
    char *js = summary_json(R, out_path);
    if (req->summary_json && js) fprintf(out, "%s\n", js);
    if (summary) *summary = js;
    else free(js);
    if (!req->quiet && !req->summary_json)
        fprintf(err, "%s/%s/%s: %s (%s), %ld dofs, %d of %d steps, %.3f s%s%s\n", sc->name, R->mt->name, R->stype->name,
                rec->status ? "NOT converged" : "converged", sb_reason_name((sb_reason)rec->reason), rec->n_dofs,
                rec->steps_done, rec->steps_planned, stats->seconds_total, out_path ? ", record " : "", out_path ? out_path : "");
    exit_code = rec->status ? SB_EXIT_NOT_CONVERGED : SB_EXIT_CONVERGED;
    goto done;
nomem:
    fprintf(err, "shellbench: out of memory\n");
    exit_code = SB_EXIT_INTERNAL;
done:
    run_cleanup(R);
    free(R);
    return exit_code;
}
