/* bhem_grid.c — patch grid of one level: masking (L-shape), periodic seams,
 * DOF layout, elements, the exact reference state from the chart, and the
 * per-quadrature-point reference quantities (BHEM paper §4.1, §4.2, App. A). */
#include "bhem.h"
#include "sb_context.h"
#include "sb_imperfection.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int bhem_fail(const bhem_state *S, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sb_verror(S ? S->ctx : NULL, status, "bhem", fmt, ap);
    va_end(ap);
    return status;
}

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
static double dist3(const double *a, const double *b)
{
    double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
    return norm3(d);
}
static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Whether a boundary condition (other than free) or a load names an edge
 * on either side of the seam in direction dir (s = 0 / 1 when dir = 0,
 * t = 0 / 1 when dir = 1). */
static int part_on_seam(const sb_part *p, int dir)
{
    return p->kind == SB_PART_EDGE && p->st0[dir] == p->st1[dir] && (p->st0[dir] == 0.0 || p->st0[dir] == 1.0);
}

static int seam_named(const sb_scene *sc, int dir)
{
    for (int b = 0; b < sc->n_bcs; b++)
        for (int k = 0; k < sc->bcs[b].n_parts && sc->bcs[b].kind != SB_BC_FREE; k++)
            if (part_on_seam(&sc->bcs[b].parts[k], dir)) return 1;
    for (int l = 0; l < sc->n_loads; l++)
        for (int k = 0; k < sc->loads[l].n_parts; k++)
            if (part_on_seam(&sc->loads[l].parts[k], dir)) return 1;
    return 0;
}

/* BHEM §4.2 "Periodic boundary conditions": a seam is identified when the
 * chart maps s = 0 and s = 1 (resp. t) onto the same curve with the same
 * first derivatives, i.e. the surface closes C1 (cylinder, full annulus),
 * and no boundary condition or load names either edge (then the seam stays
 * open: a slit). */
int bhem_detect_periodic(bhem_state *S)
{
    enum { NS = 33 };
    double scale = 0.0;
    for (int k = 0; k < NS; k++) {
        sb_jet3 J;
        double u = (double)k / (NS - 1);
        sb_geometry_eval_st(S->scene, u, 0.5, &J);
        scale = fmax(scale, norm3(J.d1) + norm3(J.d2));
        sb_geometry_eval_st(S->scene, 0.5, u, &J);
        scale = fmax(scale, norm3(J.d1) + norm3(J.d2));
    }
    if (!(scale > 0.0) || !isfinite(scale))
        return bhem_fail(S, SB_ERR_INPUT, "the scene's reference surface is degenerate (zero or non-finite tangents)");
    double tol = 1e-9 * scale;
    for (int dir = 0; dir < 2; dir++) {
        int match = 1;
        for (int k = 0; k < NS && match; k++) {
            double u = (double)k / (NS - 1);
            sb_jet3 A, B;
            if (dir == 0) {
                sb_geometry_eval_st(S->scene, 0.0, u, &A);
                sb_geometry_eval_st(S->scene, 1.0, u, &B);
            } else {
                sb_geometry_eval_st(S->scene, u, 0.0, &A);
                sb_geometry_eval_st(S->scene, u, 1.0, &B);
            }
            if (dist3(A.x, B.x) > tol || dist3(A.d1, B.d1) > tol || dist3(A.d2, B.d2) > tol) match = 0;
        }
        /* never merge two edges that carry conditions: a full annulus with a
         * load on `end` and a clamp on `start` is a slit annulus, and merging
         * would put the load on the clamp (docs/scene_format.md) */
        int slit = match && seam_named(S->scene, dir);
        if (slit) match = 0;
        if (dir == 0) S->periodic_s = match, S->slit_s = slit;
        else S->periodic_t = match, S->slit_t = slit;
    }
    if (S->scene->domain.kind == SB_DOMAIN_L_SHAPE && (S->periodic_s || S->periodic_t))
        return bhem_fail(S, SB_ERR_INPUT, "periodic seams on an L-shaped domain are not supported");
    return SB_OK;
}

