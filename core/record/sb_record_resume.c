/* sb_record_resume.c — step-boundary resume points in checkpoints.
 *
 * A checkpoint (OUT.partial) holds, besides the record so far, the group
 * /resume: the state x, v at the end of the last completed step and the
 * statistics at that moment (event counts and seconds per level, work
 * units); /history up to that boundary is the first n_iters / n_steps rows
 * of the checkpoint's own /history.  The solvers keep no state across steps
 * (every step restarts from Delta_0, a fresh factorization of the new
 * Hessian, ...), so a run resumed from such a point computes, bit for bit,
 * the steps an uninterrupted run would have computed.  Layout:
 * docs/recorded_figures.md "/resume". */
#include "sb_record_io.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- writing ------------------------------------------------------------- */

int sb_record_write_resume_log(sb_h5w *w, hid_t f, const sb_resume_log *log)
{
    int bad = 0;
    bad |= sb_h5w_attr_long(w, f, "resumes", log->count);
    bad |= sb_h5w_attr_str(w, f, "resume_steps", log->steps);
    bad |= sb_h5w_attr_dbl(w, f, "resume_setup_seconds", log->setup_seconds);
    bad |= sb_h5w_attr_dbl(w, f, "resume_lost_seconds", log->lost_seconds);
    bad |= sb_h5w_attr_str(w, f, "resume_builds", log->builds);
    return bad ? -1 : 0;
}

int sb_record_write_resume(sb_h5w *w, hid_t f, const sb_resume_point *rp)
{
    hid_t g = sb_h5w_group(w, f, "/resume");
    if (g < 0) return -1;
    const sb_stats *s = &rp->stats;
    long cnt[SB_MAX_LEVELS * SB_EV_COUNT];
    double sec[SB_MAX_LEVELS * SB_EV_COUNT], self[SB_MAX_LEVELS * SB_EV_COUNT];
    for (int l = 0; l < SB_MAX_LEVELS; l++)
        for (int e = 0; e < SB_EV_COUNT; e++) {
            cnt[l * SB_EV_COUNT + e] = s->ev[l][e].count;
            sec[l * SB_EV_COUNT + e] = s->ev[l][e].seconds;
            self[l * SB_EV_COUNT + e] = s->ev[l][e].self;
        }
    hsize_t dx = (hsize_t)rp->n_x, d2[2] = { SB_MAX_LEVELS, SB_EV_COUNT };
    int bad = 0;
    bad |= sb_h5w_attr_long(w, g, "step", rp->step);
    bad |= sb_h5w_attr_long(w, g, "n_iters", (long)s->n_iters);
    bad |= sb_h5w_attr_long(w, g, "n_steps", (long)s->n_steps);
    bad |= sb_h5w_attr_dbl(w, g, "seconds", rp->seconds);
    bad |= sb_h5w_attr_dbl(w, g, "work_assembly", s->work_assembly);
    bad |= sb_h5w_attr_dbl(w, g, "work_qp", s->work_qp);
    bad |= sb_h5w_attr_long(w, g, "not_posdef", s->not_posdef);
    bad |= sb_h5w_dset_dbl(w, g, "x", 1, &dx, rp->x, NULL);
    bad |= sb_h5w_dset_dbl(w, g, "v", 1, &dx, rp->v, NULL);
    bad |= sb_h5w_dset_long(w, g, "events_count", 2, d2, cnt, "calls");
    bad |= sb_h5w_dset_dbl(w, g, "events_seconds", 2, d2, sec, "s");
    bad |= sb_h5w_dset_dbl(w, g, "events_self_seconds", 2, d2, self, "s");
    bad |= sb_h5w_dset_dbl(w, g, "chol_flops_sum", 1, d2, s->chol_flops_sum, "flop");
    bad |= sb_h5w_dset_dbl(w, g, "chol_nnz_l_sum", 1, d2, s->chol_nnz_l_sum, "entries");
    bad |= sb_h5w_dset_dbl(w, g, "chol_factorize_cpu", 1, d2, s->chol_factorize_cpu, "s");
    bad |= sb_h5w_dset_dbl(w, g, "chol_first_factorize_cpu", 1, d2, s->chol_first_cpu, "s");
    bad |= sb_h5w_dset_dbl(w, g, "chol_first_flops", 1, d2, s->chol_first_flops, "flop");
    if (rp->has_impulse) {
        long a[SB_IMPULSE_N_COUNTS];
        hsize_t dn = SB_IMPULSE_N_COUNTS;
        sb_impulse_to_array(&rp->impulse, a);
        bad |= sb_h5w_dset_long(w, g, "impulse_counts", 1, &dn, a, NULL);
    }
    if (rp->has_mesh) {
        /* the adaptive method's discretization at the boundary (sb_method.h save_mesh) */
        hsize_t di = (hsize_t)rp->mesh.n_int, dd = (hsize_t)rp->mesh.n_dbl;
        bad |= sb_h5w_dset_int(w, g, "mesh_ints", 1, &di, rp->mesh.ints, NULL);
        bad |= sb_h5w_dset_dbl(w, g, "mesh_doubles", 1, &dd, rp->mesh.dbls, NULL);
    }
    H5Gclose(g);
    return bad ? -1 : 0;
}

