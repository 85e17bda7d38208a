/* sb_regress_calib.c — the calibration kernel of the nightly regression
 * (docs/regression.md "Calibration").  Times are judged as CPU seconds
 * divided by the median of this kernel's CPU seconds in the same
 * invocation, so that a slower (or faster) machine, or one shared with
 * other work, is not called a regression.
 *
 * The kernel is written here and calls nothing of the suite, on purpose: a
 * calibration made of the suite's own code (an assembly, a factorization)
 * would slow down with a regression of that code and normalize it away.  It
 * mixes what the suite's runs spend their time in: dense floating-point
 * work with a data set that fits the caches (a 96 x 96 matrix product, like
 * element Hessians and supernodes) and indexed memory traffic over 8 MB
 * (like sparse assembly and triangular solves), about 0.05 s each on the
 * 2-core development machine. */
#include "sb_regress.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>

enum { NDENSE = 96, DENSE_REPS = 240, NSPARSE = 1 << 20, SPARSE_REPS = 12 };

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* a result the compiler cannot drop */
static volatile double sink;

double sb_regress_calibrate(void)
{
    /* the data are allocated and touched before the clock starts: a fresh
     * 12 MB costs page faults whose (system) time varies by a factor 30 with
     * what the kernel is doing (measured 0.001-0.04 s), noise a
     * calibration must not have */
    static double a[NDENSE * NDENSE], b[NDENSE * NDENSE], c[NDENSE * NDENSE];
    double *v = malloc((size_t)NSPARSE * sizeof *v);
    uint32_t *idx = malloc((size_t)NSPARSE * sizeof *idx);
    if (!v || !idx) {
        free(v), free(idx);
        return NAN;
    }
    for (int i = 0; i < NDENSE * NDENSE; i++) a[i] = 1.0 / (1 + i % 17), b[i] = 1.0 / (1 + i % 13), c[i] = 0;
    uint32_t h = 12345u;
    for (uint32_t i = 0; i < NSPARSE; i++) v[i] = (double)(i & 1023), h = h * 1664525u + 1013904223u, idx[i] = h >> 12;
    double t0 = cpu_now();
    for (int r = 0; r < DENSE_REPS; r++)
        for (int i = 0; i < NDENSE; i++)
            for (int k = 0; k < NDENSE; k++) {
                double aik = a[i * NDENSE + k] * (1.0 + 1e-3 * r);
                for (int j = 0; j < NDENSE; j++) c[i * NDENSE + j] += aik * b[k * NDENSE + j];
            }
    double s = c[NDENSE * NDENSE / 2];
    /* indexed gathers over 8 MB in a fixed pseudo-random order (an LCG) */
    for (int r = 0; r < SPARSE_REPS; r++)
        for (uint32_t i = 0; i < NSPARSE; i++) s += 1e-9 * v[idx[i] & (NSPARSE - 1)];
    double t = cpu_now() - t0;
    free(v);
    free(idx);
    sink = s;
    return t;
}
