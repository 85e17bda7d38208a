/* cc_basis.c — subdivision basis functions N_I and their first and second
 * parametric derivatives on a face (RMTR paper §5.2, Fig. 4).
 *
 * Regular faces (four interior vertices of valence 4): the 16 uniform bicubic
 * B-splines of the 4x4 one-ring (fast path).  Other faces: the face's
 * one-ring is subdivided locally (the same rules (5.12)–(5.15) as the
 * hierarchy) until the sub-face containing (u,v) is regular; there the
 * B-spline is exact, and the weights are pulled back through the local
 * subdivision matrices.  Evaluation is exact for every point except the
 * extraordinary corner itself (never a Gauss point).  Derivatives scale by 2
 * (first) and 4 (second) per local step because child frames are the
 * parent's frame scaled by 2 (cc_subdivide).
 *
 * The control points of a face are listed canonically (cc_face_local): the
 * face's own vertices, then the faces around each corner in rotation order,
 * each listed from the corner it was reached by.  Two faces with the same
 * canonical local cage have the same basis tables (§6 "each type of
 * extraordinary face"), which cc_quad.c exploits. */
#include "cc.h"

#include <stdlib.h>
#include <string.h>

#define CC_RING_MAX_FACES 128
#define CC_MAX_DEPTH 40

