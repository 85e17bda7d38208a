/* lf_level.c — one level of linear_fem: its mesh (generated on level 0,
 * refined 1-to-4 above), the dof layout, the reference state, the per
 * triangle reference quantities (metric, warp/weft frame, reference shape
 * operator) and the hinges, then boundary conditions and loads. */
#include "sb_vec3.h"
#include "lf.h"
#include "sb_context.h"
#include "sb_geometry.h"
#include "sb_imperfection.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int lf_fail(const lf_state *S, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sb_verror(S ? S->ctx : NULL, status, "linear_fem", fmt, ap);
    va_end(ap);
    return status;
}


void lf_level_free(lf_level *L)
{
    sb_mesh_free(&L->mesh);
    sb_mesh_locator_free(&L->loc);
    sb_mesh_refinement_free(&L->rf);
    free(L->x_ref); free(L->tri); free(L->hinge);
    free(L->con); free(L->con_dofs); free(L->con_vals);
    free(L->load_vec); free(L->f_ext); free(L->mq); free(L->tri_mq);
    free(L->p_ptr); free(L->p_col); free(L->p_w);
    memset(L, 0, sizeof *L);
}

int lf_tri_dofs(const lf_state *S, const lf_level *L, int t, int *d)
{
    const lf_tri *T = &L->tri[t];
    const int ns = S->bending == LF_BEND_HINGE ? 3 : 6;
    for (int s = 0; s < ns; s++) {
        const int v = s < 3 ? T->v[s] : T->o[s - 3];
        for (int c = 0; c < 3; c++) d[3 * s + c] = v < 0 ? -1 : 3 * v + c;
    }
    if (!S->edge_dofs) return 3 * ns;
    for (int i = 0; i < 3; i++) d[18 + i] = 3 * L->nv + T->e[i];
    return 21;
}

void lf_gather(const lf_state *S, const lf_level *L, int t, const double *x, double *qe)
{
    int d[LF_NED_MAX];
    const int n = lf_tri_dofs(S, L, t, d);
    for (int a = 0; a < n; a++) qe[a] = d[a] >= 0 ? x[d[a]] : 0.0;
}

int lf_eval(const lf_state *S, const lf_level *L, const double *x, int np, const double *st, double *pos)
{
    for (int p = 0; p < np; p++) {
        double b[3];
        const int t = sb_mesh_locate(&L->mesh, &L->loc, st[2 * p], st[2 * p + 1], b);
        if (t < 0)
            return lf_fail(S, SB_ERR_INPUT, "point (s,t) = (%g,%g) lies outside the mesh", st[2 * p], st[2 * p + 1]);
        const int *v = L->mesh.tri + 3 * t;
        for (int c = 0; c < 3; c++)
            pos[3 * p + c] = b[0] * x[3 * v[0] + c] + b[1] * x[3 * v[1] + c] + b[2] * x[3 * v[2] + c];
    }
    return SB_OK;
}

/* connectivity of the triangle records */
static void tri_topology(const lf_state *S, lf_level *L)
{
    const sb_mesh *m = &L->mesh;
    for (int t = 0; t < m->nt; t++) {
        lf_tri *T = &L->tri[t];
        memset(T, 0, sizeof *T);
        for (int i = 0; i < 3; i++) {
            const int e = m->tri_edge[3 * t + i];
            T->v[i] = m->tri[3 * t + i];
            T->e[i] = e;
            const int j = m->edge_t[2 * e] == t ? 0 : 1;
            T->sigma[i] = j == 0 ? 1 : -1;
            T->o[i] = sb_mesh_edge_opp(m, e, 1 - j);
            T->kind[i] = T->o[i] >= 0 ? LF_EDGE_INTERIOR : LF_EDGE_FREE;
            T->bc[i] = -1;
            T->c[i] = T->kind[i] == LF_EDGE_INTERIOR && S->bending == LF_BEND_MIDEDGE ? 0.5 : 0.0;
        }
    }
}

