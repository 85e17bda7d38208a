/* bhem_bc.c — boundary conditions by elimination of generalized coordinates
 * (BHEM paper §4.2, "Positional constraints"): a constraint on a whole
 * boundary curve is the combination of constraints on the node values and
 * on the derivatives along (and, for clamping, across) the boundary.
 *
 * Per scene bc kind, for every node on an edge part (along = the derivative
 * kind along the edge, cross = the kind across it, mixed = kind 3):
 *   fixed     x and x_along (masked components): the whole edge curve is held,
 *             because x(s,t0) is the cubic Hermite interpolant of exactly these.
 *   clamped   x, x_along (all components) and the component of x_cross and
 *             x_mixed along the reference normal: then n.x_,cross = 0 on the
 *             whole edge, i.e. the tangent plane is held while in-plane
 *             stretching across the edge stays free.  ASSUMPTION: the normal
 *             component is a dof only if the reference normal at the node is a
 *             coordinate axis (flat clamps, all validation scenes); otherwise
 *             all three components of x_cross and x_mixed are held (a
 *             slightly stiffer clamp that also fixes in-plane stretching at the
 *             edge).
 *   symmetry  plane with normal e_a: the mirror map S = I - 2 e_a e_a^T gives
 *             x_a fixed, (x_along)_a = 0, and x_cross, x_mixed parallel to e_a,
 *             i.e. their other two components vanish (all at reference values).
 *   moving    x = c + R(f angle)(X - c) + f T and x_along = R X_along (masked);
 *             with clamp_tangent also x_cross, x_mixed = R X_(...).
 * Point parts constrain the node at the point (it must be a grid node):
 * fixed/symmetry/moving: x; clamped: x plus the normal components of the two
 * first derivatives; moving with clamp_tangent: x plus the rotated first
 * derivatives (the twisting cloth of BHEM Fig. 18, mixed derivative free).
 * A moving bc's "derivative" ("s", "t", "st") prescribes the named first
 * derivatives, rotated, at every node of its parts (the umbrella's ribs,
 * BHEM Fig. 5: position and derivative along the rib).
 * Periodic nodes are shared, so their constraints apply once.  When two bcs
 * constrain the same dof, the later bc in the scene wins. */
#include "bhem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BHEM_FREE_DOF (-2)
#define BHEM_HELD (-1)

static void mark(int *owner, int node, int kind, unsigned comps, int who)
{
    for (int c = 0; c < 3; c++)
        if (comps & (1u << c)) owner[12 * node + 3 * kind + c] = who;
}

/* component mask of the reference normal at the node if it is an axis, else 7 */
static unsigned normal_mask(const bhem_level *L, int node)
{
    const double *d1 = L->x_ref + 12 * node + 3, *d2 = L->x_ref + 12 * node + 6;
    double n[3] = { d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0] };
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; c++)
        if (fabs(n[c]) > (1.0 - 1e-9) * l) return 1u << c;
    return 7u;
}

static void constrain_node(const bhem_level *L, const sb_bc *bc, int b, int node, int along, int cross, int *owner)
{
    unsigned mask = bc->components ? bc->components : 7u;
    switch (bc->kind) {
    case SB_BC_FIXED:
        mark(owner, node, 0, mask, BHEM_HELD);
        if (along) mark(owner, node, along, mask, BHEM_HELD);
        break;
    case SB_BC_CLAMPED: {
        unsigned nm = normal_mask(L, node);
        mark(owner, node, 0, 7u, BHEM_HELD);
        if (along) {
            mark(owner, node, along, 7u, BHEM_HELD);
            mark(owner, node, cross, nm, BHEM_HELD);
            mark(owner, node, 3, nm, BHEM_HELD);
        } else {
            mark(owner, node, 1, nm, BHEM_HELD);
            mark(owner, node, 2, nm, BHEM_HELD);
        }
        break;
    }
    case SB_BC_SYMMETRY: {
        unsigned ax = 1u << bc->axis, other = 7u & ~ax;
        mark(owner, node, 0, ax, BHEM_HELD);
        if (along) {
            mark(owner, node, along, ax, BHEM_HELD);
            mark(owner, node, cross, other, BHEM_HELD);
            mark(owner, node, 3, other, BHEM_HELD);
        }
        break;
    }
    case SB_BC_MOVING:
        mark(owner, node, 0, mask, b);
        if (along) {
            mark(owner, node, along, mask, b);
            if (bc->clamp_tangent) {
                mark(owner, node, cross, mask, b);
                mark(owner, node, 3, mask, b);
            }
        } else if (bc->clamp_tangent) {
            mark(owner, node, 1, mask, b);
            mark(owner, node, 2, mask, b);
        }
        /* scene key "derivative": the named nodal first derivatives follow the
         * motion, x_,s = R X_,s (BHEM §4.2 Neumann constraints; Fig. 5's ribs) */
        if (bc->derivative & 1u) mark(owner, node, 1, mask, b);
        if (bc->derivative & 2u) mark(owner, node, 2, mask, b);
        break;
    case SB_BC_FREE:
        break;
    }
}

