/* bench_assembly.c — the cost of one assembly (energy, gradient and Hessian)
 * per degree of freedom for the rmtr and bhem methods at about 6,000 and
 * 25,000 dofs, beside the cost of one sparse Cholesky factorization of the
 * same matrix (CHOLMOD, symbolic analysis once): the reference kernel
 * (method.kernel=reference, per point) and the fast one at the portable
 * SSE2 vector width and at the CPU's widest (run.vectors; the same bits),
 * on 1, 2 and 3 threads (run.threads), all in this one run, so the ratios compare like
 * with like on a machine whatever else it runs (issue 30).
 *
 * Times: the fastest of several rounds (each round runs every configuration
 * once), as process CPU time (all threads: the cost) and wall time (the
 * thread scaling, meaningful only when the cores are otherwise idle); the
 * load average is printed.
 *
 * usage: bench_assembly [scene.json] [quick]   (default bench/scenes/drape.json) */
#include "sb_context.h"
#include "sb_linsolve.h"
#include "sb_method.h"
#include "sb_solver.h"
#include "sb_shell.h"
#include "sb_sparse.h"
#include "sb_stats.h"
#include "sb_sysinfo.h"

#include <math.h>
#include <stdio.h>
#include <time.h>
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

static int open_case(bcase *c, const char *scene, const char *method, int res, const char *kernel, int threads,
                     const char *vectors)
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
    snprintf(set, sizeof set, "run.vectors=%s", vectors);
    if (sb_paramset_set(&c->ps, set, err, sizeof err)) return -1;
    c->S = calloc(1, c->mt->state_size);
    sb_method_config cfg = { res, 1, &c->ps, NULL, 0 };
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