/* ---- reading ------------------------------------------------------------- */

static int mismatch(sb_h5r *r, const char *field, const char *theirs, const char *ours)
{
    snprintf(r->err, r->errlen, "cannot resume from %s: its %s is %s, this run's is %s", r->path, field, theirs, ours);
    return SB_ERR_INPUT;
}

/* The checkpoint is of the run `e`: same scene text, method, solver,
 * resolution, levels, dofs. */
static int check_identity(sb_h5r *r, hid_t f, const sb_run *e)
{
    char buf[SB_NAME_LEN], a[64], b[64];
    char *json = NULL;
    long n = 0;
    int res = 0, levels = 0;
    int rc = sb_h5r_attr_str(r, f, "method", buf, sizeof buf);
    if (!rc && strcmp(buf, e->method)) return mismatch(r, "method", buf, e->method);
    if (!rc) rc = sb_h5r_attr_str(r, f, "solver", buf, sizeof buf);
    if (!rc && strcmp(buf, e->solver)) return mismatch(r, "solver", buf, e->solver);
    if (!rc) rc = sb_h5r_attr_int(r, f, "res", &res);
    int res_t = 0;
    if (!rc && H5Aexists(f, "res_t") > 0) rc = sb_h5r_attr_int(r, f, "res_t", &res_t);
    if (!rc && res_t != e->res_t) {
        snprintf(a, sizeof a, "%d", res_t);
        snprintf(b, sizeof b, "%d", e->res_t);
        return mismatch(r, "res_t (elements along t)", a, b);
    }
    if (!rc && res != e->res && res != 0) {   /* 0: an older build's "the scene's resolution"; n_dofs decides */
        snprintf(a, sizeof a, "%d", res);
        snprintf(b, sizeof b, "%d", e->res);
        return mismatch(r, "res", a, b);
    }
    if (!rc) rc = sb_h5r_attr_int(r, f, "levels", &levels);
    if (!rc && levels != e->levels) {
        snprintf(a, sizeof a, "%d", levels);
        snprintf(b, sizeof b, "%d", e->levels);
        return mismatch(r, "levels", a, b);
    }
    if (!rc) rc = sb_h5r_attr_num(r, f, "n_dofs", H5T_NATIVE_LONG, &n);
    /* an adaptive method's checkpoint holds its mesh: its dofs are checked against the restored mesh */
    const int has_mesh = H5Lexists(f, "/resume", H5P_DEFAULT) > 0 && H5Lexists(f, "/resume/mesh_ints", H5P_DEFAULT) > 0;
    if (!rc && n != e->n_dofs && !has_mesh) {
        snprintf(a, sizeof a, "%ld", n);
        snprintf(b, sizeof b, "%ld", e->n_dofs);
        return mismatch(r, "n_dofs", a, b);
    }
    if (!rc) rc = sb_h5r_attr_str_alloc(r, f, "scene_json", &json);
    if (!rc && strcmp(json, e->scene_json ? e->scene_json : "")) rc = mismatch(r, "scene text", "another", e->scene_path);
    free(json);
    /* the obstacle meshes' contents (an OBJ edited since the checkpoint: the scene text is the same) */
    char sums[sizeof e->obstacle_meshes] = "";
    if (!rc && H5Aexists(f, "obstacle_meshes") > 0) rc = sb_h5r_attr_str(r, f, "obstacle_meshes", sums, sizeof sums);
    if (!rc && strcmp(sums, e->obstacle_meshes)) {
        snprintf(r->err, r->errlen, "cannot resume from %s: the scene's obstacle meshes changed since the checkpoint "
                 "was written (an OBJ file was edited): checkpoint [%s], this run [%s]; run again without --resume",
                 r->path, sums[0] ? sums : "no mesh checksums", e->obstacle_meshes[0] ? e->obstacle_meshes : "none");
        rc = SB_ERR_INPUT;
    }
    return rc;
}

