/* a3_build.c — the model data of adaptive_sqrt3 on its mesh: rest data of
 * every triangle (Eq. 9-10, 13), the bending edges (Eq. 18-19), the hybrid
 * Voronoi masses (Alg. 1, Eq. 3), the constrained dofs and the dead loads.
 *
 * Boundary conditions by elimination (the core zeroes gradient entries and
 * replaces Hessian rows by identity): fixed = the masked components of the
 * part's vertices held at the reference; moving = x = c + R(f angle)(X - c)
 * + f T on them.  Later bcs override earlier ones on shared dofs.
 * Loads (dead, scaled by the step's load factor): gravity lumped with the
 * particle masses (f_i = m_i g: the paper's particle model, assumption),
 * line loads half an edge's reference length to each end, point loads at
 * the vertex of the point. */
#include "sb_vec3.h"
#include "a3.h"
#include "sb_geometry.h"
#include "sb_context.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#define A3_FREE_DOF (-2)
#define A3_HELD (-1)

int a3_fail(const a3_state *S, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sb_verror(S ? S->ctx : NULL, status, "adaptive_sqrt3", fmt, ap);
    va_end(ap);
    return status;
}


void a3_free_model(a3_state *S)
{
    sb_mesh_locator_free(&S->loc);
    memset(&S->loc, 0, sizeof S->loc);
    free(S->x_ref); free(S->tri); free(S->edge); free(S->mass);
    free(S->con); free(S->con_dofs); free(S->con_vals);
    free(S->load_vec); free(S->f_ext);
    S->x_ref = NULL; S->tri = NULL; S->edge = NULL; S->mass = NULL;
    S->con = NULL; S->con_dofs = NULL; S->con_vals = NULL; S->load_vec = NULL; S->f_ext = NULL;
    S->n_con = S->n_edge = 0;
}

void a3_free(a3_state *S)
{
    a3_free_model(S);
    sb_mesh_free(&S->mesh);
    a3_forest_free(&S->forest);
    free(S->vmap); free(S->tmap); free(S->x_new); free(S->v_new);
    S->vmap = S->tmap = NULL;
    S->x_new = S->v_new = NULL;
}

static int build_triangles(a3_state *S)
{
    const sb_mesh *m = &S->mesh;
    const double wa = S->scene->material.warp_angle;
    for (int t = 0; t < m->nt; t++) {
        a3_tri *T = &S->tri[t];
        const int *v = m->tri + 3 * t;
        for (int i = 0; i < 3; i++) T->v[i] = v[i];
        const double *Xa = m->X + 3 * v[0], *Xb = m->X + 3 * v[1], *Xc = m->X + 3 * v[2];
        /* warp direction: the chart's d/ds at the centre, in the triangle's
         * plane, rotated by the material's warp angle about the normal */
        const double *cs = m->tri_st + 6 * t;
        sb_jet3 J;
        sb_geometry_eval_st(S->scene, (cs[0] + cs[2] + cs[4]) / 3.0, (cs[1] + cs[3] + cs[5]) / 3.0, &J);
        double d1[3], d2[3], N[3], e1[3], w[3];
        for (int c = 0; c < 3; c++) {
            d1[c] = Xb[c] - Xa[c];
            d2[c] = Xc[c] - Xa[c];
        }
        sb_cross3(d1, d2, N);
        const double an = sqrt(sb_dot3(N, N));
        double l = 0.0;
        if (an > 0.0) {
            for (int c = 0; c < 3; c++) N[c] /= an;
            const double dn = sb_dot3(J.d1, N);
            for (int c = 0; c < 3; c++) e1[c] = J.d1[c] - dn * N[c];
            l = sqrt(sb_dot3(e1, e1));
        }
        if (!(l > 0.0))
            return a3_fail(S, SB_ERR_INPUT, "the reference triangle with corner (s,t) = (%g,%g) is degenerate", cs[0], cs[1]);
        for (int c = 0; c < 3; c++) e1[c] /= l;
        sb_cross3(N, e1, d2);
        for (int c = 0; c < 3; c++) w[c] = cos(wa) * e1[c] + sin(wa) * d2[c];
        if (a3_tri_init(T, Xa, Xb, Xc, w, S->C))
            return a3_fail(S, SB_ERR_INPUT, "the reference triangle with corner (s,t) = (%g,%g) is degenerate", cs[0], cs[1]);
    }
    return SB_OK;
}

