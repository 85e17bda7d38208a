/* test_record.c — HDF5 run records: write a synthetic run, read it back,
 * atomic replacement, failure paths, unreadable files, sysinfo. */
#include "sb_record.h"
#include "sb_sysinfo.h"
#include "sb_test.h"

#include <dirent.h>
#include <hdf5.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- a synthetic run: 3 levels, 2 steps, 5 iterations, 2 probes, a 3x3
 * sample grid with 8 triangles ---------------------------------------- */
typedef struct fixture {
    sb_run run;
    sb_stats stats;
    sb_paramset ps;
    char names[2][SB_NAME_LEN];
    double traj[3 * 2 * 3], expected[6], rel[2];
    double x[27], st[18], ref[27], pos[27];
    int tris[24];
} fixture;

static const char *const trs_choices[] = { "dogleg", "steihaug_cg", NULL };
static const sb_param_def test_defs[] = {
    { "eta1", SB_PARAM_REAL, 0.1, 0.0, 1.0, NULL, "RMTR paper Table 2" },
    { "max_iter", SB_PARAM_INT, 50, 1, 1000, NULL, "iteration cap" },
    { "trs", SB_PARAM_CHOICE, 0, 0, 1, trs_choices, "subproblem solver" },
    { NULL, SB_PARAM_REAL, 0, 0, 0, NULL, NULL },
};

static void fixture_make(fixture *fx, const char *scene)
{
    memset(fx, 0, sizeof *fx);
    sb_run *r = &fx->run;
    sb_run_init(r);
    snprintf(r->scene_name, sizeof r->scene_name, "%s", scene);
    snprintf(r->scene_path, sizeof r->scene_path, "bench/scenes/%s.json", scene);
    r->scene_json = "{ \"name\": \"test\", \"note\": \"quotes \\\" and <xml> & stuff\" }";
    snprintf(r->method, sizeof r->method, "rmtr");
    snprintf(r->solver, sizeof r->solver, "tr");
    snprintf(r->method_info, sizeof r->method_info, "Catmull-Clark, 3 levels");
    r->res = 8;
    r->levels = 3;
    r->n_dofs = 243;
    sb_paramset_init(&fx->ps);
    sb_paramset_add(&fx->ps, "solver", test_defs);
    char e[256];
    sb_paramset_set(&fx->ps, "solver.eta1=0.2", e, sizeof e);
    sb_paramset_set(&fx->ps, "solver.trs=steihaug_cg", e, sizeof e);
    r->params = &fx->ps;
    r->status = 0;
    r->reason = SB_REASON_GRAD_TOL;
    r->steps_planned = 2;
    r->steps_done = 2;

    sb_stats *s = &fx->stats;
    sb_stats_init(s);
    s->n_levels = 3;
    long dofs[3] = { 27, 75, 243 };
    for (int l = 0; l < 3; l++) {
        s->n_dofs[l] = dofs[l];
        s->chol_flops[l] = 1000.0 * (l + 1);
        s->chol_nnz_l[l] = 100.0 * (l + 1);
        s->matrix_nnz[l] = 50 * (l + 1);
        for (int ev = 0; ev < SB_EV_COUNT; ev++) {
            s->ev[l][ev].count = 10 * l + ev;
            s->ev[l][ev].seconds = 0.001 * (l + 1) * (ev + 1);
        }
    }
    s->work_assembly = 7.25;
    s->work_qp = 3.5;
    s->seconds_total = 1.75;
    s->not_posdef = 2;
    double g[5] = { 1.0, 1e-2, 1e-5, 0.5, 1e-7 };
    for (int i = 0; i < 5; i++) {
        sb_iter_record it = { .step = i < 3 ? 1 : 2, .iter = i < 3 ? i : i - 3, .level = 2,
                              .f = -1.0 - i, .gnorm = g[i], .delta = 1.0, .rho = 0.9,
                              .step_norm = 0.1, .shift = 0.0, .accepted = 1,
                              .linear_iters = 10, .reason = (i == 2 || i == 4) ? SB_REASON_GRAD_TOL : 0 };
        sb_stats_push_iter(s, &it);
    }
    for (int k = 0; k < 2; k++) {
        sb_step_record st = { .step = k + 1, .t = k + 1.0, .iterations = k ? 2 : 3,
                              .reason = SB_REASON_GRAD_TOL, .f = -3.0 - k, .gnorm = g[k ? 4 : 2],
                              .seconds = 0.8, .work_assembly = 3.0, .work_qp = 1.5 };
        sb_stats_push_step(s, &st);
    }
    r->stats = s;

    r->n_probes = 2;
    snprintf(fx->names[0], SB_NAME_LEN, "tip");
    snprintf(fx->names[1], SB_NAME_LEN, "centre");
    r->probe_names = fx->names;
    for (int i = 0; i < 18; i++) fx->traj[i] = 0.01 * i;
    for (int i = 0; i < 6; i++) fx->expected[i] = i < 3 ? 0.1 * i : NAN;
    fx->rel[0] = 0.03;
    fx->rel[1] = NAN;
    r->probe_traj = fx->traj;
    r->probe_expected = fx->expected;
    r->probe_rel_error = fx->rel;

    for (int i = 0; i < 27; i++) fx->x[i] = 0.5 * i;
    r->n_x = 27;
    r->x_final = fx->x;
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            int k = 3 * j + i;
            double u = 0.5 * i, v = 0.5 * j;
            fx->st[2 * k] = u, fx->st[2 * k + 1] = v;
            fx->ref[3 * k] = u, fx->ref[3 * k + 1] = v, fx->ref[3 * k + 2] = 0.0;
            fx->pos[3 * k] = u, fx->pos[3 * k + 1] = v, fx->pos[3 * k + 2] = 0.1 * u * v;
        }
    int t = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int a = 3 * j + i, b = a + 1, c = a + 4, d = a + 3;
            int tri[6] = { a, b, c, a, c, d };
            memcpy(&fx->tris[6 * t++], tri, sizeof tri);
        }
    r->n_samples = 9;
    r->sample_st = fx->st;
    r->sample_ref = fx->ref;
    r->sample_pos = fx->pos;
    r->n_tris = 8;
    r->tris = fx->tris;
    r->has_error = 1;
    r->error_rms = 1.5e-3;
    r->error_max = 4.5e-3;
    r->error_probe = 0.03;
    snprintf(r->error_kind, sizeof r->error_kind, "field");
}

