/* sb_material.h — hyperelastic laws for thin shells / cloth.  A material sees
 * only a 2x2 symmetric Green–Lagrange strain in the local orthonormal frame of
 * the reference surface aligned with the warp direction, passed as the three
 * independent entries e = (E11, E22, E12).  Derivatives are taken w.r.t. these
 * three independent variables (so dpsi[2] = 2 S12 for the tensor stress S). */
#ifndef SB_MATERIAL_H
#define SB_MATERIAL_H

#include "../sb_scene.h"

typedef struct sb_material {
    sb_material_kind kind;
    double lambda, mu;          /* stvk plane-stress Lamé: BHEM paper Eq. (8) */
    sb_denim_params denim;      /* denim: RMTR paper Eq. (3.3)-(3.4), k in Pa */
    double thickness;           /* m */
    double density;             /* kg/m^2 */
    double warp_angle;          /* rad */
    int n_thick;                /* Gauss points through the thickness */
    double thick_pt[8], thick_w[8]; /* xi3 positions (m) and weights (m) */
} sb_material;

/* RMTR paper Table 1 denim parameters (k converted from MPa to Pa), with the
 * documented assumption mu_j1 = 1 - sum_{i>=2} mu_ji.  Used by the scene parser. */
void sb_denim_defaults(sb_denim_params *p);

/* n_thick = 0 picks the default: 2 for stvk (exact), the convergence-checked
 * number for denim (see sb_material.c). */
int sb_material_init(sb_material *m, const sb_material_spec *spec, int n_thick);

/* psi per unit reference volume (J/m^3); dpsi[3], d2psi[9] (row-major) optional. */
double sb_material_psi(const sb_material *m, const double e[3], double *dpsi, double *d2psi);

#endif