/* Every resolved parameter of this run has the checkpoint's value, but for
 * those that change where and how a run is kept, not what it computes:
 * run.checkpoint (the checkpoint interval) and run.max_memory (the memory
 * limit) may differ, and may be absent from checkpoints of older builds. */
static int check_params(sb_h5r *r, hid_t f, const sb_paramset *ps)
{
    hid_t g = H5Gopen2(f, "/params", H5P_DEFAULT);
    if (g < 0) return sb_h5r_fail(r, SB_ERR_INPUT, "missing group", "/params");
    int rc = SB_OK;
    for (int i = 0; ps && i < ps->n && !rc; i++) {
        const sb_param_value *v = &ps->v[i];
        if (!v->def || strcmp(v->key, "run.checkpoint") == 0 || strcmp(v->key, "run.max_memory") == 0) continue;
        char ours[SB_NAME_LEN], theirs[SB_NAME_LEN], field[SB_NAME_LEN + 16];
        snprintf(field, sizeof field, "parameter %s", v->key);
        sb_param_format(v, ours, sizeof ours);
        if (H5Aexists(g, v->key) <= 0) { rc = mismatch(r, field, "absent", ours); break; }
        if (v->def->kind == SB_PARAM_CHOICE) {
            rc = sb_h5r_attr_str(r, g, v->key, theirs, sizeof theirs);
            if (!rc && strcmp(theirs, ours)) rc = mismatch(r, field, theirs, ours);
        } else {
            double d = 0;
            rc = sb_h5r_attr_dbl(r, g, v->key, &d);
            snprintf(theirs, sizeof theirs, "%.17g", d);
            if (!rc && d != v->value) rc = mismatch(r, field, theirs, ours);
        }
    }
    H5Gclose(g);
    return rc;
}

/* The first n rows of the history columns under `group` into recs
 * (rec_size bytes each); every column must hold at least n rows, but for
 * /history/steps/triangles, which checkpoints of builds before it lack
 * (their rows get 0). */
