/* sb_material.c — hyperelastic laws seen by the Kirchhoff–Love kernel and by
 * triangle elements: St. Venant–Kirchhoff (BHEM paper Eq. 7-8) and the
 * orthotropic denim law (RMTR paper Eq. 3.3-3.4, Table 1).
 *
 * A material sees only the strain e = (E11, E22, E12) in the local
 * orthonormal warp/weft frame; derivatives are w.r.t. these three
 * independent numbers, so dpsi[2] = 2 S12 for the tensor stress S. */
#include "sb_material.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* ---- Gauss-Legendre ----------------------------------------------------- */

/* Nodes by Newton's method on P_n with the three-term recurrence
 * (n+1) P_{n+1} = (2n+1) x P_n - n P_{n-1}; weights 2 / ((1-x^2) P_n'(x)^2).
 * Converges to machine precision in a few steps from the Chebyshev-like
 * initial guess cos(pi (i + 3/4) / (n + 1/2)).
 *
 * Kept instead of GSL's gsl_integration_glfixed_table (issue 31) because
 * the committed records depend on these exact bits.  GSL's tabulated rules
 * are correctly rounded; for every n in 2..8 these differ from them in the
 * last bits (nodes by up to 1 ulp, weights by up to 6 ulp = 3.7 eps
 * relative; n = 1 is identical; n = 2: w = 1 + 2^-52 here, 1 in GSL).  With
 * GSL's bits the drooping scene at 363 dofs (RMTR, defaults) takes 156
 * V-cycles instead of the recorded 167 and ends at f = -10.5638 instead of
 * -10.5671 J (measured; round-off moves counts on nonconvex scenes,
 * docs/reproducibility.md).  tests/test_material.c (gauss_rules_match_gsl)
 * checks every rule against GSL's: nodes to 2 eps, weights to 8 eps. */
