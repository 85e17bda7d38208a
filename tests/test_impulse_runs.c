/* test_impulse_runs.c — contact.model = "impulse" through the method op
 * impulse_response and the run loop (docs/contact.md): both triangle
 * methods on cloth_sphere and drape_box keep every mesh vertex
 * outside the obstacle after every step (an independent inside test on the
 * method's own surface triangles); whole runs record the response (event
 * collide each step, /final/contact stats in the summary); what cannot run
 * the impulse model is refused before any work with a sentence. */
#include <hdf5.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_sh.h"
#include "run_json.h"
#include "sb_context.h"
#include "sb_impulse.h"
#include "sb_record_io.h"
#include "sb_run.h"
#include "sb_run_state.h"
#include "sb_solver.h"
#include "sb_surface.h"
#include "sb_test.h"
#include "seg_tri.h"

extern const sb_param_def sb_solve_params[];

static const char *const triangle_methods[2] = { "linear_fem", "adaptive_sqrt3" };

/* the bundled scene with contact.model = "impulse" (and more), written to a temporary file */
static int impulse_scene(const char *name, int steps, int self, int static_mode, char *path, size_t len)
{
    char src[1024];
    snprintf(src, sizeof src, "%s/bench/scenes/%s.json", sb_test_root(), name);
    json_error_t e;
    json_t *j = json_load_file(src, 0, &e);
    if (!j) return -1;
    json_t *c = json_object_get(j, "contact"), *t = json_object_get(j, "time");
    json_object_set_new(c, "model", json_string("impulse"));
    if (self) json_object_set_new(c, "self", json_true());
    json_object_set_new(t, "steps", json_integer(steps));
    if (static_mode) {
        json_object_set_new(j, "time", json_pack("{s:s, s:i}", "mode", "quasi_static", "steps", 1));
    }
    snprintf(path, len, "/tmp/sb_impulse_%s_%d_%d_%d_%ld.json", name, steps, self, static_mode, (long)getpid());
    int rc = json_dump_file(j, path, JSON_INDENT(1));
    json_decref(j);
    return rc;
}

static int inside_obstacle(const sb_scene *sc, const double *p)
{
    for (int o = 0; o < sc->n_obstacles; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        if (ob->kind == SB_OBST_SPHERE) {
            double d2 = 0;
            for (int c = 0; c < 3; c++) d2 += (p[c] - ob->center[c]) * (p[c] - ob->center[c]);
            if (d2 < ob->radius * ob->radius) return 1;
        } else if (ob->kind == SB_OBST_PLANE) {
            double d = 0;
            for (int c = 0; c < 3; c++) d += (p[c] - ob->point[c]) * ob->normal[c];
            if (d < 0) return 1;
        } else if (ob->kind == SB_OBST_BOX) {
            int in = 1;
            for (int c = 0; c < 3; c++) in &= fabs(p[c] - ob->center[c]) < ob->half[c];
            if (in) return 1;
        }
    }
    return 0;
}

/* steps of scene `name` with method mt driven directly (solve, then the
 * response), the surface's vertices checked after every step */
/* edges of the surface crossing its own triangles (no shared vertex) */
static int self_crossings(const sb_surface *s)
{
    int n = 0;
    for (int e = 0; e < s->n_tris; e++)
        for (int k = 0; k < 3; k++) {
            const int i = s->tri[3 * e + k], j = s->tri[3 * e + (k + 1) % 3];
            for (int t = 0; t < s->n_tris; t++) {
                const int *f = s->tri + 3 * t;
                if (i == f[0] || i == f[1] || i == f[2] || j == f[0] || j == f[1] || j == f[2]) continue;
                n += tb_seg_tri(s->vert + 3 * i, s->vert + 3 * j, s->vert + 3 * f[0], s->vert + 3 * f[1], s->vert + 3 * f[2]);
            }
        }
    return n;
}

typedef struct drive_out { int inside, crossings, steps; sb_impulse_stats is; } drive_out;

/* `steps` steps of the scene file `path` (self: contact.self as given, 0 or
 * 1) with method mt driven directly (solve, then the response); after every
 * step the method's surface vertices against the analytic obstacles and its
 * edges against its own triangles */