void cc_bspline1(double u, double b[4], double d1[4], double d2[4])
{
    double w = 1.0 - u, u2 = u * u, u3 = u2 * u;
    b[0] = w * w * w / 6.0;                       /* uniform cubic B-spline */
    b[1] = (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0;
    b[2] = (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0;
    b[3] = u3 / 6.0;
    d1[0] = -0.5 * w * w;
    d1[1] = 1.5 * u2 - 2.0 * u;
    d1[2] = -1.5 * u2 + u + 0.5;
    d1[3] = 0.5 * u2;
    d2[0] = w;
    d2[1] = 3.0 * u - 2.0;
    d2[2] = -3.0 * u + 1.0;
    d2[3] = u;
}

void cc_bspline_patch(double u, double v, double W[6][16])
{
    double bu[4], du[4], ddu[4], bv[4], dv[4], ddv[4];
    cc_bspline1(u, bu, du, ddu);
    cc_bspline1(v, bv, dv, ddv);
    for (int b = 0; b < 4; b++)
        for (int a = 0; a < 4; a++) {
            int i = a + 4 * b;                     /* tensor product, Fig. 4a */
            W[0][i] = bu[a] * bv[b];
            W[1][i] = du[a] * bv[b];
            W[2][i] = bu[a] * dv[b];
            W[3][i] = ddu[a] * bv[b];
            W[4][i] = du[a] * dv[b];
            W[5][i] = bu[a] * ddv[b];
        }
}

int cc_face_regular(const cc_mesh *m, int f)
{
    for (int k = 0; k < 4; k++) {
        int v = m->fv[4 * f + k];
        if (m->bnd[v] || m->val[v] != 4) return 0;
    }
    return 1;
}

/* the face across local edge k of face f, and that edge's local index there */
static int across(const cc_mesh *m, int f, int k, int *kg)
{
    int d = m->fe[4 * f + k];
    int s = (m->ef[2 * d] == f && m->efk[2 * d] == k) ? 1 : 0;
    *kg = m->efk[2 * d + s];
    return m->ef[2 * d + s];
}

int cc_face_gather16(const cc_mesh *m, int f, int idx[16])
{
    if (!cc_face_regular(m, f)) return SB_ERR_INPUT;
    const int *c = m->fv + 4 * f;
    idx[1 + 4] = c[0];
    idx[2 + 4] = c[1];
    idx[2 + 8] = c[2];
    idx[1 + 8] = c[3];
    for (int k = 0; k < 4; k++) {
        /* frame of side k: c_k at (1,1), c_{k+1} at (2,1); R(a,b) = (3-b, a) maps it to frame 0 */
        int pos[3][2] = { { 1, 0 }, { 2, 0 }, { 0, 0 } };
        for (int r = 0; r < k; r++)
            for (int p = 0; p < 3; p++) {
                int a = pos[p][0], b = pos[p][1];
                pos[p][0] = 3 - b;
                pos[p][1] = a;
            }
        int kg, kd;
        int g = across(m, f, k, &kg);
        if (g < 0) return SB_ERR_INTERNAL;
        int d = across(m, g, (kg + 1) % 4, &kd);
        if (d < 0) return SB_ERR_INTERNAL;
        idx[pos[0][0] + 4 * pos[0][1]] = m->fv[4 * g + (kg + 2) % 4];
        idx[pos[1][0] + 4 * pos[1][1]] = m->fv[4 * g + (kg + 3) % 4];
        idx[pos[2][0] + 4 * pos[2][1]] = m->fv[4 * d + (kd + 3) % 4];
    }
    return SB_OK;
}

/* Canonical local cage of face f (face 0 = f in its own frame).  inv[i] =
 * global index of local vertex i.  Returns SB_OK or an error. */
int cc_face_local(const cc_mesh *m, int f, cc_mesh *L, int *inv, int max, cc_err *e)
{
    int faces[CC_RING_MAX_FACES], start[CC_RING_MAX_FACES], nfc = 0;
    faces[nfc] = f;
    start[nfc++] = 0;
    for (int k = 0; k < 4; k++) {
        int c = m->fv[4 * f + k];
        for (int dir = 0; dir < 2; dir++) {
            int g = f, j = k;
            for (int guard = 0; guard < CC_RING_MAX_FACES; guard++) {
                int kg;
                int h = across(m, g, dir == 0 ? j : (j + 3) % 4, &kg);
                if (h < 0 || h == f) break;
                g = h;
                j = cc_face_corner(m, g, c);
                int seen = 0;
                for (int a = 0; a < nfc && !seen; a++) seen = faces[a] == g;
                if (!seen) {
                    if (nfc == CC_RING_MAX_FACES)
                        return cc_fail(e, SB_ERR_UNSUPPORTED, "face %d: one-ring of more than %d faces", f, nfc);
                    faces[nfc] = g;
                    start[nfc++] = j;
                }
            }
            if (!m->bnd[c]) break;               /* interior: one full turn suffices */
        }
    }
    /* local cage with every face listed from its start corner */
    int *map = malloc((size_t)m->nv * sizeof *map);
    if (!map) return cc_fail(e, SB_ERR_NOMEM, "out of memory (local cage)");
    int nv = 0, st = SB_OK;
    for (int a = 0; a < nfc && !st; a++)
        for (int k = 0; k < 4; k++) {
            int v = m->fv[4 * faces[a] + (start[a] + k) % 4];
            int s = 0;
            for (; s < nv && inv[s] != v; s++) {}
            if (s == nv) {
                if (nv == max) st = cc_fail(e, SB_ERR_UNSUPPORTED, "face %d has more than %d control points", f, max);
                else inv[nv++] = v;
            }
        }
    if (!st) st = cc_mesh_alloc(L, nv, nfc, 0);
    if (!st) {
        for (int s = 0; s < nv; s++) {
            map[inv[s]] = s;
            L->st[2 * s] = m->st[2 * inv[s]];
            L->st[2 * s + 1] = m->st[2 * inv[s] + 1];
        }
        for (int a = 0; a < nfc; a++) {
            for (int k = 0; k < 4; k++) L->fv[4 * a + k] = map[m->fv[4 * faces[a] + (start[a] + k) % 4]];
            L->dom[a] = m->dom[faces[a]];
        }
        st = cc_mesh_topology(L, e);
    }
    free(map);
    return st;
}

/* Weights W (6 x L->nv) of face 0 of the local cage L at (u,v), accumulated. */
static int local_eval(const cc_mesh *L, double u, double v, int depth, double *W, cc_err *e)
{
    int nv = L->nv;
    if (cc_face_regular(L, 0)) {
        int idx[16];
        double P[6][16];
        int st = cc_face_gather16(L, 0, idx);
        if (st) return cc_fail(e, st, "inconsistent regular patch");
        cc_bspline_patch(u, v, P);
        for (int r = 0; r < 6; r++)
            for (int a = 0; a < 16; a++) W[r * nv + idx[a]] += P[r][a];
        return SB_OK;
    }
    if (depth >= CC_MAX_DEPTH)
        return cc_fail(e, SB_ERR_INPUT, "basis point too close to an extraordinary vertex or the cage boundary");
    cc_mesh F, R;
    cc_csr S;
    int st = cc_subdivide(L, &F, &S, e);
    if (st) return st;
    int iu = u >= 0.5, iv = v >= 0.5;
    int k = iv ? (iu ? 2 : 3) : (iu ? 1 : 0);
    int *inv = malloc((size_t)F.nv * sizeof *inv);
    double *W2 = NULL;
    st = inv ? cc_face_local(&F, 4 * 0 + k, &R, inv, F.nv, e) : cc_fail(e, SB_ERR_NOMEM, "out of memory");
    if (!st) {
        W2 = calloc((size_t)6 * R.nv, sizeof *W2);
        st = W2 ? local_eval(&R, 2.0 * u - iu, 2.0 * v - iv, depth + 1, W2, e) : SB_ERR_NOMEM;
        if (!st) {
            static const double scale[6] = { 1, 2, 2, 4, 4, 4 };   /* d/du = 2 d/du' */
            for (int r = 0; r < 6; r++)
                for (int i = 0; i < R.nv; i++) {
                    double w = scale[r] * W2[r * R.nv + i];
                    int fi = inv[i];
                    for (int p = S.rp[fi]; p < S.rp[fi + 1]; p++) W[r * nv + S.ci[p]] += w * S.v[p];
                }
        }
        cc_mesh_free(&R);
    }
    free(W2);
    free(inv);
    cc_mesh_free(&F);
    cc_csr_free(&S);
    return st;
}

int cc_local_basis(const cc_mesh *L, double u, double v, double *W, cc_err *e)
{
    memset(W, 0, (size_t)6 * L->nv * sizeof *W);
    if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1)) return cc_fail(e, SB_ERR_INPUT, "(u,v) = (%g,%g) outside the face", u, v);
    return local_eval(L, u, v, 0, W, e);
}

int cc_face_basis(const cc_mesh *m, int f, double u, double v, int *k, int *idx, double *W, int max, cc_err *e)
{
    if (f < 0 || f >= m->nf) return cc_fail(e, SB_ERR_INPUT, "face %d does not exist", f);
    if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1)) return cc_fail(e, SB_ERR_INPUT, "(u,v) = (%g,%g) outside the face", u, v);
    if (cc_face_regular(m, f)) {
        if (max < 16) return cc_fail(e, SB_ERR_INPUT, "basis buffer too small");
        double P[6][16];
        cc_face_gather16(m, f, idx);
        cc_bspline_patch(u, v, P);
        for (int r = 0; r < 6; r++) memcpy(W + 16 * r, P[r], sizeof P[r]);
        *k = 16;
        return SB_OK;
    }
    cc_mesh L;
    int st = cc_face_local(m, f, &L, idx, max, e);
    if (st) return st;
    st = cc_local_basis(&L, u, v, W, e);
    *k = L.nv;
    cc_mesh_free(&L);
    return st;
}
