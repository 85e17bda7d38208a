/* test_bhem_impulse.c — bhem's own collision pipeline (contact.model =
 * "impulse", docs/contact.md; BHEM §5.2 CCD and §6.2 response) on the needle
 * scene (BHEM Fig. 4), tiny resolution, the first steps in which the cloth
 * lands on the needle tips:
 *   - after every step's response no needle passes through the cloth,
 *     checked independently of the CCD: the static ray–patch intersection
 *     (§5.1, core/render/sb_bezier_ray.h) of the segment from each needle's
 *     foot along its axis to its apex with every patch of the step's end
 *     state finds nothing;
 *   - without the response the same check fails (the cloth falls through),
 *     so the check can fail;
 *   - the recorded statistics are non-zero and no step is left unresolved;
 *   - the run loop path (sb_run_execute with bench/bhem/scenes/needles_impulse.json)
 *     converges and reports the statistics in its summary;
 *   - cloth_sphere under the impulse model: the cloth's points against the
 *     exact sphere;
 *   - a mesh obstacle (tests/scenes/contact/cloth_mesh_impulse.json): the
 *     cloth rests on its top face. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_sh.h"
#include "run_json.h"
#include "sb_bezier_ray.h"
#include "sb_context.h"
#include "sb_impulse.h"
#include "sb_run.h"
#include "sb_run_state.h"
#include "sb_solver.h"
#include "sb_surface.h"
#include "sb_test.h"

extern const sb_method_type sb_method_bhem;
extern const sb_param_def sb_solve_params[];

/* needles whose axis segment (foot to apex) meets the surface of x */
static int needles_through(const sb_scene *sc, const sb_method_type *mt, void *ms, int level, const double *x)
{
    sb_surface s;
    memset(&s, 0, sizeof s);
    if (mt->surface(ms, level, x, &s)) return -1;
    sb_bezier_ws *ws = sb_bezier_ws_new();
    int through = 0;
    for (int o = 0; o < sc->n_obstacles; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        if (ob->kind != SB_OBST_CAPSULE) continue;
        double d[3] = { ob->b[0] - ob->a[0], ob->b[1] - ob->a[1], ob->b[2] - ob->a[2] };
        const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + ob->radius;   /* to the apex */
        sb_ray r;
        sb_ray_init(&r, ob->a, d, 0.0, len);
        for (int e = 0; e < s.n_patches; e++) {
            sb_patch_hit h;
            if (sb_bezier_intersect(SB_ISECT_NEWTON, s.patch + (size_t)e * SB_BEZ_N, NULL, NULL, &r, len, 1e-9, ws, &h) == 1) {
                through++;
                break;
            }
        }
    }
    sb_bezier_ws_free(ws);
    sb_surface_free(&s);
    return through;
}

typedef struct outcome { int steps, converged, through_steps, first_through; sb_impulse_stats st; } outcome;

static void run_needles(sb_test_state *T, int respond, int res, int steps, outcome *out)
{
    memset(out, 0, sizeof *out);
    sb_context ctx;
    sb_scene sc;
    sb_context_init(&ctx);
    char path[1024], err[1024];
    snprintf(path, sizeof path, "%s/bench/bhem/scenes/needles_impulse.json", sb_test_root());
    CHECK_EQ_INT(sb_scene_load(path, &sc, err, sizeof err), 0);
    CHECK_EQ_INT(sc.contact.model, SB_CONTACT_IMPULSE);
    const sb_method_type *mt = &sb_method_bhem;
    const sb_solver_type *st = sb_solver_find("lsnewton");
    sb_paramset_add(&ctx.params, "run", sb_solve_params);
    if (st->params) sb_paramset_add(&ctx.params, "solver", st->params);
    sb_paramset_add(&ctx.params, "method", mt->params);
    void *ms = calloc(1, mt->state_size), *ss = calloc(1, st->state_size);
    sb_method_config cfg = { res, 1, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    int rc = mt->create(ms, &sc, &cfg);
    if (!rc) rc = sb_problem_create(&ctx, mt, ms, &sc, &p);
    if (!rc) rc = st->alloc(ss, p, &ctx.params);
    CHECK_MSG(rc == 0, "set-up: %s", ctx.err);
    if (rc) goto done;
    CHECK(!sb_problem_has_contact(p));   /* the impulse model builds no barrier */
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F);
    double *x = malloc(n * sizeof(double)), *xn = malloc(n * sizeof(double)), *v = calloc(n, sizeof(double));
    mt->initial(ms, F, x);
    for (int step = 1; step <= steps; step++) {
        sb_step_info si;
        sb_run_step_info(&sc, step, &si);
        sb_copy(n, x, xn);
        CHECK_EQ_INT(sb_problem_begin_step(p, &si, xn, v, x), 0);
        sb_step_outcome o;
        sb_reason reason = sb_solve_step_ex(st, ss, p, &ctx.params, step, x, &o);
        out->steps++;
        if (!sb_reason_converged(reason)) break;
        out->converged++;
        if (respond) CHECK_EQ_INT(mt->impulse_response(ms, &sc, sc.time.dt, si.t, xn, x, &out->st), 0);
        const int th = needles_through(&sc, mt, ms, F, x);
        CHECK(th >= 0);
        if (th > 0) {
            out->through_steps++;
            if (!out->first_through) out->first_through = step;
        }
        for (int i = 0; i < n; i++) v[i] = (x[i] - xn[i]) / sc.time.dt;
    }
    free(x); free(xn); free(v);
done:
    if (p) st->free(ss);
    sb_problem_free(p);
    mt->destroy(ms);
    free(ms); free(ss);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
}

