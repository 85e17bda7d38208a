/* a3_adapt.c — adaptivity of adaptive_sqrt3 (sqrt3 paper §5.3): the mean
 * curvature criterion (Eq. 22-23) drives sqrt3 coarsening and refinement of
 * the forest (a3_sqrt3.h) every method.adapt_every steps (the run calls the
 * adapt op, core/problem/sb_run_adapt.c); the model is then rebuilt from
 * scratch on the new mesh (masses re-lumped: Alg. 1 on the new triangles,
 * so the total mass stays rho times the area) and the state x, v is
 * carried over: vertices that stay keep their values, new vertices are
 * interpolated where they were inserted (centroid, or 1/3 and 2/3 of a
 * boundary edge: the paper's smoothing parameter alpha_n = 0, §5.1).
 *
 * Choices where the paper is silent (docs/adaptive_sqrt3.md):
 *  - |c(x_i)| of Eq. 22 with current positions and current hybrid areas;
 *    0 on boundary vertices (their one-ring is open, Eq. 22 would measure
 *    the boundary's in-plane turning, not bending).
 *  - refine a triangle of generation g when the largest |c| of its corners
 *    exceeds l_g (Eq. 23: l_base = method.curv_base, l_gmax = method.curv_max,
 *    g_max = method.max_generation); one operation per triangle and
 *    adaptation (a split, or the flip with its mate, or a boundary split).
 *  - coarsen an operation (3-to-1 join / boundary join, after flipping back)
 *    when the largest |c| over the vertices of its triangles (the one-ring of
 *    the vertex it removes) is below method.coarsen_fraction x l_g of the
 *    parent's generation; coarsening runs before refinement, on the same
 *    curvature values. */
#include "sb_vec3.h"
#include "a3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


int a3_curvature(const a3_state *S, const double *x, double *c)
{
    const sb_mesh *m = &S->mesh;
    double *K = calloc((size_t)m->nv * 4, sizeof(double));   /* 3 components + hybrid area */
    if (!K) return SB_ERR_NOMEM;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        const double *P[3] = { x + 3 * v[0], x + 3 * v[1], x + 3 * v[2] };
        double A[3];
        a3_voronoi(P[0], P[1], P[2], A);
        for (int k = 0; k < 3; k++) {
            const int i = (k + 1) % 3, j = (k + 2) % 3;
            /* cot of the angle at corner k, opposite edge (i, j) */
            double u[3], w[3], cr[3];
            for (int d = 0; d < 3; d++) {
                u[d] = P[i][d] - P[k][d];
                w[d] = P[j][d] - P[k][d];
            }
            cr[0] = u[1] * w[2] - u[2] * w[1];
            cr[1] = u[2] * w[0] - u[0] * w[2];
            cr[2] = u[0] * w[1] - u[1] * w[0];
            const double s = sqrt(sb_dot3(cr, cr));
            const double ct = s > 0 ? sb_dot3(u, w) / s : 0.0;
            for (int d = 0; d < 3; d++) {   /* Eq. 22: (cot alpha + cot beta)(x_i - x_j), one angle per triangle */
                K[4 * v[i] + d] += ct * (P[i][d] - P[j][d]);
                K[4 * v[j] + d] += ct * (P[j][d] - P[i][d]);
            }
            K[4 * v[k] + 3] += A[k];
        }
    }
    for (int i = 0; i < m->nv; i++) {
        const double *k = K + 4 * i;
        c[i] = (m->vflag[i] & SB_MESH_V_BOUNDARY) || !(k[3] > 0) ? 0.0 : sqrt(sb_dot3(k, k)) / (2.0 * k[3]);
    }
    free(K);
    return SB_OK;
}

/* Eq. 23 */
static double limit(const a3_state *S, int g)
{
    const double gm = S->max_gen > 0 ? S->max_gen : 1;
    return g / gm * (S->curv_max - S->curv_base) + S->curv_base;
}

/* the largest curvature over the vertices of op k's triangles (and of the flips that consumed them) */
static double op_curvature(const a3_forest *F, int k, const double *fc)
{
    double cmax = 0.0;
    const a3_op *o = &F->op[k];
    for (int i = 0; i < o->n_out; i++) {
        const a3_ftri *T = &F->t[o->out[i]];
        for (int a = 0; a < 3; a++) cmax = fmax(cmax, fc[T->v[a]]);
        if (!T->alive && T->child_op >= 0) {
            const a3_op *f = &F->op[T->child_op];
            for (int j = 0; j < f->n_out; j++)
                for (int a = 0; a < 3; a++) cmax = fmax(cmax, fc[F->t[f->out[j]].v[a]]);
        }
    }
    return cmax;
}

