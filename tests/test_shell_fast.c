/* test_shell_fast.c — the fast shell kernel (sb_shell_elem.c,
 * sb_section_fast.c, sb_vmath.h; issue 30): agreement with the reference
 * kernel summed over the points, finite-difference gradient and Hessian at
 * random deformed states (StVK and denim, four bases), exact symmetry, the
 * section law and the vector expm1/log1p against libm, the PSD check and
 * the strain-space projection (PSD, exact where the element Hessian is),
 * bad input. */
#include "sb_test.h"
#include "test_shell_bases.h"
#include "sb_vmath.h"
#include "sb_shell_batch.h"   /* sb_section_fast_isa: the section at a given vector width */

#include <float.h>
#include <stdlib.h>

extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda, double *w,
                   double *work, const int *lwork, int *info);

/* smallest and largest eigenvalue of a symmetric n x n matrix */
static void eig_range(int n, const double *H, double *lmin, double *lmax)
{
    double *A = malloc(sizeof(double) * n * n), *lam = malloc(sizeof(double) * n);
    int lw = 64 * n, info;
    double *wk = malloc(sizeof(double) * lw);
    memcpy(A, H, sizeof(double) * n * n);
    dsyev_("N", "U", &n, A, &n, lam, wk, &lw, &info);
    *lmin = lam[0];
    *lmax = lam[n - 1];
    free(A);
    free(lam);
    free(wk);
}

static double maxabs(size_t n, const double *a)
{
    double m = 0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
    return m;
}

enum { B_BSPLINE, B_HERMITE, B_RANDOM40, B_RANDOMMAX, B_COUNT, B_RANDOM18 = B_COUNT };
static const char *bname[B_COUNT] = { "bspline", "hermite", "random40", "random64" };

typedef struct fcase {
    sb_material m;
    int nq;
    tb_basis tb[9];
    sb_shell_basis b[9];
    sb_shell_ref r[9];
    double Xq[3 * SB_SHELL_MAX_BASIS];
    int k;
} fcase;

static void href(double u, double v, double x[3], double xu[3], double xv[3], double xuv[3])
{
    x[0] = 0.5 * u + 0.1 * v;  x[1] = 0.4 * v; x[2] = 0.1 * u * u - 0.05 * v * v + 0.03 * u * v;
    xu[0] = 0.5;               xu[1] = 0;      xu[2] = 0.2 * u + 0.03 * v;
    xv[0] = 0.1;               xv[1] = 0.4;    xv[2] = -0.1 * v + 0.03 * u;
    xuv[0] = 0;                xuv[1] = 0;     xuv[2] = 0.03;
}

/* an element of 9 points (3 x 3 Gauss for the tensor bases, random points otherwise) */
static void make_case(fcase *c, int basis, int denim, double thickness, unsigned long long *s)
{
    memset(c, 0, sizeof *c);
    sb_material_spec sp;
    if (denim) {
        sb_material_spec_denim(&sp);
    } else {
        memset(&sp, 0, sizeof sp);
        sp.kind = SB_MAT_STVK;
        sp.young = 1.0e6;
        sp.poisson = 0.3;
    }
    sp.thickness = thickness;
    sp.density = 1.0;
    sb_material_init(&c->m, &sp, 0);
    double gx[3], gw[3];
    sb_gauss_legendre(3, gx, gw);
    c->nq = 9;
    for (int p = 0; p < 9; p++) {
        const double u = 0.5 + 0.5 * gx[p % 3], v = 0.5 + 0.5 * gx[p / 3];
        switch (basis) {
        case B_BSPLINE: tb_bspline(&c->tb[p], u, v); break;
        case B_HERMITE: tb_hermite(&c->tb[p], u, v); break;
        case B_RANDOM40: tb_random(&c->tb[p], 40, s); break;
        case B_RANDOM18: tb_random(&c->tb[p], 18, s); break;   /* k not a multiple of the padding */
        default: tb_random(&c->tb[p], SB_SHELL_MAX_BASIS, s); break;
        }
        c->b[p] = tb_view(&c->tb[p]);
    }
    c->k = c->b[0].k;
    if (basis == B_BSPLINE)
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++) {
                double *X = c->Xq + 3 * (i + 4 * j);
                X[0] = 0.4 * i + 0.05 * j;
                X[1] = 0.35 * j;
                X[2] = 0.06 * sin(1.3 * i) * cos(0.7 * j);
            }
    else if (basis == B_HERMITE)
        tb_hermite_dofs(href, c->Xq);
    else
        for (int i = 0; i < 3 * c->k; i++) c->Xq[i] = tb_rand(s, -1, 1);
    for (int p = 0; p < 9; p++) sb_shell_ref_init_basis(&c->r[p], &c->b[p], c->Xq, 0.35, 0.25 * gw[p % 3] * gw[p / 3]);
}