static void fixture_free(fixture *fx) { sb_stats_free(&fx->stats); }

/* ---- temp directories ------------------------------------------------ */
static int make_dir(char *buf, size_t len)
{
    snprintf(buf, len, "/tmp/sb_test_record_XXXXXX");
    return mkdtemp(buf) != NULL;
}

static void remove_tree(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char p[1024];
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat st;
        if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode)) remove_tree(p);
        else unlink(p);
    }
    closedir(d);
    rmdir(dir);
}

/* Number of entries in dir whose name contains ".tmp." */
static int count_tmp(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) n += strstr(e->d_name, ".tmp.") != NULL;
    closedir(d);
    return n;
}

static char *slurp(const char *path, long *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) n = 0;
    if (b) b[n] = 0;
    fclose(f);
    if (len) *len = n;
    return b;
}

/* ---- tests --------------------------------------------------------------- */

SB_TEST(test_roundtrip_summary)
{
    char dir[64], path[256], err[1024] = "";
    CHECK(make_dir(dir, sizeof dir));
    snprintf(path, sizeof path, "%s/run.h5", dir);
    fixture fx;
    fixture_make(&fx, "trampoline");
    CHECK_EQ_INT(sb_record_write(&fx.run, path, err, sizeof err), SB_OK);
    CHECK_MSG(err[0] == 0, "unexpected message: %s", err);
    CHECK_EQ_INT(count_tmp(dir), 0);

    sb_record_summary s;
    int rc = sb_record_read_summary(path, &s, err, sizeof err);
    CHECK_MSG(rc == SB_OK, "read: %s", err);
    if (rc == SB_OK) {
        CHECK(strcmp(s.scene, "trampoline") == 0);
        CHECK(strcmp(s.method, "rmtr") == 0);
        CHECK(strcmp(s.solver, "tr") == 0);
        CHECK_EQ_INT(s.dofs, 243);
        CHECK_EQ_INT(s.levels, 3);
        CHECK_EQ_INT(s.steps, 2);
        CHECK_EQ_INT(s.steps_planned, 2);
        CHECK_EQ_INT(s.iterations, 5);
        CHECK_EQ_INT(s.status, 0);
        CHECK_EQ_INT(s.reason, SB_REASON_GRAD_TOL);
        CHECK(strcmp(s.reason_name, "grad_tol") == 0);
        CHECK_NEAR(s.work_assembly, 7.25, 0);
        CHECK_NEAR(s.work_qp, 3.5, 0);
        CHECK_NEAR(s.seconds, 1.75, 0);
        for (int ev = 0; ev < SB_EV_COUNT; ev++)   /* summed over 3 levels: 0.001*(1+2+3)*(ev+1) */
            CHECK_NEAR(s.seconds_event[ev], 0.006 * (ev + 1), 1e-15);
        CHECK_EQ_INT(s.has_error, 1);
        CHECK(strcmp(s.error_kind, "field") == 0);
        CHECK_NEAR(s.error_rms, 1.5e-3, 0);
        CHECK_NEAR(s.error_max, 4.5e-3, 0);
        CHECK_NEAR(s.error_probe, 0.03, 0);
        CHECK_EQ_INT(s.n_hist, 5);
        double g[5] = { 1.0, 1e-2, 1e-5, 0.5, 1e-7 };
        for (int i = 0; i < 5 && i < s.n_hist; i++) {
            CHECK_NEAR(s.hist_gnorm[i], g[i], 0);
            CHECK_EQ_INT(s.hist_step[i], i < 3 ? 1 : 2);
            CHECK_EQ_INT(s.hist_level[i], 2);
            CHECK_EQ_INT(s.hist_iter[i], i < 3 ? i : i - 3);
        }
        CHECK(strcmp(s.build_id, fx.run.build_id) == 0);
        CHECK(strcmp(s.cpu_model, fx.run.cpu_model) == 0);
        CHECK(strcmp(s.started, fx.run.started) == 0);
        CHECK_EQ_INT(s.n_cores, fx.run.n_cores);
        sb_record_summary_free(&s);
        CHECK(s.hist_gnorm == NULL && s.hist_iter == NULL && s.n_hist == 0);
    }

    int n = 0;
    double *st = NULL, *pos = NULL;
    rc = sb_record_read_samples(path, &n, &st, &pos, err, sizeof err);
    CHECK_MSG(rc == SB_OK, "samples: %s", err);
    CHECK_EQ_INT(n, 9);
    if (rc == SB_OK && n == 9) {
        int same = 1;
        for (int i = 0; i < 18; i++) same &= st[i] == fx.st[i];
        for (int i = 0; i < 27; i++) same &= pos[i] == fx.pos[i];
        CHECK(same);
    }
    free(st);
    free(pos);

    /* the XDMF sidecar points at the record's datasets by base name */
    char xpath[256];
    CHECK_EQ_INT(sb_record_xdmf_path(path, xpath, sizeof xpath), SB_OK);
    CHECK(strstr(xpath, "/run.xdmf") != NULL);
    char *x = slurp(xpath, NULL);
    CHECK(x != NULL);
    if (x) {
        CHECK(strstr(x, "TopologyType=\"Triangle\" NumberOfElements=\"8\"") != NULL);
        CHECK(strstr(x, ">run.h5:/final/triangles<") != NULL);
        CHECK(strstr(x, ">run.h5:/final/sample_pos<") != NULL);
        CHECK(strstr(x, ">run.h5:/final/sample_ref<") != NULL);
        CHECK(strstr(x, ">run.h5:/final/displacement<") != NULL);
        CHECK(strstr(x, "Dimensions=\"9 3\"") != NULL);
    }
    free(x);
    fixture_free(&fx);
    remove_tree(dir);
}

