/* cc_cage.c — coarse control cages T^0.
 *
 * Scenes: a tensor grid over the domain's grid parameter (s,t) with one ring
 * of ghost faces (RMTR paper §5.2.1, Fig. 4c), the L-shape by removing the
 * notch cells (the ghost ring then also runs along the notch, with the
 * diagonal face at the re-entrant corner so that the corner vertex stays
 * regular).  Tests: discs around one extraordinary vertex, the cube, and a
 * cage with several extraordinary vertices. */
#include "cc.h"
#include "sb_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* 1D control values x[-1..n+1] (stored at x[0..n+2]) whose uniform cubic
 * B-spline limit at knot i is lines[i]: (x_{i-1} + 4 x_i + x_{i+1})/6 = L_i,
 * closed by mirror ghosts x_{-1} = 2 x_0 - x_1 (so x_0 = L_0, the limit
 * boundary passes through the boundary control point), likewise at n. */
static int spline_controls(const double *L, int n, double *x)
{
    double *c = malloc((size_t)(n + 1) * sizeof *c), *d = malloc((size_t)(n + 1) * sizeof *d);
    if (!c || !d) {
        free(c); free(d);
        return SB_ERR_NOMEM;
    }
    double *X = x + 1;                      /* X[i] = x_i, i = -1..n+1 */
    X[0] = L[0];
    X[n] = L[n];
    /* Thomas algorithm for x_{i-1} + 4 x_i + x_{i+1} = 6 L_i, i = 1..n-1 */
    for (int i = 1; i < n; i++) {
        double rhs = 6.0 * L[i] - (i == 1 ? X[0] : 0.0) - (i == n - 1 ? X[n] : 0.0);
        double den = 4.0 - (i > 1 ? c[i - 1] : 0.0);
        c[i] = 1.0 / den;
        d[i] = (rhs - (i > 1 ? d[i - 1] : 0.0)) / den;
    }
    for (int i = n - 1; i >= 1; i--) X[i] = d[i] - (i < n - 1 ? c[i] * X[i + 1] : 0.0);
    X[-1] = 2.0 * X[0] - X[1];
    X[n + 1] = 2.0 * X[n] - X[n - 1];
    free(c);
    free(d);
    return SB_OK;
}

int cc_cage_lines(int n, double cut, int notch_high, double *lines, int *n_notch)
{
    if (n < 1) return SB_ERR_INPUT;
    if (n_notch) *n_notch = 0;
    if (!(cut > 0.0 && cut < 1.0)) {
        for (int i = 0; i <= n; i++) lines[i] = (double)i / n;
        return SB_OK;
    }
    if (n < 2) return SB_ERR_INPUT;
    double w = notch_high ? 1.0 - cut : cut;
    int m = (int)floor(n * w + 0.5);
    if (m < 1) m = 1;
    if (m > n - 1) m = n - 1;
    int lo = notch_high ? n - m : m;        /* elements on [0, cut] */
    for (int i = 0; i <= lo; i++) lines[i] = cut * i / lo;
    for (int i = lo; i <= n; i++) lines[i] = cut + (1.0 - cut) * (i - lo) / (n - lo);
    if (n_notch) *n_notch = m;
    return SB_OK;
}

static int in_notch(int i, int j, int ns, int nt, int corner, int nns, int nnt)
{
    if (corner < 0) return 0;
    int hi_s = corner == SB_CORNER_10 || corner == SB_CORNER_11;
    int hi_t = corner == SB_CORNER_11 || corner == SB_CORNER_01;
    int is = hi_s ? i >= ns - nns : i < nns;
    int it = hi_t ? j >= nt - nnt : j < nnt;
    return is && it;
}

