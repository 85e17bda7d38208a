/* bench_shell.c — throughput of the Kirchhoff–Love kernel (core/shell):
 * quadrature points per second for energy, energy + gradient and
 * energy + gradient + Hessian (exact and pseudo), StVK and denim, one core,
 * bicubic B-spline basis (k = 16) and a k = 40 basis (Catmull–Clark face at a
 * valence-16 vertex); the per-element PSD projection (48 x 48); and the flop
 * count per point of this implementation (counted from the code, see
 * kernel_flops()) against the machine's nominal peak.
 *
 * usage: bench_shell [seconds_per_case]   (default 0.3) */
#include "sb_shell.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define NPTS 64   /* distinct quadrature points cycled through */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

typedef struct bpoint {
    double N[SB_SHELL_MAX_BASIS], N1[SB_SHELL_MAX_BASIS], N2[SB_SHELL_MAX_BASIS];
    double N11[SB_SHELL_MAX_BASIS], N12[SB_SHELL_MAX_BASIS], N22[SB_SHELL_MAX_BASIS];
    sb_shell_basis b;
    sb_shell_ref r;
} bpoint;

/* cubic uniform B-spline on [0,1] */
static void bs1(double t, double f[4], double d[4], double dd[4])
{
    const double s = 1 - t;
    f[0] = s * s * s / 6;  f[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    f[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;  f[3] = t * t * t / 6;
    d[0] = -0.5 * s * s;  d[1] = (9 * t * t - 12 * t) / 6;  d[2] = (-9 * t * t + 6 * t + 3) / 6;  d[3] = 0.5 * t * t;
    dd[0] = s;  dd[1] = 3 * t - 2;  dd[2] = -3 * t + 1;  dd[3] = t;
}

static double urand(unsigned long long *rng, double a, double b)
{
    *rng ^= *rng << 13;
    *rng ^= *rng >> 7;
    *rng ^= *rng << 17;
    return a + (b - a) * (double)(*rng >> 11) / 9007199254740992.0;
}

/* k = 16: bicubic B-spline points; k > 16: smooth random weights standing in
 * for a Catmull–Clark face next to an extraordinary vertex (same arithmetic) */
static void setup(bpoint *P, int k, double *Xq, double *q)
{
    unsigned long long rng = 88172645463325252ULL;
    for (int I = 0; I < k; I++) {
        const int i = I % 4, j = (I / 4) % 4;
        Xq[3 * I] = 0.1 * i + 0.01 * (I / 16);
        Xq[3 * I + 1] = 0.1 * j + 0.013 * (I / 16);
        Xq[3 * I + 2] = 0.01 * sin(i + 2.0 * j);
    }
    for (int i = 0; i < 3 * k; i++) q[i] = Xq[i] + 0.004 * urand(&rng, -1, 1);
    for (int p = 0; p < NPTS; p++) {
        bpoint *bp = &P[p];
        if (k == 16) {
            double fu[4], du[4], ddu[4], fv[4], dv[4], ddv[4];
            bs1((p % 8 + 0.5) / 8, fu, du, ddu);
            bs1((p / 8 + 0.5) / 8, fv, dv, ddv);
            for (int j = 0; j < 4; j++)
                for (int i = 0; i < 4; i++) {
                    const int I = i + 4 * j;
                    bp->N[I] = fu[i] * fv[j];
                    bp->N1[I] = du[i] * fv[j];
                    bp->N2[I] = fu[i] * dv[j];
                    bp->N11[I] = ddu[i] * fv[j];
                    bp->N12[I] = du[i] * dv[j];
                    bp->N22[I] = fu[i] * ddv[j];
                }
        } else {
            for (int I = 0; I < k; I++) {
                bp->N[I] = urand(&rng, 0, 0.1);
                bp->N1[I] = urand(&rng, -0.2, 0.2);
                bp->N2[I] = urand(&rng, -0.2, 0.2);
                bp->N11[I] = urand(&rng, -0.5, 0.5);
                bp->N12[I] = urand(&rng, -0.5, 0.5);
                bp->N22[I] = urand(&rng, -0.5, 0.5);
            }
        }
        sb_shell_basis b = { k, bp->N, bp->N1, bp->N2, bp->N11, bp->N12, bp->N22 };
        bp->b = b;
        if (sb_shell_ref_init_basis(&bp->r, &bp->b, Xq, 0.3, 1.0 / NPTS) != SB_OK) {
            fprintf(stderr, "bench_shell: degenerate reference at point %d\n", p);
            exit(1);
        }
    }
}

enum { MODE_E, MODE_EG, MODE_EGH, MODE_EGHP, MODE_COUNT };
static const char *mode_name[MODE_COUNT] = { "energy", "energy+grad", "energy+grad+hess(exact)",
                                          "energy+grad+hess(pseudo)" };

/* Floating-point operations per point, counted from sb_shell.c (a multiply-add
 * counts 2; sqrt/div 1; transcendental calls counted separately in tr).
 *   jet gather 30k; strains and local transforms ~100;
 *   per thickness point: strain 9, stvk psi 12 (+10 derivative, +0 Hessian:
 *   constant), denim psi ~60 arithmetic + (3 log1p + 13 expm1) with Table 1,
 *   accumulation 2 (+12 gradient, +54 Hessian);
 *   gradient: forces 42, bending directions 63, local gradient 60, map 30k;
 *   Hessian: congruences 324, J build 30, D J 1080, J^T D J 1440, membrane 12,
 *   bending 2nd derivatives ~450 (exact only), Q = K W 450k,
 *   blocks 45 k(k+1) (k(k+1)/2 blocks of 45 multiply-adds), accumulation 9 k^2. */
static double kernel_flops(int mode, int k, int nt, int denim, double *tr)
{
    double f = 30.0 * k + 100 + nt * (9 + 2 + (denim ? 60 : 12));
    *tr = denim ? 16.0 * nt : 0;
    if (mode == MODE_E) return f;
    f += nt * (12 + (denim ? 20 : 10)) + 42 + 63 + 60 + 30.0 * k;
    if (mode == MODE_EG) return f;
    f += nt * 54 + 324 + 30 + 1080 + 1440 + 12 + (mode == MODE_EGH ? 450 : 0);
    f += 450.0 * k + 45.0 * k * (k + 1) + 9.0 * k * k;
    return f;
}

static double cpu_mhz(char *model, size_t len)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    double mhz = 0;
    char line[512];
    model[0] = '\0';
    if (!f) return 0;
    while (fgets(line, sizeof line, f)) {
        if (!model[0] && strncmp(line, "model name", 10) == 0) {
            const char *c = strchr(line, ':');
            if (c) snprintf(model, len, "%s", c + 2);
            model[strcspn(model, "\n")] = '\0';
        }
        if (mhz == 0 && strncmp(line, "cpu MHz", 7) == 0) {
            const char *c = strchr(line, ':');
            if (c) mhz = atof(c + 1);
        }
    }
    fclose(f);
    return mhz;
}

int main(int argc, char **argv)
{
    const double tcase = argc > 1 ? atof(argv[1]) : 0.3;
    if (!(tcase > 0)) {
        fprintf(stderr, "usage: bench_shell [seconds_per_case > 0]\n");
        return 2;
    }
    char model[128];
    const double mhz = cpu_mhz(model, sizeof model);
    printf("bench_shell: CPU %s, %.0f MHz (nominal); one core; %.2f s per case\n", model[0] ? model : "?",
           mhz, tcase);
    /* nominal peaks: the Makefile builds for the x86-64 baseline (SSE2,
     * 128-bit, no FMA): 2 adds + 2 multiplies of 2 doubles per cycle; a core
     * with two full-width 512-bit FMA pipes does 2 x 8 x 2 flop per cycle */
    printf("  nominal peak per core at %.0f MHz: %.1f GFLOP/s with SSE2 (the -O2 baseline build, 8 flop/cycle), "
           "%.1f GFLOP/s with 2 x 512-bit FMA (32 flop/cycle)\n",
           mhz, 8e-3 * mhz, 32e-3 * mhz);

    bpoint *P = malloc(sizeof(bpoint) * NPTS);
    double *H = malloc(sizeof(double) * 9 * SB_SHELL_MAX_BASIS * SB_SHELL_MAX_BASIS);
    if (!P || !H) return 1;
    double Xq[3 * SB_SHELL_MAX_BASIS], q[3 * SB_SHELL_MAX_BASIS], g[3 * SB_SHELL_MAX_BASIS];
    sb_shell_work *w = sb_shell_work_new();
    volatile double sink = 0;
    const int ks[2] = { 16, 40 };
    for (int ik = 0; ik < 2; ik++) {
        const int k = ks[ik];
        setup(P, k, Xq, q);
        for (int mat = 0; mat < 2; mat++) {
            sb_material_spec sp;
            if (mat) {
                sb_material_spec_denim(&sp);
            } else {
                memset(&sp, 0, sizeof sp);
                sp.kind = SB_MAT_STVK;
                sp.young = 1e6;
                sp.poisson = 0.3;
                sp.thickness = 1e-3;
                sp.density = 0.2;
            }
            sb_material m;
            if (sb_material_init(&m, &sp, 0) != SB_OK) return 1;
            for (int mode = 0; mode < MODE_COUNT; mode++) {
                if (k != 16 && mode == MODE_E) continue;
                memset(g, 0, sizeof g);
                memset(H, 0, sizeof(double) * 9 * k * k);
                long n = 0;
                double t0 = now(), t1 = t0;
                const sb_hess_kind kind = mode == MODE_EGHP ? SB_HESS_PSEUDO : SB_HESS_EXACT;
                double *gp = mode >= MODE_EG ? g : NULL, *hp = mode >= MODE_EGH ? H : NULL;
                do {
                    double e = 0;
                    for (int p = 0; p < NPTS; p++) e += sb_shell_energy(&m, &P[p].r, &P[p].b, q, gp, hp, kind, w);
                    sink += e;
                    n += NPTS;
                    if ((n & 1023) == 0) t1 = now();
                } while (t1 - t0 < tcase);
                const double rate = n / (t1 - t0);
                double tr;
                const double fl = kernel_flops(mode, k, m.n_thick, mat, &tr);
                printf("  %-5s k=%2d n_thick=%d %-26s %10.3e points/s  %7.0f flop/point%s  %5.2f GFLOP/s\n",
                       mat ? "denim" : "stvk", k, m.n_thick, mode_name[mode], rate, fl,
                       tr > 0 ? " (+transc.)" : "           ", rate * fl * 1e-9);
                sink += g[0] + H[1];
            }
        }
    }
    /* per-element PSD projection of a 48 x 48 element Hessian */
    {
        sb_material_spec sp;
        sb_material_spec_denim(&sp);
        sb_material m;
        sb_material_init(&m, &sp, 0);
        setup(P, 16, Xq, q);
        for (int i = 0; i < 48; i++) q[i] = Xq[i] * (i % 3 == 2 ? 1 : 0.95);
        double He[48 * 48], Hc[48 * 48];
        memset(He, 0, sizeof He);
        for (int p = 0; p < 16; p++) sb_shell_energy(&m, &P[p * 4].r, &P[p * 4].b, q, NULL, He, SB_HESS_EXACT, w);
        double *work = malloc(sizeof(double) * sb_psd_work_size(48));
        long n = 0;
        double t0 = now(), t1 = t0;
        do {
            memcpy(Hc, He, sizeof He);
            if (sb_psd_project(48, Hc, work) != SB_OK) return 1;
            n++;
            t1 = now();
        } while (t1 - t0 < tcase);
        printf("  psd projection 48x48 (dsyev): %.1f us per element, %.3e elements/s\n", 1e6 * (t1 - t0) / n,
               n / (t1 - t0));
        free(work);
    }
    sb_shell_work_free(w);
    free(P);
    free(H);
    return sink == 12345.6789 ? 3 : 0;
}
