/* lf_element.c — the triangle element (constant-strain membrane + midedge
 * shape operator, through the shared section law) and the hinge element.
 *
 * Midedge shape operator (lf.h; Grinspun et al. 2006, Chen et al. 2018).
 * With barycentric coordinates xi^1 = lambda_1, xi^2 = lambda_2 the tangents
 * are a_1 = p1 - p0, a_2 = p2 - p0 and the Crouzeix–Raviart normal field
 * n = sum_i (1 - 2 lambda_i) n_i has n_,1 = 2 (n0 - n1), n_,2 = 2 (n0 - n2).
 * b_ab = -a_a . n_,b then gives b_11 = 2 a_1.(n1 - n0), b_22 = 2 a_2.(n2 - n0),
 * b_12 = 2 a_1.(n2 - n0) = b_21.  Each n_i is at right angles to edge i and
 * a_a.n_i = sin(alpha_i) a_a.m_i with (p_{i+1} - p_i).m_i = h_i, the altitude
 * on edge i (m_i outward), and a_1.m_2 = a_2.m_1 = 0, so
 *     b = [[w0 + w1, w0], [w0, w0 + w2]],  w_i = -2 h_i sin(alpha_i).
 * We use the angle itself, w_i = -2 h_i alpha_i (the "angle" variant; sin
 * and the tan of Chen et al. 2018 differ from it at third order in alpha):
 * the sine saturates, which makes the energy periodic in a director phi and
 * unbounded below under a linear load on it (the end moment, lf_loads.c:
 * our first implementation spun the free end's director by pi), while the
 * angle keeps it growing quadratically.  Strains as in sb_shell.h: A = (a - abar)/2,
 * B = (b - bbar)/2 in covariant components, T A and T B in the local warp /
 * weft frame, energy dA * sb_shell_section(T A, T B) (its fast form,
 * sb_section_fast_isa, at the width of run.vectors).
 *
 * Derivatives: dE = nA . dA_cov + sum_i mu_i dw_i with nA = dA T^T sA,
 * nB = dA T^T sB and mu = M^T nB for B_cov = M w, M = 1/2 [[1,1,0],[1,0,1],[1,0,0]];
 * d2E = J^T D' J + sum_k nA_k d2A_k + sum_i mu_i d2w_i, J = d(A_cov, w)/dq,
 * D' = [[D_AA, D_AB M], [M^T D_BA, M^T D_BB M]], D_XY = dA T^T C_XY T;
 * w = -2 h alpha, alpha = c psi + sigma phi:
 *   dw = -2 (alpha dh + h dalpha),
 *   d2w = -2 (alpha d2h + dh dalpha^T + dalpha dh^T + h c d2psi).
 * The pseudo Hessian drops sum_i mu_i d2w_i (the second derivatives of the
 * bending strains, as for bhem). */
#include "sb_vec3.h"
#include "lf.h"
#include "sb_shell_batch.h"

#include <math.h>
#include <string.h>


/* w_i of edge i with its gradient (13: Pa, Pb, Pc, Pd, phi) and Hessian
 * (13 x 13) when non-NULL.  Returns 0 when w is identically zero. */
