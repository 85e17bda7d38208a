/* sb_imperfection.c — the symmetry-breaking imperfection of buckling scenes
 * (the wrinkled sheet of BHEM §7.1, where the paper does not say what it
 * uses): a smooth out-of-plane field delta(s,t) = A * sum_m c_m sin(pi k_m s
 * + phi_m) sin(pi l_m t + psi_m) / sum|c_m| with 32 modes, k_m, l_m in 1..24,
 * drawn once from a fixed-seed LCG (deterministic, level independent,
 * |delta| <= A).  Moved here from methods/bhem/bhem_grid.c unchanged (same
 * arithmetic, same bits) so linear_fem can put its triangle meshes on the
 * same imperfect surface.  The LCG is kept instead of a gsl_rng (issue 31):
 * its draws define the imperfect reference surface of the scenes in
 * results/bhem_report.md, and another stream would be another scene. */
#include "sb_imperfection.h"

#include <math.h>

enum { SB_IMP_MODES = 32 };

static double lcg01(unsigned long long *st)
{
    *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*st >> 11) * (1.0 / 9007199254740992.0);
}

void sb_imperfection_eval(double A, double s, double t, double out[4])
{
    unsigned long long st = 0x5eed5eedULL;
    double c[SB_IMP_MODES], k[SB_IMP_MODES], l[SB_IMP_MODES], ph[SB_IMP_MODES], ps[SB_IMP_MODES];
    double sum = 0.0;
    for (int m = 0; m < SB_IMP_MODES; m++) {
        c[m] = 2.0 * lcg01(&st) - 1.0;
        k[m] = M_PI * (1 + (int)(24.0 * lcg01(&st)));
        l[m] = M_PI * (1 + (int)(24.0 * lcg01(&st)));
        ph[m] = 2.0 * M_PI * lcg01(&st);
        ps[m] = 2.0 * M_PI * lcg01(&st);
        sum += fabs(c[m]);
    }
    out[0] = out[1] = out[2] = out[3] = 0.0;
    for (int m = 0; m < SB_IMP_MODES; m++) {
        double a = k[m] * s + ph[m], b = l[m] * t + ps[m];
        double w = A * c[m] / sum;
        out[0] += w * sin(a) * sin(b);
        out[1] += w * k[m] * cos(a) * sin(b);
        out[2] += w * l[m] * sin(a) * cos(b);
        out[3] += w * k[m] * l[m] * cos(a) * cos(b);
    }
}