static void deform(const fcase *c, int basis, double amp, unsigned long long *s, double *q)
{
    const double a = basis >= B_RANDOM40 ? 0.3 * amp : amp;   /* B_RANDOM18 too */
    double R[9], ax[3] = { tb_rand(s, -1, 1), tb_rand(s, -1, 1), tb_rand(s, -1, 1) }, t0[3] = { 0, 0, 0 };
    const double nrm = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    for (int i = 0; i < 3; i++) ax[i] /= nrm;
    tb_rotation(ax, tb_rand(s, -3, 3), R);
    for (int i = 0; i < 3 * c->k; i++) q[i] = c->Xq[i] + a * tb_rand(s, -1, 1);
    tb_apply(R, t0, q, q, c->k);
}

static double ref_energy(const fcase *c, const double *q, double *g, double *H, sb_hess_kind kind, sb_shell_work *w)
{
    double e = 0;
    for (int p = 0; p < c->nq; p++) e += sb_shell_energy(&c->m, &c->r[p], &c->b[p], q, g, H, kind, w);
    return e;
}

/* the fast element against the reference summed over its points */
SB_TEST(fast_matches_reference)
{
    unsigned long long s = 2024;
    sb_shell_work *w = sb_shell_work_new();
    sb_shell_batch *bw = sb_shell_batch_new(SB_SHELL_MAX_BASIS, 9);
    const size_t nmax = 3 * SB_SHELL_MAX_BASIS;
    double *g1 = malloc(sizeof(double) * nmax), *g2 = malloc(sizeof(double) * nmax);
    double *H1 = malloc(sizeof(double) * nmax * nmax), *H2 = malloc(sizeof(double) * nmax * nmax);
    for (int basis = 0; basis < B_COUNT; basis++)
        for (int denim = 0; denim < 2; denim++)
            for (int kind = 0; kind < 2; kind++) {
                fcase c;
                make_case(&c, basis, denim, denim ? 0.05 : 0.3, &s);
                const int n = 3 * c.k;
                double q[3 * SB_SHELL_MAX_BASIS];
                deform(&c, basis, denim ? 0.03 : 0.08, &s, q);
                memset(g1, 0, sizeof(double) * n);
                memset(g2, 0, sizeof(double) * n);
                memset(H1, 0, sizeof(double) * n * n);
                memset(H2, 0, sizeof(double) * n * n);
                const double e1 = ref_energy(&c, q, g1, H1, kind, w);
                const double e2 = sb_shell_element(&c.m, c.nq, c.r, c.b, q, g2, H2, kind, bw);
                double dg = 0, dh = 0, asym = 0;
                for (int i = 0; i < n; i++) dg = fmax(dg, fabs(g1[i] - g2[i]));
                for (int i = 0; i < n * n; i++) dh = fmax(dh, fabs(H1[i] - H2[i]));
                for (int i = 0; i < n; i++)
                    for (int j = 0; j < n; j++) asym = fmax(asym, fabs(H2[i * n + j] - H2[j * n + i]));
                CHECK_MSG(fabs(e1 - e2) <= 1e-12 * fabs(e1) && dg <= 1e-12 * maxabs(n, g1) &&
                              dh <= 1e-12 * maxabs((size_t)n * n, H1),
                          "%s %s kind %d: e %.3g, g %.3g, H %.3g relative", bname[basis], denim ? "denim" : "stvk",
                          kind, fabs(e1 - e2) / fabs(e1), dg / maxabs(n, g1), dh / maxabs((size_t)n * n, H1));
                CHECK_MSG(asym == 0.0, "not exactly symmetric: %.3g", asym);
                /* energy only and energy + gradient: the same energy and gradient */
                double g3[3 * SB_SHELL_MAX_BASIS] = { 0 };
                CHECK(sb_shell_element(&c.m, c.nq, c.r, c.b, q, NULL, NULL, kind, bw) == e2);
                CHECK(sb_shell_element(&c.m, c.nq, c.r, c.b, q, g3, NULL, kind, bw) == e2);
                CHECK(memcmp(g3, g2, sizeof(double) * n) == 0);
                /* sb_shell_element_into overwrites every entry: on a matrix of
                 * NaN it gives the bits of sb_shell_element on a zeroed one */
                for (int i = 0; i < n * n; i++) H1[i] = NAN;
                memset(g3, 0, sizeof(double) * n);
                CHECK(sb_shell_element_into(&c.m, c.nq, c.r, c.b, q, g3, H1, kind, bw) == e2);
                CHECK_MSG(memcmp(H1, H2, sizeof(double) * n * n) == 0 && memcmp(g3, g2, sizeof(double) * n) == 0,
                          "%s %s kind %d: sb_shell_element_into differs from sb_shell_element", bname[basis],
                          denim ? "denim" : "stvk", kind);
            }
    free(g1);
    free(g2);
    free(H1);
    free(H2);
    sb_shell_work_free(w);
    sb_shell_batch_free(bw);
}

