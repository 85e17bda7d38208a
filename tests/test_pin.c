/* test_pin.c — sliding pins (core/problem/sb_pin.c, docs/scene_format.md
 * "Sliding pins"):
 *  - the pin energy of bhem and linear_fem equals k/2 |x(st(f)) - p(f)|^2
 *    with st(f) on the segment and p(f) = X(st(f)) + f T, both evaluated
 *    by the method's eval_points (another code path than point_terms), at
 *    several motion factors; gradient and Hessian of Phi with the pins
 *    against central differences;
 *  - three sliding pins whose targets turn rigidly: the solved sheet is the
 *    rigidly turned sheet (a known minimizer, zero energy) to 1e-9 m;
 *  - rmtr and adaptive_sqrt3 refuse a sliding pin with a sentence. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sb_context.h"
#include "sb_method.h"
#include "sb_problem.h"
#include "sb_run.h"
#include "cli_sh.h"
#include "fd_check.h"
#include "run_json.h"
#include "sb_test.h"
#include "method_fixture.h"

extern const sb_method_type sb_method_bhem, sb_method_linear_fem;

static double rnd(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffff) / 65535.0 - 0.5;
}

typedef sb_method_fixture setup;

static int open_method(sb_test_state *T, setup *S, const char *file, const sb_method_type *mt)
{
    sb_method_fixture_init(S);
    char path[1024], err[1024];
    snprintf(path, sizeof path, "%s/tests/scenes/pin/%s", sb_test_root(), file);
    int rc = sb_scene_load(path, &S->sc, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    return rc ? -1 : sb_method_fixture_create(T, S, mt, 4);
}

static void close_method(setup *S) { sb_method_fixture_free(S); }

/* k/2 |x(st(f)) - p(f)|^2 over the held components of pin b, from eval_points;
 * |x(st(f)) - p(f)| in *dist */
static double pin_energy_expected(const setup *S, int b, double f, const double *x, const double *xref, double *dist)
{
    const sb_bc *bc = &S->sc.bcs[b];
    const double st[2] = { bc->parts[0].st[0] + f * (bc->slide_st[0] - bc->parts[0].st[0]),
                           bc->parts[0].st[1] + f * (bc->slide_st[1] - bc->parts[0].st[1]) };
    double xp[3], X[3], e = 0.0;
    S->mt->eval_points(S->ms, 0, x, 1, st, xp);
    S->mt->eval_points(S->ms, 0, xref, 1, st, X);
    for (int c = 0; c < 3; c++) {
        if (!(bc->components & (1u << c))) continue;
        const double r = xp[c] - (X[c] + f * bc->translation[c]);
        e += 0.5 * bc->slide_stiffness * r * r;
    }
    *dist = sqrt(2.0 * e / bc->slide_stiffness);
    return e;
}

SB_TEST(pin_energy_against_eval_points_and_fd)
{
    const sb_method_type *mts[] = { &sb_method_bhem, &sb_method_linear_fem };
    for (int m = 0; m < 2; m++) {
        setup S;
        if (open_method(T, &S, "slide.json", mts[m])) { close_method(&S); continue; }
        sb_problem *p = NULL;
        CHECK_EQ_INT(sb_problem_create(&S.ctx, S.mt, S.ms, &S.sc, &p), 0);
        if (!p) { close_method(&S); continue; }
        const int n = sb_problem_n(p, 0);
        double *xref = malloc(n * sizeof(double)), *x = malloc(n * sizeof(double)), *x0 = malloc(n * sizeof(double));
        double *v = calloc(n, sizeof(double)), *dir = malloc(n * sizeof(double));
        S.mt->initial(S.ms, 0, xref);
        unsigned seed = 7;
        const double fs[] = { 0.0, 0.3, 0.65, 1.0 };
        for (int k = 0; k < 4; k++) {
            sb_step_info si;
            memset(&si, 0, sizeof si);
            si.step = k + 1; si.n_steps = 4; si.t = k + 1;
            si.load_factor[0] = 1.0;
            si.motion_factor[0] = si.motion_factor[1] = fs[k];
            CHECK_EQ_INT(sb_problem_begin_step(p, &si, xref, v, x0), 0);
            for (int i = 0; i < n; i++) x[i] = x0[i] + 0.02 * rnd(&seed);
            /* Phi - E_method = E_pin (quasi-static: no inertia) */
            double phi = 0, em = 0;
            CHECK_EQ_INT(sb_problem_eval(p, 0, x, &phi, NULL, NULL), 0);
            CHECK_EQ_INT(S.mt->energy(S.ms, 0, x, &em, NULL, NULL), 0);
            double d0, d1;
            const double want = pin_energy_expected(&S, 0, fs[k], x, xref, &d0) +
                                pin_energy_expected(&S, 1, fs[k], x, xref, &d1);
            CHECK_MSG(want > 0 && fabs((phi - em) - want) <= 1e-9 * want, "%s f=%g: pin energy %.12g, expected %.12g",
                      S.mt->name, fs[k], phi - em, want);
            for (int i = 0; i < n; i++) dir[i] = rnd(&seed);
            sb_problem_constrain(p, 0, dir);
            fd_report r;
            fd_check_problem(p, 0, x, dir, 1e-6, &r);
            CHECK_MSG(r.best_grad < 1e-6 && r.best_hess < 1e-5, "%s f=%g: FD gradient %.3g, Hessian %.3g", S.mt->name,
                      fs[k], r.best_grad, r.best_hess);
            /* the violation the judge reads is |x(st(f)) - p(f)| of the worse pin */
            int np = 0;
            const double viol = sb_problem_pin_violation(p, x, &np);
            CHECK_EQ_INT(np, 2);
            CHECK_MSG(fabs(viol - fmax(d0, d1)) <= 1e-9 * fmax(d0, d1), "%s f=%g: violation %.12g, expected %.12g",
                      S.mt->name, fs[k], viol, fmax(d0, d1));
        }
        free(xref); free(x); free(x0); free(v); free(dir);
        sb_problem_free(p);
        close_method(&S);
    }
}

