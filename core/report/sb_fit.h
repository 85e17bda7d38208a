/* sb_fit.h — how a cost grows with size: the exponent p of a power law
 * y = c n^p fitted by least squares in log-log, with its confidence
 * interval from Student's t distribution (issue 42, scaling reports).
 *
 * With u = ln n, v = ln y over k points: p = S_uv / S_uu, ln c = mean(v) -
 * p mean(u), residual variance s^2 = sum (v - ln c - p u)^2 / (k - 2), the
 * standard error of p = s / sqrt(S_uu), and the interval p -+ t_{k-2,
 * (1+level)/2} se (GSL's gsl_cdf_tdist_Pinv).  Points with n <= 0 or y <= 0
 * (or non-finite) are left out. */
#ifndef SB_FIT_H
#define SB_FIT_H

typedef struct sb_power_fit {
    int points;          /* points used */
    double exponent;     /* p */
    double coefficient;  /* c */
    double se;           /* standard error of p */
    double lo, hi;       /* the interval at `level` (NaN with 2 points: no residual freedom) */
    double r2;           /* coefficient of determination in log-log */
} sb_power_fit;

/* SB_OK, or SB_ERR_INPUT when fewer than 2 usable points or all n equal,
 * or level outside (0, 1). */
int sb_fit_power_law(int k, const double *n, const double *y, double level, sb_power_fit *out);

#endif
