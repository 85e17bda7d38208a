/* sb_record_read.c — reading run records back (for reports and for
 * reference-run errors).  Anything that is not a readable shellbench record
 * (missing, not HDF5, truncated, another program's HDF5 file, a newer
 * layout) gives SB_ERR_IO or SB_ERR_INPUT and one sentence naming the file,
 * never a crash.  Layout: docs/recorded_figures.md. */
#include "sb_record_io.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Per-event seconds summed over levels, matched by event name so a file
 * with a different event list still reads. */
static int read_event_seconds(sb_h5r *r, hid_t f, sb_record_summary *s)
{
    hsize_t dims[2], dself[2];
    double *sec = NULL, *self = NULL;
    int rc = sb_h5r_dset(r, f, "/stats/events_seconds", 2, H5T_NATIVE_DOUBLE, sizeof(double), dims, (void **)&sec);
    if (rc) return rc;
    /* format 3: exclusive seconds, same shape (older records: none) */
    if (H5Lexists(f, "/stats/events_self_seconds", H5P_DEFAULT) > 0 &&
        sb_h5r_dset(r, f, "/stats/events_self_seconds", 2, H5T_NATIVE_DOUBLE, sizeof(double), dself,
                    (void **)&self) == SB_OK && (dself[0] != dims[0] || dself[1] != dims[1])) {
        free(self);
        self = NULL;
    }
    s->has_self = self != NULL;
    if (self) {
        hid_t gs = H5Gopen2(f, "/stats", H5P_DEFAULT);
        double u = 0.0;
        if (gs >= 0 && H5Aexists(gs, "seconds_unattributed") > 0) sb_h5r_attr_dbl(r, gs, "seconds_unattributed", &u);
        if (gs >= 0) H5Gclose(gs);
        s->seconds_unattributed = u;
    }
    hid_t g = H5Gopen2(f, "/stats", H5P_DEFAULT);
    hid_t a = g < 0 ? -1 : H5Aopen(g, "event_names", H5P_DEFAULT);
    hid_t t = a < 0 ? -1 : H5Aget_type(a), sp = a < 0 ? -1 : H5Aget_space(a);
    char *names = NULL;
    size_t width = t < 0 ? 0 : H5Tget_size(t);
    if (t < 0 || sp < 0 || H5Tget_class(t) != H5T_STRING || H5Tis_variable_str(t) != 0 || width == 0 ||
        H5Sget_simple_extent_npoints(sp) != (hssize_t)dims[1]) {
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "bad attribute", "/stats/event_names");
    } else if (!(names = calloc(dims[1] ? dims[1] : 1, width + 1))) {
        rc = SB_ERR_NOMEM;
        snprintf(r->err, r->errlen, "out of memory reading %s", r->path);
    } else if (dims[1] > 0 && H5Aread(a, t, names) < 0) {
        rc = sb_h5r_fail(r, SB_ERR_IO, "cannot read attribute", "/stats/event_names");
    } else {
        for (hsize_t c = 0; c < dims[1]; c++) {
            char name[64];
            snprintf(name, sizeof name, "%.*s", (int)(width < 63 ? width : 63), names + c * width);
            for (int e = 0; e < SB_EV_COUNT; e++)
                if (strcmp(name, sb_event_name((sb_event)e)) == 0)
                    for (hsize_t l = 0; l < dims[0]; l++) {
                        s->seconds_event[e] += sec[l * dims[1] + c];
                        if (self) s->seconds_self[e] += self[l * dims[1] + c];
                    }
        }
    }
    free(names);
    if (sp >= 0) H5Sclose(sp);
    if (t >= 0) H5Tclose(t);
    if (a >= 0) H5Aclose(a);
    if (g >= 0) H5Gclose(g);
    free(sec);
    free(self);
    return rc;
}