/* metric, frame and reference shape operator of every triangle */
static int tri_reference(lf_state *S, lf_level *L)
{
    const sb_mesh *m = &L->mesh;
    const double zero[3] = { 0, 0, 0 };
    for (int t = 0; t < m->nt; t++) {
        lf_tri *T = &L->tri[t];
        const double *P0 = m->X + 3 * T->v[0], *P1 = m->X + 3 * T->v[1], *P2 = m->X + 3 * T->v[2];
        double X1[3], X2[3], N[3];
        for (int c = 0; c < 3; c++) {
            X1[c] = P1[c] - P0[c];
            X2[c] = P2[c] - P0[c];
        }
        sb_cross3(X1, X2, N);
        const double an = sqrt(sb_dot3(N, N)), l1 = sqrt(sb_dot3(X1, X1));
        if (!(an > 1e-12 * l1 * sqrt(sb_dot3(X2, X2))) || !isfinite(an)) {
            const double *c = m->tri_st + 6 * t;
            return lf_fail(S, SB_ERR_INPUT,
                           "the reference surface is singular at the triangle with corner (s,t) = (%g,%g) "
                           "(zero area in 3D: a degenerate chart)", c[0], c[1]);
        }
        /* warp direction: the chart's dX/ds at the triangle's centre, measured
         * from a_1 = p1 - p0 in the triangle's plane (sb_shell.h convention) */
        const double *cs = m->tri_st + 6 * t;
        sb_jet3 J;
        sb_geometry_eval_st(S->scene, (cs[0] + cs[2] + cs[4]) / 3.0, (cs[1] + cs[3] + cs[5]) / 3.0, &J);
        double t1[3], tc[3];
        for (int c = 0; c < 3; c++) {
            t1[c] = X1[c] / l1;
            N[c] /= an;
        }
        sb_cross3(t1, J.d1, tc);
        const double off = atan2(sb_dot3(tc, N), sb_dot3(t1, J.d1));
        if (sb_shell_ref_init(&T->ref, X1, X2, zero, zero, zero, S->mat.warp_angle + off, 0.5))
            return lf_fail(S, SB_ERR_INPUT, "degenerate reference triangle %d", t);
        for (int i = 0; i < 3; i++)
            if (T->kind[i] == LF_EDGE_CLAMP) {
                memcpy(T->gv0[i], N, sizeof N);
                memcpy(T->gv[i], N, sizeof N);
            }
    }
    return SB_OK;
}

static int hinges_build(lf_level *L)
{
    const sb_mesh *m = &L->mesh;
    int n = 0;
    for (int e = 0; e < m->ne; e++) {
        const int t = m->edge_t[2 * e], k = m->edge_k[2 * e];
        if (m->edge_t[2 * e + 1] >= 0 || L->tri[t].kind[k] != LF_EDGE_FREE) n++;
    }
    L->hinge = calloc((size_t)(n ? n : 1), sizeof(lf_hinge));
    if (!L->hinge) return SB_ERR_NOMEM;
    L->n_hinge = 0;
    for (int e = 0; e < m->ne; e++) {
        const int t = m->edge_t[2 * e], k = m->edge_k[2 * e], t1 = m->edge_t[2 * e + 1];
        const lf_tri *T = &L->tri[t];
        if (t1 < 0 && T->kind[k] == LF_EDGE_FREE) continue;
        lf_hinge *h = &L->hinge[L->n_hinge++];
        h->v[0] = m->edge_v[2 * e];
        h->v[1] = m->edge_v[2 * e + 1];
        h->v[2] = T->v[k];
        h->v[3] = t1 >= 0 ? sb_mesh_edge_opp(m, e, 1) : -1;
        h->tri = t;
        h->edge = e;
        h->kind = t1 >= 0 ? LF_EDGE_INTERIOR : T->kind[k];
        h->bc = t1 >= 0 ? -1 : T->bc[k];
        memcpy(h->gv, T->gv[k], sizeof h->gv);
        memcpy(h->gv0, T->gv0[k], sizeof h->gv0);
        const double *Xa = m->X + 3 * h->v[0], *Xb = m->X + 3 * h->v[1];
        double ed[3];
        for (int c = 0; c < 3; c++) ed[c] = Xb[c] - Xa[c];
        const double le = sqrt(sb_dot3(ed, ed));
        h->R = T->ref.dA + (t1 >= 0 ? L->tri[t1].ref.dA : 0.0);
        h->coef = le / h->R;
        /* reference in-plane normal of the edge in t0, in t0's warp/weft frame */
        double mvec[3];
        for (int c = 0; c < 3; c++) ed[c] /= le;
        sb_cross3(ed, T->ref.normal, mvec);
        const double m1 = sb_dot3(mvec, T->ref.e1), m2 = sb_dot3(mvec, T->ref.e2);
        h->Bdir[0] = 0.5 * m1 * m1;
        h->Bdir[1] = 0.5 * m2 * m2;
        h->Bdir[2] = 0.5 * m1 * m2;
        double q[12];
        for (int s = 0; s < 4; s++)
            for (int c = 0; c < 3; c++) q[3 * s + c] = h->v[s] >= 0 ? m->X[3 * h->v[s] + c] : 0.0;
        h->theta_bar = lf_hinge_theta(h, q);
    }
    return SB_OK;
}

