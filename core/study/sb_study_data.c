/* sb_study_data.c — a study's records read back (sb_study_data.h): the plan
 * says which records there should be; each is read once, and its errors are
 * computed here against the scene's reference:
 *
 *   analytic probes   the record's max probe relative error (computed by the run)
 *   reference record  field RMS and max of |x(xi) - x_ref(xi)| / diameter over
 *                     the sample grid (sb_field_error), and the probe distance
 *                     max_p |x_p - x_ref,p| / diameter (probes matched by name)
 *
 * A reference that does not fit (another scene, another sample grid, an
 * unfinished or unconverged run) is refused with its sentence, which the
 * report prints; the scene then has no field error. */
#include "sb_study_data.h"
#include "sb_geometry.h"
#include "sb_record.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int sb_study_config(const sb_study *st, int n_variants, int m, int s, int v)
{
    return (m * st->n_solvers + s) * n_variants + v;
}

void sb_study_data_free(sb_study_data *d)
{
    if (d->pt)
        for (int k = 0; k < d->plan.n; k++) free(d->pt[k].pos);
    free(d->pt);
    for (int i = 0; i < SB_STUDY_MAX_SCENES; i++)
        if (d->has_ref[i]) sb_refrec_free(&d->ref[i]);
    sb_plan_free(&d->plan);
    memset(d, 0, sizeof *d);
}

static int file_exists(const char *p)
{
    struct stat s;
    return stat(p, &s) == 0;
}

/* first line of a refusal marker */
static void read_marker(const char *path, char *buf, size_t len)
{
    FILE *f = fopen(path, "r");
    buf[0] = 0;
    if (!f) return;
    char line[500];
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = 0;
        const char *s = line;
        if (!strncmp(s, "shellbench: ", 12)) s += 12;
        if (*s) {
            snprintf(buf, len, "%s", s);
            break;
        }
    }
    fclose(f);
}

/* The probe distance of a record against the reference's probes. */
static double probe_distance(const char *rec, const char *ref, double diam, FILE *err)
{
    int n1, n2;
    char (*nm1)[SB_NAME_LEN], (*nm2)[SB_NAME_LEN];
    double *p1, *p2, worst = NAN;
    char msg[1024];
    if (sb_record_read_probes(rec, &n1, &nm1, &p1, msg, sizeof msg)) {
        fprintf(err, "shellbench report: warning: %s\n", msg);
        return NAN;
    }
    if (sb_record_read_probes(ref, &n2, &nm2, &p2, msg, sizeof msg)) {
        fprintf(err, "shellbench report: warning: %s\n", msg);
        free(nm1), free(p1);
        return NAN;
    }
    for (int a = 0; a < n1; a++)
        for (int b = 0; b < n2; b++)
            if (!strcmp(nm1[a], nm2[b])) {
                double d = sqrt((p1[3 * a] - p2[3 * b]) * (p1[3 * a] - p2[3 * b]) + (p1[3 * a + 1] - p2[3 * b + 1]) *
                                (p1[3 * a + 1] - p2[3 * b + 1]) + (p1[3 * a + 2] - p2[3 * b + 2]) * (p1[3 * a + 2] - p2[3 * b + 2])) / diam;
                worst = isnan(worst) ? d : fmax(worst, d);
            }
    free(nm1), free(p1), free(nm2), free(p2);
    return worst;
}

/* self_check.rms of the provenance REF.json beside REF.h5 (NaN: none) */
static double self_check(const char *ref)
{
    char p[1100];
    size_t n = strlen(ref);
    snprintf(p, sizeof p, "%.*s.json", (int)(n > 3 && !strcmp(ref + n - 3, ".h5") ? n - 3 : n), ref);
    json_error_t e;
    json_t *o = json_load_file(p, 0, &e);
    json_t *v = o ? json_object_get(json_object_get(o, "self_check"), "rms") : NULL;
    double r = json_is_number(v) ? json_number_value(v) : NAN;
    json_decref(o);
    return r;
}