static int read_history(sb_h5r *r, hid_t f, sb_record_summary *s)
{
    hsize_t dg, ds, dl, di, dn;
    int *steps_iters = NULL;
    int rc = sb_h5r_dset(r, f, "/history/iterations/gnorm", 1, H5T_NATIVE_DOUBLE, sizeof(double), &dg, (void **)&s->hist_gnorm);
    if (!rc) rc = sb_h5r_dset(r, f, "/history/iterations/step", 1, H5T_NATIVE_INT, sizeof(int), &ds, (void **)&s->hist_step);
    if (!rc) rc = sb_h5r_dset(r, f, "/history/iterations/level", 1, H5T_NATIVE_INT, sizeof(int), &dl, (void **)&s->hist_level);
    if (!rc) rc = sb_h5r_dset(r, f, "/history/iterations/iter", 1, H5T_NATIVE_INT, sizeof(int), &di, (void **)&s->hist_iter);
    if (!rc && (ds != dg || dl != dg || di != dg)) rc = sb_h5r_fail(r, SB_ERR_INPUT, "columns of different lengths in", "/history/iterations");
    if (!rc && dg > (hsize_t)INT32_MAX) rc = sb_h5r_fail(r, SB_ERR_INPUT, "too many records in", "/history/iterations");
    if (!rc) rc = sb_h5r_dset(r, f, "/history/steps/iterations", 1, H5T_NATIVE_INT, sizeof(int), &dn, (void **)&steps_iters);
    if (rc) {
        free(steps_iters);
        return rc;
    }
    s->n_hist = (int)dg;
    /* Iterations: the per-step counts when steps were recorded (in a
     * checkpoint also those of the step under way), else the
     * history records of the finest level present (coarse-level records of
     * a multilevel solver are not outer iterations). */
    long it = 0;
    if (s->status == SB_STATUS_UNFINISHED) {
        /* a checkpoint: the finished steps plus the iterations so far of the
         * step under way (history records past the last step record) */
        for (hsize_t i = 0; i < dn; i++) it += steps_iters[i];
        for (int i = 0; i < s->n_hist; i++) it += s->hist_step[i] > (int)dn && s->hist_iter[i] > 0;
    } else if (dn > 0) {
        for (hsize_t i = 0; i < dn; i++) it += steps_iters[i];
    } else {
        int finest = 0;
        for (int i = 0; i < s->n_hist; i++) if (s->hist_level[i] > finest) finest = s->hist_level[i];
        for (int i = 0; i < s->n_hist; i++) it += s->hist_level[i] == finest;
    }
    s->iterations = it > INT32_MAX ? INT32_MAX : (int)it;
    free(steps_iters);
    return SB_OK;
}

/* "key=value, ..." of the /params attributes named in /params/_overridden */
static int read_overrides(sb_h5r *r, hid_t f, sb_record_summary *s)
{
    s->overrides[0] = 0;
    if (H5Lexists(f, "/params", H5P_DEFAULT) <= 0) return sb_h5r_fail(r, SB_ERR_INPUT, "missing group", "/params");
    hid_t g = H5Gopen2(f, "/params", H5P_DEFAULT);
    if (g < 0) return sb_h5r_fail(r, SB_ERR_INPUT, "cannot open group", "/params");
    char *list = NULL;
    int rc = H5Aexists(g, "_overridden") > 0 ? sb_h5r_attr_str_alloc(r, g, "_overridden", &list) : SB_OK;
    size_t used = 0;
    for (char *key = list ? strtok(list, ",") : NULL; key && !rc; key = strtok(NULL, ",")) {
        char value[128] = "?";
        if (H5Aexists(g, key) <= 0) continue;
        hid_t a = H5Aopen(g, key, H5P_DEFAULT);
        hid_t t = a < 0 ? -1 : H5Aget_type(a);
        H5T_class_t c = t < 0 ? H5T_NO_CLASS : H5Tget_class(t);
        if (t >= 0) H5Tclose(t);
        if (a >= 0) H5Aclose(a);
        if (c == H5T_STRING) {
            rc = sb_h5r_attr_str(r, g, key, value, sizeof value);
        } else if (c == H5T_INTEGER || c == H5T_FLOAT) {
            double v = 0;
            rc = sb_h5r_attr_dbl(r, g, key, &v);
            snprintf(value, sizeof value, "%.10g", v);
        }
        int n = snprintf(s->overrides + used, sizeof s->overrides - used, "%s%s=%s", used ? ", " : "", key, value);
        if (n < 0 || used + (size_t)n >= sizeof s->overrides) break;
        used += (size_t)n;
    }
    free(list);
    H5Gclose(g);
    return rc;
}