/* Read raw datasets/attributes with the HDF5 API: what h5dump / h5py see. */
SB_TEST(test_layout_raw)
{
    char dir[64], path[256], err[1024] = "";
    CHECK(make_dir(dir, sizeof dir));
    snprintf(path, sizeof path, "%s/raw.h5", dir);
    fixture fx;
    fixture_make(&fx, "plate");
    /* a scene text larger than the 64 KiB compact-attribute limit */
    size_t big = 200000;
    char *json = malloc(big + 1);
    for (size_t i = 0; i < big; i++) json[i] = (char)('a' + i % 26);
    json[big] = 0;
    fx.run.scene_json = json;
    CHECK_MSG(sb_record_write(&fx.run, path, err, sizeof err) == SB_OK, "%s", err);

    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK(f >= 0);
    if (f >= 0) {
        hid_t a = H5Aopen(f, "scene_json", H5P_DEFAULT), t = H5Aget_type(a);
        CHECK_EQ_INT(H5Tget_size(t), big + 1);
        char *back = malloc(big + 1);
        CHECK(H5Aread(a, t, back) >= 0 && memcmp(back, json, big + 1) == 0);
        free(back);
        H5Tclose(t);
        H5Aclose(a);

        hid_t g = H5Gopen2(f, "/params", H5P_DEFAULT);
        double eta1 = 0;
        long maxit = 0;
        a = H5Aopen(g, "solver.eta1", H5P_DEFAULT);
        H5Aread(a, H5T_NATIVE_DOUBLE, &eta1);
        H5Aclose(a);
        a = H5Aopen(g, "solver.max_iter", H5P_DEFAULT);
        H5Aread(a, H5T_NATIVE_LONG, &maxit);
        H5Aclose(a);
        char trs[32] = "";
        a = H5Aopen(g, "solver.trs", H5P_DEFAULT);
        t = H5Aget_type(a);
        CHECK(H5Tget_class(t) == H5T_STRING && H5Tget_size(t) < sizeof trs);
        H5Aread(a, t, trs);
        H5Tclose(t);
        H5Aclose(a);
        H5Gclose(g);
        CHECK_NEAR(eta1, 0.2, 0);
        CHECK_EQ_INT(maxit, 50);
        CHECK(strcmp(trs, "steihaug_cg") == 0);

        long cnt[3][SB_EV_COUNT];
        hid_t d = H5Dopen2(f, "/stats/events_count", H5P_DEFAULT);
        CHECK(H5Dread(d, H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, cnt) >= 0);
        H5Dclose(d);
        CHECK_EQ_INT(cnt[2][SB_EV_FACTORIZE], 20 + SB_EV_FACTORIZE);
        double traj[3][2][3];
        d = H5Dopen2(f, "/probes/trajectory", H5P_DEFAULT);
        CHECK(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, traj) >= 0);
        H5Dclose(d);
        CHECK_NEAR(traj[2][1][2], 0.01 * 17, 1e-15);
        int tris[8][3];
        d = H5Dopen2(f, "/final/triangles", H5P_DEFAULT);
        CHECK(H5Dread(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, tris) >= 0);
        H5Dclose(d);
        CHECK_EQ_INT(tris[7][2], 7);
        double disp[9][3];
        d = H5Dopen2(f, "/final/displacement", H5P_DEFAULT);
        CHECK(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, disp) >= 0);
        H5Dclose(d);
        CHECK_NEAR(disp[8][2], 0.1, 1e-15);
        H5Fclose(f);
    }
    /* h5dump reads the whole file (skipped when h5dump is absent) */
    if (system("command -v h5dump >/dev/null 2>&1") == 0) {
        char cmd[512];
        snprintf(cmd, sizeof cmd, "h5dump -H '%s' > /dev/null 2>&1", path);
        CHECK_EQ_INT(system(cmd), 0);
        snprintf(cmd, sizeof cmd, "h5dump -d /history/iterations/gnorm '%s' > /dev/null 2>&1", path);
        CHECK_EQ_INT(system(cmd), 0);
    } else {
        printf("    (h5dump not found: h5dump check skipped)\n");
    }
    free(json);
    fixture_free(&fx);
    remove_tree(dir);
}

