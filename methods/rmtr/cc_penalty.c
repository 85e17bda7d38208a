/* cc_penalty.c — boundary conditions by the penalty method and the
 * boundary/point loads of the rmtr method.
 *
 * Edges (RMTR paper (3.6)): E = beta/2 ||x - b||^2_{L2(d omega)}, the L2
 * norm along the boundary curve integrated with the level's Gauss rule on
 * every domain-face edge that lies on a constrained part, measured in the
 * reference arc length |dX/dtau| dtau.  Only the masked components are
 * penalized; rotations stay free ("applied just on the displacement field",
 * §7).  beta = scale * h^-sigma per level (§3.1, sigma = 5 in §7.1).
 * Points (drape corners; ASSUMPTION, the paper does not spell it out): the
 * point penalty beta/2 |x(xi_p) - b_p|^2 with the same beta and no length
 * factor.  A Gauss point is constrained when its limit grid parameter lies on
 * the part (sb_part_contains_st), so parts ending inside an element edge are
 * resolved to the Gauss points.
 * Boundary data b (§6): recomputed on every level at every step from the
 * reference positions: fixed b = X, moving b = c + R(f angle)(X - c) + f t.
 * Line loads E = -int f . x ds, point loads E = -F . x(xi_p).
 * Clamped and symmetry edges (ASSUMPTION, the paper penalizes positions
 * only): besides the positions (all components for clamped, e_axis for
 * symmetry) the rotation about the edge is penalized through the slope of the
 * surface across the edge, theta = (dx/dc . N) / |dX/dc| with c the face
 * parameter across the edge and N the reference unit normal (theta = 0 in the
 * reference since dX/dc is tangent): E = beta_s/2 int theta^2 ds with
 * beta_s = beta h^2, the position penalty scaled by the level's h^2 so that
 * h theta and a displacement are penalized alike.  Linear in x, so the
 * penalty's Hessian is constant.  Moving edges with prescribed tangents and
 * end moments are not supported by this method (error at creation). */
#include "cc_method.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct ptbuf { cc_pt *pt; double *N; int n, cap; long nN, capN; } ptbuf;

static int push(ptbuf *B, const cc_pt *p, int k, const double *N)
{
    if (B->n == B->cap) {
        int cap = B->cap ? 2 * B->cap : 64;
        cc_pt *q = realloc(B->pt, (size_t)cap * sizeof *q);
        if (!q) return SB_ERR_NOMEM;
        B->pt = q;
        B->cap = cap;
    }
    if (B->nN + k > B->capN) {
        long cap = 2 * B->capN + k + 256;
        double *q = realloc(B->N, (size_t)cap * sizeof *q);
        if (!q) return SB_ERR_NOMEM;
        B->N = q;
        B->capN = cap;
    }
    B->pt[B->n] = *p;
    B->pt[B->n].off = B->nN;
    memcpy(B->N + B->nN, N, (size_t)k * sizeof *N);
    B->nN += k;
    B->n++;
    return SB_OK;
}

/* Basis at (u,v) of element el, in the element's node order. */
static int elem_basis(const cc_level *L, int el, double u, double v, double *W, int *k, cc_err *e)
{
    int idx[CC_MAX_BASIS];
    int st = cc_face_basis(L->mesh, L->quad.face[el], u, v, k, idx, W, CC_MAX_BASIS, e);
    if (st) return st;
    const int *nd = L->quad.enode + L->quad.eoff[el];
    if (*k != L->quad.eoff[el + 1] - L->quad.eoff[el] || memcmp(nd, idx, (size_t)*k * sizeof *idx) != 0)
        return cc_fail(e, SB_ERR_INTERNAL, "basis node order differs from the element's");
    return SB_OK;
}

static void combine(const double *N, int k, const int *nd, const double *v, int dim, double *out)
{
    for (int c = 0; c < dim; c++) out[c] = 0;
    for (int a = 0; a < k; a++)
        for (int c = 0; c < dim; c++) out[c] += N[a] * v[dim * nd[a] + c];
}