/* the sheet turned rigidly by 30 deg about z through (0.5, 0.5, 0) */
static void rigid(const double X[3], double y[3])
{
    const double th = 30.0 * M_PI / 180.0, dx = X[0] - 0.5, dy = X[1] - 0.5;
    y[0] = 0.5 + cos(th) * dx - sin(th) * dy;
    y[1] = 0.5 + sin(th) * dx + cos(th) * dy;
    y[2] = X[2];
}

SB_TEST(rigidly_turning_pins_turn_the_sheet)
{
    const char *methods[] = { "bhem", "linear_fem" };
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/pin/rotate.json", sb_test_root());
    for (int m = 0; m < 2; m++) {
        sb_run_request req;
        sb_test_request(&req, scene, methods[m], "lsnewton", 0);
        int code = -1;
        json_t *o = sb_test_run_json(&req, &code);
        CHECK_MSG(o && code == 0, "%s: exit %d", methods[m], code);
        if (!o) continue;
        CHECK(!strcmp(json_string_value(json_object_get(o, "status")), "converged"));
        const char *key;
        json_t *pr;
        int n = 0;
        json_object_foreach(json_object_get(o, "probes"), key, pr) {
            double pos[3], d[3], X[3], y[3];
            for (int c = 0; c < 3; c++) {
                pos[c] = json_real_value(json_array_get(json_object_get(pr, "position"), c));
                d[c] = json_real_value(json_array_get(json_object_get(pr, "displacement"), c));
                X[c] = pos[c] - d[c];
            }
            rigid(X, y);
            for (int c = 0; c < 3; c++)
                CHECK_MSG(fabs(pos[c] - y[c]) < 1e-9, "%s probe %s: x_%d = %.12g, rigid %.12g", methods[m], key, c,
                          pos[c], y[c]);
            n++;
        }
        CHECK_EQ_INT(n, 3);
        /* the pins count as penalty constraints in the judge */
        json_t *pen = json_object_get(o, "penalty");
        CHECK_MSG(json_is_object(pen) && json_real_value(json_object_get(pen, "position_max")) < 1e-9,
                  "%s: penalty report missing or violated", methods[m]);
        json_decref(o);
    }
}

SB_TEST(methods_without_point_terms_refuse_a_sliding_pin)
{
    const char *methods[] = { "rmtr", "adaptive_sqrt3" };
    const char *solvers[] = { "lsnewton", "linearized" };
    for (int m = 0; m < 2; m++) {
        char out[4096], err[4096];
        int rc = sb_sh(out, sizeof out, err, sizeof err,
                       "%s run --scene %s/tests/scenes/pin/slide.json --method %s --solver %s --out none --quiet",
                       sb_test_bin(), sb_test_root(), methods[m], solvers[m]);
        CHECK_MSG(rc == 2 && strstr(err, "slid") && strstr(err, "boundary"), "%s: exit %d, %s", methods[m], rc, err);
    }
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(pin_energy_against_eval_points_and_fd), SB_CASE(rigidly_turning_pins_turn_the_sheet),
        SB_CASE(methods_without_point_terms_refuse_a_sliding_pin), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
