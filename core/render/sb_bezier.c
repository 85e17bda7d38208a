/* sb_bezier.c — bicubic Bézier patches: basis, evaluation, De Casteljau
 * subdivision, bounds, and the exact conversions from the B-spline and
 * Hermite forms (see sb_bezier.h). */
#include "sb_bezier.h"

#include <math.h>
#include <string.h>

void sb_bernstein3(double t, double b[4], double d1[4], double d2[4])
{
    const double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
    if (d1) {
        d1[0] = -3.0 * s * s;
        d1[1] = 3.0 * s * s - 6.0 * t * s;
        d1[2] = 6.0 * t * s - 3.0 * t * t;
        d1[3] = 3.0 * t * t;
    }
    if (d2) {
        d2[0] = 6.0 * s;
        d2[1] = 18.0 * t - 12.0;
        d2[2] = 6.0 - 18.0 * t;
        d2[3] = 6.0 * t;
    }
}

void sb_bezier_basis(double u, double v, double W[6][16])
{
    double a[4], da[4], dda[4], b[4], db[4], ddb[4];
    sb_bernstein3(u, a, da, dda);
    sb_bernstein3(v, b, db, ddb);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const int I = i + 4 * j;
            W[0][I] = a[i] * b[j];
            W[1][I] = da[i] * b[j];
            W[2][I] = a[i] * db[j];
            W[3][I] = dda[i] * b[j];
            W[4][I] = da[i] * db[j];
            W[5][I] = a[i] * ddb[j];
        }
}

void sb_bezier_eval(const double *P, double u, double v, double x[3], double xu[3], double xv[3])
{
    double a[4], da[4], b[4], db[4];
    sb_bernstein3(u, a, da, NULL);
    sb_bernstein3(v, b, db, NULL);
    double X[3] = { 0, 0, 0 }, U[3] = { 0, 0, 0 }, V[3] = { 0, 0, 0 };
    for (int j = 0; j < 4; j++) {
        /* row j: curve in u */
        double r[3] = { 0, 0, 0 }, ru[3] = { 0, 0, 0 };
        for (int i = 0; i < 4; i++) {
            const double *p = P + 3 * (i + 4 * j);
            for (int c = 0; c < 3; c++) {
                r[c] += a[i] * p[c];
                ru[c] += da[i] * p[c];
            }
        }
        for (int c = 0; c < 3; c++) {
            X[c] += b[j] * r[c];
            U[c] += b[j] * ru[c];
            V[c] += db[j] * r[c];
        }
    }
    for (int c = 0; c < 3; c++) {
        x[c] = X[c];
        if (xu) xu[c] = U[c];
        if (xv) xv[c] = V[c];
    }
}

/* De Casteljau on the 4 points p[0], p[st], p[2 st], p[3 st] (3 coordinates
 * each, stride `st` doubles): left half into lo, right half into hi (same
 * strides); either may be NULL. */
static void casteljau(const double *p, int st, double t, double *lo, double *hi)
{
    for (int c = 0; c < 3; c++) {
        const double p0 = p[c], p1 = p[st + c], p2 = p[2 * st + c], p3 = p[3 * st + c];
        const double q0 = p0 + t * (p1 - p0), q1 = p1 + t * (p2 - p1), q2 = p2 + t * (p3 - p2);
        const double r0 = q0 + t * (q1 - q0), r1 = q1 + t * (q2 - q1);
        const double s0 = r0 + t * (r1 - r0);
        if (lo) { lo[c] = p0; lo[st + c] = q0; lo[2 * st + c] = r0; lo[3 * st + c] = s0; }
        if (hi) { hi[c] = s0; hi[st + c] = r1; hi[2 * st + c] = q2; hi[3 * st + c] = p3; }
    }
}

void sb_bezier_split_u(const double *P, double t, double *lo, double *hi)
{
    double in[SB_BEZ_N];
    memcpy(in, P, sizeof in);
    for (int j = 0; j < 4; j++)
        casteljau(in + 12 * j, 3, t, lo ? lo + 12 * j : NULL, hi ? hi + 12 * j : NULL);
}

void sb_bezier_split_v(const double *P, double t, double *lo, double *hi)
{
    double in[SB_BEZ_N];
    memcpy(in, P, sizeof in);
    for (int i = 0; i < 4; i++)
        casteljau(in + 3 * i, 12, t, lo ? lo + 3 * i : NULL, hi ? hi + 3 * i : NULL);
}

