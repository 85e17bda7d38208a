/* cc_quad.c — quadrature tables of one level (RMTR paper §6: "we compute
 * basis functions and their derivatives at quadrature points ... only for one
 * ordinary face and each type of extraordinary face").  Elements are the
 * domain faces of the cage (ghost faces carry no integration, §5.2.1).
 * Quadrature: ng x ng Gauss–Legendre points on the face's (u,v) square (the
 * paper does not state its rule; ng is the method parameter "gauss"). */
#include "cc_method.h"

#include <stdlib.h>
#include <string.h>

static int add_cfg(cc_quad *Q, int k, int nfv, const int *fv)
{
    if (Q->ncfg == Q->capcfg) {
        int cap = Q->capcfg ? 2 * Q->capcfg : 4;
        cc_cfg *c = realloc(Q->cfg, (size_t)cap * sizeof *c);
        if (!c) return -1;
        Q->cfg = c;
        Q->capcfg = cap;
    }
    cc_cfg *c = &Q->cfg[Q->ncfg];
    memset(c, 0, sizeof *c);
    c->k = k;
    c->nfv = nfv;
    c->tab = malloc((size_t)Q->nq * 6 * k * sizeof *c->tab);
    if (nfv) {
        c->fv = malloc((size_t)nfv * sizeof *c->fv);
        if (c->fv) memcpy(c->fv, fv, (size_t)nfv * sizeof *fv);
    }
    if (!c->tab || (nfv && !c->fv)) {
        free(c->tab);
        free(c->fv);
        return -1;
    }
    return Q->ncfg++;
}

void cc_quad_free(cc_quad *Q)
{
    for (int c = 0; c < Q->ncfg; c++) {
        free(Q->cfg[c].tab);
        free(Q->cfg[c].fv);
    }
    free(Q->cfg);
    free(Q->face);
    free(Q->ecfg);
    free(Q->eoff);
    free(Q->enode);
    memset(Q, 0, sizeof *Q);
}

int cc_quad_build(cc_quad *Q, const cc_mesh *m, int ng, cc_err *e)
{
    memset(Q, 0, sizeof *Q);
    double x[8], w[8];
    if (ng < 1 || ng > 8 || sb_gauss_legendre(ng, x, w) != SB_OK)
        return cc_fail(e, SB_ERR_INPUT, "gauss = %d points per direction is outside [1, 8]", ng);
    Q->ng = ng;
    Q->nq = ng * ng;
    for (int a = 0; a < ng; a++) {
        Q->gp[a] = 0.5 * (1.0 + x[a]);          /* [-1,1] -> [0,1] */
        Q->gw[a] = 0.5 * w[a];
    }
    for (int f = 0; f < m->nf; f++) Q->ne += m->dom[f];
    long cap = 16L * Q->ne + 64;
    Q->face = malloc((size_t)Q->ne * sizeof *Q->face);
    Q->ecfg = malloc((size_t)Q->ne * sizeof *Q->ecfg);
    Q->eoff = malloc(((size_t)Q->ne + 1) * sizeof *Q->eoff);
    Q->enode = malloc((size_t)cap * sizeof *Q->enode);
    int st = (!Q->face || !Q->ecfg || !Q->eoff || !Q->enode || add_cfg(Q, 16, 0, NULL) != 0) ? SB_ERR_NOMEM : SB_OK;
    /* configuration 0: the regular bicubic B-spline patch */
    for (int q = 0; q < Q->nq && !st; q++) {
        double P[6][16];
        cc_bspline_patch(Q->gp[q % ng], Q->gp[q / ng], P);
        for (int r = 0; r < 6; r++) memcpy(Q->cfg[0].tab + (size_t)(6 * q + r) * 16, P[r], sizeof P[r]);
    }
    double *W = malloc((size_t)6 * CC_MAX_BASIS * sizeof *W);
    if (!W) st = SB_ERR_NOMEM;
    int ie = 0;
    Q->eoff[0] = 0;
    for (int f = 0; f < m->nf && !st; f++) {
        if (!m->dom[f]) continue;
        int nodes[CC_MAX_BASIS], k = 16, c = 0;
        if (cc_face_regular(m, f)) {
            st = cc_face_gather16(m, f, nodes);
        } else {
            cc_mesh L;
            st = cc_face_local(m, f, &L, nodes, CC_MAX_BASIS, e);
            if (st) break;
            k = L.nv;
            /* same canonical local cage = same tables */
            for (c = 1; c < Q->ncfg; c++)
                if (Q->cfg[c].k == k && Q->cfg[c].nfv == 4 * L.nf &&
                    memcmp(Q->cfg[c].fv, L.fv, (size_t)4 * L.nf * sizeof *L.fv) == 0) break;
            if (c == Q->ncfg) {
                c = add_cfg(Q, k, 4 * L.nf, L.fv);
                if (c < 0) st = SB_ERR_NOMEM;
                for (int q = 0; q < Q->nq && !st; q++) {
                    st = cc_local_basis(&L, Q->gp[q % ng], Q->gp[q / ng], W, e);
                    if (!st) memcpy(Q->cfg[c].tab + (size_t)6 * q * k, W, (size_t)6 * k * sizeof *W);
                }
            }
            cc_mesh_free(&L);
        }
        if (st) break;
        if (Q->eoff[ie] + k > cap) {
            cap = 2 * cap + k;
            int *p = realloc(Q->enode, (size_t)cap * sizeof *p);
            if (!p) {
                st = SB_ERR_NOMEM;
                break;
            }
            Q->enode = p;
        }
        memcpy(Q->enode + Q->eoff[ie], nodes, (size_t)k * sizeof *nodes);
        Q->face[ie] = f;
        Q->ecfg[ie] = c;
        Q->eoff[ie + 1] = Q->eoff[ie] + k;
        ie++;
    }
    free(W);
    if (st) {
        if (st == SB_ERR_NOMEM) cc_fail(e, st, "out of memory building quadrature tables");
        cc_quad_free(Q);
    }
    return st;
}

sb_shell_basis cc_quad_basis(const cc_quad *Q, int e, int q)
{
    const cc_cfg *c = &Q->cfg[Q->ecfg[e]];
    const double *t = c->tab + (size_t)6 * q * c->k;
    sb_shell_basis b = { c->k, t, t + c->k, t + 2 * c->k, t + 3 * c->k, t + 4 * c->k, t + 5 * c->k };
    return b;
}
