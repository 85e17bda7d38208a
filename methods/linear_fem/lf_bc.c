/* lf_bc.c — boundary conditions of linear_fem by elimination of dofs (the
 * core zeroes their gradient and replaces their Hessian rows by identity)
 * plus, for rotations, the director / ghost data of the boundary edges.
 *
 *   fixed      the masked position components of every vertex on the part.
 *   moving     x = c + R(f angle)(X - c) + f T on the part's vertices (masked);
 *              with clamp_tangent the edges are clamped as below with the
 *              clamp normal rotated by R(f angle).
 *   symmetry   plane with normal e_a: component a of every vertex held; the
 *              midedge normal of each edge of the part is held in the plane's
 *              trace, n = +-(t x e_a)/|t x e_a| (t the current edge), so the
 *              surface meets the plane at right angles (midedge: alpha = the
 *              angle from the face normal to n, director dof held; hinge: a
 *              mirror ghost hinge with that angle).
 *   clamped    all position components of the part's vertices, and the edge
 *              normal held at the reference face normal of its triangle
 *              (midedge: alpha = the angle to it, director held; hinge: ghost
 *              hinge of the triangle's mirror image).  Triangle meshes have no
 *              rotation at a vertex: clamping a point (or prescribing its
 *              tangents) is refused.
 *   free       nothing (natural boundary: zero force and, with edge directors,
 *              zero moment; the averaged director and the hinge put no bending
 *              across free edges).
 * A point part must be a vertex of the mesh (corners always are; jitter never
 * moves vertices at the scene's points).  Later bcs override earlier ones on
 * shared dofs and edges. */
#include "sb_vec3.h"
#include "lf.h"
#include "sb_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LF_FREE_DOF (-2)
#define LF_HELD (-1)


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

static void mark_vertex(int *owner, int v, unsigned mask, int who)
{
    for (int c = 0; c < 3; c++)
        if (mask & (1u << c)) owner[3 * v + c] = who;
}

/* edge rotation data for clamp / symmetry edges of a part */
static int edges_of_part(lf_state *S, lf_level *L, int b, const sb_part *pt, int *owner, int *tmp)
{
    const sb_bc *bc = &S->scene->bcs[b];
    const sb_mesh *m = &L->mesh;
    const int n = sb_mesh_part_edges(m, pt, tmp);
    if (n <= 0)
        return lf_fail(S, SB_ERR_INPUT, "boundary[%d] (%s on \"%s\"): the part has no boundary edge in the mesh "
                       "(it lies on an identified seam)", b, bc_name(bc->kind), pt->name);
    for (int k = 0; k < n; k++) {
        const int e = tmp[k], t = m->edge_t[2 * e], i = m->edge_k[2 * e];
        lf_tri *T = &L->tri[t];
        T->kind[i] = bc->kind == SB_BC_SYMMETRY ? LF_EDGE_SYM : LF_EDGE_CLAMP;
        T->bc[i] = (short)b;
        T->c[i] = S->bending == LF_BEND_MIDEDGE ? 1.0 : 0.0;
        if (bc->kind == SB_BC_SYMMETRY) {
            /* sign so that the trace normal points along the reference face normal */
            const double *Xa = m->X + 3 * m->edge_v[2 * e], *Xb = m->X + 3 * m->edge_v[2 * e + 1];
            const double *Xc = m->X + 3 * T->v[i];
            double ed[3], ac[3], N[3], ax[3] = { 0, 0, 0 }, tr[3];
            for (int c = 0; c < 3; c++) {
                ed[c] = Xb[c] - Xa[c];
                ac[c] = Xc[c] - Xa[c];
            }
            sb_cross3(ed, ac, N);
            ax[bc->axis] = 1.0;
            sb_cross3(ed, ax, tr);
            const double ltr = sqrt(sb_dot3(tr, tr)), led = sqrt(sb_dot3(ed, ed));
            if (!(ltr > 0.5 * led))
                return lf_fail(S, SB_ERR_INPUT, "boundary[%d] (symmetry on \"%s\"): the edge is not perpendicular "
                               "to the symmetry plane's normal e_%c", b, pt->name, "xyz"[bc->axis]);
            const double sg = sb_dot3(tr, N) >= 0 ? 1.0 : -1.0;
            for (int c = 0; c < 3; c++) T->gv[i][c] = T->gv0[i][c] = sg * ax[c];
        }
        if (S->edge_dofs) owner[3 * L->nv + e] = LF_HELD;
    }
    return SB_OK;
}