void sb_bezier_sub(const double *P, double u0, double u1, double v0, double v1, double *out)
{
    double A[SB_BEZ_N];
    memcpy(A, P, sizeof A);
    /* [u0,1] first, then [0, (u1-u0)/(1-u0)] of that */
    if (u0 > 0.0) sb_bezier_split_u(A, u0, NULL, A);
    if (u1 < 1.0) sb_bezier_split_u(A, u0 < 1.0 ? (u1 - u0) / (1.0 - u0) : 1.0, A, NULL);
    if (v0 > 0.0) sb_bezier_split_v(A, v0, NULL, A);
    if (v1 < 1.0) sb_bezier_split_v(A, v0 < 1.0 ? (v1 - v0) / (1.0 - v0) : 1.0, A, NULL);
    memcpy(out, A, sizeof A);
}

void sb_bezier_bounds(const double *P, double lo[3], double hi[3])
{
    for (int c = 0; c < 3; c++) lo[c] = hi[c] = P[c];
    for (int k = 1; k < 16; k++)
        for (int c = 0; c < 3; c++) {
            const double x = P[3 * k + c];
            if (x < lo[c]) lo[c] = x;
            if (x > hi[c]) hi[c] = x;
        }
}

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

void sb_bezier_derivative_bounds(const double *P, double L[2], double M[3])
{
    /* x_u = 3 sum B^2_i(u) B^3_j(v) (p_{i+1,j} - p_ij): |x_u| <= 3 max |first difference|;
     * x_uu = 6 sum (second differences), x_uv = 9 sum (mixed differences) */
    double lu = 0, lv = 0, muu = 0, muv = 0, mvv = 0, d[3];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const double *p = P + 3 * (i + 4 * j);
            if (i < 3) {
                for (int c = 0; c < 3; c++) d[c] = p[3 + c] - p[c];
                lu = fmax(lu, norm3(d));
            }
            if (j < 3) {
                for (int c = 0; c < 3; c++) d[c] = p[12 + c] - p[c];
                lv = fmax(lv, norm3(d));
            }
            if (i < 2) {
                for (int c = 0; c < 3; c++) d[c] = p[6 + c] - 2.0 * p[3 + c] + p[c];
                muu = fmax(muu, norm3(d));
            }
            if (j < 2) {
                for (int c = 0; c < 3; c++) d[c] = p[24 + c] - 2.0 * p[12 + c] + p[c];
                mvv = fmax(mvv, norm3(d));
            }
            if (i < 3 && j < 3) {
                for (int c = 0; c < 3; c++) d[c] = p[15 + c] - p[12 + c] - p[3 + c] + p[c];
                muv = fmax(muv, norm3(d));
            }
        }
    L[0] = 3.0 * lu;
    L[1] = 3.0 * lv;
    M[0] = 6.0 * muu;
    M[1] = 9.0 * muv;
    M[2] = 6.0 * mvv;
}

/* Uniform cubic B-spline segment -> Bézier (per direction):
 * b0 = (P0 + 4 P1 + P2)/6, b1 = (2 P1 + P2)/3, b2 = (P1 + 2 P2)/3, b3 = (P1 + 4 P2 + P3)/6 */
static const double BS2BZ[4][4] = {
    { 1.0 / 6, 4.0 / 6, 1.0 / 6, 0 },
    { 0, 2.0 / 3, 1.0 / 3, 0 },
    { 0, 1.0 / 3, 2.0 / 3, 0 },
    { 0, 1.0 / 6, 4.0 / 6, 1.0 / 6 },
};

void sb_bspline_to_bezier(const double *B, double *P)
{
    double T[SB_BEZ_N];   /* converted along u */
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            for (int c = 0; c < 3; c++) {
                double s = 0;
                for (int a = 0; a < 4; a++) s += BS2BZ[i][a] * B[3 * (a + 4 * j) + c];
                T[3 * (i + 4 * j) + c] = s;
            }
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            for (int c = 0; c < 3; c++) {
                double s = 0;
                for (int b = 0; b < 4; b++) s += BS2BZ[j][b] * T[3 * (i + 4 * b) + c];
                P[3 * (i + 4 * j) + c] = s;
            }
}

void sb_hermite_to_bezier(const double H[4][4][3], double *P)
{
    for (int q = 0; q < 2; q++)
        for (int p = 0; p < 2; p++) {
            const double (*h)[3] = H[p + 2 * q];
            const double su = p ? -1.0 : 1.0, sv = q ? -1.0 : 1.0;
            const int ci = 3 * p, cj = 3 * q, ii = p ? 2 : 1, jj = q ? 2 : 1;
            for (int c = 0; c < 3; c++) {
                P[3 * (ci + 4 * cj) + c] = h[0][c];
                P[3 * (ii + 4 * cj) + c] = h[0][c] + su * h[1][c] / 3.0;
                P[3 * (ci + 4 * jj) + c] = h[0][c] + sv * h[2][c] / 3.0;
                P[3 * (ii + 4 * jj) + c] = h[0][c] + su * h[1][c] / 3.0 + sv * h[2][c] / 3.0 + su * sv * h[3][c] / 9.0;
            }
        }
}