static int add_edge_part(const cc_state *S, const cc_level *L, const sb_part *part, cc_pt proto, int slope,
                         ptbuf *B, cc_err *e)
{
    const cc_mesh *m = L->mesh;
    const cc_quad *Q = &L->quad;
    double W[6 * CC_MAX_BASIS];
    (void)S;
    for (int el = 0; el < Q->ne; el++) {
        int f = Q->face[el];
        const int *nd = Q->enode + Q->eoff[el];
        for (int k = 0; k < 4; k++) {
            int d = m->fe[4 * f + k];
            int g = m->ef[2 * d] == f ? m->ef[2 * d + 1] : m->ef[2 * d];
            if (g >= 0 && m->dom[g]) continue;               /* interior edge */
            for (int a = 0; a < Q->ng; a++) {
                double t = Q->gp[a];
                double u = k == 0 ? t : k == 1 ? 1 : k == 2 ? 1 - t : 0;
                double v = k == 0 ? 0 : k == 1 ? t : k == 2 ? 1 : 1 - t;
                int kk, st = elem_basis(L, el, u, v, W, &kk, e);
                if (st) return st;
                double stp[2], T[3];
                combine(W, kk, nd, m->st, 2, stp);
                if (!sb_part_contains_st(part, stp[0], stp[1], 1e-9)) continue;
                combine(W + (k % 2 == 0 ? 1 : 2) * kk, kk, nd, L->X, 3, T);   /* dX/dtau */
                cc_pt p = proto;
                p.elem = el;
                p.w = Q->gw[a] * sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2]);
                combine(W, kk, nd, L->X, 3, p.X);
                if ((st = push(B, &p, kk, W))) return cc_fail(e, st, "out of memory (boundary points)");
                if (!slope) continue;
                /* the slope across the edge: derivative along the other face parameter */
                const double *Wc = W + (k % 2 == 0 ? 2 : 1) * kk;
                double C[3], Nr[3];
                combine(Wc, kk, nd, L->X, 3, C);
                Nr[0] = T[1] * C[2] - T[2] * C[1];
                Nr[1] = T[2] * C[0] - T[0] * C[2];
                Nr[2] = T[0] * C[1] - T[1] * C[0];
                double nn = sqrt(Nr[0] * Nr[0] + Nr[1] * Nr[1] + Nr[2] * Nr[2]), cc = C[0] * C[0] + C[1] * C[1] + C[2] * C[2];
                if (!(nn > 0 && cc > 0)) return cc_fail(e, SB_ERR_INPUT, "degenerate reference surface at a clamped edge");
                cc_pt q = p;
                q.kind = CC_PT_SLOPE;
                q.w = p.w / cc;
                q.inv_len = 1.0 / sqrt(cc);
                for (int c = 0; c < 3; c++) q.n[c] = Nr[c] / nn;
                if ((st = push(B, &q, kk, Wc))) return cc_fail(e, st, "out of memory (boundary points)");
            }
        }
    }
    return SB_OK;
}

static int add_point_part(const cc_level *L, const sb_part *part, cc_pt proto, ptbuf *B, cc_err *e)
{
    int f, k;
    double u, v, W[6 * CC_MAX_BASIS];
    if (cc_level_locate(L, part->st[0], part->st[1], &f, &u, &v))
        return cc_fail(e, SB_ERR_INPUT, "point (%g, %g) of part %s is not in the domain", part->xi[0], part->xi[1], part->name);
    int el = cc_level_element_of_face(L, f);
    int st = elem_basis(L, el, u, v, W, &k, e);
    if (st) return st;
    cc_pt p = proto;
    p.elem = el;
    p.w = 1.0;
    combine(W, k, L->quad.enode + L->quad.eoff[el], L->X, 3, p.X);
    return push(B, &p, k, W) ? cc_fail(e, SB_ERR_NOMEM, "out of memory (boundary points)") : SB_OK;
}