static int apply_part(lf_state *S, lf_level *L, int b, const sb_part *pt, int *owner, int *tmp)
{
    const sb_bc *bc = &S->scene->bcs[b];
    const unsigned mask = bc->components ? bc->components : 7u;
    const int rot = bc->kind == SB_BC_CLAMPED || bc->kind == SB_BC_SYMMETRY ||
                    (bc->kind == SB_BC_MOVING && bc->clamp_tangent);
    if (pt->kind == SB_PART_POINT && rot && bc->kind != SB_BC_SYMMETRY)
        return lf_fail(S, SB_ERR_UNSUPPORTED,
                       "boundary[%d] (%s at point \"%s\"%s) cannot be imposed by linear_fem: a triangle mesh has no "
                       "rotation at a vertex, so a point can be fixed or moved but not clamped", b, bc_name(bc->kind),
                       pt->name, bc->kind == SB_BC_MOVING ? " with clamp_tangent" : "");
    const int nvp = sb_mesh_part_vertices(&L->mesh, pt, tmp);
    if (nvp < 0) return nvp;
    if (nvp == 0) {
        if (pt->kind == SB_PART_POINT)
            return lf_fail(S, SB_ERR_INPUT, "boundary[%d] (%s at \"%s\", (s,t) = (%g,%g)): the point is not a vertex "
                           "of the mesh; linear_fem constrains vertices, choose a resolution with a vertex there",
                           b, bc_name(bc->kind), pt->name, pt->st[0], pt->st[1]);
        return lf_fail(S, SB_ERR_INPUT, "boundary[%d] (%s on \"%s\"): the edge contains no vertex of the mesh", b,
                       bc_name(bc->kind), pt->name);
    }
    for (int k = 0; k < nvp; k++) {
        const int v = tmp[k];
        switch (bc->kind) {
        case SB_BC_FIXED: mark_vertex(owner, v, mask, LF_HELD); break;
        case SB_BC_CLAMPED: mark_vertex(owner, v, 7u, LF_HELD); break;
        case SB_BC_SYMMETRY: mark_vertex(owner, v, 1u << bc->axis, LF_HELD); break;
        case SB_BC_MOVING: mark_vertex(owner, v, mask, b); break;
        case SB_BC_FREE: break;
        }
    }
    if (pt->kind == SB_PART_EDGE && rot) return edges_of_part(S, L, b, pt, owner, tmp);
    return SB_OK;
}

