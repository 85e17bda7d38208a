/* bench_assembly.c — the cost of one assembly (energy, gradient and Hessian)
 * per degree of freedom for the rmtr and bhem methods at about 6,000 and
 * 25,000 dofs, beside the cost of one sparse Cholesky factorization of the
 * same matrix (CHOLMOD, symbolic analysis once): the reference kernel
 * (method.kernel=reference, per point) and the fast one, on 1, 2 and 3
 * threads (run.threads), all in this one run, so the ratios compare like
 * with like on a machine whatever else it runs (issue 30).
 *
 * Times: the fastest of several repetitions (wall clock), so that a
 * neighbour's burst of load inflates no figure; the load average is printed.
 *
 * usage: bench_assembly [scene.json] [quick]   (default bench/scenes/drape.json) */
#include "sb_context.h"
#include "sb_linsolve.h"
#include "sb_method.h"
#include "sb_solver.h"
#include "sb_sparse.h"
#include "sb_stats.h"
#include "sb_sysinfo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const sb_method_type *sb_method_find(const char *name);

typedef struct bcase {
    sb_scene sc;
    sb_paramset ps;
    const sb_method_type *mt;
    void *S;
    sb_pattern *pat;
    int n;
    double *x, *g;
    sb_matrix H;
} bcase;

static int open_case(bcase *c, const char *scene, const char *method, int res, const char *kernel, int threads)
{
    char err[1024], set[64];
    memset(c, 0, sizeof *c);
    if (sb_scene_load(scene, &c->sc, err, sizeof err)) {
        fprintf(stderr, "bench_assembly: %s\n", err);
        return -1;
    }
    c->mt = sb_method_find(method);
    sb_paramset_init(&c->ps);
    sb_paramset_add(&c->ps, "method", c->mt->params);
    sb_paramset_add(&c->ps, "run", sb_solve_params);
    snprintf(set, sizeof set, "method.kernel=%s", kernel);
    sb_paramset_set(&c->ps, set, err, sizeof err);
    snprintf(set, sizeof set, "run.threads=%d", threads);
    if (sb_paramset_set(&c->ps, set, err, sizeof err)) return -1;
    c->S = calloc(1, c->mt->state_size);
    sb_method_config cfg = { res, 1, &c->ps, NULL };
    if (c->mt->create(c->S, &c->sc, &cfg)) {
        free(c->S);
        c->S = NULL;
        return -1;
    }
    c->n = c->mt->n_dofs(c->S, 0);
    const int bs = c->mt->block_size(c->S, 0);
    sb_pattern_builder *pb = sb_pattern_builder_new(c->n / bs, bs);
    c->mt->pattern(c->S, 0, pb);
    if (sb_pattern_builder_finish(pb, &c->pat)) return -1;
    sb_matrix_init(&c->H, c->pat);
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = si.n_steps = 1;
    si.t = 1;
    for (int i = 0; i < SB_SCENE_MAX_LOADS; i++) si.load_factor[i] = 1;
    for (int i = 0; i < SB_SCENE_MAX_BCS; i++) si.motion_factor[i] = 1;
    c->mt->set_step(c->S, &si);
    c->x = malloc(sizeof(double) * c->n);
    c->g = malloc(sizeof(double) * c->n);
    c->mt->initial(c->S, 0, c->x);
    /* a deformed state: a smooth sag (the energy's every term is active) */
    for (int i = 2; i < c->n; i += 3) c->x[i] += 1e-3 * sin(0.37 * i);
    return 0;
}

static void close_case(bcase *c)
{
    if (c->S) {
        c->mt->destroy(c->S);
        free(c->S);
    }
    sb_matrix_free(&c->H);
    sb_pattern_free(c->pat);
    free(c->x);
    free(c->g);
    sb_scene_free(&c->sc);
}

/* fastest of reps assemblies: what = 0 energy, 1 + gradient, 2 + Hessian */
static double time_assembly(bcase *c, int what, int reps)
{
    double best = INFINITY, f;
    for (int r = 0; r < reps; r++) {
        memset(c->g, 0, sizeof(double) * c->n);
        sb_matrix_zero(&c->H);
        const double t0 = sb_now();
        c->mt->energy(c->S, 0, c->x, &f, what ? c->g : NULL, what == 2 ? &c->H : NULL);
        const double t = sb_now() - t0;
        if (t < best) best = t;
    }
    return best;
}

