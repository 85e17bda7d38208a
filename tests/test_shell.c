/* test_shell.c — the Kirchhoff–Love kernel against closed forms: rigid
 * motions, BHEM Eq. (7) with 2 thickness points, uniaxial stretch, pure
 * bending into a cylinder, denim small-strain stiffness along warp and weft,
 * warp-frame handling, bad input.  (Finite differences: test_shell_fd.c;
 * PSD projection and external loads: test_shell_psd.c.) */
#include "sb_test.h"
#include "test_shell_bases.h"

#include <stdlib.h>

static sb_material mat_stvk(double Y, double nu, double h, int n_thick)
{
    sb_material_spec s;
    memset(&s, 0, sizeof s);
    s.kind = SB_MAT_STVK;
    s.young = Y;
    s.poisson = nu;
    s.thickness = h;
    s.density = 0.3;
    sb_material m;
    sb_material_init(&m, &s, n_thick);
    return m;
}

static sb_material mat_denim(void)
{
    sb_material_spec s;
    sb_material_spec_denim(&s);
    sb_material m;
    sb_material_init(&m, &s, 0);
    return m;
}

/* flat B-spline control net with spacing (hx, hy), optionally curved in z */
static void bspline_net(double *Xq, double hx, double hy, double bump)
{
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *X = Xq + 3 * (i + 4 * j);
            X[0] = hx * i;
            X[1] = hy * j;
            X[2] = bump * ((i - 1.5) * (i - 1.5) - 0.5 * (j - 1.5) * (j - 1.5));
        }
}

static void hmap(double u, double v, double x[3], double xu[3], double xv[3], double xuv[3])
{
    x[0] = 0.3 * u + 0.05 * v;  x[1] = 0.25 * v + 0.02 * u * v; x[2] = 0.04 * u * u + 0.02 * v * v;
    xu[0] = 0.3;                xu[1] = 0.02 * v;               xu[2] = 0.08 * u;
    xv[0] = 0.05;               xv[1] = 0.25 + 0.02 * u;        xv[2] = 0.04 * v;
    xuv[0] = 0;                 xuv[1] = 0.02;                  xuv[2] = 0;
}

/* ---- rigid motions --------------------------------------------------------- */

/* which dofs are positions (translate with a rigid motion): B-spline all,
 * Hermite the value dofs (4c + 0), Taylor the first */
static int is_position(int basis, int I)
{
    return basis == 0 ? 1 : basis == 1 ? (I % 4 == 0) : (I == 0);
}

