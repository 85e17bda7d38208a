/* sb_fit.c — power-law exponent with a t interval (sb_fit.h). */
#include "sb_fit.h"
#include "sb_common.h"

#include <gsl/gsl_cdf.h>
#include <math.h>

int sb_fit_power_law(int k, const double *n, const double *y, double level, sb_power_fit *out)
{
    out->points = 0;
    out->exponent = out->coefficient = out->se = out->lo = out->hi = out->r2 = NAN;
    if (!(level > 0.0 && level < 1.0)) return SB_ERR_INPUT;
    double su = 0, sv = 0;
    int m = 0;
    for (int i = 0; i < k; i++)
        if (n[i] > 0 && y[i] > 0 && isfinite(n[i]) && isfinite(y[i])) {
            su += log(n[i]);
            sv += log(y[i]);
            m++;
        }
    if (m < 2) return SB_ERR_INPUT;
    const double mu = su / m, mv = sv / m;
    double suu = 0, suv = 0, svv = 0;
    for (int i = 0; i < k; i++)
        if (n[i] > 0 && y[i] > 0 && isfinite(n[i]) && isfinite(y[i])) {
            const double du = log(n[i]) - mu, dv = log(y[i]) - mv;
            suu += du * du;
            suv += du * dv;
            svv += dv * dv;
        }
    if (!(suu > 0)) return SB_ERR_INPUT;
    const double p = suv / suu, lc = mv - p * mu;
    double rss = 0;
    for (int i = 0; i < k; i++)
        if (n[i] > 0 && y[i] > 0 && isfinite(n[i]) && isfinite(y[i])) {
            const double r = log(y[i]) - lc - p * log(n[i]);
            rss += r * r;
        }
    out->points = m;
    out->exponent = p;
    out->coefficient = exp(lc);
    out->r2 = svv > 0 ? 1.0 - rss / svv : 1.0;
    if (m > 2) {
        const double se = sqrt(rss / (m - 2) / suu);
        const double t = gsl_cdf_tdist_Pinv(0.5 * (1.0 + level), (double)(m - 2));
        out->se = se;
        out->lo = p - t * se;
        out->hi = p + t * se;
    }
    return SB_OK;
}
