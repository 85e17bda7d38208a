/* bench_supernodes.c — what bounds CHOLMOD's factorization rate on a
 * method's Hessian (issue 42's goal: at least half the one-core DGEMM rate
 * at >= 1e5 dofs).  Supernodal CHOLMOD spends its flops in dense kernels
 * (DPOTRF, DTRSM, DSYRK/DGEMM) on each supernode's panel; a 2-D mesh's
 * nested-dissection ordering gives many narrow supernodes, on which those
 * kernels run far below the large-matrix DGEMM rate.  This bench measures
 * that ceiling for one scene, method and resolution:
 *
 *   1. the method's Hessian at the scene's first step, from its initial
 *      state, analysed and factorized by the suite's own path
 *      (sb_problem_factor: the run's ordering and supernode settings);
 *   2. the supernodes binned by column count k (sb_linsolve_supernodes):
 *      count, columns, share of the dense flops, flop-weighted mean k and
 *      m (rows with the diagonal block);
 *   3. per bin, the rate of the same dense work on a panel of that mean
 *      shape, measured here (DPOTRF k, DTRSM (m-k) x k, DSYRK of the
 *      (m-k) x k block: what CHOLMOD's supernodal numeric factorization does
 *      per supernode, there split over the ancestors it updates and followed
 *      by a scatter-add, so this is an upper bound on its rate);
 *   4. the ceiling = total flops / sum over bins of (flops / rate): the
 *      rate CHOLMOD could reach if every supernode ran at the dense kernels'
 *      speed for its shape, beside the rate achieved here (CHOLMOD's flop
 *      count over the process CPU seconds of its numeric factorizations,
 *      best of REPS after the first; the first, in which CHOLMOD allocates
 *      and first touches the factor's values, is reported apart).
 *
 *   build/bench/bench_supernodes SCENE METHOD RES [KEY=VALUE ...] [reps=N] [panels=0]
 *
 * reps: factorizations timed after the first (best taken); panels=0: no
 * dense panel rates (when profiling the factorizations alone).
 *
 * Output: CSV, one row per non-empty bin, then "summary," rows (key,value).
 * Process CPU time throughout (one BLAS thread: OPENBLAS_NUM_THREADS=1),
 * so other processes on the machine change the figures little. */
#define _POSIX_C_SOURCE 200809L
#include "sb_context.h"
#include "sb_run_state.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <cholmod.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void dtrsm_(const char *side, const char *uplo, const char *ta, const char *diag, const int *m, const int *n,
            const double *alpha, const double *a, const int *lda, double *b, const int *ldb);
void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k, const double *alpha, const double *a,
            const int *lda, const double *beta, double *c, const int *ldc);

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* GFLOP/s of one supernode's dense work on an m x k panel (k >= 1, m >= k):
 * the panel is made SPD-friendly (diagonally dominant top block) and
 * refreshed from a saved copy before every repetition; repetitions until
 * 0.2 CPU seconds, best of 3 such rounds. */