SB_TEST(rigid_motions)
{
    unsigned long long s = 17;
    sb_shell_work *w = sb_shell_work_new();
    for (int mk = 0; mk < 2; mk++) {
        sb_material m = mk ? mat_denim() : mat_stvk(1e6, 0.3, 0.01, 0);
        for (int basis = 0; basis < 3; basis++) {
            tb_basis b;
            double Xq[48], q[48], q2[48], g[48], g2[48];
            if (basis == 0) {
                tb_bspline(&b, 0.37, 0.61);
                bspline_net(Xq, 0.3, 0.25, 0.02);
            } else if (basis == 1) {
                tb_hermite(&b, 0.37, 0.61);
                tb_hermite_dofs(hmap, Xq);
            } else {
                tb_taylor(&b);
                const double y[18] = { 0.1, 0.2, 0.3, 1, 0.1, 0, 0.2, 0.9, 0.1, 0, 0.1, 1.5, 0.2, 0, 0.3, 0, 0.1, -0.7 };
                memcpy(Xq, y, sizeof y);
            }
            const int k = b.k;
            sb_shell_basis v = tb_view(&b);
            sb_shell_ref r;
            CHECK_EQ_INT(sb_shell_ref_init_basis(&r, &v, Xq, 0.4, 0.3), SB_OK);
            /* rest state: zero energy and gradient */
            memset(g, 0, sizeof g);
            double e = sb_shell_energy(&m, &r, &v, Xq, g, NULL, SB_HESS_EXACT, w);
            CHECK_NEAR(e, 0.0, 1e-20);
            double gmax = 0;
            for (int i = 0; i < 3 * k; i++) gmax = fmax(gmax, fabs(g[i]));
            CHECK_MSG(gmax < 1e-9, "rest gradient %.3g (basis %d)", gmax, basis);
            /* rigid motion of the rest state */
            double R[9], ax[3] = { 0.48, -0.6, 0.64 };
            const double t[3] = { 0.3, -1.2, 2.0 };
            tb_rotation(ax, 1.1, R);
            for (int I = 0; I < k; I++)
                for (int i = 0; i < 3; i++)
                    q[3 * I + i] = R[3 * i] * Xq[3 * I] + R[3 * i + 1] * Xq[3 * I + 1] + R[3 * i + 2] * Xq[3 * I + 2] +
                                   (is_position(basis, I) ? t[i] : 0.0);
            memset(g, 0, sizeof g);
            e = sb_shell_energy(&m, &r, &v, q, g, NULL, SB_HESS_EXACT, w);
            CHECK_NEAR(e, 0.0, 1e-18);
            gmax = 0;
            for (int i = 0; i < 3 * k; i++) gmax = fmax(gmax, fabs(g[i]));
            CHECK_MSG(gmax < 1e-8, "rigid gradient %.3g (basis %d)", gmax, basis);
            /* deformed state: energy invariant, gradient rotates with the state */
            for (int i = 0; i < 3 * k; i++) q[i] = Xq[i] + 0.02 * tb_rand(&s, -1, 1);
            memset(g, 0, sizeof g);
            e = sb_shell_energy(&m, &r, &v, q, g, NULL, SB_HESS_EXACT, w);
            CHECK(e > 0);
            for (int I = 0; I < k; I++)
                for (int i = 0; i < 3; i++)
                    q2[3 * I + i] = R[3 * i] * q[3 * I] + R[3 * i + 1] * q[3 * I + 1] + R[3 * i + 2] * q[3 * I + 2] +
                                    (is_position(basis, I) ? t[i] : 0.0);
            memset(g2, 0, sizeof g2);
            double e2 = sb_shell_energy(&m, &r, &v, q2, g2, NULL, SB_HESS_EXACT, w);
            CHECK_REL(e2, e, 1e-10);
            double gm = 0, dg = 0;
            for (int I = 0; I < k; I++)
                for (int i = 0; i < 3; i++) {
                    const double rg = R[3 * i] * g[3 * I] + R[3 * i + 1] * g[3 * I + 1] + R[3 * i + 2] * g[3 * I + 2];
                    dg = fmax(dg, fabs(rg - g2[3 * I + i]));
                    gm = fmax(gm, fabs(rg));
                }
            CHECK_MSG(dg < 1e-9 * gm, "rotated gradient mismatch %.3g of %.3g", dg, gm);
        }
    }
    sb_shell_work_free(w);
}

/* ---- BHEM Eq. (7)-(8) ---------------------------------------------------------- */

/* independent evaluation of Eq. (7) in covariant components:
 * V = (A_ab A_cd h + 1/3 B_ab B_cd h^3) H^abcd,
 * H^abcd = lambda/2 a^ab a^cd + mu a^bc a^ad  (Eq. 8) */
static double bhem_eq7(const sb_material *m, const double y[6][3], const double Y[6][3])
{
    double a[2][2], ab[2][2], b[2][2], bb[2][2], n[3], N[3];
    const double *x1 = y[1], *x2 = y[2], *X1 = Y[1], *X2 = Y[2];
    n[0] = x1[1] * x2[2] - x1[2] * x2[1];
    n[1] = x1[2] * x2[0] - x1[0] * x2[2];
    n[2] = x1[0] * x2[1] - x1[1] * x2[0];
    N[0] = X1[1] * X2[2] - X1[2] * X2[1];
    N[1] = X1[2] * X2[0] - X1[0] * X2[2];
    N[2] = X1[0] * X2[1] - X1[1] * X2[0];
    const double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), lN = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    const double *d1[2] = { x1, x2 }, *D1[2] = { X1, X2 };
    const double *d2[2][2] = { { y[3], y[4] }, { y[4], y[5] } }, *D2[2][2] = { { Y[3], Y[4] }, { Y[4], Y[5] } };
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            a[i][j] = ab[i][j] = b[i][j] = bb[i][j] = 0;
            for (int c = 0; c < 3; c++) {
                a[i][j] += d1[i][c] * d1[j][c];
                ab[i][j] += D1[i][c] * D1[j][c];
                b[i][j] += d2[i][j][c] * n[c] / ln;
                bb[i][j] += D2[i][j][c] * N[c] / lN;
            }
        }
    const double det = ab[0][0] * ab[1][1] - ab[0][1] * ab[1][0];
    const double ai[2][2] = { { ab[1][1] / det, -ab[0][1] / det }, { -ab[1][0] / det, ab[0][0] / det } };
    double V = 0;
    const double h = m->thickness;
    for (int p = 0; p < 2; p++)
        for (int q = 0; q < 2; q++)
            for (int r = 0; r < 2; r++)
                for (int s = 0; s < 2; s++) {
                    const double H = 0.5 * m->lambda * ai[p][q] * ai[r][s] + m->mu * ai[q][r] * ai[p][s];
                    const double A1 = 0.5 * (a[p][q] - ab[p][q]), A2 = 0.5 * (a[r][s] - ab[r][s]);
                    const double B1 = 0.5 * (b[p][q] - bb[p][q]), B2 = 0.5 * (b[r][s] - bb[r][s]);
                    V += (A1 * A2 * h + B1 * B2 * h * h * h / 3.0) * H;
                }
    return V;
}

