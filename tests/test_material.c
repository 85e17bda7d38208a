/* test_material.c — StVK and denim laws (sb_material.c): parameters, analytic
 * values, finite-difference derivatives, small-strain stiffness, domain
 * guards, input validation, Gauss rules and the denim thickness-point study. */
#include "sb_test.h"
#include "sb_gsl.h"
#include "sb_material.h"
#include "test_shell_bases.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <string.h>

static sb_material stvk(double Y, double nu, double h)
{
    sb_material_spec s;
    memset(&s, 0, sizeof s);
    s.kind = SB_MAT_STVK;
    s.young = Y;
    s.poisson = nu;
    s.thickness = h;
    s.density = 0.2;
    sb_material m;
    int st = sb_material_init(&m, &s, 0);
    (void)st;
    return m;
}

static sb_material denim(int n_thick)
{
    sb_material_spec s;
    sb_material_spec_denim(&s);
    sb_material m;
    sb_material_init(&m, &s, n_thick);
    return m;
}

/* Central differences of psi (gradient) and dpsi (Hessian) at e with step h;
 * returns the max relative errors (relative to the max entry). */
static void fd_errors(const sb_material *m, const double e[3], double h, double *eg, double *eh)
{
    double d[3], H[9], gmax = 0, hmax = 0, ge = 0, he = 0;
    sb_material_psi(m, e, d, H);
    for (int i = 0; i < 3; i++) gmax = fmax(gmax, fabs(d[i]));
    for (int i = 0; i < 9; i++) hmax = fmax(hmax, fabs(H[i]));
    for (int j = 0; j < 3; j++) {
        double ep[3] = { e[0], e[1], e[2] }, em[3] = { e[0], e[1], e[2] }, dp[3], dm[3];
        ep[j] += h;
        em[j] -= h;
        double fp = sb_material_psi(m, ep, dp, NULL), fm = sb_material_psi(m, em, dm, NULL);
        ge = fmax(ge, fabs((fp - fm) / (2 * h) - d[j]));
        for (int i = 0; i < 3; i++) he = fmax(he, fabs((dp[i] - dm[i]) / (2 * h) - H[3 * i + j]));
    }
    *eg = ge / gmax;
    *eh = he / hmax;
}

/* Shared finite-difference assertion: over steps h0, h0/4, h0/16, h0/64 the error
 * must fall by >= 8x per step (O(h^2) predicts 16x) until it reaches the
 * roundoff floor, and the best error must be below tol. */
static void check_fd_rates(sb_test_state *T, const sb_material *m, const double e[3], double h0,
                           double floor_, double tol)
{
    double eg[4], eh[4];
    for (int s = 0; s < 4; s++) fd_errors(m, e, h0 / pow(4.0, s), &eg[s], &eh[s]);
    for (int s = 0; s < 3; s++) {
        CHECK_MSG(eg[s + 1] <= eg[s] / 8 || eg[s + 1] < floor_,
                  "gradient FD error %.3g -> %.3g at e = (%g, %g, %g)", eg[s], eg[s + 1], e[0], e[1], e[2]);
        CHECK_MSG(eh[s + 1] <= eh[s] / 8 || eh[s + 1] < floor_,
                  "Hessian FD error %.3g -> %.3g at e = (%g, %g, %g)", eh[s], eh[s + 1], e[0], e[1], e[2]);
    }
    CHECK_MSG(eg[3] < tol && eh[3] < tol, "FD errors %.3g %.3g above %.3g", eg[3], eh[3], tol);
}

SB_TEST(stvk_lame_and_values)
{
    const double Y = 2.0e6, nu = 0.3;
    sb_material m = stvk(Y, nu, 1e-3);
    /* BHEM paper Eq. (8) */
    CHECK_REL(m.lambda, Y * nu / (1 - nu * nu), 1e-15);
    CHECK_REL(m.mu, Y / (2 * (1 + nu)), 1e-15);
    CHECK_EQ_INT(m.n_thick, 2);
    /* psi = lambda/2 (tr E)^2 + mu tr(E^2), E = [[a, c], [c, b]] */
    const double e[3] = { 0.03, -0.01, 0.02 };
    const double tr = e[0] + e[1], trE2 = e[0] * e[0] + e[1] * e[1] + 2 * e[2] * e[2];
    CHECK_REL(sb_material_psi(&m, e, NULL, NULL), 0.5 * m.lambda * tr * tr + m.mu * trE2, 1e-14);
    /* uniaxial stress state check: S = lambda tr E I + 2 mu E, dpsi[2] = 2 S12 */
    double d[3];
    sb_material_psi(&m, e, d, NULL);
    CHECK_REL(d[0], m.lambda * tr + 2 * m.mu * e[0], 1e-14);
    CHECK_REL(d[2], 2 * (2 * m.mu * e[2]), 1e-14);
    /* plane-stress uniaxial: E22 chosen so S22 = 0 -> S11 = Y E11 */
    const double E11 = 0.01, E22 = -m.lambda / (m.lambda + 2 * m.mu) * E11;
    const double eu[3] = { E11, E22, 0 };
    sb_material_psi(&m, eu, d, NULL);
    CHECK_NEAR(d[1], 0.0, 1e-9 * Y);
    CHECK_REL(d[0], Y * E11, 1e-12);
}

