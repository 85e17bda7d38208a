/* sb_shell.c — the Kirchhoff–Love energy of one quadrature point, with its
 * gradient and Hessian w.r.t. the 3k control values, for any scalar basis
 * x(xi) = sum_I N_I(xi) q_I.
 *
 * Route (own derivation, equivalent to BHEM paper App. B Eq. 39-65; every
 * piece is verified by finite differences in tests/test_shell_fd.c):
 *
 * 1. Local jet y = (x_,1, x_,2, x_,11, x_,12, x_,22) in R^15 (5 slots of 3).
 *    dy_s / dq_I = W_s^I Id_3 with W^I = (N1, N2, N11, N12, N22)_I.
 * 2. Strains (BHEM paper Eq. 4a, 5, 6a; the C term is dropped):
 *      A_ab = (x_,a . x_,b - abar_ab)/2,  B_ab = (x_,ab . n - bbar_ab)/2,
 *      n = c/|c|, c = x_,1 x x_,2, and in the local frame e(xi3) = T (A - 2 xi3 B).
 * 3. Through-thickness Gauss rule (points and weights in metres):
 *      energy/area = sum_g w_g psi(T (A - 2 xi_g B)).
 *    For a quadratic psi (StVK) two points integrate exactly:
 *      int_{-h/2}^{h/2} psi(A - 2 xi3 B) dxi3 = h psi(A) + 4 psi(B) h^3/12
 *                                             = h psi(A) + (h^3/3) psi(B),
 *    which is BHEM paper Eq. (7) with its H of Eq. (8) (psi(E) = H^abcd E_ab E_cd
 *    = lambda/2 (tr E)^2 + mu tr(E^2)); tested in test_shell.c.  Factor
 *    convention: Eq. (7) multiplies B B by h^3/3 with B = (b - bbar)/2; App. B
 *    Eq. (42) writes the same with beta = 2 B and h^3/12 (4/12 = 1/3), so the
 *    paper is self-consistent and agrees with E = A - 2 xi3 B.
 * 4. Energy e(y); gradient de/dy and Hessian d2e/dy2 (15 x 15) from
 *      d2e/dy2 = J^T D J + sum_i nA_i d2A_i/dy2 + sum_i nB_i d2B_i/dy2,
 *    J = d(A, B)/dy (6 x 15), D = d2e/d(A,B)^2 (6 x 6), nA, nB = de/dA, de/dB.
 *    For the bending part, f(x1, x2, v) = v . n(c(x1, x2)) gives
 *      df/dc = P v / |c|,  P = I - n n^T,
 *      d2f/dc2 = (-(v n^T + n v^T) - f (I - 3 n n^T)) / |c|^2,
 *      dc = -[x2] dx1 + [x1] dx2,  d2c[dx1, dx2] = dx1 x dx2,
 *    and since f is linear in v, sum_i nB_i B_i needs one evaluation with
 *    V = sum_i nB_i/2 v_i.
 * 5. Map to the basis: g_I = sum_s W_s^I (de/dy_s),
 *    H_IJ = sum_{s,t} W_s^I W_t^J (d2e/dy_s dy_t), done as Q_J = K W^J
 *    (15 x 3) then H_IJ = sum_s W_s^I Q_J[s]: 45 multiply-adds per 3x3 block.
 *
 * Hessian kinds: EXACT; PSEUDO (BHEM paper §6.1 / App. B "pseudo Hessian":
 * drop the second derivatives of the bending strains, d2 beta / dq dq; the
 * membrane second derivatives Eq. 51-53 are cheap and kept); PSD is EXACT
 * here and is projected per element by the caller with sb_psd_project(). */
#include "sb_shell.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct sb_shell_work {
    double W[SB_SHELL_MAX_BASIS][5];   /* basis derivative weights, gathered per point */
};

sb_shell_work *sb_shell_work_new(void)
{
    return calloc(1, sizeof(sb_shell_work));
}