static int edge_w(const lf_state *S, const lf_tri *T, int i, const double *qe, double *w, double *g13, double *H13)
{
    const int kind = T->kind[i];
    const int has_phi = S->edge_dofs;
    const double phi = has_phi ? qe[18 + i] : 0.0;
    if (kind == LF_EDGE_FREE && !has_phi) { *w = 0.0; return 0; }
    double P[12];
    memcpy(P, qe + 3 * ((i + 1) % 3), 3 * sizeof(double));   /* Pa */
    memcpy(P + 3, qe + 3 * ((i + 2) % 3), 3 * sizeof(double));/* Pb */
    memcpy(P + 6, qe + 3 * i, 3 * sizeof(double));           /* Pc */
    if (kind == LF_EDGE_INTERIOR) memcpy(P + 9, qe + 9 + 3 * i, 3 * sizeof(double));
    else memset(P + 9, 0, 3 * sizeof(double));
    double e[3], u[3], ac[3];
    for (int c = 0; c < 3; c++) {
        e[c] = P[3 + c] - P[c];
        ac[c] = P[6 + c] - P[c];
    }
    sb_cross3(e, ac, u);   /* (Pb - Pa) x (Pc - Pa) = face normal of T */
    const int need = g13 || H13;
    lf_dep dep[3];
    lf_dep_normal(&dep[0], P, 0, 1, 2);
    dep[1].kind = LF_DEP_CONST;
    lf_dep_edge(&dep[2], 0, 1);
    /* altitude h = |u| / |e| (its 9 variables (u, v, e) do not involve v) */
    double gh[12], g9h[9], H81h[81];
    const double h = lf_ratio(u, e, need ? g9h : NULL, H13 ? H81h : NULL);
    if (need) {
        memset(gh, 0, sizeof gh);
        lf_chain(dep, g9h, NULL, 12, gh, NULL);
    }
    /* director angle alpha = c psi + sigma phi */
    const double cpsi = T->c[i];
    double psi = 0.0, gp[12], g9p[9], H81p[81];
    if (need) memset(gp, 0, sizeof gp);
    if (cpsi != 0.0) {
        double v[3];
        if (kind == LF_EDGE_INTERIOR) {
            double ab[3], ad[3];
            for (int c = 0; c < 3; c++) {
                ab[c] = P[c] - P[3 + c];
                ad[c] = P[9 + c] - P[3 + c];
            }
            sb_cross3(ab, ad, v);                   /* (Pa - Pb) x (Pd - Pb): normal of (Pb, Pa, Pd) */
            lf_dep_normal(&dep[1], P, 1, 0, 3);
        } else if (kind == LF_EDGE_CLAMP) {
            memcpy(v, T->gv[i], sizeof v);
            dep[1].kind = LF_DEP_CONST;
        } else {                                 /* symmetry: v = e x (sign axis) */
            sb_cross3(e, T->gv[i], v);
            lf_dep_cross_edge(&dep[1], 0, 1, T->gv[i]);
        }
        psi = lf_angle(u, v, e, need ? g9p : NULL, H13 ? H81p : NULL);
        if (need) lf_chain(dep, g9p, NULL, 12, gp, NULL);
    }
    const double sig = T->sigma[i];
    const double alpha = cpsi * psi + sig * phi;
    *w = -2.0 * h * alpha;
    if (!need) return 1;
    double ga[13];
    for (int k = 0; k < 12; k++) ga[k] = cpsi * gp[k];
    ga[12] = has_phi ? sig : 0.0;
    if (g13) {
        for (int k = 0; k < 12; k++) g13[k] = -2.0 * (alpha * gh[k] + h * ga[k]);
        g13[12] = -2.0 * h * ga[12];
    }
    if (H13) {
        /* d2w = -2 (alpha d2h + dh dalpha^T + dalpha dh^T + h c d2psi): the
         * chain rule is linear in (g9, H81), so alpha d2h + h c d2psi is one
         * pass of it over alpha (g9h, H81h) + h c (g9p, H81p) (dep[1] is v's
         * dependence, which h's derivatives do not touch) */
        double g9c[9], H81c[81], K[144];
        const double sp = cpsi != 0.0 ? h * cpsi : 0.0;
        for (int k = 0; k < 9; k++) g9c[k] = alpha * g9h[k] + (sp != 0.0 ? sp * g9p[k] : 0.0);
        for (int k = 0; k < 81; k++) H81c[k] = alpha * H81h[k] + (sp != 0.0 ? sp * H81p[k] : 0.0);
        memset(K, 0, sizeof K);
        lf_chain(dep, g9c, H81c, 12, NULL, K);
        for (int a = 0; a < 13; a++) {
            const double gha = a < 12 ? gh[a] : 0.0;
            for (int b = 0; b < 13; b++) {
                const double ghb = b < 12 ? gh[b] : 0.0;
                double v = gha * ga[b] + ga[a] * ghb;
                if (a < 12 && b < 12) v += K[12 * a + b];
                H13[13 * a + b] = -2.0 * v;
            }
        }
    }
    return 1;
}