static void read_point(sb_study_data *d, sb_study_point *q, FILE *err)
{
    const sb_study *st = d->st;
    const sb_plan_run *r = &d->plan.runs[q->run];
    const int i = r->scene;
    sb_record_summary s;
    char msg[1536];
    if (sb_record_read_summary(r->out, &s, msg, sizeof msg)) {
        fprintf(err, "shellbench report: warning: %s (counted as not run)\n", msg);
        q->state = SB_POINT_MISSING;
        snprintf(q->why, sizeof q->why, "unreadable record");
        return;
    }
    if (sb_study_record_check(st, r, msg, sizeof msg) == SB_ERR_INPUT) {
        /* another run's record in this run's place (sb_study_records.c): not counted */
        fprintf(err, "shellbench report: warning: %s (counted as not run)\n", msg);
        sb_record_summary_free(&s);
        q->state = SB_POINT_MISSING;
        snprintf(q->why, sizeof q->why, "not the planned run's record (misplaced)");
        return;
    }
    q->state = SB_POINT_RECORDED;
    q->status = s.status;
    snprintf(q->reason, sizeof q->reason, "%s", s.reason_name);
    q->dofs = s.dofs;
    q->steps = s.steps;
    q->steps_planned = s.steps_planned;
    q->iterations = s.iterations;
    q->seconds = s.seconds;
    q->work = s.work_assembly;
    q->energy = s.energy_final;
    q->below_reference = s.below_reference;
    snprintf(q->build, sizeof q->build, "%s", s.build_id);
    if (s.has_error && !strcmp(s.error_kind, "probes")) q->err_probe = s.error_probe;
    sb_record_summary_free(&s);
    double *st_grid = NULL;
    if (sb_record_read_samples(r->out, &q->n_samples, &st_grid, &q->pos, msg, sizeof msg)) {
        fprintf(err, "shellbench report: warning: %s\n", msg);
        q->n_samples = 0;
    }
    if (d->has_ref[i] < 0 && q->n_samples > 0 && st->scenes[i].reference[0]) {
        /* the scene's reference, checked against the first record's grid */
        const sb_study_scene *sc = &st->scenes[i];
        if (sb_refrec_load_opt(sc->reference, sc->name, sc->scene->json_text, q->n_samples, st_grid,
                               st->allow_unsealed_reference, &d->ref[i],
                           d->ref_why[i], sizeof d->ref_why[i]) == SB_OK) {
            d->has_ref[i] = 1;
            d->ref_check[i] = self_check(sc->reference);
        }
        else
            d->has_ref[i] = 0;
    }
    if (d->has_ref[i] == 1 && q->n_samples > 0) {
        int same = q->n_samples == d->ref[i].n;
        for (int k = 0; same && k < 2 * q->n_samples; k++) same = fabs(st_grid[k] - d->ref[i].st[k]) <= 1e-12;
        if (same) {
            sb_field_error(q->n_samples, q->pos, d->ref[i].pos, d->diameter[i], &q->err_rms, &q->err_max);
            if (!isfinite(q->err_probe)) q->err_probe = probe_distance(r->out, d->ref[i].path, d->diameter[i], err);
        } else {
            fprintf(err, "shellbench report: warning: %s samples another grid than the reference %s: no field error\n",
                    r->out, d->ref[i].path);
        }
    }
    free(st_grid);
    switch (st->scenes[i].error) {
    case SB_ERRKIND_PROBE: q->error = q->err_probe; break;
    case SB_ERRKIND_FIELD_RMS: q->error = q->err_rms; break;
    case SB_ERRKIND_FIELD_MAX: q->error = q->err_max; break;
    default: q->error = NAN;
    }
    /* an error is the error of a solved scene only */
    if (q->status != 0) q->error = NAN;
}

