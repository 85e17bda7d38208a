/* cc_hier.c — the nested level hierarchy T^0 ⊂ T^1 ⊂ ... (RMTR paper
 * (5.7), §5.2.1): subdivide the whole cage (ghost ring included), then drop
 * the outer layer of ghost faces, so every level keeps exactly one ghost ring.
 * S_l^{l+1} is the subdivision matrix restricted to the kept fine vertices.
 * Also the C side of the OpenSubdiv shim (S in cc_subdivide's ordering). */
#include "cc.h"
#include "cc_osd_shim.h"

#include <stdlib.h>
#include <string.h>

static int find_edge(const cc_mesh *m, int a, int b)
{
    for (int p = m->veo[a]; p < m->veo[a + 1]; p++) {
        int d = m->ve[p];
        if ((m->ev[2 * d] == a && m->ev[2 * d + 1] == b) || (m->ev[2 * d] == b && m->ev[2 * d + 1] == a))
            return d;
    }
    return -1;
}

int cc_osd_subdiv_matrix(const cc_mesh *c, cc_csr *S, cc_err *e)
{
    int n1 = 0, *kind, *pa, *pb, *rp, *ci;
    double *w;
    char msg[200] = "";
    memset(S, 0, sizeof *S);
    int st = cc_osd_refine(c->nv, c->nf, c->fv, &n1, &kind, &pa, &pb, &rp, &ci, &w, msg, sizeof msg);
    if (st) {
        free(kind); free(pa); free(pb); free(rp); free(ci); free(w);
        return cc_fail(e, SB_ERR_INTERNAL, "%s", msg);
    }
    int nfine = c->nv + c->ne + c->nf;
    int *row_of = malloc((size_t)nfine * sizeof *row_of);   /* cc index -> osd index */
    st = (!row_of || n1 != nfine) ? SB_ERR_INTERNAL : SB_OK;
    if (!st) {
        for (int i = 0; i < nfine; i++) row_of[i] = -1;
        for (int i = 0; i < n1 && !st; i++) {
            int r = -1;
            if (kind[i] == 0) r = pa[i];
            else if (kind[i] == 2) r = c->nv + c->ne + pa[i];
            else {
                int d = find_edge(c, pa[i], pb[i]);
                r = d < 0 ? -1 : c->nv + d;
            }
            if (r < 0 || r >= nfine || row_of[r] >= 0) st = SB_ERR_INTERNAL;
            else row_of[r] = i;
        }
    }
    if (!st) st = cc_csr_init(S, nfine, c->nv, (long)rp[n1]);
    for (int r = 0; r < nfine && !st; r++) {
        int i = row_of[r];
        st = cc_csr_row(S, r, rp[i + 1] - rp[i], ci + rp[i], w + rp[i]);
    }
    free(row_of);
    free(kind); free(pa); free(pb); free(rp); free(ci); free(w);
    if (st) {
        cc_csr_free(S);
        return cc_fail(e, st, "OpenSubdiv refinement does not match the cage (%d vs %d fine vertices)", n1, nfine);
    }
    return SB_OK;
}

int cc_osd_limit_dense(const cc_mesh *m, int np, const int *face, const double *uv, double *W, cc_err *e)
{
    char msg[200] = "";
    if (cc_osd_limit(m->nv, m->nf, m->fv, np, face, uv, 10, W, msg, sizeof msg))
        return cc_fail(e, SB_ERR_INTERNAL, "%s", msg);
    return SB_OK;
}

void cc_hier_free(cc_hier *h)
{
    for (int l = 0; l < CC_MAX_LEVELS; l++) {
        cc_mesh_free(&h->mesh[l]);
        cc_csr_free(&h->S[l]);
        free(h->vmap[l]);
    }
    memset(h, 0, sizeof *h);
}

int cc_hier_build(cc_hier *h, cc_mesh *coarse, int nlev, int use_osd, cc_err *e)
{
    memset(h, 0, sizeof *h);
    h->mesh[0] = *coarse;
    memset(coarse, 0, sizeof *coarse);
    h->nlev = 1;
    if (nlev < 1 || nlev > CC_MAX_LEVELS) {
        cc_hier_free(h);
        return cc_fail(e, SB_ERR_INPUT, "levels = %d outside [1, %d]", nlev, CC_MAX_LEVELS);
    }
    for (int l = 0; l + 1 < nlev; l++) {
        cc_mesh full;
        cc_csr S;
        int st = cc_subdivide(&h->mesh[l], &full, &S, e);
        if (st) {
            cc_hier_free(h);
            return st;
        }
        if (use_osd) {
            cc_csr So;
            st = cc_osd_subdiv_matrix(&h->mesh[l], &So, e);
            cc_csr_free(&S);
            S = So;
        }
        int *vmap = malloc((size_t)full.nv * sizeof *vmap);
        int *rows = malloc((size_t)full.nv * sizeof *rows);
        if (!st && (!vmap || !rows)) st = cc_fail(e, SB_ERR_NOMEM, "out of memory building level %d", l + 1);
        if (!st) st = cc_keep_ring(&full, &h->mesh[l + 1], vmap, e);
        if (!st) {
            for (int v = 0; v < full.nv; v++)
                if (vmap[v] >= 0) rows[vmap[v]] = v;
            st = cc_csr_select_rows(&S, h->mesh[l + 1].nv, rows, &h->S[l]);
            if (st) cc_fail(e, st, "out of memory building S at level %d", l);
        }
        free(rows);
        cc_mesh_free(&full);
        cc_csr_free(&S);
        h->vmap[l] = vmap;
        h->nlev = l + 2;
        if (st) {
            cc_hier_free(h);
            return st;
        }
    }
    return SB_OK;
}