int sb_gauss_legendre(int n, double *x, double *w)
{
    if (n < 1 || n > SB_MAX_THICK || !x || !w) return SB_ERR_INPUT;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < n; i++) {
        double z = cos(pi * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = z;
            for (int j = 1; j < n; j++) {
                double p2 = ((2 * j + 1) * z * p1 - j * p0) / (j + 1);
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-16) break;
        }
        {   /* final derivative at the converged node */
            double p0 = 1.0, p1 = z;
            for (int j = 1; j < n; j++) {
                double p2 = ((2 * j + 1) * z * p1 - j * p0) / (j + 1);
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
        }
        x[i] = -z;  /* ascending order */
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    if (n % 2 == 1) x[n / 2] = 0.0;
    return SB_OK;
}

/* ---- denim parameters (RMTR paper Table 1) -------------------------------- */

void sb_denim_defaults(sb_denim_params *p)
{
    memset(p, 0, sizeof *p);
    /* k_i in MPa in Table 1, stored in Pa. */
    p->k[0] = 4.79e6;
    p->k[1] = 4.52e6;
    p->k[2] = 9.03e6;
    p->k[3] = 2.44e6;
    p->d[0] = 5;
    p->d[1] = 1;
    p->d[2] = 5;
    p->d[3] = 3;
    /* mu[j][i] = mu_{j+1, i+1}, alpha likewise (Table 1). */
    static const double mu1[5] = { 0, -1482.1, 276.43, 2407.67, 3416.79 };
    static const double al1[5] = { -7.80, 10.80, 18.95, -12.89, 1.61 };
    static const double mu3[5] = { 0, 0.658, -185.7, -45.82, 146.98 };
    static const double al3[5] = { 12.71, -12802.0, 17.91, 30.07, 24.68 };
    static const double mu4[3] = { 0, 0.79, 11.08 };
    static const double al4[3] = { 2.95, -2823.9, 4.29 };
    for (int i = 0; i < 5; i++) {
        p->mu[0][i] = mu1[i];
        p->alpha[0][i] = al1[i];
        p->mu[2][i] = mu3[i];
        p->alpha[2][i] = al3[i];
    }
    for (int i = 0; i < 3; i++) {
        p->mu[3][i] = mu4[i];
        p->alpha[3][i] = al4[i];
    }
    p->alpha[1][0] = 1.0;   /* alpha_21 = 1, d_2 = 1 */
    /* ASSUMPTION (Table 1 omits mu_j1): mu_j1 = 1 - sum_{i>=2} mu_ji, so that
     * phi_j'(0) = sum_i mu_ji = 1 and k_j is the small-strain stiffness.
     * For j = 2 (d_2 = 1, alpha_21 = 1) this gives phi_2(u) = u.
     * Resulting values: mu_11 = -4617.79, mu_21 = 1, mu_31 = 84.882,
     * mu_41 = -10.87. */
    for (int j = 0; j < 4; j++) {
        double s = 0.0;
        for (int i = 1; i < p->d[j]; i++) s += p->mu[j][i];
        p->mu[j][0] = 1.0 - s;
    }
}

void sb_material_spec_denim(sb_material_spec *s)
{
    memset(s, 0, sizeof *s);
    s->kind = SB_MAT_DENIM;
    sb_denim_defaults(&s->denim);
    s->thickness = 0.66e-3;   /* Table 1: tau = 0.66 mm */
    s->density = 0.4;         /* Table 1: rho = 0.4 kg/m^2 (areal) */
    s->warp_angle = 0.0;
}

/* ---- default number of thickness points ------------------------------------
 *
 * stvk: psi is quadratic in xi3, so 2 Gauss points are exact (BHEM Eq. 7).
 * denim: (3.3)-(3.4) is far from polynomial (alpha_32 = -12802 saturates
 * phi_3 at |E22| ~ 1/sqrt(12802) ~ 0.009), so the integrand in xi3 has a
 * steep feature once the bending strain at the surfaces, tau/(2R), reaches
 * about 1 %.  Convergence check (tests/test_material.c, denim_thickness_
 * convergence, re-runs a reduced version): 2000 random states, membrane
 * strains E11, E22 in [-0.02, 0.05], E12 in [-0.03, 0.03], bending radius R
 * log-uniform in [Rmin, 100 Rmin] in a random direction, tau = 0.66 mm, worst
 * relative error against a 64 x 8-point composite Gauss rule:
 *
 *   R >= 2 cm (surface bending strain <= 1.65 %)
 *     n   energy   membrane force   bending moment
 *     4   9.2e-4      4.9e-3           1.1e-2
 *     5   9.1e-5      6.7e-4           1.3e-3
 *     6   1.2e-5      8.7e-5           2.9e-4
 *     8   1.9e-7      5.5e-7           6.2e-6
 *   R >= 5 cm: n = 4 already gives 1.5e-6 / 9.1e-6 / 8.7e-5.
 *   R >= 1 cm: n = 6 gives 2.3e-3 / 1.6e-2 / 1.1e-2, n = 8 1.5e-4 / 2.1e-3 / 1.1e-3.
 *
 * Default: n_thick = 6 (SB_DENIM_N_THICK), the smallest n whose energy,
 * membrane-force and moment errors are all below 1e-3 for R >= 2 cm, i.e. for
 * folds of radius >= 30 thicknesses.  Sharper folds need n_thick = 8 (the
 * maximum); the cost of the kernel grows linearly with n_thick. */

/* ---- init ------------------------------------------------------------------ */

static int fail(char *err, size_t len, const char *fmt, ...)
{
    if (err && len) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, len, fmt, ap);
        va_end(ap);
    }
    return SB_ERR_INPUT;
}

static void denim_admissible_range(sb_material *m, int j);