static int build_edges(a3_state *S)
{
    const sb_mesh *m = &S->mesh;
    int n = 0;
    for (int e = 0; e < m->ne; e++) n += m->edge_t[2 * e + 1] >= 0;
    S->edge = calloc((size_t)(n ? n : 1), sizeof *S->edge);
    if (!S->edge) return SB_ERR_NOMEM;
    S->n_edge = 0;
    for (int e = 0; e < m->ne; e++) {
        const int t0 = m->edge_t[2 * e], t1 = m->edge_t[2 * e + 1];
        if (t1 < 0) continue;
        a3_edge *E = &S->edge[S->n_edge++];
        E->v[0] = m->edge_v[2 * e];
        E->v[1] = m->edge_v[2 * e + 1];
        E->v[2] = sb_mesh_edge_opp(m, e, 0);
        E->v[3] = sb_mesh_edge_opp(m, e, 1);
        a3_bend_weights(m->X + 3 * E->v[0], m->X + 3 * E->v[1], m->X + 3 * E->v[2], m->X + 3 * E->v[3], E->k);
        /* Eq. 18: 3 / (A_0 + A_1), times the stiffness factor k_b (a3.h) */
        E->q = S->kb * 3.0 / (S->tri[t0].area + S->tri[t1].area);
        for (int i = 0; i < 4; i++)
            if (!isfinite(E->k[i]))
                return a3_fail(S, SB_ERR_INPUT, "degenerate reference triangles at edge %d (infinite cotangent)", e);
    }
    return SB_OK;
}

static int build_mass(a3_state *S)
{
    const sb_mesh *m = &S->mesh;
    const double rho = S->scene->material.density;
    S->mass = calloc((size_t)m->nv, sizeof *S->mass);
    if (!S->mass) return SB_ERR_NOMEM;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        double A[3];
        a3_voronoi(m->X + 3 * v[0], m->X + 3 * v[1], m->X + 3 * v[2], A);
        for (int i = 0; i < 3; i++) S->mass[v[i]] += rho * A[i];   /* Eq. 3: m = A_hybrid rho */
    }
    return SB_OK;
}

static const char *bc_name(sb_bc_kind k)
{
    switch (k) {
    case SB_BC_FIXED: return "fixed";
    case SB_BC_CLAMPED: return "clamped";
    case SB_BC_SYMMETRY: return "symmetry";
    case SB_BC_MOVING: return "moving";
    default: return "free";
    }
}