static int apply_part(bhem_state *S, bhem_level *L, int b, const sb_part *pt, int *owner)
{
    const sb_bc *bc = &S->scene->bcs[b];
    const double tol = 1e-9;
    int found = 0;
    if (pt->kind == SB_PART_POINT) {
        double a = pt->st[0] * L->n1, c = pt->st[1] * L->n2;
        int i = (int)lround(a), j = (int)lround(c);
        int node = (fabs(a - i) < 1e-6 && fabs(c - j) < 1e-6) ? bhem_node_at(S, L, i, j) : -1;
        if (node < 0)
            return bhem_fail(S, SB_ERR_INPUT,
                             "bc %d: point \"%s\" at (s,t) = (%g,%g) is not a node of the %dx%d patch grid; BHEM "
                             "constrains generalized coordinates at nodes (§4.2), choose a resolution with a node there",
                             b, pt->name, pt->st[0], pt->st[1], L->n1, L->n2);
        constrain_node(L, bc, b, node, 0, 0, owner);
        return SB_OK;
    }
    int const_t = fabs(pt->st0[1] - pt->st1[1]) < tol;
    int along = const_t ? 1 : 2, cross = const_t ? 2 : 1;
    for (int j = 0; j < L->nn2; j++)
        for (int i = 0; i < L->nn1; i++) {
            double s = i * L->hs, t = j * L->ht;
            int on = const_t ? (fabs(t - pt->st0[1]) < tol && s > pt->st0[0] - tol && s < pt->st1[0] + tol)
                             : (fabs(s - pt->st0[0]) < tol && t > pt->st0[1] - tol && t < pt->st1[1] + tol);
            int node = on ? bhem_node_at(S, L, i, j) : -1;
            if (node < 0) continue;
            constrain_node(L, bc, b, node, along, cross, owner);
            found++;
        }
    if (!found)
        return bhem_fail(S, SB_ERR_INPUT, "bc %d: edge \"%s\" contains no node of the %dx%d patch grid",
                         b, pt->name, L->n1, L->n2);
    return SB_OK;
}

int bhem_bc_build(bhem_state *S, bhem_level *L)
{
    const sb_scene *sc = S->scene;
    int *owner = malloc(sizeof(int) * (size_t)L->n_dofs);
    if (!owner) return SB_ERR_NOMEM;
    for (int k = 0; k < L->n_dofs; k++) owner[k] = BHEM_FREE_DOF;
    int rc = SB_OK;
    for (int b = 0; b < sc->n_bcs && rc == SB_OK; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind == SB_BC_SYMMETRY && (bc->axis < 0 || bc->axis > 2)) {
            rc = bhem_fail(S, SB_ERR_INPUT, "bc %d: symmetry axis %d is not 0, 1 or 2", b, bc->axis);
            break;
        }
        if (bc->kind == SB_BC_MOVING && bc->slide) continue;   /* a penalty in the core (sb_pin.h), not eliminated */
        for (int k = 0; k < bc->n_parts && rc == SB_OK; k++) rc = apply_part(S, L, b, &bc->parts[k], owner);
    }
    if (rc) { free(owner); return rc; }
    int n = 0;
    for (int k = 0; k < L->n_dofs; k++) n += owner[k] != BHEM_FREE_DOF;
    L->n_con = n;
    L->con = malloc(sizeof(bhem_con) * (size_t)(n ? n : 1));
    L->con_dofs = malloc(sizeof(int) * (size_t)(n ? n : 1));
    L->con_vals = malloc(sizeof(double) * (size_t)(n ? n : 1));
    if (!L->con || !L->con_dofs || !L->con_vals) { free(owner); return SB_ERR_NOMEM; }
    n = 0;
    for (int k = 0; k < L->n_dofs; k++)
        if (owner[k] != BHEM_FREE_DOF) {
            L->con[n].dof = k;
            L->con[n].bc = owner[k];
            L->con_dofs[n++] = k;
        }
    free(owner);
    L->dir.n = L->n_con;
    L->dir.dofs = L->con_dofs;
    L->dir.values = L->con_vals;
    bhem_bc_update(S, L);
    return SB_OK;
}

/* Prescribed values at the current step: reference values, or the rigid
 * motion of a moving bc (sb_scene.h: x = c + R(f angle)(X - c) + f T; the
 * derivative coordinates rotate: x_k = R X_k). */
void bhem_bc_update(bhem_state *S, bhem_level *L)
{
    const sb_scene *sc = S->scene;
    double R[SB_SCENE_MAX_BCS][9];
    for (int b = 0; b < sc->n_bcs; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind != SB_BC_MOVING) continue;
        double f = S->motion_factor[b];
        double an = sqrt(bc->rot_axis[0] * bc->rot_axis[0] + bc->rot_axis[1] * bc->rot_axis[1] +
                         bc->rot_axis[2] * bc->rot_axis[2]);
        if (an > 0.0) {
            double ax[3] = { bc->rot_axis[0] / an, bc->rot_axis[1] / an, bc->rot_axis[2] / an };
            sb_rotation(ax, f * bc->rot_angle, R[b]);
        } else {
            memset(R[b], 0, sizeof R[b]);
            R[b][0] = R[b][4] = R[b][8] = 1.0;
        }
    }
    for (int k = 0; k < L->n_con; k++) {
        int dof = L->con[k].dof, b = L->con[k].bc;
        if (b < 0) { L->con_vals[k] = L->x_ref[dof]; continue; }
        const sb_bc *bc = &sc->bcs[b];
        int base = dof - dof % 3, c = dof % 3, kind = (dof % 12) / 3;
        const double *X = L->x_ref + base, *Rb = R[b];
        double f = S->motion_factor[b], v;
        if (kind == 0) {
            v = bc->rot_center[c] + f * bc->translation[c];
            for (int d = 0; d < 3; d++) v += Rb[3 * c + d] * (X[d] - bc->rot_center[d]);
        } else {
            v = 0.0;
            for (int d = 0; d < 3; d++) v += Rb[3 * c + d] * X[d];
        }
        L->con_vals[k] = v;
    }
}