static double loadavg(void)
{
    double l = -1;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1) l = -1;
        fclose(f);
    }
    return l;
}

static void bench_method(const char *scene, const char *method, int res, int quick)
{
    const char *kernels[2] = { "reference", "fast" };
    double t_ref_h = 0;
    bcase c;
    for (int kk = 0; kk < 2; kk++)
        for (int threads = 1; threads <= (kk ? 3 : 1); threads++) {
            if (open_case(&c, scene, method, res, kernels[kk], threads)) {
                printf("| %s | %d | cannot set up |\n", method, res);
                close_case(&c);
                return;
            }
            const int reps = quick ? 2 : (c.n > 15000 ? 3 : 5);
            const double te = time_assembly(&c, 0, reps), tg = time_assembly(&c, 1, reps);
            const double th = time_assembly(&c, 2, reps);
            if (kk == 0) t_ref_h = th;
            const double us = 1e6 / c.n;
            printf("| %s | %s | %d | %s | %d | %.2f | %.2f | %.2f | %.2f |\n", method, scene, c.n, kernels[kk], threads,
                   te * us, tg * us, th * us, t_ref_h / th);
            fflush(stdout);
            if (kk == 1 && threads == 1) {
                /* the factorization of this matrix at the reference state (PSD: no
                 * early stop at a negative pivot), shifted to be definite */
                sb_context ctx;
                sb_context_init(&ctx);
                c.mt->initial(c.S, 0, c.x);
                double f;
                sb_matrix_zero(&c.H);
                c.mt->energy(c.S, 0, c.x, &f, NULL, &c.H);
                sb_linsolve *ls = NULL;
                const double t0 = sb_now();
                int rc = sb_linsolve_create(&ctx, 0, &c.H, &ls);
                const double ta = sb_now() - t0;
                double tf = INFINITY, dmax = 0;
                for (int i = 0; i < c.n; i++) dmax = fmax(dmax, c.H.val[c.pat->diag[i]]);
                for (int r = 0; !rc && r < reps; r++) {
                    const double t1 = sb_now();
                    rc = sb_linsolve_factor(ls, 1e-6 * dmax);
                    tf = fmin(tf, sb_now() - t1);
                }
                if (rc == SB_OK)
                    printf("|   factorization (CHOLMOD) | | %d | analyze %.2f us/dof | | factorize | | %.2f | nnz(L) %.3g, "
                           "%.3g flop |\n",
                           c.n, ta * us, tf * us, sb_linsolve_nnz_l(ls), sb_linsolve_flops(ls));
                else
                    printf("|   factorization (CHOLMOD) | | %d | failed (%d) |\n", c.n, rc);
                sb_linsolve_free(ls);
                sb_context_free(&ctx);
            }
            close_case(&c);
        }
}

int main(int argc, char **argv)
{
    const char *scene = argc > 1 ? argv[1] : "bench/scenes/drape.json";
    const int quick = argc > 2 && strcmp(argv[2], "quick") == 0;
    printf("bench_assembly: one assembly per dof (us/dof, fastest of several, wall clock), %s; load average %.1f "
           "on %ld cores\n",
           scene, loadavg(), (long)sb_sysinfo_cores());
    printf("| method | scene | dofs | kernel | threads | energy | + gradient | + Hessian | Hessian speedup vs "
           "reference |\n|---|---|--:|---|--:|--:|--:|--:|--:|\n");
    /* about 6,000 and 25,000 dofs: rmtr 3 (N+3)^2, bhem 12 (N+1)^2 */
    bench_method(scene, "rmtr", 44, quick);
    bench_method(scene, "bhem", 22, quick);
    if (!quick) {
        bench_method(scene, "rmtr", 90, quick);
        bench_method(scene, "bhem", 45, quick);
    }
    printf("load average after: %.1f\n", loadavg());
    return 0;
}