int cc_cage_grid(const double *sl, int ns, const double *tl, int nt, int notch_corner, int nns, int nnt,
                 cc_mesh *m, cc_err *e)
{
    memset(m, 0, sizeof *m);
    if (ns < 1 || nt < 1) return cc_fail(e, SB_ERR_INPUT, "cage needs at least one element per side (got %d x %d)", ns, nt);
    for (int i = 0; i < ns; i++)
        if (!(sl[i + 1] > sl[i])) return cc_fail(e, SB_ERR_INPUT, "cage lines in s must increase");
    for (int j = 0; j < nt; j++)
        if (!(tl[j + 1] > tl[j])) return cc_fail(e, SB_ERR_INPUT, "cage lines in t must increase");
    if (notch_corner >= 0 && (nns < 1 || nns >= ns || nnt < 1 || nnt >= nt))
        return cc_fail(e, SB_ERR_INPUT, "notch of %d x %d cells does not fit a %d x %d cage", nns, nnt, ns, nt);
    int cw = ns + 2, ch = nt + 2;           /* cells i = -1..ns, j = -1..nt */
    int vw = ns + 3, vh = nt + 3;           /* vertices i = -1..ns+1 */
    unsigned char *dom = calloc((size_t)cw * ch, 1), *inc = calloc((size_t)cw * ch, 1);
    int *vid = malloc((size_t)vw * vh * sizeof *vid);
    double *sx = malloc((size_t)(ns + 3) * sizeof *sx), *ty = malloc((size_t)(nt + 3) * sizeof *ty);
    int st = (!dom || !inc || !vid || !sx || !ty) ? SB_ERR_NOMEM : SB_OK;
    if (!st) st = spline_controls(sl, ns, sx);
    if (!st) st = spline_controls(tl, nt, ty);
    if (st) goto done;
#define C(i, j) (((j) + 1) * cw + (i) + 1)
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) dom[C(i, j)] = !in_notch(i, j, ns, nt, notch_corner, nns, nnt);
    int nf = 0;
    for (int j = -1; j <= nt; j++)
        for (int i = -1; i <= ns; i++) {
            int any = 0;
            for (int b = j - 1; b <= j + 1; b++)
                for (int a = i - 1; a <= i + 1; a++)
                    if (a >= 0 && a < ns && b >= 0 && b < nt) any |= dom[C(a, b)];
            inc[C(i, j)] = (unsigned char)any;
            nf += any;
        }
    for (int p = 0; p < vw * vh; p++) vid[p] = -1;
#define VI(i, j) (((j) + 1) * vw + (i) + 1)
    for (int j = -1; j <= nt; j++)
        for (int i = -1; i <= ns; i++)
            if (inc[C(i, j)]) vid[VI(i, j)] = vid[VI(i + 1, j)] = vid[VI(i + 1, j + 1)] = vid[VI(i, j + 1)] = 0;
    int nv = 0;
    for (int j = -1; j <= nt + 1; j++)
        for (int i = -1; i <= ns + 1; i++)
            if (vid[VI(i, j)] == 0) vid[VI(i, j)] = ++nv;   /* 1-based while counting */
    st = cc_mesh_alloc(m, nv, nf, 1);
    if (st) goto done;
    for (int j = -1; j <= nt + 1; j++)
        for (int i = -1; i <= ns + 1; i++) {
            int v = vid[VI(i, j)] - 1;
            if (v < 0) continue;
            m->st[2 * v] = sx[i + 1];
            m->st[2 * v + 1] = ty[j + 1];
            m->grid[2 * v] = i;
            m->grid[2 * v + 1] = j;
        }
    int q = 0;
    for (int j = -1; j <= nt; j++)
        for (int i = -1; i <= ns; i++) {
            if (!inc[C(i, j)]) continue;
            m->fv[4 * q] = vid[VI(i, j)] - 1;
            m->fv[4 * q + 1] = vid[VI(i + 1, j)] - 1;
            m->fv[4 * q + 2] = vid[VI(i + 1, j + 1)] - 1;
            m->fv[4 * q + 3] = vid[VI(i, j + 1)] - 1;
            m->dom[q] = dom[C(i, j)];
            m->cell[2 * q] = i;
            m->cell[2 * q + 1] = j;
            q++;
        }
#undef C
#undef VI
    st = cc_mesh_topology(m, e);
done:
    free(dom); free(inc); free(vid); free(sx); free(ty);
    if (st) {
        if (st == SB_ERR_NOMEM) cc_fail(e, st, "out of memory building a %d x %d cage", ns, nt);
        cc_mesh_free(m);
    }
    return st;
}

/* ---- test cages ------------------------------------------------------------ */

