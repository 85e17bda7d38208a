/* cc_level.c — one level of the rmtr discretization: reference control
 * points, quadrature tables and reference quantities, penalty parameter,
 * the structured (s,t) -> face lookup and the projection from the next finer
 * level.
 *
 * Reference geometry (isogeometric, RMTR paper §5.2): the control point with
 * grid parameter (s_I, t_I) gets X_I = chart(s_I, t_I) (sb_geometry_eval_st);
 * the reference surface is sum N_I X_I on every level.  For the plane (all
 * RMTR scenes) the chart is affine in (s,t), so this is exact and identical
 * on all levels.  ASSUMPTION for curved charts (cylinder, sphere): the
 * reference surface is the spline through these control points, an O(h^2)
 * approximation of the chart that differs slightly between levels.
 *
 * Mesh size h (for beta = scale h^-sigma, paper §3.1, §7.1): the longest edge
 * of the reference control net over domain faces; h = 1/n for the 1 m
 * square with n x n elements. */
#include "cc_method.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void cc_level_free(cc_level *L)
{
    free(L->X);
    cc_quad_free(&L->quad);
    free(L->felem);
    free(L->ref);
    free(L->pt);
    free(L->ptN);
    free(L->ept);
    free(L->sx);
    free(L->ty);
    free(L->cellface);
    cc_csr_free(&L->P);
    cc_lsq_free(L->lsq);
    memset(L, 0, sizeof *L);
}

static int build_lookup(cc_level *L)
{
    const cc_mesh *m = L->mesh;
    int i0 = 1 << 30, i1 = -(1 << 30), j0 = 1 << 30, j1 = -(1 << 30);
    for (int v = 0; v < m->nv; v++) {
        i0 = m->grid[2 * v] < i0 ? m->grid[2 * v] : i0;
        i1 = m->grid[2 * v] > i1 ? m->grid[2 * v] : i1;
        j0 = m->grid[2 * v + 1] < j0 ? m->grid[2 * v + 1] : j0;
        j1 = m->grid[2 * v + 1] > j1 ? m->grid[2 * v + 1] : j1;
    }
    if (m->nv < 1 || i1 - i0 < 2 || j1 - j0 < 2 || i1 - i0 > (1 << 20) || j1 - j0 > (1 << 20)) return SB_ERR_INPUT;
    L->i0 = i0;
    L->j0 = j0;
    L->ni = i1 - i0 + 1;
    L->nj = j1 - j0 + 1;
    L->sx = malloc((size_t)L->ni * sizeof *L->sx);
    L->ty = malloc((size_t)L->nj * sizeof *L->ty);
    L->cellface = malloc((size_t)(L->ni - 1) * (L->nj - 1) * sizeof *L->cellface);
    if (!L->sx || !L->ty || !L->cellface) return SB_ERR_NOMEM;
    for (int v = 0; v < m->nv; v++) {       /* tensor-product cage: s depends on i only */
        L->sx[m->grid[2 * v] - i0] = m->st[2 * v];
        L->ty[m->grid[2 * v + 1] - j0] = m->st[2 * v + 1];
    }
    for (int c = 0; c < (L->ni - 1) * (L->nj - 1); c++) L->cellface[c] = -1;
    for (int f = 0; f < m->nf; f++)
        if (m->dom[f]) L->cellface[(m->cell[2 * f + 1] - j0) * (L->ni - 1) + m->cell[2 * f] - i0] = f;
    return SB_OK;
}

/* limit of the 1D cubic B-spline with controls x at knot i (array index) */
static double knot(const double *x, int i) { return (x[i - 1] + 4.0 * x[i] + x[i + 1]) / 6.0; }

/* Invert the monotone 1D spline on the domain cells [a0, a1) of controls x:
 * cell index (array index of the cell's left vertex) and local u. */