/* element index of edge-local index k (0..11 points Pa Pb Pc Pd, 12 phi) */
static inline int edge_map(int i, int k)
{
    if (k == 12) return 18 + i;
    static const int off[4] = { 1, 2, 0, 3 };
    const int q = k / 3, slot = q < 3 ? (i + off[q]) % 3 : 3 + i;
    return 3 * slot + k % 3;
}

void lf_tri_bending(const lf_state *S, const lf_tri *T, const double *qe, double b[3])
{
    double w[3];
    for (int i = 0; i < 3; i++) edge_w(S, T, i, qe, &w[i], NULL, NULL);
    b[0] = w[0] + w[1];
    b[1] = w[0] + w[2];
    b[2] = w[0];
}

/* covariant membrane strain of the triangle */
static void membrane_cov(const lf_tri *T, const double *qe, double a1[3], double a2[3], double A[3])
{
    for (int c = 0; c < 3; c++) {
        a1[c] = qe[3 + c] - qe[c];
        a2[c] = qe[6 + c] - qe[c];
    }
    A[0] = 0.5 * (sb_dot3(a1, a1) - T->ref.abar[0]);
    A[1] = 0.5 * (sb_dot3(a2, a2) - T->ref.abar[1]);
    A[2] = 0.5 * (sb_dot3(a1, a2) - T->ref.abar[2]);
}

static inline void mulT(const double *T, const double *x, double *y)   /* y = T x */
{
    for (int i = 0; i < 3; i++) y[i] = T[3 * i] * x[0] + T[3 * i + 1] * x[1] + T[3 * i + 2] * x[2];
}

int lf_tri_strains(lf_state *S, const lf_level *L, int t, const double *qe, double A[3], double B[3])
{
    const lf_tri *T = &L->tri[t];
    double a1[3], a2[3], Ac[3], Bc[3] = { 0, 0, 0 };
    membrane_cov(T, qe, a1, a2, Ac);
    if (S->bending == LF_BEND_MIDEDGE) {
        double b[3];
        lf_tri_bending(S, T, qe, b);
        for (int k = 0; k < 3; k++) Bc[k] = 0.5 * (b[k] - T->bbar[k]);
    }
    mulT(T->ref.T, Ac, A);
    mulT(T->ref.T, Bc, B);
    for (int k = 0; k < 3; k++)
        if (!isfinite(A[k]) || !isfinite(B[k])) return SB_NONFINITE;
    return SB_OK;
}

/* follower pressure E = -p det(p0, p1, p2) / 6 (enclosed-volume potential, sb_shell_ext.c) */
static double follower(double p, const double *qe, double *ge, double *Ke, int ld)
{
    const double *P[3] = { qe, qe + 3, qe + 6 };
    double c12[3];
    sb_cross3(P[1], P[2], c12);
    const double s = -p / 6.0;
    const double E = s * sb_dot3(P[0], c12);
    if (ge)
        for (int a = 0; a < 3; a++) {
            double c[3];
            sb_cross3(P[(a + 1) % 3], P[(a + 2) % 3], c);
            for (int k = 0; k < 3; k++) ge[3 * a + k] += s * c[k];
        }
    if (Ke)
        for (int a = 0; a < 3; a++) {
            const int b = (a + 1) % 3;
            const double *pc = P[(a + 2) % 3];
            /* block (a,b) = -s [pc]x, (b,a) = +s [pc]x */
            const double Sk[9] = { 0, -pc[2], pc[1], pc[2], 0, -pc[0], -pc[1], pc[0], 0 };
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    Ke[(3 * a + i) * ld + 3 * b + j] -= s * Sk[3 * i + j];
                    Ke[(3 * b + i) * ld + 3 * a + j] += s * Sk[3 * i + j];
                }
        }
    return E;
}