static int read_columns(sb_h5r *r, hid_t f, const char *group, const sb_record_column *cols, int ncols,
                        void *recs, size_t rec_size, size_t n)
{
    for (int c = 0; c < ncols; c++) {
        char name[128];
        snprintf(name, sizeof name, "%s/%s", group, cols[c].name);
        hsize_t d = 0;
        void *buf = NULL;
        /* columns newer than some checkpoints: absent reads as zeros */
        if ((cols[c].since_v3 || strcmp(cols[c].name, "triangles") == 0 || strncmp(cols[c].name, "krylov_", 7) == 0) &&
            H5Lexists(f, name, H5P_DEFAULT) <= 0)
            continue;
        int rc = sb_h5r_dset(r, f, name, 1, cols[c].is_int ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
                             cols[c].is_int ? sizeof(int) : sizeof(double), &d, &buf);
        if (!rc && d < n) rc = sb_h5r_fail(r, SB_ERR_INPUT, "too few rows before the resume point in", name);
        for (size_t i = 0; !rc && i < n; i++)
            memcpy((char *)recs + i * rec_size + cols[c].off, (char *)buf + i * (cols[c].is_int ? sizeof(int) : sizeof(double)),
                   cols[c].is_int ? sizeof(int) : sizeof(double));
        free(buf);
        if (rc) return rc;
    }
    return SB_OK;
}

static int read_log(sb_h5r *r, hid_t f, sb_resume_log *log)
{
    memset(log, 0, sizeof *log);
    if (H5Aexists(f, "resumes") <= 0) return SB_OK;   /* written before resumes existed: none */
    int rc = sb_h5r_attr_int(r, f, "resumes", &log->count);
    if (!rc) rc = sb_h5r_attr_str(r, f, "resume_steps", log->steps, sizeof log->steps);
    if (!rc) rc = sb_h5r_attr_dbl(r, f, "resume_setup_seconds", &log->setup_seconds);
    if (!rc) rc = sb_h5r_attr_dbl(r, f, "resume_lost_seconds", &log->lost_seconds);
    if (!rc) rc = sb_h5r_attr_str(r, f, "resume_builds", log->builds, sizeof log->builds);
    return rc;
}

/* events_count / events_seconds of /resume: SB_MAX_LEVELS x the file's
 * events, matched by name (/stats/event_names); events this build has and
 * the file does not (a checkpoint of an older build) start at zero, an
 * event the file has and this build does not is refused. */
