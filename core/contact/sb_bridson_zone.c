/* sb_bridson_zone.c — the rigid motion of an impact zone (Provot 1997;
 * Bridson, Fedkiw & Anderson 2002, §7.4): the zone's vertices move as one
 * rigid body with the zone's linear and angular momentum (sb_bridson.h). */
#include "sb_bridson.h"

#include <math.h>

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* omega = I^+ L for the symmetric positive semi-definite 3x3 I: Jacobi
 * eigen-decomposition, inverse eigenvalues above 1e-12 of the largest (a
 * collinear zone has no inertia about its line; no spin is given there) */
static void solve_inertia(const double I[9], const double L[3], double w[3])
{
    double A[9], V[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    for (int i = 0; i < 9; i++) A[i] = I[i];
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = fabs(A[1]) + fabs(A[2]) + fabs(A[5]);
        if (off <= 1e-300 || off <= 1e-15 * (fabs(A[0]) + fabs(A[4]) + fabs(A[8]))) break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                double apq = A[3 * p + q];
                if (apq == 0) continue;
                double th = 0.5 * (A[3 * q + q] - A[3 * p + p]) / apq;
                double t = (th >= 0 ? 1 : -1) / (fabs(th) + sqrt(th * th + 1)), c = 1 / sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; k++) {   /* A = J^T A J, V = V J */
                    double akp = A[3 * k + p], akq = A[3 * k + q];
                    A[3 * k + p] = c * akp - s * akq;
                    A[3 * k + q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {
                    double apk = A[3 * p + k], aqk = A[3 * q + k];
                    A[3 * p + k] = c * apk - s * aqk;
                    A[3 * q + k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    double vkp = V[3 * k + p], vkq = V[3 * k + q];
                    V[3 * k + p] = c * vkp - s * vkq;
                    V[3 * k + q] = s * vkp + c * vkq;
                }
            }
    }
    double lmax = fmax(fmax(fabs(A[0]), fabs(A[4])), fabs(A[8]));
    for (int i = 0; i < 3; i++) w[i] = 0;
    for (int k = 0; k < 3; k++) {
        double lam = A[4 * k];
        if (!(lam > 1e-12 * lmax)) continue;
        double c = (V[k] * L[0] + V[3 + k] * L[1] + V[6 + k] * L[2]) / lam;
        for (int i = 0; i < 3; i++) w[i] += c * V[3 * i + k];
    }
}

void sb_rigid_zone(int n, const double *x0, double *v, const double *m, double dt, double vc[3], double omega[3])
{
    /* Bridson §7.4: x_cm = sum m x / M, v_cm = sum m v / M,
     * L = sum m (x - x_cm) x (v - v_cm), I = sum m (|r|^2 Id - r r^T),
     * omega = I^-1 L; the new positions x_cm + dt v_cm + R(omega dt) r */
    double M = 0, xc[3] = { 0, 0, 0 }, L[3] = { 0, 0, 0 }, I[9] = { 0 };
    for (int i = 0; i < 3; i++) vc[i] = 0;
    for (int k = 0; k < n; k++) {
        M += m[k];
        for (int i = 0; i < 3; i++) { xc[i] += m[k] * x0[3 * k + i]; vc[i] += m[k] * v[3 * k + i]; }
    }
    for (int i = 0; i < 3; i++) { xc[i] /= M; vc[i] /= M; }
    for (int k = 0; k < n; k++) {
        double r[3], u[3], c[3];
        for (int i = 0; i < 3; i++) { r[i] = x0[3 * k + i] - xc[i]; u[i] = v[3 * k + i] - vc[i]; }
        cross3(r, u, c);
        double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        for (int i = 0; i < 3; i++) {
            L[i] += m[k] * c[i];
            for (int j = 0; j < 3; j++) I[3 * i + j] += m[k] * ((i == j) * rr - r[i] * r[j]);
        }
    }
    solve_inertia(I, L, omega);
    /* rotation by theta = |omega| dt about omega (Rodrigues) */
    double th = sqrt(omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2]) * dt, k[3] = { 0, 0, 0 };
    if (th > 0)
        for (int i = 0; i < 3; i++) k[i] = omega[i] * dt / th;
    const double C = cos(th), S = sin(th);
    for (int j = 0; j < n; j++) {
        double r[3], kr[3], Rr[3];
        for (int i = 0; i < 3; i++) r[i] = x0[3 * j + i] - xc[i];
        cross3(k, r, kr);
        double kd = k[0] * r[0] + k[1] * r[1] + k[2] * r[2];
        for (int i = 0; i < 3; i++) {
            Rr[i] = C * r[i] + S * kr[i] + (1 - C) * kd * k[i];
            v[3 * j + i] = vc[i] + (Rr[i] - r[i]) / dt;
        }
    }
}