int sb_study_data_load(const sb_study *st, sb_study_data *d, FILE *err)
{
    memset(d, 0, sizeof *d);
    d->st = st;
    char msg[1024];
    if (sb_study_plan(st, &d->plan, msg, sizeof msg)) {
        fprintf(err, "shellbench report: %s: %s\n", st->path, msg);
        return SB_ERR_INPUT;
    }
    d->n_configs = st->n_methods * st->n_solvers * d->plan.n_variants;
    for (int i = 0; i < st->n_scenes; i++) {
        d->has_ref[i] = -1;   /* not tried yet */
        d->ref_check[i] = NAN;
        d->diameter[i] = sb_domain_diameter(&st->scenes[i].scene->domain);
        if (!st->scenes[i].reference[0])
            snprintf(d->ref_why[i], sizeof d->ref_why[i], "%s", st->scenes[i].error == SB_ERRKIND_PROBE ? "analytic (probes)" : "none");
    }
    d->pt = calloc((size_t)(d->plan.n ? d->plan.n : 1), sizeof *d->pt);
    if (!d->pt) {
        sb_plan_free(&d->plan);
        return SB_ERR_NOMEM;
    }
    for (int k = 0; k < d->plan.n; k++) {
        const sb_plan_run *r = &d->plan.runs[k];
        sb_study_point *q = &d->pt[k];
        q->run = k;
        q->config = sb_study_config(st, d->plan.n_variants, r->method, r->solver, r->variant);
        q->dofs = r->dofs;
        q->err_probe = q->err_rms = q->err_max = q->error = q->energy = q->seconds = q->work = NAN;
        q->below_reference = NAN;
        snprintf(q->why, sizeof q->why, "%s", r->why);
        if (r->state == SB_PLAN_SKIP) q->state = SB_POINT_SKIPPED;
        else if (r->state == SB_PLAN_NOT_APPLICABLE) q->state = SB_POINT_NOT_APPLICABLE;
        else if (r->state == SB_PLAN_REFUSED) q->state = SB_POINT_REFUSED;
        else if (file_exists(r->out)) read_point(d, q, err);
        else {
            char rp[1100];
            sb_plan_refused_path(r->out, rp, sizeof rp);
            if (file_exists(rp)) {
                q->state = SB_POINT_REFUSED;
                read_marker(rp, q->why, sizeof q->why);
            } else {
                q->state = SB_POINT_MISSING;
                snprintf(q->why, sizeof q->why, "not run yet");
            }
        }
    }
    for (int i = 0; i < st->n_scenes; i++)
        if (d->has_ref[i] < 0) {
            if (st->scenes[i].reference[0] && !d->ref_why[i][0])
                snprintf(d->ref_why[i], sizeof d->ref_why[i], "%s (no record of the scene to check it against)", st->scenes[i].reference);
            d->has_ref[i] = 0;
        }
    return SB_OK;
}

void sb_study_config_label(const sb_study_data *d, int config, char *buf, size_t len)
{
    const sb_study *st = d->st;
    int nv = d->plan.n_variants > 0 ? d->plan.n_variants : 1;
    sb_plan_run r;
    memset(&r, 0, sizeof r);
    r.variant = config % nv;
    r.solver = (config / nv) % st->n_solvers;
    r.method = config / (nv * st->n_solvers);
    sb_plan_config_label(st, &r, buf, len);
}

double sb_point_cost(const sb_study_point *q, int cost)
{
    return cost == 0 ? q->seconds : q->work;
}

int sb_study_curve(const sb_study_data *d, int i, int c, int cost, int *idx)
{
    int n = 0;
    for (int k = 0; k < d->plan.n; k++) {
        const sb_study_point *q = &d->pt[k];
        const sb_plan_run *r = &d->plan.runs[k];
        double x = sb_point_cost(q, cost);
        if (r->scene != i || q->config != c || r->start != 0 || q->state != SB_POINT_RECORDED || q->status != 0 ||
            !isfinite(q->error) || !(q->error > 0) || !(x > 0) || !isfinite(x))
            continue;
        int j = n++;
        /* insertion by (dofs, cost) */
        while (j > 0 && (d->pt[idx[j - 1]].dofs > q->dofs ||
                         (d->pt[idx[j - 1]].dofs == q->dofs && sb_point_cost(&d->pt[idx[j - 1]], cost) > x))) {
            idx[j] = idx[j - 1];
            j--;
        }
        idx[j] = k;
    }
    return n;
}

int sb_study_has_record(const sb_study_data *d, int i, int c)
{
    for (int k = 0; k < d->plan.n; k++)
        if (d->plan.runs[k].scene == i && d->pt[k].config == c && d->pt[k].state == SB_POINT_RECORDED) return 1;
    return 0;
}

double sb_study_reach(const sb_study_data *d, int i, int c, int cost, double target, long *lo, long *hi, double *best)
{
    int n0 = d->plan.n ? d->plan.n : 1;
    int *idx = malloc((size_t)n0 * sizeof *idx);
    double *x = malloc((size_t)n0 * sizeof *x), *e = malloc((size_t)n0 * sizeof *e), v = INFINITY;
    if (lo) *lo = 0;
    if (hi) *hi = 0;
    if (best) *best = NAN;
    if (idx && x && e) {
        int n = sb_study_curve(d, i, c, cost, idx), from, first;
        for (int k = 0; k < n; k++) x[k] = sb_point_cost(&d->pt[idx[k]], cost), e[k] = d->pt[idx[k]].error;
        if (n > 0) {
            v = sb_wp_cost_to_reach(n, x, e, target, &from, &first);
            if (best) *best = e[n - 1];
            if (hi) *hi = d->pt[idx[from >= 0 ? from : n - 1]].dofs;
            if (lo && from > 0) *lo = d->pt[idx[from - 1]].dofs;
        }
    }
    free(idx), free(x), free(e);
    return v;
}
