/* sb_record_write.c — one HDF5 file per run, written atomically.
 *
 * The file is built under PATH.tmp.<pid>, flushed, closed and fsync'ed, the
 * XDMF sidecar likewise, and only then both are renamed onto their final
 * names, so an interrupted run or sweep never leaves a truncated record and
 * never damages an earlier one.  The layout (every group, dataset and
 * attribute, with units) is documented in docs/recorded_figures.md. */
#include "sb_output.h"
#include "sb_record_io.h"
#include "sb_sysinfo.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void sb_run_init(sb_run *run)
{
    memset(run, 0, sizeof *run);
    sb_sysinfo_build_id(run->build_id, sizeof run->build_id);
    sb_sysinfo_cpu_model(run->cpu_model, sizeof run->cpu_model);
    run->n_cores = sb_sysinfo_cores();
    sb_sysinfo_now_iso(run->started, sizeof run->started);
    snprintf(run->error_kind, sizeof run->error_kind, "none");
}

const char *sb_validation_name(int v)
{
    return v == SB_VALIDATION_PASSED ? "passed" : v == SB_VALIDATION_FAILED ? "failed" : "none";
}

/* ---- the layout ---------------------------------------------------------- */

static int write_root(sb_h5w *w, hid_t f, const sb_run *r)
{
    char host[128], now[32], core[64];
    sb_sysinfo_hostname(host, sizeof host);
    sb_sysinfo_blas_core(core, sizeof core);
    const char *coretype = getenv("OPENBLAS_CORETYPE");
    sb_sysinfo_now_iso(now, sizeof now);
    const char *blas = getenv("OPENBLAS_NUM_THREADS");
    int bad = 0;
    bad |= sb_h5w_attr_str(w, f, "format", SB_RECORD_FORMAT_NAME);
    bad |= sb_h5w_attr_long(w, f, "format_version", SB_RECORD_FORMAT_VERSION);
    bad |= sb_h5w_attr_str(w, f, "scene_name", r->scene_name);
    bad |= sb_h5w_attr_str(w, f, "scene_path", r->scene_path);
    bad |= sb_h5w_attr_str(w, f, "scene_json", r->scene_json);
    if (r->obstacle_meshes[0]) bad |= sb_h5w_attr_str(w, f, "obstacle_meshes", r->obstacle_meshes);
    bad |= sb_h5w_attr_str(w, f, "method", r->method);
    bad |= sb_h5w_attr_str(w, f, "solver", r->solver);
    bad |= sb_h5w_attr_str(w, f, "method_info", r->method_info);
    bad |= sb_h5w_attr_str(w, f, "solver_info", r->solver_info);
    bad |= sb_h5w_attr_long(w, f, "res", r->res);
    bad |= sb_h5w_attr_long(w, f, "res_t", r->res_t);
    bad |= sb_h5w_attr_long(w, f, "levels", r->levels);
    bad |= sb_h5w_attr_long(w, f, "n_dofs", r->n_dofs);
    bad |= sb_h5w_attr_str(w, f, "build_id", r->build_id);
    bad |= sb_h5w_attr_str(w, f, "cpu_model", r->cpu_model);
    bad |= sb_h5w_attr_long(w, f, "n_cores", r->n_cores);
    bad |= sb_h5w_attr_str(w, f, "hostname", host);
    bad |= sb_h5w_attr_str(w, f, "openblas_num_threads", blas ? blas : "unset");
    bad |= sb_h5w_attr_str(w, f, "blas_core", core);
    bad |= sb_h5w_attr_str(w, f, "openblas_coretype", coretype ? coretype : "unset");
    bad |= sb_h5w_attr_str(w, f, "started", r->started);
    bad |= sb_h5w_attr_str(w, f, "written", now);
    bad |= sb_h5w_attr_long(w, f, "status", r->status);
    bad |= sb_h5w_attr_str(w, f, "reason", sb_reason_name((sb_reason)r->reason));
    bad |= sb_h5w_attr_long(w, f, "reason_code", r->reason);
    bad |= sb_h5w_attr_long(w, f, "steps_planned", r->steps_planned);
    bad |= sb_h5w_attr_long(w, f, "steps_done", r->steps_done);
    bad |= sb_h5w_attr_str(w, f, "validation", sb_validation_name(r->validation));
    bad |= sb_h5w_attr_dbl(w, f, "potential_change", r->has_potential ? r->potential_change : NAN);
    bad |= sb_h5w_attr_dbl(w, f, "energy_final", r->has_energy ? r->energy_final : NAN);
    return bad ? -1 : 0;
}