static double panel_rate(int k, int m)
{
    const int r = m - k;
    double *P = malloc(sizeof(double) * (size_t)m * (size_t)k), *P0 = malloc(sizeof(double) * (size_t)m * (size_t)k);
    double *C = r > 0 ? malloc(sizeof(double) * (size_t)r * (size_t)r) : NULL;
    if (!P || !P0 || (r > 0 && !C)) {
        free(P); free(P0); free(C);
        return NAN;
    }
    unsigned s = 2463534242u;
    for (int j = 0; j < k; j++)
        for (int i = 0; i < m; i++) {
            s ^= s << 13, s ^= s >> 17, s ^= s << 5;
            P0[(size_t)j * m + i] = (double)(s >> 8) / 16777216.0 - 0.5 + (i == j ? (double)m : 0.0);
        }
    if (r > 0) memset(C, 0, sizeof(double) * (size_t)r * (size_t)r);
    const double fl = (double)k * k * k / 3.0 + (double)r * k * k + (double)r * r * k;
    const double one = 1.0, mone = -1.0;
    double best = 0.0;
    for (int round = 0; round < 3; round++) {
        long reps = 0;
        double t = 0.0;
        while (t < 0.2) {
            memcpy(P, P0, sizeof(double) * (size_t)m * (size_t)k);
            double t0 = cpu_now();
            int info = 0;
            dpotrf_("L", &k, P, &m, &info);
            if (r > 0) {
                dtrsm_("R", "L", "T", "N", &r, &k, &one, P, &m, P + k, &m);
                dsyrk_("L", "N", &r, &k, &mone, P + k, &m, &one, C, &r);
            }
            t += cpu_now() - t0;
            reps++;
        }
        const double g = fl * (double)reps / t / 1e9;
        if (g > best) best = g;
    }
    free(P); free(P0); free(C);
    return best;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: %s SCENE METHOD RES [KEY=VALUE ...] [reps=N] [panels=0]\n", argv[0]);
        return 2;
    }
    const sb_method_type *mt = sb_method_find(argv[2]);
    const sb_solver_type *st = sb_solver_find("lsnewton");
    const int res = atoi(argv[3]);
    if (!mt || res < 1) {
        fprintf(stderr, "bench_supernodes: unknown method %s or bad resolution %s\n", argv[2], argv[3]);
        return 2;
    }
    sb_context ctx;
    if (sb_context_init(&ctx)) return 3;
    sb_scene sc;
    char path[1024], err[2048] = "";
    if (sb_scene_resolve(argv[1], path, sizeof path) || sb_scene_load(path, &sc, err, sizeof err)) {
        fprintf(stderr, "bench_supernodes: cannot load scene %s%s%s\n", argv[1], err[0] ? ": " : "", err);
        return 2;
    }
    sb_paramset_add(&ctx.params, "run", sb_solve_params);
    sb_paramset_add(&ctx.params, "solver", st->params);
    sb_paramset_add(&ctx.params, "method", mt->params);
    int reps = 2, panels = 1;
    for (int a = 4; a < argc; a++) {
        if (!strncmp(argv[a], "reps=", 5)) {
            reps = atoi(argv[a] + 5);
            continue;
        }
        if (!strncmp(argv[a], "panels=", 7)) {
            panels = atoi(argv[a] + 7);
            continue;
        }
        if (sb_paramset_set(&ctx.params, argv[a], err, sizeof err)) {
            fprintf(stderr, "bench_supernodes: %s\n", err);
            return 2;
        }
    }
    if (reps < 1) reps = 1;
    void *ms = calloc(1, mt->state_size);
    sb_method_config cfg = { res, 1, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    if (!ms || mt->create(ms, &sc, &cfg) || sb_problem_create(&ctx, mt, ms, &sc, &p)) {
        fprintf(stderr, "bench_supernodes: set-up failed: %s\n", ctx.err);
        return 3;
    }
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F);
    double *x = malloc(sizeof(double) * n), *x0 = malloc(sizeof(double) * n), *v0 = calloc(n, sizeof(double));
    double *g = malloc(sizeof(double) * n), *d = malloc(sizeof(double) * n);
    if (!x || !x0 || !v0 || !g || !d) return 3;
    mt->initial(ms, F, x);
    sb_step_info si;
    sb_run_step_info(&sc, 1, &si);   /* the scene's first step, as a run makes it */
    sb_problem_begin_step(p, &si, x, v0, x0);
    double f;
    if (sb_problem_eval(p, F, x0, &f, g, sb_problem_hessian(p, F))) {
        fprintf(stderr, "bench_supernodes: the Hessian at the start is not finite\n");
        return 3;
    }
    /* the numeric work is the same for any shift that makes H positive
     * definite: the smallest of 0, 1e-8, 1e-6 ... times the largest diagonal */
    sb_problem_hess_diag(p, F, d);
    double dmax = 0.0;
    for (int i = 0; i < n; i++) dmax = fmax(dmax, fabs(d[i]));
    double shift = 0.0, c_first = ctx.stats.chol_factorize_cpu[F];
    int rc = sb_problem_factor(p, F, shift);
    for (double e = 1e-8; rc == SB_NOT_POSDEF && e < 1.0; e *= 100.0) {
        c_first = ctx.stats.chol_factorize_cpu[F];
        rc = sb_problem_factor(p, F, shift = e * dmax);
    }
    /* the first successful factorization: CHOLMOD allocates and first
     * touches the factor's values in it (page faults are process CPU time) */
    c_first = ctx.stats.chol_factorize_cpu[F] - c_first;
    if (rc != SB_OK) {
        fprintf(stderr, "bench_supernodes: no positive definite shift found (%s)\n", ctx.err);
        return 3;
    }
    /* the repeats: CPU seconds, and the kernel's share of them (the page
     * faults of CHOLMOD's per-call temporaries: the permuted copy of A and
     * the update workspace are allocated and freed in every call) */
    double best = INFINITY, best_sys = 0.0;
    for (int k = 0; k < reps; k++) {
        struct rusage u0, u1;
        getrusage(RUSAGE_SELF, &u0);
        double c0 = ctx.stats.chol_factorize_cpu[F];
        if (sb_problem_factor(p, F, shift) != SB_OK) return 3;
        getrusage(RUSAGE_SELF, &u1);
        const double c = ctx.stats.chol_factorize_cpu[F] - c0;
        if (c < best) {
            best = c;
            best_sys = (double)(u1.ru_stime.tv_sec - u0.ru_stime.tv_sec) +
                       1e-6 * (double)(u1.ru_stime.tv_usec - u0.ru_stime.tv_usec);
        }
    }
    sb_supernode_bins b;
    if (sb_linsolve_supernodes(sb_problem_linsolve(p, F), &b)) {
        fprintf(stderr, "bench_supernodes: the factor is not supernodal\n");
        return 3;
    }
    const double cm_flops = ctx.stats.chol_flops[F];
    const cholmod_common *cm = ctx.cholmod;   /* the ordering CHOLMOD chose */
    printf("k_lo,k_hi,supernodes,columns,flops_share,mean_k,mean_m,dense_gflops\n");
    double t_model = 0.0, narrow = 0.0;
    for (int i = 0; i < SB_SN_BINS; i++) {
        if (b.supernodes[i] == 0) continue;
        int k = (int)lround(b.mean_k[i]), m = (int)lround(b.mean_m[i]);
        if (k < 1) k = 1;
        if (m < k) m = k;
        double r = b.flops[i] > 0 && panels ? panel_rate(k, m) : NAN;
        if (b.flops[i] > 0 && r > 0) t_model += b.flops[i] / (r * 1e9);
        if (i < 5) narrow += b.flops[i];
        printf("%ld,%ld,%ld,%ld,%.6f,%.1f,%.1f,%.2f\n", 1L << i, i == SB_SN_BINS - 1 ? -1L : (2L << i) - 1,
               b.supernodes[i], b.columns[i], b.flops[i] / b.flops_total, b.mean_k[i], b.mean_m[i], r);
    }
    const double ceiling = b.flops_total / t_model / 1e9, achieved = cm_flops / best / 1e9;
    printf("summary,scene,%s\nsummary,method,%s\nsummary,res,%d\nsummary,dofs,%d\n", argv[1], argv[2], res, n);
    printf("summary,supernodes_setting,%s\n",
           sb_param_int_or(&ctx.params, "run.supernodes", SB_SUPERNODES_CHOLMOD) == SB_SUPERNODES_WIDE ? "wide" : "cholmod");
    printf("summary,supernodes,%ld\nsummary,nnz_l,%.0f\nsummary,cholmod_flops,%.6g\nsummary,panel_flops,%.6g\n",
           b.n_super, ctx.stats.chol_nnz_l[F], cm_flops, b.flops_total);
    printf("summary,flops_share_k_below_32,%.4f\n", narrow / b.flops_total);
    printf("summary,ordering,%s\n", cm->method[cm->selected].ordering == CHOLMOD_AMD ? "amd" :
           cm->method[cm->selected].ordering == CHOLMOD_METIS ? "metis" :
           cm->method[cm->selected].ordering == CHOLMOD_NESDIS ? "nesdis" :
           cm->method[cm->selected].ordering == CHOLMOD_COLAMD ? "colamd" :
           cm->method[cm->selected].ordering == CHOLMOD_NATURAL ? "natural" : "given");
    printf("summary,factorize_cpu_s,%.4f\nsummary,achieved_gflops,%.3f\nsummary,ceiling_gflops,%.3f\n"
           "summary,achieved_over_ceiling,%.3f\nsummary,shift,%g\n", best, achieved, ceiling, achieved / ceiling, shift);
    printf("summary,first_factorize_cpu_s,%.4f\nsummary,first_gflops,%.3f\n", c_first, cm_flops / c_first / 1e9);
    printf("summary,factorize_system_s,%.4f\n", best_sys);
    free(x); free(x0); free(v0); free(g); free(d);
    sb_problem_free(p);
    mt->destroy(ms);
    free(ms);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
    return 0;
}