/* Star of n sectors with k x k cells: vertex id of sector-local (a,b). */
static int star_vid(int n, int k, int j, int a, int b)
{
    if (a == 0 && b == 0) return 0;
    if (b == 0) return 1 + j * k + (a - 1);                        /* ray j */
    if (a == 0) return 1 + ((j + 1) % n) * k + (b - 1);            /* ray j+1 */
    return 1 + n * k + j * k * k + (a - 1) * k + (b - 1);          /* sector interior */
}

static int star_raw(int n, int k, cc_mesh *m)
{
    int nv = 1 + n * k + n * k * k, nf = n * k * k;
    int st = cc_mesh_alloc(m, nv, nf, 0);
    if (st) return st;
    const double pi = 3.14159265358979323846;
    for (int j = 0; j < n; j++) {
        double d0[2] = { cos(2 * pi * j / n), sin(2 * pi * j / n) };
        double d1[2] = { cos(2 * pi * (j + 1) / n), sin(2 * pi * (j + 1) / n) };
        for (int a = 0; a <= k; a++)
            for (int b = 0; b <= k; b++) {
                int v = star_vid(n, k, j, a, b);
                m->st[2 * v] = (a * d0[0] + b * d1[0]) / k;
                m->st[2 * v + 1] = (a * d0[1] + b * d1[1]) / k;
            }
        for (int a = 0; a < k; a++)
            for (int b = 0; b < k; b++) {
                int q = j * k * k + a * k + b;
                m->fv[4 * q] = star_vid(n, k, j, a, b);
                m->fv[4 * q + 1] = star_vid(n, k, j, a + 1, b);
                m->fv[4 * q + 2] = star_vid(n, k, j, a + 1, b + 1);
                m->fv[4 * q + 3] = star_vid(n, k, j, a, b + 1);
                m->dom[q] = (a < k - 1 && b < k - 1);   /* outer ring of cells = ghost */
            }
    }
    return SB_OK;
}

int cc_cage_star(int valence, int k, cc_mesh *m, cc_err *e)
{
    memset(m, 0, sizeof *m);
    if (valence < 3 || 2 * valence + 8 > CC_MAX_BASIS || k < 3)
        return cc_fail(e, SB_ERR_INPUT, "star cage: valence %d (3..%d) and k %d (>= 3) unsupported",
                       valence, (CC_MAX_BASIS - 8) / 2, k);
    int st = star_raw(valence, k, m);
    if (st) return cc_fail(e, st, "out of memory building a star cage");
    st = cc_mesh_topology(m, e);
    if (st) cc_mesh_free(m);
    return st;
}

int cc_cage_cube(cc_mesh *m, cc_err *e)
{
    static const int F[6][4] = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 },
                                 { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 3, 0, 4, 7 } };
    int st = cc_mesh_alloc(m, 8, 6, 0);
    if (st) return cc_fail(e, st, "out of memory building the cube");
    for (int v = 0; v < 8; v++) {
        m->st[2 * v] = (v == 1 || v == 2 || v == 5 || v == 6) ? 1.0 : 0.0;
        m->st[2 * v + 1] = (v == 2 || v == 3 || v == 6 || v == 7) ? 1.0 : 0.0;
    }
    memcpy(m->fv, F, sizeof F);
    memset(m->dom, 1, 6);
    st = cc_mesh_topology(m, e);
    if (st) cc_mesh_free(m);
    return st;
}

/* Glue star B (sector jb, side b = k) onto star A (sector ja, side a = k):
 * A(ja, k, b) == B(jb, b, k), b = 0..k, which makes the two faces along the
 * seam oppositely oriented.  B's parameters are moved by the similarity that
 * maps its seam onto A's.  Appends B into `all` (vertex map in bmap). */
