/* sb_record_mesh.c — the method's own triangle surface at every step of a
 * record (sb_mesh_series, sb_record.h), for methods whose `surface` op gives
 * triangles (linear_fem, adaptive_sqrt3, whose mesh changes during a run).
 *
 * Layout (docs/recorded_figures.md "/steps/mesh"):
 *   /steps/mesh                      attributes topologies, rows
 *   /steps/mesh/topology_of   [rows] int: the topology version of each step row
 *   /steps/mesh/topology/NNNNNN/triangles [nt, 3] int, reference [nv, 3] (m),
 *                                    st [nv, 2]: one group per version
 *   /steps/mesh/pos/NNNNNN    [nv, 3] (m): the vertices after step NNNNNN
 * Topology is stored once per version, positions once per step; the sidecar
 * RUN.mesh.xdmf is a temporal collection whose step grids reference their
 * version's triangles, so ParaView plays the run on its real triangles with
 * point and cell counts that change with the mesh (`make check-paraview`).
 * Positions are not duplicated as displacements (as /steps/displacement
 * does for the sample grid): the version's reference is an attribute of the
 * grid, ParaView's Calculator gives the difference. */
#include "sb_record_io.h"


#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* ---- the series in memory ------------------------------------------------ */

static void topo_free(sb_mesh_topo *t)
{
    free(t->tri);
    free(t->ref);
    free(t->st);
    memset(t, 0, sizeof *t);
}

void sb_mesh_series_free(sb_mesh_series *s)
{
    if (!s) return;
    for (int k = 0; k < s->n_topo; k++) topo_free(&s->topo[k]);
    for (int k = 0; k < s->rows; k++) free(s->row_pos[k]);
    free(s->topo);
    free(s->row_topo);
    free(s->row_pos);
    memset(s, 0, sizeof *s);
}

static int same_topo(const sb_mesh_topo *t, int nv, int nt, const int *tri, const double *ref, const double *st)
{
    return t->nv == nv && t->nt == nt && memcmp(t->tri, tri, (size_t)nt * 3 * sizeof *tri) == 0 &&
           memcmp(t->ref, ref, (size_t)nv * 3 * sizeof *ref) == 0 &&
           (!st || memcmp(t->st, st, (size_t)nv * 2 * sizeof *st) == 0);
}

static void *copy_of(const void *p, size_t n)
{
    void *q = malloc(n ? n : 1);
    if (q && n) memcpy(q, p, n);
    return q;
}

int sb_mesh_series_put(sb_mesh_series *s, int row, int nv, int nt, const int *tri, const double *ref,
                       const double *st, const double *pos)
{
    if (row < 0 || row > s->rows || nv < 0 || nt < 0) return SB_ERR_INTERNAL;
    int v = s->n_topo - 1;
    if (v < 0 || !same_topo(&s->topo[v], nv, nt, tri, ref, st)) {
        if (s->n_topo == s->cap_topo) {
            const int c = s->cap_topo ? 2 * s->cap_topo : 8;
            sb_mesh_topo *q = realloc(s->topo, (size_t)c * sizeof *q);
            if (!q) return SB_ERR_NOMEM;
            s->topo = q;
            s->cap_topo = c;
        }
        sb_mesh_topo *t = &s->topo[s->n_topo];
        memset(t, 0, sizeof *t);
        t->nv = nv;
        t->nt = nt;
        t->tri = copy_of(tri, (size_t)nt * 3 * sizeof *tri);
        t->ref = copy_of(ref, (size_t)nv * 3 * sizeof *ref);
        t->st = calloc((size_t)(nv ? nv : 1) * 2, sizeof *t->st);
        if (!t->tri || !t->ref || !t->st) {
            topo_free(t);
            return SB_ERR_NOMEM;
        }
        if (st) memcpy(t->st, st, (size_t)nv * 2 * sizeof *st);
        v = s->n_topo++;
    }
    if (row == s->rows && s->rows == s->cap_rows) {
        const int c = s->cap_rows ? 2 * s->cap_rows : 64;
        int *rt = realloc(s->row_topo, (size_t)c * sizeof *rt);
        if (!rt) return SB_ERR_NOMEM;
        s->row_topo = rt;
        double **rp = realloc(s->row_pos, (size_t)c * sizeof *rp);
        if (!rp) return SB_ERR_NOMEM;
        s->row_pos = rp;
        s->cap_rows = c;
    }
    double *p = copy_of(pos, (size_t)nv * 3 * sizeof *pos);
    if (!p) return SB_ERR_NOMEM;
    if (row < s->rows) {
        s->points -= s->topo[s->row_topo[row]].nv;
        free(s->row_pos[row]);
    } else {
        s->rows++;
    }
    s->row_topo[row] = v;
    s->row_pos[row] = p;
    s->points += nv;
    return SB_OK;
}

/* ---- writing ------------------------------------------------------------- */