static int write_params(sb_h5w *w, hid_t f, const sb_paramset *ps)
{
    hid_t g = sb_h5w_group(w, f, "/params");
    if (g < 0) return -1;
    int bad = 0;
    char overridden[4096] = "";
    size_t used = 0;
    for (int i = 0; ps && i < ps->n && !bad; i++) {
        const sb_param_value *v = &ps->v[i];
        if (!v->def) continue;
        if (v->def->kind == SB_PARAM_CHOICE) {
            char text[SB_NAME_LEN];
            sb_param_format(v, text, sizeof text);
            bad |= sb_h5w_attr_str(w, g, v->key, text);
        } else if (v->def->kind == SB_PARAM_INT) {
            bad |= sb_h5w_attr_long(w, g, v->key, (long)v->value);
        } else {
            bad |= sb_h5w_attr_dbl(w, g, v->key, v->value);
        }
        if (v->overridden && used < sizeof overridden) {
            int n = snprintf(overridden + used, sizeof overridden - used, "%s%s", used ? "," : "", v->key);
            if (n > 0) used += (size_t)n;
        }
    }
    if (!bad) bad |= sb_h5w_attr_str(w, g, "_overridden", overridden);
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* Rows of the per-level tables: the declared levels, extended to the last
 * level that saw any event (sb_stats_event clamps levels to SB_MAX_LEVELS). */
static int stats_rows(const sb_stats *s)
{
    int rows = s->n_levels < 0 ? 0 : s->n_levels > SB_MAX_LEVELS ? SB_MAX_LEVELS : s->n_levels;
    for (int l = rows; l < SB_MAX_LEVELS; l++)
        for (int e = 0; e < SB_EV_COUNT; e++)
            if (s->ev[l][e].count || s->ev[l][e].seconds != 0.0) rows = l + 1;
    return rows;
}

/* seconds_total minus every event's exclusive seconds and the resumed
 * processes' set-up: the time no event covers (issue 42) */
static double unattributed(const sb_stats *s, const sb_resume_log *log, double extra)
{
    double u = s->seconds_total + extra - (log ? log->setup_seconds : 0.0);
    for (int l = 0; l < SB_MAX_LEVELS; l++)
        for (int e = 0; e < SB_EV_COUNT; e++) u -= s->ev[l][e].self;
    return u - extra;
}

/* The per-level event tables; `extra` seconds (the record's own write) are
 * added to event `xe` on level `xl` (xe < 0: none). */
static void event_tables(const sb_stats *s, int rows, int xe, int xl, double extra, long *cnt, double *sec,
                         double *self)
{
    for (int l = 0; l < rows; l++)
        for (int e = 0; e < SB_EV_COUNT; e++) {
            const int k = l * SB_EV_COUNT + e, add = e == xe && l == xl;
            if (cnt) cnt[k] = s->ev[l][e].count + add;
            sec[k] = s->ev[l][e].seconds + (add ? extra : 0.0);
            self[k] = s->ev[l][e].self + (add ? extra : 0.0);
        }
}

static int write_stats(sb_h5w *w, hid_t f, const sb_stats *s, const sb_run *r)
{
    hid_t g = sb_h5w_group(w, f, "/stats");
    if (g < 0) return -1;
    int rows = stats_rows(s);
    long cnt[SB_MAX_LEVELS * SB_EV_COUNT];
    double sec[SB_MAX_LEVELS * SB_EV_COUNT], self[SB_MAX_LEVELS * SB_EV_COUNT];
    const int xe = r->write_event > 0 && r->write_t0 > 0 ? r->write_event : -1;
    const int xl = s->n_levels > 0 ? s->n_levels - 1 : 0;
    if (xe >= 0 && xl >= rows) rows = xl + 1;
    event_tables(s, rows, xe, xl, 0.0, cnt, sec, self);
    char names[SB_EV_COUNT][16];
    for (int e = 0; e < SB_EV_COUNT; e++) snprintf(names[e], sizeof names[e], "%s", sb_event_name((sb_event)e));
    hsize_t d2[2] = { (hsize_t)rows, SB_EV_COUNT }, d1 = (hsize_t)rows;
    int bad = 0;
    bad |= sb_h5w_dset_long(w, g, "events_count", 2, d2, cnt, "calls");
    bad |= sb_h5w_dset_dbl(w, g, "events_seconds", 2, d2, sec, "s");
    bad |= sb_h5w_dset_dbl(w, g, "events_self_seconds", 2, d2, self, "s");
    bad |= sb_h5w_attr_str_array(w, g, "event_names", SB_EV_COUNT, sizeof names[0], &names[0][0]);
    bad |= sb_h5w_dset_long(w, g, "n_dofs", 1, &d1, s->n_dofs, "dofs");
    bad |= sb_h5w_dset_dbl(w, g, "chol_flops", 1, &d1, s->chol_flops, "flop");
    bad |= sb_h5w_dset_dbl(w, g, "chol_nnz_l", 1, &d1, s->chol_nnz_l, "entries");
    bad |= sb_h5w_dset_long(w, g, "matrix_nnz", 1, &d1, s->matrix_nnz, "entries");
    bad |= sb_h5w_dset_dbl(w, g, "chol_flops_sum", 1, &d1, s->chol_flops_sum, "flop");
    bad |= sb_h5w_dset_dbl(w, g, "chol_nnz_l_sum", 1, &d1, s->chol_nnz_l_sum, "entries");
    bad |= sb_h5w_dset_dbl(w, g, "chol_factor_entries", 1, &d1, s->chol_factor_entries, "entries");
    bad |= sb_h5w_dset_dbl(w, g, "chol_factorize_cpu", 1, &d1, s->chol_factorize_cpu, "s");
    bad |= sb_h5w_dset_dbl(w, g, "chol_first_factorize_cpu", 1, &d1, s->chol_first_cpu, "s");
    bad |= sb_h5w_dset_dbl(w, g, "chol_first_flops", 1, &d1, s->chol_first_flops, "flop");
    bad |= sb_h5w_attr_dbl(w, g, "memory_estimate", s->mem_estimate);
    bad |= sb_h5w_attr_dbl(w, g, "peak_rss_start", s->peak_rss_start);
    bad |= sb_h5w_attr_dbl(w, g, "peak_rss_setup", s->peak_rss_setup);
    bad |= sb_h5w_attr_dbl(w, g, "peak_rss_analyzed", s->peak_rss_analyzed);
    bad |= sb_h5w_attr_dbl(w, g, "peak_rss", s->peak_rss);
    bad |= sb_h5w_attr_dbl(w, g, "seconds_unattributed", unattributed(s, &r->resumed, 0.0));
    bad |= sb_h5w_attr_dbl(w, g, "work_assembly", s->work_assembly);
    bad |= sb_h5w_attr_dbl(w, g, "work_qp", s->work_qp);
    bad |= sb_h5w_attr_dbl(w, g, "seconds_total", s->seconds_total);
    bad |= sb_h5w_attr_long(w, g, "not_posdef", s->not_posdef);
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* The history columns (sb_record_io.h).  "units" attributes are written
 * only where the unit does not depend on the method's DOF layout (||g||,
 * Delta, step norms mix position DOFs (m) with Hermite derivative DOFs). */
const sb_record_column sb_record_iter_cols[] = {
    { "step", offsetof(sb_iter_record, step), 1, "", 0 },
    { "iter", offsetof(sb_iter_record, iter), 1, "", 0 },
    { "level", offsetof(sb_iter_record, level), 1, "", 0 },
    { "f", offsetof(sb_iter_record, f), 0, "J", 0 },
    { "gnorm", offsetof(sb_iter_record, gnorm), 0, "", 0 },
    { "delta", offsetof(sb_iter_record, delta), 0, "", 0 },
    { "rho", offsetof(sb_iter_record, rho), 0, "", 0 },
    { "step_norm", offsetof(sb_iter_record, step_norm), 0, "", 0 },
    { "shift", offsetof(sb_iter_record, shift), 0, "", 0 },
    { "accepted", offsetof(sb_iter_record, accepted), 1, "", 0 },
    { "linear_iters", offsetof(sb_iter_record, linear_iters), 1, "", 0 },
    { "reason", offsetof(sb_iter_record, reason), 1, "", 0 },
    { "seconds", offsetof(sb_iter_record, seconds), 0, "s", 1 },
    { "seconds_assembly", offsetof(sb_iter_record, seconds_assembly), 0, "s", 1 },
    { "seconds_analyze", offsetof(sb_iter_record, seconds_analyze), 0, "s", 1 },
    { "seconds_factorize", offsetof(sb_iter_record, seconds_factorize), 0, "s", 1 },
    { "seconds_solve", offsetof(sb_iter_record, seconds_solve), 0, "s", 1 },
    { "seconds_contact", offsetof(sb_iter_record, seconds_contact), 0, "s", 1 },
    { "krylov_rtol", offsetof(sb_iter_record, krylov_rtol), 0, "", 0 },
    { "krylov_status", offsetof(sb_iter_record, krylov_status), 1, "", 0 },
};
const int sb_record_n_iter_cols = (int)(sizeof sb_record_iter_cols / sizeof *sb_record_iter_cols);
const sb_record_column sb_record_step_cols[] = {
    { "step", offsetof(sb_step_record, step), 1, "", 0 },
    { "t", offsetof(sb_step_record, t), 0, "", 0 },
    { "iterations", offsetof(sb_step_record, iterations), 1, "", 0 },
    { "reason", offsetof(sb_step_record, reason), 1, "", 0 },
    { "f", offsetof(sb_step_record, f), 0, "J", 0 },
    { "gnorm", offsetof(sb_step_record, gnorm), 0, "", 0 },
    { "seconds", offsetof(sb_step_record, seconds), 0, "s", 0 },
    { "work_assembly", offsetof(sb_step_record, work_assembly), 0, "WU", 0 },
    { "work_qp", offsetof(sb_step_record, work_qp), 0, "WU", 0 },
    { "force_scale", offsetof(sb_step_record, force_scale), 0, "", 0 },
    { "gstop", offsetof(sb_step_record, gstop), 0, "", 0 },
    { "gnoise", offsetof(sb_step_record, gnoise), 0, "", 1 },
    { "dofs", offsetof(sb_step_record, dofs), 1, "", 0 },
    { "triangles", offsetof(sb_step_record, triangles), 1, "", 0 },
    { "seconds_assembly", offsetof(sb_step_record, seconds_assembly), 0, "s", 1 },
    { "seconds_analyze", offsetof(sb_step_record, seconds_analyze), 0, "s", 1 },
    { "seconds_factorize", offsetof(sb_step_record, seconds_factorize), 0, "s", 1 },
    { "seconds_solve", offsetof(sb_step_record, seconds_solve), 0, "s", 1 },
    { "seconds_contact", offsetof(sb_step_record, seconds_contact), 0, "s", 1 },
    { "seconds_adapt", offsetof(sb_step_record, seconds_adapt), 0, "s", 1 },
    { "seconds_record", offsetof(sb_step_record, seconds_record), 0, "s", 1 },
    { "seconds_checkpoint", offsetof(sb_step_record, seconds_checkpoint), 0, "s", 1 },
    { "peak_rss", offsetof(sb_step_record, peak_rss), 0, "B", 1 },
};
const int sb_record_n_step_cols = (int)(sizeof sb_record_step_cols / sizeof *sb_record_step_cols);

/* buf holds n doubles (reused for int columns). */
static int write_columns(sb_h5w *w, hid_t g, const sb_record_column *cols, int ncols, const void *recs,
                         size_t rec_size, size_t n, double *buf)
{
    hsize_t d = (hsize_t)n;
    int *ibuf = (int *)(void *)buf;   /* sizeof(int) <= sizeof(double) */
    for (int c = 0; c < ncols; c++) {
        const char *base = (const char *)recs + cols[c].off;
        for (size_t i = 0; i < n; i++) {
            if (cols[c].is_int) memcpy(&ibuf[i], base + i * rec_size, sizeof(int));
            else memcpy(&buf[i], base + i * rec_size, sizeof(double));
        }
        int rc = cols[c].is_int ? sb_h5w_dset_int(w, g, cols[c].name, 1, &d, ibuf, cols[c].units[0] ? cols[c].units : NULL)
                                : sb_h5w_dset_dbl(w, g, cols[c].name, 1, &d, buf, cols[c].units[0] ? cols[c].units : NULL);
        if (rc) return -1;
    }
    return 0;
}

static int write_history(sb_h5w *w, hid_t f, const sb_stats *s)
{
    hid_t g = sb_h5w_group(w, f, "/history");
    if (g < 0) return -1;
    char names[SB_REASON_COUNT][32];
    for (int r = 0; r < SB_REASON_COUNT; r++) snprintf(names[r], sizeof names[r], "%s", sb_reason_name((sb_reason)r));
    int bad = sb_h5w_attr_str_array(w, g, "reason_names", SB_REASON_COUNT, sizeof names[0], &names[0][0]);
    size_t nmax = s->n_iters > s->n_steps ? s->n_iters : s->n_steps;
    double *buf = malloc((nmax ? nmax : 1) * sizeof *buf);
    if (!buf) bad = -1, sb_h5w_fail(w, g, "(out of memory)");
    hid_t gi = bad ? -1 : sb_h5w_group(w, f, "/history/iterations");
    hid_t gs = gi < 0 ? -1 : sb_h5w_group(w, f, "/history/steps");
    if (gi < 0 || gs < 0) bad = -1;
    if (!bad) bad |= write_columns(w, gi, sb_record_iter_cols, sb_record_n_iter_cols, s->iters,
                                   sizeof *s->iters, s->n_iters, buf);
    if (!bad) bad |= write_columns(w, gs, sb_record_step_cols, sb_record_n_step_cols, s->steps,
                                   sizeof *s->steps, s->n_steps, buf);
    free(buf);
    if (gs >= 0) H5Gclose(gs);
    if (gi >= 0) H5Gclose(gi);
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* /probes/checks: every expected value of every probe, judged (docs/trust.md) */
static int write_checks(sb_h5w *w, hid_t probes, const sb_run *r)
{
    hid_t g = sb_h5w_group(w, probes, "checks");
    if (g < 0) return -1;
    const size_t n = (size_t)(r->n_checks > 0 ? r->n_checks : 0);
    int *ib = malloc((n ? n : 1) * 3 * sizeof *ib);
    double *db = malloc((n ? n : 1) * 6 * sizeof *db);
    int bad = !ib || !db ? sb_h5w_fail(w, g, "checks (out of memory)") : 0;
    if (!bad) {
        int *probe = ib, *comp = ib + n, *passed = ib + 2 * n;
        double *exp = db, *meas = db + 3 * n;
        hsize_t d1 = n, d2[2] = { n, 3 };
        for (size_t i = 0; i < n; i++) {
            probe[i] = r->checks[i].probe;
            comp[i] = r->checks[i].component;
            passed[i] = r->checks[i].passed;
            memcpy(exp + 3 * i, r->checks[i].expected, 3 * sizeof(double));
            memcpy(meas + 3 * i, r->checks[i].measured, 3 * sizeof(double));
        }
        bad |= sb_h5w_dset_int(w, g, "probe", 1, &d1, probe, NULL);
        bad |= sb_h5w_dset_int(w, g, "component", 1, &d1, comp, NULL);
        bad |= sb_h5w_dset_int(w, g, "passed", 1, &d1, passed, NULL);
        bad |= sb_h5w_dset_dbl(w, g, "expected", 2, d2, exp, "m");
        bad |= sb_h5w_dset_dbl(w, g, "measured", 2, d2, meas, "m");
        for (size_t i = 0; i < n; i++) db[i] = r->checks[i].rel_error;
        bad |= sb_h5w_dset_dbl(w, g, "rel_error", 1, &d1, db, NULL);
        for (size_t i = 0; i < n; i++) db[i] = r->checks[i].signed_error;
        bad |= sb_h5w_dset_dbl(w, g, "signed_error", 1, &d1, db, NULL);
        for (size_t i = 0; i < n; i++) db[i] = r->checks[i].tol;
        bad |= sb_h5w_dset_dbl(w, g, "tol", 1, &d1, db, NULL);
    }
    free(ib);
    free(db);
    H5Gclose(g);
    return bad ? -1 : 0;
}

static int write_probes(sb_h5w *w, hid_t f, const sb_run *r)
{
    hid_t g = sb_h5w_group(w, f, "/probes");
    if (g < 0) return -1;
    hsize_t np = (hsize_t)r->n_probes;
    hsize_t dt[3] = { (hsize_t)r->steps_done + 1, np, 3 }, de[2] = { np, 3 };
    int bad = 0;
    hsize_t d1 = np;
    hid_t sp = H5Screate_simple(1, &d1, NULL), t = sb_h5w_str_type(SB_NAME_LEN);
    hid_t ds = (sp < 0 || t < 0) ? -1 : H5Dcreate2(g, "names", t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (ds < 0 || (np > 0 && H5Dwrite(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, r->probe_names) < 0))
        bad = sb_h5w_fail(w, g, "names");
    if (ds >= 0) H5Dclose(ds);
    if (t >= 0) H5Tclose(t);
    if (sp >= 0) H5Sclose(sp);
    bad |= sb_h5w_dset_dbl(w, g, "trajectory", 3, dt, r->probe_traj, "m");
    bad |= sb_h5w_dset_dbl(w, g, "expected", 2, de, r->probe_expected, "m");
    bad |= sb_h5w_dset_dbl(w, g, "rel_error", 1, &d1, r->probe_rel_error, NULL);
    if (!bad) bad |= write_checks(w, g, r);
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* /final/material: where the final state strains the material (sb_material_state.h) */
static int write_material(sb_h5w *w, hid_t final, const sb_material_state *m)
{
    hid_t g = sb_h5w_group(w, final, "material");
    if (g < 0) return -1;
    int bad = 0;
    bad |= sb_h5w_attr_long(w, g, "points", m->points);
    bad |= sb_h5w_attr_long(w, g, "soft_membrane", m->soft_membrane);
    bad |= sb_h5w_attr_long(w, g, "soft_section", m->soft_section);
    bad |= sb_h5w_attr_dbl(w, g, "area", m->area);
    bad |= sb_h5w_attr_dbl(w, g, "soft_area", m->soft_area);
    bad |= sb_h5w_attr_dbl(w, g, "soft_area_fraction", m->area > 0 ? m->soft_area / m->area : 0.0);
    bad |= sb_h5w_attr_long(w, g, "below_reference", m->below_reference);
    bad |= sb_h5w_attr_dbl(w, g, "below_reference_area_fraction", m->area > 0 ? m->below_reference_area / m->area : 0.0);
    bad |= sb_h5w_attr_dbl(w, g, "max_E11", m->max_strain[0]);
    bad |= sb_h5w_attr_dbl(w, g, "max_E22", m->max_strain[1]);
    bad |= sb_h5w_attr_dbl(w, g, "max_E12", m->max_strain[2]);
    bad |= sb_h5w_attr_dbl(w, g, "min_rel_eig", m->min_rel_eig);
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* /final/penalty: the penalty-imposed constraints at the final state (docs/trust.md) */
static int write_penalty(sb_h5w *w, hid_t final, const sb_run *r)
{
    hid_t g = sb_h5w_group(w, final, "penalty");
    if (g < 0) return -1;
    int bad = 0;
    bad |= sb_h5w_attr_dbl(w, g, "beta", r->penalty_beta);
    bad |= sb_h5w_attr_dbl(w, g, "position_max", r->penalty_position);
    bad |= sb_h5w_attr_dbl(w, g, "rotation_max", r->penalty_rotation);
    bad |= sb_h5w_attr_dbl(w, g, "displacement_scale", r->penalty_scale);
    bad |= sb_h5w_attr_dbl(w, g, "relative", r->penalty_relative);
    bad |= sb_h5w_attr_dbl(w, g, "tol", r->penalty_tol);
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* /final/contact: contact sample points and distances (docs/contact.md) */
static int write_contact(sb_h5w *w, hid_t final, const sb_run *r)
{
    hid_t g = sb_h5w_group(w, final, "contact");
    if (g < 0) return -1;
    int bad = 0;
    if (r->has_contact) {
        bad |= sb_h5w_attr_long(w, g, "points", (long)r->contact_points);
        bad |= sb_h5w_attr_long(w, g, "active", (long)r->contact_active);
        bad |= sb_h5w_attr_long(w, g, "inside", (long)r->contact_inside);
        bad |= sb_h5w_attr_long(w, g, "steps_inside", (long)r->contact_steps_inside);
        bad |= sb_h5w_attr_dbl(w, g, "min_distance", r->contact_min_distance);
    }
    /* issue 37: why a moving obstacle stopped the run, and what the
       no-penetration guarantee covered */
    if (r->has_between) bad |= sb_h5w_attr_long(w, g, "steps_between", (long)r->contact_steps_between);
    if (r->contact_stop[0]) bad |= sb_h5w_attr_str(w, g, "stopped", r->contact_stop);
    if (r->contact_coverage[0]) bad |= sb_h5w_attr_str(w, g, "coverage", r->contact_coverage);
    if (r->has_impulse) {   /* contact.model = "impulse" (sb_impulse.h) */
        long a[SB_IMPULSE_N_COUNTS];
        sb_impulse_to_array(&r->impulse, a);
        bad |= sb_h5w_attr_str(w, g, "model", "impulse");
        for (int k = 0; k < SB_IMPULSE_N_COUNTS; k++) bad |= sb_h5w_attr_long(w, g, sb_impulse_count_names[k], a[k]);
    }
    H5Gclose(g);
    return bad ? -1 : 0;
}

static int write_final(sb_h5w *w, hid_t f, const sb_run *r)
{
    hid_t g = sb_h5w_group(w, f, "/final");
    if (g < 0) return -1;
    size_t ns = (size_t)r->n_samples;
    double *disp = malloc((ns ? ns : 1) * 3 * sizeof *disp);
    if (!disp) {
        H5Gclose(g);
        return sb_h5w_fail(w, -1, "/final/displacement (out of memory)");
    }
    for (size_t i = 0; i < 3 * ns; i++) disp[i] = r->sample_pos[i] - r->sample_ref[i];
    hsize_t dx = (hsize_t)r->n_x, d2[2] = { ns, 2 }, d3[2] = { ns, 3 }, dt[2] = { (hsize_t)r->n_tris, 3 };
    int bad = 0;
    bad |= sb_h5w_dset_dbl(w, g, "x", 1, &dx, r->x_final, NULL);
    bad |= sb_h5w_dset_dbl(w, g, "sample_st", 2, d2, r->sample_st, NULL);
    bad |= sb_h5w_dset_dbl(w, g, "sample_ref", 2, d3, r->sample_ref, "m");
    bad |= sb_h5w_dset_dbl(w, g, "sample_pos", 2, d3, r->sample_pos, "m");
    bad |= sb_h5w_dset_dbl(w, g, "displacement", 2, d3, disp, "m");
    bad |= sb_h5w_dset_int(w, g, "triangles", 2, dt, r->tris, NULL);
    free(disp);
    if (!bad && r->has_material) bad |= write_material(w, g, &r->material);
    if (!bad && r->has_penalty) bad |= write_penalty(w, g, r);
    if (!bad && (r->has_contact || r->has_impulse)) bad |= write_contact(w, g, r);
    H5Gclose(g);
    return bad ? -1 : 0;
}

static int write_error(sb_h5w *w, hid_t f, const sb_run *r)
{
    hid_t g = sb_h5w_group(w, f, "/error");
    if (g < 0) return -1;
    int bad = 0;
    bad |= sb_h5w_attr_str(w, g, "kind", r->has_error ? r->error_kind : "none");
    bad |= sb_h5w_attr_long(w, g, "has_error", r->has_error);
    bad |= sb_h5w_attr_dbl(w, g, "rms", r->has_error ? r->error_rms : NAN);
    bad |= sb_h5w_attr_dbl(w, g, "max", r->has_error ? r->error_max : NAN);
    bad |= sb_h5w_attr_dbl(w, g, "probe", r->has_error ? r->error_probe : NAN);
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* The record's own write so far (sb_run.write_event) into /stats: the event
 * tables, seconds_total and seconds_unattributed rewritten in place. */
static int patch_own_write(sb_h5w *w, hid_t f, const sb_stats *s, const sb_run *r)
{
    const double extra = sb_now() - r->write_t0;
    int rows = stats_rows(s);
    const int xl = s->n_levels > 0 ? s->n_levels - 1 : 0;
    if (xl >= rows) rows = xl + 1;
    long cnt[SB_MAX_LEVELS * SB_EV_COUNT];
    double sec[SB_MAX_LEVELS * SB_EV_COUNT], self[SB_MAX_LEVELS * SB_EV_COUNT];
    event_tables(s, rows, r->write_event, xl, extra, cnt, sec, self);
    const double total = s->seconds_total + extra, un = unattributed(s, &r->resumed, 0.0);
    int bad = 0;
    hid_t g = H5Gopen2(f, "/stats", H5P_DEFAULT);
    if (g < 0) return sb_h5w_fail(w, -1, "/stats (reopening)");
    const char *dn[3] = { "events_count", "events_seconds", "events_self_seconds" };
    const void *db[3] = { cnt, sec, self };
    for (int k = 0; k < 3 && !bad; k++) {
        hid_t d = H5Dopen2(g, dn[k], H5P_DEFAULT);
        if (d < 0 || H5Dwrite(d, k ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, db[k]) < 0)
            bad = sb_h5w_fail(w, -1, dn[k]);
        if (d >= 0) H5Dclose(d);
    }
    const char *an[2] = { "seconds_total", "seconds_unattributed" };
    const double av[2] = { total, un };
    for (int k = 0; k < 2 && !bad; k++) {
        hid_t a = H5Aopen(g, an[k], H5P_DEFAULT);
        if (a < 0 || H5Awrite(a, H5T_NATIVE_DOUBLE, &av[k]) < 0) bad = sb_h5w_fail(w, -1, an[k]);
        if (a >= 0) H5Aclose(a);
    }
    H5Gclose(g);
    return bad;
}

/* Root attributes may exceed the 64 KiB limit of compact attribute storage
 * (scene_json): the 1.8 object format with dense attribute storage lifts it. */
static int write_file(const sb_run *run, const sb_stats *stats, const char *tmp, sb_h5w *w)
{
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE), fapl = H5Pcreate(H5P_FILE_ACCESS);
    hid_t f = -1;
    /* the user block holds the checksum, written once the file is closed (sb_checksum.c) */
    if (fcpl >= 0 && fapl >= 0 && H5Pset_attr_phase_change(fcpl, 0, 0) >= 0 &&
        H5Pset_userblock(fcpl, SB_RECORD_USERBLOCK) >= 0 &&
        H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18) >= 0)
        f = H5Fcreate(tmp, H5F_ACC_TRUNC, fcpl, fapl);
    if (fcpl >= 0) H5Pclose(fcpl);
    if (fapl >= 0) H5Pclose(fapl);
    if (f < 0) return sb_h5w_fail(w, -1, "(file creation)");
    int bad = write_root(w, f, run);
    if (!bad) bad = write_params(w, f, run->params);
    if (!bad) bad = write_stats(w, f, stats, run);
    if (!bad) bad = write_history(w, f, stats);
    if (!bad) bad = write_probes(w, f, run);
    if (!bad) bad = write_final(w, f, run);
    if (!bad) bad = write_error(w, f, run);
    if (!bad) bad = sb_record_write_steps(w, f, run);
    if (!bad) bad = sb_record_write_mesh(w, f, run);
    if (!bad) bad = sb_record_write_resume_log(w, f, &run->resumed);
    if (!bad && run->resume) bad = sb_record_write_resume(w, f, run->resume);
    if (!bad && run->write_event > 0 && run->write_t0 > 0) bad = patch_own_write(w, f, stats, run);
    if (!bad && H5Fflush(f, H5F_SCOPE_GLOBAL) < 0) bad = sb_h5w_fail(w, -1, "(flush)");
    if (H5Fclose(f) < 0 && !bad) bad = sb_h5w_fail(w, -1, "(close)");
    return bad;
}

/* ---- validation and the atomic replacement ------------------------------- */

static int validate(const sb_run *r, const char *path, char *err, size_t errlen)
{
#define BAD(...) do { snprintf(err, errlen, __VA_ARGS__); return SB_ERR_INPUT; } while (0)
    if (!r) BAD("sb_record_write: no run given");
    if (!path || !path[0]) BAD("sb_record_write: empty output path");
    if (r->n_probes < 0 || r->n_x < 0 || r->n_samples < 0 || r->n_tris < 0 || r->steps_done < 0)
        BAD("cannot record %s: negative count (probes %d, x %d, samples %d, triangles %d, steps %d)",
            path, r->n_probes, r->n_x, r->n_samples, r->n_tris, r->steps_done);
    if (r->n_checks < 0 || (r->n_checks > 0 && !r->checks))
        BAD("cannot record %s: %d probe checks but no check array", path, r->n_checks);
    if (r->n_probes > 0 && (!r->probe_names || !r->probe_traj || !r->probe_expected || !r->probe_rel_error))
        BAD("cannot record %s: %d probes but their names/trajectory/expected/rel_error arrays are missing",
            path, r->n_probes);
    if (r->n_x > 0 && !r->x_final) BAD("cannot record %s: n_x = %d but no final state", path, r->n_x);
    if (r->n_samples > 0 && (!r->sample_st || !r->sample_ref || !r->sample_pos))
        BAD("cannot record %s: %d samples but the st/ref/pos arrays are missing", path, r->n_samples);
    if (r->n_tris > 0 && !r->tris) BAD("cannot record %s: %d triangles but no index array", path, r->n_tris);
    for (long i = 0; i < 3L * r->n_tris; i++)
        if (r->tris[i] < 0 || r->tris[i] >= r->n_samples)
            BAD("cannot record %s: triangle %ld refers to sample %d, outside [0, %d)", path, i / 3,
                r->tris[i], r->n_samples);
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) BAD("cannot record run: %s is a directory", path);
    const sb_stats *s = r->stats;
    if (s && ((s->n_iters > 0 && !s->iters) || (s->n_steps > 0 && !s->steps)))
        BAD("cannot record %s: statistics history arrays are missing", path);
    if (s && (s->n_iters > INT32_MAX || s->n_steps > INT32_MAX))
        BAD("cannot record %s: history too long", path);
    const sb_resume_point *rp = r->resume;
    /* an adaptive run's resume point may hold the mesh before the adaptation of the step under way */
    if (rp && ((rp->n_x != r->n_x && !rp->has_mesh) || !rp->x || !rp->v || !s || rp->stats.n_iters > s->n_iters ||
               rp->stats.n_steps > s->n_steps || rp->step > r->steps_done))
        BAD("cannot record %s: resume point (step %d, %zu iterations) inconsistent with the record", path,
            rp->step, rp->stats.n_iters);
#undef BAD
    return SB_OK;
}

int sb_record_write(const sb_run *run, const char *path, char *err, size_t errlen)
{
    int rc = validate(run, path, err, errlen);
    if (rc) return rc;
    char tmp[4096], xpath[4096], xtmp[4096], spath[4096], stmp[4096], mpath[4096], mtmp[4096];
    long pid = (long)getpid();
    if (snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, pid) >= (int)sizeof tmp ||
        sb_record_xdmf_path(path, xpath, sizeof xpath) != SB_OK ||
        snprintf(xtmp, sizeof xtmp, "%s.tmp.%ld", xpath, pid) >= (int)sizeof xtmp ||
        sb_record_steps_xdmf_path(path, spath, sizeof spath) != SB_OK ||
        snprintf(stmp, sizeof stmp, "%s.tmp.%ld", spath, pid) >= (int)sizeof stmp ||
        sb_record_mesh_xdmf_path(path, mpath, sizeof mpath) != SB_OK ||
        snprintf(mtmp, sizeof mtmp, "%s.tmp.%ld", mpath, pid) >= (int)sizeof mtmp) {
        snprintf(err, errlen, "cannot record run: output path too long (%zu characters)", strlen(path));
        return SB_ERR_INPUT;
    }
    /* Only new paths and regular files are replaced (sb_output.h): a device,
     * FIFO or symbolic link at the path is never renamed over. */
    sb_output_kind kind;
    if (sb_output_check(path, "record", &kind, err, errlen) || kind == SB_OUTPUT_DISCARD ||
        sb_output_check(xpath, "XDMF sidecar", &kind, err, errlen) || kind == SB_OUTPUT_DISCARD ||
        sb_output_check(spath, "XDMF time-series sidecar", &kind, err, errlen) || kind == SB_OUTPUT_DISCARD ||
        sb_output_check(mpath, "XDMF mesh time-series sidecar", &kind, err, errlen) || kind == SB_OUTPUT_DISCARD) {
        if (kind == SB_OUTPUT_DISCARD) snprintf(err, errlen, "will not write record %s: the null device", path);
        return SB_ERR_INPUT;
    }
    /* Create the temp file ourselves first: errno then names the cause
     * (missing directory, permission, a directory in the way); a stale one
     * of an earlier process with our pid is replaced, a link there is not
     * followed. */
    unlink(tmp);
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
    if (fd < 0) {
        snprintf(err, errlen, "cannot write record %s: cannot create %s: %s", path, tmp, strerror(errno));
        return SB_ERR_IO;
    }
    close(fd);

    sb_stats empty;
    const sb_stats *stats = run->stats;
    if (!stats) {
        sb_stats_init(&empty);
        stats = &empty;
    }
    /* HDF5 prints its error stack by default: silence it while we write and
     * report errors ourselves; restore the caller's handler afterwards. */
    H5E_auto2_t old_fn = NULL;
    void *old_data = NULL;
    H5Eget_auto2(H5E_DEFAULT, &old_fn, &old_data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    sb_h5w w = { "" };
    int bad = write_file(run, stats, tmp, &w);
    H5Eset_auto2(H5E_DEFAULT, old_fn, old_data);
    if (bad) {
        unlink(tmp);
        snprintf(err, errlen, "cannot write record %s: HDF5 failed writing %s", path, w.failed);
        return SB_ERR_IO;
    }
    if ((rc = sb_record_seal(tmp, err, errlen)) != SB_OK) {
        unlink(tmp);
        return rc;
    }
    if (sb_record_fsync_path(tmp) != 0) {
        snprintf(err, errlen, "cannot write record %s: fsync of %s failed: %s", path, tmp, strerror(errno));
        unlink(tmp);
        return SB_ERR_IO;
    }
    unlink(xtmp);   /* fopen below would follow a link left there */
    rc = sb_record_write_xdmf(run, xtmp, sb_record_basename(path), err, errlen);
    const int steps = run->sample_traj && run->n_samples > 0;
    if (!rc && steps) rc = sb_record_write_steps_xdmf(run, stmp, sb_record_basename(path), err, errlen);
    const int mesh = run->mesh && run->mesh->rows > 0;
    if (mesh) unlink(mtmp);
    if (!rc && mesh) rc = sb_record_write_mesh_xdmf(run, mtmp, sb_record_basename(path), err, errlen);
    if (rc) {
        unlink(tmp);
        unlink(xtmp);
        if (steps) unlink(stmp);
        if (mesh) unlink(mtmp);
        return rc;
    }
    /* The record first: a sidecar never points at a record that is not there. */
    if (rename(tmp, path) != 0) {
        snprintf(err, errlen, "cannot write record %s: rename from %s failed: %s", path, tmp, strerror(errno));
        unlink(tmp);
        unlink(xtmp);
        if (steps) unlink(stmp);
        if (mesh) unlink(mtmp);
        return SB_ERR_IO;
    }
    if (rename(xtmp, xpath) != 0) {
        snprintf(err, errlen, "record %s written, but its XDMF sidecar %s could not be renamed into place: %s",
                 path, xpath, strerror(errno));
        unlink(xtmp);
        if (steps) unlink(stmp);
        if (mesh) unlink(mtmp);
        return SB_ERR_IO;
    }
    /* the time series; an older sidecar of a run that kept none would point at nothing */
    if (steps ? rename(stmp, spath) != 0 : (unlink(spath) != 0 && errno != ENOENT)) {
        snprintf(err, errlen, "record %s written, but its time-series sidecar %s could not be %s: %s", path, spath,
                 steps ? "renamed into place" : "removed", strerror(errno));
        if (steps) unlink(stmp);
        if (mesh) unlink(mtmp);
        return SB_ERR_IO;
    }
    if (mesh ? rename(mtmp, mpath) != 0 : (unlink(mpath) != 0 && errno != ENOENT)) {
        snprintf(err, errlen, "record %s written, but its mesh time-series sidecar %s could not be %s: %s", path, mpath,
                 mesh ? "renamed into place" : "removed", strerror(errno));
        if (mesh) unlink(mtmp);
        return SB_ERR_IO;
    }
    sb_record_fsync_dir(path);
    return SB_OK;
}
