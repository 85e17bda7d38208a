/* test_a3_resume.c — checkpoints and --resume of an adaptive run
 * (adaptive_sqrt3; sb_method.h save_mesh / restore_mesh, sb_run_adapt.c):
 * a run stopped twice (once just before an adaptation, once just after
 * one) and resumed equals the uninterrupted run bit for bit — final state,
 * per-step history (dofs, triangles, f, |g|), event counts, the recorded
 * mesh series (topology versions, positions) — and a checkpoint whose
 * mesh is malformed (re-sealed, so its checksum passes) is refused with
 * the file named.  Also the records side
 * of adaptive meshes: /steps/mesh changes its topology with the mesh, the
 * step history counts the triangles, RUN.mesh.xdmf references every
 * version. */
#include "sb_test.h"
#include "run_json.h"
#include "sb_record.h"
#include "sb_record_io.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *SCENE =
    "{\"name\": \"t\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1.5]},"
    " \"geometry\": {\"type\": \"plane\"}, \"material\": {\"model\": \"stvk\", \"young\": 1e6, \"poisson\": 0.33,"
    " \"thickness\": 0.001, \"density\": 0.1}, \"loads\": [{\"type\": \"gravity\", \"acceleration\": [0, -9.81, -5]}],"
    " \"boundary\": [{\"type\": \"fixed\", \"at\": [0, 1.5]}],"
    " \"time\": {\"mode\": \"dynamic\", \"dt\": 0.005, \"steps\": 40}, \"probes\": [{\"name\": \"p\", \"at\": [0.5, 0]}]}";

static char dir[256], scene[300];

static json_t *run(const char *out, int resume, int stop_after, int *code)
{
    const char *sets[] = { "method.max_generation=4", "method.curv_base=0.01", "method.curv_max=0.1",
                           "run.single_step_rtol=1e300" };
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = scene;
    rq.method = "adaptive_sqrt3";
    rq.solver = "linearized";
    rq.res = 4;
    rq.out = out;
    rq.quiet = 1;
    rq.n_sets = 4;
    rq.sets = sets;
    rq.resume = resume;
    rq.stop_after_steps = stop_after;
    return sb_test_run_json(&rq, code);
}

/* a 1-D dataset of the record as doubles (ints converted); NULL when absent */
static double *column(const char *path, const char *name, int *n)
{
    *n = 0;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) return NULL;
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    double *buf = NULL;
    if (d >= 0) {
        hid_t sp = H5Dget_space(d);
        hssize_t m = H5Sget_simple_extent_npoints(sp);
        buf = malloc((size_t)(m > 0 ? m : 1) * sizeof *buf);
        if (buf && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0) *n = (int)m;
        H5Sclose(sp);
        H5Dclose(d);
    }
    H5Fclose(f);
    return buf;
}

static int same_column(const char *a, const char *b, const char *name)
{
    int na = 0, nb = 0;
    double *ca = column(a, name, &na), *cb = column(b, name, &nb);
    const int same = na > 0 && na == nb && memcmp(ca, cb, (size_t)na * sizeof *ca) == 0;
    free(ca);
    free(cb);
    return same;
}

static long count_of(json_t *o, const char *event)
{
    return (long)json_integer_value(json_object_get(json_object_get(o, "counts"), event));
}