/* Symmetry-breaking imperfection (method.imperfection; the wrinkled sheet of
 * BHEM §7.1): the field of core/scene/sb_imperfection.c, added along the
 * reference node normal n: x += delta n, hs x_s += hs delta_s n, ...  (the
 * derivative of n is neglected: exact for flat sheets, O(A * curvature)
 * otherwise).  The imperfect surface IS the stress free reference. */

static int check_notch(bhem_state *S, int n1, int n2)
{
    double s01[2], t01[2];
    if (S->scene->domain.kind != SB_DOMAIN_L_SHAPE) return SB_OK;
    if (!sb_domain_notch_st(&S->scene->domain, s01, t01)) return SB_OK;
    for (int k = 0; k < 2; k++) {
        double a = s01[k] * n1, b = t01[k] * n2;
        if (fabs(a - round(a)) > 1e-9 || fabs(b - round(b)) > 1e-9)
            return bhem_fail(S, SB_ERR_INPUT,
                             "the L-shape notch [%g,%g]x[%g,%g] in (s,t) does not align with the %dx%d patch grid "
                             "of the coarsest level; choose a resolution whose grid lines pass through the notch corners",
                             s01[0], s01[1], t01[0], t01[1], n1, n2);
    }
    return SB_OK;
}

int bhem_level_build(bhem_state *S, bhem_level *L, int n1, int n2)
{
    const sb_scene *sc = S->scene;
    int rc = check_notch(S, n1, n2);
    if (rc) return rc;
    L->n1 = n1; L->n2 = n2;
    L->hs = 1.0 / n1; L->ht = 1.0 / n2;
    L->nn1 = n1 + 1; L->nn2 = n2 + 1;
    int ncell = n1 * n2, ngrid = L->nn1 * L->nn2;
    L->cell_elem = malloc(sizeof(int) * (size_t)ncell);
    L->node_id = malloc(sizeof(int) * (size_t)ngrid);
    L->node_i = malloc(sizeof(int) * (size_t)ngrid);
    L->node_j = malloc(sizeof(int) * (size_t)ngrid);
    if (!L->cell_elem || !L->node_id || !L->node_i || !L->node_j) return SB_ERR_NOMEM;

    /* cells: active when the cell centre lies in the domain (L-shape masking) */
    L->n_elems = 0;
    for (int j = 0; j < n2; j++)
        for (int i = 0; i < n1; i++) {
            double s = (i + 0.5) * L->hs, t = (j + 0.5) * L->ht;
            int in = sb_domain_contains_st(&sc->domain, s, t);
            L->cell_elem[i + n1 * j] = in ? L->n_elems++ : -1;
        }
    if (L->n_elems == 0) return bhem_fail(S, SB_ERR_INPUT, "no patch of the %dx%d grid lies in the domain", n1, n2);

    /* nodes: active when they touch an active cell; seams identified */
    for (int k = 0; k < ngrid; k++) L->node_id[k] = -1;
    L->n_nodes = 0;
    for (int j = 0; j < L->nn2; j++)
        for (int i = 0; i < L->nn1; i++) {
            int act = 0;
            for (int dj = -1; dj <= 0 && !act; dj++)
                for (int di = -1; di <= 0 && !act; di++) {
                    int ci = i + di, cj = j + dj;
                    if (ci >= 0 && ci < n1 && cj >= 0 && cj < n2 && L->cell_elem[ci + n1 * cj] >= 0) act = 1;
                }
            if (!act) continue;
            int ri = (S->periodic_s && i == n1) ? 0 : i;
            int rj = (S->periodic_t && j == n2) ? 0 : j;
            if (ri != i || rj != j) {
                L->node_id[i + L->nn1 * j] = L->node_id[ri + L->nn1 * rj];
                continue;
            }
            L->node_i[L->n_nodes] = i;
            L->node_j[L->n_nodes] = j;
            L->node_id[i + L->nn1 * j] = L->n_nodes++;
        }
    L->n_dofs = 12 * L->n_nodes;

    /* elements: 16 basis functions (4 corners x 4 kinds), 48 dofs */
    L->elem_cell = malloc(sizeof(int) * (size_t)L->n_elems);
    L->elem_dofs = malloc(sizeof(int) * (size_t)L->n_elems * BHEM_NED);
    L->x_ref = malloc(sizeof(double) * (size_t)L->n_dofs);
    if (!L->elem_cell || !L->elem_dofs || !L->x_ref) return SB_ERR_NOMEM;
    for (int c = 0; c < ncell; c++) {
        int e = L->cell_elem[c];
        if (e < 0) continue;
        int i = c % n1, j = c / n1;
        L->elem_cell[e] = c;
        for (int corner = 0; corner < 4; corner++) {
            int nd = L->node_id[(i + (corner & 1)) + L->nn1 * (j + (corner >> 1))];
            for (int kind = 0; kind < 4; kind++)
                for (int cc = 0; cc < 3; cc++)
                    L->elem_dofs[e * BHEM_NED + 3 * (4 * corner + kind) + cc] = 12 * nd + 3 * kind + cc;
        }
    }

    /* exact reference state from the chart (issue: "initial values come
     * exactly from the chart, including the mixed derivative"), scaled by the
     * patch size (bhem.h). */
    for (int n = 0; n < L->n_nodes; n++) {
        double s = L->node_i[n] * L->hs, t = L->node_j[n] * L->ht;
        sb_jet3 J;
        sb_geometry_eval_st(sc, s, t, &J);
        double *q = L->x_ref + 12 * n, nrm[3];
        cross3(J.d1, J.d2, nrm);
        double an = norm3(nrm), l1 = norm3(J.d1), l2 = norm3(J.d2);
        if (!(an > 1e-12 * l1 * l2) || !isfinite(an))
            return bhem_fail(S, SB_ERR_INPUT,
                             "the reference surface is singular at grid node (s,t) = (%g,%g) (parallel or zero "
                             "tangents, e.g. an annulus with r_in = 0 or a sphere pole); BHEM needs a regular chart", s, t);
        double imp[4] = { 0, 0, 0, 0 };
        if (S->imperfection > 0.0) sb_imperfection_eval(S->imperfection, s, t, imp);
        for (int c = 0; c < 3; c++) {
            double nc = nrm[c] / an;
            q[c] = J.x[c] + imp[0] * nc;
            q[3 + c] = L->hs * (J.d1[c] + imp[1] * nc);
            q[6 + c] = L->ht * (J.d2[c] + imp[2] * nc);
            q[9 + c] = L->hs * L->ht * (J.d12[c] + imp[3] * nc);
        }
    }
    return SB_OK;
}

