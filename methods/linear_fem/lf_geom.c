/* lf_geom.c — exact first and second derivatives of the geometric pieces of
 * the triangle elements: the signed dihedral / director angle, the altitude
 * ratio |u|/|e|, and the chain rule from (u, v, e) to element points through
 * triangle normals (bilinear) and edge vectors (linear).  Own derivation;
 * every formula is checked by finite differences (tests/test_lf_geom.c).
 *
 * Angle: psi = atan2(Y, X), Y = (u x v).e, X = |e| (u.v).  For u, v at right
 * angles to e, u x v = |u||v| sin(psi) e/|e|, so psi is the rotation about
 * +e that takes u to v.  With r2 = X^2 + Y^2:
 *   psi_i  = (X Y_i - Y X_i) / r2
 *   psi_ij = (X Y_ij - Y X_ij + Y_i X_j - X_i Y_j) / r2 - 2 psi_i (X X_j + Y Y_j) / r2,
 *   Y_u = v x e, Y_v = e x u, Y_e = u x v;  Y_uv = -[e]x, Y_ue = [v]x, Y_ve = -[u]x;
 *   X_u = |e| v, X_v = |e| u, X_e = (u.v) e^;  X_uv = |e| I, X_ue = v e^T,
 *   X_ve = u e^T, X_ee = (u.v)(I - e^ e^T)/|e|.
 * Triangle normal n = x × y + y × z + z × x: dn/dx = [z - y]x (cyclic), and
 * lambda . d2n[dx, dy] = -dx . [lambda]x dy for the cyclic pairs (x,y), (y,z),
 * (z,x) (the transposed blocks get +[lambda]x). */
#include "sb_vec3.h"
#include "lf.h"

#include <math.h>
#include <string.h>

/* S = [v]x (S w = v x w) */
static inline void skew(const double *v, double *S)
{
    S[0] = 0;     S[1] = -v[2]; S[2] = v[1];
    S[3] = v[2];  S[4] = 0;     S[5] = -v[0];
    S[6] = -v[1]; S[7] = v[0];  S[8] = 0;
}

void lf_dep_normal(lf_dep *d, const double *P, int sx, int sy, int sz)
{
    const double *x = P + 3 * sx, *y = P + 3 * sy, *z = P + 3 * sz;
    double zy[3], xz[3], yx[3];
    for (int c = 0; c < 3; c++) {
        zy[c] = z[c] - y[c];
        xz[c] = x[c] - z[c];
        yx[c] = y[c] - x[c];
    }
    d->kind = LF_DEP_NORMAL;
    d->n = 3;
    d->slot[0] = sx; d->slot[1] = sy; d->slot[2] = sz;
    skew(zy, d->B[0]);
    skew(xz, d->B[1]);
    skew(yx, d->B[2]);
}

void lf_dep_edge(lf_dep *d, int sa, int sb)
{
    d->kind = LF_DEP_LINEAR;
    d->n = 2;
    d->slot[0] = sa;
    d->slot[1] = sb;
    memset(d->B, 0, sizeof d->B);
    d->B[0][0] = d->B[0][4] = d->B[0][8] = -1.0;
    d->B[1][0] = d->B[1][4] = d->B[1][8] = 1.0;
}

void lf_dep_cross_edge(lf_dep *d, int sa, int sb, const double g[3])
{
    /* w = (P_b - P_a) x g = -[g]x (P_b - P_a) */
    d->kind = LF_DEP_LINEAR;
    d->n = 2;
    d->slot[0] = sa;
    d->slot[1] = sb;
    skew(g, d->B[0]);
    skew(g, d->B[1]);
    for (int i = 0; i < 9; i++) d->B[1][i] = -d->B[1][i];
}