SB_TEST(stopped_and_resumed_adaptive_run_equals_uninterrupted_run)
{
    char a[300], b[300], pb[320], msg[1024];
    snprintf(a, sizeof a, "%s/a.h5", dir);
    snprintf(b, sizeof b, "%s/b.h5", dir);
    snprintf(pb, sizeof pb, "%s.partial", b);
    int code = -1;
    json_t *A = run(a, 0, 0, &code);
    CHECK_EQ_INT(code, 0);
    /* adaptations before steps 6, 11, 16, ...: stop before one (after 15) and right after one (after 21) */
    json_t *S = run(b, 0, 15, &code);
    CHECK_EQ_INT(code, 4);
    json_decref(S);
    sb_record_summary rs;
    CHECK_EQ_INT(sb_record_read_summary(pb, &rs, msg, sizeof msg), SB_OK);
    CHECK(rs.status == SB_STATUS_UNFINISHED && rs.resume_point == 15);
    sb_record_summary_free(&rs);
    S = run(b, 1, 21, &code);
    CHECK_EQ_INT(code, 4);
    json_decref(S);
    json_t *B = run(b, 1, 0, &code);
    CHECK_EQ_INT(code, 0);
    CHECK(A && B);
    if (!A || !B) return;
    const char *events[] = { "energy", "gradient", "hessian", "analyze", "factorize", "solve", "adapt", "record" };
    for (int e = 0; e < 8; e++)
        CHECK_MSG(count_of(A, events[e]) == count_of(B, events[e]), "%s: %ld uninterrupted, %ld resumed", events[e],
                  count_of(A, events[e]), count_of(B, events[e]));
    CHECK(count_of(A, "adapt") == 7 && count_of(A, "analyze") > 2);
    CHECK_EQ_INT((int)json_integer_value(json_object_get(json_object_get(B, "resumed"), "count")), 2);
    CHECK(json_integer_value(json_object_get(A, "dofs")) == json_integer_value(json_object_get(B, "dofs")));
    CHECK(json_integer_value(json_object_get(A, "triangles")) > 32);
    /* final state and the per-step history, bit for bit */
    sb_record_setup xa, xb;
    CHECK_EQ_INT(sb_record_read_setup(a, &xa, msg, sizeof msg), SB_OK);
    CHECK_EQ_INT(sb_record_read_setup(b, &xb, msg, sizeof msg), SB_OK);
    CHECK(xa.n_x == xb.n_x && xa.n_x > 75 && memcmp(xa.x, xb.x, (size_t)xa.n_x * sizeof *xa.x) == 0);
    sb_record_setup_free(&xa);
    sb_record_setup_free(&xb);
    const char *cols[] = { "/history/steps/dofs", "/history/steps/triangles", "/history/steps/f",
                           "/history/steps/gnorm", "/history/steps/iterations", "/history/iterations/gnorm",
                           "/steps/mesh/topology_of", "/probes/trajectory" };
    for (int c = 0; c < 8; c++) CHECK_MSG(same_column(a, b, cols[c]), "%s differs after the resumes", cols[c]);
    /* triangles beside dofs: 3 dofs a vertex, and the count changes with the mesh */
    int nd = 0, nt = 0;
    double *dofs = column(a, "/history/steps/dofs", &nd), *tris = column(a, "/history/steps/triangles", &nt);
    CHECK(nd == 40 && nt == 40);
    if (nd == 40 && nt == 40) {
        CHECK(tris[0] == 32 && dofs[0] == 75);
        CHECK(tris[39] > tris[0] && dofs[39] > dofs[0]);
    }
    free(dofs);
    free(tris);
    /* the mesh series: one topology version per mesh, positions bit for bit */
    sb_mesh_series ma, mb;
    memset(&ma, 0, sizeof ma);
    memset(&mb, 0, sizeof mb);
    CHECK_EQ_INT(sb_record_read_mesh_series(a, 41, &ma, msg, sizeof msg), SB_OK);
    CHECK_EQ_INT(sb_record_read_mesh_series(b, 41, &mb, msg, sizeof msg), SB_OK);
    CHECK(ma.rows == 41 && mb.rows == 41 && ma.n_topo == mb.n_topo && ma.n_topo > 2);
    for (int k = 0; k < ma.rows && k < mb.rows; k++) {
        const int nv = ma.topo[ma.row_topo[k]].nv;
        CHECK(ma.row_topo[k] == mb.row_topo[k] && memcmp(ma.row_pos[k], mb.row_pos[k], (size_t)nv * 3 * sizeof(double)) == 0);
    }
    /* the last row's triangles are the history's last count */
    if (ma.rows == 41) CHECK_EQ_INT(ma.topo[ma.row_topo[40]].nt, (int)json_integer_value(json_object_get(A, "triangles")));
    sb_mesh_series_free(&ma);
    sb_mesh_series_free(&mb);
    /* the sidecar plays every version */
    char xd[320], line[512];
    snprintf(xd, sizeof xd, "%s/a.mesh.xdmf", dir);
    FILE *f = fopen(xd, "r");
    CHECK(f != NULL);
    int grids = 0, last_topo = 0;
    while (f && fgets(line, sizeof line, f)) {
        grids += strstr(line, "<Grid Name=\"step ") != NULL;
        const char *p = strstr(line, "/steps/mesh/topology/");
        if (p && strstr(p, "/triangles")) last_topo = atoi(p + strlen("/steps/mesh/topology/"));
    }
    if (f) fclose(f);
    CHECK(grids == 41 && last_topo > 2);
    json_decref(A);
    json_decref(B);
}