/* No probes, no iterations, no samples, no stats: zero-length datasets. */
SB_TEST(test_empty_run)
{
    char dir[64], path[256], err[1024] = "";
    CHECK(make_dir(dir, sizeof dir));
    snprintf(path, sizeof path, "%s/empty", dir);   /* no .h5: sidecar gets .xdmf appended */
    sb_run r;
    sb_run_init(&r);
    snprintf(r.scene_name, sizeof r.scene_name, "empty");
    r.status = 1;
    r.reason = SB_REASON_MAX_ITER;
    CHECK_MSG(sb_record_write(&r, path, err, sizeof err) == SB_OK, "%s", err);
    sb_record_summary s;
    CHECK_MSG(sb_record_read_summary(path, &s, err, sizeof err) == SB_OK, "%s", err);
    CHECK_EQ_INT(s.n_hist, 0);
    CHECK_EQ_INT(s.iterations, 0);
    CHECK_EQ_INT(s.has_error, 0);
    CHECK(strcmp(s.error_kind, "none") == 0);
    CHECK(strcmp(s.reason_name, "max_iter") == 0);
    sb_record_summary_free(&s);
    int n = -1;
    double *st = NULL, *pos = NULL;
    CHECK_MSG(sb_record_read_samples(path, &n, &st, &pos, err, sizeof err) == SB_OK, "%s", err);
    CHECK_EQ_INT(n, 0);
    free(st);
    free(pos);
    char xpath[300];
    snprintf(xpath, sizeof xpath, "%s.xdmf", path);
    CHECK(access(xpath, R_OK) == 0);
    CHECK_EQ_INT(count_tmp(dir), 0);

    /* Iterations without step records: counted at the finest level only. */
    sb_stats stats;
    sb_stats_init(&stats);
    for (int i = 0; i < 6; i++) {
        sb_iter_record it = { .step = 1, .iter = i, .level = i % 3 == 2 ? 0 : 1, .gnorm = 1.0 / (i + 1) };
        sb_stats_push_iter(&stats, &it);
    }
    r.stats = &stats;
    CHECK_MSG(sb_record_write(&r, path, err, sizeof err) == SB_OK, "%s", err);
    CHECK_MSG(sb_record_read_summary(path, &s, err, sizeof err) == SB_OK, "%s", err);
    CHECK_EQ_INT(s.n_hist, 6);
    CHECK_EQ_INT(s.iterations, 4);
    sb_record_summary_free(&s);
    sb_stats_free(&stats);
    remove_tree(dir);
}