SB_TEST(stvk_fd_derivatives)
{
    sb_material m = stvk(1.0e6, 0.45, 1e-3);
    unsigned long long s = 7;
    for (int t = 0; t < 10; t++) {
        double e[3] = { tb_rand(&s, -0.2, 0.3), tb_rand(&s, -0.2, 0.3), tb_rand(&s, -0.2, 0.2) };
        /* psi is quadratic: central differences are exact up to roundoff */
        double eg, eh;
        fd_errors(&m, e, 1e-3, &eg, &eh);
        CHECK(eg < 1e-9);
        CHECK(eh < 1e-9);
    }
}

SB_TEST(denim_table1_and_assumption)
{
    sb_denim_params p;
    sb_denim_defaults(&p);
    /* Table 1, k in MPa -> Pa */
    CHECK_REL(p.k[0], 4.79e6, 1e-15);
    CHECK_REL(p.k[1], 4.52e6, 1e-15);
    CHECK_REL(p.k[2], 9.03e6, 1e-15);
    CHECK_REL(p.k[3], 2.44e6, 1e-15);
    CHECK_EQ_INT(p.d[0], 5);
    CHECK_EQ_INT(p.d[1], 1);
    CHECK_EQ_INT(p.d[2], 5);
    CHECK_EQ_INT(p.d[3], 3);
    CHECK_REL(p.alpha[2][1], -12802.0, 1e-15);
    CHECK_REL(p.alpha[3][1], -2823.9, 1e-15);
    CHECK_REL(p.mu[0][4], 3416.79, 1e-15);
    CHECK_REL(p.mu[2][1], 0.658, 1e-15);
    /* assumption mu_j1 = 1 - sum_{i>=2} mu_ji  =>  phi_j'(0) = 1 */
    CHECK_REL(p.mu[0][0], -4617.79, 1e-12);
    CHECK_REL(p.mu[2][0], 84.882, 1e-12);
    CHECK_REL(p.mu[3][0], -10.87, 1e-12);
    for (int j = 0; j < 4; j++) {
        double d1, d2;
        double f = sb_denim_phi(&p, j, 0.0, &d1, &d2);
        CHECK_NEAR(f, 0.0, 0.0);
        CHECK_NEAR(d1, 1.0, 1e-11);
    }
    /* d_2 = 1, alpha_21 = 1 -> phi_2(u) = u, also for negative u */
    for (double u = -3.0; u <= 3.0; u += 0.75) CHECK_NEAR(sb_denim_phi(&p, 1, u, NULL, NULL), u, 1e-15);
    /* spec helper: tau 0.66 mm, rho 0.4 kg/m^2 */
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    CHECK_REL(sp.thickness, 0.66e-3, 1e-15);
    CHECK_REL(sp.density, 0.4, 1e-15);
}