/* method.imperfection: every vertex on the imperfect reference surface
 * X = chart(s,t) + delta(s,t) n(s,t) of core/scene/sb_imperfection.c, the
 * field bhem adds at its nodes (so both methods buckle from the same
 * surface; n = the chart's unit normal).  Recomputed from the chart at every
 * level (refined vertices are not interpolated: level independent).  The
 * imperfect surface is the stress-free reference and the initial state. */
static int imperfect(lf_state *S, sb_mesh *m)
{
    for (int v = 0; v < m->nv; v++) {
        const double s = m->st[2 * v], t = m->st[2 * v + 1];
        sb_jet3 J;
        sb_geometry_eval_st(S->scene, s, t, &J);
        double n[3], imp[4];
        sb_cross3(J.d1, J.d2, n);
        const double an = sqrt(sb_dot3(n, n));
        if (!(an > 0.0) || !isfinite(an))
            return lf_fail(S, SB_ERR_INPUT, "method.imperfection: the reference surface has no normal at (s,t) = (%g,%g)",
                           s, t);
        sb_imperfection_eval(S->imperfection, s, t, imp);
        for (int c = 0; c < 3; c++) m->X[3 * v + c] = J.x[c] + imp[0] * n[c] / an;
    }
    return SB_OK;
}

int lf_level_build(lf_state *S, int l)
{
    lf_level *L = &S->lv[l];
    char err[512];
    int rc;
    if (l == 0) {
        const int sh = S->n_levels - 1;
        sb_mesh_spec spec = { S->res >> sh, S->cells_t >> sh, (sb_mesh_pattern)S->pattern, S->jitter, S->seed };
        const char *rng = NULL;
        rc = sb_mesh_from_domain(S->scene, &spec, &L->mesh, &rng, err, sizeof err);
        if (rc) return lf_fail(S, rc, "%s", err);
        if (rng) S->rng_name = rng;
    } else {
        rc = sb_mesh_refine4(&S->lv[l - 1].mesh, S->scene, &L->mesh, &L->rf);
        if (rc) return lf_fail(S, rc, "refining level %d failed (status %d)", l - 1, rc);
    }
    if ((rc = sb_mesh_check(&L->mesh, err, sizeof err))) return lf_fail(S, SB_ERR_INTERNAL, "mesh check: %s", err);
    if (S->imperfection > 0.0 && (rc = imperfect(S, &L->mesh))) return rc;
    const sb_mesh *m = &L->mesh;
    L->nv = m->nv;
    L->ne = m->ne;
    L->nt = m->nt;
    L->n_dofs = 3 * m->nv + (S->edge_dofs ? m->ne : 0);
    L->x_ref = calloc((size_t)L->n_dofs, sizeof(double));
    L->tri = calloc((size_t)m->nt, sizeof(lf_tri));
    if (!L->x_ref || !L->tri) return SB_ERR_NOMEM;
    memcpy(L->x_ref, m->X, sizeof(double) * 3 * (size_t)m->nv);
    if ((rc = sb_mesh_locator_build(m, &L->loc))) return rc;
    tri_topology(S, L);
    if ((rc = lf_bc_build(S, L))) return rc;
    if ((rc = tri_reference(S, L))) return rc;
    /* reference shape operator, with the boundary kinds and ghosts set */
    double qe[LF_NED_MAX];
    if (S->bending == LF_BEND_MIDEDGE)
        for (int t = 0; t < m->nt; t++) {
            lf_gather(S, L, t, L->x_ref, qe);
            lf_tri_bending(S, &L->tri[t], qe, L->tri[t].bbar);
            for (int k = 0; k < 3; k++)
                if (!isfinite(L->tri[t].bbar[k])) return lf_fail(S, SB_ERR_INPUT, "non-finite reference curvature");
        }
    if (S->bending == LF_BEND_HINGE && (rc = hinges_build(L))) return rc;
    lf_bc_update(S, L);
    return lf_loads_build(S, L);
}