/* relative FD errors of the fast gradient (from energies) and Hessian (from gradients) */
static void fd_err(const fcase *c, const double *q, double h, sb_shell_batch *bw, double *eg, double *eh)
{
    const int n = 3 * c->k;
    double *x = malloc(sizeof(double) * n), *g = calloc(n, sizeof(double)), *H = calloc((size_t)n * n, sizeof(double));
    double *gp = malloc(sizeof(double) * n), *gm = malloc(sizeof(double) * n);
    memcpy(x, q, sizeof(double) * n);
    sb_shell_element(&c->m, c->nq, c->r, c->b, q, g, H, SB_HESS_EXACT, bw);
    double ge = 0, he = 0;
    for (int j = 0; j < n; j++) {
        memset(gp, 0, sizeof(double) * n);
        memset(gm, 0, sizeof(double) * n);
        x[j] = q[j] + h;
        const double fp = sb_shell_element(&c->m, c->nq, c->r, c->b, x, gp, NULL, SB_HESS_EXACT, bw);
        x[j] = q[j] - h;
        const double fm = sb_shell_element(&c->m, c->nq, c->r, c->b, x, gm, NULL, SB_HESS_EXACT, bw);
        x[j] = q[j];
        ge = fmax(ge, fabs((fp - fm) / (2 * h) - g[j]));
        for (int i = 0; i < n; i++) he = fmax(he, fabs((gp[i] - gm[i]) / (2 * h) - H[(size_t)i * n + j]));
    }
    *eg = ge / maxabs(n, g);
    *eh = he / maxabs((size_t)n * n, H);
    free(x);
    free(g);
    free(H);
    free(gp);
    free(gm);
}

/* central differences over four steps h0 4^-s: O(h^2) decay (>= 8x per step
 * until the round-off floor) and the smallest-step error below 1e-5, as
 * tests/test_shell_fd.c asserts for the reference kernel */
static void run_fd(sb_test_state *T, int denim, double thickness, double amp, int nstates)
{
    unsigned long long s = 777 + 13 * denim + (unsigned long long)(thickness * 1000);
    sb_shell_batch *bw = sb_shell_batch_new(SB_SHELL_MAX_BASIS, 9);
    for (int basis = 0; basis < B_COUNT; basis++) {
        fcase c;
        make_case(&c, basis, denim, thickness, &s);
        for (int st = 0; st < (basis == B_RANDOMMAX ? 1 : nstates); st++) {
            double q[3 * SB_SHELL_MAX_BASIS], eg[4], eh[4];
            deform(&c, basis, amp, &s, q);
            for (int k = 0; k < 4; k++) fd_err(&c, q, 1e-3 / pow(4.0, k), bw, &eg[k], &eh[k]);
            for (int k = 0; k < 3; k++) {
                CHECK_MSG(eg[k + 1] <= eg[k] / 8 || eg[k + 1] < 1e-9, "%s %s: gradient FD %.3g -> %.3g", bname[basis],
                          denim ? "denim" : "stvk", eg[k], eg[k + 1]);
                CHECK_MSG(eh[k + 1] <= eh[k] / 8 || eh[k + 1] < 1e-9, "%s %s: Hessian FD %.3g -> %.3g", bname[basis],
                          denim ? "denim" : "stvk", eh[k], eh[k + 1]);
            }
            CHECK_MSG(eg[3] < 1e-5 && eh[3] < 1e-5, "%s %s: FD errors %.3g %.3g", bname[basis],
                      denim ? "denim" : "stvk", eg[3], eh[3]);
        }
    }
    sb_shell_batch_free(bw);
}

SB_TEST(fast_fd_stvk) { run_fd(T, 0, 0.8, 0.08, 2); }
SB_TEST(fast_fd_denim) { run_fd(T, 1, 0.05, 0.03, 2); }