static void glue_map(int nA, int nB, int k, int ja, int jb, int offB, int *bmap, const double *stA,
                     const double *stB, double *st_out)
{
    int nvB = 1 + nB * k + nB * k * k;
    for (int v = 0; v < nvB; v++) bmap[v] = offB + v;
    for (int b = 0; b <= k; b++) bmap[star_vid(nB, k, jb, b, k)] = star_vid(nA, k, ja, k, b);
    /* similarity z -> alpha z + beta taking B's seam ends to A's (complex arithmetic by hand) */
    int p0 = star_vid(nB, k, jb, 0, k), p1 = star_vid(nB, k, jb, k, k);
    int q0 = star_vid(nA, k, ja, k, 0), q1 = star_vid(nA, k, ja, k, k);
    double dz[2] = { stB[2 * p1] - stB[2 * p0], stB[2 * p1 + 1] - stB[2 * p0 + 1] };
    double dw[2] = { stA[2 * q1] - stA[2 * q0], stA[2 * q1 + 1] - stA[2 * q0 + 1] };
    double nz = dz[0] * dz[0] + dz[1] * dz[1];
    double al[2] = { (dw[0] * dz[0] + dw[1] * dz[1]) / nz, (dw[1] * dz[0] - dw[0] * dz[1]) / nz };
    for (int v = 0; v < nvB; v++) {
        double z[2] = { stB[2 * v] - stB[2 * p0], stB[2 * v + 1] - stB[2 * p0 + 1] };
        st_out[2 * v] = stA[2 * q0] + al[0] * z[0] - al[1] * z[1];
        st_out[2 * v + 1] = stA[2 * q0 + 1] + al[0] * z[1] + al[1] * z[0];
    }
}

/* Star of valence 5 with a valence-3 star glued on sector 0 and a valence-6
 * star glued on sector 2 (k = 4 cells per sector side). */
int cc_cage_multi(cc_mesh *m, cc_err *e)
{
    const int k = 4, nA = 5, nB = 3, nC = 6;
    cc_mesh A, B, C;
    memset(m, 0, sizeof *m);
    int st = star_raw(nA, k, &A);
    if (!st) st = star_raw(nB, k, &B);
    if (!st) st = star_raw(nC, k, &C);
    int *bmap = malloc((size_t)(B.nv + C.nv) * sizeof *bmap);
    double *stb = malloc((size_t)2 * (B.nv + C.nv) * sizeof *stb);
    if (st || !bmap || !stb) {
        free(bmap); free(stb);
        cc_mesh_free(&A); cc_mesh_free(&B); cc_mesh_free(&C);
        return cc_fail(e, SB_ERR_NOMEM, "out of memory building the multi cage");
    }
    int *cmap = bmap + B.nv;
    glue_map(nA, nB, k, 0, 0, A.nv, bmap, A.st, B.st, stb);
    glue_map(nA, nC, k, 2, 0, A.nv + B.nv, cmap, A.st, C.st, stb + 2 * B.nv);
    /* compact: drop the glued copies of B and C */
    int ntot = A.nv + B.nv + C.nv;
    int *newid = malloc((size_t)ntot * sizeof *newid);
    unsigned char *used = calloc((size_t)ntot, 1);
    st = (!newid || !used) ? SB_ERR_NOMEM : SB_OK;
    if (!st) {
        for (int v = 0; v < A.nv; v++) used[v] = 1;
        for (int v = 0; v < B.nv; v++) used[bmap[v]] = 1;
        for (int v = 0; v < C.nv; v++) used[cmap[v]] = 1;
        int nv = 0;
        for (int v = 0; v < ntot; v++) newid[v] = used[v] ? nv++ : -1;
        st = cc_mesh_alloc(m, nv, A.nf + B.nf + C.nf, 0);
        if (!st) {
            for (int v = 0; v < A.nv; v++) memcpy(m->st + 2 * newid[v], A.st + 2 * v, 2 * sizeof(double));
            for (int v = 0; v < B.nv + C.nv; v++)
                if (bmap[v] >= A.nv) memcpy(m->st + 2 * newid[bmap[v]], stb + 2 * v, 2 * sizeof(double));
            int q = 0;
            const cc_mesh *parts[3] = { &A, &B, &C };
            const int *maps[3] = { NULL, bmap, cmap };
            for (int p = 0; p < 3; p++)
                for (int f = 0; f < parts[p]->nf; f++, q++) {
                    for (int c = 0; c < 4; c++) {
                        int v = parts[p]->fv[4 * f + c];
                        m->fv[4 * q + c] = newid[maps[p] ? maps[p][v] : v];
                    }
                    m->dom[q] = parts[p]->dom[f];
                }
            st = cc_mesh_topology(m, e);
        }
    }
    free(newid); free(used); free(bmap); free(stb);
    cc_mesh_free(&A); cc_mesh_free(&B); cc_mesh_free(&C);
    if (st) {
        if (st == SB_ERR_NOMEM) cc_fail(e, st, "out of memory building the multi cage");
        cc_mesh_free(m);
    }
    return st;
}
