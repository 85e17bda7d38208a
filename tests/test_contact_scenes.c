/* test_contact_scenes.c — the intersection-free guarantee (docs/contact.md):
 * on every bundled contact scene (bench/scenes with "obstacles"), with every
 * method and every potential solver (lsnewton, tr, damped, rmtr on two
 * levels, linearized), no contact sample point is inside an obstacle after
 * any accepted iteration of any step.  The solvers are driven directly
 * (set / iterate) so that every iterate is checked, at a low resolution and
 * over the first steps of each scene (the cloth reaches the obstacles
 * within them; damped, capped at 15 iterations a step, may lag behind). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sb_context.h"
#include "sb_run.h"
#include "sb_run_state.h"
#include "sb_solver.h"
#include "sb_test.h"
#include "run_json.h"

extern const sb_method_type sb_method_bhem, sb_method_subdiv, sb_method_linear_fem;
extern const sb_param_def sb_solve_params[];

typedef struct result { int iterations, accepted, inside, nonfinite; double dmin, min_step; } result;

static void run_case(sb_test_state *T, const char *scene, const sb_method_type *mt, const char *solver, int res,
                     int levels, int steps, result *out)
{
    memset(out, 0, sizeof *out);
    out->dmin = INFINITY;
    out->min_step = INFINITY;
    sb_context ctx;
    sb_scene sc;
    sb_context_init(&ctx);
    char path[1024], err[1024];
    snprintf(path, sizeof path, "%s/bench/scenes/%s.json", sb_test_root(), scene);
    CHECK_EQ_INT(sb_scene_load(path, &sc, err, sizeof err), 0);
    const sb_solver_type *st = sb_solver_find(solver);
    CHECK(st != NULL);
    sb_paramset_add(&ctx.params, "run", sb_solve_params);
    if (st->params) sb_paramset_add(&ctx.params, "solver", st->params);
    if (mt->params) sb_paramset_add(&ctx.params, "method", mt->params);
    void *ms = calloc(1, mt->state_size), *ss = calloc(1, st->state_size);
    sb_method_config cfg = { res, levels, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    int rc = mt->create(ms, &sc, &cfg);
    CHECK_MSG(rc == 0, "%s/%s: %s", scene, mt->name, ctx.err);
    if (!rc) rc = sb_problem_create(&ctx, mt, ms, &sc, &p);
    if (!rc) rc = st->alloc(ss, p, &ctx.params);
    CHECK_MSG(rc == 0, "%s/%s/%s: %s", scene, mt->name, solver, ctx.err);
    if (rc) goto done;
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F);
    double *x = malloc(n * sizeof(double)), *xn = malloc(n * sizeof(double)), *v = calloc(n, sizeof(double));
    mt->initial(ms, F, x);
    for (int step = 1; step <= steps; step++) {
        sb_step_info si;
        sb_run_step_info(&sc, step, &si);
        sb_copy(n, x, xn);
        CHECK_EQ_INT(sb_problem_begin_step(p, &si, xn, v, x), 0);
        sb_iterate_info info;
        memset(&info, 0, sizeof info);
        rc = st->set(ss, p, x, &info);
        if (rc == SB_NONFINITE) { out->nonfinite++; break; }
        const double g0 = info.gnorm;
        const int maxit = (st->flags & SB_SOLVER_SINGLE_STEP) ? 1 : strcmp(solver, "damped") == 0 ? 15 : 40;
        for (int it = 0; it < maxit; it++) {
            memset(&info, 0, sizeof info);
            rc = st->iterate(ss, p, x, &info);
            CHECK_MSG(rc >= 0, "%s/%s/%s step %d: %s", scene, mt->name, solver, step, ctx.err);
            if (rc < 0) break;
            out->iterations++;
            out->accepted += info.accepted;
            if (st->flags & SB_SOLVER_SINGLE_STEP) out->min_step = fmin(out->min_step, info.rho);
            double dmin;
            int act, ins;
            sb_problem_contact_measure(p, x, &dmin, &act, &ins);
            out->inside += ins;
            out->dmin = fmin(out->dmin, dmin);
            if (info.fail == SB_REASON_NONFINITE) out->nonfinite++;
            if (info.fail || info.gnorm <= 1e-9 * g0) break;
        }
        for (int i = 0; i < n; i++) v[i] = (x[i] - xn[i]) / sc.time.dt;
    }
    free(x); free(xn); free(v);
done:
    if (st && p) st->free(ss);
    sb_problem_free(p);
    if (!rc || p) mt->destroy(ms);
    free(ms); free(ss);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
}

SB_TEST(no_sample_point_inside_after_any_iteration)
{
    static const char *const scenes[] = { "cloth_sphere", "drape_box", "needles" };
    static const int steps[] = { 14, 12, 8 };
    /* needles at the scene's resolution: coarser sample points pass between the needles (docs/contact.md) */
    static const int res[] = { 4, 4, 8 };
    const sb_method_type *mts[] = { &sb_method_bhem, &sb_method_subdiv, &sb_method_linear_fem };
    static const char *const solvers[] = { "lsnewton", "tr", "damped", "linearized", "rmtr" };
    for (int s = 0; s < 3; s++)
        for (int m = 0; m < 3; m++)
            for (int k = 0; k < 5; k++) {
                const int rmtr = strcmp(solvers[k], "rmtr") == 0;
                result r;
                run_case(T, scenes[s], mts[m], solvers[k], res[s], rmtr ? 2 : 1, steps[s], &r);
                printf("    %-12s %-10s %-10s %4d iterations, %4d accepted, min distance %.3g m, inside %d%s\n",
                       scenes[s], mts[m]->name, solvers[k], r.iterations, r.accepted, r.dmin, r.inside,
                       r.nonfinite ? " (nonfinite recorded)" : "");
                CHECK_MSG(r.inside == 0, "%s/%s/%s: %d sample points inside after accepted iterations", scenes[s],
                          mts[m]->name, solvers[k], r.inside);
                CHECK(r.accepted > 0);
                /* linearized: one Newton step on Phi (barrier gradient and Hessian
                 * included) from x_n, shortened by the step filter where it would
                 * carry a point into an obstacle (docs/contact.md) */
                if (strcmp(solvers[k], "linearized") == 0)
                    CHECK_MSG(r.min_step < 1.0, "%s/%s/linearized: the filter never shortened a step", scenes[s],
                              mts[m]->name);
                /* the cloth reaches the obstacle within these steps */
                if (strcmp(solvers[k], "damped") != 0) CHECK_MSG(r.dmin < 0.005, "%s/%s/%s: min distance %g", scenes[s],
                                                                  mts[m]->name, solvers[k], r.dmin);
            }
}