double lf_tri_energy(lf_state *S, lf_level *L, int t, const double *qe, double *ge, double *Ke)
{
    const lf_tri *T = &L->tri[t];
    const int n = lf_ned(S), bend = S->bending == LF_BEND_MIDEDGE;
    const int need_g = ge || Ke, need_h = Ke != NULL;
    double a1[3], a2[3], Ac[3], w[3] = { 0, 0, 0 }, gw[3][13], Hw[3][169];
    int wact[3] = { 0, 0, 0 };
    membrane_cov(T, qe, a1, a2, Ac);
    if (bend)
        for (int i = 0; i < 3; i++)
            wact[i] = edge_w(S, T, i, qe, &w[i], need_g ? gw[i] : NULL, need_h ? Hw[i] : NULL);
    const double Bc[3] = { 0.5 * (w[0] + w[1] - T->bbar[0]), 0.5 * (w[0] + w[2] - T->bbar[1]),
                           0.5 * (w[0] - T->bbar[2]) };
    double Al[3], Bl[3], sA[3], sB[3], C6[36];
    mulT(T->ref.T, Ac, Al);
    mulT(T->ref.T, Bc, Bl);
    const double dA = T->ref.dA;
    /* the section law's fast form (sb_section_fast.c: denim's thickness points in vectors, StVK by its moments) */
    double E = dA * sb_section_fast_isa(S->isa, &S->mat, Al, Bl, need_g ? sA : NULL, need_g ? sB : NULL, need_h ? C6 : NULL);
    if (need_g) {
        const double *Tm = T->ref.T;
        double nA[3], nB[3], mu[3];
        for (int i = 0; i < 3; i++) {
            nA[i] = dA * (Tm[i] * sA[0] + Tm[3 + i] * sA[1] + Tm[6 + i] * sA[2]);
            nB[i] = dA * (Tm[i] * sB[0] + Tm[3 + i] * sB[1] + Tm[6 + i] * sB[2]);
        }
        mu[0] = 0.5 * (nB[0] + nB[1] + nB[2]);
        mu[1] = 0.5 * nB[0];
        mu[2] = 0.5 * nB[1];
        /* J: rows A11, A22, A12, w0, w1, w2 over the n element dofs */
        double J[6][LF_NED_MAX];
        memset(J, 0, sizeof J);
        for (int c = 0; c < 3; c++) {
            J[0][3 + c] = a1[c];  J[0][c] = -a1[c];
            J[1][6 + c] = a2[c];  J[1][c] = -a2[c];
            J[2][3 + c] = 0.5 * a2[c];  J[2][6 + c] = 0.5 * a1[c];  J[2][c] = -0.5 * (a1[c] + a2[c]);
        }
        for (int i = 0; i < 3; i++)
            if (wact[i])
                for (int k = 0; k < 13; k++) {
                    if (k == 12 && !S->edge_dofs) continue;
                    J[3 + i][edge_map(i, k)] += gw[i][k];
                }
        if (ge)
            for (int a = 0; a < n; a++)
                ge[a] += nA[0] * J[0][a] + nA[1] * J[1][a] + nA[2] * J[2][a] + mu[0] * J[3][a] + mu[1] * J[4][a] +
                         mu[2] * J[5][a];
        if (Ke) {
            /* D' (6 x 6) in the variables (A_cov, w) */
            double D[6][6], Tt[9], CT[9], R[9];
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) Tt[3 * i + j] = Tm[3 * j + i];
            for (int blk = 0; blk < 4; blk++) {
                const int rb = blk / 2, cb = blk % 2;
                /* R = T^T C_blk T */
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) {
                        double v = 0;
                        for (int k = 0; k < 3; k++) v += C6[6 * (3 * rb + i) + 3 * cb + k] * Tm[3 * k + j];
                        CT[3 * i + j] = v;
                    }
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++)
                        R[3 * i + j] = dA * (Tt[3 * i] * CT[j] + Tt[3 * i + 1] * CT[3 + j] + Tt[3 * i + 2] * CT[6 + j]);
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) D[3 * rb + i][3 * cb + j] = R[3 * i + j];
            }
            /* B_cov = M w: right-multiply B columns by M, left-multiply B rows by M^T */
            static const double M[3][3] = { { 0.5, 0.5, 0.0 }, { 0.5, 0.0, 0.5 }, { 0.5, 0.0, 0.0 } };
            double Dp[6][6];
            for (int i = 0; i < 6; i++)
                for (int j = 0; j < 6; j++) {
                    double v = 0;
                    if (i < 3 && j < 3) v = D[i][j];
                    else if (i < 3) for (int k = 0; k < 3; k++) v += D[i][3 + k] * M[k][j - 3];
                    else if (j < 3) for (int k = 0; k < 3; k++) v += M[k][i - 3] * D[3 + k][j];
                    else
                        for (int k = 0; k < 3; k++)
                            for (int l = 0; l < 3; l++) v += M[k][i - 3] * D[3 + k][3 + l] * M[l][j - 3];
                    Dp[i][j] = v;
                }
            const int nr = bend ? 6 : 3;
            /* J's columns 0-8 (the triangle's points) have all nr rows; the
             * opposite point of edge i (9 + 3i ..) and its director (18 + i)
             * only row 3 + i (w_i), none without bending: Z = D' J and
             * J^T Z over the nonzero rows alone */
            int one[LF_NED_MAX];
            for (int a = 0; a < n; a++) one[a] = a < 9 ? -1 : a < 18 ? 3 + (a - 9) / 3 : 3 + (a - 18);
            double Z[6][LF_NED_MAX];
            for (int a = 0; a < n; a++) {
                const int ka = one[a];
                if (ka < 0)
                    for (int i = 0; i < nr; i++) {
                        double v = 0;
                        for (int k = 0; k < nr; k++) v += Dp[i][k] * J[k][a];
                        Z[i][a] = v;
                    }
                else
                    for (int i = 0; i < nr; i++) Z[i][a] = ka < nr ? Dp[i][ka] * J[ka][a] : 0.0;
            }
            for (int a = 0; a < n; a++) {
                const int ka = one[a];
                for (int b = a; b < n; b++) {
                    double v = 0;
                    if (ka < 0)
                        for (int k = 0; k < nr; k++) v += J[k][a] * Z[k][b];
                    else if (ka < nr)
                        v = J[ka][a] * Z[ka][b];
                    Ke[a * n + b] += v;
                    if (b != a) Ke[b * n + a] += v;
                }
            }
            /* membrane second derivatives (constant patterns) */
            for (int c = 0; c < 3; c++) {
                const int i0 = c, i1 = 3 + c, i2 = 6 + c;
                Ke[i1 * n + i1] += nA[0];  Ke[i0 * n + i0] += nA[0];
                Ke[i0 * n + i1] -= nA[0];  Ke[i1 * n + i0] -= nA[0];
                Ke[i2 * n + i2] += nA[1];  Ke[i0 * n + i0] += nA[1];
                Ke[i0 * n + i2] -= nA[1];  Ke[i2 * n + i0] -= nA[1];
                Ke[i0 * n + i0] += nA[2];
                Ke[i0 * n + i1] -= 0.5 * nA[2];  Ke[i1 * n + i0] -= 0.5 * nA[2];
                Ke[i0 * n + i2] -= 0.5 * nA[2];  Ke[i2 * n + i0] -= 0.5 * nA[2];
                Ke[i1 * n + i2] += 0.5 * nA[2];  Ke[i2 * n + i1] += 0.5 * nA[2];
            }
            /* bending strain second derivatives (dropped by the pseudo Hessian) */
            if (S->hess != SB_HESS_PSEUDO)
                for (int i = 0; i < 3; i++) {
                    if (!wact[i] || mu[i] == 0.0) continue;
                    const int nk = S->edge_dofs ? 13 : 12;
                    int map[13];
                    for (int k = 0; k < nk; k++) map[k] = edge_map(i, k);
                    for (int a = 0; a < nk; a++)
                        for (int b = 0; b < nk; b++) Ke[map[a] * n + map[b]] += mu[i] * Hw[i][13 * a + b];
                }
        }
    }
    if (S->p_follow != 0.0) E += follower(S->p_follow, qe, ge, Ke, n);
    if (L->n_mq) E += lf_moment_energy(S, L, t, qe, ge, Ke);
    return E;
}