void lf_chain(const lf_dep dep[3], const double g[9], const double *H, int ld, double *G, double *K)
{
    for (int w = 0; w < 3; w++) {
        const lf_dep *d = &dep[w];
        if (d->kind == LF_DEP_CONST) continue;
        const double *gw = g + 3 * w;
        if (G)
            for (int k = 0; k < d->n; k++) {
                const double *B = d->B[k];
                double *Gs = G + 3 * d->slot[k];
                for (int j = 0; j < 3; j++) Gs[j] += B[j] * gw[0] + B[3 + j] * gw[1] + B[6 + j] * gw[2];
            }
    }
    if (!K) return;
    /* K += J^T H J, J = dw/dP, gathered by point slot: J_s = sum of the
     * terms B (dep w) that act on slot s, so that T_s = H J_s (9 x 3) is
     * formed once per slot and K_{rs} = J_r^T T_s once per slot pair r <= s
     * (the mirrored block added as its transpose): about half the flops of
     * one product B1^T H B2 per pair of terms (a shared point, e.g. the
     * edge's end points in u, v and e, has up to three terms). */
    int slots[9], nt[9], tw[9][3];
    const double *tb[9][3];
    int ns = 0;
    for (int w = 0; w < 3; w++) {
        const lf_dep *d = &dep[w];
        if (d->kind == LF_DEP_CONST) continue;
        for (int k = 0; k < d->n; k++) {
            int s = 0;
            while (s < ns && slots[s] != d->slot[k]) s++;
            if (s == ns) { slots[ns] = d->slot[k]; nt[ns++] = 0; }
            tw[s][nt[s]] = w;
            tb[s][nt[s]++] = d->B[k];
        }
    }
    for (int s2 = 0; s2 < ns; s2++) {
        double Ts[9][3];   /* H J_s2: rows w0, w1, w2 */
        memset(Ts, 0, sizeof Ts);
        for (int t = 0; t < nt[s2]; t++) {
            const int w2 = tw[s2][t];
            const double *B2 = tb[s2][t];
            for (int r = 0; r < 9; r++) {
                const double *Hr = H + 9 * r + 3 * w2;
                for (int j = 0; j < 3; j++) Ts[r][j] += Hr[0] * B2[j] + Hr[1] * B2[3 + j] + Hr[2] * B2[6 + j];
            }
        }
        for (int s1 = 0; s1 <= s2; s1++) {
            double Kb[3][3] = { { 0 } };
            for (int t = 0; t < nt[s1]; t++) {
                const double *B1 = tb[s1][t], (*Tw)[3] = Ts + 3 * tw[s1][t];
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) Kb[i][j] += B1[i] * Tw[0][j] + B1[3 + i] * Tw[1][j] + B1[6 + i] * Tw[2][j];
            }
            double *K12 = K + (size_t)(3 * slots[s1]) * ld + 3 * slots[s2];
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) K12[(size_t)i * ld + j] += Kb[i][j];
            if (s1 != s2) {
                double *K21 = K + (size_t)(3 * slots[s2]) * ld + 3 * slots[s1];
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) K21[(size_t)i * ld + j] += Kb[j][i];
            }
        }
    }
    /* second derivatives of the bilinear triangle normals */
    for (int w = 0; w < 3; w++) {
        const lf_dep *d = &dep[w];
        if (d->kind != LF_DEP_NORMAL) continue;
        double S[9];
        skew(g + 3 * w, S);
        for (int p = 0; p < 3; p++) {
            const int a = d->slot[p], b = d->slot[(p + 1) % 3];
            double *Kab = K + (size_t)(3 * a) * ld + 3 * b, *Kba = K + (size_t)(3 * b) * ld + 3 * a;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    Kab[(size_t)i * ld + j] -= S[3 * i + j];
                    Kba[(size_t)i * ld + j] += S[3 * i + j];
                }
        }
    }
}