static void drive_file(sb_test_state *T, const char *path, const sb_method_type *mt, int steps, int self, drive_out *out)
{
    char err[1024];
    const char *name = path;
    memset(out, 0, sizeof *out);
    sb_context ctx;
    sb_scene sc;
    sb_context_init(&ctx);
    CHECK_EQ_INT(sb_scene_load(path, &sc, err, sizeof err), 0);
    sc.contact.self = self;
    const int potential = (mt->flags & SB_METHOD_POTENTIAL) != 0;
    const sb_solver_type *st = sb_solver_find(potential ? "lsnewton" : "linearized");
    sb_paramset_add(&ctx.params, "run", sb_solve_params);
    if (st->params) sb_paramset_add(&ctx.params, "solver", st->params);
    if (mt->params) sb_paramset_add(&ctx.params, "method", mt->params);
    void *ms = calloc(1, mt->state_size), *ss = calloc(1, st->state_size);
    sb_method_config cfg = { 8, 1, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    int rc = mt->create(ms, &sc, &cfg);
    if (!rc) rc = sb_problem_create(&ctx, mt, ms, &sc, &p);
    if (!rc) rc = st->alloc(ss, p, &ctx.params);
    CHECK_MSG(rc == 0, "%s/%s: %s", name, mt->name, ctx.err);
    if (rc) goto done;
    CHECK(!sb_problem_has_contact(p));   /* no barrier terms under the impulse model */
    CHECK(sb_problem_has_impulse(p));
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F);
    double *x = malloc(n * sizeof(double)), *xn = malloc(n * sizeof(double)), *v = calloc(n, sizeof(double));
    mt->initial(ms, F, x);
    sb_impulse_stats is;
    memset(&is, 0, sizeof is);
    int inside = 0, checked = 0;
    for (int step = 1; step <= steps; step++) {
        sb_step_info si;
        sb_run_step_info(&sc, step, &si);
        sb_copy(n, x, xn);
        CHECK_EQ_INT(sb_problem_begin_step(p, &si, xn, v, x), 0);
        sb_step_outcome o;
        sb_reason r = sb_solve_step_ex(st, ss, p, &ctx.params, step, x, &o);
        CHECK_MSG(r != SB_REASON_NONFINITE, "%s/%s step %d: nonfinite", name, mt->name, step);
        CHECK_EQ_INT(sb_problem_impulse(p, si.t, xn, x, &is), SB_OK);
        for (int i = 0; i < n; i++) v[i] = (x[i] - xn[i]) / sc.time.dt;
        sb_surface surf;
        memset(&surf, 0, sizeof surf);
        CHECK_EQ_INT(mt->surface(ms, F, x, &surf), 0);
        for (int k = 0; k < surf.n_verts; k++) inside += inside_obstacle(&sc, surf.vert + 3 * k);
        checked += surf.n_verts;
        out->crossings += self_crossings(&surf);
        sb_surface_free(&surf);
        out->steps = step;
    }
    printf("    %-12s %-15s self %d: %d vertex checks, %d inside, %d self-crossings; proximity %ld, CCD tests %ld, "
           "hits %ld, passes %ld, zones %ld, unresolved %ld\n", sc.name, mt->name, self, checked, inside,
           out->crossings, is.proximity_impulses, is.ccd_tests, is.ccd_hits, is.ccd_iterations, is.impact_zones,
           is.unresolved_steps);
    out->inside = inside;
    out->is = is;
    CHECK_EQ_INT(sb_stats_event_total(&ctx.stats, SB_EV_COLLIDE).count, steps);
    free(x); free(xn); free(v);
done:
    if (p) st->free(ss);
    sb_problem_free(p);
    mt->destroy(ms);
    free(ms); free(ss);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
}

/* a bundled scene with contact.model = "impulse": no vertex inside the obstacle after any step */
static void drive(sb_test_state *T, const char *name, const sb_method_type *mt, int steps)
{
    char path[1024];
    CHECK_EQ_INT(impulse_scene(name, steps, 0, 0, path, sizeof path), 0);
    drive_out o;
    drive_file(T, path, mt, steps, 0, &o);
    unlink(path);
    CHECK_MSG(o.inside == 0, "%s/%s: %d vertices inside the obstacle after a step", name, mt->name, o.inside);
    CHECK(o.is.proximity_impulses + o.is.ccd_hits > 0);   /* the cloth reached the obstacle */
    CHECK_EQ_INT(o.is.unresolved_steps, 0);
}