/* the section law: StVK by its moments, denim with vector exp/log */
SB_TEST(section_fast_matches)
{
    unsigned long long s = 99;
    for (int mat = 0; mat < 2; mat++)
        for (int beyond = 0; beyond < 2; beyond++)
            for (int nt = 0; nt <= 8; nt += nt ? 1 : 2) {
                sb_material_spec sp;
                if (mat) {
                    sb_material_spec_denim(&sp);
                    sp.denim.beyond_fit = beyond;
                } else {
                    memset(&sp, 0, sizeof sp);
                    sp.kind = SB_MAT_STVK;
                    sp.young = 1e6;
                    sp.poisson = 0.3;
                    sp.thickness = 1e-3;
                }
                sb_material m;
                if (sb_material_init(&m, &sp, nt) != SB_OK) continue;
                const double kmax = mat ? 9.03e6 : 1e6, h = sp.thickness;
                double worst[3] = { 0, 0, 0 };
                int nan1 = 0, nan_mismatch = 0;
                for (int it = 0; it < 3000; it++) {
                    const double sc = it % 3 == 0 ? 0.01 : it % 3 == 1 ? 0.1 : 0.4;
                    double A[3], B[3], a1[3], b1[3], c1[36], a2[3], b2[3], c2[36];
                    for (int i = 0; i < 3; i++) {
                        A[i] = tb_rand(&s, -sc, sc);
                        B[i] = tb_rand(&s, -sc, sc) * 0.3 / h;
                    }
                    const double e1 = sb_shell_section(&m, A, B, a1, b1, c1);
                    const double e2 = sb_shell_section_fast(&m, A, B, a2, b2, c2);
                    if (isnan(e1) || isnan(e2)) {
                        nan1++;
                        nan_mismatch += isnan(e1) != isnan(e2);
                        continue;
                    }
                    /* scales: energy and forces of the strains' magnitude */
                    double a2n = 0, gs = 0, cs = maxabs(36, c1);
                    for (int i = 0; i < 3; i++) {
                        a2n += A[i] * A[i] + h * h * B[i] * B[i];
                        gs = fmax(gs, fmax(fabs(a1[i]), fabs(b1[i])));
                    }
                    worst[0] = fmax(worst[0], fabs(e1 - e2) / fmax(fabs(e1), kmax * h * a2n));
                    for (int i = 0; i < 3; i++) worst[1] = fmax(worst[1], fmax(fabs(a1[i] - a2[i]), fabs(b1[i] - b2[i])) / gs);
                    for (int i = 0; i < 36; i++) worst[2] = fmax(worst[2], fabs(c1[i] - c2[i]) / cs);
                }
                CHECK_MSG(nan_mismatch == 0, "mat %d beyond %d: %d NaN mismatches", mat, beyond, nan_mismatch);
                CHECK_MSG(worst[0] < 1e-11 && worst[1] < 1e-11 && worst[2] < 1e-11,
                          "mat %d beyond %d n_thick %d: e %.3g g %.3g C %.3g", mat, beyond, m.n_thick, worst[0],
                          worst[1], worst[2]);
                if (mat && beyond) CHECK(nan1 > 0);   /* the admissible range was met */
            }
}

static double ulp_of(double x) { return fabs(nextafter(x, INFINITY) - x); }

/* sb_vexpm1 / sb_vlog1p against libm over their ranges, and special values */
SB_TEST(vmath_accuracy)
{
    unsigned long long s = 5;
    double we = 0, wl = 0;
    for (int it = 0; it < 200000; it++) {
        double x[SB_VL], u[SB_VL];
        for (int l = 0; l < SB_VL; l++) {
            const double a = tb_rand(&s, 0, 1);
            const int reg = (it + l) % 4;
            x[l] = reg == 0 ? (a - 0.5) * 1e-6 : reg == 1 ? (a - 0.5) * 2 : reg == 2 ? (a - 0.5) * 80 : -40 + a * 749;
            u[l] = reg == 0 ? (a - 0.5) * 1e-8 : reg == 1 ? a * 2 - 0.999 : reg == 2 ? pow(10, a * 40 - 20) : a * 100;
        }
        const sb_vd E = sb_vexpm1(sb_vload(x)), L = sb_vlog1p(sb_vload(u));
        for (int l = 0; l < SB_VL; l++) {
            const double re = expm1(x[l]), rl = log1p(u[l]);
            if (isfinite(re)) we = fmax(we, fabs(E[l] - re) / ulp_of(re));
            wl = fmax(wl, fabs(L[l] - rl) / ulp_of(rl));
        }
    }
    CHECK_MSG(we <= 3 && wl <= 3, "expm1 %.2f ulp, log1p %.2f ulp", we, wl);
    const double sx[8] = { -1, -2, NAN, INFINITY, 0, -41, 710, 1e-300 };
    for (int i = 0; i < 8; i += SB_VL) {
        double a[8];
        for (int l = 0; l < SB_VL; l++) a[l] = sx[(i + l) % 8];
        const sb_vd E = sb_vexpm1(sb_vload(a)), L = sb_vlog1p(sb_vload(a));
        for (int l = 0; l < SB_VL; l++) {
            const double re = expm1(a[l]), rl = log1p(a[l]);
            CHECK_MSG((isnan(re) && isnan(E[l])) || E[l] == re, "expm1(%g) = %g, libm %g", a[l], E[l], re);
            CHECK_MSG((isnan(rl) && isnan(L[l])) || L[l] == rl, "log1p(%g) = %g, libm %g", a[l], L[l], rl);
        }
    }
}

