/* test_shell_bases.h — small scalar bases for the shell-kernel tests (test
 * helpers, not method code): bicubic uniform B-spline on one element,
 * bicubic Hermite on one element, the 6-function Taylor jet basis, and a
 * random "basis" of any size (the kernel only sees numbers).  Also a tiny
 * deterministic random generator and finite-difference helpers. */
#ifndef TEST_SHELL_BASES_H
#define TEST_SHELL_BASES_H

#include "sb_shell.h"

#include <math.h>
#include <string.h>

typedef struct tb_basis {
    int k;
    double N[SB_SHELL_MAX_BASIS], N1[SB_SHELL_MAX_BASIS], N2[SB_SHELL_MAX_BASIS];
    double N11[SB_SHELL_MAX_BASIS], N12[SB_SHELL_MAX_BASIS], N22[SB_SHELL_MAX_BASIS];
} tb_basis;

static inline sb_shell_basis tb_view(const tb_basis *b)
{
    sb_shell_basis v = { b->k, b->N, b->N1, b->N2, b->N11, b->N12, b->N22 };
    return v;
}

/* deterministic uniform numbers in [a, b) (xorshift64*) */
static inline double tb_rand(unsigned long long *s, double a, double b)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    unsigned long long r = *s * 2685821657736338717ULL;
    return a + (b - a) * (double)(r >> 11) * (1.0 / 9007199254740992.0);
}

/* 1D cubic uniform B-spline pieces on [0,1]: value, first, second derivative */
static inline void tb_bspline1(double t, double f[4], double d[4], double dd[4])
{
    const double s = 1.0 - t;
    f[0] = s * s * s / 6.0;
    f[1] = (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
    f[2] = (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
    f[3] = t * t * t / 6.0;
    d[0] = -0.5 * s * s;
    d[1] = (9.0 * t * t - 12.0 * t) / 6.0;
    d[2] = (-9.0 * t * t + 6.0 * t + 3.0) / 6.0;
    d[3] = 0.5 * t * t;
    dd[0] = s;
    dd[1] = 3.0 * t - 2.0;
    dd[2] = -3.0 * t + 1.0;
    dd[3] = t;
}

/* 1D cubic Hermite on [0,1]: (value at 0, slope at 0, value at 1, slope at 1) */
static inline void tb_hermite1(double t, double f[4], double d[4], double dd[4])
{
    f[0] = 2 * t * t * t - 3 * t * t + 1;  d[0] = 6 * t * t - 6 * t;      dd[0] = 12 * t - 6;
    f[1] = t * t * t - 2 * t * t + t;      d[1] = 3 * t * t - 4 * t + 1;  dd[1] = 6 * t - 4;
    f[2] = -2 * t * t * t + 3 * t * t;     d[2] = -6 * t * t + 6 * t;     dd[2] = -12 * t + 6;
    f[3] = t * t * t - t * t;              d[3] = 3 * t * t - 2 * t;      dd[3] = 6 * t - 2;
}

/* tensor product of two 1D families of 4: index I = i + 4 j */
static inline void tb_tensor(tb_basis *b, const double fu[4], const double du[4], const double ddu[4],
                             const double fv[4], const double dv[4], const double ddv[4], const int *map)
{
    b->k = 16;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const int I = map ? map[i + 4 * j] : i + 4 * j;
            b->N[I] = fu[i] * fv[j];
            b->N1[I] = du[i] * fv[j];
            b->N2[I] = fu[i] * dv[j];
            b->N11[I] = ddu[i] * fv[j];
            b->N12[I] = du[i] * dv[j];
            b->N22[I] = fu[i] * ddv[j];
        }
}

/* bicubic uniform B-spline element, parameter (u,v) in [0,1]^2 */
static inline void tb_bspline(tb_basis *b, double u, double v)
{
    double fu[4], du[4], ddu[4], fv[4], dv[4], ddv[4];
    tb_bspline1(u, fu, du, ddu);
    tb_bspline1(v, fv, dv, ddv);
    tb_tensor(b, fu, du, ddu, fv, dv, ddv, NULL);
}

/* bicubic Hermite element (BHEM paper Eq. 14-16 in spirit): for corner
 * c = (a,b) in {0,1}^2 (c = a + 2b) the dofs are x, x_u, x_v, x_uv at the
 * corner, index 4c + {0,1,2,3}.  Parameter (u,v) in [0,1]^2. */
static inline void tb_hermite(tb_basis *b, double u, double v)
{
    double fu[4], du[4], ddu[4], fv[4], dv[4], ddv[4];
    tb_hermite1(u, fu, du, ddu);
    tb_hermite1(v, fv, dv, ddv);
    /* 1D index i: 0 = value@0, 1 = slope@0, 2 = value@1, 3 = slope@1 */
    int map[16];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const int a = i / 2, bb = j / 2, c = a + 2 * bb;
            const int kind = (i % 2) + 2 * (j % 2);   /* 0 x, 1 x_u, 2 x_v, 3 x_uv */
            map[i + 4 * j] = 4 * c + kind;
        }
    tb_tensor(b, fu, du, ddu, fv, dv, ddv, map);
}