void sb_shell_work_free(sb_shell_work *w)
{
    free(w);
}

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
/* [v]_x, the cross-product matrix (BHEM paper Eq. 65) */
static inline void skew3(const double *v, double S[9])
{
    S[0] = 0;     S[1] = -v[2]; S[2] = v[1];
    S[3] = v[2];  S[4] = 0;     S[5] = -v[0];
    S[6] = -v[1]; S[7] = v[0];  S[8] = 0;
}
static inline void mul33(const double *A, const double *B, double *C)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}
/* r = T^T s for the 3x3 row-major T */
static inline void mulT3(const double *T, const double *s, double *r)
{
    for (int i = 0; i < 3; i++) r[i] = T[i] * s[0] + T[3 + i] * s[1] + T[6 + i] * s[2];
}
/* R = T^T C T */
static void congruence3(const double *T, const double *C, double *R)
{
    double CT[9];
    mul33(C, T, CT);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            R[3 * i + j] = T[i] * CT[j] + T[3 + i] * CT[3 + j] + T[6 + i] * CT[6 + j];
}
/* add s * M (3x3) into the 15x15 K at slot block (a, b) */
static inline void kadd(double K[15][15], int a, int b, double s, const double *M)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) K[3 * a + i][3 * b + j] += s * M[3 * i + j];
}

/* Slots of the local jet. */
enum { S_X1 = 0, S_X2 = 1, S_X11 = 2, S_X12 = 3, S_X22 = 4 };
/* bending component i (Voigt 11, 22, 12) -> slot of x_,ab */
static const int bslot[3] = { S_X11, S_X22, S_X12 };

/* Through-thickness integration (BHEM paper Eq. 6a-7, RMTR paper Eq. 3.2):
 * energy/area = sum_g w_g psi(A - 2 xi_g B) with the material's Gauss points
 * (metres).  Exact with 2 points for StVK: h psi(A) + (h^3/3) psi(B). */
double sb_shell_section(const sb_material *m, const double A[3], const double B[3], double sA[3],
                        double sB[3], double C[36])
{
    if (!m || !A || !B || m->n_thick < 1 || m->n_thick > 8) return NAN;
    const int need_g = sA || sB || C, need_h = C != NULL;
    double e = 0.0, gA[3] = { 0 }, gB[3] = { 0 }, CAA[9] = { 0 }, CAB[9] = { 0 }, CBB[9] = { 0 };
    for (int g = 0; g < m->n_thick; g++) {
        const double xi = m->thick_pt[g], wg = m->thick_w[g];
        const double eps[3] = { A[0] - 2.0 * xi * B[0], A[1] - 2.0 * xi * B[1], A[2] - 2.0 * xi * B[2] };
        double s[3], Cg[9];
        e += wg * sb_material_psi(m, eps, need_g ? s : NULL, need_h ? Cg : NULL);
        if (need_g) {
            const double wb = -2.0 * xi * wg;   /* dE/dB = -2 xi3 */
            for (int i = 0; i < 3; i++) {
                gA[i] += wg * s[i];
                gB[i] += wb * s[i];
            }
            if (need_h) {
                const double wbb = 4.0 * xi * xi * wg;
                for (int i = 0; i < 9; i++) {
                    CAA[i] += wg * Cg[i];
                    CAB[i] += wb * Cg[i];
                    CBB[i] += wbb * Cg[i];
                }
            }
        }
    }
    if (sA) memcpy(sA, gA, sizeof gA);
    if (sB) memcpy(sB, gB, sizeof gB);
    if (C)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                C[6 * i + j] = CAA[3 * i + j];
                C[6 * i + 3 + j] = C[6 * (3 + j) + i] = CAB[3 * i + j];
                C[6 * (3 + i) + 3 + j] = CBB[3 * i + j];
            }
    return e;
}

/* 1. Local jet y = (x_,1, x_,2, x_,11, x_,12, x_,22) and the weights W^I */
static void gather_jet(const sb_shell_basis *b, const double *q, double (*W)[5], double y[5][3])
{
    memset(y, 0, 15 * sizeof(double));
    for (int I = 0; I < b->k; I++) {
        W[I][0] = b->N1[I];
        W[I][1] = b->N2[I];
        W[I][2] = b->N11[I];
        W[I][3] = b->N12[I];
        W[I][4] = b->N22[I];
        const double *qi = q + 3 * I;
        for (int s = 0; s < 5; s++) {
            y[s][0] += W[I][s] * qi[0];
            y[s][1] += W[I][s] * qi[1];
            y[s][2] += W[I][s] * qi[2];
        }
    }
}

/* 2. Strains from the jet: BHEM paper Eq. (4a), (5), (6a) without the C
 * term; covariant A, B mapped to the local warp/weft frame, TA = T A,
 * TB = T B; n the unit normal, rho = |x_,1 x x_,2|. */