int sb_record_write_mesh(sb_h5w *w, hid_t f, const sb_run *r)
{
    const sb_mesh_series *s = r->mesh;
    if (!s || s->rows <= 0) return 0;
    const int rows = s->rows < r->steps_done + 1 ? s->rows : r->steps_done + 1;
    hid_t g0 = H5Lexists(f, "/steps", H5P_DEFAULT) > 0 ? H5Gopen2(f, "/steps", H5P_DEFAULT)
                                                       : sb_h5w_group(w, f, "/steps");
    if (g0 < 0) return sb_h5w_fail(w, -1, "/steps");
    H5Gclose(g0);
    hid_t g = sb_h5w_group(w, f, "/steps/mesh");
    if (g < 0) return -1;
    int bad = sb_h5w_attr_long(w, g, "topologies", s->n_topo);
    bad |= sb_h5w_attr_long(w, g, "rows", rows);
    hsize_t d1 = (hsize_t)rows;
    bad |= sb_h5w_dset_int(w, g, "topology_of", 1, &d1, s->row_topo, NULL);
    hid_t gt = bad ? -1 : sb_h5w_group(w, f, "/steps/mesh/topology");
    hid_t gp = gt < 0 ? -1 : sb_h5w_group(w, f, "/steps/mesh/pos");
    if (gt < 0 || gp < 0) bad = -1;
    for (int k = 0; k < s->n_topo && !bad; k++) {
        char name[48];
        snprintf(name, sizeof name, "%06d", k);
        hid_t gk = sb_h5w_group(w, gt, name);
        if (gk < 0) { bad = -1; break; }
        const sb_mesh_topo *t = &s->topo[k];
        hsize_t dt[2] = { (hsize_t)t->nt, 3 }, dr[2] = { (hsize_t)t->nv, 3 }, ds[2] = { (hsize_t)t->nv, 2 };
        bad |= sb_h5w_dset_int(w, gk, "triangles", 2, dt, t->tri, NULL);
        bad |= sb_h5w_dset_dbl(w, gk, "reference", 2, dr, t->ref, "m");
        bad |= sb_h5w_dset_dbl(w, gk, "st", 2, ds, t->st, NULL);
        H5Gclose(gk);
    }
    for (int k = 0; k < rows && !bad; k++) {
        char name[48];
        snprintf(name, sizeof name, "%06d", k);
        hsize_t d2[2] = { (hsize_t)s->topo[s->row_topo[k]].nv, 3 };
        bad |= sb_h5w_dset_dbl(w, gp, name, 2, d2, s->row_pos[k], "m");
    }
    if (gp >= 0) H5Gclose(gp);
    if (gt >= 0) H5Gclose(gt);
    H5Gclose(g);
    return bad ? -1 : 0;
}

int sb_record_mesh_xdmf_path(const char *h5path, char *buf, size_t len)
{
    if (!h5path || !buf || len == 0) return SB_ERR_INPUT;
    size_t n = strlen(h5path);
    int w;
    if (n > 3 && strcmp(h5path + n - 3, ".h5") == 0)
        w = snprintf(buf, len, "%.*s.mesh.xdmf", (int)(n - 3), h5path);
    else
        w = snprintf(buf, len, "%s.mesh.xdmf", h5path);
    return (w < 0 || (size_t)w >= len) ? SB_ERR_INPUT : SB_OK;
}

/* ---- reading ------------------------------------------------------------- */

static int read_topo(sb_h5r *r, hid_t f, int k, sb_mesh_topo *t)
{
    char name[96];
    hsize_t dt[2], dr[2], ds[2];
    memset(t, 0, sizeof *t);
    snprintf(name, sizeof name, "/steps/mesh/topology/%06d/triangles", k);
    int rc = sb_h5r_dset(r, f, name, 2, H5T_NATIVE_INT, sizeof(int), dt, (void **)&t->tri);
    snprintf(name, sizeof name, "/steps/mesh/topology/%06d/reference", k);
    if (!rc) rc = sb_h5r_dset(r, f, name, 2, H5T_NATIVE_DOUBLE, sizeof(double), dr, (void **)&t->ref);
    snprintf(name, sizeof name, "/steps/mesh/topology/%06d/st", k);
    if (!rc) rc = sb_h5r_dset(r, f, name, 2, H5T_NATIVE_DOUBLE, sizeof(double), ds, (void **)&t->st);
    if (!rc && (dt[1] != 3 || dr[1] != 3 || ds[1] != 2 || ds[0] != dr[0] || dr[0] > (hsize_t)INT32_MAX / 3 ||
                dt[0] > (hsize_t)INT32_MAX / 3))
        rc = sb_h5r_fail(r, SB_ERR_INPUT, "inconsistent shapes in", name);
    if (!rc) {
        t->nv = (int)dr[0];
        t->nt = (int)dt[0];
        for (long i = 0; i < 3L * t->nt && !rc; i++)
            if (t->tri[i] < 0 || t->tri[i] >= t->nv)
                rc = sb_h5r_fail(r, SB_ERR_INPUT, "a triangle refers to a missing vertex in", name);
    }
    if (rc) topo_free(t);
    return rc;
}