int a3_adapt(void *state, const double *x, const double *v, int *changed)
{
    a3_state *S = state;
    a3_forest *F = &S->forest;
    *changed = 0;
    if (!S->adaptive) return SB_OK;
    const sb_mesh *m = &S->mesh;
    double *c = malloc(sizeof(double) * (size_t)m->nv), *fc = calloc((size_t)F->nv, sizeof(double));
    int *pending = malloc(sizeof(int) * (size_t)(m->nt ? m->nt : 1));
    if (!c || !fc || !pending) { free(c); free(fc); free(pending); return SB_ERR_NOMEM; }
    int rc = a3_curvature(S, x, c), n_pending = 0, ops = 0;
    for (int i = 0; i < m->nv; i++) fc[S->vmap[i]] = c[i];
    /* the triangles to refine, decided on the current mesh */
    for (int t = 0; t < m->nt && !rc; t++) {
        const int f = S->tmap[t], g = F->t[f].gen;
        const int *tv = m->tri + 3 * t;
        const double cm = fmax(c[tv[0]], fmax(c[tv[1]], c[tv[2]]));
        if (g < S->max_gen && cm > limit(S, g)) pending[n_pending++] = f;
    }
    /* coarsening (§5.2), newest operations first */
    for (int k = F->nop - 1; k >= 0 && !rc; k--) {
        const a3_op *o = &F->op[k];
        if (!o->applied || o->kind == A3_OP_FLIP) continue;
        if (op_curvature(F, k, fc) >= S->coarsen_frac * limit(S, F->t[o->in[0]].gen)) continue;
        int r = a3_forest_coarsen(F, k);
        if (r < 0) rc = r;
        else ops += r;
    }
    /* refinement (§5.1) */
    for (int i = 0; i < n_pending && !rc; i++) {
        if (!F->t[pending[i]].alive) continue;
        int r = a3_forest_refine(F, pending[i]);
        if (r < 0) rc = r;
        else ops += r;
    }
    free(c);
    free(pending);
    if (rc || !ops) { free(fc); return rc; }
    /* the state on every forest vertex: kept where it was, interpolated where inserted */
    double *fx = malloc(sizeof(double) * 6 * (size_t)F->nv);
    unsigned char *has = calloc((size_t)F->nv, 1);
    free(fc);
    if (!fx || !has) { free(fx); free(has); return SB_ERR_NOMEM; }
    for (int i = 0; i < m->nv; i++) {
        const int f = S->vmap[i];
        memcpy(fx + 6 * f, x + 3 * i, 3 * sizeof(double));
        memcpy(fx + 6 * f + 3, v + 3 * i, 3 * sizeof(double));
        has[f] = 1;
    }
    for (int f = 0; f < F->nv; f++) {
        if (has[f]) continue;
        double acc[6] = { 0 };
        int ok = F->vpar[3 * f] >= 0;
        for (int k = 0; k < 3 && ok; k++) {
            const int p = F->vpar[3 * f + k];
            if (p < 0 || F->vw[3 * f + k] == 0.0) continue;
            if (!has[p]) { ok = 0; break; }
            for (int d = 0; d < 6; d++) acc[d] += F->vw[3 * f + k] * fx[6 * p + d];
        }
        if (ok) {
            memcpy(fx + 6 * f, acc, sizeof acc);
            has[f] = 1;
        }
    }
    a3_free_model(S);
    rc = a3_build_model(S);
    if (!rc) {
        double *xn = realloc(S->x_new, sizeof(double) * (size_t)S->n_dofs);
        double *vn = xn ? realloc(S->v_new, sizeof(double) * (size_t)S->n_dofs) : NULL;
        if (xn) S->x_new = xn;
        if (vn) S->v_new = vn;
        if (!xn || !vn) rc = SB_ERR_NOMEM;
        for (int i = 0; i < S->nv && !rc; i++) {
            const int f = S->vmap[i];
            if (!has[f]) { rc = a3_fail(S, SB_ERR_INTERNAL, "no state for the new vertex %d", f); break; }
            memcpy(S->x_new + 3 * i, fx + 6 * f, 3 * sizeof(double));
            memcpy(S->v_new + 3 * i, fx + 6 * f + 3, 3 * sizeof(double));
        }
    }
    free(fx);
    free(has);
    if (!rc) {
        *changed = 1;
        S->n_adapt_changes++;
    }
    return rc;
}

int a3_adapt_state(void *state, double *x, double *v)
{
    a3_state *S = state;
    if (!S->x_new) return SB_ERR_INTERNAL;
    memcpy(x, S->x_new, sizeof(double) * (size_t)S->n_dofs);
    memcpy(v, S->v_new, sizeof(double) * (size_t)S->n_dofs);
    return SB_OK;
}