/* A failed write returns an error naming the path, leaves no temp file and
 * leaves an earlier good record (and its sidecar) untouched. */
SB_TEST(test_failed_write_keeps_good_file)
{
    char dir[64], path[256], tmp[300], err[1024] = "";
    CHECK(make_dir(dir, sizeof dir));
    snprintf(path, sizeof path, "%s/run.h5", dir);
    fixture good, bad;
    fixture_make(&good, "good_scene");
    fixture_make(&bad, "bad_scene");
    CHECK_MSG(sb_record_write(&good.run, path, err, sizeof err) == SB_OK, "%s", err);
    long len0 = 0, xlen0 = 0;
    char *bytes0 = slurp(path, &len0);
    char xpath[256];
    sb_record_xdmf_path(path, xpath, sizeof xpath);
    char *xbytes0 = slurp(xpath, &xlen0);

    /* 1. the record's temp name is taken by a directory (works as root too) */
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
    CHECK(mkdir(tmp, 0755) == 0);
    err[0] = 0;
    CHECK_EQ_INT(sb_record_write(&bad.run, path, err, sizeof err), SB_ERR_IO);
    CHECK_MSG(strstr(err, path) != NULL, "message does not name the path: %s", err);
    rmdir(tmp);
    /* 2. the sidecar's temp name is taken: the HDF5 temp must be removed */
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", xpath, (long)getpid());
    CHECK(mkdir(tmp, 0755) == 0);
    err[0] = 0;
    CHECK_EQ_INT(sb_record_write(&bad.run, path, err, sizeof err), SB_ERR_IO);
    CHECK_MSG(strstr(err, "XDMF") != NULL, "message: %s", err);
    rmdir(tmp);
    CHECK_EQ_INT(count_tmp(dir), 0);
    /* 3. invalid input (triangle index out of range) is an input error */
    bad.run.tris[5] = 99;
    CHECK_EQ_INT(sb_record_write(&bad.run, path, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "triangle") != NULL, "message: %s", err);
    bad.run.tris[5] = 0;
    bad.run.n_probes = 2;
    bad.run.probe_traj = NULL;
    CHECK_EQ_INT(sb_record_write(&bad.run, path, err, sizeof err), SB_ERR_INPUT);

    long len1 = 0, xlen1 = 0;
    char *bytes1 = slurp(path, &len1), *xbytes1 = slurp(xpath, &xlen1);
    CHECK(bytes0 && bytes1 && len0 == len1 && memcmp(bytes0, bytes1, (size_t)len0) == 0);
    CHECK(xbytes0 && xbytes1 && xlen0 == xlen1 && memcmp(xbytes0, xbytes1, (size_t)xlen0) == 0);
    sb_record_summary s;
    CHECK(sb_record_read_summary(path, &s, err, sizeof err) == SB_OK && strcmp(s.scene, "good_scene") == 0);
    sb_record_summary_free(&s);
    CHECK_EQ_INT(count_tmp(dir), 0);

    /* 4. unwritable locations */
    snprintf(tmp, sizeof tmp, "%s/no/such/dir/run.h5", dir);
    CHECK_EQ_INT(sb_record_write(&good.run, tmp, err, sizeof err), SB_ERR_IO);
    CHECK_MSG(strstr(err, tmp) != NULL, "message: %s", err);
    CHECK_EQ_INT(sb_record_write(&good.run, "/proc/sb_test_record.h5", err, sizeof err), SB_ERR_IO);
    CHECK_EQ_INT(sb_record_write(&good.run, "", err, sizeof err), SB_ERR_INPUT);
    free(bytes0);
    free(bytes1);
    free(xbytes0);
    free(xbytes1);
    fixture_free(&good);
    fixture_free(&bad);
    remove_tree(dir);
}