static int read_pos(sb_h5r *r, hid_t f, int k, int nv, double **pos)
{
    char name[64];
    hsize_t d[2];
    snprintf(name, sizeof name, "/steps/mesh/pos/%06d", k);
    int rc = sb_h5r_dset(r, f, name, 2, H5T_NATIVE_DOUBLE, sizeof(double), d, (void **)pos);
    if (!rc && (d[0] != (hsize_t)nv || d[1] != 3)) rc = sb_h5r_fail(r, SB_ERR_INPUT, "unexpected shape of", name);
    if (rc) {
        free(*pos);
        *pos = NULL;
    }
    return rc;
}

/* topology_of and the counts of /steps/mesh */
static int read_index(sb_h5r *r, hid_t f, int **topo_of, int *rows, int *n_topo)
{
    *topo_of = NULL;
    if (H5Lexists(f, "/steps", H5P_DEFAULT) <= 0 || H5Lexists(f, "/steps/mesh", H5P_DEFAULT) <= 0) {
        snprintf(r->err, r->errlen, "%s has no per-step mesh (/steps/mesh): its method has no triangle surface, "
                 "or it was written before the mesh was kept", r->path);
        return SB_ERR_INPUT;
    }
    hid_t g = H5Gopen2(f, "/steps/mesh", H5P_DEFAULT);
    if (g < 0) return sb_h5r_fail(r, SB_ERR_INPUT, "cannot open", "/steps/mesh");
    int rc = sb_h5r_attr_int(r, g, "topologies", n_topo);
    H5Gclose(g);
    hsize_t d = 0;
    if (!rc) rc = sb_h5r_dset(r, f, "/steps/mesh/topology_of", 1, H5T_NATIVE_INT, sizeof(int), &d, (void **)topo_of);
    if (!rc && d > (hsize_t)INT32_MAX) rc = sb_h5r_fail(r, SB_ERR_INPUT, "too many rows in", "/steps/mesh/topology_of");
    if (!rc) {
        *rows = (int)d;
        for (int k = 0; k < *rows && !rc; k++)
            if ((*topo_of)[k] < 0 || (*topo_of)[k] >= *n_topo)
                rc = sb_h5r_fail(r, SB_ERR_INPUT, "a step refers to a missing topology in", "/steps/mesh/topology_of");
    }
    if (rc) {
        free(*topo_of);
        *topo_of = NULL;
    }
    return rc;
}

int sb_record_has_mesh_series(const char *path, int *rows)
{
    char err[512];
    sb_h5r r = { path, err, sizeof err, NULL, NULL };
    hid_t f;
    int *of = NULL, nt = 0, n = 0;
    int rc = sb_h5r_open(&r, &f);
    if (!rc) {
        rc = read_index(&r, f, &of, &n, &nt);
        sb_h5r_close(&r, f);
    }
    free(of);
    if (rows) *rows = rc ? 0 : n;
    return rc == SB_OK;
}

int sb_record_read_mesh_series(const char *path, int rows, sb_mesh_series *s, char *err, size_t errlen)
{
    sb_mesh_series_free(s);
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    int *of = NULL, n = 0, nt = 0;
    int rc = sb_h5r_open(&r, &f);
    if (rc) return rc;
    rc = read_index(&r, f, &of, &n, &nt);
    if (!rc && n < rows) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "fewer rows than the resume point in", "/steps/mesh");
    sb_mesh_topo *topo = rc ? NULL : calloc((size_t)(nt ? nt : 1), sizeof *topo);
    if (!rc && !topo) rc = SB_ERR_NOMEM;
    for (int k = 0; k < nt && !rc; k++) rc = read_topo(&r, f, k, &topo[k]);
    for (int k = 0; k < rows && !rc; k++) {
        const sb_mesh_topo *t = &topo[of[k]];
        double *pos = NULL;
        rc = read_pos(&r, f, k, t->nv, &pos);
        if (!rc) rc = sb_mesh_series_put(s, k, t->nv, t->nt, t->tri, t->ref, t->st, pos);
        free(pos);
    }
    for (int k = 0; topo && k < nt; k++) topo_free(&topo[k]);
    free(topo);
    free(of);
    sb_h5r_close(&r, f);
    if (rc) sb_mesh_series_free(s);
    if (rc == SB_ERR_NOMEM) snprintf(err, errlen, "out of memory reading /steps/mesh of %s", path);
    return rc;
}

int sb_record_read_step_mesh(const char *path, int step, sb_mesh_topo *topo, double **pos, char *err,
                             size_t errlen)
{
    memset(topo, 0, sizeof *topo);
    *pos = NULL;
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    int *of = NULL, n = 0, nt = 0;
    int rc = sb_h5r_open(&r, &f);
    if (rc) return rc;
    rc = read_index(&r, f, &of, &n, &nt);
    if (!rc && (step < 0 || step >= n)) {
        snprintf(err, errlen, "%s: step %d is not in the recorded mesh series (steps 0 to %d)", path, step, n - 1);
        rc = SB_ERR_INPUT;
    }
    if (!rc) rc = read_topo(&r, f, of[step], topo);
    if (!rc) rc = read_pos(&r, f, step, topo->nv, pos);
    if (rc) topo_free(topo);
    free(of);
    sb_h5r_close(&r, f);
    return rc;
}
