/* bench_cond.c — condition number of the Hessian against dofs (RMTR paper
 * Fig. 9 left): trampoline, subdivision method, dt = 1, the Hessian of the
 * incremental potential at the converged first step.  lambda_max by power
 * iteration on H, lambda_min by inverse power iteration with the CHOLMOD
 * factor (H is positive definite at a minimizer; a failed factorization is
 * reported as indefinite).
 *
 *   bench_cond [SCENE] [MAX_RES]          cond against dofs (default trampoline, 32)
 *   bench_cond SCENE RES sigma            cond against the penalty exponent
 *                                         sigma = 3..7 at one resolution (Fig. 9 right) */
#include "sb_context.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double rayleigh_power(sb_problem *p, int F, int n, int inverse, int iters, double *v, double *w)
{
    double lam = 0;
    for (int i = 0; i < n; i++) v[i] = 1.0 + 0.1 * sin(1.7 * i);   /* deterministic start */
    sb_scal(n, 1.0 / sb_norm2(n, v), v);
    for (int k = 0; k < iters; k++) {
        if (inverse) {
            if (sb_problem_solve(p, F, v, w) != SB_OK) return NAN;
        } else {
            sb_problem_hess_mult(p, F, v, w);
        }
        double nw = sb_norm2(n, w);
        if (!(nw > 0)) return NAN;
        lam = sb_dot(n, v, w);                          /* Rayleigh quotient of H or H^{-1} */
        sb_copy(n, w, v);
        sb_scal(n, 1.0 / nw, v);
    }
    return inverse ? 1.0 / lam : lam;
}

/* cond(H) of SCENE at resolution res and penalty exponent sigma; 0 or an exit code */
static int measure(const char *scene_name, int res, double sigma, int *n_out, double *lmin_out, double *lmax_out,
                   int *conv)
{
    sb_context ctx;
    sb_context_init(&ctx);
    sb_scene sc;
    char path[1024], err[2048];
    if (sb_scene_resolve(scene_name, path, sizeof path) || sb_scene_load(path, &sc, err, sizeof err)) {
        fprintf(stderr, "bench_cond: cannot load scene %s\n", scene_name);
        return 2;
    }
    const sb_method_type *mt = sb_method_find("rmtr");
    const sb_solver_type *st = sb_solver_find("lsnewton");
    sb_paramset_add(&ctx.params, "run", sb_solve_params);
    sb_paramset_add(&ctx.params, "solver", st->params);
    sb_paramset_add(&ctx.params, "method", mt->params);
    char set[64], perr[256];
    snprintf(set, sizeof set, "method.sigma=%g", sigma);
    /* the stopping rule results/rmtr/cond*.md were computed with (docs/trust.md) */
    if (sb_paramset_set(&ctx.params, "run.stop=paper", perr, sizeof perr) ||
        sb_paramset_set(&ctx.params, set, perr, sizeof perr)) {
        fprintf(stderr, "bench_cond: %s\n", perr);
        return 2;
    }
    void *ms = calloc(1, mt->state_size), *ss = calloc(1, st->state_size);
    sb_method_config cfg = { res, 1, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    if (mt->create(ms, &sc, &cfg) || sb_problem_create(&ctx, mt, ms, &sc, &p) || st->alloc(ss, p, &ctx.params)) {
        fprintf(stderr, "bench_cond: set-up failed: %s\n", ctx.err);
        return 3;
    }
    int n = sb_problem_n(p, 0);
    double *x = malloc(n * sizeof(double)), *x0 = malloc(n * sizeof(double)), *v0 = calloc(n, sizeof(double));
    double *v = malloc(n * sizeof(double)), *w = malloc(n * sizeof(double)), *g = malloc(n * sizeof(double));
    mt->initial(ms, 0, x);
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1; si.n_steps = sc.time.steps; si.dt = sc.time.dt; si.t = sc.time.dt;
    for (int i = 0; i < sc.n_loads; i++) si.load_factor[i] = sb_load_factor(&sc, &sc.loads[i], 1);
    for (int i = 0; i < sc.n_bcs; i++) si.motion_factor[i] = sb_bc_motion_factor(&sc, &sc.bcs[i], 1);
    sb_problem_begin_step(p, &si, x, v0, x0);
    int it; double f, gn;
    sb_reason why = sb_solve_step(st, ss, p, &ctx.params, 1, x0, &it, &f, &gn);
    sb_problem_eval(p, 0, x0, &f, g, sb_problem_hessian(p, 0));
    double lmax = rayleigh_power(p, 0, n, 0, 300, v, w), lmin = NAN;
    if (sb_problem_factor(p, 0, 0.0) == SB_OK) lmin = rayleigh_power(p, 0, n, 1, 100, v, w);
    *lmin_out = lmin; *lmax_out = lmax; *n_out = n; *conv = sb_reason_converged(why);
    fflush(stdout);
    free(x); free(x0); free(v0); free(v); free(w); free(g);
    st->free(ss);
    free(ss);
    sb_problem_free(p);
    mt->destroy(ms);
    free(ms);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
    return 0;
}

int main(int argc, char **argv)
{
    const char *scene_name = argc > 1 ? argv[1] : "trampoline";
    int max_res = argc > 2 ? atoi(argv[2]) : 32;
    int n, conv, rc;
    double lmin, lmax;
    if (argc > 3 && !strcmp(argv[3], "sigma")) {
        printf("| sigma | dofs | lambda_min | lambda_max | cond(H) |\n|--:|--:|--:|--:|--:|\n");
        for (int k = 3; k <= 7; k++) {
            if ((rc = measure(scene_name, max_res, k, &n, &lmin, &lmax, &conv))) return rc;
            printf("| %d | %d | %.3g | %.3g | %.2g%s |\n", k, n, lmin, lmax, lmax / lmin, conv ? "" : " (step not converged)");
            fflush(stdout);
        }
        return 0;
    }
    static const double paper[] = { 1e8, 1e9, 1e10, 1e11, 1e12, 1e13 };
    printf("| dofs | lambda_min | lambda_max | cond(H) | paper (Fig. 9) |\n|--:|--:|--:|--:|--:|\n");
    for (int res = 4, k = 0; res <= max_res; res *= 2, k++) {
        if ((rc = measure(scene_name, res, 5.0, &n, &lmin, &lmax, &conv))) return rc;
        printf("| %d | %.3g | %.3g | %.2g%s | %.0e |\n", n, lmin, lmax, lmax / lmin,
               conv ? "" : " (step not converged)", k < 6 ? paper[k] : NAN);
        fflush(stdout);
    }
    return 0;
}
