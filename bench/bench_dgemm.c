/* bench_dgemm.c — the machine's dense rate: OpenBLAS DGEMM (C = A B + C,
 * n x n, 2 n^3 flops) on one thread and on all cores, in GFLOP/s, the
 * figure the scaling report holds CHOLMOD's achieved factorization rate
 * against (issue 42: supernodal CHOLMOD spends its flops in DGEMM/DSYRK/
 * DPOTRF on the supernodes, so DGEMM's rate is its ceiling).
 *
 *   build/bench/bench_dgemm [n ...]          default n = 256 512 1024 2048
 *
 * Uses the kernel set OpenBLAS picked (OPENBLAS_CORETYPE pins another, as
 * the suite's benches pin Prescott) and prints it; the thread count is set
 * with openblas_set_num_threads (1, then the online cores).  Wall time
 * (CLOCK_MONOTONIC) and process CPU time, best of 5 repetitions after one
 * warm-up; on a shared machine the best repetition is the least disturbed.
 * Output: one line per (threads, n) and last lines "dgemm_1core_gflops X"
 * and "dgemm_allcores_gflops Y" (the best wall rate over the sizes) for
 * scripts. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>
#include <dlfcn.h>

void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha,
            const double *a, const int *lda, const double *b, const int *ldb, const double *beta, double *c,
            const int *ldc);

/* OpenBLAS's own calls, asked of the BLAS already loaded (libblas.so.3 is
 * OpenBLAS's when Debian's alternative points there), as sb_sysinfo.c does */
static void *blas_sym(const char *name)
{
    static const char *const libs[] = { "libopenblas.so.0", "libblas.so.3" };
    for (size_t i = 0; i < sizeof libs / sizeof libs[0]; i++) {
        void *h = dlopen(libs[i], RTLD_LAZY | RTLD_NOLOAD);
        void *f = h ? dlsym(h, name) : NULL;
        if (f) return f;
    }
    return NULL;
}

static double now(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double rate(int n, int reps, double *cpu_rate)
{
    double *a = malloc(sizeof(double) * (size_t)n * (size_t)n);
    double *b = malloc(sizeof(double) * (size_t)n * (size_t)n);
    double *c = malloc(sizeof(double) * (size_t)n * (size_t)n);
    if (!a || !b || !c) {
        fprintf(stderr, "bench_dgemm: no memory for n = %d\n", n);
        exit(3);
    }
    unsigned s = 12345u;
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++) {
        s = s * 1103515245u + 12345u;
        a[i] = (double)(s >> 8) / 16777216.0 - 0.5;
        s = s * 1103515245u + 12345u;
        b[i] = (double)(s >> 8) / 16777216.0 - 0.5;
        c[i] = 0.0;
    }
    const double one = 1.0, zero = 0.0;
    dgemm_("N", "N", &n, &n, &n, &one, a, &n, b, &n, &zero, c, &n); /* warm-up */
    double best = 1e300, best_cpu = 1e300;
    for (int r = 0; r < reps; r++) {
        double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
        dgemm_("N", "N", &n, &n, &n, &one, a, &n, b, &n, &one, c, &n);
        double w = now(CLOCK_MONOTONIC) - w0, cp = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
        if (w < best) best = w;
        if (cp < best_cpu) best_cpu = cp;
    }
    volatile double sink = c[0];
    (void)sink;
    free(a);
    free(b);
    free(c);
    double flops = 2.0 * (double)n * (double)n * (double)n;
    *cpu_rate = flops / best_cpu * 1e-9;
    return flops / best * 1e-9;
}

int main(int argc, char **argv)
{
    int ns[16] = { 256, 512, 1024, 2048 }, nn = 4;
    if (argc > 1) {
        nn = 0;
        for (int i = 1; i < argc && nn < 16; i++) ns[nn++] = atoi(argv[i]);
    }
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (cores < 1) cores = 1;
    const char *ct = getenv("OPENBLAS_CORETYPE");
    char *(*corename)(void) = (char *(*)(void))blas_sym("openblas_get_corename");
    char *(*config)(void) = (char *(*)(void))blas_sym("openblas_get_config");
    void (*set_threads)(int) = (void (*)(int))blas_sym("openblas_set_num_threads");
    if (!set_threads) {
        fprintf(stderr, "bench_dgemm: the BLAS is not OpenBLAS (no openblas_set_num_threads)\n");
        return 2;
    }
    printf("# OpenBLAS core %s (OPENBLAS_CORETYPE=%s), config: %s\n", corename ? corename() : "unknown",
           ct ? ct : "unset", config ? config() : "unknown");
    printf("# threads  n  GFLOP/s(wall, best of 5)  GFLOP/s(process CPU)\n");
    double best[2] = { 0, 0 };
    int tc[2] = { 1, (int)cores };
    for (int t = 0; t < (cores > 1 ? 2 : 1); t++) {
        set_threads(tc[t]);
        for (int i = 0; i < nn; i++) {
            double cpu;
            double g = rate(ns[i], 5, &cpu);
            printf("%d %d %.2f %.2f\n", tc[t], ns[i], g, cpu);
            fflush(stdout);
            if (g > best[t]) best[t] = g;
        }
    }
    printf("dgemm_1core_gflops %.2f\n", best[0]);
    if (cores > 1) printf("dgemm_allcores_gflops %.2f (%ld threads)\n", best[1], cores);
    return 0;
}