static int read_events(sb_h5r *r, hid_t f, sb_stats *s)
{
    hsize_t d1[2], d2[2];
    long *cnt = NULL;
    double *sec = NULL, *self = NULL, *fl = NULL, *lz = NULL, *fc = NULL, *f1c = NULL, *f1f = NULL;
    hsize_t d3[2], d4[2] = { 0, 0 }, d5[2] = { 0, 0 }, d6[2] = { 0, 0 }, d7[2] = { 0, 0 }, d8[2] = { 0, 0 };
    int rc = sb_h5r_dset(r, f, "/resume/events_count", 2, H5T_NATIVE_LONG, sizeof(long), d1, (void **)&cnt);
    if (!rc) rc = sb_h5r_dset(r, f, "/resume/events_seconds", 2, H5T_NATIVE_DOUBLE, sizeof(double), d2, (void **)&sec);
    /* format version 3 (issue 42): exclusive seconds and CHOLMOD sums; older checkpoints have neither */
    if (!rc && H5Lexists(f, "/resume/events_self_seconds", H5P_DEFAULT) > 0) {
        rc = sb_h5r_dset(r, f, "/resume/events_self_seconds", 2, H5T_NATIVE_DOUBLE, sizeof(double), d3, (void **)&self);
        if (!rc && (d3[0] != d2[0] || d3[1] != d2[1]))
            rc = sb_h5r_fail(r, SB_ERR_INPUT, "event table of another shape in", "/resume/events_self_seconds");
    }
    if (!rc && H5Lexists(f, "/resume/chol_flops_sum", H5P_DEFAULT) > 0 &&
        !(rc = sb_h5r_dset(r, f, "/resume/chol_flops_sum", 1, H5T_NATIVE_DOUBLE, sizeof(double), d4, (void **)&fl)) &&
        H5Lexists(f, "/resume/chol_nnz_l_sum", H5P_DEFAULT) > 0)
        rc = sb_h5r_dset(r, f, "/resume/chol_nnz_l_sum", 1, H5T_NATIVE_DOUBLE, sizeof(double), d5, (void **)&lz);
    /* format 4: CPU seconds of the factorizations; an older checkpoint's start from zero */
    if (!rc && H5Lexists(f, "/resume/chol_factorize_cpu", H5P_DEFAULT) > 0)
        rc = sb_h5r_dset(r, f, "/resume/chol_factorize_cpu", 1, H5T_NATIVE_DOUBLE, sizeof(double), d6, (void **)&fc);
    /* format 5: the first factorization after each analysis, apart */
    if (!rc && H5Lexists(f, "/resume/chol_first_factorize_cpu", H5P_DEFAULT) > 0 &&
        !(rc = sb_h5r_dset(r, f, "/resume/chol_first_factorize_cpu", 1, H5T_NATIVE_DOUBLE, sizeof(double), d7,
                           (void **)&f1c)) &&
        H5Lexists(f, "/resume/chol_first_flops", H5P_DEFAULT) > 0)
        rc = sb_h5r_dset(r, f, "/resume/chol_first_flops", 1, H5T_NATIVE_DOUBLE, sizeof(double), d8, (void **)&f1f);
    for (int l = 0; !rc && l < SB_MAX_LEVELS; l++) {
        if (fl && (hsize_t)l < d4[0]) s->chol_flops_sum[l] = fl[l];
        if (lz && (hsize_t)l < d5[0]) s->chol_nnz_l_sum[l] = lz[l];
        if (fc && (hsize_t)l < d6[0]) s->chol_factorize_cpu[l] = fc[l];
        if (f1c && (hsize_t)l < d7[0]) s->chol_first_cpu[l] = f1c[l];
        if (f1f && (hsize_t)l < d8[0]) s->chol_first_flops[l] = f1f[l];
    }
    free(fl);
    free(lz);
    free(fc);
    free(f1c);
    free(f1f);
    if (!rc && (d1[0] != SB_MAX_LEVELS || d1[1] < 1 || d1[1] > 64 || d2[0] != d1[0] || d2[1] != d1[1]))
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "event table of another shape (another build's event list) in", "/resume");
    hid_t g = rc ? -1 : H5Gopen2(f, "/stats", H5P_DEFAULT);
    hid_t a = g < 0 ? -1 : H5Aopen(g, "event_names", H5P_DEFAULT);
    hid_t t = a < 0 ? -1 : H5Aget_type(a), sp = a < 0 ? -1 : H5Aget_space(a);
    size_t width = t < 0 ? 0 : H5Tget_size(t);
    const int ne = rc ? 0 : (int)d1[1];
    char *names = width && ne ? calloc((size_t)ne, width + 1) : NULL;
    if (!rc && (!names || sp < 0 || H5Sget_simple_extent_npoints(sp) != ne || H5Tget_class(t) != H5T_STRING ||
                H5Aread(a, t, names) < 0))
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "cannot read", "/stats/event_names");
    for (int c = 0; !rc && c < ne; c++) {
        char name[64];
        int e = 0;
        snprintf(name, sizeof name, "%.*s", (int)(width < 63 ? width : 63), names + (size_t)c * width);
        while (e < SB_EV_COUNT && strcmp(name, sb_event_name((sb_event)e))) e++;
        if (e == SB_EV_COUNT) {
            rc = sb_h5r_fail(r, SB_ERR_INPUT, "event unknown to this build in", "/stats/event_names");
            break;
        }
        for (int l = 0; l < SB_MAX_LEVELS; l++) {
            s->ev[l][e].count = cnt[l * ne + c];
            s->ev[l][e].seconds = sec[l * ne + c];
            s->ev[l][e].self = self ? self[l * ne + c] : sec[l * ne + c];   /* older: as inclusive */
        }
    }
    free(names);
    if (sp >= 0) H5Sclose(sp);
    if (t >= 0) H5Tclose(t);
    if (a >= 0) H5Aclose(a);
    if (g >= 0) H5Gclose(g);
    free(cnt);
    free(sec);
    free(self);
    return rc;
}