static void local_strains(const sb_shell_ref *r, double y[5][3], double n[3], double *rho, double TA[3],
                          double TB[3])
{
    const double *x1 = y[S_X1], *x2 = y[S_X2];
    const double *v[3] = { y[S_X11], y[S_X22], y[S_X12] };
    double c[3];
    cross3(x1, x2, c);
    *rho = sqrt(dot3(c, c));
    const double irho = 1.0 / *rho;
    for (int i = 0; i < 3; i++) n[i] = c[i] * irho;
    const double A[3] = { 0.5 * (dot3(x1, x1) - r->abar[0]), 0.5 * (dot3(x2, x2) - r->abar[1]),
                          0.5 * (dot3(x1, x2) - r->abar[2]) };
    const double B[3] = { 0.5 * (dot3(v[0], n) - r->bbar[0]), 0.5 * (dot3(v[1], n) - r->bbar[1]),
                          0.5 * (dot3(v[2], n) - r->bbar[2]) };
    const double *T = r->T;
    for (int i = 0; i < 3; i++) {
        TA[i] = T[3 * i] * A[0] + T[3 * i + 1] * A[1] + T[3 * i + 2] * A[2];
        TB[i] = T[3 * i] * B[0] + T[3 * i + 1] * B[1] + T[3 * i + 2] * B[2];
    }
}

int sb_shell_strains(const sb_shell_ref *r, const sb_shell_basis *b, const double *q, sb_shell_work *w,
                     double A[3], double B[3])
{
    if (!r || !b || !q || !w || !A || !B || b->k < 1 || b->k > SB_SHELL_MAX_BASIS || !b->N1 || !b->N2 || !b->N11 ||
        !b->N12 || !b->N22)
        return SB_ERR_INPUT;
    double y[5][3], n[3], rho;
    gather_jet(b, q, w->W, y);
    local_strains(r, y, n, &rho, A, B);
    for (int i = 0; i < 3; i++)
        if (!isfinite(A[i]) || !isfinite(B[i])) return SB_NONFINITE;
    return SB_OK;
}