double lf_angle(const double u[3], const double v[3], const double e[3], double *g, double *H)
{
    double uv[3];
    sb_cross3(u, v, uv);
    const double le = sqrt(sb_dot3(e, e)), udv = sb_dot3(u, v);
    const double Y = sb_dot3(uv, e), X = le * udv;
    const double psi = atan2(Y, X);
    if (!g && !H) return psi;
    const double r2 = X * X + Y * Y, ir2 = 1.0 / r2;
    const double eh[3] = { e[0] / le, e[1] / le, e[2] / le };
    double Yg[9], Xg[9], gg[9];
    sb_cross3(v, e, Yg);
    sb_cross3(e, u, Yg + 3);
    memcpy(Yg + 6, uv, sizeof uv);
    for (int c = 0; c < 3; c++) {
        Xg[c] = le * v[c];
        Xg[3 + c] = le * u[c];
        Xg[6 + c] = udv * eh[c];
    }
    for (int i = 0; i < 9; i++) gg[i] = (X * Yg[i] - Y * Xg[i]) * ir2;
    if (g) memcpy(g, gg, sizeof gg);
    if (!H) return psi;
    double Yh[81], Xh[81], S[9];
    memset(Yh, 0, sizeof Yh);
    memset(Xh, 0, sizeof Xh);
    /* blocks: (row block, col block) */
#define BLK(M, r, c, i, j) M[(3 * (r) + (i)) * 9 + 3 * (c) + (j)]
    skew(e, S);   /* Y_uv = -[e]x, Y_vu = [e]x */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) { BLK(Yh, 0, 1, i, j) = -S[3 * i + j]; BLK(Yh, 1, 0, i, j) = S[3 * i + j]; }
    skew(v, S);   /* Y_ue = [v]x, Y_eu = -[v]x */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) { BLK(Yh, 0, 2, i, j) = S[3 * i + j]; BLK(Yh, 2, 0, i, j) = -S[3 * i + j]; }
    skew(u, S);   /* Y_ve = -[u]x, Y_ev = [u]x */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) { BLK(Yh, 1, 2, i, j) = -S[3 * i + j]; BLK(Yh, 2, 1, i, j) = S[3 * i + j]; }
    for (int i = 0; i < 3; i++) {
        BLK(Xh, 0, 1, i, i) = BLK(Xh, 1, 0, i, i) = le;
        for (int j = 0; j < 3; j++) {
            BLK(Xh, 0, 2, i, j) = BLK(Xh, 2, 0, j, i) = v[i] * eh[j];
            BLK(Xh, 1, 2, i, j) = BLK(Xh, 2, 1, j, i) = u[i] * eh[j];
            BLK(Xh, 2, 2, i, j) = udv * ((i == j) - eh[i] * eh[j]) / le;
        }
    }
#undef BLK
    for (int i = 0; i < 9; i++)
        for (int j = 0; j < 9; j++)
            H[9 * i + j] = (X * Yh[9 * i + j] - Y * Xh[9 * i + j] + Yg[i] * Xg[j] - Xg[i] * Yg[j]) * ir2 -
                           2.0 * gg[i] * (X * Xg[j] + Y * Yg[j]) * ir2;
    for (int i = 0; i < 9; i++)
        for (int j = i + 1; j < 9; j++) H[9 * i + j] = H[9 * j + i] = 0.5 * (H[9 * i + j] + H[9 * j + i]);
    return psi;
}

double lf_ratio(const double u[3], const double e[3], double *g, double *H)
{
    const double lu = sqrt(sb_dot3(u, u)), le = sqrt(sb_dot3(e, e));
    const double h = lu / le;
    if (!g && !H) return h;
    const double uh[3] = { u[0] / lu, u[1] / lu, u[2] / lu }, eh[3] = { e[0] / le, e[1] / le, e[2] / le };
    if (g)
        for (int c = 0; c < 3; c++) {
            g[c] = uh[c] / le;
            g[3 + c] = 0.0;
            g[6 + c] = -h * eh[c] / le;
        }
    if (H) {
        memset(H, 0, 81 * sizeof *H);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double d = i == j;
                H[9 * i + j] = (d - uh[i] * uh[j]) / (lu * le);
                H[9 * i + 6 + j] = H[9 * (6 + j) + i] = -uh[i] * eh[j] / (le * le);
                H[9 * (6 + i) + 6 + j] = h * (3.0 * (eh[i] * eh[j]) - d) / (le * le);
            }
    }
    return h;
}
