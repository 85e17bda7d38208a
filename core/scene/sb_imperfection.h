/* sb_imperfection.h — the deterministic out-of-plane imperfection field of
 * the buckling scenes (method.imperfection of bhem and linear_fem), so that
 * both methods start from the same imperfect reference surface. */
#ifndef SB_IMPERFECTION_H
#define SB_IMPERFECTION_H

/* delta(s,t) = A sum_m c_m sin(pi k_m s + phi_m) sin(pi l_m t + psi_m) / sum|c_m|
 * over 32 modes, k_m, l_m in 1..24, drawn once from a fixed-seed LCG
 * (deterministic, resolution independent, |delta| <= A), with its
 * derivatives: out = { delta, d/ds, d/dt, d2/dsdt } at the grid parameter
 * (s,t).  The bits are those bhem has always used (results/bhem_report.md's
 * wrinkled sheets are made with them). */
void sb_imperfection_eval(double A, double s, double t, double out[4]);

#endif