SB_TEST(denim_phi_against_direct_formula)
{
    /* expm1/log1p route against the literal (u+1)^alpha of Eq. (3.4) where the
     * latter is well conditioned (moderate u) */
    sb_denim_params p;
    sb_denim_defaults(&p);
    for (int j = 0; j < 4; j++)
        for (double u = 0.05; u < 0.6; u += 0.1) {
            double ref = 0, ref1 = 0;
            for (int i = 0; i < p.d[j]; i++) {
                ref += p.mu[j][i] / p.alpha[j][i] * (pow(u + 1, p.alpha[j][i]) - 1);
                ref1 += p.mu[j][i] * pow(u + 1, p.alpha[j][i] - 1);
            }
            double d1;
            double f = sb_denim_phi(&p, j, u, &d1, NULL);
            CHECK_REL(f, ref, 1e-9);
            CHECK_REL(d1, ref1, 1e-9);
        }
    /* the material's cached fast path agrees with sb_denim_phi (Eq. 3.3) */
    sb_material m = denim(0);
    unsigned long long s = 5;
    for (int t = 0; t < 20; t++) {
        const double e[3] = { tb_rand(&s, -0.1, 0.2), tb_rand(&s, -0.1, 0.2), tb_rand(&s, -0.1, 0.1) };
        const double ref = 0.5 * p.k[0] * sb_denim_phi(&p, 0, e[0] * e[0], NULL, NULL) +
                           p.k[1] * sb_denim_phi(&p, 1, e[0] * e[1], NULL, NULL) +
                           0.5 * p.k[2] * sb_denim_phi(&p, 2, e[1] * e[1], NULL, NULL) +
                           p.k[3] * sb_denim_phi(&p, 3, e[2] * e[2], NULL, NULL);
        CHECK_REL(sb_material_psi(&m, e, NULL, NULL), ref, 1e-13);
    }
}

SB_TEST(denim_small_strain_is_linear_orthotropic)
{
    sb_material m = denim(0);
    const double *k = m.denim.k;
    double H[9], d[3];
    const double z[3] = { 0, 0, 0 };
    CHECK_NEAR(sb_material_psi(&m, z, d, H), 0.0, 0.0);
    /* d2psi(0) = [[k1, k2, 0], [k2, k3, 0], [0, 0, 2 k4]] (dpsi[2] = 2 S12) */
    CHECK_REL(H[0], k[0], 1e-10);
    CHECK_REL(H[1], k[1], 1e-10);
    CHECK_REL(H[3], k[1], 1e-10);
    CHECK_REL(H[4], k[2], 1e-10);
    CHECK_REL(H[8], 2 * k[3], 1e-10);
    CHECK_NEAR(H[2], 0, 0);
    CHECK_NEAR(H[5], 0, 0);
    /* psi(s e) / s^2 -> 1/2 e^T C e, with error O(s^2) */
    const double e[3] = { 0.8, -0.5, 0.6 };
    const double q = 0.5 * (k[0] * e[0] * e[0] + 2 * k[1] * e[0] * e[1] + k[2] * e[1] * e[1]) +
                     k[3] * e[2] * e[2];
    double prev = INFINITY;
    for (double s = 1e-3; s > 1e-6; s /= 10) {
        const double es[3] = { s * e[0], s * e[1], s * e[2] };
        double r = sb_rel_err(sb_material_psi(&m, es, NULL, NULL) / (s * s), q);
        CHECK_MSG(r < prev / 50 || r < 1e-9, "small-strain error %.3g after %.3g", r, prev);
        prev = r;
    }
    CHECK(prev < 1e-6);
}

SB_TEST(denim_fd_derivatives)
{
    sb_material m = denim(0);
    unsigned long long s = 11;
    for (int t = 0; t < 20; t++) {
        double e[3] = { tb_rand(&s, -0.05, 0.15), tb_rand(&s, -0.05, 0.15), tb_rand(&s, -0.1, 0.1) };
        /* the law varies on strain scales ~ 1/sqrt(12802) ~ 0.009: steps below that */
        check_fd_rates(T, &m, e, 2e-3, 1e-8, 3e-5);
    }
    /* near the steep region of phi_3 */
    const double e1[3] = { 0.0, 0.009, 0.0 }, e2[3] = { 0.002, -0.004, 0.001 };
    check_fd_rates(T, &m, e1, 2.5e-4, 1e-8, 1e-6);
    check_fd_rates(T, &m, e2, 5e-4, 1e-8, 1e-6);
}

