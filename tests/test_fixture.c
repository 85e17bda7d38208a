/* test_fixture.c — the membrane test fixture: finite-difference checks of the
 * whole incremental potential (elastic + gravity + inertia + Rayleigh damping,
 * with Dirichlet elimination), and identity/adjoint checks of its transfers. */
#include "sb_test.h"
#include "fd_check.h"
#include "sb_context.h"
#include "sb_scene.h"

#include <stdlib.h>
#include <string.h>

extern const sb_method_type sb_fixture_membrane;

typedef struct setup {
    sb_context ctx;
    sb_scene scene;
    void *ms;
    sb_problem *p;
    double *x, *v;
} setup;

static int make(setup *S, const char *scene, int res, int levels)
{
    memset(S, 0, sizeof *S);
    char path[1024], err[1024];
    snprintf(path, sizeof path, "%s/tests/scenes/%s", sb_test_root(), scene);
    if (sb_context_init(&S->ctx) || sb_scene_load(path, &S->scene, err, sizeof err)) {
        printf("setup: %s\n", err);
        return -1;
    }
    S->ms = calloc(1, sb_fixture_membrane.state_size);
    sb_method_config cfg = { res, levels, &S->ctx.params, &S->ctx, 0 };
    if (sb_fixture_membrane.create(S->ms, &S->scene, &cfg)) return -1;
    if (sb_problem_create(&S->ctx, &sb_fixture_membrane, S->ms, &S->scene, &S->p)) return -1;
    int n = sb_problem_n(S->p, levels - 1);
    S->x = malloc(n * sizeof(double));
    S->v = calloc(n, sizeof(double));
    sb_fixture_membrane.initial(S->ms, levels - 1, S->x);
    return 0;
}

static void destroy(setup *S)
{
    sb_problem_free(S->p);
    sb_fixture_membrane.destroy(S->ms);
    free(S->ms);
    free(S->x);
    free(S->v);
    sb_scene_free(&S->scene);
    sb_context_free(&S->ctx);
}

static double rnd(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return ((*s >> 8) / 16777216.0) - 0.5;
}

SB_TEST(fd_dynamic_with_damping)
{
    setup S;
    CHECK(make(&S, "membrane_dynamic.json", 6, 1) == 0);
    int n = sb_problem_n(S.p, 0);
    unsigned seed = 7;
    for (int i = 0; i < n; i++) S.v[i] = 0.1 * rnd(&seed);
    /* step 1: sets xhat, the lagged damping matrix and constrained values */
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1; si.n_steps = 3; si.dt = 0.1; si.t = 0.1;
    si.load_factor[0] = 1.0;
    double *x0 = malloc(n * sizeof(double)), *xs = malloc(n * sizeof(double)), *dir = malloc(n * sizeof(double));
    for (int i = 0; i < n; i++) xs[i] = S.x[i] + 0.02 * rnd(&seed);   /* a deformed x_n */
    CHECK_EQ_INT(sb_problem_begin_step(S.p, &si, xs, S.v, x0), 0);
    for (int trial = 0; trial < 3; trial++) {
        double *x = malloc(n * sizeof(double));
        for (int i = 0; i < n; i++) { x[i] = x0[i] + 0.05 * rnd(&seed); dir[i] = rnd(&seed); }
        sb_problem_impose(S.p, 0, x);
        sb_problem_constrain(S.p, 0, dir);
        fd_report r;
        fd_check_problem(S.p, 0, x, dir, 1e-3, &r);
        printf("  grad %.3g %.3g %.3g %.3g  hess %.3g %.3g %.3g %.3g\n", r.grad_err[0], r.grad_err[1], r.grad_err[2], r.grad_err[3], r.hess_err[0], r.hess_err[1], r.hess_err[2], r.hess_err[3]);
        CHECK_MSG(r.best_grad < 1e-6, "gradient FD error %.3g", r.best_grad);
        CHECK_MSG(r.grad_err[1] < r.grad_err[0] / 8 || r.grad_err[0] < 1e-9, "gradient FD errors %.3g %.3g", r.grad_err[0], r.grad_err[1]);
        CHECK_MSG(r.best_hess < 1e-6, "Hessian FD error %.3g", r.best_hess);
        /* second-order convergence: error falls ~16x per 4x smaller step at first */
        CHECK_MSG(r.hess_err[1] < r.hess_err[0] / 8 || r.hess_err[0] < 1e-9, "Hessian FD errors %.3g %.3g", r.hess_err[0], r.hess_err[1]);
        free(x);
    }
    free(x0); free(xs); free(dir);
    destroy(&S);
}

SB_TEST(transfers_identity_and_adjoint)
{
    setup S;
    CHECK(make(&S, "membrane_dynamic.json", 8, 3) == 0);
    unsigned seed = 99;
    for (int lc = 0; lc < 2; lc++) {
        int nc = sb_problem_n(S.p, lc), nf = sb_problem_n(S.p, lc + 1);
        double *xc = malloc(nc * sizeof(double)), *xf = malloc(nf * sizeof(double));
        double *yf = malloc(nf * sizeof(double)), *yc = malloc(nc * sizeof(double)), *back = malloc(nc * sizeof(double));
        for (int i = 0; i < nc; i++) xc[i] = rnd(&seed);
        for (int i = 0; i < nf; i++) yf[i] = rnd(&seed);
        /* P I = id (method ops, without the core's constraint handling) */
        CHECK_EQ_INT(sb_fixture_membrane.prolong(S.ms, lc, xc, xf), 0);
        CHECK_EQ_INT(sb_fixture_membrane.project(S.ms, lc, xf, back), 0);
        double e = 0;
        for (int i = 0; i < nc; i++) e = fmax(e, fabs(back[i] - xc[i]));
        CHECK(e < 1e-15);
        /* <I xc, yf> = <xc, R yf> */
        CHECK_EQ_INT(sb_fixture_membrane.restrict_adj(S.ms, lc, yf, yc), 0);
        CHECK_NEAR(sb_dot(nf, xf, yf), sb_dot(nc, xc, yc), 1e-12 * (1 + fabs(sb_dot(nf, xf, yf))));
        /* I reproduces the reference (bilinear) geometry of a plane exactly */
        double *Xc = malloc(nc * sizeof(double)), *Xf = malloc(nf * sizeof(double));
        sb_fixture_membrane.initial(S.ms, lc, Xc);
        sb_fixture_membrane.initial(S.ms, lc + 1, Xf);
        sb_fixture_membrane.prolong(S.ms, lc, Xc, xf);
        e = 0;
        for (int i = 0; i < nf; i++) e = fmax(e, fabs(xf[i] - Xf[i]));
        CHECK(e < 1e-14);
        free(xc); free(xf); free(yf); free(yc); free(back); free(Xc); free(Xf);
    }
    destroy(&S);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(fd_dynamic_with_damping), SB_CASE(transfers_identity_and_adjoint), SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
