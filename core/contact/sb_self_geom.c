/* sb_self_geom.c — typed squared distances of point–triangle and edge–edge
 * pairs with exact derivatives, IPC's edge–edge mollifier and the static
 * segment–triangle test (sb_self_geom.h).
 *
 * Every distance type is the minimum over k = 0, 1 or 2 free parameters
 * beta of |r(x, beta)|^2 with r = sum_i c_i(beta) x_i, the coefficients c_i
 * affine in beta (a vertex, a point on an edge, a point in a face): e.g.
 * point–face r = p - t0 - beta1 (t1 - t0) - beta2 (t2 - t0) (IPC, Li et al.
 * 2020 §4.2: the distance of the closest features).  With F(x, beta) =
 * |r|^2 and beta*(x) the minimizer (F_beta = 0), the envelope theorem gives
 *   grad f = F_x,   Hess f = F_xx - F_xbeta F_betabeta^{-1} F_betax,
 * exact; F_xx = 2 c c^T (x) I3, F_xbeta_j = 2 C_j r + 2 c J_j (J_j = dr/dbeta_j),
 * F_betabeta = 2 J^T J (r is affine in beta). */
#include "sb_self_geom.h"

#include <math.h>
#include <string.h>

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

typedef struct type_def { double c0[4]; int k; double C[2][4]; } type_def;

static const type_def TYPES[SB_DIST_NTYPES] = {
    [SB_PT_P_T0] = { { 1, -1, 0, 0 }, 0, { { 0 } } },
    [SB_PT_P_T1] = { { 1, 0, -1, 0 }, 0, { { 0 } } },
    [SB_PT_P_T2] = { { 1, 0, 0, -1 }, 0, { { 0 } } },
    [SB_PT_P_E01] = { { 1, -1, 0, 0 }, 1, { { 0, 1, -1, 0 } } },     /* p - t0 - b (t1 - t0) */
    [SB_PT_P_E12] = { { 1, 0, -1, 0 }, 1, { { 0, 0, 1, -1 } } },     /* p - t1 - b (t2 - t1) */
    [SB_PT_P_E20] = { { 1, 0, 0, -1 }, 1, { { 0, -1, 0, 1 } } },     /* p - t2 - b (t0 - t2) */
    [SB_PT_P_T] = { { 1, -1, 0, 0 }, 2, { { 0, 1, -1, 0 }, { 0, 1, 0, -1 } } },
    [SB_EE_A0B0] = { { 1, 0, -1, 0 }, 0, { { 0 } } },
    [SB_EE_A0B1] = { { 1, 0, 0, -1 }, 0, { { 0 } } },
    [SB_EE_A1B0] = { { 0, 1, -1, 0 }, 0, { { 0 } } },
    [SB_EE_A1B1] = { { 0, 1, 0, -1 }, 0, { { 0 } } },
    [SB_EE_A_B0] = { { 1, 0, -1, 0 }, 1, { { -1, 1, 0, 0 } } },      /* a0 + s (a1 - a0) - b0 */
    [SB_EE_A_B1] = { { 1, 0, 0, -1 }, 1, { { -1, 1, 0, 0 } } },
    [SB_EE_A0_B] = { { 1, 0, -1, 0 }, 1, { { 0, 0, 1, -1 } } },      /* a0 - b0 - t (b1 - b0) */
    [SB_EE_A1_B] = { { 0, 1, -1, 0 }, 1, { { 0, 0, 1, -1 } } },
    [SB_EE_A_B] = { { 1, 0, -1, 0 }, 2, { { -1, 1, 0, 0 }, { 0, 0, 1, -1 } } },
};