SB_TEST(denim_nonfinite_guards)
{
    sb_material m = denim(0);
    double d[3], H[9];
    /* absurd strain: overflow in (u+1)^30 -> non-finite energy, no crash */
    const double big[3] = { 1e200, 0, 0 };
    CHECK(!isfinite(sb_material_psi(&m, big, d, H)));
    const double nan3[3] = { NAN, 0, 0 };
    CHECK(isnan(sb_material_psi(&m, nan3, d, H)));
    /* phi_2 = u is defined everywhere: E11 E22 < -1 stays finite with Table 1 */
    const double neg[3] = { 2.0, -0.6, 0.0 };
    CHECK(isfinite(sb_denim_phi(&m.denim, 1, neg[0] * neg[1], NULL, NULL)));
    /* a user law with alpha_21 != 1 is outside its domain for u <= -1: NaN
     * when states beyond the fit are inadmissible ... */
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    sp.denim.alpha[1][0] = 2.0;
    sp.denim.beyond_fit = 1;
    sb_material m2;
    CHECK_EQ_INT(sb_material_init(&m2, &sp, 0), SB_OK);
    CHECK(isnan(sb_material_psi(&m2, neg, d, H)));
    CHECK(isnan(d[0]) && isnan(H[0]));
    /* ... and fine inside it */
    const double ok[3] = { 0.1, -0.05, 0.0 };
    CHECK(isfinite(sb_material_psi(&m2, ok, d, H)));
    /* the default continuation makes it finite there too */
    sp.denim.beyond_fit = 0;
    CHECK_EQ_INT(sb_material_init(&m2, &sp, 0), SB_OK);
    CHECK(isfinite(sb_material_psi(&m2, neg, d, H)) && isfinite(d[0]) && isfinite(H[0]));
}

/* Table 1's weft law phi_3 loses monotonicity at u ~ 0.1025 and is unbounded
 * below beyond: such states are inadmissible (NaN energy), see sb_material.c */
SB_TEST(denim_admissible_range)
{
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    sp.denim.beyond_fit = 1;     /* "inadmissible" */
    sb_material m;
    CHECK_EQ_INT(sb_material_init(&m, &sp, 0), SB_OK);
    CHECK(m.denim_u_max[2] > 0.09 && m.denim_u_max[2] < 0.11);
    double d1, d2;
    /* phi_3' > 0 just inside, <= 0 just outside */
    sb_denim_phi(&m.denim, 2, 0.999 * m.denim_u_max[2], &d1, &d2);
    CHECK(d1 > 0);
    sb_denim_phi(&m.denim, 2, 1.001 * m.denim_u_max[2], &d1, &d2);
    CHECK(d1 <= 0);
    double e_in[3] = { 0.0, 0.99 * sqrt(m.denim_u_max[2]), 0.0 }, e_out[3] = { 0.0, 1.01 * sqrt(m.denim_u_max[2]), 0.0 };
    CHECK(isfinite(sb_material_psi(&m, e_in, NULL, NULL)));
    CHECK(isnan(sb_material_psi(&m, e_out, NULL, NULL)));
    /* the unbounded branch the guard removes: phi_3 at u = 0.36 is hugely negative */
    CHECK(sb_denim_phi(&m.denim, 2, 0.36, NULL, NULL) < -1e3);
    /* the linear mixed law and the monotone warp / shear laws have no bound within reach */
    CHECK(!isfinite(m.denim_u_max[1]) && m.denim_u_max[0] > 1.0 && m.denim_u_max[3] > 1.0);
}

/* Default (beyond_fit = extend): past the peak of phi_3' (u_join < u_max)
 * phi_3 continues linearly, so psi is finite, C^1, increasing and convex in
 * E22 beyond the fit, with correct derivatives there, and unchanged inside. */
