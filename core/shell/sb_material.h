/* sb_material.h — hyperelastic laws for thin shells / cloth.  A material sees
 * only a 2x2 symmetric Green–Lagrange strain in the local orthonormal frame of
 * the reference surface aligned with the warp direction, passed as the three
 * independent entries e = (E11, E22, E12).  Derivatives are taken w.r.t. these
 * three independent variables (so dpsi[2] = 2 S12 for the tensor stress S). */
#ifndef SB_MATERIAL_H
#define SB_MATERIAL_H

#include "sb_scene.h"

typedef struct sb_material {
    sb_material_kind kind;
    double lambda, mu;          /* stvk plane-stress Lamé: BHEM paper Eq. (8) */
    sb_denim_params denim;      /* denim: RMTR paper Eq. (3.3)-(3.4), k in Pa */
    double thickness;           /* m */
    double density;             /* kg/m^2 */
    double warp_angle;          /* rad */
    int n_thick;                /* Gauss points through the thickness */
    double thick_pt[8], thick_w[8]; /* xi3 positions (m) and weights (m) */
    /* added (additive): denim coefficients cached by sb_material_init, so
     * re-run sb_material_init after changing `denim`:  mu/alpha, mu (alpha-1),
     * and whether phi_j is linear (every alpha_ji = 1) */
    double denim_mu_over_alpha[4][SB_DENIM_MAX_TERMS];
    double denim_mu_alpha_m1[4][SB_DENIM_MAX_TERMS];
    int denim_linear[4];
    /* admissible range of each phi_j argument: [u_min, u_max] up to the first
     * loss of monotonicity of phi_j (see sb_material.c, denim_admissible_range) */
    double denim_u_min[4], denim_u_max[4];
    /* continuation beyond the fit (beyond_fit = extend): past u_join_hi (below
     * u_join_lo) phi_j is continued linearly from its value f_join and slope
     * g_join there (the maximum of phi_j' inside the admissible range) */
    double denim_join_hi[4], denim_join_lo[4];
    double denim_fj_hi[4], denim_gj_hi[4], denim_fj_lo[4], denim_gj_lo[4];
} sb_material;

/* RMTR paper Table 1 denim parameters (k converted from MPa to Pa), with the
 * documented assumption mu_j1 = 1 - sum_{i>=2} mu_ji.  Used by the scene parser. */
void sb_denim_defaults(sb_denim_params *p);

/* n_thick = 0 picks the default: 2 for stvk (exact), the convergence-checked
 * number for denim (see sb_material.c); otherwise 2..SB_MAX_THICK.  Returns
 * SB_OK or SB_ERR_INPUT (see sb_material_init_msg for the message). */
int sb_material_init(sb_material *m, const sb_material_spec *spec, int n_thick);

/* psi per unit reference volume (J/m^3); dpsi[3], d2psi[9] (row-major) optional.
 * Non-finite strain, or a denim argument outside the domain of (3.4)
 * (u + 1 <= 0 in a term with alpha != 1), gives a NaN result (the caller
 * records SB_NONFINITE); it never crashes. */
double sb_material_psi(const sb_material *m, const double e[3], double *dpsi, double *d2psi);

/* ---- additions (issue 3 implementer; additive only) --------------------- */

/* Default Gauss points through the thickness: stvk is exact with 2 (psi is
 * quadratic in xi3); denim's default comes from the convergence check
 * documented in sb_material.c (tests/test_material.c re-runs it). */
#define SB_STVK_N_THICK 2
#define SB_DENIM_N_THICK 6
#define SB_MAX_THICK 8

/* Like sb_material_init, with a message ("material.poisson = 1.2: must lie in
 * (-1, 1)") in err when the input is rejected.  err may be NULL. */
int sb_material_init_msg(sb_material *m, const sb_material_spec *spec, int n_thick,
                         char *err, size_t errlen);

/* A complete spec for the RMTR paper's denim (Table 1): parameters, thickness
 * tau = 0.66 mm, areal density 0.4 kg/m^2, warp along a_1. */
void sb_material_spec_denim(sb_material_spec *s);

/* n-point Gauss-Legendre rule on [-1, 1], 1 <= n <= SB_MAX_THICK. */
int sb_gauss_legendre(int n, double *x, double *w);

/* Denim response function phi_j of RMTR paper Eq. (3.4) and its first two
 * derivatives (d1, d2 optional).  Exposed for tests and reports. */
double sb_denim_phi(const sb_denim_params *p, int j, double u, double *d1, double *d2);

#endif