double sb_typed_dist2(sb_dist_type type, const double x[12], double *g, double *H)
{
    const type_def *T = &TYPES[type];
    const int k = T->k;
    double r0[3] = { 0, 0, 0 }, J[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } };
    for (int i = 0; i < 4; i++)
        for (int a = 0; a < 3; a++) {
            r0[a] += T->c0[i] * x[3 * i + a];
            for (int j = 0; j < k; j++) J[j][a] += T->C[j][i] * x[3 * i + a];
        }
    /* beta* = -(J^T J)^{-1} J^T r0 */
    double A[2][2] = { { 0, 0 }, { 0, 0 } }, Ai[2][2] = { { 0, 0 }, { 0, 0 } }, beta[2] = { 0, 0 };
    for (int i = 0; i < k; i++)
        for (int j = 0; j < k; j++) A[i][j] = dot3(J[i], J[j]);
    if (k == 1) Ai[0][0] = 1 / A[0][0];
    if (k == 2) {
        const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
        Ai[0][0] = A[1][1] / det;
        Ai[1][1] = A[0][0] / det;
        Ai[0][1] = Ai[1][0] = -A[0][1] / det;
    }
    for (int i = 0; i < k; i++)
        for (int j = 0; j < k; j++) beta[i] -= Ai[i][j] * dot3(J[j], r0);
    double r[3], c[4];
    for (int a = 0; a < 3; a++) r[a] = r0[a] + beta[0] * J[0][a] + beta[1] * J[1][a];
    for (int i = 0; i < 4; i++) c[i] = T->c0[i] + beta[0] * T->C[0][i] + beta[1] * T->C[1][i];
    if (g)
        for (int i = 0; i < 4; i++)
            for (int a = 0; a < 3; a++) g[3 * i + a] = 2 * c[i] * r[a];
    if (H) {
        double Fxb[2][12];
        for (int j = 0; j < k; j++)
            for (int i = 0; i < 4; i++)
                for (int a = 0; a < 3; a++) Fxb[j][3 * i + a] = 2 * T->C[j][i] * r[a] + 2 * c[i] * J[j][a];
        for (int p = 0; p < 12; p++)
            for (int q = 0; q < 12; q++) {
                double h = (p % 3 == q % 3) ? 2 * c[p / 3] * c[q / 3] : 0.0;
                /* (2A)^{-1} = Ai / 2 */
                for (int i = 0; i < k; i++)
                    for (int j = 0; j < k; j++) h -= 0.5 * Fxb[i][p] * Ai[i][j] * Fxb[j][q];
                H[12 * p + q] = h;
            }
    }
    return dot3(r, r);
}

sb_dist_type sb_pt_type(const double p[3], const double t0[3], const double t1[3], const double t2[3])
{
    double e1[3], e2[3], w[3];
    for (int a = 0; a < 3; a++) { e1[a] = t1[a] - t0[a]; e2[a] = t2[a] - t0[a]; w[a] = p[a] - t0[a]; }
    const double a11 = dot3(e1, e1), a12 = dot3(e1, e2), a22 = dot3(e2, e2), b1 = dot3(w, e1), b2 = dot3(w, e2);
    const double det = a11 * a22 - a12 * a12;
    if (det > 0) {
        const double u = (a22 * b1 - a12 * b2) / det, v = (a11 * b2 - a12 * b1) / det;
        if (u >= 0 && v >= 0 && u + v <= 1) return SB_PT_P_T;
    }
    /* outside the face: the closest of the three edges (a vertex when the
       clamped parameter is an end) */
    const double *V[3] = { t0, t1, t2 };
    static const sb_dist_type edge[3] = { SB_PT_P_E01, SB_PT_P_E12, SB_PT_P_E20 };
    static const sb_dist_type vert[3] = { SB_PT_P_T0, SB_PT_P_T1, SB_PT_P_T2 };
    double best = INFINITY;
    sb_dist_type bt = SB_PT_P_T0;
    for (int e = 0; e < 3; e++) {
        const double *u = V[e], *v = V[(e + 1) % 3];
        double d[3], q[3];
        for (int a = 0; a < 3; a++) { d[a] = v[a] - u[a]; q[a] = p[a] - u[a]; }
        const double L2 = dot3(d, d);
        double s = L2 > 0 ? dot3(q, d) / L2 : 0;
        sb_dist_type t = edge[e];
        if (s <= 0) { s = 0; t = vert[e]; }
        else if (s >= 1) { s = 1; t = vert[(e + 1) % 3]; }
        double r2 = 0;
        for (int a = 0; a < 3; a++) r2 += (q[a] - s * d[a]) * (q[a] - s * d[a]);
        if (r2 < best) { best = r2; bt = t; }
    }
    return bt;
}