SB_TEST(denim_continuation_beyond_fit)
{
    sb_material m = denim(0);
    sb_material_spec sp;
    sb_material_spec_denim(&sp);
    sp.denim.beyond_fit = 1;
    sb_material mi;
    CHECK_EQ_INT(sb_material_init(&mi, &sp, 0), SB_OK);
    const double uj = m.denim_join_hi[2], um = m.denim_u_max[2];
    CHECK(uj > 0.5 * um && uj < um);
    /* phi_3' peaks at the join: phi_3'' = 0 there (C^2 join) */
    double d1, d2;
    sb_denim_phi(&m.denim, 2, uj, &d1, &d2);
    CHECK(d1 > 0 && fabs(d2) < 1e-6 * d1 / uj);
    /* unchanged inside the fit below the join */
    const double e_in[3] = { 0.01, 0.9 * sqrt(uj), 0.02 };
    double da[3], db[3];
    CHECK_NEAR(sb_material_psi(&m, e_in, da, NULL), sb_material_psi(&mi, e_in, db, NULL), 0.0);
    /* finite, increasing and convex in E22 far beyond u_max */
    double prev = -INFINITY, prev_slope = -INFINITY;
    for (int k = 0; k < 40; k++) {
        const double e22 = 0.9 * sqrt(uj) + 0.02 * k, e[3] = { 0.0, e22, 0.0 };
        double d[3], H[9];
        double f = sb_material_psi(&m, e, d, H);
        CHECK(isfinite(f) && f > prev && d[1] > prev_slope && H[4] > 0);
        prev = f;
        prev_slope = d[1];
    }
    /* C^1 across the join, and the FD checks on both sides and beyond u_max */
    const double ej = sqrt(uj), lo[3] = { 0.0, ej - 1e-7, 0.0 }, hi[3] = { 0.0, ej + 1e-7, 0.0 };
    double fl = sb_material_psi(&m, lo, da, NULL), fh = sb_material_psi(&m, hi, db, NULL);
    /* no jump: the difference across 2e-7 is the slope times 2e-7 */
    CHECK(fabs((fh - fl) - 0.5 * (da[1] + db[1]) * 2e-7) < 1e-3 * fabs(da[1]) * 2e-7);
    CHECK(fabs(db[1] - da[1]) < 1e-5 * fabs(da[1]));
    const double e_beyond[3] = { 0.003, 1.3 * sqrt(um), 0.002 }, e_join[3] = { 0.001, 1.05 * ej, -0.002 };
    check_fd_rates(T, &m, e_beyond, 1e-4, 1e-8, 1e-6);
    check_fd_rates(T, &m, e_join, 1e-4, 1e-8, 1e-6);
}

SB_TEST(init_rejects_bad_input)
{
    sb_material m;
    sb_material_spec s;
    char err[256];
    memset(&s, 0, sizeof s);
    s.kind = SB_MAT_STVK;
    s.young = 1e6;
    s.poisson = 0.3;
    s.thickness = 1e-3;
    s.density = 1.0;
    CHECK_EQ_INT(sb_material_init_msg(&m, &s, 0, err, sizeof err), SB_OK);
    s.poisson = 1.0;
    CHECK_EQ_INT(sb_material_init_msg(&m, &s, 0, err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "poisson") != NULL);
    s.poisson = 0.3;
    s.young = -1;
    CHECK_EQ_INT(sb_material_init(&m, &s, 0), SB_ERR_INPUT);
    s.young = 1e6;
    s.thickness = 0;
    CHECK_EQ_INT(sb_material_init_msg(&m, &s, 0, err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "thickness") != NULL);
    s.thickness = NAN;
    CHECK_EQ_INT(sb_material_init(&m, &s, 0), SB_ERR_INPUT);
    s.thickness = 1e-3;
    CHECK_EQ_INT(sb_material_init(&m, &s, 9), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_material_init_msg(&m, &s, 1, err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "n_thick") != NULL);
    CHECK_EQ_INT(sb_material_init(&m, &s, 8), SB_OK);
    CHECK_EQ_INT(sb_material_init(&m, &s, -1), SB_ERR_INPUT);
    s.kind = (sb_material_kind)7;
    CHECK_EQ_INT(sb_material_init(&m, &s, 0), SB_ERR_INPUT);
    sb_material_spec_denim(&s);
    s.denim.alpha[0][2] = 0.0;
    CHECK_EQ_INT(sb_material_init_msg(&m, &s, 0, err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "alpha") != NULL);
    sb_material_spec_denim(&s);
    s.denim.d[3] = 6;
    CHECK_EQ_INT(sb_material_init(&m, &s, 0), SB_ERR_INPUT);
    sb_material_spec_denim(&s);
    CHECK_EQ_INT(sb_material_init(&m, &s, 0), SB_OK);
    CHECK_EQ_INT(m.n_thick, SB_DENIM_N_THICK);
    CHECK_EQ_INT(sb_material_init(NULL, &s, 0), SB_ERR_INPUT);
}

