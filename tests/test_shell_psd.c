/* test_shell_psd.c — per-element PSD projection (sb_psd.c) and the external
 * potential (sb_shell_ext.c): gravity, dead and follower pressure. */
#include "sb_test.h"
#include "test_shell_bases.h"

#include <stdlib.h>

extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
                   double *w, double *work, const int *lwork, int *info);

/* eigenvalues (ascending) and, if V != NULL, eigenvectors (column-major) */
static void eig(int n, const double *H, double *lam, double *V)
{
    double *A = malloc(sizeof(double) * n * n);
    int lw = 64 * n, info;
    double *wk = malloc(sizeof(double) * lw);
    memcpy(A, H, sizeof(double) * n * n);
    dsyev_(V ? "V" : "N", "U", &n, A, &n, lam, wk, &lw, &info);
    if (V) memcpy(V, A, sizeof(double) * n * n);
    free(A);
    free(wk);
}

static double maxabs(int n, const double *a)
{
    double m = 0;
    for (int i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
    return m;
}

SB_TEST(psd_random_indefinite)
{
    const int n = 30;
    unsigned long long s = 41;
    double *H = malloc(sizeof(double) * n * n), *P = malloc(sizeof(double) * n * n);
    double *V = malloc(sizeof(double) * n * n), lam[30], lp[30];
    double *work = malloc(sizeof(double) * sb_psd_work_size(n));
    for (int i = 0; i < n; i++)
        for (int j = 0; j <= i; j++) H[i * n + j] = H[j * n + i] = tb_rand(&s, -1, 1);
    memcpy(P, H, sizeof(double) * n * n);
    CHECK_EQ_INT(sb_psd_project(n, P, work), SB_OK);
    eig(n, H, lam, V);
    CHECK(lam[0] < -0.5);   /* the test matrix is indefinite */
    eig(n, P, lp, NULL);
    const double nrm = fmax(fabs(lam[0]), fabs(lam[n - 1]));
    CHECK_MSG(lp[0] >= -1e-13 * nrm, "min eigenvalue after projection %.3g", lp[0]);
    /* eigenpairs: P v = max(lambda, 0) v */
    double err = 0;
    for (int j = 0; j < n; j++) {
        const double *v = V + j * n, l = fmax(lam[j], 0);
        for (int a = 0; a < n; a++) {
            double pv = 0;
            for (int b = 0; b < n; b++) pv += P[a * n + b] * v[b];
            err = fmax(err, fabs(pv - l * v[a]));
        }
    }
    CHECK_MSG(err < 1e-12 * nrm, "eigenpair error %.3g", err);
    /* symmetric and idempotent */
    double asym = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) asym = fmax(asym, fabs(P[i * n + j] - P[j * n + i]));
    CHECK(asym < 1e-14 * nrm);
    memcpy(H, P, sizeof(double) * n * n);
    CHECK_EQ_INT(sb_psd_project(n, P, work), SB_OK);
    double d = 0;
    for (int i = 0; i < n * n; i++) d = fmax(d, fabs(P[i] - H[i]));
    CHECK(d < 1e-12 * nrm);
    /* SPD input comes back bit-for-bit */
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double sum = 0;
            for (int k = 0; k < n; k++) sum += V[k * n + i] * V[k * n + j] * (1.0 + k);
            H[i * n + j] = sum;
        }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < i; j++) H[i * n + j] = H[j * n + i];
    memcpy(P, H, sizeof(double) * n * n);
    CHECK_EQ_INT(sb_psd_project(n, P, work), SB_OK);
    CHECK(memcmp(P, H, sizeof(double) * n * n) == 0);
    /* bad input */
    P[7] = NAN;
    CHECK_EQ_INT(sb_psd_project(n, P, work), SB_NONFINITE);
    CHECK_EQ_INT(sb_psd_project(0, P, work), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_psd_project(n, NULL, work), SB_ERR_INPUT);
    CHECK(sb_psd_work_size(0) == 0);
    free(H);
    free(P);
    free(V);
    free(work);
}