int sb_record_read_summary(const char *path, sb_record_summary *s, char *err, size_t errlen)
{
    if (!s) return SB_ERR_INPUT;
    memset(s, 0, sizeof *s);
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    int rc = sb_h5r_open(&r, &f);
    hid_t ge = -1, gs = -1;
    if (!rc) {
        long dofs_l = 0;
        rc = sb_h5r_attr_str(&r, f, "scene_name", s->scene, sizeof s->scene);
        if (!rc) rc = sb_h5r_attr_str(&r, f, "method", s->method, sizeof s->method);
        if (!rc) rc = sb_h5r_attr_str(&r, f, "solver", s->solver, sizeof s->solver);
        if (!rc) rc = sb_h5r_attr_num(&r, f, "n_dofs", H5T_NATIVE_LONG, &dofs_l);
        s->dofs = dofs_l;
        if (!rc) rc = sb_h5r_attr_int(&r, f, "levels", &s->levels);
        if (!rc) rc = sb_h5r_attr_int(&r, f, "res", &s->res);
        if (!rc && H5Aexists(f, "res_t") > 0) rc = sb_h5r_attr_int(&r, f, "res_t", &s->res_t);
        if (!rc) rc = sb_h5r_attr_int(&r, f, "steps_done", &s->steps);
        if (!rc) rc = sb_h5r_attr_int(&r, f, "steps_planned", &s->steps_planned);
        if (!rc) rc = sb_h5r_attr_int(&r, f, "status", &s->status);
        if (!rc) rc = sb_h5r_attr_int(&r, f, "reason_code", &s->reason);
        if (!rc) rc = sb_h5r_attr_str(&r, f, "reason", s->reason_name, sizeof s->reason_name);
        if (!rc) rc = sb_h5r_attr_int(&r, f, "n_cores", &s->n_cores);
        if (!rc) rc = sb_h5r_attr_str(&r, f, "build_id", s->build_id, sizeof s->build_id);
        if (!rc) rc = sb_h5r_attr_str(&r, f, "cpu_model", s->cpu_model, sizeof s->cpu_model);
        snprintf(s->blas_core, sizeof s->blas_core, "unknown");
        if (!rc && H5Aexists(f, "blas_core") > 0) rc = sb_h5r_attr_str(&r, f, "blas_core", s->blas_core, sizeof s->blas_core);
        if (!rc) rc = sb_h5r_attr_str(&r, f, "started", s->started, sizeof s->started);
        if (!rc && H5Aexists(f, "resumes") > 0) rc = sb_h5r_attr_int(&r, f, "resumes", &s->resumes);
        if (!rc && H5Aexists(f, "resume_steps") > 0)
            rc = sb_h5r_attr_str(&r, f, "resume_steps", s->resume_steps, sizeof s->resume_steps);
        s->potential_change = NAN;
        if (!rc && H5Aexists(f, "validation") > 0)
            rc = sb_h5r_attr_str(&r, f, "validation", s->validation, sizeof s->validation);
        if (!rc && H5Aexists(f, "potential_change") > 0)
            rc = sb_h5r_attr_dbl(&r, f, "potential_change", &s->potential_change);
        s->energy_final = NAN;
        if (!rc && H5Aexists(f, "energy_final") > 0) rc = sb_h5r_attr_dbl(&r, f, "energy_final", &s->energy_final);
        s->below_reference = NAN;
        if (!rc && H5Lexists(f, "/final", H5P_DEFAULT) > 0 && H5Lexists(f, "/final/material", H5P_DEFAULT) > 0) {
            hid_t gm = H5Gopen2(f, "/final/material", H5P_DEFAULT);
            if (gm >= 0) {
                if (H5Aexists(gm, "below_reference_area_fraction") > 0)
                    rc = sb_h5r_attr_dbl(&r, gm, "below_reference_area_fraction", &s->below_reference);
                H5Gclose(gm);
            }
        }
        s->resume_point = -1;
        hid_t gr = rc || H5Lexists(f, "/resume", H5P_DEFAULT) <= 0 ? -1 : H5Gopen2(f, "/resume", H5P_DEFAULT);
        if (gr >= 0) {
            rc = sb_h5r_attr_int(&r, gr, "step", &s->resume_point);
            H5Gclose(gr);
        }
    }
    if (!rc && (gs = H5Gopen2(f, "/stats", H5P_DEFAULT)) < 0) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "missing group", "/stats");
    if (!rc) rc = sb_h5r_attr_dbl(&r, gs, "work_assembly", &s->work_assembly);
    if (!rc) rc = sb_h5r_attr_dbl(&r, gs, "work_qp", &s->work_qp);
    if (!rc) rc = sb_h5r_attr_dbl(&r, gs, "seconds_total", &s->seconds);
    if (!rc) rc = read_event_seconds(&r, f, s);
    if (!rc) rc = read_overrides(&r, f, s);
    if (!rc) rc = read_history(&r, f, s);
    if (!rc && (ge = H5Gopen2(f, "/error", H5P_DEFAULT)) < 0) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "missing group", "/error");
    if (!rc) rc = sb_h5r_attr_int(&r, ge, "has_error", &s->has_error);
    if (!rc) rc = sb_h5r_attr_str(&r, ge, "kind", s->error_kind, sizeof s->error_kind);
    if (!rc) rc = sb_h5r_attr_dbl(&r, ge, "rms", &s->error_rms);
    if (!rc) rc = sb_h5r_attr_dbl(&r, ge, "max", &s->error_max);
    if (!rc) rc = sb_h5r_attr_dbl(&r, ge, "probe", &s->error_probe);
    if (ge >= 0) H5Gclose(ge);
    if (gs >= 0) H5Gclose(gs);
    sb_h5r_close(&r, f);
    if (rc) sb_record_summary_free(s);
    return rc;
}

