/* cc_subdiv.c — one uniform Catmull–Clark step written out by the rules of
 * the RMTR paper: face points (5.12), edge points (5.13), vertex points (5.14)
 * inside the cage; on the cage boundary the curve rules of Appendix A:
 * edge midpoints (A.1) and the boundary vertex rule (A.2).
 *
 * Note on (A.2): written with the new midpoints e^{l+1} the printed formula
 * 0.125 e_I + 0.75 v + 0.125 e_{I+1} would not reproduce the cubic B-spline
 * boundary curve.  We implement the cubic B-spline rule of Fig. 11,
 * v^{l+1} = 3/4 v^l + 1/8 (w_I + w_{I+1}) with w the two coarse boundary
 * neighbours, i.e. 1/2 v^l + 1/4 (e_I^{l+1} + e_{I+1}^{l+1}); this is what
 * OpenSubdiv does with VTX_BOUNDARY_EDGE_ONLY (tests/test_cc_subdiv.c).
 * Only ghost faces touch the cage boundary and the outer ghost ring is
 * dropped after every step (§5.2.1), so these rules never reach the domain. */
#include "cc.h"

#include <stdlib.h>
#include <string.h>

/* child k of a face occupies quadrant (iu,iv) of the parent's (u,v) square */
void cc_child_offset(int k, int *iu, int *iv)
{
    static const int off[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
    *iu = off[k & 3][0];
    *iv = off[k & 3][1];
}

/* the other endpoint of edge d seen from v */
static int other_end(const cc_mesh *m, int d, int v)
{
    return m->ev[2 * d] == v ? m->ev[2 * d + 1] : m->ev[2 * d];
}

static int add_face_avg(cc_row *r, const cc_mesh *c, int f, double w)
{
    int st = 0;
    for (int k = 0; k < 4; k++) st |= cc_row_add(r, c->fv[4 * f + k], 0.25 * w);   /* (5.12) */
    return st ? SB_ERR_NOMEM : SB_OK;
}

static int vertex_row(const cc_mesh *c, int v, cc_row *r)
{
    int st = 0;
    if (c->bnd[v]) {
        /* boundary curve rule, Appendix A (A.2), see the note above */
        st |= cc_row_add(r, v, 0.75);
        for (int p = c->veo[v]; p < c->veo[v + 1]; p++) {
            int d = c->ve[p];
            if (c->ef[2 * d + 1] < 0) st |= cc_row_add(r, other_end(c, d, v), 0.125);
        }
        return st ? SB_ERR_NOMEM : SB_OK;
    }
    /* (5.14): (n-2)/n v + 1/n^2 sum e^l + 1/n^2 sum f^{l+1} */
    double n = c->val[v];
    st |= cc_row_add(r, v, (n - 2.0) / n);
    for (int p = c->veo[v]; p < c->veo[v + 1]; p++) st |= cc_row_add(r, other_end(c, c->ve[p], v), 1.0 / (n * n));
    for (int p = c->vfo[v]; p < c->vfo[v + 1]; p++) st |= add_face_avg(r, c, c->vf[p], 1.0 / (n * n));
    return st ? SB_ERR_NOMEM : SB_OK;
}

static int edge_row(const cc_mesh *c, int d, cc_row *r)
{
    int st = 0;
    if (c->ef[2 * d + 1] < 0) {
        /* (A.1): boundary edge midpoint */
        st |= cc_row_add(r, c->ev[2 * d], 0.5);
        st |= cc_row_add(r, c->ev[2 * d + 1], 0.5);
    } else {
        /* (5.13): (e^l + v^l + f_I^{l+1} + f_{I+1}^{l+1}) / 4 */
        st |= cc_row_add(r, c->ev[2 * d], 0.25);
        st |= cc_row_add(r, c->ev[2 * d + 1], 0.25);
        st |= add_face_avg(r, c, c->ef[2 * d], 0.25);
        st |= add_face_avg(r, c, c->ef[2 * d + 1], 0.25);
    }
    return st ? SB_ERR_NOMEM : SB_OK;
}

int cc_subdivide(const cc_mesh *c, cc_mesh *f, cc_csr *S, cc_err *e)
{
    int nv = c->nv, ne = c->ne, nf = c->nf;
    int nfv = nv + ne + nf;
    memset(S, 0, sizeof *S);
    int st = cc_mesh_alloc(f, nfv, 4 * nf, c->grid != NULL);
    if (st) return cc_fail(e, st, "cannot allocate the subdivided cage (%d vertices)", nfv);
    st = cc_csr_init(S, nfv, nv, 10L * nfv);
    if (st) {
        cc_mesh_free(f);
        return cc_fail(e, st, "cannot allocate the subdivision matrix");
    }
    cc_row r = { 0, 0, NULL, NULL };
    for (int i = 0; i < nfv && !st; i++) {
        r.n = 0;
        if (i < nv) st = vertex_row(c, i, &r);
        else if (i < nv + ne) st = edge_row(c, i - nv, &r);
        else st = add_face_avg(&r, c, i - nv - ne, 1.0);
        if (!st) st = cc_csr_row(S, i, r.n, r.c, r.v);
    }
    cc_row_free(&r);
    if (st) {
        cc_mesh_free(f);
        cc_csr_free(S);
        return cc_fail(e, st, "out of memory assembling the subdivision matrix");
    }
    /* children: corner k of face q -> fine face 4q+k, frame aligned with the parent */
    for (int q = 0; q < nf; q++) {
        int V[4], E[4], F = nv + ne + q;
        for (int k = 0; k < 4; k++) {
            V[k] = c->fv[4 * q + k];
            E[k] = nv + c->fe[4 * q + k];
        }
        const int ch[4][4] = { { V[0], E[0], F, E[3] }, { E[0], V[1], E[1], F },
                               { F, E[1], V[2], E[2] }, { E[3], F, E[2], V[3] } };
        for (int k = 0; k < 4; k++) {
            memcpy(f->fv + 4 * (4 * q + k), ch[k], sizeof ch[k]);
            f->dom[4 * q + k] = c->dom[q];
            if (c->cell) {
                int iu, iv;
                cc_child_offset(k, &iu, &iv);
                f->cell[2 * (4 * q + k)] = 2 * c->cell[2 * q] + iu;
                f->cell[2 * (4 * q + k) + 1] = 2 * c->cell[2 * q + 1] + iv;
            }
        }
    }
    cc_csr_apply(S, 2, c->st, f->st);
    if (c->grid) {
        for (int v = 0; v < nv; v++) {
            f->grid[2 * v] = 2 * c->grid[2 * v];
            f->grid[2 * v + 1] = 2 * c->grid[2 * v + 1];
        }
        for (int d = 0; d < ne; d++)
            for (int s = 0; s < 2; s++)
                f->grid[2 * (nv + d) + s] = c->grid[2 * c->ev[2 * d] + s] + c->grid[2 * c->ev[2 * d + 1] + s];
        for (int q = 0; q < nf; q++)
            for (int s = 0; s < 2; s++) {
                int sum = 0;
                for (int k = 0; k < 4; k++) sum += c->grid[2 * c->fv[4 * q + k] + s];
                f->grid[2 * (nv + ne + q) + s] = sum / 2;
            }
    }
    st = cc_mesh_topology(f, e);
    if (st) {
        cc_mesh_free(f);
        cc_csr_free(S);
    }
    return st;
}

int cc_keep_ring(const cc_mesh *full, cc_mesh *kept, int *vmap, cc_err *e)
{
    unsigned char *touch = calloc((size_t)full->nv, 1);
    int *faces = malloc((size_t)full->nf * sizeof *faces);
    if (!touch || !faces) {
        free(touch); free(faces);
        return cc_fail(e, SB_ERR_NOMEM, "out of memory dropping the outer ghost ring");
    }
    for (int q = 0; q < full->nf; q++)
        if (full->dom[q])
            for (int k = 0; k < 4; k++) touch[full->fv[4 * q + k]] = 1;
    int nk = 0;
    for (int q = 0; q < full->nf; q++) {
        int keep = 0;
        for (int k = 0; k < 4; k++) keep |= touch[full->fv[4 * q + k]];
        if (keep) faces[nk++] = q;
    }
    /* kept vertices in increasing full index (vertex points, edge points, face points) */
    for (int v = 0; v < full->nv; v++) vmap[v] = -1;
    for (int a = 0; a < nk; a++)
        for (int k = 0; k < 4; k++) vmap[full->fv[4 * faces[a] + k]] = 1;
    int nv = 0;
    for (int v = 0; v < full->nv; v++)
        if (vmap[v] > 0) vmap[v] = nv++;
    int st = nk ? cc_mesh_alloc(kept, nv, nk, full->grid != NULL) : SB_ERR_INPUT;
    if (st) {
        free(touch); free(faces);
        return cc_fail(e, st, nk ? "out of memory dropping the outer ghost ring" : "the cage has no domain face");
    }
    for (int a = 0; a < nk; a++) {
        int q = faces[a];
        for (int k = 0; k < 4; k++) kept->fv[4 * a + k] = vmap[full->fv[4 * q + k]];
        kept->dom[a] = full->dom[q];
        if (full->cell) {
            kept->cell[2 * a] = full->cell[2 * q];
            kept->cell[2 * a + 1] = full->cell[2 * q + 1];
        }
    }
    for (int v = 0; v < full->nv; v++) {
        int i = vmap[v];
        if (i < 0) continue;
        kept->st[2 * i] = full->st[2 * v];
        kept->st[2 * i + 1] = full->st[2 * v + 1];
        if (full->grid) {
            kept->grid[2 * i] = full->grid[2 * v];
            kept->grid[2 * i + 1] = full->grid[2 * v + 1];
        }
    }
    free(touch);
    free(faces);
    st = cc_mesh_topology(kept, e);
    if (st) cc_mesh_free(kept);
    return st;
}