int sb_record_read_resume(const char *path, const sb_run *expect, sb_resume_point *rp, double *ckpt_seconds,
                          char *ckpt_build, size_t build_len, sb_resume_log *log, double *probe_traj,
                          char *err, size_t errlen)
{
    memset(rp, 0, sizeof *rp);
    sb_stats_init(&rp->stats);
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f, g = -1, gs = -1;
    int rc = sb_h5r_open(&r, &f), status = 0;
    long n_iters = 0, n_steps = 0;
    if (!rc) rc = sb_h5r_attr_int(&r, f, "status", &status);
    if (!rc && status != SB_STATUS_UNFINISHED) rc = mismatch(&r, "status", "finished", "a checkpoint's (2)");
    if (!rc) rc = check_identity(&r, f, expect);
    if (!rc) rc = check_params(&r, f, expect->params);
    if (!rc && (g = H5Gopen2(f, "/resume", H5P_DEFAULT)) < 0) {
        snprintf(err, errlen, "cannot resume from %s: it has no /resume group (written by a build without "
                              "step-boundary resume); move it away to start the run afresh", path);
        rc = SB_ERR_INPUT;
    }
    if (!rc) rc = sb_h5r_attr_int(&r, g, "step", &rp->step);
    if (!rc) rc = sb_h5r_attr_num(&r, g, "n_iters", H5T_NATIVE_LONG, &n_iters);
    if (!rc) rc = sb_h5r_attr_num(&r, g, "n_steps", H5T_NATIVE_LONG, &n_steps);
    if (!rc) rc = sb_h5r_attr_dbl(&r, g, "seconds", &rp->seconds);
    if (!rc) rc = sb_h5r_attr_dbl(&r, g, "work_assembly", &rp->stats.work_assembly);
    if (!rc) rc = sb_h5r_attr_dbl(&r, g, "work_qp", &rp->stats.work_qp);
    if (!rc) rc = sb_h5r_attr_num(&r, g, "not_posdef", H5T_NATIVE_LONG, &rp->stats.not_posdef);
    if (!rc && (rp->step < 0 || rp->step > expect->steps_planned || n_steps != rp->step || n_iters < 0 || n_iters > INT32_MAX))
        rc = sb_h5r_fail(&r, SB_ERR_INPUT, "inconsistent step / history counts in", "/resume");
    hsize_t dx = 0, dv = 0;
    if (!rc) rc = sb_h5r_dset(&r, f, "/resume/x", 1, H5T_NATIVE_DOUBLE, sizeof(double), &dx, (void **)&rp->x);
    if (!rc) rc = sb_h5r_dset(&r, f, "/resume/v", 1, H5T_NATIVE_DOUBLE, sizeof(double), &dv, (void **)&rp->v);
    if (!rc && H5Lexists(f, "/resume/mesh_ints", H5P_DEFAULT) > 0) {
        hsize_t di = 0, dd = 0;
        rc = sb_h5r_dset(&r, f, "/resume/mesh_ints", 1, H5T_NATIVE_INT, sizeof(int), &di, (void **)&rp->mesh.ints);
        if (!rc) rc = sb_h5r_dset(&r, f, "/resume/mesh_doubles", 1, H5T_NATIVE_DOUBLE, sizeof(double), &dd,
                                  (void **)&rp->mesh.dbls);
        if (!rc && (di > (hsize_t)INT32_MAX || dd > (hsize_t)INT32_MAX))
            rc = sb_h5r_fail(&r, SB_ERR_INPUT, "too long a mesh in", "/resume");
        if (!rc) {
            rp->mesh.n_int = (int)di;
            rp->mesh.n_dbl = (int)dd;
            rp->has_mesh = 1;
        }
    }
    if (!rc && H5Lexists(f, "/resume/impulse_counts", H5P_DEFAULT) > 0) {
        /* the impulse response's counts (older checkpoints: none, the
           resumed run then counts its own steps only: counted_steps) */
        hsize_t dn = 0;
        long *a = NULL;
        rc = sb_h5r_dset(&r, f, "/resume/impulse_counts", 1, H5T_NATIVE_LONG, sizeof(long), &dn, (void **)&a);
        if (!rc && dn != SB_IMPULSE_N_COUNTS) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "impulse counts of the wrong length in", "/resume");
        if (!rc) {
            sb_impulse_from_array(&rp->impulse, a);
            rp->has_impulse = 1;
        }
        free(a);
    }
    if (!rc && ((!rp->has_mesh && dx != (hsize_t)expect->n_dofs) || dv != dx || dx > (hsize_t)INT32_MAX))
        rc = sb_h5r_fail(&r, SB_ERR_INPUT, "state of the wrong length in", "/resume");
    if (!rc) rp->n_x = (int)dx;
    if (!rc) rc = read_events(&r, f, &rp->stats);
    if (!rc) {
        rp->stats.iters = calloc((size_t)(n_iters ? n_iters : 1), sizeof *rp->stats.iters);
        rp->stats.steps = calloc((size_t)(n_steps ? n_steps : 1), sizeof *rp->stats.steps);
        if (!rp->stats.iters || !rp->stats.steps) rc = SB_ERR_NOMEM, snprintf(err, errlen, "out of memory reading %s", path);
        rp->stats.cap_iters = (size_t)(n_iters ? n_iters : 1);
        rp->stats.cap_steps = (size_t)(n_steps ? n_steps : 1);
    }
    if (!rc) rc = read_columns(&r, f, "/history/iterations", sb_record_iter_cols, sb_record_n_iter_cols, rp->stats.iters,
                               sizeof *rp->stats.iters, (size_t)n_iters);
    if (!rc) rc = read_columns(&r, f, "/history/steps", sb_record_step_cols, sb_record_n_step_cols, rp->stats.steps,
                               sizeof *rp->stats.steps, (size_t)n_steps);
    if (!rc) {
        rp->stats.n_iters = (size_t)n_iters;
        rp->stats.n_steps = (size_t)n_steps;
    }
    if (!rc && expect->n_probes > 0) {
        hsize_t d3[3];
        double *traj = NULL;
        rc = sb_h5r_dset(&r, f, "/probes/trajectory", 3, H5T_NATIVE_DOUBLE, sizeof(double), d3, (void **)&traj);
        if (!rc && (d3[0] < (hsize_t)rp->step + 1 || d3[1] != (hsize_t)expect->n_probes || d3[2] != 3))
            rc = sb_h5r_fail(&r, SB_ERR_INPUT, "probe trajectory shorter than the resume point in", "/probes/trajectory");
        if (!rc) memcpy(probe_traj, traj, ((size_t)rp->step + 1) * (size_t)expect->n_probes * 3 * sizeof(double));
        free(traj);
    }
    if (!rc && (gs = H5Gopen2(f, "/stats", H5P_DEFAULT)) < 0) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "missing group", "/stats");
    if (!rc) rc = sb_h5r_attr_dbl(&r, gs, "seconds_total", ckpt_seconds);
    if (!rc) rc = sb_h5r_attr_str(&r, f, "build_id", ckpt_build, build_len);
    if (!rc) rc = read_log(&r, f, log);
    if (gs >= 0) H5Gclose(gs);
    if (g >= 0) H5Gclose(g);
    sb_h5r_close(&r, f);
    if (rc) sb_resume_point_free(rp);
    return rc;
}

void sb_resume_point_free(sb_resume_point *rp)
{
    if (!rp) return;
    free(rp->x);
    free(rp->v);
    sb_blob_free(&rp->mesh);
    rp->has_mesh = 0;
    sb_stats_free(&rp->stats);
    rp->x = rp->v = NULL;
    rp->n_x = 0;
}