int sb_material_init_msg(sb_material *m, const sb_material_spec *spec, int n_thick,
                         char *err, size_t errlen)
{
    if (err && errlen) err[0] = '\0';
    if (!m || !spec) return fail(err, errlen, "material: NULL argument");
    memset(m, 0, sizeof *m);
    if (!(isfinite(spec->thickness) && spec->thickness > 0))
        return fail(err, errlen, "material.thickness = %g: must be finite and > 0", spec->thickness);
    if (!(isfinite(spec->density) && spec->density >= 0))
        return fail(err, errlen, "material.density = %g: must be finite and >= 0", spec->density);
    if (!isfinite(spec->warp_angle))
        return fail(err, errlen, "material.warp_angle = %g: must be finite", spec->warp_angle);
    /* one point (xi3 = 0) would see no bending strain at all: rejected */
    if (n_thick < 0 || n_thick == 1 || n_thick > SB_MAX_THICK)
        return fail(err, errlen, "n_thick = %d: must be 0 (default) or lie in 2..%d (one point sees no bending)",
                    n_thick, SB_MAX_THICK);

    m->kind = spec->kind;
    m->thickness = spec->thickness;
    m->density = spec->density;
    m->warp_angle = spec->warp_angle;

    switch (spec->kind) {
    case SB_MAT_STVK: {
        double Y = spec->young, nu = spec->poisson;
        if (!(isfinite(Y) && Y > 0))
            return fail(err, errlen, "material.young = %g: must be finite and > 0", Y);
        /* plane-stress stiffness is positive definite iff -1 < nu < 1 */
        if (!(isfinite(nu) && nu > -1.0 && nu < 1.0))
            return fail(err, errlen, "material.poisson = %g: must lie in (-1, 1)", nu);
        /* BHEM paper Eq. (8): lambda = Y nu / (1 - nu^2), mu = Y / (2 (1 + nu)) */
        m->lambda = Y * nu / (1.0 - nu * nu);
        m->mu = Y / (2.0 * (1.0 + nu));
        if (n_thick == 0) n_thick = SB_STVK_N_THICK;
        break;
    }
    case SB_MAT_DENIM: {
        const sb_denim_params *p = &spec->denim;
        for (int j = 0; j < 4; j++) {
            if (!(isfinite(p->k[j]) && p->k[j] >= 0))
                return fail(err, errlen, "material.denim.k[%d] = %g: must be finite and >= 0", j + 1, p->k[j]);
            if (p->d[j] < 1 || p->d[j] > SB_DENIM_MAX_TERMS)
                return fail(err, errlen, "material.denim.d[%d] = %d: must lie in 1..%d", j + 1, p->d[j],
                            SB_DENIM_MAX_TERMS);
            for (int i = 0; i < p->d[j]; i++) {
                if (!isfinite(p->mu[j][i]))
                    return fail(err, errlen, "material.denim.mu[%d][%d] is not finite", j + 1, i + 1);
                if (!(isfinite(p->alpha[j][i]) && p->alpha[j][i] != 0.0))
                    return fail(err, errlen, "material.denim.alpha[%d][%d] = %g: must be finite and != 0",
                                j + 1, i + 1, p->alpha[j][i]);
            }
        }
        m->denim = *p;
        for (int j = 0; j < 4; j++) {
            m->denim_linear[j] = 1;
            for (int i = 0; i < p->d[j]; i++) {
                m->denim_mu_over_alpha[j][i] = p->mu[j][i] / p->alpha[j][i];
                m->denim_mu_alpha_m1[j][i] = p->mu[j][i] * (p->alpha[j][i] - 1.0);
                if (p->alpha[j][i] != 1.0) m->denim_linear[j] = 0;
            }
        }
        for (int j = 0; j < 4; j++) denim_admissible_range(m, j);
        if (n_thick == 0) n_thick = SB_DENIM_N_THICK;
        break;
    }
    default:
        return fail(err, errlen, "material.kind = %d: unknown", (int)spec->kind);
    }

    /* Gauss points on [-h/2, h/2] in metres: sum w f(xi3) ~ int f dxi3. */
    double gx[SB_MAX_THICK], gw[SB_MAX_THICK];
    sb_gauss_legendre(n_thick, gx, gw);
    m->n_thick = n_thick;
    for (int i = 0; i < n_thick; i++) {
        m->thick_pt[i] = 0.5 * m->thickness * gx[i];
        m->thick_w[i] = 0.5 * m->thickness * gw[i];
    }
    return SB_OK;
}

int sb_material_init(sb_material *m, const sb_material_spec *spec, int n_thick)
{
    return sb_material_init_msg(m, spec, n_thick, NULL, 0);
}

/* ---- St. Venant–Kirchhoff -------------------------------------------------- */

/* psi(E) = lambda/2 (tr E)^2 + mu tr(E^2)   (BHEM paper Eq. 7-8 in an
 * orthonormal frame, where abar^{alpha beta} = delta).  With e = (E11, E22, E12):
 * tr E = e0 + e1, tr(E^2) = e0^2 + e1^2 + 2 e2^2. */
static double stvk_psi(const sb_material *m, const double e[3], double *dpsi, double *d2psi)
{
    const double la = m->lambda, mu = m->mu, tr = e[0] + e[1];
    if (dpsi) {
        dpsi[0] = la * tr + 2.0 * mu * e[0];
        dpsi[1] = la * tr + 2.0 * mu * e[1];
        dpsi[2] = 4.0 * mu * e[2];
    }
    if (d2psi) {
        d2psi[0] = la + 2.0 * mu; d2psi[1] = la;             d2psi[2] = 0.0;
        d2psi[3] = la;            d2psi[4] = la + 2.0 * mu;  d2psi[5] = 0.0;
        d2psi[6] = 0.0;           d2psi[7] = 0.0;            d2psi[8] = 4.0 * mu;
    }
    return 0.5 * la * tr * tr + mu * (e[0] * e[0] + e[1] * e[1] + 2.0 * e[2] * e[2]);
}