/* adaptive_sqrt3 changes its mesh every 5th step, and with it the sample
 * points (docs/contact.md "Adaptive meshes"): through the run itself
 * (sb_run_execute, the `shellbench run` path), where the linearized solver's
 * one accepted iteration per step ends every step and each step end is
 * measured (contact.inside, contact.steps_inside), and a point the new
 * surface put inside an obstacle would start the next step at infinite
 * energy (a recorded `nonfinite`, not converged).  At res 4 the coarse
 * mesh's refinement puts points inside the sphere and the box
 * (contact.separated > 0): the separation is exercised, not assumed. */
SB_TEST(adaptive_sqrt3_no_sample_point_inside)
{
    static const char *const scenes[] = { "cloth_sphere", "drape_box", "needles" };
    static const int res[] = { 4, 4, 8 }, steps[] = { 30, 30, 25 };
    static const char *const sets[] = { "run.single_step_rtol=1e300" };
    long separated_total = 0;
    for (int s = 0; s < 3; s++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/bench/scenes/%s.json", sb_test_root(), scenes[s]);
        sb_run_request rq;
        memset(&rq, 0, sizeof rq);
        rq.scene = path;
        rq.method = "adaptive_sqrt3";
        rq.solver = "linearized";
        rq.res = res[s];
        rq.out = "none";
        rq.quiet = 1;
        rq.n_sets = 1;
        rq.sets = sets;
        int code = -1;
        json_t *o = sb_test_run_json(&rq, &code);
        CHECK_MSG(code == 0 && o, "%s/adaptive_sqrt3: exit %d", scenes[s], code);
        if (!o) continue;
        json_t *c = json_object_get(o, "contact");
        const long inside = (long)json_integer_value(json_object_get(c, "inside"));
        const long steps_inside = (long)json_integer_value(json_object_get(c, "steps_inside"));
        const long sep = (long)json_integer_value(json_object_get(c, "separated"));
        const long adapt = (long)json_integer_value(json_object_get(json_object_get(o, "counts"), "adapt"));
        const double dmin = json_number_value(json_object_get(c, "min_distance"));
        printf("    %-12s adaptive_sqrt3 linearized res %d: %ld steps, %ld adaptations, %ld pushes out, "
               "min distance %.3g m, inside %ld\n", scenes[s], res[s],
               (long)json_integer_value(json_object_get(o, "steps")), adapt, sep, dmin, inside);
        CHECK_EQ_INT(json_integer_value(json_object_get(o, "steps")), steps[s]);
        CHECK_EQ_INT(inside, 0);
        CHECK_EQ_INT(steps_inside, 0);
        CHECK(dmin > 0);
        CHECK(adapt >= 4);
        if (s < 2) CHECK_MSG(dmin < 0.005, "%s: the cloth never reached the obstacle (min distance %g)", scenes[s], dmin);
        separated_total += sep;
        json_decref(o);
    }
    CHECK_MSG(separated_total > 0, "no adaptation put a point inside: the separation was not exercised");
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = { SB_CASE(no_sample_point_inside_after_any_iteration),
                                          SB_CASE(adaptive_sqrt3_no_sample_point_inside), SB_END };
    return sb_test_main(argc, argv, cases);
}