/* sb_psd_check: PSD matrices with a null space pass, indefinite ones fail */
SB_TEST(psd_check_basic)
{
    const int n = 24;
    unsigned long long s = 8;
    double *V = malloc(sizeof(double) * n * n), *H = malloc(sizeof(double) * n * n), *w = malloc(sizeof(double) * n * n);
    for (int i = 0; i < n * n; i++) V[i] = tb_rand(&s, -1, 1);
    for (int pass = 0; pass < 3; pass++) {
        /* H = sum_k lambda_k v_k v_k^T, rank 18 (six zero eigenvalues) */
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                double sum = 0;
                for (int k = 0; k < 18; k++) {
                    const double lam = pass == 2 && k == 3 ? -1e-6 : 1.0 + k;
                    sum += lam * V[k * n + i] * V[k * n + j];
                }
                H[i * n + j] = sum;
            }
        for (int i = 0; i < n; i++)
            for (int j = 0; j < i; j++) H[i * n + j] = H[j * n + i];
        if (pass == 1) H[5 * n + 5] -= 1e-3;   /* a negative direction */
        CHECK_EQ_INT(sb_psd_check(n, H, w), pass == 0);
    }
    H[0] = NAN;
    CHECK_EQ_INT(sb_psd_check(n, H, w), 0);
    CHECK_EQ_INT(sb_psd_check(0, H, w), 0);
    free(V);
    free(H);
    free(w);
}

/* kind PSD: the strain-space projection is PSD; sb_shell_element_psd keeps a
 * PSD element Hessian bit-for-bit and projects an indefinite one */
