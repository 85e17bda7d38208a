/* test_fit.c — the power-law fit of scaling reports (sb_fit.h): synthetic
 * series with known exponents and noise, the interval's width and coverage. */
#include "sb_common.h"
#include "sb_fit.h"
#include "sb_test.h"

#include <math.h>

/* a deterministic noise of relative size a: multiplicative, mean-free */
static double noise(int i, double a)
{
    unsigned long long z = 0x9E3779B97F4A7C15ull * (unsigned long long)(i + 1);
    z = (z ^ (z >> 31)) * 0xBF58476D1CE4E5B9ull;
    z ^= z >> 29;
    return 1.0 + a * (2.0 * ((double)(z >> 11) * 0x1.0p-53) - 1.0);
}

/* measured-looking series: c n^p times a fixed relative scatter of up to
 * 4 % (a = 1), or exact (a = 0) */
static void series(int k, double p, double c, double a, double *n, double *y)
{
    static const double scatter[6] = { 0.03, -0.04, 0.02, -0.01, 0.04, -0.03 };
    for (int i = 0; i < k; i++) {
        n[i] = 1e3 * pow(4.0, i);          /* the study's dof targets: 1e3 .. 2.56e5 */
        y[i] = c * pow(n[i], p) * (1.0 + a * scatter[i % 6]);
    }
}

SB_TEST(linear_series_gives_one)
{
    double n[6], y[6];
    sb_power_fit f;
    series(6, 1.0, 2e-6, 1.0, n, y);
    CHECK_EQ_INT(sb_fit_power_law(6, n, y, 0.95, &f), SB_OK);
    CHECK_EQ_INT(f.points, 6);
    CHECK_MSG(f.lo <= 1.0 && 1.0 <= f.hi, "1 outside [%g, %g] (p = %g)", f.lo, f.hi, f.exponent);
    CHECK(f.hi - f.lo < 0.1);
    CHECK(f.r2 > 0.99);
    /* exact data: the exponent and the coefficient exactly, a zero-width interval */
    series(5, 1.0, 3.0, 0.0, n, y);
    CHECK_EQ_INT(sb_fit_power_law(5, n, y, 0.95, &f), SB_OK);
    CHECK_NEAR(f.exponent, 1.0, 1e-12);
    CHECK_REL(f.coefficient, 3.0, 1e-10);
    CHECK(f.hi - f.lo < 1e-10);
}

SB_TEST(three_halves_series_gives_one_and_a_half)
{
    double n[6], y[6];
    sb_power_fit f;
    series(6, 1.5, 1e-8, 1.0, n, y);
    CHECK_EQ_INT(sb_fit_power_law(6, n, y, 0.95, &f), SB_OK);
    CHECK_MSG(f.lo <= 1.5 && 1.5 <= f.hi, "1.5 outside [%g, %g] (p = %g)", f.lo, f.hi, f.exponent);
    CHECK_MSG(!(f.lo <= 1.0 && 1.0 <= f.hi), "1 inside [%g, %g]: O(n^1.5) not told from O(n)", f.lo, f.hi);
    /* the largest four sizes, as the report fits them */
    CHECK_EQ_INT(sb_fit_power_law(4, n + 2, y + 2, 0.95, &f), SB_OK);
    CHECK_MSG(f.lo <= 1.5 && 1.5 <= f.hi, "1.5 outside [%g, %g] over the largest four", f.lo, f.hi);
}

/* The t interval's coverage over many noisy series: about 95 % (a z
 * interval with 2 degrees of freedom would cover far less). */
SB_TEST(interval_covers_at_its_level)
{
    int covered = 0, trials = 2000;
    for (int t = 0; t < trials; t++) {
        double n[4], y[4];
        for (int i = 0; i < 4; i++) {
            n[i] = 1e3 * pow(4.0, i);
            /* log-normal-ish noise from a sum of uniforms (Irwin-Hall, 12 terms) */
            double s = 0;
            for (int j = 0; j < 12; j++) s += noise(t * 1000 + i * 16 + j, 1.0);
            y[i] = n[i] * exp(0.1 * (s - 12.0));
        }
        sb_power_fit f;
        if (sb_fit_power_law(4, n, y, 0.95, &f) == SB_OK && f.lo <= 1.0 && 1.0 <= f.hi) covered++;
    }
    const double share = (double)covered / trials;
    CHECK_MSG(share > 0.93 && share < 0.97, "coverage %.3f of a 95 %% interval", share);
}

SB_TEST(bad_input_is_refused)
{
    double n[3] = { 1e3, 1e3, 1e3 }, y[3] = { 1, 2, 3 }, z[3] = { 0, -1, NAN };
    sb_power_fit f;
    CHECK_EQ_INT(sb_fit_power_law(3, n, y, 0.95, &f), SB_ERR_INPUT);   /* one size */
    CHECK_EQ_INT(sb_fit_power_law(3, y, z, 0.95, &f), SB_ERR_INPUT);   /* no usable y */
    CHECK_EQ_INT(sb_fit_power_law(3, y, y, 1.5, &f), SB_ERR_INPUT);    /* level */
    /* two points: an exponent, no interval */
    CHECK_EQ_INT(sb_fit_power_law(2, y, y, 0.95, &f), SB_OK);
    CHECK_NEAR(f.exponent, 1.0, 1e-12);
    CHECK(isnan(f.lo) && isnan(f.hi));
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(linear_series_gives_one),
        SB_CASE(three_halves_series_gives_one_and_a_half),
        SB_CASE(interval_covers_at_its_level),
        SB_CASE(bad_input_is_refused),
        SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