static int build_bcs(a3_state *S)
{
    const sb_scene *sc = S->scene;
    const sb_mesh *m = &S->mesh;
    int *owner = malloc(sizeof(int) * (size_t)S->n_dofs), *tmp = malloc(sizeof(int) * (size_t)(m->nv + 1));
    if (!owner || !tmp) { free(owner); free(tmp); return SB_ERR_NOMEM; }
    for (int k = 0; k < S->n_dofs; k++) owner[k] = A3_FREE_DOF;
    int rc = SB_OK;
    for (int b = 0; b < sc->n_bcs && rc == SB_OK; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind == SB_BC_FREE) continue;
        const unsigned mask = bc->components ? bc->components : 7u;
        for (int p = 0; p < bc->n_parts && rc == SB_OK; p++) {
            const sb_part *pt = &bc->parts[p];
            const int nvp = sb_mesh_part_vertices(m, pt, tmp);
            if (nvp <= 0) {
                rc = a3_fail(S, SB_ERR_INPUT, "boundary[%d] (%s at \"%s\"): %s", b, bc_name(bc->kind), pt->name,
                             pt->kind == SB_PART_POINT ? "the point is not a vertex of the mesh; choose a resolution "
                             "with a vertex there" : "the edge contains no vertex of the mesh");
                break;
            }
            for (int k = 0; k < nvp; k++)
                for (int c = 0; c < 3; c++)
                    if (mask & (1u << c)) owner[3 * tmp[k] + c] = bc->kind == SB_BC_MOVING ? b : A3_HELD;
        }
    }
    free(tmp);
    if (rc) { free(owner); return rc; }
    int n = 0;
    for (int k = 0; k < S->n_dofs; k++) n += owner[k] != A3_FREE_DOF;
    S->n_con = n;
    S->con = malloc(sizeof *S->con * (size_t)(n ? n : 1));
    S->con_dofs = malloc(sizeof(int) * (size_t)(n ? n : 1));
    S->con_vals = malloc(sizeof(double) * (size_t)(n ? n : 1));
    if (!S->con || !S->con_dofs || !S->con_vals) { free(owner); return SB_ERR_NOMEM; }
    n = 0;
    for (int k = 0; k < S->n_dofs; k++)
        if (owner[k] != A3_FREE_DOF) {
            S->con[n].dof = k;
            S->con[n].bc = owner[k];
            S->con_dofs[n++] = k;
        }
    free(owner);
    S->dir.n = S->n_con;
    S->dir.dofs = S->con_dofs;
    S->dir.values = S->con_vals;
    return SB_OK;
}