/* Hinge: E = R Psi(0, kappa Bdir), kappa = -coef (theta - theta_bar). */
static double hinge_angle(const lf_hinge *hg, const double *q, double *g12, double *K12);
double lf_hinge_theta(const lf_hinge *h, const double *q12) { return hinge_angle(h, q12, NULL, NULL); }

double lf_hinge_energy(lf_state *S, const lf_hinge *hg, const double *q, double *g12, double *K12)
{
    const int need = g12 || K12;
    double gt[12], Kt[144];
    const double theta = hinge_angle(hg, q, need ? gt : NULL, K12 ? Kt : NULL);
    const double kappa = -hg->coef * (theta - hg->theta_bar);
    const double B[3] = { kappa * hg->Bdir[0], kappa * hg->Bdir[1], kappa * hg->Bdir[2] }, A0[3] = { 0, 0, 0 };
    double sA[3], sB[3], C6[36];
    const double E = hg->R * sb_section_fast_isa(S->isa, &S->mat, A0, B, need ? sA : NULL, need ? sB : NULL, K12 ? C6 : NULL);
    if (!need) return E;
    const double d1 = sB[0] * hg->Bdir[0] + sB[1] * hg->Bdir[1] + sB[2] * hg->Bdir[2];   /* dPsi/dkappa */
    const double dE = -hg->R * hg->coef * d1;                                              /* dE/dtheta */
    if (g12)
        for (int a = 0; a < 12; a++) g12[a] += dE * gt[a];
    if (K12) {
        double d2 = 0;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) d2 += hg->Bdir[i] * C6[6 * (3 + i) + 3 + j] * hg->Bdir[j];
        const double ddE = hg->R * hg->coef * hg->coef * d2;
        const int exact = S->hess != SB_HESS_PSEUDO;
        for (int a = 0; a < 12; a++)
            for (int b = 0; b < 12; b++) K12[12 * a + b] += ddE * gt[a] * gt[b] + (exact ? dE * Kt[12 * a + b] : 0.0);
    }
    return E;
}