SB_TEST(stvk_two_points_equal_bhem_eq7)
{
    unsigned long long s = 23;
    sb_shell_work *w = sb_shell_work_new();
    for (int basis = 0; basis < 2; basis++)
        for (int t = 0; t < 5; t++) {
            const double h = 0.02 + 0.05 * t;   /* thick enough for bending to weigh */
            sb_material m2 = mat_stvk(3e5, 0.35, h, 2), m6 = mat_stvk(3e5, 0.35, h, 6);
            tb_basis b;
            double Xq[48], q[48], y[6][3], Y[6][3];
            if (basis == 0) {
                tb_bspline(&b, tb_rand(&s, 0, 1), tb_rand(&s, 0, 1));
                bspline_net(Xq, 0.3, 0.25, 0.03);
            } else {
                tb_hermite(&b, tb_rand(&s, 0, 1), tb_rand(&s, 0, 1));
                tb_hermite_dofs(hmap, Xq);
            }
            for (int i = 0; i < 48; i++) q[i] = Xq[i] + 0.03 * tb_rand(&s, -1, 1);
            sb_shell_basis v = tb_view(&b);
            sb_shell_ref r;
            sb_shell_ref_init_basis(&r, &v, Xq, tb_rand(&s, -3, 3), 0.7);
            const double e2 = sb_shell_energy(&m2, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w);
            const double e6 = sb_shell_energy(&m6, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w);
            tb_jet(&b, q, y);
            tb_jet(&b, Xq, Y);
            /* energy = dA * Eq. (7): h psi(A) + (h^3/3) psi(B) */
            CHECK_REL(e2, r.dA * bhem_eq7(&m2, y, Y), 1e-11);
            /* two points are exact for StVK: more points change nothing */
            CHECK_REL(e6, e2, 1e-12);
        }
    sb_shell_work_free(w);
}

/* ---- uniaxial stretch ------------------------------------------------------------ */

SB_TEST(stvk_uniaxial_stretch)
{
    const double Y = 2e6, nu = 0.3, h = 1e-3, sp = 0.3;
    sb_material m = mat_stvk(Y, nu, h, 0);
    sb_shell_work *w = sb_shell_work_new();
    tb_basis b;
    tb_bspline(&b, 0.45, 0.2);
    double Xq[48], q[48], g[48];
    bspline_net(Xq, sp, sp, 0.0);
    sb_shell_basis v = tb_view(&b);
    sb_shell_ref r;
    sb_shell_ref_init_basis(&r, &v, Xq, 0.0, 1.0);
    CHECK_REL(r.dA, sp * sp, 1e-14);
    for (double st = 0.9; st <= 1.21; st += 0.05) {
        for (int I = 0; I < 16; I++) {
            q[3 * I] = st * Xq[3 * I];
            q[3 * I + 1] = Xq[3 * I + 1];
            q[3 * I + 2] = 0;
        }
        memset(g, 0, sizeof g);
        const double e = sb_shell_energy(&m, &r, &v, q, g, NULL, SB_HESS_EXACT, w);
        /* E11 = (s^2 - 1)/2, others 0: psi = (lambda/2 + mu) E11^2, energy = dA h psi */
        const double E11 = 0.5 * (st * st - 1);
        const double ref = r.dA * h * (0.5 * m.lambda + m.mu) * E11 * E11;
        CHECK_REL(e, ref, 1e-12);
        /* dE/ds = sum_I g_I . dq_I/ds = dA h (lambda + 2 mu) E11 s */
        double dEds = 0;
        for (int I = 0; I < 16; I++) dEds += g[3 * I] * Xq[3 * I];
        CHECK_NEAR(dEds, r.dA * h * (m.lambda + 2 * m.mu) * E11 * st, 1e-12 * Y * h * r.dA);
    }
    sb_shell_work_free(w);
}