SB_TEST(gauss_rules)
{
    for (int n = 1; n <= SB_MAX_THICK; n++) {
        double x[SB_MAX_THICK], w[SB_MAX_THICK];
        CHECK_EQ_INT(sb_gauss_legendre(n, x, w), SB_OK);
        /* exact for degree <= 2n-1: int_{-1}^{1} t^p = 2/(p+1) for even p */
        for (int p = 0; p <= 2 * n - 1; p++) {
            double s = 0;
            for (int i = 0; i < n; i++) s += w[i] * pow(x[i], p);
            CHECK_NEAR(s, p % 2 ? 0.0 : 2.0 / (p + 1), 1e-14);
        }
        /* and not for degree 2n */
        double s = 0;
        for (int i = 0; i < n; i++) s += w[i] * pow(x[i], 2 * n);
        CHECK(fabs(s - 2.0 / (2 * n + 1)) > 1e-6);
    }
    CHECK_EQ_INT(sb_gauss_legendre(0, NULL, NULL), SB_ERR_INPUT);
    /* thickness points in metres: sum w = h, sum w xi^2 = h^3/12 */
    sb_material m = denim(5);
    double sw = 0, s2 = 0;
    for (int i = 0; i < m.n_thick; i++) {
        sw += m.thick_w[i];
        s2 += m.thick_w[i] * m.thick_pt[i] * m.thick_pt[i];
        CHECK(fabs(m.thick_pt[i]) < 0.5 * m.thickness);
    }
    CHECK_REL(sw, m.thickness, 1e-14);
    CHECK_REL(s2, pow(m.thickness, 3) / 12, 1e-13);
}

/* The hand-written rules are kept for their committed bits (sb_material.c);
 * they must still be GSL's Gauss-Legendre rules up to round-off: nodes within
 * 2 eps and weights within 8 eps relative of GSL's (measured: 1 ulp and 6 ulp
 * = 3.7 eps at most; zero nodes exactly zero). */
SB_TEST(gauss_rules_match_gsl)
{
    for (int n = 1; n <= SB_MAX_THICK; n++) {
        double x[SB_MAX_THICK], w[SB_MAX_THICK];
        CHECK_EQ_INT(sb_gauss_legendre(n, x, w), SB_OK);
        gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc((size_t)n);
        CHECK(t != NULL);
        if (!t) return;
        for (int i = 0; i < n; i++) {
            double xg, wg;
            CHECK_EQ_INT(gsl_integration_glfixed_point(-1.0, 1.0, (size_t)i, &xg, &wg, t), GSL_SUCCESS);
            CHECK_NEAR(x[i], xg, 2 * DBL_EPSILON * fabs(xg));
            CHECK_NEAR(w[i], wg, 8 * DBL_EPSILON * fabs(wg));
        }
        gsl_integration_glfixed_table_free(t);
    }
}

/* The bisections of the denim admissible range are kept for their committed
 * bits (sb_material.c); they must find what GSL's Brent solver finds, to
 * round-off: u_max where phi_3' reaches 0, and the join where phi_3'' = 0
 * (the peak of phi_3'), on brackets chosen independently of the code. */
typedef struct { const sb_denim_params *p; int j, order; } phi_root;
static double phi_deriv(double u, void *data)
{
    const phi_root *r = data;
    double d1, d2;
    sb_denim_phi(r->p, r->j, u, &d1, &d2);
    return r->order == 1 ? d1 : d2;
}

SB_TEST(denim_range_matches_brent)
{
    sb_material m = denim(0);
    phi_root slope = { &m.denim, 2, 1 }, curv = { &m.denim, 2, 2 };
    double u_max, u_join;
    int it;
    /* phi_3' > 0 at 0.05, < 0 at 0.15; phi_3'' > 0 at 0.05, < 0 at 0.09 */
    CHECK_EQ_INT(sb_root_brent(phi_deriv, &slope, 0.05, 0.15, 0.0, 4 * DBL_EPSILON, 200, &u_max, &it), SB_OK);
    CHECK_REL(m.denim_u_max[2], u_max, 1e-14);
    CHECK_EQ_INT(sb_root_brent(phi_deriv, &curv, 0.05, 0.09, 0.0, 4 * DBL_EPSILON, 200, &u_join, &it), SB_OK);
    CHECK_REL(m.denim_join_hi[2], u_join, 1e-14);
    CHECK(u_join < u_max);
}

/* Reduced re-run of the convergence check documented in sb_material.c:
 * random membrane strains, bending radius R in [2 cm, 2 m]; the default
 * n_thick must keep energy, membrane force and moment errors below 1e-3
 * against a composite 16 x 8-point Gauss rule. */