static double clk(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* one assembly: what = 0 energy, 1 + gradient, 2 + Hessian; wall and process CPU seconds */
static void assemble_once(bcase *c, int what, double *wall, double *cpu)
{
    double f;
    memset(c->g, 0, sizeof(double) * c->n);
    sb_matrix_zero(&c->H);
    const double w0 = clk(CLOCK_MONOTONIC), c0 = clk(CLOCK_PROCESS_CPUTIME_ID);
    c->mt->energy(c->S, 0, c->x, &f, what ? c->g : NULL, what == 2 ? &c->H : NULL);
    *cpu = clk(CLOCK_PROCESS_CPUTIME_ID) - c0;
    *wall = clk(CLOCK_MONOTONIC) - w0;
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

/* the reference kernel; the fast one at the portable SSE2 width and at the
 * CPU's widest (run.vectors=auto, the default), on 1, 2 and 3 threads.
 * Column 2 (fast, auto, 1 thread) is what a run uses by default. */
#define NCONF 5
static const char *const conf_kernel[NCONF] = { "reference", "fast", "fast", "fast", "fast" };
static const char *const conf_vectors[NCONF] = { "auto", "sse2", "auto", "auto", "auto" };
static const int conf_threads[NCONF] = { 1, 1, 1, 2, 3 };

/* the configurations side by side, in rounds (each round assembles
 * every configuration once), keeping each one's fastest */
static void bench_method(const char *scene, const char *method, int res, int quick)
{
    bcase c[NCONF];
    /* `make NATIVE=1` has its own width only: its row 1 repeats row 2 */
    const int have_sse2 = strcmp(sb_shell_isa_name(SB_ISA_BASE), "sse2") == 0;
    const char *vec[NCONF];
    for (int k = 0; k < NCONF; k++) vec[k] = !have_sse2 && strcmp(conf_vectors[k], "sse2") == 0 ? "auto" : conf_vectors[k];
    for (int k = 0; k < NCONF; k++)
        if (open_case(&c[k], scene, method, res, conf_kernel[k], conf_threads[k], vec[k])) {
            printf("| %s | %d | cannot set up |\n", method, res);
            for (int j = 0; j <= k; j++) close_case(&c[j]);
            return;
        }
    const int n = c[0].n, rounds = quick ? 2 : (n > 15000 ? 3 : 5);
    double wall[NCONF][3], cpu[NCONF][3];
    for (int k = 0; k < NCONF; k++)
        for (int w = 0; w < 3; w++) wall[k][w] = cpu[k][w] = INFINITY;
    for (int r = 0; r < rounds; r++)
        for (int w = 0; w < 3; w++)
            for (int k = 0; k < NCONF; k++) {
                double tw, tc;
                assemble_once(&c[k], w, &tw, &tc);
                wall[k][w] = fmin(wall[k][w], tw);
                cpu[k][w] = fmin(cpu[k][w], tc);
            }
    const double us = 1e6 / n;
    for (int k = 0; k < NCONF; k++) {
        char kern[64];
        snprintf(kern, sizeof kern, "%s%s%s", conf_kernel[k], k ? " " : "",
                 k ? (strcmp(vec[k], "auto") ? vec[k] : sb_shell_isa_name(sb_shell_isa_best())) : "");
        printf("| %s | %d | %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", method, n, kern, conf_threads[k],
               cpu[k][0] * us, cpu[k][1] * us, cpu[k][2] * us, cpu[0][2] / cpu[k][2], wall[k][2] * us,
               wall[2][2] / wall[k][2]);
    }
    /* the factorization of this matrix at the reference state (PSD: no early
     * stop at a negative pivot), shifted to be definite */
    sb_context ctx;
    sb_context_init(&ctx);
    c[2].mt->initial(c[2].S, 0, c[2].x);
    double f;
    sb_matrix_zero(&c[2].H);
    c[2].mt->energy(c[2].S, 0, c[2].x, &f, NULL, &c[2].H);
    sb_linsolve *ls = NULL;
    double t0 = clk(CLOCK_PROCESS_CPUTIME_ID);
    int rc = sb_linsolve_create(&ctx, 0, &c[2].H, &ls);
    const double ta = clk(CLOCK_PROCESS_CPUTIME_ID) - t0;
    double tf = INFINITY, dmax = 0;
    for (int i = 0; i < n; i++) dmax = fmax(dmax, c[2].H.val[c[2].pat->diag[i]]);
    for (int r = 0; !rc && r < rounds; r++) {
        t0 = clk(CLOCK_PROCESS_CPUTIME_ID);
        rc = sb_linsolve_factor(ls, 1e-6 * dmax);
        tf = fmin(tf, clk(CLOCK_PROCESS_CPUTIME_ID) - t0);
    }
    if (rc == SB_OK)
        printf("| %s | %d | factorization (CHOLMOD, one thread) | | analyze %.2f | | factorize %.2f | "
               "| nnz(L) %.3g | %.3g flop |\n",
               method, n, ta * us, tf * us, sb_linsolve_nnz_l(ls), sb_linsolve_flops(ls));
    else
        printf("| %s | %d | factorization failed (%d) |\n", method, n, rc);
    fflush(stdout);
    sb_linsolve_free(ls);
    sb_context_free(&ctx);
    for (int k = 0; k < NCONF; k++) close_case(&c[k]);
}

int main(int argc, char **argv)
{
    const char *scene = argc > 1 ? argv[1] : "bench/scenes/drape.json";
    const int quick = argc > 2 && strcmp(argv[2], "quick") == 0;
    printf("bench_assembly: one assembly per dof, us/dof, fastest of several rounds, %s; load average %.1f on %ld "
           "cores\n  CPU: process CPU time (all threads); wall: elapsed (thread scaling, meaningful on an idle "
           "machine only)\n",
           scene, loadavg(), (long)sb_sysinfo_cores());
    printf("| method | dofs | kernel | threads | energy CPU | + gradient CPU | + Hessian CPU | Hessian CPU speedup vs "
           "reference | + Hessian wall | wall speedup vs 1 thread |\n|---|--:|---|--:|--:|--:|--:|--:|--:|--:|\n");
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