int lf_bc_build(lf_state *S, lf_level *L)
{
    const sb_scene *sc = S->scene;
    const int nt = L->n_dofs + L->mesh.ne + L->nv + 1;
    int *owner = malloc(sizeof(int) * (size_t)L->n_dofs), *tmp = malloc(sizeof(int) * (size_t)nt);
    if (!owner || !tmp) { free(owner); free(tmp); return SB_ERR_NOMEM; }
    for (int k = 0; k < L->n_dofs; k++) owner[k] = LF_FREE_DOF;
    int rc = SB_OK;
    for (int b = 0; b < sc->n_bcs && rc == SB_OK; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind == SB_BC_SYMMETRY && (bc->axis < 0 || bc->axis > 2)) {
            rc = lf_fail(S, SB_ERR_INPUT, "boundary[%d]: symmetry axis %d is not 0, 1 or 2", b, bc->axis);
            break;
        }
        if (bc->kind == SB_BC_MOVING && bc->slide) continue;   /* a penalty in the core (sb_pin.h), not eliminated */
        for (int k = 0; k < bc->n_parts && rc == SB_OK; k++) rc = apply_part(S, L, b, &bc->parts[k], owner, tmp);
    }
    free(tmp);
    if (rc) { free(owner); return rc; }
    int n = 0;
    for (int k = 0; k < L->n_dofs; k++) n += owner[k] != LF_FREE_DOF;
    L->n_con = n;
    L->con = malloc(sizeof(lf_con) * (size_t)(n ? n : 1));
    L->con_dofs = malloc(sizeof(int) * (size_t)(n ? n : 1));
    L->con_vals = malloc(sizeof(double) * (size_t)(n ? n : 1));
    if (!L->con || !L->con_dofs || !L->con_vals) { free(owner); return SB_ERR_NOMEM; }
    n = 0;
    for (int k = 0; k < L->n_dofs; k++)
        if (owner[k] != LF_FREE_DOF) {
            L->con[n].dof = k;
            L->con[n].bc = owner[k];
            L->con_dofs[n++] = k;
        }
    free(owner);
    L->dir.n = L->n_con;
    L->dir.dofs = L->con_dofs;
    L->dir.values = L->con_vals;
    return SB_OK;
}

/* rotation of a moving bc at the current step */
static void bc_rotation(const lf_state *S, int b, double R[9])
{
    const sb_bc *bc = &S->scene->bcs[b];
    const double an = sqrt(sb_dot3(bc->rot_axis, bc->rot_axis));
    if (an > 0.0) {
        const double ax[3] = { bc->rot_axis[0] / an, bc->rot_axis[1] / an, bc->rot_axis[2] / an };
        sb_rotation(ax, S->motion_factor[b] * bc->rot_angle, R);
    } else {
        memset(R, 0, 9 * sizeof *R);
        R[0] = R[4] = R[8] = 1.0;
    }
}

/* Prescribed values at the current step and the ghost normals of moving clamps. */
void lf_bc_update(lf_state *S, lf_level *L)
{
    const sb_scene *sc = S->scene;
    for (int k = 0; k < L->n_con; k++) {
        const int dof = L->con[k].dof, b = L->con[k].bc;
        if (b < 0 || dof >= 3 * L->nv) { L->con_vals[k] = L->x_ref[dof]; continue; }
        const sb_bc *bc = &sc->bcs[b];
        double R[9];
        bc_rotation(S, b, R);
        const int c = dof % 3;
        const double *X = L->x_ref + (dof - c), f = S->motion_factor[b];
        double v = bc->rot_center[c] + f * bc->translation[c];
        for (int d = 0; d < 3; d++) v += R[3 * c + d] * (X[d] - bc->rot_center[d]);
        L->con_vals[k] = v;
    }
    for (int t = 0; t < L->nt; t++) {
        lf_tri *T = &L->tri[t];
        for (int i = 0; i < 3; i++) {
            if (T->kind[i] != LF_EDGE_CLAMP || T->bc[i] < 0 || sc->bcs[T->bc[i]].kind != SB_BC_MOVING) continue;
            double R[9];
            bc_rotation(S, T->bc[i], R);
            for (int c = 0; c < 3; c++) T->gv[i][c] = sb_dot3(R + 3 * c, T->gv0[i]);
        }
    }
    for (int h = 0; h < L->n_hinge; h++) {
        lf_hinge *hg = &L->hinge[h];
        if (hg->kind != LF_EDGE_CLAMP || hg->bc < 0 || sc->bcs[hg->bc].kind != SB_BC_MOVING) continue;
        double R[9];
        bc_rotation(S, hg->bc, R);
        for (int c = 0; c < 3; c++) hg->gv[c] = sb_dot3(R + 3 * c, hg->gv0);
    }
}