SB_TEST(no_needle_through_the_cloth)
{
    outcome o;
    run_needles(T, 1, 4, 12, &o);
    printf("    response: %d/%d steps converged, %d steps with a needle through; impulses %ld, CCD tests %ld, "
           "hits %ld, passes %ld, unresolved %ld\n", o.converged, o.steps, o.through_steps, o.st.proximity_impulses,
           o.st.ccd_tests, o.st.ccd_hits, o.st.ccd_iterations, o.st.unresolved_steps);
    CHECK_EQ_INT(o.converged, 12);
    CHECK_EQ_INT(o.through_steps, 0);
    CHECK(o.st.ccd_hits > 0);
    CHECK(o.st.proximity_impulses > 0);
    CHECK(o.st.ccd_tests > o.st.ccd_hits);
    CHECK(o.st.ccd_iterations > 0);
    CHECK_EQ_INT(o.st.unresolved_steps, 0);
    CHECK_EQ_INT(o.st.impact_zones, 0);
}

SB_TEST(without_the_response_the_check_fails)
{
    outcome o;
    run_needles(T, 0, 4, 12, &o);
    printf("    no response: first step with a needle through: %d\n", o.first_through);
    CHECK(o.through_steps > 0);
    CHECK_EQ_INT(o.st.ccd_tests, 0);
}

SB_TEST(run_loop_reports_the_stats)
{
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/bench/bhem/scenes/needles_impulse.json", sb_test_root());
    sb_run_request rq;
    sb_test_request(&rq, scene, "bhem", "lsnewton", 4);
    int code = -1;
    json_t *o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 0);
    CHECK(o != NULL);
    if (!o) return;
    json_t *im = json_object_get(o, "contact");   /* the impulse counts live in the contact object */
    CHECK(im != NULL);
    CHECK(json_integer_value(json_object_get(im, "ccd_hits")) > 0);
    CHECK(json_integer_value(json_object_get(im, "proximity_impulses")) > 0);
    CHECK_EQ_INT(json_integer_value(json_object_get(im, "unresolved_steps")), 0);
    /* no barrier sample points: the contact object holds the impulse model's counts only */
    json_t *co = json_object_get(o, "contact");
    CHECK(co && json_object_get(co, "points") == NULL);
    CHECK(co && json_is_string(json_object_get(co, "model")) &&
          !strcmp(json_string_value(json_object_get(co, "model")), "impulse"));
    json_decref(o);
}

/* cloth_sphere (a cloth falling on a ball, friction 0.3) switched to the
 * impulse model: the cloth's sample points against the exact sphere
 * (sb_obstacle_toi).  After every response each sample point
 * (contact.samples per patch side) is outside the ball by at least half the
 * push-out, and the cloth's centre rests on top of the ball at the end. */