SB_TEST(triangle_methods_keep_vertices_outside)
{
    /* the triangle methods (Bridson's pipeline; bhem's own response is another
       pipeline with another surface) */
    for (int i = 0; i < 2; i++) {
        const sb_method_type *mt = sb_method_find(triangle_methods[i]);
        CHECK(mt && mt->impulse_response && mt->surface);
        if (!mt || !mt->impulse_response || !mt->surface) continue;
        drive(T, "cloth_sphere", mt, 14);
        drive(T, "drape_box", mt, 14);
    }
}

SB_TEST(folding_strip_on_the_ground)
{
    /* tests/scenes/contact/fold_ground.json: the strip folded onto itself;
       with contact.self no edge crosses a triangle after any step, and
       without it the same fold does cross (the check can fail) */
    char path[1024];
    snprintf(path, sizeof path, "%s/tests/scenes/contact/fold_ground.json", sb_test_root());
    const int steps = 45;
    for (int i = 0; i < 2; i++) {
        const sb_method_type *mt = sb_method_find(triangle_methods[i]);
        CHECK(mt && mt->impulse_response && mt->surface);
        if (!mt || !mt->impulse_response || !mt->surface) continue;
        drive_out o;
        drive_file(T, path, mt, steps, 1, &o);
        CHECK(o.steps == steps);
        CHECK_MSG(o.crossings == 0, "%s: %d self-crossings with contact.self", mt->name, o.crossings);
        CHECK_EQ_INT(o.inside, 0);
        CHECK_EQ_INT(o.is.unresolved_steps, 0);
        drive_file(T, path, mt, steps, 0, &o);
        CHECK_MSG(o.crossings > 0, "%s: the fold never crossed itself without self-contact", mt->name);
    }
}

static json_t *run(const char *scene, const char *method, const char *solver, int n_sets, const char *const *sets,
                   int *code)
{
    sb_run_request req;
    sb_test_request(&req, scene, method, solver, 0);
    req.summary_json = 1;
    req.n_sets = n_sets;
    req.sets = sets;
    return sb_test_run_json(&req, code);
}

SB_TEST(runs_record_the_response)
{
    static const char *const rtol[] = { "run.single_step_rtol=1e300" };
    struct { const char *scene, *method, *solver; int self, ns; } cases[] = {
        { "cloth_sphere", "linear_fem", "lsnewton", 0, 0 },
        { "drape_box", "linear_fem", "lsnewton", 1, 0 },
        { "cloth_sphere", "adaptive_sqrt3", "linearized", 0, 1 },
        { "drape_box", "adaptive_sqrt3", "linearized", 1, 1 },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char path[1024];
        CHECK_EQ_INT(impulse_scene(cases[k].scene, 12, cases[k].self, 0, path, sizeof path), 0);
        int code = -1;
        json_t *j = run(path, cases[k].method, cases[k].solver, cases[k].ns, rtol, &code);
        unlink(path);
        CHECK_MSG(code == 0 && j, "%s/%s: exit %d", cases[k].scene, cases[k].method, code);
        if (!j) continue;
        json_t *co = json_object_get(j, "contact");
        CHECK(co && strcmp(json_string_value(json_object_get(co, "model")), "impulse") == 0);
        CHECK(json_integer_value(json_object_get(co, "ccd_tests")) > 0);
        CHECK(json_integer_value(json_object_get(co, "proximity_impulses")) + json_integer_value(json_object_get(co, "ccd_hits")) > 0);
        CHECK_EQ_INT(json_integer_value(json_object_get(co, "unresolved_steps")), 0);
        CHECK_EQ_INT(json_integer_value(json_object_get(json_object_get(j, "counts"), "collide")), 12);
        CHECK(json_real_value(json_object_get(json_object_get(j, "seconds"), "collide")) > 0);
        CHECK(json_object_get(co, "points") == NULL);   /* no barrier sample points */
        json_decref(j);
    }
}

static long read_attr_long(const char *path, const char *obj, const char *name)
{
    long v = -1;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);   /* a missing attribute is an answer here */
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) return -1;
    hid_t a = H5Aopen_by_name(f, obj, name, H5P_DEFAULT, H5P_DEFAULT);
    if (a >= 0) {
        if (H5Aread(a, H5T_NATIVE_LONG, &v) < 0) v = -1;
        H5Aclose(a);
    }
    H5Fclose(f);
    return v;
}