SB_TEST(damaged_mesh_in_a_checkpoint_is_refused)
{
    char c[300], pc[320];
    snprintf(c, sizeof c, "%s/c.h5", dir);
    snprintf(pc, sizeof pc, "%s.partial", c);
    int code = -1;
    json_t *S = run(c, 0, 12, &code);
    CHECK_EQ_INT(code, 4);
    json_decref(S);
    /* overwrite one triangle's corner with a vertex that does not exist */
    hid_t f = H5Fopen(pc, H5F_ACC_RDWR, H5P_DEFAULT);
    CHECK(f >= 0);
    if (f < 0) return;
    hid_t d = H5Dopen2(f, "/resume/mesh_ints", H5P_DEFAULT);
    CHECK(d >= 0);
    if (d >= 0) {
        hid_t sp = H5Dget_space(d);
        hssize_t n = H5Sget_simple_extent_npoints(sp);
        int *v = malloc((size_t)n * sizeof *v);
        if (v && H5Dread(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0) {
            const int nv = v[1];
            v[6 + 5 * nv] = nv + 7;   /* triangle 0, corner 0 */
            H5Dwrite(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
        }
        free(v);
        H5Sclose(sp);
        H5Dclose(d);
    }
    H5Fclose(f);
    char m2[512];
    CHECK_EQ_INT(sb_record_seal(pc, m2, sizeof m2), SB_OK);   /* sealed again: the mesh check, not the checksum, refuses it */
    char *buf = NULL;
    size_t len = 0;
    FILE *err = open_memstream(&buf, &len), *devnull = fopen("/dev/null", "w");
    const char *sets[] = { "method.max_generation=4", "method.curv_base=0.01", "method.curv_max=0.1",
                           "run.single_step_rtol=1e300" };
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = scene;
    rq.method = "adaptive_sqrt3";
    rq.solver = "linearized";
    rq.res = 4;
    rq.out = c;
    rq.quiet = 1;
    rq.n_sets = 4;
    rq.sets = sets;
    rq.resume = 1;
    char *js = NULL;
    code = sb_run_execute(&rq, devnull, err, &js);
    fclose(err);
    fclose(devnull);
    free(js);
    CHECK_EQ_INT(code, 2);
    CHECK_MSG(buf && strstr(buf, pc) && strstr(buf, "malformed"), "message: %s", buf ? buf : "");
    free(buf);
}

int main(int argc, char **argv)
{
    snprintf(dir, sizeof dir, "/tmp/sb_test_a3_resume_%d", (int)getpid());
    char cmd[400];
    snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
    if (system(cmd) != 0) return 1;
    snprintf(scene, sizeof scene, "%s/t.json", dir);
    FILE *fp = fopen(scene, "w");
    if (!fp) return 1;
    fputs(SCENE, fp);
    fclose(fp);
    static const sb_test_case cases[] = {
        SB_CASE(stopped_and_resumed_adaptive_run_equals_uninterrupted_run),
        SB_CASE(damaged_mesh_in_a_checkpoint_is_refused),
        SB_END
    };
    int rc = sb_test_main(argc, argv, cases);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) rc = rc ? rc : 1;
    return rc;
}