void sb_record_library_init(void) { H5dont_atexit(); }

const char *sb_record_status_name(int status)
{
    return status == 0 ? "converged" : status == 1 ? "not converged" : status == SB_STATUS_UNFINISHED ? "unfinished"
         : status < 0 ? "failed" : "unknown";
}

void sb_record_summary_free(sb_record_summary *s)
{
    if (!s) return;
    free(s->hist_gnorm);
    free(s->hist_step);
    free(s->hist_level);
    free(s->hist_iter);
    s->hist_iter = NULL;
    s->hist_gnorm = NULL;
    s->hist_step = NULL;
    s->hist_level = NULL;
    s->n_hist = 0;
}

int sb_record_read_samples(const char *path, int *n, double **st, double **pos,
                           char *err, size_t errlen)
{
    if (!n || !st || !pos) return SB_ERR_INPUT;
    *n = 0;
    *st = *pos = NULL;
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    hsize_t ds[2], dp[2];
    int rc = sb_h5r_open(&r, &f);
    if (!rc) rc = sb_h5r_dset(&r, f, "/final/sample_st", 2, H5T_NATIVE_DOUBLE, sizeof(double), ds, (void **)st);
    if (!rc) rc = sb_h5r_dset(&r, f, "/final/sample_pos", 2, H5T_NATIVE_DOUBLE, sizeof(double), dp, (void **)pos);
    if (!rc && (ds[1] != 2 || dp[1] != 3 || ds[0] != dp[0] || ds[0] > (hsize_t)INT32_MAX))
        rc = sb_h5r_fail(&r, SB_ERR_INPUT, "inconsistent shapes of", "/final/sample_st and /final/sample_pos");
    sb_h5r_close(&r, f);
    if (rc) {
        free(*st);
        free(*pos);
        *st = *pos = NULL;
        return rc;
    }
    *n = (int)ds[0];
    return SB_OK;
}

typedef struct param_walk {
    sb_h5r *r;
    sb_record_setup *s;
    int rc;
} param_walk;

/* one /params attribute "method.KEY" as the assignment "method.KEY=VALUE";
 * solver.linear into s->linear (a study's configurations differ by it) */