/* ---- denim ------------------------------------------------------------------- */

/* RMTR paper Eq. (3.4): phi_j(u) = sum_i mu_ji / alpha_ji ((u+1)^alpha_ji - 1).
 *
 * Numerics.  Several |alpha| are large (alpha_32 = -12802, alpha_42 = -2823.9),
 * so (u+1)^alpha - 1 is evaluated as expm1(alpha log1p(u)): no cancellation
 * for small u, and for large |alpha log1p(u)| exp() under/overflows cleanly
 * (u + 1 > 1 with alpha < 0 -> 0, harmless; overflow -> +Inf, reported as a
 * non-finite energy by the caller).
 *   phi'  = sum mu (u+1)^(alpha-1),  phi'' = sum mu (alpha-1) (u+1)^(alpha-2).
 * Domain guard: u = E11^2, E22^2, E12^2 >= 0 always; u = E11 E22 (j = 2) can be
 * negative.  A term with alpha = 1 is evaluated exactly as mu u (valid for every
 * u; this is the whole of phi_2 with Table 1).  For any other alpha, u <= -1 is
 * outside the domain of (u+1)^alpha and the result is NaN on purpose. */
double sb_denim_phi(const sb_denim_params *p, int j, double u, double *d1, double *d2)
{
    double f = 0.0, g = 0.0, h = 0.0;
    const double L = log1p(u), inv = 1.0 / (1.0 + u);
    const int outside = !(u > -1.0);
    for (int i = 0; i < p->d[j]; i++) {
        const double mu = p->mu[j][i], al = p->alpha[j][i];
        if (al == 1.0) {
            f += mu * u;
            g += mu;
            continue;
        }
        if (outside) {
            f = g = h = NAN;
            break;
        }
        const double em1 = expm1(al * L);        /* (u+1)^alpha - 1 */
        const double pw = em1 + 1.0;             /* (u+1)^alpha, one transcendental per term */
        f += mu / al * em1;
        g += mu * pw * inv;                      /* mu (u+1)^(alpha-1) */
        h += mu * (al - 1.0) * pw * inv * inv;   /* mu (alpha-1) (u+1)^(alpha-2) */
    }
    if (d1) *d1 = g;
    if (d2) *d2 = h;
    return f;
}

/* Same as sb_denim_phi with the coefficients cached in m (hot path):
 * phi = sum c0 em1,  phi' = inv sum mu (em1 + 1),  phi'' = inv^2 sum c2 (em1 + 1)
 * with em1 = expm1(alpha log1p(u)), inv = 1/(1+u), c0 = mu/alpha, c2 = mu (alpha-1).
 * Same domain guard as sb_denim_phi. */
static inline double phi_fast(const sb_material *m, int j, double u, double *d1, double *d2)
{
    const sb_denim_params *p = &m->denim;
    const int d = p->d[j];
    if (m->denim_linear[j]) {   /* every alpha = 1: phi = (sum mu) u */
        double s = 0.0;
        for (int i = 0; i < d; i++) s += p->mu[j][i];
        *d1 = s;
        *d2 = 0.0;
        return s * u;
    }
    if (!(u > -1.0)) {
        *d1 = *d2 = NAN;
        return NAN;
    }
    const double L = log1p(u);
    double f = 0.0, g = 0.0, g1 = 0.0, h = 0.0;
    for (int i = 0; i < d; i++) {
        const double al = p->alpha[j][i], mu = p->mu[j][i];
        if (al == 1.0) {   /* exact linear term */
            f += mu * u;
            g1 += mu;
            continue;
        }
        const double em1 = expm1(al * L), pw = em1 + 1.0;
        f += m->denim_mu_over_alpha[j][i] * em1;
        g += mu * pw;
        h += m->denim_mu_alpha_m1[j][i] * pw;
    }
    const double inv = 1.0 / (1.0 + u);
    *d1 = g1 + g * inv;
    *d2 = h * inv * inv;
    return f;
}