static int add_parts(const cc_state *S, const cc_level *L, int np, const sb_part *parts, cc_pt proto, int slope,
                     ptbuf *B, cc_err *e)
{
    for (int i = 0; i < np; i++) {
        int st = parts[i].kind == SB_PART_POINT ? add_point_part(L, &parts[i], proto, B, e)
                                                : add_edge_part(S, L, &parts[i], proto, slope, B, e);
        if (st) return st;
    }
    return SB_OK;
}

int cc_points_build(cc_state *S, int l, cc_err *e)
{
    const sb_scene *sc = S->scene;
    cc_level *L = &S->lv[l];
    ptbuf B = { 0 };
    int st = SB_OK;
    for (int b = 0; b < sc->n_bcs && !st; b++) {
        const sb_bc *bc = &sc->bcs[b];
        cc_pt proto = { 0 };
        proto.kind = CC_PT_PENALTY;
        proto.src = b;
        proto.mask = bc->components ? bc->components : 7u;
        if (bc->kind == SB_BC_FREE) continue;
        const int slope = bc->kind == SB_BC_CLAMPED || bc->kind == SB_BC_SYMMETRY;
        if (bc->kind == SB_BC_CLAMPED) proto.mask = 7u;
        if (bc->kind == SB_BC_SYMMETRY) proto.mask = 1u << bc->axis;
        if (bc->kind == SB_BC_MOVING && bc->slide)
            st = cc_fail(e, SB_ERR_UNSUPPORTED, "boundary condition %d (a sliding pin, \"slide\") is not supported by "
                         "the rmtr method: its penalty points are fixed at set-up, a pin between control points "
                         "that moves every step is not implemented", b);
        else if (bc->kind == SB_BC_MOVING && bc->clamp_tangent)
            st = cc_fail(e, SB_ERR_UNSUPPORTED, "boundary condition %d (moving with prescribed tangents) is "
                         "not supported by the rmtr penalty method", b);
        else st = add_parts(S, L, bc->n_parts, bc->parts, proto, slope, &B, e);
    }
    for (int i = 0; i < sc->n_loads && !st; i++) {
        const sb_load *ld = &sc->loads[i];
        cc_pt proto = { 0 };
        proto.src = i;
        if (ld->kind == SB_LOAD_LINE) {
            proto.kind = CC_PT_LINE_LOAD;
            st = add_parts(S, L, ld->n_parts, ld->parts, proto, 0, &B, e);
        } else if (ld->kind == SB_LOAD_POINT) {
            proto.kind = CC_PT_POINT_LOAD;
            st = add_parts(S, L, ld->n_parts, ld->parts, proto, 0, &B, e);
        } else if (ld->kind == SB_LOAD_END_MOMENT) {
            st = cc_fail(e, SB_ERR_UNSUPPORTED, "load %d: end moments are not supported by the rmtr method", i);
        }
    }
    /* sort by element (counting sort) */
    int ne = L->quad.ne;
    L->ept = calloc((size_t)ne + 1, sizeof *L->ept);
    L->pt = malloc((size_t)(B.n ? B.n : 1) * sizeof *L->pt);
    L->ptN = B.N;
    B.N = NULL;
    if (!st && (!L->ept || !L->pt)) st = cc_fail(e, SB_ERR_NOMEM, "out of memory (boundary points)");
    if (!st) {
        for (int i = 0; i < B.n; i++) L->ept[B.pt[i].elem + 1]++;
        for (int el = 0; el < ne; el++) L->ept[el + 1] += L->ept[el];
        int *fill = calloc((size_t)ne + 1, sizeof *fill);
        if (!fill) st = cc_fail(e, SB_ERR_NOMEM, "out of memory (boundary points)");
        for (int i = 0; i < B.n && !st; i++) {
            int el = B.pt[i].elem;
            L->pt[L->ept[el] + fill[el]++] = B.pt[i];
        }
        free(fill);
        L->npt = B.n;
    }
    free(B.pt);
    free(B.N);
    if (!st) cc_points_update(S, l);
    return st;
}

