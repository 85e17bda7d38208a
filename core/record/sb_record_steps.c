/* sb_record_steps.c — the time series of a record: the sample grid after
 * every step, /steps/sample_pos [steps_done + 1, n_samples, 3] (m) with the
 * step times /steps/t, written with the record and read back for
 * `shellbench render --step` and --resume.  The XDMF sidecar plays it as a
 * temporal collection (sb_record_xdmf.c). */
#include "sb_record_io.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int sb_record_write_steps(sb_h5w *w, hid_t f, const sb_run *r)
{
    if (!r->sample_traj || r->n_samples <= 0) return 0;
    hid_t g = sb_h5w_group(w, f, "/steps");
    if (g < 0) return -1;
    const int rows = r->steps_done + 1;
    double *t = malloc((size_t)rows * sizeof *t);
    if (!t) {
        H5Gclose(g);
        return sb_h5w_fail(w, -1, "/steps/t (out of memory)");
    }
    /* the time of row k: the recorded step's t (dynamic: seconds; quasi-static: the load step) */
    t[0] = 0.0;
    for (int k = 1; k < rows; k++) {
        t[k] = k;
        if (r->stats && (size_t)k <= r->stats->n_steps && r->stats->steps[k - 1].step == k) t[k] = r->stats->steps[k - 1].t;
    }
    hsize_t d3[3] = { (hsize_t)rows, (hsize_t)r->n_samples, 3 }, d1 = (hsize_t)rows;
    int bad = sb_h5w_dset_dbl(w, g, "sample_pos", 3, d3, r->sample_traj, "m");
    bad |= sb_h5w_dset_dbl(w, g, "t", 1, &d1, t, NULL);
    free(t);
    H5Gclose(g);
    return bad ? -1 : 0;
}

void sb_record_samples_free(sb_record_samples *s)
{
    if (!s) return;
    free(s->st);
    free(s->ref);
    free(s->pos);
    free(s->tris);
    memset(s, 0, sizeof *s);
}

/* rows [0, nrows) of /steps/sample_pos as a hyperslab starting at row `first` */
static int read_rows(sb_h5r *r, hid_t f, int first, int nrows, int n, double *out)
{
    hid_t d = H5Dopen2(f, "/steps/sample_pos", H5P_DEFAULT);
    if (d < 0) {
        snprintf(r->err, r->errlen, "%s has no per-step surfaces (/steps/sample_pos): written before they were kept",
                 r->path);
        return SB_ERR_INPUT;
    }
    hid_t sp = H5Dget_space(d);
    hsize_t dims[3] = { 0, 0, 0 };
    int rc = SB_OK;
    if (sp < 0 || H5Sget_simple_extent_ndims(sp) != 3 || H5Sget_simple_extent_dims(sp, dims, NULL) < 0 ||
        dims[1] != (hsize_t)n || dims[2] != 3)
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "unexpected shape of", "/steps/sample_pos");
    else if ((hsize_t)first + (hsize_t)nrows > dims[0]) {
        snprintf(r->err, r->errlen, "%s: step %d is past the last recorded step, %d", r->path, first + nrows - 1,
                 (int)dims[0] - 1);
        rc = SB_ERR_INPUT;
    } else {
        hsize_t start[3] = { (hsize_t)first, 0, 0 }, count[3] = { (hsize_t)nrows, (hsize_t)n, 3 };
        hid_t ms = H5Screate_simple(3, count, NULL);
        if (ms < 0 || H5Sselect_hyperslab(sp, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
            H5Dread(d, H5T_NATIVE_DOUBLE, ms, sp, H5P_DEFAULT, out) < 0)
            rc = sb_h5r_fail(r, SB_ERR_IO, "cannot read", "/steps/sample_pos");
        if (ms >= 0) H5Sclose(ms);
    }
    if (sp >= 0) H5Sclose(sp);
    H5Dclose(d);
    return rc;
}

int sb_record_read_step_samples(const char *path, int step, sb_record_samples *s, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    hsize_t ds[2], dr[2], dt[2];
    int rc = sb_h5r_open(&r, &f);
    if (!rc) rc = sb_h5r_dset(&r, f, "/final/sample_st", 2, H5T_NATIVE_DOUBLE, sizeof(double), ds, (void **)&s->st);
    if (!rc) rc = sb_h5r_dset(&r, f, "/final/sample_ref", 2, H5T_NATIVE_DOUBLE, sizeof(double), dr, (void **)&s->ref);
    if (!rc) rc = sb_h5r_dset(&r, f, "/final/triangles", 2, H5T_NATIVE_INT, sizeof(int), dt, (void **)&s->tris);
    if (!rc && (ds[1] != 2 || dr[1] != 3 || dr[0] != ds[0] || dt[1] != 3 || ds[0] > (hsize_t)INT32_MAX / 3 ||
                dt[0] > (hsize_t)INT32_MAX / 3))
        rc = sb_h5r_fail(&r, SB_ERR_INPUT, "inconsistent shapes of", "/final/sample_st, sample_ref and triangles");
    if (!rc) {
        s->n = (int)ds[0];
        s->n_tris = (int)dt[0];
        for (long i = 0; i < 3L * s->n_tris && !rc; i++)
            if (s->tris[i] < 0 || s->tris[i] >= s->n)
                rc = sb_h5r_fail(&r, SB_ERR_INPUT, "a triangle refers to a missing sample in", "/final/triangles");
    }
    if (!rc && H5Lexists(f, "/steps", H5P_DEFAULT) > 0 && H5Lexists(f, "/steps/sample_pos", H5P_DEFAULT) > 0) {
        hid_t d = H5Dopen2(f, "/steps/sample_pos", H5P_DEFAULT);
        hid_t sp = d < 0 ? -1 : H5Dget_space(d);
        hsize_t dims[3];
        if (sp >= 0 && H5Sget_simple_extent_ndims(sp) == 3 && H5Sget_simple_extent_dims(sp, dims, NULL) >= 0)
            s->n_steps = (int)dims[0];
        if (sp >= 0) H5Sclose(sp);
        if (d >= 0) H5Dclose(d);
    }
    if (!rc) {
        if (step < 0) {
            hsize_t dp[2];
            rc = sb_h5r_dset(&r, f, "/final/sample_pos", 2, H5T_NATIVE_DOUBLE, sizeof(double), dp, (void **)&s->pos);
            if (!rc && (dp[0] != ds[0] || dp[1] != 3))
                rc = sb_h5r_fail(&r, SB_ERR_INPUT, "inconsistent shape of", "/final/sample_pos");
        } else if (s->n_steps == 0) {
            snprintf(err, errlen, "%s has no per-step surfaces (/steps/sample_pos): written before they were kept, "
                     "or by a run too large to keep them", path);
            rc = SB_ERR_INPUT;
        } else if (!(s->pos = malloc((size_t)(s->n ? s->n : 1) * 3 * sizeof(double)))) {
            rc = sb_h5r_fail(&r, SB_ERR_NOMEM, "out of memory reading", "/steps/sample_pos");
        } else {
            rc = read_rows(&r, f, step, 1, s->n, s->pos);
        }
    }
    sb_h5r_close(&r, f);
    if (rc) sb_record_samples_free(s);
    return rc;
}

int sb_record_read_sample_traj(const char *path, int step, int n, double *traj, char *err, size_t errlen)
{
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    int rc = sb_h5r_open(&r, &f);
    if (!rc) rc = read_rows(&r, f, 0, step + 1, n, traj);
    sb_h5r_close(&r, f);
    return rc;
}