/* Admissible range of phi_j (assumption; the RMTR paper is silent).  Table
 * 1's fit is a sum of powers (u+1)^alpha with coefficients of both signs, and
 * the weft law phi_3 loses monotonicity at u ~ 0.1025 (Green weft strain
 * ~ 0.32) and is unbounded below beyond it: a trust-region or line-search
 * trial step that reaches that branch would see an arbitrarily large "energy
 * decrease" and be accepted.  We therefore treat every state whose argument
 * leaves [u_min, u_max] — the interval around 0 on which phi_j' > 0 — as
 * inadmissible: the energy is NaN there, so trial points are rejected and the
 * solvers back off; a converged state never lies there.  The interval is
 * found by scanning phi_j' on a fine grid and refining by bisection. */
static double phi_prime(const sb_material *m, int j, double u)
{
    double d1, d2;
    phi_fast(m, j, u, &d1, &d2);
    return d1;
}

static double first_nonmonotone(const sb_material *m, int j, double dir, double limit)
{
    const int n = 4000;
    double prev = 0.0;
    for (int k = 1; k <= n; k++) {
        double u = dir * limit * k / n;
        double d = phi_prime(m, j, u);
        if (!(d > 0.0)) {
            double lo = prev, hi = u;         /* phi' > 0 at lo, <= 0 (or NaN) at hi */
            for (int it = 0; it < 60; it++) {
                double mid = 0.5 * (lo + hi);
                if (phi_prime(m, j, mid) > 0.0) lo = mid;
                else hi = mid;
            }
            return lo;
        }
        prev = u;
    }
    return dir * INFINITY;
}

/* Where phi_j' is largest on the admissible side [0, bound] (bound finite):
 * scanned on a grid, an interior maximum refined by bisection on phi_j'' = 0.
 *
 * The bisections here are kept instead of GSL's Brent solver (issue 31)
 * because the committed records depend on their exact bits.  Both run to
 * the last bit, but phi_j' and phi_j'' change sign noisily in their last
 * bits near a root, so the two methods stop at different doubles: for
 * Table 1's weft law Brent (sb_root_brent) gives u_max 15 ulp and the join
 * u_join_hi 2 ulp away from the bisection, and with Brent's join the drape
 * at 1,083 dofs (RMTR, defaults) takes 782 V-cycles instead of the recorded
 * 679 (measured).  tests/test_material.c
 * (denim_range_matches_brent) checks both points against Brent's. */