SB_TEST(cloth_points_against_a_sphere)
{
    sb_context ctx;
    sb_scene sc;
    sb_context_init(&ctx);
    char path[1024], err[1024];
    snprintf(path, sizeof path, "%s/bench/scenes/cloth_sphere.json", sb_test_root());
    CHECK_EQ_INT(sb_scene_load(path, &sc, err, sizeof err), 0);
    sc.contact.model = SB_CONTACT_IMPULSE;
    const sb_method_type *mt = &sb_method_bhem;
    const sb_solver_type *st = sb_solver_find("lsnewton");
    sb_paramset_add(&ctx.params, "run", sb_solve_params);
    if (st->params) sb_paramset_add(&ctx.params, "solver", st->params);
    sb_paramset_add(&ctx.params, "method", mt->params);
    void *ms = calloc(1, mt->state_size), *ss = calloc(1, st->state_size);
    sb_method_config cfg = { 4, 1, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    int rc = mt->create(ms, &sc, &cfg);
    if (!rc) rc = sb_problem_create(&ctx, mt, ms, &sc, &p);
    if (!rc) rc = st->alloc(ss, p, &ctx.params);
    CHECK_MSG(rc == 0, "set-up: %s", ctx.err);
    if (rc) goto done;
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F), ps = 4 * sc.contact.samples + 1, np = ps * ps;
    double *x = malloc(n * sizeof(double)), *xn = malloc(n * sizeof(double)), *v = calloc(n, sizeof(double));
    double *stp = malloc(2 * np * sizeof(double)), *pos = malloc(3 * np * sizeof(double));
    for (int j = 0; j < ps; j++)
        for (int i = 0; i < ps; i++) {
            stp[2 * (i + ps * j)] = (double)i / (ps - 1);
            stp[2 * (i + ps * j) + 1] = (double)j / (ps - 1);
        }
    const sb_obstacle_spec *ball = &sc.obstacles[0];
    sb_impulse_stats is;
    memset(&is, 0, sizeof is);
    mt->initial(ms, F, x);
    int converged = 0;
    double dmin = INFINITY;
    for (int step = 1; step <= 20; step++) {
        sb_step_info si;
        sb_run_step_info(&sc, step, &si);
        sb_copy(n, x, xn);
        CHECK_EQ_INT(sb_problem_begin_step(p, &si, xn, v, x), 0);
        sb_step_outcome o;
        if (!sb_reason_converged(sb_solve_step_ex(st, ss, p, &ctx.params, step, x, &o))) break;
        converged++;
        CHECK_EQ_INT(mt->impulse_response(ms, &sc, sc.time.dt, si.t, xn, x, &is), 0);
        CHECK_EQ_INT(mt->eval_points(ms, F, x, np, stp, pos), 0);
        for (int k = 0; k < np; k++) {
            const double *q = pos + 3 * k;
            const double d = sqrt((q[0] - ball->center[0]) * (q[0] - ball->center[0]) + (q[1] - ball->center[1]) * (q[1] - ball->center[1]) +
                                  (q[2] - ball->center[2]) * (q[2] - ball->center[2])) - ball->radius;
            dmin = fmin(dmin, d);
        }
        for (int i = 0; i < n; i++) v[i] = (x[i] - xn[i]) / sc.time.dt;
    }
    const double *c = pos + 3 * (np / 2);   /* the centre (s, t) = (1/2, 1/2) */
    printf("    cloth_sphere, impulse: %d/20 steps, smallest sample-point distance %.3g m, centre z %.4f m; "
           "impulses %ld, hits %ld, unresolved %ld\n", converged, dmin, c[2], is.proximity_impulses, is.ccd_hits,
           is.unresolved_steps);
    CHECK_EQ_INT(converged, 20);
    CHECK_MSG(dmin >= 0.5e-4, "a sample point %.3g m from the ball", dmin);
    CHECK(is.ccd_hits > 0);
    CHECK_EQ_INT(is.unresolved_steps, 0);
    CHECK_NEAR(c[2], ball->center[2] + ball->radius, 2e-3);   /* on top of the ball */
    free(x); free(xn); free(v); free(stp); free(pos);
done:
    if (p) st->free(ss);
    sb_problem_free(p);
    mt->destroy(ms);
    free(ms); free(ss);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
}

/* A mesh obstacle (a cube as an OBJ, top face 10 cm below the cloth) under
 * the impulse model, through the run loop: the cloth's points against the
 * triangles and the mesh's vertices against the patches; the cloth's centre
 * (a sample point over the top face) ends on the face, not through it. */
SB_TEST(cloth_on_a_mesh_box)
{
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/contact/cloth_mesh_impulse.json", sb_test_root());
    sb_run_request rq;
    sb_test_request(&rq, scene, "bhem", "lsnewton", 4);
    int code = -1;
    json_t *o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 0);
    CHECK(o != NULL);
    if (!o) return;
    json_t *im = json_object_get(o, "contact");
    CHECK(json_integer_value(json_object_get(im, "ccd_hits")) > 0);
    CHECK_EQ_INT(json_integer_value(json_object_get(im, "unresolved_steps")), 0);
    const double z = json_real_value(json_array_get(json_object_get(json_object_get(json_object_get(o, "probes"), "center"),
                                                                    "position"), 2));
    printf("    cloth on a mesh box: centre z %.5f m (top face at -0.1)\n", z);
    CHECK(z > -0.1 && z < -0.09);   /* on the face (free fall would end near -0.2) */
    json_decref(o);
}

/* bhem's response handles obstacles only: a scene asking for self-contact
 * under the impulse model is refused before any work, with a sentence */
SB_TEST(self_contact_under_the_impulse_model_is_refused)
{
    static char err[2048];
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s run --scene tests/scenes/contact/fold_ground.json --method bhem "
                       "--solver lsnewton --out none --quiet", sb_test_root(), sb_test_bin()), 2);
    CHECK(strstr(err, "self-contact") && strstr(err, "bhem"));
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = { SB_CASE(no_needle_through_the_cloth), SB_CASE(without_the_response_the_check_fails),
                                          SB_CASE(run_loop_reports_the_stats),
                                          SB_CASE(cloth_points_against_a_sphere),
                                          SB_CASE(cloth_on_a_mesh_box),
                                          SB_CASE(self_contact_under_the_impulse_model_is_refused), SB_END };
    return sb_test_main(argc, argv, cases);
}