/* ---- pure bending into a cylinder ------------------------------------------------- */

SB_TEST(stvk_cylinder_bending)
{
    const double Y = 1e6, nu = 0.3, h = 2e-3;
    sb_material m = mat_stvk(Y, nu, h, 0);
    const double D = Y * h * h * h / (12 * (1 - nu * nu));
    sb_shell_work *w = sb_shell_work_new();
    /* Taylor jet: exact.  Flat reference (x1 = e1, x2 = e2), deformed onto a
     * cylinder of radius R about an axis along e2 (isometric: A = 0):
     * x1 = e1, x2 = e2, x11 = e3 / R.  bending energy/area = D / (2 R^2). */
    tb_basis b;
    tb_taylor(&b);
    sb_shell_basis v = tb_view(&b);
    const double X[18] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    for (int ia = 0; ia < 3; ia++) {
        sb_shell_ref r;
        sb_shell_ref_init_basis(&r, &v, X, 0.7 * ia, 1.0);   /* isotropic: warp angle irrelevant */
        for (double R = 0.01; R < 2; R *= 3) {
            for (int sign = -1; sign <= 1; sign += 2) {
                double q[18];
                memcpy(q, X, sizeof q);
                q[11] = sign / R;
                const double e = sb_shell_energy(&m, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w);
                CHECK_REL(e, D / (2 * R * R), 1e-12);
            }
            /* bending about the other axis and a twist-free saddle: energy sums */
            double q[18];
            memcpy(q, X, sizeof q);
            q[11] = 1 / R;
            q[17] = -1 / R;   /* x22 = -e3/R: saddle, kappa = diag(1,-1)/R */
            const double e = sb_shell_energy(&m, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w);
            /* h^3/3 psi(B), B = kappa/2: psi = mu tr(B^2) = mu/(2R^2) */
            CHECK_REL(e, h * h * h / 3 * m.mu * 2 * 0.25 / (R * R), 1e-12);
        }
    }
    /* same with a bicubic Hermite element interpolating the cylinder: the
     * Hermite interpolant of a cylinder is not exact, error -> 0 with size */
    tb_basis hb;
    double prev = INFINITY;
    for (double L = 0.2; L > 0.02; L /= 2) {
        const double R = 0.25;
        double Xq[48], q[48];
        for (int c = 0; c < 4; c++) {
            const double u = c % 2, vv = c / 2;
            double *x = Xq + 12 * c;
            /* reference: flat square L x L */
            const double ref[12] = { L * u, L * vv, 0, L, 0, 0, 0, L, 0, 0, 0, 0 };
            memcpy(x, ref, sizeof ref);
            /* deformed: the square rolled onto the cylinder, arc length L u */
            const double ph = L * u / R;
            const double def[12] = { R * sin(ph), L * vv, R * (1 - cos(ph)), L * cos(ph), 0, L * sin(ph),
                                     0, L, 0, 0, 0, 0 };
            memcpy(q + 12 * c, def, sizeof def);
        }
        /* integrate over the element with 4x4 Gauss points */
        double gx[4], gwt[4], e = 0, area = 0;
        sb_gauss_legendre(4, gx, gwt);
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                tb_hermite(&hb, 0.5 + 0.5 * gx[i], 0.5 + 0.5 * gx[j]);
                sb_shell_basis hv = tb_view(&hb);
                sb_shell_ref r;
                sb_shell_ref_init_basis(&r, &hv, Xq, 0.0, 0.25 * gwt[i] * gwt[j]);
                e += sb_shell_energy(&m, &r, &hv, q, NULL, NULL, SB_HESS_EXACT, w);
                area += r.dA;
            }
        CHECK_REL(area, L * L, 1e-12);
        const double rel = sb_rel_err(e / area, D / (2 * R * R));
        /* includes the membrane energy of the interpolation error */
        CHECK_MSG(rel < prev, "Hermite cylinder error %.3g did not drop below %.3g", rel, prev);
        prev = rel;
    }
    CHECK_MSG(prev < 2e-2, "Hermite cylinder error %.3g", prev);
    sb_shell_work_free(w);
}