/* Hermite dofs from a map F with its jet at the 4 corners of [0,1]^2 */
typedef void (*tb_map_fn)(double u, double v, double x[3], double xu[3], double xv[3], double xuv[3]);
static inline void tb_hermite_dofs(tb_map_fn F, double *q)
{
    for (int c = 0; c < 4; c++) {
        const double u = c % 2, v = c / 2;
        F(u, v, q + 3 * (4 * c), q + 3 * (4 * c + 1), q + 3 * (4 * c + 2), q + 3 * (4 * c + 3));
    }
}

/* Taylor jet basis at the origin: 1, u, v, u^2/2, u v, v^2/2, so that
 * q = (x, x_1, x_2, x_11, x_12, x_22) reproduces any jet exactly. */
static inline void tb_taylor(tb_basis *b)
{
    memset(b, 0, sizeof *b);
    b->k = 6;
    b->N[0] = 1;
    b->N1[1] = 1;
    b->N2[2] = 1;
    b->N11[3] = 1;
    b->N12[4] = 1;
    b->N22[5] = 1;
}

/* random weights: not a partition of unity, just numbers (tests the mapping) */
static inline void tb_random(tb_basis *b, int k, unsigned long long *s)
{
    b->k = k;
    for (int I = 0; I < k; I++) {
        b->N[I] = tb_rand(s, 0, 0.2);
        b->N1[I] = tb_rand(s, -0.3, 0.3);
        b->N2[I] = tb_rand(s, -0.3, 0.3);
        b->N11[I] = tb_rand(s, -0.5, 0.5);
        b->N12[I] = tb_rand(s, -0.5, 0.5);
        b->N22[I] = tb_rand(s, -0.5, 0.5);
    }
}

/* jet of x(u,v) = sum N_I q_I */
static inline void tb_jet(const tb_basis *b, const double *q, double y[6][3])
{
    memset(y, 0, 18 * sizeof(double));
    for (int I = 0; I < b->k; I++)
        for (int c = 0; c < 3; c++) {
            y[0][c] += b->N[I] * q[3 * I + c];
            y[1][c] += b->N1[I] * q[3 * I + c];
            y[2][c] += b->N2[I] * q[3 * I + c];
            y[3][c] += b->N11[I] * q[3 * I + c];
            y[4][c] += b->N12[I] * q[3 * I + c];
            y[5][c] += b->N22[I] * q[3 * I + c];
        }
}

/* rotation matrix about a unit axis (Rodrigues) */
static inline void tb_rotation(const double ax[3], double ang, double R[9])
{
    const double c = cos(ang), s = sin(ang), t = 1 - c;
    const double x = ax[0], y = ax[1], z = ax[2];
    R[0] = t * x * x + c;     R[1] = t * x * y - s * z; R[2] = t * x * z + s * y;
    R[3] = t * x * y + s * z; R[4] = t * y * y + c;     R[5] = t * y * z - s * x;
    R[6] = t * x * z - s * y; R[7] = t * y * z + s * x; R[8] = t * z * z + c;
}

static inline void tb_apply(const double R[9], const double t[3], const double *q, double *out, int k)
{
    for (int I = 0; I < k; I++) {
        const double *p = q + 3 * I;
        double r[3];
        for (int i = 0; i < 3; i++) r[i] = R[3 * i] * p[0] + R[3 * i + 1] * p[1] + R[3 * i + 2] * p[2] + t[i];
        memcpy(out + 3 * I, r, sizeof r);
    }
}

#endif