int bhem_level_quadrature(bhem_state *S, bhem_level *L)
{
    double gx[BHEM_NQ1], gw[BHEM_NQ1];
    bhem_gauss_rule(gx, gw);
    for (int b = 0; b < BHEM_NQ1; b++)
        for (int a = 0; a < BHEM_NQ1; a++) {
            int q = a + BHEM_NQ1 * b;
            bhem_qp_basis *B = &L->qb[q];
            bhem_basis_eval(gx[a], gx[b], L->hs, L->ht, B->N, B->N1, B->N2, B->N11, B->N12, B->N22);
            L->qw[q] = L->hs * L->ht * gw[a] * gw[b];   /* App. A, Eq. (36) */
        }
    L->ref = malloc(sizeof(sb_shell_ref) * (size_t)L->n_elems * BHEM_NQP);
    if (!L->ref) return SB_ERR_NOMEM;
    double qe[BHEM_NED];
    for (int e = 0; e < L->n_elems; e++) {
        bhem_gather(L, e, L->x_ref, qe);
        for (int q = 0; q < BHEM_NQP; q++) {
            const bhem_qp_basis *B = &L->qb[q];
            sb_shell_basis sb = { BHEM_NB, B->N, B->N1, B->N2, B->N11, B->N12, B->N22 };
            sb_shell_ref *r = &L->ref[(size_t)e * BHEM_NQP + q];
            /* reference quantities from the Hermite interpolant of the chart,
             * so that the discrete rest state is exactly stress free */
            sb_shell_ref_init_basis(r, &sb, qe, S->mat.warp_angle, L->qw[q]);
            if (!(r->dA > 0.0) || !isfinite(r->dA)) {
                int c = L->elem_cell[e];
                return bhem_fail(S, SB_ERR_INPUT, "degenerate reference surface in patch (%d,%d) of the %dx%d grid",
                                 c % L->n1, c / L->n1, L->n1, L->n2);
            }
        }
    }
    return SB_OK;
}