SB_TEST(psd_strain_space)
{
    unsigned long long s = 31;
    sb_shell_batch *bw = sb_shell_batch_new(SB_SHELL_MAX_BASIS, 9);
    double *H = malloc(sizeof(double) * 192 * 192), *P = malloc(sizeof(double) * 192 * 192);
    double *Kx = calloc(192 * 192, sizeof(double)), *work = malloc(sizeof(double) * sb_psd_work_size(192));
    for (int denim = 0; denim < 2; denim++) {
        fcase c;
        make_case(&c, B_BSPLINE, denim, denim ? 0.01 : 0.01, &s);
        const int n = 3 * c.k;
        double q[48];
        int path = -1;
        /* rest: PSD (rigid modes at zero), kept exactly */
        memset(H, 0, sizeof(double) * n * n);
        sb_shell_element(&c.m, c.nq, c.r, c.b, c.Xq, NULL, H, SB_HESS_EXACT, bw);
        memset(P, 0, sizeof(double) * n * n);
        sb_shell_element_psd(&c.m, c.nq, c.r, c.b, c.Xq, NULL, P, Kx, 0, bw, work, &path);
        CHECK_EQ_INT(path, 0);
        CHECK(memcmp(P, H, sizeof(double) * n * n) == 0);
        /* compressed and bent: the exact Hessian is indefinite */
        for (int i = 0; i < n; i++) q[i] = c.Xq[i] * (i % 3 == 2 ? 1.0 : 0.93);
        for (int i = 2; i < n; i += 3) q[i] += 0.02 * tb_rand(&s, -1, 1);
        memset(H, 0, sizeof(double) * n * n);
        sb_shell_element(&c.m, c.nq, c.r, c.b, q, NULL, H, SB_HESS_EXACT, bw);
        double lmin, lmax;
        eig_range(n, H, &lmin, &lmax);
        CHECK_MSG(lmin < -1e-6 * lmax, "%s: the compressed element is not indefinite (%.3g / %.3g)",
                  denim ? "denim" : "stvk", lmin, lmax);
        CHECK_EQ_INT(sb_psd_check(n, H, work), 0);
        /* the projection alone */
        memset(P, 0, sizeof(double) * n * n);
        sb_shell_element(&c.m, c.nq, c.r, c.b, q, NULL, P, SB_HESS_PSD, bw);
        eig_range(n, P, &lmin, &lmax);
        CHECK_MSG(lmin >= -1e-12 * lmax, "%s: projected min eigenvalue %.3g of %.3g", denim ? "denim" : "stvk", lmin,
                  lmax);
        CHECK_EQ_INT(sb_psd_check(n, P, work), 1);
        /* through sb_shell_element_psd: the exact Hessian minus the 3-slot
         * difference equals the projection computed from scratch */
        memset(H, 0, sizeof(double) * n * n);
        double gq[48] = { 0 }, gr[48] = { 0 };
        const double e1 = sb_shell_element_psd(&c.m, c.nq, c.r, c.b, q, gq, H, Kx, 0, bw, work, &path);
        const double e2 = sb_shell_element(&c.m, c.nq, c.r, c.b, q, gr, NULL, SB_HESS_EXACT, bw);
        CHECK_EQ_INT(path, 1);
        CHECK(e1 == e2 && memcmp(gq, gr, sizeof gq) == 0);
        double dmax = 0;
        for (int i = 0; i < n * n; i++) dmax = fmax(dmax, fabs(H[i] - P[i]));
        CHECK_MSG(dmax <= 1e-12 * maxabs((size_t)n * n, P), "%s: difference path vs projection %.3g of %.3g",
                  denim ? "denim" : "stvk", dmax, maxabs((size_t)n * n, P));
        /* with a PSD other term (a penalty-like N N^T) */
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) Kx[i * n + j] = i % 3 == j % 3 ? 1e3 * c.tb[0].N[i / 3] * c.tb[0].N[j / 3] : 0.0;
        memset(H, 0, sizeof(double) * n * n);
        sb_shell_element_psd(&c.m, c.nq, c.r, c.b, q, NULL, H, Kx, 1, bw, work, &path);
        CHECK_EQ_INT(path, 1);
        eig_range(n, H, &lmin, &lmax);
        CHECK_MSG(lmin >= -1e-12 * lmax, "with Kx: min eigenvalue %.3g of %.3g", lmin, lmax);
        /* an indefinite other term: the whole element is clamped (eigenvalues) */
        for (int i = 0; i < n * n; i++) Kx[i] = -Kx[i];
        memset(H, 0, sizeof(double) * n * n);
        sb_shell_element_psd(&c.m, c.nq, c.r, c.b, q, NULL, H, Kx, 1, bw, work, &path);
        CHECK_EQ_INT(path, 2);
        eig_range(n, H, &lmin, &lmax);
        CHECK_MSG(lmin >= -1e-12 * lmax, "eigen clamp: min eigenvalue %.3g of %.3g", lmin, lmax);
        memset(Kx, 0, sizeof(double) * 192 * 192);
    }
    free(H);
    free(P);
    free(Kx);
    free(work);
    sb_shell_batch_free(bw);
}

/* The denim section law at every vector width this CPU runs gives the same
 * bits as at SSE2 (sb_section_denim.c: one lane per thickness point, sums in
 * the 2-lane order), for every rule size 1..8 (odd ones have a padding
 * lane), both continuations beyond the fit (beyond = NaN included), with
 * and without derivatives. */
SB_TEST(section_widths_same_bits)
{
    unsigned long long s = 4242;
    int compared = 0, nans = 0;
    for (int isa = SB_ISA_AVX2; isa < SB_ISA_COUNT; isa++) {
        if (!sb_shell_isa_supported((sb_shell_isa)isa)) continue;
        for (int beyond = 0; beyond < 2; beyond++)
            for (int nt = 1; nt <= 8; nt++) {
                sb_material_spec sp;
                sb_material_spec_denim(&sp);
                sp.denim.beyond_fit = beyond;
                sb_material m;
                if (sb_material_init(&m, &sp, nt) != SB_OK) continue;
                for (int it = 0; it < 400; it++) {
                    const double sc = it % 3 == 0 ? 0.01 : it % 3 == 1 ? 0.1 : 0.4;
                    double A[3], B[3], a0[3], b0[3], c0[36], a1[3], b1[3], c1[36];
                    for (int i = 0; i < 3; i++) {
                        A[i] = tb_rand(&s, -sc, sc);
                        B[i] = tb_rand(&s, -sc, sc) * 0.3 / sp.thickness;
                    }
                    const int with = it % 4;   /* 0: energy only, 1: + sA sB, 2-3: + C */
                    const double e0 = sb_section_fast_isa(SB_ISA_BASE, &m, A, B, with ? a0 : NULL, with ? b0 : NULL,
                                                          with > 1 ? c0 : NULL);
                    const double e1 = sb_section_fast_isa((sb_shell_isa)isa, &m, A, B, with ? a1 : NULL,
                                                          with ? b1 : NULL, with > 1 ? c1 : NULL);
                    nans += isnan(e0);
                    int same = memcmp(&e0, &e1, sizeof e0) == 0;
                    if (with) same = same && memcmp(a0, a1, sizeof a0) == 0 && memcmp(b0, b1, sizeof b0) == 0;
                    if (with > 1) same = same && memcmp(c0, c1, sizeof c0) == 0;
                    CHECK_MSG(same, "%s, n_thick %d, beyond_fit %d, case %d: not the same bits as %s",
                              sb_shell_isa_name((sb_shell_isa)isa), nt, beyond, it, sb_shell_isa_name(SB_ISA_BASE));
                    if (!same) return;
                    compared++;
                }
            }
    }
    printf("# %d section evaluations compared bit for bit (%d of them NaN: outside the fit)\n", compared, nans);
}