static int invert_1d(const double *x, int a0, int a1, double s, int *cell, double *u)
{
    const double tol = 1e-12;
    if (s < knot(x, a0) - tol || s > knot(x, a1) + tol) return SB_ERR_INPUT;
    int i = a0;
    while (i + 1 < a1 && s > knot(x, i + 1)) i++;
    double lo = 0, hi = 1, K0 = knot(x, i), K1 = knot(x, i + 1);
    double w = (s - K0) / (K1 - K0);
    w = w < 0 ? 0 : (w > 1 ? 1 : w);
    for (int it = 0; it < 60; it++) {       /* safeguarded Newton on sum B_a(w) x_a = s */
        double b[4], d1[4], d2[4], g = -s, dg = 0;
        cc_bspline1(w, b, d1, d2);
        for (int a = 0; a < 4; a++) {
            g += b[a] * x[i - 1 + a];
            dg += d1[a] * x[i - 1 + a];
        }
        if (fabs(g) < 1e-15) break;
        if (g > 0) hi = w; else lo = w;
        double wn = dg > 0 ? w - g / dg : -1;
        w = (wn > lo && wn < hi) ? wn : 0.5 * (lo + hi);
    }
    *cell = i;
    *u = w;
    return SB_OK;
}

int cc_level_locate(const cc_level *L, double s, double t, int *face, double *u, double *v)
{
    if (!L->sx) return SB_ERR_UNSUPPORTED;
    /* domain cells have grid indices 0 .. n-1: array indices -i0 .. */
    int ci, cj;
    double uu, vv;
    if (invert_1d(L->sx, -L->i0, L->ni - 2, s, &ci, &uu) ||
        invert_1d(L->ty, -L->j0, L->nj - 2, t, &cj, &vv)) return SB_ERR_INPUT;
    const double tol = 1e-9;
    for (int di = 0; di <= 1; di++)
        for (int dj = 0; dj <= 1; dj++) {
            /* on a cell line, also try the neighbouring cell (L-shape notch edges) */
            int a = ci, b = cj;
            double x = uu, y = vv;
            if (di) {
                if (uu < tol) { a = ci - 1; x = 1; }
                else if (uu > 1 - tol) { a = ci + 1; x = 0; }
                else continue;
            }
            if (dj) {
                if (vv < tol) { b = cj - 1; y = 1; }
                else if (vv > 1 - tol) { b = cj + 1; y = 0; }
                else continue;
            }
            if (a < 0 || b < 0 || a >= L->ni - 1 || b >= L->nj - 1) continue;
            int f = L->cellface[b * (L->ni - 1) + a];
            if (f >= 0) {
                *face = f;
                *u = x;
                *v = y;
                return SB_OK;
            }
        }
    return SB_ERR_INPUT;
}

int cc_level_element_of_face(const cc_level *L, int face)
{
    return face >= 0 && face < L->mesh->nf ? L->felem[face] : -1;
}

/* The reference geometry of level l's quadrature points (sb_shell_ref:
 * metric, curvature, area element, weight) into out (NULL: each point is
 * checked and dropped), and the level's mesh size into *h when asked (the
 * longest cage edge of an element's face). */
static int ref_fill(cc_state *S, int l, sb_shell_ref *out, double *h, cc_err *e)
{
    cc_level *L = &S->lv[l];
    const cc_mesh *m = L->mesh;
    const cc_quad *Q = &L->quad;
    double Xq[3 * CC_MAX_BASIS];
    sb_shell_ref tmp;
    double hmax = 0;
    for (int el = 0; el < Q->ne; el++) {
        const int *nd = Q->enode + Q->eoff[el];
        int k = Q->eoff[el + 1] - Q->eoff[el];
        for (int a = 0; a < k; a++) memcpy(Xq + 3 * a, L->X + 3 * nd[a], 3 * sizeof(double));
        for (int q = 0; q < Q->nq; q++) {
            sb_shell_basis b = cc_quad_basis(Q, el, q);
            double w = Q->gw[q % Q->ng] * Q->gw[q / Q->ng];
            if (sb_shell_ref_init_basis(out ? &out[(size_t)el * Q->nq + q] : &tmp, &b, Xq, S->mat.warp_angle, w) != SB_OK)
                return cc_fail(e, SB_ERR_INPUT, "degenerate reference surface on level %d (face %d)", l, Q->face[el]);
        }
        const int *c = m->fv + 4 * Q->face[el];
        for (int a = 0; a < 4; a++) {
            const double *p = L->X + 3 * c[a], *r = L->X + 3 * c[(a + 1) % 4];
            double d = sqrt((p[0] - r[0]) * (p[0] - r[0]) + (p[1] - r[1]) * (p[1] - r[1]) + (p[2] - r[2]) * (p[2] - r[2]));
            hmax = d > hmax ? d : hmax;
        }
    }
    if (h) *h = hmax;
    return SB_OK;
}

