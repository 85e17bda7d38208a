/* bench_shell.c — throughput of the Kirchhoff–Love kernels (core/shell): the
 * reference kernel (sb_shell_energy, per quadrature point) and the fast one
 * (sb_shell_element, the points of an element batched; issue 30), on the
 * same elements in the same run, as quadrature points per second and their
 * ratio: energy, + gradient, + exact and pseudo Hessian, StVK and denim,
 * elements of a bicubic patch (k = 16) with 3 x 3 points (an rmtr face) and
 * 4 x 4 points (a bhem patch), and k = 40 (a Catmull–Clark face at a
 * valence-16 vertex) with 3 x 3; the section law alone; the PSD treatment of
 * an indefinite 48 x 48 element Hessian (reference: eigenvalue clamp,
 * dsyev; fast: sb_shell_element_psd) and the PSD check of a PSD one.
 *
 * Timing: CPU time of this thread (CLOCK_THREAD_CPUTIME_ID), the two kernels
 * alternating in short rounds, so that other processes on the machine
 * change neither figure much and their ratio even less.  GFLOP/s: flops
 * counted from the code (kernel_flops, fast_flops) per CPU second.
 *
 * usage: bench_shell [seconds_per_case]   (default 0.25) */
#include "sb_shell.h"
#include "sb_simd.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define NQMAX 16

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

typedef struct bpoint {
    double N[SB_SHELL_MAX_BASIS], N1[SB_SHELL_MAX_BASIS], N2[SB_SHELL_MAX_BASIS];
    double N11[SB_SHELL_MAX_BASIS], N12[SB_SHELL_MAX_BASIS], N22[SB_SHELL_MAX_BASIS];
} bpoint;

typedef struct belem {
    int k, nq;
    bpoint P[NQMAX];
    sb_shell_basis b[NQMAX];
    sb_shell_ref r[NQMAX];
    double Xq[3 * SB_SHELL_MAX_BASIS], q[3 * SB_SHELL_MAX_BASIS];
} belem;

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

/* k = 16: bicubic B-spline element with ng x ng Gauss-like points; k > 16:
 * smooth random weights standing in for a Catmull–Clark face next to an
 * extraordinary vertex (the same arithmetic); deformed by a small random
 * displacement (every term of the energy active) */