SB_TEST(record_holds_the_counts)
{
    char path[1024], h5[1100];
    CHECK_EQ_INT(impulse_scene("drape_box", 12, 0, 0, path, sizeof path), 0);
    snprintf(h5, sizeof h5, "%s.h5", path);
    sb_run_request req;
    sb_test_request(&req, path, "linear_fem", "lsnewton", 0);
    req.out = h5;
    req.summary_json = 1;
    int code = -1;
    json_t *j = sb_test_run_json(&req, &code);
    CHECK_EQ_INT(code, 0);
    if (j) {
        json_t *co = json_object_get(j, "contact");
        static const char *const keys[] = { "proximity_impulses", "ccd_tests", "ccd_hits", "ccd_iterations",
                                            "impact_zones", "unresolved_steps" };
        for (int k = 0; k < 6; k++)
            CHECK_MSG(read_attr_long(h5, "/final/contact", keys[k]) == json_integer_value(json_object_get(co, keys[k])),
                      "/final/contact/%s", keys[k]);
        CHECK(read_attr_long(h5, "/final/contact", "ccd_tests") > 0);
        CHECK(read_attr_long(h5, "/final/contact", "points") == -1);   /* no barrier figures */
        json_decref(j);
    }
    unlink(h5);
    unlink(path);
    char side[1200];   /* the record's XDMF companions */
    snprintf(side, sizeof side, "%.*s.xdmf", (int)(strlen(h5) - 3), h5);
    unlink(side);
    snprintf(side, sizeof side, "%.*s.steps.xdmf", (int)(strlen(h5) - 3), h5);
    unlink(side);
}

/* A checkpoint whose /resume/impulse_counts has the wrong length (a copy
 * of the real one, rewritten) is refused as input before any step, with a
 * sentence naming the file and the group; the real one is left alone */