/* Level l's stored reference geometry, built at its first use (issue 38):
 * a coarser level's is read only where its own energy, mass or material
 * state is evaluated (the rmtr solver's coarse models and nested start);
 * lsnewton, tr and damped with pcg-mg (Galerkin coarse operators) never
 * do, and it is a quarter of the subdivision method's reference data (60
 * MB of rmtr's pcg-mg run at 2.5e5 dofs).  Checked at cc_level_build, so
 * this cannot fail but for memory. */
int cc_level_ref(cc_state *S, int l)
{
    cc_level *L = &S->lv[l];
    if (L->ref) return SB_OK;
    sb_shell_ref *r = malloc((size_t)L->quad.ne * L->quad.nq * sizeof *r);
    if (!r) return SB_ERR_NOMEM;
    int st = ref_fill(S, l, r, NULL, NULL);
    if (st) {
        free(r);
        return st;
    }
    L->ref = r;
    return SB_OK;
}

int cc_level_build(cc_state *S, int l, cc_err *e)
{
    cc_level *L = &S->lv[l];
    memset(L, 0, sizeof *L);
    L->mesh = &S->hier.mesh[l];
    const cc_mesh *m = L->mesh;
    L->nv = m->nv;
    L->X = malloc((size_t)3 * m->nv * sizeof *L->X);
    if (!L->X) return cc_fail(e, SB_ERR_NOMEM, "out of memory (level %d)", l);
    for (int v = 0; v < m->nv; v++) {
        sb_jet3 j;
        sb_geometry_eval_st(S->scene, m->st[2 * v], m->st[2 * v + 1], &j);
        memcpy(L->X + 3 * v, j.x, sizeof j.x);
    }
    int st = cc_quad_build(&L->quad, m, S->ng, e);
    if (st) return st;
    const cc_quad *Q = &L->quad;
    L->felem = malloc((size_t)m->nf * sizeof *L->felem);
    if (!L->felem) return cc_fail(e, SB_ERR_NOMEM, "out of memory (level %d)", l);
    for (int f = 0; f < m->nf; f++) L->felem[f] = -1;
    for (int el = 0; el < Q->ne; el++) L->felem[Q->face[el]] = el;
    /* the reference geometry: checked (and h taken) on every level now,
     * stored now on the finest level only (cc_level_ref) */
    if ((st = ref_fill(S, l, NULL, &L->h, e))) return st;
    if (l == S->nlev - 1 && (st = cc_level_ref(S, l))) return cc_fail(e, st, "out of memory (level %d)", l);
    if (!(L->h > 0)) return cc_fail(e, SB_ERR_INPUT, "level %d has zero mesh size", l);
    /* beta = h^-sigma (§3.1) times the scene's factor (cc_beta.c: exactly 1
     * for the paper's cloth, so its beta is bit for bit the paper's) */
    double h = S->beta_finest ? S->lv[S->nlev - 1].h : L->h;
    L->beta = S->beta_scale * S->beta_factor * pow(h, -S->sigma);
    if (m->grid && (st = build_lookup(L))) return cc_fail(e, st, "out of memory (level %d lookup)", l);
    if (l + 1 < S->nlev) {
        if (S->proj == CC_PROJ_REVERSE) st = cc_reverse_build(m, &S->hier.mesh[l + 1], S->hier.vmap[l], &L->P, e);
        else if (S->proj == CC_PROJ_RESTRICT) st = cc_restrict_scaled_build(&S->hier.S[l], &L->P, e);
        else st = cc_lsq_create(&S->hier.S[l], &L->lsq, e);
        if (st) return st;
    }
    return cc_points_build(S, l, e);
}