/* element Hessian of a bicubic B-spline element, 3x3 Gauss points */
static void element_hessian(const sb_material *m, const double *Xq, const double *q, double *H, sb_shell_work *w)
{
    double gx[3], gw[3];
    sb_gauss_legendre(3, gx, gw);
    memset(H, 0, sizeof(double) * 48 * 48);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            tb_basis b;
            tb_bspline(&b, 0.5 + 0.5 * gx[i], 0.5 + 0.5 * gx[j]);
            sb_shell_basis v = tb_view(&b);
            sb_shell_ref r;
            sb_shell_ref_init_basis(&r, &v, Xq, 0.3, 0.25 * gw[i] * gw[j]);
            sb_shell_energy(m, &r, &v, q, NULL, H, SB_HESS_EXACT, w);
        }
}

SB_TEST(psd_element_hessian)
{
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    sp.thickness = 0.01;
    sb_material m;
    sb_material_init(&m, &sp, 0);
    sb_shell_work *w = sb_shell_work_new();
    double Xq[48], q[48];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *X = Xq + 3 * (i + 4 * j);
            X[0] = 0.1 * i;
            X[1] = 0.1 * j;
            X[2] = 0.01 * (i - 1.5) * (j - 1.5);
        }
    double H[48 * 48], P[48 * 48];
    double lam[48], work_[48 + 48 * 48 + 34 * 48];
    CHECK(sb_psd_work_size(48) <= sizeof work_ / sizeof work_[0]);
    /* rest state: PSD (rigid modes at zero): the projection changes nothing
     * beyond roundoff of the zero eigenvalues */
    element_hessian(&m, Xq, Xq, H, w);
    memcpy(P, H, sizeof H);
    CHECK_EQ_INT(sb_psd_project(48, P, work_), SB_OK);
    const double nrm = maxabs(48 * 48, H);
    double d = 0;
    for (int i = 0; i < 48 * 48; i++) d = fmax(d, fabs(P[i] - H[i]));
    CHECK_MSG(d <= 1e-12 * nrm, "rest Hessian changed by %.3g of %.3g", d, nrm);
    /* compressed state: the exact Hessian is indefinite, the projection is not */
    for (int i = 0; i < 48; i++) q[i] = Xq[i] * (i % 3 == 2 ? 1.0 : 0.93);
    element_hessian(&m, Xq, q, H, w);
    eig(48, H, lam, NULL);
    CHECK(lam[0] < -1e-6 * lam[47]);
    memcpy(P, H, sizeof H);
    CHECK_EQ_INT(sb_psd_project(48, P, work_), SB_OK);
    eig(48, P, lam, NULL);
    CHECK_MSG(lam[0] >= -1e-12 * lam[47], "projected min eigenvalue %.3g", lam[0]);
    sb_shell_work_free(w);
}

/* ---- external potential ------------------------------------------------------- */

SB_TEST(gravity_and_dead_pressure)
{
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    sb_material m;
    sb_material_init(&m, &sp, 0);
    tb_basis b;
    tb_bspline(&b, 0.3, 0.7);
    sb_shell_basis v = tb_view(&b);
    double Xq[48], q[48], g[48];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *X = Xq + 3 * (i + 4 * j);
            X[0] = 0.2 * i;
            X[1] = 0.25 * j;
            X[2] = 0.02 * i * j;
        }
    unsigned long long s = 3;
    for (int i = 0; i < 48; i++) q[i] = Xq[i] + 0.05 * tb_rand(&s, -1, 1);
    sb_shell_ref r;
    sb_shell_ref_init_basis(&r, &v, Xq, 0, 0.4);
    const double gv[3] = { 0, 0, -9.81 }, p = 250.0;
    double y[6][3];
    tb_jet(&b, q, y);
    memset(g, 0, sizeof g);
    double e = sb_shell_external(&m, &r, &v, q, gv, 0.0, 0, g, NULL);
    CHECK_REL(e, -m.density * r.dA * (gv[2] * y[0][2]), 1e-13);
    /* B-splines are a partition of unity: the nodal forces sum to rho g dA */
    double fz = 0;
    for (int I = 0; I < 16; I++) fz -= g[3 * I + 2];
    CHECK_REL(fz, m.density * gv[2] * r.dA, 1e-13);
    /* dead pressure along the reference normal */
    memset(g, 0, sizeof g);
    e = sb_shell_external(&m, &r, &v, q, NULL, p, 0, g, NULL);
    const double nx = r.normal[0] * y[0][0] + r.normal[1] * y[0][1] + r.normal[2] * y[0][2];
    CHECK_REL(e, -p * r.dA * nx, 1e-13);
    double f[3] = { 0, 0, 0 };
    for (int I = 0; I < 16; I++)
        for (int c = 0; c < 3; c++) f[c] -= g[3 * I + c];
    for (int c = 0; c < 3; c++) CHECK_NEAR(f[c], p * r.dA * r.normal[c], 1e-12 * p * r.dA);
    /* bad input */
    CHECK(isnan(sb_shell_external(&m, &r, NULL, q, gv, 0, 0, NULL, NULL)));
    sb_shell_basis nb = v;
    nb.N = NULL;
    CHECK(isnan(sb_shell_external(&m, &r, &nb, q, gv, 0, 0, NULL, NULL)));
}