static double argmax_slope(const sb_material *m, int j, double bound)
{
    const int n = 2000;
    int kbest = 0;
    double best = phi_prime(m, j, 0.0);
    for (int k = 1; k < n; k++) {
        double d = phi_prime(m, j, bound * k / n);
        if (d > best) { best = d; kbest = k; }
    }
    if (kbest == 0) return 0.0;
    double lo = bound * (kbest - 1) / n, hi = bound * (kbest + 1) / n;   /* phi' rises at lo, falls at hi */
    for (int it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi), d1, d2;
        phi_fast(m, j, mid, &d1, &d2);
        if ((d2 > 0.0) == (bound > 0.0)) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

static void denim_admissible_range(sb_material *m, int j)
{
    m->denim_u_max[j] = first_nonmonotone(m, j, 1.0, 100.0);
    /* only the mixed argument u_2 = E11 E22 can be negative; the others are squares */
    m->denim_u_min[j] = j == 1 ? first_nonmonotone(m, j, -1.0, 1.0 - 1e-9) : 0.0;
    if (m->denim_linear[j]) {
        m->denim_u_max[j] = INFINITY;
        m->denim_u_min[j] = -INFINITY;
    }
    /* Continuation beyond the fit (ASSUMPTION, the paper is silent): past the
     * point where phi_j' peaks inside the admissible range, phi_j continues
     * linearly with that peak slope.  The join is C^2 at an interior peak
     * (phi_j'' = 0 there), each term k_j/2 phi_j(E^2) stays convex in E, and the
     * energy is bounded below, so every configuration has a finite energy —
     * a coarse level of a multilevel hierarchy or a far trial point included —
     * while states inside the fit up to the peak are unchanged. */
    double d2;
    m->denim_join_hi[j] = isfinite(m->denim_u_max[j]) ? argmax_slope(m, j, m->denim_u_max[j]) : INFINITY;
    m->denim_join_lo[j] = j == 1 && isfinite(m->denim_u_min[j]) ? argmax_slope(m, j, m->denim_u_min[j]) : -INFINITY;
    if (isfinite(m->denim_join_hi[j]))
        m->denim_fj_hi[j] = phi_fast(m, j, m->denim_join_hi[j], &m->denim_gj_hi[j], &d2);
    if (isfinite(m->denim_join_lo[j]))
        m->denim_fj_lo[j] = phi_fast(m, j, m->denim_join_lo[j], &m->denim_gj_lo[j], &d2);
}

/* phi_j with the continuation beyond the fit (see denim_admissible_range) */
static inline double phi_cont(const sb_material *m, int j, double u, double *d1, double *d2)
{
    if (u > m->denim_join_hi[j]) {
        *d1 = m->denim_gj_hi[j];
        *d2 = 0.0;
        return m->denim_fj_hi[j] + m->denim_gj_hi[j] * (u - m->denim_join_hi[j]);
    }
    if (u < m->denim_join_lo[j]) {
        *d1 = m->denim_gj_lo[j];
        *d2 = 0.0;
        return m->denim_fj_lo[j] + m->denim_gj_lo[j] * (u - m->denim_join_lo[j]);
    }
    return phi_fast(m, j, u, d1, d2);
}

/* RMTR paper Eq. (3.3):
 *   psi = k1/2 phi1(E11^2) + k2 phi2(E11 E22) + k3/2 phi3(E22^2) + k4 phi4(E12^2)
 * with E the strain in the warp/weft frame (E~ = O^T E O of the paper).
 * Chain rule with u1 = e0^2, u2 = e0 e1, u3 = e1^2, u4 = e2^2. */
static double denim_psi(const sb_material *m, const double e[3], double *dpsi, double *d2psi)
{
    const double *k = m->denim.k;
    double g1, g2, g3, g4, h1, h2, h3, h4;
    const double e0 = e[0], e1 = e[1], e2 = e[2];
    const double u1 = e0 * e0, u2 = e0 * e1, u3 = e1 * e1, u4 = e2 * e2;
    if (m->denim.beyond_fit &&
        (u1 > m->denim_u_max[0] || u2 > m->denim_u_max[1] || u2 < m->denim_u_min[1] || u3 > m->denim_u_max[2] ||
         u4 > m->denim_u_max[3])) {
        /* outside the admissible range (see denim_admissible_range) */
        if (dpsi) dpsi[0] = dpsi[1] = dpsi[2] = NAN;
        if (d2psi) for (int i = 0; i < 9; i++) d2psi[i] = NAN;
        return NAN;
    }
    double f1, f2, f3, f4;
    if (m->denim.beyond_fit) {
        f1 = phi_fast(m, 0, u1, &g1, &h1);
        f2 = phi_fast(m, 1, u2, &g2, &h2);
        f3 = phi_fast(m, 2, u3, &g3, &h3);
        f4 = phi_fast(m, 3, u4, &g4, &h4);
    } else {
        f1 = phi_cont(m, 0, u1, &g1, &h1);
        f2 = phi_cont(m, 1, u2, &g2, &h2);
        f3 = phi_cont(m, 2, u3, &g3, &h3);
        f4 = phi_cont(m, 3, u4, &g4, &h4);
    }
    if (dpsi) {
        dpsi[0] = k[0] * g1 * e0 + k[1] * g2 * e1;
        dpsi[1] = k[1] * g2 * e0 + k[2] * g3 * e1;
        dpsi[2] = 2.0 * k[3] * g4 * e2;
    }
    if (d2psi) {
        d2psi[0] = k[0] * (g1 + 2.0 * e0 * e0 * h1) + k[1] * h2 * e1 * e1;
        d2psi[1] = k[1] * (g2 + h2 * e0 * e1);
        d2psi[2] = 0.0;
        d2psi[3] = d2psi[1];
        d2psi[4] = k[2] * (g3 + 2.0 * e1 * e1 * h3) + k[1] * h2 * e0 * e0;
        d2psi[5] = 0.0;
        d2psi[6] = 0.0;
        d2psi[7] = 0.0;
        d2psi[8] = 2.0 * k[3] * (g4 + 2.0 * e2 * e2 * h4);
    }
    return 0.5 * k[0] * f1 + k[1] * f2 + 0.5 * k[2] * f3 + k[3] * f4;
}

double sb_material_psi(const sb_material *m, const double e[3], double *dpsi, double *d2psi)
{
    switch (m->kind) {
    case SB_MAT_STVK: return stvk_psi(m, e, dpsi, d2psi);
    case SB_MAT_DENIM: return denim_psi(m, e, dpsi, d2psi);
    }
    if (dpsi) dpsi[0] = dpsi[1] = dpsi[2] = NAN;
    if (d2psi) for (int i = 0; i < 9; i++) d2psi[i] = NAN;
    return NAN;
}