/* closest points of segments a0a1 and b0b1 (Ericson, Real-Time Collision
 * Detection §5.1.9): parameters s, t; nearly parallel segments (sin^2 of
 * their angle below 1e-10) take s = 0 first */
static void closest_segments(const double a0[3], const double a1[3], const double b0[3], const double b1[3],
                             double *s_out, double *t_out)
{
    double d1[3], d2[3], r[3];
    for (int i = 0; i < 3; i++) { d1[i] = a1[i] - a0[i]; d2[i] = b1[i] - b0[i]; r[i] = a0[i] - b0[i]; }
    const double a = dot3(d1, d1), e = dot3(d2, d2), f = dot3(d2, r), c = dot3(d1, r), b = dot3(d1, d2);
    const double denom = a * e - b * b;
    double s = 0, t;
    if (denom > 1e-10 * a * e) {
        s = (b * f - c * e) / denom;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
    }
    t = (b * s + f) / e;
    if (t < 0) {
        t = 0;
        s = -c / a;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
    } else if (t > 1) {
        t = 1;
        s = (b - c) / a;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
    }
    *s_out = s;
    *t_out = t;
}

static double segment_distance(const double a0[3], const double a1[3], const double b0[3], const double b1[3])
{
    double s, t, d2 = 0;
    closest_segments(a0, a1, b0, b1, &s, &t);
    for (int i = 0; i < 3; i++) {
        const double q = a0[i] + s * (a1[i] - a0[i]) - b0[i] - t * (b1[i] - b0[i]);
        d2 += q * q;
    }
    return sqrt(d2);
}

sb_dist_type sb_ee_type(const double a0[3], const double a1[3], const double b0[3], const double b1[3])
{
    double s, t;
    closest_segments(a0, a1, b0, b1, &s, &t);
    const int si = s <= 0 ? 0 : s >= 1 ? 1 : 2, ti = t <= 0 ? 0 : t >= 1 ? 1 : 2;
    static const sb_dist_type map[3][3] = {
        { SB_EE_A0B0, SB_EE_A0B1, SB_EE_A0_B },
        { SB_EE_A1B0, SB_EE_A1B1, SB_EE_A1_B },
        { SB_EE_A_B0, SB_EE_A_B1, SB_EE_A_B },
    };
    return map[si][ti];
}

/* IPC §4.3: mollifier of the edge–edge barrier for nearly parallel edges */
double sb_ee_mollifier(const double x[12], double eps_x, double *g, double *H)
{
    double u[3], v[3];
    for (int a = 0; a < 3; a++) { u[a] = x[3 + a] - x[a]; v[a] = x[9 + a] - x[6 + a]; }
    const double uu = dot3(u, u), vv = dot3(v, v), uv = dot3(u, v);
    const double c = uu * vv - uv * uv;   /* |u x v|^2 */
    if (c >= eps_x) {
        if (g) memset(g, 0, 12 * sizeof *g);
        if (H) memset(H, 0, 144 * sizeof *H);
        return 1.0;
    }
    const double m = (-c / eps_x + 2) * c / eps_x, dm = 2 / eps_x - 2 * c / (eps_x * eps_x),
                 ddm = -2 / (eps_x * eps_x);
    /* derivatives of c w.r.t. u and v, then to the vertices: u = a1 - a0, v = b1 - b0 */
    double gu[3], gv[3], Huu[9], Hvv[9], Huv[9];
    for (int i = 0; i < 3; i++) {
        gu[i] = 2 * vv * u[i] - 2 * uv * v[i];
        gv[i] = 2 * uu * v[i] - 2 * uv * u[i];
        for (int j = 0; j < 3; j++) {
            const double d = i == j ? 1.0 : 0.0;
            Huu[3 * i + j] = 2 * vv * d - 2 * v[i] * v[j];
            Hvv[3 * i + j] = 2 * uu * d - 2 * u[i] * u[j];
            Huv[3 * i + j] = 4 * u[i] * v[j] - 2 * v[i] * u[j] - 2 * uv * d;
        }
    }
    static const double sign[4] = { -1, 1, -1, 1 };
    double gc[12];
    for (int i = 0; i < 4; i++)
        for (int a = 0; a < 3; a++) gc[3 * i + a] = sign[i] * (i < 2 ? gu[a] : gv[a]);
    if (g)
        for (int p = 0; p < 12; p++) g[p] = dm * gc[p];
    if (H)
        for (int p = 0; p < 12; p++)
            for (int q = 0; q < 12; q++) {
                const int i = p / 3, j = q / 3, a = p % 3, b = q % 3;
                double hc;
                if (i < 2 && j < 2) hc = Huu[3 * a + b];
                else if (i >= 2 && j >= 2) hc = Hvv[3 * a + b];
                else if (i < 2) hc = Huv[3 * a + b];
                else hc = Huv[3 * b + a];
                H[12 * p + q] = ddm * gc[p] * gc[q] + dm * sign[i] * sign[j] * hc;
            }
    return m;
}

