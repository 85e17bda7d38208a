/* sb_vmath.h — expm1 and log1p on vectors of SB_VL doubles (sb_simd.h), for
 * the denim law of the fast section (sb_section_fast.c), where the
 * reference calls libm 16 times per thickness point.
 *
 * Both follow the classic argument reductions of fdlibm (Sun Microsystems,
 * s_expm1.c and s_log1p.c) with Taylor polynomials of high enough degree
 * instead of its minimax ones, evaluated by Estrin's scheme; measured error against glibc below 3 ulp
 * over their whole ranges (tests/test_shell_fast.c, vmath_accuracy).
 * Branch-free: special inputs are patched by lane selects at the end.
 * Assumes the default rounding mode (round to nearest). */
#ifndef SB_VMATH_H
#define SB_VMATH_H

#include "sb_simd.h"

#include <math.h>

/* ln 2 split so that k * LN2_HI is exact for |k| < 2^20 (fdlibm) */
#define SB_LN2_HI 6.93147180369123816490e-01
#define SB_LN2_LO 1.90821492927058770002e-10
#define SB_INV_LN2 1.44269504088896338700e+00
#define SB_ROUND_MAGIC 6755399441055744.0   /* 1.5 * 2^52: x + M - M rounds x to an integer */

/* Polynomial coefficients as vectors in memory: GCC would otherwise
 * rebuild each uniform constant with a scalar load and a shuffle before
 * every use; reading them through a pointer it cannot see through (the
 * empty asm) makes each one a memory operand of the multiply-add. */
#if SB_VL == 2
#define SB_VC(x) { (x), (x) }
#elif SB_VL == 4
#define SB_VC(x) { (x), (x), (x), (x) }
#else
#define SB_VC(x) { (x), (x), (x), (x), (x), (x), (x), (x) }
#endif
static const double sb_expm1_c[12][SB_VL] __attribute__((aligned(64))) = {
    SB_VC(1.0 / 6227020800.0), SB_VC(1.0 / 479001600.0), SB_VC(1.0 / 39916800.0), SB_VC(1.0 / 3628800.0),
    SB_VC(1.0 / 362880.0),     SB_VC(1.0 / 40320.0),     SB_VC(1.0 / 5040.0),     SB_VC(1.0 / 720.0),
    SB_VC(1.0 / 120.0),        SB_VC(1.0 / 24.0),        SB_VC(1.0 / 6.0),        SB_VC(0.5)
};
static const double sb_log1p_c[10][SB_VL] __attribute__((aligned(64))) = {
    SB_VC(2.0 / 21.0), SB_VC(2.0 / 19.0), SB_VC(2.0 / 17.0), SB_VC(2.0 / 15.0), SB_VC(2.0 / 13.0),
    SB_VC(2.0 / 11.0), SB_VC(2.0 / 9.0),  SB_VC(2.0 / 7.0),  SB_VC(2.0 / 5.0),  SB_VC(2.0 / 3.0)
};
static inline const sb_vd *sb_vopaque(const double (*t)[SB_VL])
{
    const sb_vd *p = (const sb_vd *)t;
    __asm__("" : "+r"(p));
    return p;
}

/* expm1(x) = e^x - 1.  Reduction x = k ln2 + r, |r| <= ln2/2; expm1(r) by
 * its Taylor series to r^13/13! (truncation < 2e-17 relative); then
 * e^x - 1 = 2^k expm1(r) + (2^k - 1), exact scaling and one rounding.
 * x < -40: -1 (e^x below half an ulp of 1); x > 709: +Inf (documented
 * simplification: libm overflows only above 709.78, and a power this large
 * makes the denim energy non-finite anyway); NaN stays NaN. */