static void bad_counts_are_refused(sb_test_state *T, sb_run_request *req, const char *out)
{
    char bad[1200], bad_partial[1300], good_partial[1300], cmd[3000];
    snprintf(bad, sizeof bad, "%s.bad.h5", out);
    snprintf(bad_partial, sizeof bad_partial, "%s.partial", bad);
    snprintf(good_partial, sizeof good_partial, "%s.partial", out);
    snprintf(cmd, sizeof cmd, "cp '%s' '%s'", good_partial, bad_partial);
    CHECK_EQ_INT(system(cmd), 0);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(bad_partial, H5F_ACC_RDWR, H5P_DEFAULT);
    CHECK(f >= 0);
    if (f < 0) return;
    CHECK(H5Ldelete(f, "/resume/impulse_counts", H5P_DEFAULT) >= 0);
    hsize_t n = 3;
    long three[3] = { 1, 2, 3 };
    hid_t sp = H5Screate_simple(1, &n, NULL);
    hid_t d = H5Dcreate2(f, "/resume/impulse_counts", H5T_NATIVE_LONG, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    CHECK(d >= 0 && H5Dwrite(d, H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, three) >= 0);
    H5Dclose(d);
    H5Sclose(sp);
    H5Fclose(f);
    char msg[512];
    CHECK_EQ_INT(sb_record_seal(bad_partial, msg, sizeof msg), 0);   /* sealed again: a well-formed file, wrong content */
    const char *keep = req->out;
    req->out = bad;
    char *err = NULL, *js = NULL;
    size_t len = 0;
    FILE *es = open_memstream(&err, &len), *devnull = fopen("/dev/null", "w");
    const int code = sb_run_execute(req, devnull, es, &js);
    fclose(es);
    if (devnull) fclose(devnull);
    CHECK_EQ_INT(code, SB_EXIT_INPUT);
    CHECK_MSG(err && strstr(err, "impulse counts of the wrong length") && strstr(err, bad_partial),
              "message: %s", err ? err : "(none)");
    free(js);
    free(err);
    req->out = keep;
    unlink(bad_partial);
}

/* A run stopped part-way and resumed counts the collision response over
 * every step (the counts travel in the checkpoint's /resume/impulse_counts),
 * equal to the uninterrupted run's, and the broad phase's queries are
 * recorded (adaptive_sqrt3 with self-contact: the triangle pipeline) */
SB_TEST(a_resumed_run_counts_every_step)
{
    static const char *const rtol[] = { "run.single_step_rtol=1e300" };
    char path[1024], whole[1100], pieces[1100];
    CHECK_EQ_INT(impulse_scene("drape_box", 12, 1, 0, path, sizeof path), 0);
    snprintf(whole, sizeof whole, "%s.whole.h5", path);
    snprintf(pieces, sizeof pieces, "%s.pieces.h5", path);
    static const char *const keys[] = { "proximity_impulses", "ccd_tests", "ccd_hits", "ccd_iterations",
                                        "impact_zones", "unresolved_steps", "counted_steps", "broad_queries",
                                        "broad_candidates" };
    sb_run_request req;
    sb_test_request(&req, path, "adaptive_sqrt3", "linearized", 0);
    req.sets = rtol;
    req.n_sets = 1;
    req.out = whole;
    int code = -1;
    json_t *j = sb_test_run_json(&req, &code);
    CHECK_EQ_INT(code, 0);
    json_decref(j);
    req.out = pieces;
    for (int stop = 5; stop <= 12; stop += 7) {   /* steps 1-5, then 6-12 resumed */
        req.stop_after_steps = stop < 12 ? stop : 0;
        req.resume = stop > 5;
        if (stop > 5) bad_counts_are_refused(T, &req, pieces);
        j = sb_test_run_json(&req, &code);
        CHECK_EQ_INT(code, stop < 12 ? SB_EXIT_STOPPED : 0);
        json_decref(j);
    }
    for (int k = 0; k < 9; k++) {
        const long a = read_attr_long(whole, "/final/contact", keys[k]), b = read_attr_long(pieces, "/final/contact", keys[k]);
        CHECK_MSG(a == b && a >= 0, "/final/contact/%s: uninterrupted %ld, resumed %ld", keys[k], a, b);
    }
    CHECK_EQ_INT(read_attr_long(pieces, "/final/contact", "counted_steps"), 12);
    CHECK(read_attr_long(whole, "/final/contact", "broad_candidates") > read_attr_long(whole, "/final/contact", "ccd_tests") / 100);
    CHECK(read_attr_long(whole, "/final/contact", "broad_queries") > 0);
    const char *outs[2] = { whole, pieces };
    for (int k = 0; k < 2; k++) {
        char side[1200];
        unlink(outs[k]);
        snprintf(side, sizeof side, "%.*s.xdmf", (int)(strlen(outs[k]) - 3), outs[k]);
        unlink(side);
        snprintf(side, sizeof side, "%.*s.steps.xdmf", (int)(strlen(outs[k]) - 3), outs[k]);
        unlink(side);
        snprintf(side, sizeof side, "%.*s.mesh.xdmf", (int)(strlen(outs[k]) - 3), outs[k]);
        unlink(side);
    }
    unlink(path);
}

SB_TEST(refusals)
{
    char path[1024];
    int code = -1;
    /* a static scene has no velocities to act on */
    CHECK_EQ_INT(impulse_scene("drape_box", 1, 0, 1, path, sizeof path), 0);
    char out[4096], err[4096];
    code = sb_sh(out, sizeof out, err, sizeof err, "'%s' run --scene '%s' --method linear_fem --solver lsnewton --out none",
                 sb_test_bin(), path);
    CHECK_EQ_INT(code, 2);
    CHECK_MSG(strstr(err, "static scene") != NULL, "%s", err);
    unlink(path);
    /* a method without the op */
    CHECK_EQ_INT(impulse_scene("drape_box", 2, 0, 0, path, sizeof path), 0);
    int refused = 0;
    for (int i = 0; i < sb_method_count(); i++) {
        const sb_method_type *mt = sb_method_at(i);
        if (mt->impulse_response || (mt->flags & SB_METHOD_TEST_FIXTURE)) continue;
        code = sb_sh(out, sizeof out, err, sizeof err, "'%s' run --scene '%s' --method %s --solver lsnewton --out none",
                     sb_test_bin(), path, mt->name);
        CHECK_EQ_INT(code, 2);
        CHECK_MSG(strstr(err, "has no impulse-based collision response") != NULL, "%s: %s", mt->name, err);
        refused++;
    }
    printf("    %d methods without the op refused\n", refused);
    unlink(path);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = { SB_CASE(triangle_methods_keep_vertices_outside),
                                          SB_CASE(folding_strip_on_the_ground),
                                          SB_CASE(runs_record_the_response),
                                          SB_CASE(record_holds_the_counts),
                                          SB_CASE(a_resumed_run_counts_every_step), SB_CASE(refusals), SB_END };
    return sb_test_main(argc, argv, cases);
}