/* Missing, non-HDF5, truncated and foreign HDF5 files are clean errors. */
SB_TEST(test_unreadable_files)
{
    char dir[64], path[256], p[300], err[1024];
    CHECK(make_dir(dir, sizeof dir));
    sb_record_summary s;
    int n;
    double *st, *pos;

    snprintf(p, sizeof p, "%s/missing.h5", dir);
    CHECK_EQ_INT(sb_record_read_summary(p, &s, err, sizeof err), SB_ERR_IO);
    CHECK_MSG(strstr(err, p) && strstr(err, "No such file"), "message: %s", err);
    CHECK_EQ_INT(sb_record_read_samples(p, &n, &st, &pos, err, sizeof err), SB_ERR_IO);
    CHECK(st == NULL && pos == NULL && n == 0);

    snprintf(p, sizeof p, "%s/text.h5", dir);
    FILE *f = fopen(p, "w");
    fputs("this is not HDF5\n", f);
    fclose(f);
    CHECK_EQ_INT(sb_record_read_summary(p, &s, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "not an HDF5 file") != NULL, "message: %s", err);
    CHECK_EQ_INT(sb_record_read_summary(dir, &s, err, sizeof err), SB_ERR_INPUT);

    snprintf(p, sizeof p, "%s/foreign.h5", dir);
    hid_t h = H5Fcreate(p, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Fclose(h);
    CHECK_EQ_INT(sb_record_read_summary(p, &s, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "not a shellbench run record") != NULL, "message: %s", err);

    /* truncated copies of a good record at several lengths */
    snprintf(path, sizeof path, "%s/good.h5", dir);
    fixture fx;
    fixture_make(&fx, "trunc");
    CHECK_MSG(sb_record_write(&fx.run, path, err, sizeof err) == SB_OK, "%s", err);
    long len = 0;
    char *bytes = slurp(path, &len);
    CHECK(bytes && len > 1000);
    double cut[4] = { 0.05, 0.3, 0.6, 0.95 };
    for (int k = 0; k < 4 && bytes; k++) {
        snprintf(p, sizeof p, "%s/trunc%d.h5", dir, k);
        f = fopen(p, "wb");
        fwrite(bytes, 1, (size_t)(cut[k] * (double)len), f);
        fclose(f);
        int rc = sb_record_read_summary(p, &s, err, sizeof err);
        CHECK_MSG(rc == SB_ERR_IO || rc == SB_ERR_INPUT, "truncated at %.0f%%: rc %d", 100 * cut[k], rc);
        CHECK_MSG(strstr(err, p) != NULL, "message: %s", err);
        CHECK(s.hist_gnorm == NULL);
        rc = sb_record_read_samples(p, &n, &st, &pos, err, sizeof err);
        CHECK(rc == SB_ERR_IO || rc == SB_ERR_INPUT);
    }
    free(bytes);
    fixture_free(&fx);
    remove_tree(dir);
}

SB_TEST(test_sysinfo)
{
    char buf[128];
    sb_sysinfo_cpu_model(buf, sizeof buf);
    CHECK(buf[0] != 0);
    CHECK(sb_sysinfo_cores() >= 1);
    sb_sysinfo_now_iso(buf, sizeof buf);
    CHECK_EQ_INT(strlen(buf), 20);
    CHECK(buf[4] == '-' && buf[10] == 'T' && buf[19] == 'Z');
    sb_sysinfo_build_id(buf, sizeof buf);
    CHECK(buf[0] != 0);
    /* the BLAS kernel set: the one OPENBLAS_CORETYPE asked for (make test pins it) when OpenBLAS is loaded */
    sb_sysinfo_blas_core(buf, sizeof buf);
    CHECK(buf[0] != 0);
    const char *ct = getenv("OPENBLAS_CORETYPE");
    if (ct && *ct && strcmp(buf, "unknown") != 0)
        CHECK_MSG(strcasecmp(buf, ct) == 0, "OPENBLAS_CORETYPE=%s but OpenBLAS runs %s", ct, buf);
    char tiny[4];
    sb_sysinfo_cpu_model(tiny, sizeof tiny);
    CHECK(strlen(tiny) <= 3);
    char xp[8];
    CHECK_EQ_INT(sb_record_xdmf_path("a/very/long/name.h5", xp, sizeof xp), SB_ERR_INPUT);
    char xq[64];
    CHECK(sb_record_xdmf_path("out/r.h5", xq, sizeof xq) == SB_OK && strcmp(xq, "out/r.xdmf") == 0);
}

static const sb_test_case cases[] = {
    SB_CASE(test_roundtrip_summary),
    SB_CASE(test_layout_raw),
    SB_CASE(test_empty_run),
    SB_CASE(test_failed_write_keeps_good_file),
    SB_CASE(test_unreadable_files),
    SB_CASE(test_sysinfo),
    SB_END,
};

int main(int argc, char **argv) { return sb_test_main(argc, argv, cases); }