static inline sb_vd sb_vexpm1(sb_vd x)
{
    /* special lanes (x < -40, x > 709) compute garbage and are replaced at
     * the end; NaN propagates through the arithmetic */
    const sb_vi small = x < -40.0, big = x > 709.0;
    const sb_vd t = x * SB_INV_LN2 + SB_ROUND_MAGIC;
    const sb_vd kf = t - SB_ROUND_MAGIC;
    const sb_vi ki = sb_vasint(t) - sb_vasint(sb_vbcast(SB_ROUND_MAGIC));
    const sb_vd r = (x - kf * SB_LN2_HI) - kf * SB_LN2_LO;
    /* expm1(r) = r + r^2 p(r), p(r) = sum_{m=0..11} r^m / (m+2)!, by Estrin's
     * scheme (pairs, then powers r^2, r^4, r^8): a chain of ~5 dependent
     * steps instead of Horner's 11 */
    const sb_vd *c = sb_vopaque(sb_expm1_c);   /* c[11 - m] = 1/(m+2)! */
    const sb_vd r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
    const sb_vd q0 = c[11] + c[10] * r, q1 = c[9] + c[8] * r, q2 = c[7] + c[6] * r;
    const sb_vd q3 = c[5] + c[4] * r, q4 = c[3] + c[2] * r, q5 = c[1] + c[0] * r;
    const sb_vd p = (q0 + q1 * r2) + (q2 + q3 * r2) * r4 + (q4 + q5 * r2) * r8;
    const sb_vd em = r + r2 * p;
    const sb_vd two_k = sb_vasdbl((ki + 1023) << 52);   /* 2^k, -58 <= k <= 1023 on the regular lanes */
    const sb_vd y = two_k * em + (two_k - 1.0);
    return sb_vselect(big, sb_vbcast(INFINITY), sb_vselect(small, sb_vbcast(-1.0), y));
}

/* log1p(u) = log(1 + u).  w = 1 + u rounded, with the correction
 * c = (u - (w - 1)) / w for the rounding; w = 2^e m, m in [sqrt2/2, sqrt2);
 * f = m - 1, s = f / (2 + f), log(1 + f) = f - f^2/2 + s (f^2/2 + R(s^2)),
 * R(z) = sum_{i=1..10} 2 z^i / (2i + 1) (2 atanh s; truncation < 1e-17
 * relative for |s| <= 0.1716).  u = -1: -Inf; u < -1 or NaN: NaN; +Inf: +Inf. */
static inline sb_vd sb_vlog1p(sb_vd u)
{
    /* lanes outside (-1, Inf) compute garbage and are replaced at the end;
     * NaN propagates through c */
    const sb_vd w = 1.0 + u;
    const sb_vd c = (u - (w - 1.0)) / w;
    const sb_vi bits = sb_vasint(w);
    /* exponent by a logical shift (SSE2 has no 64-bit arithmetic shift) */
    sb_vi e = (sb_vi)((sb_vu)bits >> 52) - 1023;
    sb_vd m = sb_vasdbl((bits & 0x000fffffffffffffLL) | 0x3ff0000000000000LL);   /* [1, 2) */
    const sb_vi hi = m > 1.41421356237309504880;
    m = sb_vselect(hi, m * 0.5, m);
    e = e - hi;   /* hi is -1 where true */
    /* e as a double: exact through the 1.5 * 2^52 + e trick (spacing 1 there) */
    const sb_vd ef = sb_vasdbl(sb_vasint(sb_vbcast(SB_ROUND_MAGIC)) + e) - SB_ROUND_MAGIC;
    const sb_vd f = m - 1.0;
    const sb_vd s = f / (2.0 + f), z = s * s, hfsq = 0.5 * f * f;
    /* R(z) = sum_{i=1..10} c_i z^i, c_i = 2 / (2i + 1), by Estrin's scheme */
    const sb_vd *cl = sb_vopaque(sb_log1p_c);   /* cl[10 - i] = 2 / (2i + 1) */
    const sb_vd z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
    const sb_vd a0 = cl[9] + cl[8] * z, a1 = cl[7] + cl[6] * z, a2 = cl[5] + cl[4] * z;
    const sb_vd a3 = cl[3] + cl[2] * z, a4 = cl[1] + cl[0] * z;
    const sb_vd R = z * ((a0 + a1 * z2) + (a2 + a3 * z2) * z4 + a4 * z8);
    const sb_vd y = ef * SB_LN2_HI + ((f - (hfsq - s * (hfsq + R))) + (ef * SB_LN2_LO + c));
    sb_vd out = sb_vselect(u < -1.0, sb_vbcast(NAN), y);
    out = sb_vselect(u == -1.0, sb_vbcast(-INFINITY), out);
    return sb_vselect(u == INFINITY, sb_vbcast(INFINITY), out);
}

/* Batched forms: y[i] = expm1(x[i]) / log1p(x[i]) for n independent
 * vectors, the same arithmetic; one loop of independent evaluations, whose
 * short Estrin chains the machine overlaps. */
static inline void sb_vexpm1_n(int n, const sb_vd *x, sb_vd *y)
{
    for (int i = 0; i < n; i++) y[i] = sb_vexpm1(x[i]);
}

static inline void sb_vlog1p_n(int n, const sb_vd *u, sb_vd *y)
{
    for (int i = 0; i < n; i++) y[i] = sb_vlog1p(u[i]);
}

#endif