static double thick_integral(const sb_material *m, const double A[3], const double K[3], int n, int sub,
                             double fA[3], double fK[3])
{
    double gx[SB_MAX_THICK], gw[SB_MAX_THICK], h = m->thickness, s = 0;
    sb_gauss_legendre(n, gx, gw);
    fA[0] = fA[1] = fA[2] = fK[0] = fK[1] = fK[2] = 0;
    for (int j = 0; j < sub; j++) {
        const double a = -h / 2 + h * j / sub, b = a + h / sub;
        for (int i = 0; i < n; i++) {
            const double xi = 0.5 * (a + b) + 0.5 * (b - a) * gx[i], w = 0.5 * (b - a) * gw[i];
            const double e[3] = { A[0] - xi * K[0], A[1] - xi * K[1], A[2] - xi * K[2] };
            double d[3];
            s += w * sb_material_psi(m, e, d, NULL);
            for (int c = 0; c < 3; c++) {
                fA[c] += w * d[c];
                fK[c] -= w * xi * d[c];
            }
        }
    }
    return s;
}

SB_TEST(denim_thickness_convergence)
{
    sb_material m = denim(0);
    unsigned long long s = 3;
    double worst[SB_MAX_THICK + 1][3];
    memset(worst, 0, sizeof worst);
    for (int t = 0; t < 150; t++) {
        const double A[3] = { tb_rand(&s, -0.02, 0.05), tb_rand(&s, -0.02, 0.05), tb_rand(&s, -0.03, 0.03) };
        const double R = 0.02 * pow(100.0, tb_rand(&s, 0, 1)), th = tb_rand(&s, 0, 3.14159);
        const double K[3] = { cos(th) * cos(th) / R, sin(th) * sin(th) / R, sin(th) * cos(th) / R };
        double rA[3], rK[3], fA[3], fK[3];
        const double ref = thick_integral(&m, A, K, 8, 16, rA, rK);
        for (int n = 2; n <= SB_MAX_THICK; n += 2) {
            const double v = thick_integral(&m, A, K, n, 1, fA, fK);
            double na = 0, da = 0, nk = 0, dk = 0;
            for (int c = 0; c < 3; c++) {
                na += rA[c] * rA[c];
                da += (fA[c] - rA[c]) * (fA[c] - rA[c]);
                nk += rK[c] * rK[c];
                dk += (fK[c] - rK[c]) * (fK[c] - rK[c]);
            }
            worst[n][0] = fmax(worst[n][0], fabs(v - ref) / fabs(ref));
            worst[n][1] = fmax(worst[n][1], sqrt(da / na));
            worst[n][2] = fmax(worst[n][2], sqrt(dk / nk));
        }
    }
    for (int n = 2; n <= SB_MAX_THICK; n += 2)
        printf("    n_thick %d: energy %.1e  membrane force %.1e  moment %.1e\n", n, worst[n][0], worst[n][1],
               worst[n][2]);
    const int nd = SB_DENIM_N_THICK;
    CHECK_MSG(worst[nd][0] < 1e-3 && worst[nd][1] < 1e-3 && worst[nd][2] < 1e-3,
              "default n_thick %d: errors %.2g %.2g %.2g", nd, worst[nd][0], worst[nd][1], worst[nd][2]);
    /* and the check has teeth: 2 points are far off for denim */
    CHECK(worst[2][2] > 1e-2);
    /* StVK: 2 points exact */
    sb_material_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.kind = SB_MAT_STVK;
    sp.young = 1e6;
    sp.poisson = 0.3;
    sp.thickness = 1e-3;
    sb_material st;
    sb_material_init(&st, &sp, 0);
    const double A[3] = { 0.01, 0.02, -0.01 }, K[3] = { 50, -20, 30 };
    double a1[3], k1[3], a2[3], k2[3];
    CHECK_REL(thick_integral(&st, A, K, 2, 1, a1, k1), thick_integral(&st, A, K, 8, 4, a2, k2), 1e-13);
}

static const sb_test_case cases[] = {
    SB_CASE(stvk_lame_and_values),
    SB_CASE(stvk_fd_derivatives),
    SB_CASE(denim_table1_and_assumption),
    SB_CASE(denim_phi_against_direct_formula),
    SB_CASE(denim_small_strain_is_linear_orthotropic),
    SB_CASE(denim_fd_derivatives),
    SB_CASE(denim_nonfinite_guards),
    SB_CASE(denim_admissible_range), SB_CASE(denim_continuation_beyond_fit), SB_CASE(init_rejects_bad_input),
    SB_CASE(gauss_rules), SB_CASE(gauss_rules_match_gsl), SB_CASE(denim_range_matches_brent),
    SB_CASE(denim_thickness_convergence),
    SB_END
};

int main(int argc, char **argv)
{
    return sb_test_main(argc, argv, cases);
}