void cc_points_update(cc_state *S, int l)
{
    const sb_scene *sc = S->scene;
    cc_level *L = &S->lv[l];
    for (int i = 0; i < L->npt; i++) {
        cc_pt *p = &L->pt[i];
        if (p->kind == CC_PT_SLOPE) continue;   /* target slope 0, fixed */
        if (p->kind == CC_PT_PENALTY) {
            const sb_bc *bc = &sc->bcs[p->src];
            memcpy(p->b, p->X, sizeof p->b);
            if (bc->kind != SB_BC_MOVING) continue;
            double f = S->motion_factor[p->src], R[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
            double an = bc->rot_axis[0] * bc->rot_axis[0] + bc->rot_axis[1] * bc->rot_axis[1] + bc->rot_axis[2] * bc->rot_axis[2];
            if (an > 0 && bc->rot_angle != 0) sb_rotation(bc->rot_axis, f * bc->rot_angle, R);
            double r[3] = { p->X[0] - bc->rot_center[0], p->X[1] - bc->rot_center[1], p->X[2] - bc->rot_center[2] };
            for (int c = 0; c < 3; c++)      /* b = c + R(f angle)(X - c) + f t (sb_scene.h) */
                p->b[c] = bc->rot_center[c] + R[3 * c] * r[0] + R[3 * c + 1] * r[1] + R[3 * c + 2] * r[2] +
                          f * bc->translation[c];
        } else {
            const sb_load *ld = &sc->loads[p->src];
            for (int c = 0; c < 3; c++) p->b[c] = S->load_factor[p->src] * ld->vec[c];
        }
    }
}

double cc_points_energy(const cc_state *S, const cc_level *L, int el, const double *qe, double *ge, double *Ke)
{
    int k = L->quad.eoff[el + 1] - L->quad.eoff[el], n = 3 * k;
    double E = 0;
    (void)S;
    for (int i = L->ept[el]; i < L->ept[el + 1]; i++) {
        const cc_pt *p = &L->pt[i];
        const double *N = L->ptN + p->off;
        double x[3] = { 0, 0, 0 };
        for (int a = 0; a < k; a++)
            for (int c = 0; c < 3; c++) x[c] += N[a] * qe[3 * a + c];
        if (p->kind == CC_PT_SLOPE) {
            /* x here is dx/dc; E = beta h^2 / 2 w (dx/dc . N)^2, w = weight / |dX/dc|^2 */
            const double bw = L->beta * L->h * L->h * p->w;
            const double th = x[0] * p->n[0] + x[1] * p->n[1] + x[2] * p->n[2];
            E += 0.5 * bw * th * th;
            if (ge)
                for (int a = 0; a < k; a++)
                    for (int c = 0; c < 3; c++) ge[3 * a + c] += bw * th * N[a] * p->n[c];
            if (Ke)
                for (int a = 0; a < k; a++)
                    for (int b = 0; b < k; b++)
                        for (int c = 0; c < 3; c++)
                            for (int d = 0; d < 3; d++) Ke[(3 * a + c) * n + 3 * b + d] += bw * N[a] * N[b] * p->n[c] * p->n[d];
            continue;
        }
        if (p->kind == CC_PT_PENALTY) {
            double bw = L->beta * p->w;
            for (int c = 0; c < 3; c++) {
                if (!(p->mask & (1u << c))) continue;
                double r = x[c] - p->b[c];
                E += 0.5 * bw * r * r;                                  /* (3.6) */
                if (ge)
                    for (int a = 0; a < k; a++) ge[3 * a + c] += bw * r * N[a];
                if (Ke)
                    for (int a = 0; a < k; a++)
                        for (int b = 0; b < k; b++) Ke[(3 * a + c) * n + 3 * b + c] += bw * N[a] * N[b];
            }
        } else {
            E -= p->w * (p->b[0] * x[0] + p->b[1] * x[1] + p->b[2] * x[2]);
            if (ge)
                for (int a = 0; a < k; a++)
                    for (int c = 0; c < 3; c++) ge[3 * a + c] -= p->w * p->b[c] * N[a];
        }
    }
    return E;
}