/* theta with its gradient / Hessian over (Pa, Pb, Pc, Pd) (zeroed here) */
static double hinge_angle(const lf_hinge *hg, const double *q, double *g12, double *K12)
{
    const double *Pa = q, *Pb = q + 3, *Pc = q + 6, *Pd = q + 9;
    double e[3], ac[3], u[3], v[3];
    for (int c = 0; c < 3; c++) {
        e[c] = Pb[c] - Pa[c];
        ac[c] = Pc[c] - Pa[c];
    }
    sb_cross3(e, ac, u);
    lf_dep dep[3];
    lf_dep_normal(&dep[0], q, 0, 1, 2);
    lf_dep_edge(&dep[2], 0, 1);
    if (hg->kind == LF_EDGE_INTERIOR) {
        double ab[3], ad[3];
        for (int c = 0; c < 3; c++) {
            ab[c] = Pa[c] - Pb[c];
            ad[c] = Pd[c] - Pb[c];
        }
        sb_cross3(ab, ad, v);
        lf_dep_normal(&dep[1], q, 1, 0, 3);
    } else if (hg->kind == LF_EDGE_CLAMP) {
        memcpy(v, hg->gv, sizeof v);
        dep[1].kind = LF_DEP_CONST;
    } else {
        sb_cross3(e, hg->gv, v);
        lf_dep_cross_edge(&dep[1], 0, 1, hg->gv);
    }
    const int need = g12 || K12;
    double g9[9], H81[81];
    const double theta = lf_angle(u, v, e, need ? g9 : NULL, K12 ? H81 : NULL);
    if (!need) return theta;
    memset(g12, 0, 12 * sizeof *g12);
    if (K12) memset(K12, 0, 144 * sizeof *K12);
    lf_chain(dep, g9, K12 ? H81 : NULL, 12, g12, K12);
    return theta;
}