int bhem_level_ensure_quadrature(bhem_state *S, bhem_level *L)
{
    return L->ref ? SB_OK : bhem_level_quadrature(S, L);
}

void bhem_level_free(bhem_level *L)
{
    free(L->node_id); free(L->node_i); free(L->node_j);
    free(L->cell_elem); free(L->elem_cell); free(L->elem_dofs);
    free(L->x_ref); free(L->ref);
    free(L->con); free(L->con_dofs); free(L->con_vals);
    free(L->load_vec); free(L->f_ext);
    free(L->mq); free(L->elem_mq);
    free(L->p_ptr); free(L->p_col); free(L->p_w);
    memset(L, 0, sizeof *L);
}

int bhem_node_at(const bhem_state *S, const bhem_level *L, int i, int j)
{
    (void)S;
    if (i < 0 || j < 0 || i >= L->nn1 || j >= L->nn2) return -1;
    return L->node_id[i + L->nn1 * j];
}

void bhem_gather(const bhem_level *L, int e, const double *x, double *qe)
{
    const int *d = L->elem_dofs + (size_t)e * BHEM_NED;
    for (int a = 0; a < BHEM_NED; a++) qe[a] = x[d[a]];
}

/* Patch containing (s,t); on patch borders an active neighbour is taken when
 * the first candidate is masked.  Returns the element or -1. */
int bhem_locate(const bhem_level *L, double s, double t, double *th1, double *th2)
{
    if (!(s >= -1e-12 && s <= 1.0 + 1e-12 && t >= -1e-12 && t <= 1.0 + 1e-12)) return -1;
    double us = s * L->n1, ut = t * L->n2;
    int i0 = (int)floor(us), j0 = (int)floor(ut);
    for (int dj = 0; dj >= -1; dj--)
        for (int di = 0; di >= -1; di--) {
            int i = i0 + di, j = j0 + dj;
            if (i >= L->n1) i = L->n1 - 1;
            if (j >= L->n2) j = L->n2 - 1;
            if (i < 0) i = 0;
            if (j < 0) j = 0;
            double a = us - i, b = ut - j;
            if (a < -1e-9 || a > 1.0 + 1e-9 || b < -1e-9 || b > 1.0 + 1e-9) continue;
            int e = L->cell_elem[i + L->n1 * j];
            if (e < 0) continue;
            *th1 = fmin(1.0, fmax(0.0, a));
            *th2 = fmin(1.0, fmax(0.0, b));
            return e;
        }
    return -1;
}

int bhem_eval(const bhem_state *S, const bhem_level *L, const double *x, int np,
              const double *st, double *pos)
{
    double N[BHEM_NB], qe[BHEM_NED];
    for (int p = 0; p < np; p++) {
        double th1, th2;
        int e = bhem_locate(L, st[2 * p], st[2 * p + 1], &th1, &th2);
        if (e < 0)
            return bhem_fail(S, SB_ERR_INPUT, "point (s,t) = (%g,%g) lies outside the domain", st[2 * p], st[2 * p + 1]);
        bhem_basis_eval(th1, th2, L->hs, L->ht, N, NULL, NULL, NULL, NULL, NULL);
        bhem_gather(L, e, x, qe);
        for (int c = 0; c < 3; c++) {
            double v = 0.0;
            for (int I = 0; I < BHEM_NB; I++) v += N[I] * qe[3 * I + c];   /* Eq. (16) */
            pos[3 * p + c] = v;
        }
    }
    return SB_OK;
}