static void setup(belem *E, int k, int ng, double amp)
{
    unsigned long long rng = 88172645463325252ULL;
    E->k = k;
    E->nq = ng * ng;
    for (int I = 0; I < k; I++) {
        const int i = I % 4, j = (I / 4) % 4;
        E->Xq[3 * I] = 0.1 * i + 0.01 * (I / 16);
        E->Xq[3 * I + 1] = 0.1 * j + 0.013 * (I / 16);
        E->Xq[3 * I + 2] = 0.01 * sin(i + 2.0 * j);
    }
    for (int i = 0; i < 3 * k; i++) E->q[i] = E->Xq[i] + amp * urand(&rng, -1, 1);
    for (int p = 0; p < E->nq; p++) {
        bpoint *bp = &E->P[p];
        if (k == 16) {
            double fu[4], du[4], ddu[4], fv[4], dv[4], ddv[4];
            bs1((p % ng + 0.5) / ng, fu, du, ddu);
            bs1((p / ng + 0.5) / ng, fv, dv, ddv);
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
        E->b[p] = b;
        if (sb_shell_ref_init_basis(&E->r[p], &E->b[p], E->Xq, 0.3, 1.0 / E->nq) != SB_OK) {
            fprintf(stderr, "bench_shell: degenerate reference at point %d\n", p);
            exit(1);
        }
    }
}

enum { MODE_E, MODE_EG, MODE_EGH, MODE_EGHP, MODE_COUNT };
static const char *mode_name[MODE_COUNT] = { "energy", "+ gradient", "+ Hessian (exact)", "+ Hessian (pseudo)" };

/* Floating-point operations per point of the reference kernel, counted from
 * sb_shell.c (a multiply-add counts 2; sqrt/div 1; transcendental calls in tr):
 *   jet gather 30k; strains and local transforms ~100;
 *   per thickness point: strain 9, stvk psi 12 (+10 derivative, +0 Hessian),
 *   denim psi ~60 arithmetic + (3 log1p + 13 expm1) with Table 1,
 *   accumulation 2 (+12 gradient, +54 Hessian);
 *   gradient: forces 42, bending directions 63, local gradient 60, map 30k;
 *   Hessian: congruences 324, J build 30, D J 1080, J^T D J 1440, membrane 12,
 *   bending 2nd derivatives ~450 (exact only), Q = K W 450k,
 *   blocks 45 k(k+1), accumulation 9 k^2. */
static double kernel_flops(int mode, int k, int nt, int denim)
{
    double f = 30.0 * k + 100 + nt * (9 + 2 + (denim ? 60 : 12));
    if (mode == MODE_E) return f;
    f += nt * (12 + (denim ? 20 : 10)) + 42 + 63 + 60 + 30.0 * k;
    if (mode == MODE_EG) return f;
    f += nt * 54 + 324 + 30 + 1080 + 1440 + 12 + (mode == MODE_EGH ? 450 : 0);
    f += 450.0 * k + 45.0 * k * (k + 1) + 9.0 * k * k;
    return f;
}

/* The same per point for the fast kernel (sb_shell_elem.c; kp = k padded
 * to the tile): jet 30 kp; strains ~100; section as above (StVK by its
 * moments: ~60 + 90 with C); gradient 165 + map 30 kp; Hessian: D 324,
 * J^T D J ~1300, bending ~450 (exact), Z 300 kp, the products
 * 2 x 5 nq x (tiles x MR x NR) per element, the scatter 9 k^2 per element. */
static double fast_flops(int mode, int k, int nq, int nt, int denim)
{
    const int kp = (k + 3) / 4 * 4;
    double sec = denim ? nt * (9 + 2 + 60) : 60;
    double f = 30.0 * kp + 100 + sec;
    if (mode == MODE_E) return f;
    f += (denim ? nt * 32 : 30) + 165 + 30.0 * kp;
    if (mode == MODE_EG) return f;
    f += (denim ? nt * 54 : 90) + 324 + 1300 + (mode == MODE_EGH ? 450 : 0) + 300.0 * kp;
    /* 3 full products kp x kp and 3 on and above the diagonal 4 x 4 tiles */
    const double t = kp / 4.0, tiles = 3 * t * t + 3 * t * (t + 1) / 2;
    f += (2.0 * 5 * nq * tiles * 16 + 9.0 * k * k) / nq;
    return f;
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

static volatile double sink;

/* element energies (and derivatives) of the reference kernel and the fast
 * kernel at each batch of bws (one per vector width), for about `t` CPU
 * seconds in total, in rounds alternating between them: CPU seconds per
 * element of each (o[0] the reference, o[1 + i] the fast kernel on bws[i]) */
#define NKER 3
typedef struct pair_out { double ref, fast, wide; } pair_out;

static double run_one(int which, const sb_material *m, belem *E, double *gp, double *hp, sb_hess_kind kind,
                      sb_shell_work *w, sb_shell_batch *const *bws, long reps)
{
    double s = 0;
    for (long i = 0; i < reps; i++) {
        if (which == 0) {
            double e = 0;
            for (int p = 0; p < E->nq; p++) e += sb_shell_energy(m, &E->r[p], &E->b[p], E->q, gp, hp, kind, w);
            s += e;
        } else {
            s += sb_shell_element(m, E->nq, E->r, E->b, E->q, gp, hp, kind, bws[which - 1]);
        }
    }
    return s;
}

static pair_out time_pair(const sb_material *m, belem *E, int mode, double t, sb_shell_work *w,
                          sb_shell_batch *const *bws, int nb)
{
    const int n = 3 * E->k, nk = 1 + nb;
    static double g[3 * SB_SHELL_MAX_BASIS], H[9 * SB_SHELL_MAX_BASIS * SB_SHELL_MAX_BASIS];
    memset(g, 0, sizeof(double) * n);
    memset(H, 0, sizeof(double) * n * n);
    const sb_hess_kind kind = mode == MODE_EGHP ? SB_HESS_PSEUDO : SB_HESS_EXACT;
    double *gp = mode >= MODE_EG ? g : NULL, *hp = mode >= MODE_EGH ? H : NULL;
    /* batches long enough (~0.2 ms) that reading the thread clock (a system
     * call) costs nothing measurable */
    long reps[NKER];
    for (int j = 0; j < nk; j++) {
        reps[j] = 1;
        for (;;) {
            const double t0 = cpu_now();
            sink += run_one(j, m, E, gp, hp, kind, w, bws, reps[j]);
            if (cpu_now() - t0 > 2e-4 || reps[j] > (1L << 30)) break;
            reps[j] *= 2;
        }
    }
    const int rounds = 8;
    double tt[NKER] = { 0 };
    long nn[NKER] = { 0 };
    for (int round = 0; round < rounds; round++)
        for (int j = 0; j < nk; j++) {
            double t0 = cpu_now(), t1;
            do {
                sink += run_one(j, m, E, gp, hp, kind, w, bws, reps[j]);
                nn[j] += reps[j];
            } while ((t1 = cpu_now()) - t0 < t / (nk * rounds));
            tt[j] += t1 - t0;
        }
    sink += g[0] + H[1];
    pair_out o = { tt[0] / nn[0], tt[1] / nn[1], nb > 1 ? tt[2] / nn[2] : tt[1] / nn[1] };
    return o;
}

static void material(sb_material *m, int denim)
{
    sb_material_spec sp;
    if (denim) {
        sb_material_spec_denim(&sp);
    } else {
        memset(&sp, 0, sizeof sp);
        sp.kind = SB_MAT_STVK;
        sp.young = 1e6;
        sp.poisson = 0.3;
        sp.thickness = 1e-3;
        sp.density = 0.2;
    }
    if (sb_material_init(m, &sp, 0) != SB_OK) exit(1);
}

int main(int argc, char **argv)
{
    const double tcase = argc > 1 ? atof(argv[1]) : 0.25;
    if (!(tcase > 0)) {
        fprintf(stderr, "usage: bench_shell [seconds_per_case > 0]\n");
        return 2;
    }
    char model[128];
    const double mhz = cpu_mhz(model, sizeof model);
    printf("bench_shell: CPU %s, %.0f MHz (nominal); one core; thread CPU time, %.2f s per case; load average "
           "%.1f\n",
           model[0] ? model : "?", mhz, tcase, loadavg());
#if defined(__AVX512F__)
    const char *isa = "AVX-512 (native build)";
#elif defined(__AVX__)
    const char *isa = "AVX (native build)";
#else
    const char *isa = "SSE2 (the portable default build)";
#endif
    printf("  vectors of %d doubles, %s; nominal peak per core at %.0f MHz: %.1f GFLOP/s with SSE2 (2 adds + 2 "
           "multiplies of 2 doubles per cycle), %.1f GFLOP/s with 2 x 512-bit FMA\n\n",
           SB_VL, isa, mhz, 8e-3 * mhz, 32e-3 * mhz);

    belem *E = malloc(sizeof *E);
    sb_shell_work *w = sb_shell_work_new();
    /* bws[0]: the products at the build's base width (SSE2 in the default
     * build); bws[1]: at the widest this CPU runs (the default of every
     * run), when wider: the same bits (sb_elem_tile.c), another speed */
    sb_shell_batch *bws[2] = { sb_shell_batch_new(SB_SHELL_MAX_BASIS, NQMAX), sb_shell_batch_new(SB_SHELL_MAX_BASIS, NQMAX) };
    if (!E || !w || !bws[0] || !bws[1]) return 1;
    sb_shell_batch_set_isa(bws[0], SB_ISA_BASE);
    const sb_shell_isa best = sb_shell_isa_best();
    const int nb = best == SB_ISA_BASE ? 1 : 2;
    sb_shell_batch *bw = bws[nb - 1];
    const char *bn = sb_shell_isa_name(SB_ISA_BASE), *wn = sb_shell_isa_name(best);
    printf("fast kernel products: %s (this CPU's widest; the run default)%s%s%s\n\n", wn,
           nb > 1 ? ", also timed at " : "", nb > 1 ? bn : "", nb > 1 ? " (the portable baseline)" : "");
    printf("| material | k | points | evaluation | reference points/s | fast %s points/s | fast %s / reference |", bn, bn);
    if (nb > 1) printf(" fast %s points/s | fast %s / reference | %s / %s |", wn, wn, wn, bn);
    printf(" fast GFLOP/s |\n|---|--:|--:|---|--:|--:|--:|%s--:|\n", nb > 1 ? "--:|--:|--:|" : "");
    const int ks[3] = { 16, 16, 40 }, ngs[3] = { 3, 4, 3 };
    for (int ic = 0; ic < 3; ic++)
        for (int mat = 0; mat < 2; mat++) {
            sb_material m;
            material(&m, mat);
            setup(E, ks[ic], ngs[ic], 0.004);
            for (int mode = 0; mode < MODE_COUNT; mode++) {
                if (ic == 1 && mode != MODE_EGH) continue;   /* the bhem patch: the Hessian only */
                const pair_out o = time_pair(&m, E, mode, tcase, w, bws, nb);
                const double rr = E->nq / o.ref, rf = E->nq / o.fast, rw = E->nq / o.wide;
                printf("| %s | %d | %d | %s | %.3e | %.3e | %.2f |", mat ? "denim" : "stvk", E->k, E->nq,
                       mode_name[mode], rr, rf, o.ref / o.fast);
                if (nb > 1) printf(" %.3e | %.2f | %.2f |", rw, o.ref / o.wide, o.fast / o.wide);
                printf(" %.2f |\n", rw * fast_flops(mode, E->k, E->nq, m.n_thick, mat) * 1e-9);
                fflush(stdout);
            }
        }
    /* reference GFLOP/s of the per-point kernel, as counted before issue 30 */
    {
        sb_material m;
        material(&m, 0);
        setup(E, 16, 3, 0.004);
        const pair_out o = time_pair(&m, E, MODE_EGH, tcase, w, bws, nb);
        printf("\nreference kernel, stvk k = 16, + Hessian: %.2f GFLOP/s (%.0f flop/point counted); fast (%s): %.2f "
               "GFLOP/s (%.0f flop/point)\n",
               E->nq / o.ref * kernel_flops(MODE_EGH, 16, 2, 0) * 1e-9, kernel_flops(MODE_EGH, 16, 2, 0), wn,
               E->nq / o.wide * fast_flops(MODE_EGH, 16, 9, 2, 0) * 1e-9, fast_flops(MODE_EGH, 16, 9, 2, 0));
    }

    /* the section law alone (per quadrature point, with tangent) */
    printf("\n| section law (with tangent) | reference ns/point | fast ns/point | fast / reference |\n|---|--:|--:|--:|\n");
    for (int mat = 0; mat < 2; mat++) {
        sb_material m;
        material(&m, mat);
        double A[16][3], B[16][3], sA[3], sB[3], C[36];
        for (int i = 0; i < 16; i++)
            for (int c = 0; c < 3; c++) {
                A[i][c] = 0.01 * sin(i + c);
                B[i][c] = 3 * cos(1.3 * i + c);
            }
        double tr = 0, tf = 0;
        long nr = 0, nf = 0;
        for (int round = 0; round < 8; round++) {
            double t0 = cpu_now(), t1;
            do {
                for (int r = 0; r < 64; r++)
                    for (int i = 0; i < 16; i++) sink += sb_shell_section(&m, A[i], B[i], sA, sB, C) + C[7];
                nr += 1024;
            } while ((t1 = cpu_now()) - t0 < tcase / 16);
            tr += t1 - t0;
            t0 = cpu_now();
            do {
                for (int r = 0; r < 64; r++)
                    for (int i = 0; i < 16; i++) sink += sb_shell_section_fast(&m, A[i], B[i], sA, sB, C) + C[7];
                nf += 1024;
            } while ((t1 = cpu_now()) - t0 < tcase / 16);
            tf += t1 - t0;
        }
        printf("| %s, %d thickness points | %.1f | %.1f | %.2f |\n", mat ? "denim" : "stvk", m.n_thick, 1e9 * tr / nr,
               1e9 * tf / nf, (tr / nr) / (tf / nf));
    }

    /* PSD: an indefinite element Hessian (compressed denim element, 3 x 3
     * points): the reference clamps its eigenvalues (dsyev); the fast path
     * checks it (sb_psd_check) and, indefinite, projects in strain space;
     * and the check alone on a PSD element (the rest state), which is kept */
    for (int mat = 1; mat >= 0; mat--) {
        sb_material m;
        material(&m, mat);
        setup(E, 16, 3, 0.0);
        for (int i = 0; i < 48; i++) E->q[i] = E->Xq[i] * (i % 3 == 2 ? 1 : 0.95);
        double He[48 * 48], Hc[48 * 48], Hrest[48 * 48], Kx[48 * 48];
        memset(He, 0, sizeof He);
        memset(Hrest, 0, sizeof Hrest);
        memset(Kx, 0, sizeof Kx);
        sb_shell_element(&m, E->nq, E->r, E->b, E->q, NULL, He, SB_HESS_EXACT, bw);
        sb_shell_element(&m, E->nq, E->r, E->b, E->Xq, NULL, Hrest, SB_HESS_EXACT, bw);
        double *work = malloc(sizeof(double) * sb_psd_work_size(48));
        double tr = 0, tf = 0, tc = 0, tx = 0, ti = 0;
        long nr = 0, nf = 0, nc = 0, nx = 0, ni = 0;
        int path = -1, kept = -1;
        for (int round = 0; round < 4; round++) {
            double t0 = cpu_now(), t1;
            do {
                memcpy(Hc, He, sizeof He);
                if (sb_psd_project(48, Hc, work) != SB_OK) return 1;
                nr++;
            } while ((t1 = cpu_now()) - t0 < tcase / 8);
            tr += t1 - t0;
            t0 = cpu_now();
            do {
                memset(Hc, 0, sizeof Hc);
                sb_shell_element_psd(&m, E->nq, E->r, E->b, E->q, NULL, Hc, Kx, 0, bw, work, &path);
                nf++;
            } while ((t1 = cpu_now()) - t0 < tcase / 8);
            tf += t1 - t0;
            t0 = cpu_now();
            do {
                memset(Hc, 0, sizeof Hc);
                sb_shell_element(&m, E->nq, E->r, E->b, E->q, NULL, Hc, SB_HESS_EXACT, bw);
                nx++;
            } while ((t1 = cpu_now()) - t0 < tcase / 8);
            tx += t1 - t0;
            t0 = cpu_now();
            do {
                for (int r = 0; r < 16; r++) kept = sb_psd_check(48, Hrest, work);
                nc += 16;
            } while ((t1 = cpu_now()) - t0 < tcase / 16);
            tc += t1 - t0;
            t0 = cpu_now();
            do {
                for (int r = 0; r < 16; r++) sink += sb_psd_check(48, He, work);
                ni += 16;
            } while ((t1 = cpu_now()) - t0 < tcase / 16);
            ti += t1 - t0;
        }
        /* the PSD treatment proper: the fast PSD element less the exact one */
        const double tpsd = tf / nf - tx / nx;
        printf("\nPSD, 48 x 48 element Hessian (%s, compressed 5 %%, indefinite):\n"
               "  reference, eigenvalue clamp (dsyev) of the exact element matrix: %.1f us per element\n"
               "  fast, exact element + check + strain-space projection (path %d): %.1f us, of which %.1f us beyond "
               "the exact element: %.1f x faster than the clamp\n"
               "  (the check of this element alone: %.1f us)\n"
               "  fast, check of a PSD element (rest state, kept: %d): %.1f us, %.1f x faster than the clamp\n",
               mat ? "denim" : "stvk", 1e6 * tr / nr, path, 1e6 * tf / nf, 1e6 * tpsd, (tr / nr) / tpsd, 1e6 * ti / ni,
               kept,
               1e6 * tc / nc,
               (tr / nr) / (tc / nc));
        free(work);
    }
    printf("load average after: %.1f\n", loadavg());
    sb_shell_work_free(w);
    sb_shell_batch_free(bws[0]);
    sb_shell_batch_free(bws[1]);
    free(E);
    return sink == 12345.6789 ? 3 : 0;
}