double sb_shell_energy(const sb_material *m, const sb_shell_ref *r, const sb_shell_basis *b,
                       const double *q, double *grad, double *hess, sb_hess_kind kind,
                       sb_shell_work *w)
{
    /* bad input: NaN energy (the caller records SB_NONFINITE), never a crash */
    if (!m || !r || !b || !q || !w || b->k < 1 || b->k > SB_SHELL_MAX_BASIS || !b->N1 || !b->N2 ||
        !b->N11 || !b->N12 || !b->N22 || m->n_thick < 1 || m->n_thick > 8)
        return NAN;
    const int k = b->k;
    double (*W)[5] = w->W;

    /* 1.-2. the jet y and the local-frame strains */
    double y[5][3], n[3], rho, TA[3], TB[3];
    gather_jet(b, q, W, y);
    local_strains(r, y, n, &rho, TA, TB);
    const double irho = 1.0 / rho;
    const double *x1 = y[S_X1], *x2 = y[S_X2];
    const double *v[3] = { y[S_X11], y[S_X22], y[S_X12] };
    const double *T = r->T;

    /* 3. through the thickness (BHEM paper Eq. 6a, 7) */
    const int need_g = grad || hess, need_h = hess != NULL;
    double sA[3], sB[3], C6[36];
    const double dA = r->dA;
    const double e = dA * sb_shell_section(m, TA, TB, need_g ? sA : NULL, need_g ? sB : NULL,
                                           need_h ? C6 : NULL);
    if (!need_g) return e;

    /* 4a. generalized forces in covariant components: nA = dA T^T sA, nB = dA T^T sB */
    double nA[3], nB[3];
    mulT3(T, sA, nA);
    mulT3(T, sB, nB);
    for (int i = 0; i < 3; i++) {
        nA[i] *= dA;
        nB[i] *= dA;
    }

    /* P v / |c| for each bending component, and for V = sum nB_i/2 v_i */
    double gv[3][3], V[3], gV[3];
    for (int i = 0; i < 3; i++) {
        const double f = dot3(v[i], n);
        for (int d = 0; d < 3; d++) gv[i][d] = (v[i][d] - f * n[d]) * irho;
    }
    for (int d = 0; d < 3; d++) {
        V[d] = 0.5 * (nB[0] * v[0][d] + nB[1] * v[1][d] + nB[2] * v[2][d]);
        gV[d] = 0.5 * (nB[0] * gv[0][d] + nB[1] * gv[1][d] + nB[2] * gv[2][d]);
    }

    /* 4b. local gradient de/dy (5 x 3) */
    double G[5][3], t[3];
    for (int d = 0; d < 3; d++) {
        G[S_X1][d] = nA[0] * x1[d] + 0.5 * nA[2] * x2[d];
        G[S_X2][d] = nA[1] * x2[d] + 0.5 * nA[2] * x1[d];
        for (int i = 0; i < 3; i++) G[bslot[i]][d] = 0.5 * nB[i] * n[d];
    }
    cross3(x2, gV, t);   /* J1^T gV with J1 = dc/dx1 = -[x2] */
    for (int d = 0; d < 3; d++) G[S_X1][d] += t[d];
    cross3(gV, x1, t);   /* J2^T gV with J2 = dc/dx2 = [x1] */
    for (int d = 0; d < 3; d++) G[S_X2][d] += t[d];

    if (grad) {
        for (int I = 0; I < k; I++) {
            double *gi = grad + 3 * I;
            for (int s = 0; s < 5; s++) {
                gi[0] += W[I][s] * G[s][0];
                gi[1] += W[I][s] * G[s][1];
                gi[2] += W[I][s] * G[s][2];
            }
        }
    }
    if (!hess) return e;

    /* 4c. local Hessian K (15 x 15) */
    double K[15][15];
    {
        /* J = d(A0,A1,A2,B0,B1,B2)/dy */
        double Jm[6][15];
        memset(Jm, 0, sizeof Jm);
        for (int d = 0; d < 3; d++) {
            Jm[0][3 * S_X1 + d] = x1[d];
            Jm[1][3 * S_X2 + d] = x2[d];
            Jm[2][3 * S_X1 + d] = 0.5 * x2[d];
            Jm[2][3 * S_X2 + d] = 0.5 * x1[d];
        }
        for (int i = 0; i < 3; i++) {
            double t1[3], t2[3];
            cross3(x2, gv[i], t1);
            cross3(gv[i], x1, t2);
            for (int d = 0; d < 3; d++) {
                Jm[3 + i][3 * bslot[i] + d] = 0.5 * n[d];
                Jm[3 + i][3 * S_X1 + d] = 0.5 * t1[d];
                Jm[3 + i][3 * S_X2 + d] = 0.5 * t2[d];
            }
        }
        /* D = dA [T^T CAA T, T^T CAB T; T^T CAB T, T^T CBB T] */
        double D[6][6], R[9], CAA[9], CAB[9], CBB[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                CAA[3 * i + j] = C6[6 * i + j];
                CAB[3 * i + j] = C6[6 * i + 3 + j];
                CBB[3 * i + j] = C6[6 * (3 + i) + 3 + j];
            }
        congruence3(T, CAA, R);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) D[i][j] = dA * R[3 * i + j];
        congruence3(T, CAB, R);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) D[i][3 + j] = D[3 + j][i] = dA * R[3 * i + j];
        congruence3(T, CBB, R);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) D[3 + i][3 + j] = dA * R[3 * i + j];
        /* K = J^T (D J) */
        double DJ[6][15];
        for (int i = 0; i < 6; i++)
            for (int a = 0; a < 15; a++) {
                double s = 0;
                for (int j = 0; j < 6; j++) s += D[i][j] * Jm[j][a];
                DJ[i][a] = s;
            }
        for (int a = 0; a < 15; a++)
            for (int bb = a; bb < 15; bb++) {
                double s = 0;
                for (int i = 0; i < 6; i++) s += Jm[i][a] * DJ[i][bb];
                K[a][bb] = K[bb][a] = s;
            }
    }
    /* membrane second derivatives (BHEM paper Eq. 51-53) */
    for (int d = 0; d < 3; d++) {
        K[3 * S_X1 + d][3 * S_X1 + d] += nA[0];
        K[3 * S_X2 + d][3 * S_X2 + d] += nA[1];
        K[3 * S_X1 + d][3 * S_X2 + d] += 0.5 * nA[2];
        K[3 * S_X2 + d][3 * S_X1 + d] += 0.5 * nA[2];
    }
    /* bending second derivatives (dropped by the pseudo Hessian) */
    if (kind != SB_HESS_PSEUDO) {
        const double fV = dot3(V, n), ir2 = irho * irho;
        double Hc[9], X1[9], X2[9], P[9], M1[9], M2[9], S[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double id = i == j ? 1.0 : 0.0;
                Hc[3 * i + j] = (-(V[i] * n[j] + n[i] * V[j]) - fV * (id - 3.0 * n[i] * n[j])) * ir2;
                P[3 * i + j] = (id - n[i] * n[j]) * irho;   /* P / |c| */
            }
        skew3(x1, X1);
        skew3(x2, X2);
        /* (x1,x1): J1^T Hc J1 = -X2 Hc X2 */
        mul33(X2, Hc, M1);
        mul33(M1, X2, M2);
        kadd(K, S_X1, S_X1, -1.0, M2);
        /* (x1,x2): J1^T Hc J2 - [gV] = X2 Hc X1 - [gV] */
        mul33(M1, X1, M2);
        skew3(gV, S);
        for (int i = 0; i < 9; i++) M2[i] -= S[i];
        kadd(K, S_X1, S_X2, 1.0, M2);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) K[3 * S_X2 + j][3 * S_X1 + i] += M2[3 * i + j];
        /* (x2,x2): J2^T Hc J2 = -X1 Hc X1 */
        mul33(X1, Hc, M1);
        mul33(M1, X1, M2);
        kadd(K, S_X2, S_X2, -1.0, M2);
        /* (x1, v_i) = nB_i/2 X2 P/|c|;  (x2, v_i) = -nB_i/2 X1 P/|c| */
        mul33(X2, P, M1);
        mul33(X1, P, M2);
        for (int i = 0; i < 3; i++) {
            const int sv = bslot[i];
            const double h = 0.5 * nB[i];
            for (int a = 0; a < 3; a++)
                for (int bb = 0; bb < 3; bb++) {
                    const double m1 = h * M1[3 * a + bb], m2 = -h * M2[3 * a + bb];
                    K[3 * S_X1 + a][3 * sv + bb] += m1;
                    K[3 * sv + bb][3 * S_X1 + a] += m1;
                    K[3 * S_X2 + a][3 * sv + bb] += m2;
                    K[3 * sv + bb][3 * S_X2 + a] += m2;
                }
        }
    }

    /* 5. map to the basis: H_IJ = sum_s W_s^I (sum_t K[s][t] W_t^J), upper blocks + mirror */
    const int n3 = 3 * k;
    for (int J = 0; J < k; J++) {
        double Q[15][3];
        const double *wj = W[J];
        for (int a = 0; a < 15; a++)
            for (int d = 0; d < 3; d++)
                Q[a][d] = K[a][d] * wj[0] + K[a][3 + d] * wj[1] + K[a][6 + d] * wj[2] +
                          K[a][9 + d] * wj[3] + K[a][12 + d] * wj[4];
        for (int I = 0; I <= J; I++) {
            const double *wi = W[I];
            double Mb[3][3];
            for (int cc = 0; cc < 3; cc++)
                for (int d = 0; d < 3; d++)
                    Mb[cc][d] = wi[0] * Q[cc][d] + wi[1] * Q[3 + cc][d] + wi[2] * Q[6 + cc][d] +
                                wi[3] * Q[9 + cc][d] + wi[4] * Q[12 + cc][d];
            if (I == J) /* exact symmetry despite the summation order */
                for (int cc = 0; cc < 3; cc++)
                    for (int d = cc + 1; d < 3; d++) Mb[cc][d] = Mb[d][cc] = 0.5 * (Mb[cc][d] + Mb[d][cc]);
            double *h0 = hess + (size_t)(3 * I) * n3 + 3 * J;
            for (int cc = 0; cc < 3; cc++)
                for (int d = 0; d < 3; d++) h0[(size_t)cc * n3 + d] += Mb[cc][d];
            if (I != J) {
                double *h1 = hess + (size_t)(3 * J) * n3 + 3 * I;
                for (int cc = 0; cc < 3; cc++)
                    for (int d = 0; d < 3; d++) h1[(size_t)d * n3 + cc] += Mb[cc][d];
            }
        }
    }
    return e;
}