int sb_segment_triangle_intersect(const double a[3], const double b[3], const double t0[3], const double t1[3],
                                  const double t2[3])
{
    double e1[3], e2[3], n[3], wa[3], wb[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = t1[i] - t0[i];
        e2[i] = t2[i] - t0[i];
        wa[i] = a[i] - t0[i];
        wb[i] = b[i] - t0[i];
    }
    cross3(e1, e2, n);
    const double nn = sqrt(dot3(n, n));
    if (!(nn > 0)) return 0;
    const double da = dot3(n, wa) / nn, db = dot3(n, wb) / nn;
    double L = 0;
    for (int i = 0; i < 3; i++) L = fmax(L, fmax(fabs(e1[i]), fmax(fabs(e2[i]), fabs(b[i] - a[i]))));
    const double tol = 1e-12 * L;
    const int sa = da > tol ? 1 : da < -tol ? -1 : 0, sbb = db > tol ? 1 : db < -tol ? -1 : 0;
    if (sa != 0 && sa == sbb) return 0;              /* both strictly on one side */
    const double *V[3] = { t0, t1, t2 };
    if (sa == 0 && sbb == 0) {
        /* in the plane: an endpoint in the triangle or a crossing of an edge */
        for (int e = 0; e < 3; e++)
            if (segment_distance(a, b, V[e], V[(e + 1) % 3]) <= 1e-10 * L) return 1;
        const double *P[2] = { a, b };
        for (int k = 0; k < 2; k++) {
            double s0 = 0, s1 = 0, s2 = 0;
            for (int e = 0; e < 3; e++) {
                double d[3], q[3], c[3];
                for (int i = 0; i < 3; i++) { d[i] = V[(e + 1) % 3][i] - V[e][i]; q[i] = P[k][i] - V[e][i]; }
                cross3(d, q, c);
                const double sv = dot3(c, n);
                if (e == 0) s0 = sv; else if (e == 1) s1 = sv; else s2 = sv;
            }
            if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return 1;
        }
        return 0;
    }
    /* the crossing point of the segment with the plane, in the closed triangle */
    /* an endpoint within tol of the plane is the crossing point */
    const double t = sa == 0 ? 0.0 : sbb == 0 ? 1.0 : da / (da - db);
    double q[3];
    for (int i = 0; i < 3; i++) q[i] = a[i] + t * (b[i] - a[i]);
    double w[3];
    for (int i = 0; i < 3; i++) w[i] = q[i] - t0[i];
    const double a11 = dot3(e1, e1), a12 = dot3(e1, e2), a22 = dot3(e2, e2), b1 = dot3(w, e1), b2 = dot3(w, e2);
    const double det = a11 * a22 - a12 * a12;
    const double u = (a22 * b1 - a12 * b2) / det, v = (a11 * b2 - a12 * b1) / det;
    const double eps = 1e-10;
    return u >= -eps && v >= -eps && u + v <= 1 + eps;
}

double sb_self_segment_distance(const double a0[3], const double a1[3], const double b0[3], const double b1[3])
{
    return segment_distance(a0, a1, b0, b1);
}