/* ---- denim in the kernel: small strain, warp and weft ------------------------------ */

SB_TEST(denim_small_strain_warp_weft)
{
    sb_material m = mat_denim();
    const double *k = m.denim.k, h = m.thickness;
    sb_shell_work *w = sb_shell_work_new();
    tb_basis b;
    tb_taylor(&b);
    sb_shell_basis v = tb_view(&b);
    /* reference: non-orthogonal parametrization of the plane, a1 = (2,0,0), a2 = (0.6, 1.5, 0) */
    const double X[18] = { 0, 0, 0, 2, 0, 0, 0.6, 1.5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    const double eps = 1e-5;
    for (int dir = 0; dir < 3; dir++) {
        /* warp along a_1 rotated by theta; stretch along the warp (dir 0), the
         * weft (dir 1), or shear warp/weft (dir 2) */
        const double theta = 0.6;
        sb_shell_ref r;
        CHECK_EQ_INT(sb_shell_ref_init_basis(&r, &v, X, theta, 1.0), SB_OK);
        /* deformation gradient F = I + eps d (x) d' in the plane */
        const double *d = dir == 1 ? r.e2 : r.e1, *dp = dir == 0 ? r.e1 : r.e2;
        double q[18];
        memcpy(q, X, sizeof q);
        for (int s = 1; s <= 2; s++) {
            const double *Xa = X + 3 * s;
            const double proj = dp[0] * Xa[0] + dp[1] * Xa[1] + dp[2] * Xa[2];
            for (int c = 0; c < 3; c++) q[3 * s + c] = Xa[c] + eps * d[c] * proj;
        }
        const double e = sb_shell_energy(&m, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w) / r.dA;
        double ref;
        if (dir == 0) ref = h * 0.5 * k[0] * pow(eps + 0.5 * eps * eps, 2);   /* E11 = eps + eps^2/2 */
        else if (dir == 1) ref = h * 0.5 * k[2] * pow(eps + 0.5 * eps * eps, 2);
        else {
            /* F = I + eps e1 (x) e2: E12 = eps/2, E22 = eps^2/2 */
            const double E12 = 0.5 * eps, E22 = 0.5 * eps * eps;
            ref = h * (k[3] * E12 * E12 + 0.5 * k[2] * E22 * E22);
        }
        CHECK_REL(e, ref, 1e-5);
    }
    sb_shell_work_free(w);
}

SB_TEST(frame_and_reference)
{
    /* T maps covariant strains to the orthonormal warp frame: check on a
     * skewed, curved reference that the local frame is orthonormal, tangent,
     * at the warp angle from a_1, and that StVK does not see the warp angle */
    const double X1[3] = { 1.0, 0.2, 0.1 }, X2[3] = { 0.3, 0.8, -0.2 }, X11[3] = { 0, 0.1, 1 },
                 X12[3] = { 0.1, 0, 0.3 }, X22[3] = { 0, 0, -0.5 };
    sb_shell_ref r;
    const double th = 0.9;
    CHECK_EQ_INT(sb_shell_ref_init(&r, X1, X2, X11, X12, X22, th, 0.5), SB_OK);
    const double d11 = r.e1[0] * r.e1[0] + r.e1[1] * r.e1[1] + r.e1[2] * r.e1[2];
    const double d12 = r.e1[0] * r.e2[0] + r.e1[1] * r.e2[1] + r.e1[2] * r.e2[2];
    const double d1n = r.e1[0] * r.normal[0] + r.e1[1] * r.normal[1] + r.e1[2] * r.normal[2];
    CHECK_NEAR(d11, 1, 1e-14);
    CHECK_NEAR(d12, 0, 1e-14);
    CHECK_NEAR(d1n, 0, 1e-14);
    const double l1 = sqrt(X1[0] * X1[0] + X1[1] * X1[1] + X1[2] * X1[2]);
    CHECK_NEAR((r.e1[0] * X1[0] + r.e1[1] * X1[1] + r.e1[2] * X1[2]) / l1, cos(th), 1e-14);
    CHECK_REL(r.dA, 0.5 * r.sqrt_a, 1e-15);
    /* contravariant metric is the inverse */
    CHECK_NEAR(r.abar[0] * r.ainv[0] + r.abar[2] * r.ainv[2], 1, 1e-14);
    CHECK_NEAR(r.abar[0] * r.ainv[2] + r.abar[2] * r.ainv[1], 0, 1e-14);
    /* StVK energy independent of the warp angle */
    sb_material m = mat_stvk(1e6, 0.3, 0.05, 0);
    tb_basis b;
    tb_taylor(&b);
    sb_shell_basis v = tb_view(&b);
    const double Xq[18] = { 0, 0, 0, 1.0, 0.2, 0.1, 0.3, 0.8, -0.2, 0, 0.1, 1, 0.1, 0, 0.3, 0, 0, -0.5 };
    double q[18];
    for (int i = 0; i < 18; i++) q[i] = Xq[i] * (1 + 0.05 * sin(i));
    sb_shell_work *w = sb_shell_work_new();
    double e0 = 0;
    for (int i = 0; i < 4; i++) {
        sb_shell_ref_init_basis(&r, &v, Xq, 0.8 * i, 1.0);
        const double e = sb_shell_energy(&m, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w);
        if (i == 0) e0 = e;
        else CHECK_REL(e, e0, 1e-12);
    }
    /* denim does see it */
    sb_material dm = mat_denim();
    sb_shell_ref_init_basis(&r, &v, Xq, 0.0, 1.0);
    const double ea = sb_shell_energy(&dm, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w);
    sb_shell_ref_init_basis(&r, &v, Xq, 0.7, 1.0);
    const double eb = sb_shell_energy(&dm, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w);
    CHECK(sb_rel_err(ea, eb) > 1e-3);
    sb_shell_work_free(w);
}

SB_TEST(bad_input_gives_nonfinite)
{
    sb_shell_ref r;
    const double X1[3] = { 1, 0, 0 }, X2[3] = { 2, 0, 0 }, Z[3] = { 0, 0, 0 };
    CHECK_EQ_INT(sb_shell_ref_init(&r, X1, X2, Z, Z, Z, 0, 1), SB_ERR_INPUT);
    CHECK(isnan(r.dA));
    const double Xn[3] = { NAN, 0, 0 }, Y2[3] = { 0, 1, 0 };
    CHECK_EQ_INT(sb_shell_ref_init(&r, Xn, Y2, Z, Z, Z, 0, 1), SB_ERR_INPUT);
    sb_material m = mat_stvk(1e6, 0.3, 1e-3, 0);
    tb_basis b;
    tb_taylor(&b);
    sb_shell_basis v = tb_view(&b);
    sb_shell_work *w = sb_shell_work_new();
    double q[18] = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };   /* x1 || x2 */
    double g[18] = { 0 }, H[18 * 18] = { 0 };
    /* degenerate reference -> NaN energy */
    CHECK(!isfinite(sb_shell_energy(&m, &r, &v, q, g, H, SB_HESS_EXACT, w)));
    /* good reference, degenerate current state -> non-finite, no crash */
    CHECK_EQ_INT(sb_shell_ref_init(&r, X1, Y2, Z, Z, Z, 0, 1), SB_OK);
    CHECK(!isfinite(sb_shell_energy(&m, &r, &v, q, g, H, SB_HESS_EXACT, w)));
    /* too many basis functions, missing arrays, no workspace */
    sb_shell_basis big = v;
    big.k = SB_SHELL_MAX_BASIS + 1;
    CHECK(isnan(sb_shell_energy(&m, &r, &big, q, NULL, NULL, SB_HESS_EXACT, w)));
    sb_shell_basis miss = v;
    miss.N12 = NULL;
    CHECK(isnan(sb_shell_energy(&m, &r, &miss, q, NULL, NULL, SB_HESS_EXACT, w)));
    CHECK(isnan(sb_shell_energy(&m, &r, &v, q, NULL, NULL, SB_HESS_EXACT, NULL)));
    sb_material bad = m;
    bad.n_thick = 0;
    CHECK(isnan(sb_shell_energy(&bad, &r, &v, q, NULL, NULL, SB_HESS_EXACT, w)));
    CHECK_EQ_INT(sb_shell_ref_init_basis(&r, &big, q, 0, 1), SB_ERR_INPUT);
    /* the names table */
    CHECK(strcmp(sb_hess_kind_names[SB_HESS_EXACT], "exact") == 0);
    CHECK(strcmp(sb_hess_kind_names[SB_HESS_PSEUDO], "pseudo") == 0);
    CHECK(strcmp(sb_hess_kind_names[SB_HESS_PSD], "psd") == 0);
    CHECK(sb_hess_kind_names[3] == NULL);
    sb_shell_work_free(w);
}

