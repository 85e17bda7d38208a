/* sb_record_steps.c — the time series of a record: the sample grid after
 * every step k = 0 .. steps_done, one dataset /steps/sample_pos/NNNNNN
 * [n_samples, 3] (m) per step (zero-padded step number) and its
 * displacement from the reference /steps/displacement/NNNNNN, with the
 * step times /steps/t; written with the record and read back for
 * `shellbench render --step` and --resume.  One dataset per step rather
 * than one 3-D array, and the displacement stored rather than an XDMF
 * Function: ParaView's Xdmf3 readers read neither hyperslabs nor functions
 * (`make check-paraview`).  The sidecar RUN.steps.xdmf plays it as a
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
    hsize_t d2[2] = { (hsize_t)r->n_samples, 3 }, d1 = (hsize_t)rows;
    int bad = sb_h5w_dset_dbl(w, g, "t", 1, &d1, t, NULL);
    hid_t gp = bad ? -1 : sb_h5w_group(w, f, "/steps/sample_pos");
    if (gp < 0) bad = -1;
    hid_t gd = bad ? -1 : sb_h5w_group(w, f, "/steps/displacement");
    if (gd < 0) bad = -1;
    const size_t n3 = (size_t)r->n_samples * 3;
    double *disp = bad ? NULL : malloc(n3 * sizeof *disp);
    if (!bad && !disp) bad = sb_h5w_fail(w, -1, "/steps/displacement (out of memory)");
    for (int k = 0; k < rows && !bad; k++) {
        char name[32];
        snprintf(name, sizeof name, "%06d", k);
        const double *pos = r->sample_traj + (size_t)k * n3;
        for (size_t i = 0; i < n3; i++) disp[i] = pos[i] - r->sample_ref[i];
        bad |= sb_h5w_dset_dbl(w, gp, name, 2, d2, pos, "m");
        bad |= sb_h5w_dset_dbl(w, gd, name, 2, d2, disp, "m");
    }
    free(disp);
    if (gd >= 0) H5Gclose(gd);
    if (gp >= 0) H5Gclose(gp);
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

/* rows [first, first + nrows) of the time series into out (n x 3 each) */
static int read_rows(sb_h5r *r, hid_t f, int first, int nrows, int n, double *out)
{
    if (H5Lexists(f, "/steps", H5P_DEFAULT) <= 0 || H5Lexists(f, "/steps/sample_pos", H5P_DEFAULT) <= 0) {
        snprintf(r->err, r->errlen, "%s has no per-step surfaces (/steps/sample_pos): written before they were kept",
                 r->path);
        return SB_ERR_INPUT;
    }
    for (int k = first; k < first + nrows; k++) {
        char name[64];
        snprintf(name, sizeof name, "/steps/sample_pos/%06d", k);
        if (H5Lexists(f, name, H5P_DEFAULT) <= 0) {
            snprintf(r->err, r->errlen, "%s: step %d is not in the recorded time series (%s missing)", r->path, k, name);
            return SB_ERR_INPUT;
        }
        hsize_t d[2];
        double *buf = NULL;
        int rc = sb_h5r_dset(r, f, name, 2, H5T_NATIVE_DOUBLE, sizeof(double), d, (void **)&buf);
        if (!rc && (d[0] != (hsize_t)n || d[1] != 3)) rc = sb_h5r_fail(r, SB_ERR_INPUT, "unexpected shape of", name);
        if (!rc) memcpy(out + (size_t)(k - first) * n * 3, buf, (size_t)n * 3 * sizeof(double));
        free(buf);
        if (rc) return rc;
    }
    return SB_OK;
}

/* number of steps in the time series (0: none) */
static int count_rows(hid_t f)
{
    if (H5Lexists(f, "/steps", H5P_DEFAULT) <= 0 || H5Lexists(f, "/steps/sample_pos", H5P_DEFAULT) <= 0) return 0;
    hid_t g = H5Gopen2(f, "/steps/sample_pos", H5P_DEFAULT);
    if (g < 0) return 0;
    H5G_info_t info;
    int n = H5Gget_info(g, &info) >= 0 && info.nlinks < 100000000 ? (int)info.nlinks : 0;
    H5Gclose(g);
    return n;
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
    if (!rc) s->n_steps = count_rows(f);
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
