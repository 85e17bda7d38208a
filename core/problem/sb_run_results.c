/* sb_run_results.c — what a run reports besides its iterations: the sample
 * grid, probes, the error against the scene's reference, the material state
 * and the JSON summary (sb_run_state.h). */
#include "sb_run_state.h"
#include "sb_geometry.h"
#include "sb_reference.h"
#include "sb_surface.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

/* Sample grid (n x n in (s,t), points inside the domain) and its triangles. */
int sb_run_build_samples(run_state *R)
{
    const int n = R->n_grid;
    if (n < 2 || n > SB_RUN_MAX_SAMPLES) return SB_ERR_INPUT;   /* n * n * 6 stays far inside int */
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

void sb_run_step_info(const sb_scene *sc, int step, sb_step_info *si)
{
    memset(si, 0, sizeof *si);
    si->step = step;
    si->n_steps = sc->time.steps;
    si->dt = sc->time.mode == SB_TIME_DYNAMIC ? sc->time.dt : 0.0;
    si->t = sc->time.mode == SB_TIME_DYNAMIC ? step * sc->time.dt : (double)step;
    for (int i = 0; i < sc->n_loads; i++) si->load_factor[i] = sb_load_factor(sc, &sc->loads[i], step);
    for (int i = 0; i < sc->n_bcs; i++) si->motion_factor[i] = sb_bc_motion_factor(sc, &sc->bcs[i], step);
}

double sb_run_probe_rel_error(const sb_probe *p, const double u[3])
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

int sb_run_record_probes(run_state *R, int step_slot)
{
    const sb_scene *sc = &R->scene;
    if (!R->mt->eval_points) return SB_OK;
    int F = sb_problem_finest(R->prob);
    /* the sample grid of this step: the record's time series (sb_record_steps.c) */
    sb_run *rec = &R->rec;
    if (rec->sample_traj && rec->n_samples > 0 &&
        R->mt->eval_points(R->ms, F, R->x, rec->n_samples, rec->sample_st,
                           rec->sample_traj + (size_t)step_slot * rec->n_samples * 3))
        return SB_ERR_INTERNAL;
    if (!sc->n_probes) return SB_OK;
    double st[2 * SB_SCENE_MAX_PROBES];
    for (int p = 0; p < sc->n_probes; p++) { st[2 * p] = sc->probes[p].st[0]; st[2 * p + 1] = sc->probes[p].st[1]; }
    return R->mt->eval_points(R->ms, F, R->x, sc->n_probes, st, R->rec.probe_traj + (size_t)step_slot * sc->n_probes * 3);
}

int sb_run_record_mesh(run_state *R, int step_slot, int *n_tris)
{
    *n_tris = 0;
    if (!R->tri_surface) return SB_OK;
    sb_surface s;
    memset(&s, 0, sizeof s);
    const int F = sb_problem_finest(R->prob);
    int rc = R->mt->surface(R->ms, F, R->x, &s);
    if (!rc && (s.n_patches > 0 || !s.vert || !s.tri)) rc = SB_ERR_INTERNAL;
    if (!rc) *n_tris = s.n_tris;
    sb_mesh_series *ms = &R->mesh_series;
    if (!rc && R->rec.mesh && ms->points + s.n_verts > ((long)1 << 22)) {
        /* a bound like the sample grid's: the series stops being kept */
        fprintf(R->err, "shellbench: note: the per-step mesh of %s passed 2^22 stored vertices at step %d: "
                            "not recorded (the sample-grid time series is)\n", R->mt->name, step_slot);
        sb_mesh_series_free(ms);
        R->rec.mesh = NULL;
    }
    if (!rc && R->rec.mesh) {
        double *ref = s.vert_ref;
        if (!ref && !(ref = calloc((size_t)(s.n_verts ? s.n_verts : 1) * 3, sizeof *ref))) rc = SB_ERR_NOMEM;
        if (!rc) rc = sb_mesh_series_put(ms, step_slot, s.n_verts, s.n_tris, s.tri, ref, s.vert_st, s.vert);
        if (ref != s.vert_ref) free(ref);
    }
    sb_surface_free(&s);
    return rc;
}

static void json_set_num(json_t *o, const char *k, double v)
{
    json_object_set_new(o, k, isfinite(v) ? json_real(v) : json_null());
}

char *sb_run_summary_json(run_state *R, const char *out_path)
{
    const sb_stats *st = &R->ctx.stats;
    json_t *o = json_object();
    json_object_set_new(o, "scene", json_string(R->scene.name));
    json_object_set_new(o, "method", json_string(R->mt->name));
    json_object_set_new(o, "solver", json_string(R->stype->name));
    json_object_set_new(o, "method_info", json_string(R->rec.method_info));
    if (R->rec.solver_info[0]) json_object_set_new(o, "solver_info", json_string(R->rec.solver_info));
    json_object_set_new(o, "dofs", json_integer(R->rec.n_dofs));
    /* triangle methods: the triangles of the last step's mesh (per step: /history/steps/triangles) */
    if (R->tri_surface && st->n_steps) json_object_set_new(o, "triangles", json_integer(st->steps[st->n_steps - 1].triangles));
    json_object_set_new(o, "levels", json_integer(R->rec.levels));
    json_object_set_new(o, "res", json_integer(R->rec.res));
    json_object_set_new(o, "res_t", json_integer(R->rec.res_t > 0 ? R->rec.res_t : R->rec.res));
    json_object_set_new(o, "steps", json_integer(R->rec.steps_done));
    json_object_set_new(o, "steps_planned", json_integer(R->rec.steps_planned));
    json_object_set_new(o, "status", json_string(R->rec.status == 0 ? "converged" : "not_converged"));
    json_object_set_new(o, "reason", json_string(sb_reason_name((sb_reason)R->rec.reason)));
    long iters = 0;
    for (size_t i = 0; i < st->n_steps; i++) iters += st->steps[i].iterations;
    json_object_set_new(o, "iterations", json_integer(iters));
    if (st->n_steps) {
        /* f: Phi of the last step at the final state (inertia included, and the
         * constant -F.X of dead loads at the reference position); the potential
         * change Phi_E(x) - Phi_E(X) is comparable across methods (docs/trust.md) */
        json_set_num(o, "f", st->steps[st->n_steps - 1].f);
        json_set_num(o, "gnorm", st->steps[st->n_steps - 1].gnorm);
    }
    if (R->rec.has_potential) json_set_num(o, "potential_change", R->rec.potential_change);
    else json_object_set_new(o, "potential_change", json_null());
    json_t *wu = json_object();
    json_set_num(wu, "assembly", st->work_assembly);
    json_set_num(wu, "qp", st->work_qp);
    json_object_set_new(o, "work_units", wu);
    json_t *sec = json_object();
    json_set_num(sec, "total", st->seconds_total);
    for (int e = 0; e < SB_EV_COUNT; e++) json_set_num(sec, sb_event_name((sb_event)e), sb_stats_event_total(st, (sb_event)e).seconds);
    json_object_set_new(o, "seconds", sec);
    /* exclusive seconds (issue 42): they and `unattributed` add up to the total */
    json_t *self = json_object();
    double attributed = R->rec.resumed.setup_seconds;
    for (int e = 0; e < SB_EV_COUNT; e++) {
        const double v = sb_stats_self_total(st, (sb_event)e);
        json_set_num(self, sb_event_name((sb_event)e), v);
        attributed += v;
    }
    json_set_num(self, "unattributed", st->seconds_total - attributed);
    json_object_set_new(o, "seconds_self", self);
    json_t *cnt = json_object();
    for (int e = 0; e < SB_EV_COUNT; e++) json_object_set_new(cnt, sb_event_name((sb_event)e), json_integer(sb_stats_event_total(st, (sb_event)e).count));
    json_object_set_new(o, "counts", cnt);
    json_t *lin = json_object();
    int F = R->rec.levels - 1;
    json_set_num(lin, "matrix_nnz", (double)st->matrix_nnz[F]);
    json_set_num(lin, "factor_nnz", st->chol_nnz_l[F]);
    json_set_num(lin, "factor_flops", st->chol_flops[F]);
    json_set_num(lin, "factor_flops_sum", st->chol_flops_sum[F]);
    json_set_num(lin, "factor_entries", st->chol_factor_entries[F]);
    json_set_num(lin, "factorize_cpu_seconds", st->chol_factorize_cpu[F]);
    json_set_num(lin, "first_factorize_cpu_seconds", st->chol_first_cpu[F]);
    json_object_set_new(lin, "not_posdef", json_integer(st->not_posdef));
    json_object_set_new(o, "linear_algebra", lin);
    /* the up-front estimate (sb_memory.h) beside what the process took */
    json_t *mem = json_object();
    struct rusage ru;
    json_set_num(mem, "estimate_bytes", R->mem_estimate);
    if (getrusage(RUSAGE_SELF, &ru) == 0) json_set_num(mem, "peak_rss_bytes", 1024.0 * (double)ru.ru_maxrss);
    json_set_num(mem, "peak_rss_setup_bytes", st->peak_rss_setup);
    json_object_set_new(o, "memory", mem);
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
            /* the first expected value as before; every one under "checks" */
            static const char *const comp[] = { "x", "y", "z", "norm" };
            if (sp->expected_component < 0)
                json_object_set_new(q, "expected", json_pack("[fff]", sp->expected[0], sp->expected[1], sp->expected[2]));
            else
                json_set_num(q, "expected", sp->expected[0]);
            json_object_set_new(q, "component", json_string(sp->expected_component < 0 ? "vector" : comp[sp->expected_component]));
            json_set_num(q, "rel_error", R->rec.probe_rel_error[p]);
            json_set_num(q, "tol", sp->tol);
            json_t *checks = json_array();
            int passed = 1, any = 0;
            for (int c = 0; c < R->rec.n_checks; c++) {
                const sb_check_row *row = &R->rec.checks[c];
                if (row->probe != p) continue;
                json_t *ck = json_object();
                json_object_set_new(ck, "component", json_string(row->component < 0 ? "vector" : comp[row->component]));
                if (row->component < 0) {
                    json_object_set_new(ck, "expected", json_pack("[fff]", row->expected[0], row->expected[1], row->expected[2]));
                    json_object_set_new(ck, "measured", json_pack("[fff]", row->measured[0], row->measured[1], row->measured[2]));
                } else {
                    json_set_num(ck, "expected", row->expected[0]);
                    json_set_num(ck, "measured", row->measured[0]);
                }
                json_set_num(ck, "rel_error", row->rel_error);
                json_set_num(ck, "signed_error", row->signed_error);
                json_set_num(ck, "tol", row->tol);
                json_object_set_new(ck, "passed", json_boolean(row->passed));
                json_array_append_new(checks, ck);
                if (!any) json_set_num(q, "signed_error", row->signed_error);
                any = 1;
                passed &= row->passed;
            }
            if (any) json_object_set_new(q, "passed", json_boolean(passed));
            json_object_set_new(q, "checks", checks);
        }
        json_object_set_new(pr, sp->name, q);
    }
    json_object_set_new(o, "probes", pr);
    json_object_set_new(o, "validation", json_string(sb_validation_name(R->rec.validation)));
    if (R->rec.has_material) {
        const sb_material_state *m = &R->rec.material;
        json_t *ma = json_object();
        json_object_set_new(ma, "points", json_integer(m->points));
        json_object_set_new(ma, "soft_membrane", json_integer(m->soft_membrane));
        json_object_set_new(ma, "soft_section", json_integer(m->soft_section));
        json_set_num(ma, "soft_area_fraction", m->area > 0 ? m->soft_area / m->area : 0.0);
        json_object_set_new(ma, "below_reference", json_integer(m->below_reference));
        json_set_num(ma, "below_reference_area_fraction", m->area > 0 ? m->below_reference_area / m->area : 0.0);
        json_object_set_new(ma, "max_strain", json_pack("[fff]", m->max_strain[0], m->max_strain[1], m->max_strain[2]));
        json_set_num(ma, "min_rel_eig", m->min_rel_eig);
        json_object_set_new(o, "material", ma);
    } else {
        json_object_set_new(o, "material", json_null());
    }
    if (R->rec.has_penalty) {
        /* the constraints imposed by penalty at the final state (docs/trust.md) */
        json_t *pe = json_object();
        json_set_num(pe, "beta", R->rec.penalty_beta);
        json_set_num(pe, "position_max", R->rec.penalty_position);
        json_set_num(pe, "rotation_max", R->rec.penalty_rotation);
        json_set_num(pe, "displacement_scale", R->rec.penalty_scale);
        json_set_num(pe, "relative", R->rec.penalty_relative);
        json_set_num(pe, "tol", R->rec.penalty_tol);
        json_object_set_new(o, "penalty", pe);
    } else {
        json_object_set_new(o, "penalty", json_null());
    }
    if (R->rec.has_contact || R->rec.has_impulse) {
        /* contact sample points and distances (docs/contact.md); absent without obstacles */
        json_t *co = json_object();
        if (R->rec.has_contact) {
            json_object_set_new(co, "points", json_integer(R->rec.contact_points));
            json_object_set_new(co, "active", json_integer(R->rec.contact_active));
            json_object_set_new(co, "inside", json_integer(R->rec.contact_inside));
            json_object_set_new(co, "steps_inside", json_integer(R->rec.contact_steps_inside));

            json_set_num(co, "min_distance", R->rec.contact_min_distance);
        }
        if (R->rec.has_self) {
            /* self-contact: candidate pairs and pairs within dhat at the end,
               smallest pair distance over the step ends, steps that ended with
               a sample edge through a sample triangle */
            json_t *se = json_object();
            json_object_set_new(se, "pairs", json_integer(R->rec.self_pairs));
            json_object_set_new(se, "active", json_integer(R->rec.self_active));
            json_set_num(se, "min_distance", R->rec.self_min_distance);
            json_object_set_new(se, "steps_crossing", json_integer(R->rec.self_steps_crossing));
            json_object_set_new(co, "self", se);
        }
        if (R->mt && R->mt->adapt) json_object_set_new(co, "separated", json_integer(R->contact_separated));
        /* steps that ended with an obstacle crossing the cloth between
           sample points (-1: not checked; issue 37) */
        if (R->rec.has_between) json_object_set_new(co, "steps_between", json_integer(R->rec.contact_steps_between));
        if (R->rec.contact_stop[0]) json_object_set_new(co, "stopped", json_string(R->rec.contact_stop));
        if (R->rec.contact_coverage[0]) json_object_set_new(co, "coverage", json_string(R->rec.contact_coverage));
        if (R->rec.has_impulse) {   /* contact.model = "impulse" (sb_impulse.h) */
            long a[SB_IMPULSE_N_COUNTS];
            sb_impulse_to_array(&R->rec.impulse, a);
            json_object_set_new(co, "model", json_string("impulse"));
            for (int k = 0; k < SB_IMPULSE_N_COUNTS; k++)
                json_object_set_new(co, sb_impulse_count_names[k], json_integer(a[k]));
        }
        json_object_set_new(o, "contact", co);
    }
    json_set_num(o, "energy_final", R->rec.has_energy ? R->rec.energy_final : NAN);
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
int sb_run_compute_error(run_state *R, FILE *err, int allow_unsealed, int skip_file)
{
    int rc = SB_OK;
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
    } else if (sc->reference.kind == SB_REF_FILE && rec->n_samples > 0 && !skip_file) {
        sb_refrec ref;
        char msg[2048];
        if (sb_refrec_load_opt(sc->reference.file, sc->name, sc->json_text, rec->n_samples, rec->sample_st, allow_unsealed,
                           &ref, msg, sizeof msg)) {
            /* the verdict of check and of the run's start (sb_reference_check): refused, exit 2 */
            fprintf(err, "shellbench: scene %s: no error computed: %s\n", sc->name, msg);
            rc = SB_ERR_INPUT;
        } else {
            sb_field_error(ref.n, rec->sample_pos, ref.pos, sb_domain_diameter(&sc->domain), &rec->error_rms,
                           &rec->error_max);
            rec->has_error = 1;
            snprintf(rec->error_kind, sizeof rec->error_kind, "field");
            sb_refrec_free(&ref);
        }
    }
    if (!rec->has_error) snprintf(rec->error_kind, sizeof rec->error_kind, "none");
    return rc;
}

/* rec->material: where the current state strains the material (methods
 * with material_state); part of the record's time */
void sb_run_record_material(run_state *R)
{
    sb_run *rec = &R->rec;
    if (R->material_current && rec->has_material) return;   /* the last step's judgement, of this x */
    rec->has_material = R->mt->material_state &&
        R->mt->material_state(R->ms, sb_problem_finest(R->prob), R->x, &rec->material) == SB_OK;
}


/* rec->energy_final: E(x) of the method at the last step's loads and
 * boundary data (elastic + external + penalty; the core's inertia term is
 * left out), called directly so that it is not counted as solver work */
void sb_run_record_energy(run_state *R)
{
    sb_run *rec = &R->rec;
    if (rec->has_potential && rec->has_energy) return;   /* E(x) of sb_run_potential_change, the same call */
    double e = NAN;
    rec->has_energy = R->mt->energy(R->ms, sb_problem_finest(R->prob), R->x, &e, NULL, NULL) == SB_OK && isfinite(e);
    rec->energy_final = rec->has_energy ? e : NAN;
}