/* The products at every vector width this CPU runs (sb_elem_tile.c:
 * SSE2, AVX2, AVX-512) give the same bits: energy, gradient and Hessian of
 * kinds EXACT, PSEUDO and PSD, and sb_shell_element_psd's difference path
 * (its Gram product), for k = 16, 18 (padded), 40 and 64. */
SB_TEST(vector_widths_same_bits)
{
    const size_t nmax = 3 * SB_SHELL_MAX_BASIS;
    double *g0 = malloc(sizeof(double) * nmax), *g1 = malloc(sizeof(double) * nmax);
    double *H0 = malloc(sizeof(double) * nmax * nmax), *H1 = malloc(sizeof(double) * nmax * nmax);
    double *Kx = calloc(nmax * nmax, sizeof(double)), *work = malloc(sizeof(double) * sb_psd_work_size((int)nmax));
    sb_shell_batch *b0 = sb_shell_batch_new(SB_SHELL_MAX_BASIS, 9), *b1 = sb_shell_batch_new(SB_SHELL_MAX_BASIS, 9);
    CHECK(sb_shell_batch_set_isa(b0, SB_ISA_BASE) == SB_OK && sb_shell_batch_isa(b0) == SB_ISA_BASE);
    CHECK(sb_shell_batch_set_isa(b0, (sb_shell_isa)7) == SB_ERR_INPUT);
    CHECK(sb_shell_batch_isa(b1) == sb_shell_isa_best());
    int tested = 0;
    for (int isa = SB_ISA_AVX2; isa < SB_ISA_COUNT; isa++) {
        if (!sb_shell_isa_supported((sb_shell_isa)isa)) {
            CHECK(sb_shell_batch_set_isa(b1, (sb_shell_isa)isa) == SB_ERR_UNSUPPORTED);
            printf("# %s: not run by this CPU or not in this build, not compared\n", sb_shell_isa_name((sb_shell_isa)isa));
            continue;
        }
        CHECK(sb_shell_batch_set_isa(b1, (sb_shell_isa)isa) == SB_OK);
        unsigned long long s = 77;
        const int bases[5] = { B_BSPLINE, B_HERMITE, B_RANDOM18, B_RANDOM40, B_RANDOMMAX };
        for (int ib = 0; ib < 5; ib++)
            for (int denim = 0; denim < 2; denim++) {
                fcase c;
                make_case(&c, bases[ib], denim, denim ? 0.05 : 0.3, &s);
                const int n = 3 * c.k;
                double q[3 * SB_SHELL_MAX_BASIS];
                deform(&c, bases[ib], denim ? 0.03 : 0.08, &s, q);
                if (bases[ib] == B_BSPLINE) /* compressed: indefinite, so element_psd takes its difference path */
                    for (int i = 0; i < n; i++) q[i] = c.Xq[i] * (i % 3 == 2 ? 1.0 : 0.93);
                for (int kind = 0; kind < 4; kind++) {
                    memset(g0, 0, sizeof(double) * n);
                    memset(g1, 0, sizeof(double) * n);
                    memset(H0, 0, sizeof(double) * n * n);
                    memset(H1, 0, sizeof(double) * n * n);
                    double e0, e1;
                    int p0 = -1, p1 = -1;
                    if (kind < 3) {
                        const sb_hess_kind hk = kind == 0 ? SB_HESS_EXACT : kind == 1 ? SB_HESS_PSEUDO : SB_HESS_PSD;
                        e0 = sb_shell_element(&c.m, c.nq, c.r, c.b, q, g0, H0, hk, b0);
                        e1 = sb_shell_element(&c.m, c.nq, c.r, c.b, q, g1, H1, hk, b1);
                    } else {
                        e0 = sb_shell_element_psd(&c.m, c.nq, c.r, c.b, q, g0, H0, Kx, 0, b0, work, &p0);
                        e1 = sb_shell_element_psd(&c.m, c.nq, c.r, c.b, q, g1, H1, Kx, 0, b1, work, &p1);
                        CHECK_EQ_INT(p0, p1);
                        if (bases[ib] == B_BSPLINE) CHECK_EQ_INT(p1, 1);
                    }
                    CHECK_MSG(memcmp(&e0, &e1, sizeof e0) == 0 && memcmp(g0, g1, sizeof(double) * n) == 0 &&
                                  memcmp(H0, H1, sizeof(double) * n * n) == 0,
                              "%s, %s k = %d, %s, kind %d: not the same bits as %s", sb_shell_isa_name((sb_shell_isa)isa),
                              bases[ib] == B_RANDOM18 ? "random18" : bname[bases[ib]], c.k, denim ? "denim" : "stvk",
                              kind, sb_shell_isa_name(SB_ISA_BASE));
                    tested++;
                }
            }
    }
    printf("# %d element evaluations compared bit for bit against %s\n", tested, sb_shell_isa_name(SB_ISA_BASE));
    free(g0);
    free(g1);
    free(H0);
    free(H1);
    free(Kx);
    free(work);
    sb_shell_batch_free(b0);
    sb_shell_batch_free(b1);
}