/* the section law used by the kernel and offered to triangle elements */
SB_TEST(section_law)
{
    sb_material st = mat_stvk(2e6, 0.3, 1e-3, 0);
    const double A[3] = { 0.01, -0.004, 0.006 }, B[3] = { 30, -12, 8 };
    const double z[3] = { 0, 0, 0 };
    /* BHEM Eq. (7): h psi(A) + (h^3/3) psi(B) */
    const double ref = st.thickness * sb_material_psi(&st, A, NULL, NULL) +
                       pow(st.thickness, 3) / 3 * sb_material_psi(&st, B, NULL, NULL);
    CHECK_REL(sb_shell_section(&st, A, B, NULL, NULL, NULL), ref, 1e-13);
    CHECK_NEAR(sb_shell_section(&st, z, z, NULL, NULL, NULL), 0.0, 0.0);
    /* denim: derivatives by central differences on the 6 strain entries */
    sb_material dm = mat_denim();
    double sA[3], sB[3], C[36];
    const double A2[3] = { 0.02, 0.01, -0.01 }, B2[3] = { 20, -8, 5 };
    sb_shell_section(&dm, A2, B2, sA, sB, C);
    const double g6[6] = { sA[0], sA[1], sA[2], sB[0], sB[1], sB[2] };
    double prev_g = INFINITY, prev_h = INFINITY;
    for (int st_ = 0; st_ < 3; st_++) {
        double eg = 0, eh = 0, gm = 0, hm = 0;
        for (int j = 0; j < 6; j++) {
            const double h = (j < 3 ? 1e-4 : 0.1) / pow(4.0, st_);
            double Ap[3], Bp[3], Am[3], Bm[3], gAp[3], gBp[3], gAm[3], gBm[3];
            memcpy(Ap, A2, sizeof Ap); memcpy(Am, A2, sizeof Am);
            memcpy(Bp, B2, sizeof Bp); memcpy(Bm, B2, sizeof Bm);
            if (j < 3) { Ap[j] += h; Am[j] -= h; } else { Bp[j - 3] += h; Bm[j - 3] -= h; }
            const double fp = sb_shell_section(&dm, Ap, Bp, gAp, gBp, NULL);
            const double fm = sb_shell_section(&dm, Am, Bm, gAm, gBm, NULL);
            eg = fmax(eg, fabs((fp - fm) / (2 * h) - g6[j]));
            gm = fmax(gm, fabs(g6[j]));
            for (int i = 0; i < 6; i++) {
                const double gp = i < 3 ? gAp[i] : gBp[i - 3], gmi = i < 3 ? gAm[i] : gBm[i - 3];
                eh = fmax(eh, fabs((gp - gmi) / (2 * h) - C[6 * i + j]));
                hm = fmax(hm, fabs(C[6 * i + j]));
            }
        }
        eg /= gm;
        eh /= hm;
        CHECK_MSG(eg < prev_g / 8 || eg < 1e-9, "section gradient FD %.3g after %.3g", eg, prev_g);
        CHECK_MSG(eh < prev_h / 8 || eh < 1e-9, "section Hessian FD %.3g after %.3g", eh, prev_h);
        prev_g = eg;
        prev_h = eh;
    }
    CHECK(prev_g < 1e-6 && prev_h < 1e-6);
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) CHECK_NEAR(C[6 * i + j], C[6 * j + i], 1e-12 * fabs(C[0]));
    sb_material bad = dm;
    bad.n_thick = 0;
    CHECK(isnan(sb_shell_section(&bad, A, B, NULL, NULL, NULL)));
}

static const sb_test_case cases[] = {
    SB_CASE(rigid_motions),
    SB_CASE(stvk_two_points_equal_bhem_eq7),
    SB_CASE(stvk_uniaxial_stretch),
    SB_CASE(stvk_cylinder_bending),
    SB_CASE(denim_small_strain_warp_weft),
    SB_CASE(frame_and_reference),
    SB_CASE(bad_input_gives_nonfinite),
    SB_CASE(section_law),
    SB_END
};

int main(int argc, char **argv)
{
    return sb_test_main(argc, argv, cases);
}