static double follower_energy(const sb_material *m, const sb_shell_ref *r, const sb_shell_basis *v,
                              const double *q, double *g, double *H)
{
    const double gv[3] = { 0.3, 0, -9.81 };
    return sb_shell_external(m, r, v, q, gv, 1.5e3, 1, g, H);
}

SB_TEST(follower_pressure_fd)
{
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    sb_material m;
    sb_material_init(&m, &sp, 0);
    tb_basis b;
    tb_bspline(&b, 0.62, 0.41);
    sb_shell_basis v = tb_view(&b);
    double Xq[48], q[48], x[48], g[48], gp[48], gm[48];
    double H[48 * 48];
    unsigned long long s = 8;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *X = Xq + 3 * (i + 4 * j);
            X[0] = 0.2 * i;
            X[1] = 0.25 * j;
            X[2] = 0.03 * i * i;
        }
    for (int i = 0; i < 48; i++) q[i] = Xq[i] + 0.05 * tb_rand(&s, -1, 1);
    sb_shell_ref r;
    sb_shell_ref_init_basis(&r, &v, Xq, 0, 0.4);
    memset(g, 0, sizeof g);
    memset(H, 0, sizeof H);
    follower_energy(&m, &r, &v, q, g, H);
    memcpy(x, q, sizeof x);
    /* energy is cubic in q: central differences are exact up to roundoff for
     * the gradient's O(h^2) term only through the third derivative -> check at
     * two steps that the error falls as h^2 or sits at roundoff */
    double eg[2] = { 0, 0 }, eh[2] = { 0, 0 };
    for (int st = 0; st < 2; st++) {
        const double h = st ? 1e-4 : 1e-3;
        for (int j = 0; j < 48; j++) {
            memset(gp, 0, sizeof gp);
            memset(gm, 0, sizeof gm);
            x[j] = q[j] + h;
            const double fp = follower_energy(&m, &r, &v, x, gp, NULL);
            x[j] = q[j] - h;
            const double fm = follower_energy(&m, &r, &v, x, gm, NULL);
            x[j] = q[j];
            eg[st] = fmax(eg[st], fabs((fp - fm) / (2 * h) - g[j]));
            for (int i = 0; i < 48; i++) eh[st] = fmax(eh[st], fabs((gp[i] - gm[i]) / (2 * h) - H[i * 48 + j]));
        }
        eg[st] /= maxabs(48, g);
        eh[st] /= maxabs(48 * 48, H);
    }
    CHECK_MSG(eg[1] < 1e-9 && (eg[1] < eg[0] / 50 || eg[1] < 1e-12), "follower gradient FD %.3g %.3g", eg[0], eg[1]);
    CHECK_MSG(eh[1] < 1e-9, "follower Hessian FD %.3g %.3g", eh[0], eh[1]);
    double asym = 0;
    for (int i = 0; i < 48; i++)
        for (int j = 0; j < 48; j++) asym = fmax(asym, fabs(H[i * 48 + j] - H[j * 48 + i]));
    CHECK(asym < 1e-14 * maxabs(48 * 48, H));
    /* dead pressure has no Hessian */
    memset(H, 0, sizeof H);
    sb_shell_external(&m, &r, &v, q, NULL, 1e3, 0, NULL, H);
    CHECK(maxabs(48 * 48, H) == 0.0);
}