SB_TEST(fast_bad_input)
{
    unsigned long long s = 3;
    fcase c;
    make_case(&c, B_BSPLINE, 0, 0.01, &s);
    sb_shell_batch *bw = sb_shell_batch_new(16, 9);
    double g[48] = { 0 };
    CHECK(isnan(sb_shell_element(NULL, c.nq, c.r, c.b, c.Xq, g, NULL, SB_HESS_EXACT, bw)));
    CHECK(isnan(sb_shell_element(&c.m, 10, c.r, c.b, c.Xq, g, NULL, SB_HESS_EXACT, bw)));   /* nq > nqmax */
    CHECK(isnan(sb_shell_element(&c.m, c.nq, c.r, c.b, c.Xq, g, NULL, SB_HESS_EXACT, NULL)));
    sb_shell_basis bb[9];
    memcpy(bb, c.b, sizeof bb);
    bb[4].k = 15;   /* points of different sizes */
    CHECK(isnan(sb_shell_element(&c.m, c.nq, c.r, bb, c.Xq, g, NULL, SB_HESS_EXACT, bw)));
    bb[4].k = 16;
    bb[4].N12 = NULL;
    CHECK(isnan(sb_shell_element(&c.m, c.nq, c.r, bb, c.Xq, g, NULL, SB_HESS_EXACT, bw)));
    sb_shell_batch *big = sb_shell_batch_new(40, 9);
    fcase c40;
    make_case(&c40, B_RANDOM40, 0, 0.01, &s);
    CHECK(isnan(sb_shell_element(&c40.m, c40.nq, c40.r, c40.b, c40.Xq, NULL, NULL, SB_HESS_EXACT, bw)));   /* k > kmax */
    CHECK(isfinite(sb_shell_element(&c40.m, c40.nq, c40.r, c40.b, c40.Xq, NULL, NULL, SB_HESS_EXACT, big)));
    CHECK(sb_shell_batch_new(0, 9) == NULL && sb_shell_batch_new(16, 0) == NULL &&
          sb_shell_batch_new(SB_SHELL_MAX_BASIS + 1, 9) == NULL);
    /* a degenerate current surface: non-finite energy, no crash */
    double q[48] = { 0 };
    CHECK(!isfinite(sb_shell_element(&c.m, c.nq, c.r, c.b, q, g, NULL, SB_HESS_EXACT, bw)));
    sb_shell_batch_free(bw);
    sb_shell_batch_free(big);
}

static const sb_test_case cases[] = {
    SB_CASE(fast_matches_reference),
    SB_CASE(fast_fd_stvk),
    SB_CASE(fast_fd_denim),
    SB_CASE(section_fast_matches),
    SB_CASE(vmath_accuracy),
    SB_CASE(psd_check_basic),
    SB_CASE(psd_strain_space),
    SB_CASE(section_widths_same_bits),
    SB_CASE(vector_widths_same_bits),
    SB_CASE(fast_bad_input),
    SB_END
};

int main(int argc, char **argv) { return sb_test_main(argc, argv, cases); }