void a3_bc_update(a3_state *S)
{
    const sb_scene *sc = S->scene;
    for (int k = 0; k < S->n_con; k++) {
        const int dof = S->con[k].dof, b = S->con[k].bc;
        if (b < 0) { S->con_vals[k] = S->x_ref[dof]; continue; }
        const sb_bc *bc = &sc->bcs[b];
        double R[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
        const double an = sqrt(sb_dot3(bc->rot_axis, bc->rot_axis)), f = S->motion_factor[b];
        if (an > 0.0) {
            const double ax[3] = { bc->rot_axis[0] / an, bc->rot_axis[1] / an, bc->rot_axis[2] / an };
            sb_rotation(ax, f * bc->rot_angle, R);
        }
        const int c = dof % 3;
        const double *X = S->x_ref + (dof - c);
        double v = bc->rot_center[c] + f * bc->translation[c];
        for (int d = 0; d < 3; d++) v += R[3 * c + d] * (X[d] - bc->rot_center[d]);
        S->con_vals[k] = v;
    }
}

static int build_loads(a3_state *S)
{
    const sb_scene *sc = S->scene;
    const sb_mesh *m = &S->mesh;
    const int n = S->n_dofs;
    S->load_vec = calloc((size_t)n * (size_t)(sc->n_loads ? sc->n_loads : 1), sizeof(double));
    S->f_ext = calloc((size_t)n, sizeof(double));
    int *tmp = malloc(sizeof(int) * (size_t)(m->ne + 1));
    if (!S->load_vec || !S->f_ext || !tmp) { free(tmp); return SB_ERR_NOMEM; }
    int rc = SB_OK;
    for (int k = 0; k < sc->n_loads && rc == SB_OK; k++) {
        const sb_load *ld = &sc->loads[k];
        double *b = S->load_vec + (size_t)k * n;
        if (ld->kind == SB_LOAD_GRAVITY) {
            for (int v = 0; v < m->nv; v++)
                for (int c = 0; c < 3; c++) b[3 * v + c] += S->mass[v] * ld->vec[c];
        } else if (ld->kind == SB_LOAD_LINE) {
            for (int p = 0; p < ld->n_parts && rc == SB_OK; p++) {
                const int ne = ld->parts[p].kind == SB_PART_EDGE ? sb_mesh_part_edges(m, &ld->parts[p], tmp) : 0;
                if (ne <= 0) { rc = a3_fail(S, SB_ERR_INPUT, "loads[%d]: \"%s\" is not an edge with boundary edges in the mesh", k, ld->parts[p].name); break; }
                sb_mesh_lump_line_load(m, tmp, ne, ld->vec, b);
            }
        } else if (ld->kind == SB_LOAD_POINT) {
            for (int p = 0; p < ld->n_parts && rc == SB_OK; p++) {
                const int v = ld->parts[p].kind == SB_PART_POINT ? sb_mesh_point_vertex(m, &ld->parts[p]) : -1;
                if (v < 0) { rc = a3_fail(S, SB_ERR_INPUT, "loads[%d]: point \"%s\" is not a vertex of the mesh; choose a resolution with a vertex there", k, ld->parts[p].name); break; }
                for (int c = 0; c < 3; c++) b[3 * v + c] += ld->vec[c];
            }
        }
    }
    free(tmp);
    return rc;
}

void a3_loads_update(a3_state *S)
{
    memset(S->f_ext, 0, sizeof(double) * (size_t)S->n_dofs);
    for (int k = 0; k < S->scene->n_loads; k++)
        sb_axpy(S->n_dofs, S->load_factor[k], S->load_vec + (size_t)k * S->n_dofs, S->f_ext);
}

int a3_build(a3_state *S)
{
    char err[512];
    sb_mesh base;
    sb_mesh_init(&base);
    sb_mesh_spec spec = { S->res, S->cells_t, (sb_mesh_pattern)S->pattern, 0.0, 1 };
    const char *rng = NULL;
    int rc = sb_mesh_from_domain(S->scene, &spec, &base, &rng, err, sizeof err);
    if (rc) { sb_mesh_free(&base); return a3_fail(S, rc, "%s", err); }
    rc = a3_forest_init(&S->forest, &base, S->max_gen);
    sb_mesh_free(&base);
    if (rc == SB_ERR_UNSUPPORTED)
        return a3_fail(S, rc, "scene %s: the domain has identified seams, which sqrt3 refinement does not support",
                       S->scene->name);
    if (rc) return rc;
    /* method.adaptive = 0: the full resolution, every triangle at the finest generation */
    if (!S->adaptive && (rc = a3_forest_refine_all(&S->forest))) return rc;
    return a3_build_model(S);
}

int a3_build_model(a3_state *S)
{
    char err[512];
    int rc;
    free(S->vmap);
    S->vmap = NULL;
    if ((rc = a3_forest_mesh(&S->forest, S->scene, &S->mesh, &S->vmap))) return rc;
    if ((rc = sb_mesh_check(&S->mesh, err, sizeof err))) return a3_fail(S, SB_ERR_INTERNAL, "mesh check: %s", err);
    const sb_mesh *m = &S->mesh;
    /* mesh triangle -> forest triangle (a3_forest_mesh exports the alive ones in record order) */
    free(S->tmap);
    S->tmap = malloc(sizeof(int) * (size_t)(m->nt ? m->nt : 1));
    if (!S->tmap) return SB_ERR_NOMEM;
    for (int t = 0, k = 0; t < S->forest.nt; t++)
        if (S->forest.t[t].alive) S->tmap[k++] = t;
    S->nv = m->nv;
    S->nt = m->nt;
    S->n_dofs = 3 * m->nv;
    S->x_ref = malloc(sizeof(double) * (size_t)S->n_dofs);
    S->tri = calloc((size_t)m->nt, sizeof *S->tri);
    if (!S->x_ref || !S->tri) return SB_ERR_NOMEM;
    memcpy(S->x_ref, m->X, sizeof(double) * (size_t)S->n_dofs);
    if ((rc = sb_mesh_locator_build(m, &S->loc))) return rc;
    if ((rc = build_triangles(S)) || (rc = build_edges(S)) || (rc = build_mass(S)) || (rc = build_bcs(S)) ||
        (rc = build_loads(S)))
        return rc;
    a3_bc_update(S);
    a3_loads_update(S);
    return SB_OK;
}