static herr_t collect_param(hid_t loc, const char *name, const H5A_info_t *info, void *data)
{
    (void)info;
    param_walk *w = data;
    if (!strcmp(name, "solver.linear")) {
        w->rc = sb_h5r_attr_str(w->r, loc, name, w->s->linear, sizeof w->s->linear);
        return w->rc ? -1 : 0;
    }
    if (strncmp(name, "method.", 7) != 0 || w->s->n_sets >= SB_RECORD_MAX_SETS) return 0;
    char value[256];
    hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
    hid_t t = a < 0 ? -1 : H5Aget_type(a);
    H5T_class_t c = t < 0 ? H5T_NO_CLASS : H5Tget_class(t);
    int rc = SB_OK;
    if (c == H5T_STRING) {
        rc = sb_h5r_attr_str(w->r, loc, name, value, sizeof value);
    } else if (c == H5T_INTEGER) {
        long long v = 0;
        rc = sb_h5r_attr_num(w->r, loc, name, H5T_NATIVE_LLONG, &v);
        snprintf(value, sizeof value, "%lld", v);
    } else if (c == H5T_FLOAT) {
        double v = 0;
        rc = sb_h5r_attr_num(w->r, loc, name, H5T_NATIVE_DOUBLE, &v);
        snprintf(value, sizeof value, "%.17g", v);
    } else {
        rc = sb_h5r_fail(w->r, SB_ERR_INPUT, "parameter of unknown type:", name);
    }
    if (t >= 0) H5Tclose(t);
    if (a >= 0) H5Aclose(a);
    if (!rc) snprintf(w->s->sets[w->s->n_sets++], sizeof w->s->sets[0], "%s=%s", name, value);
    w->rc = rc;
    return rc ? -1 : 0;
}

static int read_setup(const char *path, sb_record_setup *s, int want_x, char *err, size_t errlen)
{
    if (!s) return SB_ERR_INPUT;
    memset(s, 0, sizeof *s);
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f, gp = -1;
    hsize_t dx;
    int rc = sb_h5r_open(&r, &f);
    if (!rc) rc = sb_h5r_attr_str_alloc(&r, f, "scene_json", &s->scene_json);
    if (!rc) rc = sb_h5r_attr_str(&r, f, "scene_path", s->scene_path, sizeof s->scene_path);
    if (!rc) rc = sb_h5r_attr_str(&r, f, "scene_name", s->scene, sizeof s->scene);
    if (!rc) rc = sb_h5r_attr_str(&r, f, "method", s->method, sizeof s->method);
    if (!rc) rc = sb_h5r_attr_str(&r, f, "solver", s->solver, sizeof s->solver);
    if (!rc) rc = sb_h5r_attr_int(&r, f, "res", &s->res);
    if (!rc && H5Aexists(f, "res_t") > 0) rc = sb_h5r_attr_int(&r, f, "res_t", &s->res_t);
    if (!rc) rc = sb_h5r_attr_int(&r, f, "levels", &s->levels);
    if (!rc) rc = sb_h5r_attr_int(&r, f, "status", &s->status);
    if (!rc) rc = sb_h5r_attr_int(&r, f, "steps_done", &s->steps_done);
    if (!rc && (gp = H5Gopen2(f, "/params", H5P_DEFAULT)) < 0) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "missing group", "/params");
    if (!rc) {
        param_walk w = { &r, s, SB_OK };
        hsize_t idx = 0;
        if (H5Aiterate2(gp, H5_INDEX_NAME, H5_ITER_INC, &idx, collect_param, &w) < 0)
            rc = w.rc ? w.rc : sb_h5r_fail(&r, SB_ERR_IO, "cannot list the attributes of", "/params");
    }
    if (!rc && want_x) {
        rc = sb_h5r_dset(&r, f, "/final/x", 1, H5T_NATIVE_DOUBLE, sizeof(double), &dx, (void **)&s->x);
        if (!rc && dx > (hsize_t)INT32_MAX) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "implausibly long", "/final/x");
        if (!rc) s->n_x = (int)dx;
    }
    if (gp >= 0) H5Gclose(gp);
    sb_h5r_close(&r, f);
    if (rc) sb_record_setup_free(s);
    return rc;
}

int sb_record_read_setup(const char *path, sb_record_setup *s, char *err, size_t errlen)
{
    return read_setup(path, s, 1, err, errlen);
}

int sb_record_read_identity(const char *path, sb_record_setup *s, char *err, size_t errlen)
{
    return read_setup(path, s, 0, err, errlen);
}

void sb_record_setup_free(sb_record_setup *s)
{
    if (!s) return;
    free(s->scene_json);
    free(s->x);
    s->scene_json = NULL;
    s->x = NULL;
    s->n_x = 0;
}

int sb_record_keeps_state(const char *path, char *err, size_t errlen)
{
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    int rc = sb_h5r_open(&r, &f);
    if (!rc) rc = H5Lexists(f, "/final", H5P_DEFAULT) > 0 && H5Lexists(f, "/final/x", H5P_DEFAULT) > 0;
    sb_h5r_close(&r, f);
    return rc;
}