/* sphere chart jets (theta, phi) */
static void sphere(double R, double th, double ph, double y[6][3])
{
    const double st = sin(th), ct = cos(th), sp = sin(ph), cp = cos(ph);
    const double x[3] = { R * st * cp, R * st * sp, R * ct };
    const double xt[3] = { R * ct * cp, R * ct * sp, -R * st };
    const double xp[3] = { -R * st * sp, R * st * cp, 0 };
    const double xtt[3] = { -x[0], -x[1], -x[2] };
    const double xtp[3] = { -R * ct * sp, R * ct * cp, 0 };
    const double xpp[3] = { -R * st * cp, -R * st * sp, 0 };
    memcpy(y[0], x, sizeof x);
    memcpy(y[1], xt, sizeof x);
    memcpy(y[2], xp, sizeof x);
    memcpy(y[3], xtt, sizeof x);
    memcpy(y[4], xtp, sizeof x);
    memcpy(y[5], xpp, sizeof x);
}

SB_TEST(follower_pressure_closed_sphere)
{
    /* On a closed surface E = -p V and the variational force equals p n da
     * (boundary terms vanish).  Sphere by (theta, phi): Gauss in theta,
     * trapezoid in phi (periodic), Taylor jet basis at each point. */
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    sb_material m;
    sb_material_init(&m, &sp, 0);
    tb_basis b;
    tb_taylor(&b);
    sb_shell_basis v = tb_view(&b);
    const double R = 0.7, p = 2.0e3, pi = 3.14159265358979323846;
    const int nt = 8, nph = 32, ns = 4;   /* ns theta sub-intervals of nt Gauss points */
    double gx[8], gw[8];
    sb_gauss_legendre(nt, gx, gw);
    double e = 0, lhs = 0, rhs = 0;
    int bad_ref = 0;
    for (int is = 0; is < ns; is++)
        for (int i = 0; i < nt; i++)
            for (int j = 0; j < nph; j++) {
                const double th = pi * (is + 0.5 + 0.5 * gx[i]) / ns, ph = 2 * pi * j / nph;
                const double wt = 0.5 * pi / ns * gw[i] * 2 * pi / nph;
                double y[6][3], g[18] = { 0 };
                sphere(R, th, ph, y);
                sb_shell_ref r;
                bad_ref += sb_shell_ref_init(&r, y[1], y[2], y[3], y[4], y[5], 0, wt) != SB_OK;
                e += sb_shell_external(&m, &r, &v, &y[0][0], NULL, p, 1, g, NULL);
                /* virtual displacement f(x) = (x0^2, x0 x1, sin x2) and its first jet */
                const double *x = y[0];
                const double f[3] = { x[0] * x[0], x[0] * x[1], sin(x[2]) };
                double jf[18] = { 0 };
                memcpy(jf, f, sizeof f);
                for (int a = 1; a <= 2; a++) {
                    const double *t = y[a];
                    jf[3 * a + 0] = 2 * x[0] * t[0];
                    jf[3 * a + 1] = x[1] * t[0] + x[0] * t[1];
                    jf[3 * a + 2] = cos(x[2]) * t[2];
                }
                for (int c = 0; c < 18; c++) lhs += g[c] * jf[c];
                /* -p int n . f da, n da = x_theta x x_phi dtheta dphi */
                double c[3];
                c[0] = y[1][1] * y[2][2] - y[1][2] * y[2][1];
                c[1] = y[1][2] * y[2][0] - y[1][0] * y[2][2];
                c[2] = y[1][0] * y[2][1] - y[1][1] * y[2][0];
                rhs -= p * wt * (c[0] * f[0] + c[1] * f[1] + c[2] * f[2]);
            }
    CHECK_EQ_INT(bad_ref, 0);
    CHECK_REL(e, -p * 4.0 / 3.0 * pi * R * R * R, 1e-10);
    CHECK_REL(lhs, rhs, 1e-8);
    CHECK(fabs(rhs) > 1e-3 * p);   /* the check is not 0 = 0 */
}

static const sb_test_case cases[] = {
    SB_CASE(psd_random_indefinite),
    SB_CASE(psd_element_hessian),
    SB_CASE(gravity_and_dead_pressure),
    SB_CASE(follower_pressure_fd),
    SB_CASE(follower_pressure_closed_sphere),
    SB_END
};

int main(int argc, char **argv)
{
    return sb_test_main(argc, argv, cases);
}
