/* cc_mesh.c — quad control cages: storage, edge/adjacency construction,
 * sub-cage extraction.  Topology is built once per cage (set-up only). */
#include "cc.h"

#include <stdlib.h>
#include <string.h>

int cc_mesh_alloc(cc_mesh *m, int nv, int nf, int structured)
{
    memset(m, 0, sizeof *m);
    if (nv <= 0 || nf <= 0) return SB_ERR_INPUT;
    m->nv = nv;
    m->nf = nf;
    m->fv = calloc((size_t)4 * nf, sizeof *m->fv);
    m->dom = calloc((size_t)nf, 1);
    m->st = calloc((size_t)2 * nv, sizeof *m->st);
    if (structured) {
        m->grid = calloc((size_t)2 * nv, sizeof *m->grid);
        m->cell = calloc((size_t)2 * nf, sizeof *m->cell);
    }
    if (!m->fv || !m->dom || !m->st || (structured && (!m->grid || !m->cell))) {
        cc_mesh_free(m);
        return SB_ERR_NOMEM;
    }
    return SB_OK;
}

void cc_mesh_free(cc_mesh *m)
{
    free(m->fv); free(m->dom); free(m->st); free(m->grid); free(m->cell);
    free(m->fe); free(m->ev); free(m->ef); free(m->efk);
    free(m->val); free(m->bnd);
    free(m->vfo); free(m->vf); free(m->veo); free(m->ve);
    memset(m, 0, sizeof *m);
}

typedef struct half { int a, b, f, k; } half;

static int half_cmp(const void *x, const void *y)
{
    const half *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return (p->f > q->f) - (p->f < q->f);
}

int cc_mesh_topology(cc_mesh *m, cc_err *e)
{
    int nv = m->nv, nf = m->nf, nh = 4 * nf;
    for (int i = 0; i < nh; i++)
        if (m->fv[i] < 0 || m->fv[i] >= nv)
            return cc_fail(e, SB_ERR_INPUT, "cage face %d has vertex index %d outside [0,%d)", i / 4, m->fv[i], nv);
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 4; k++)
            for (int j = k + 1; j < 4; j++)
                if (m->fv[4 * f + k] == m->fv[4 * f + j])
                    return cc_fail(e, SB_ERR_INPUT, "cage face %d repeats vertex %d", f, m->fv[4 * f + k]);
    half *h = malloc((size_t)nh * sizeof *h);
    m->fe = malloc((size_t)nh * sizeof *m->fe);
    m->ev = malloc((size_t)2 * nh * sizeof *m->ev);
    m->ef = malloc((size_t)2 * nh * sizeof *m->ef);
    m->efk = malloc((size_t)2 * nh * sizeof *m->efk);
    m->val = calloc((size_t)nv, sizeof *m->val);
    m->bnd = calloc((size_t)nv, 1);
    m->vfo = calloc((size_t)nv + 1, sizeof *m->vfo);
    m->vf = malloc((size_t)nh * sizeof *m->vf);
    m->veo = calloc((size_t)nv + 1, sizeof *m->veo);
    int *nbe = calloc((size_t)nv, sizeof *nbe);
    if (!h || !m->fe || !m->ev || !m->ef || !m->efk || !m->val || !m->bnd || !m->vfo || !m->vf ||
        !m->veo || !nbe) {
        free(h); free(nbe);
        return cc_fail(e, SB_ERR_NOMEM, "out of memory building cage topology");
    }
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 4; k++) {
            int a = m->fv[4 * f + k], b = m->fv[4 * f + (k + 1) % 4];
            h[4 * f + k] = (half){ a < b ? a : b, a < b ? b : a, f, k };
        }
    qsort(h, (size_t)nh, sizeof *h, half_cmp);
    int ne = 0, st = SB_OK;
    for (int i = 0; i < nh && !st;) {
        int j = i + 1;
        while (j < nh && h[j].a == h[i].a && h[j].b == h[i].b) j++;
        if (j - i > 2) {
            st = cc_fail(e, SB_ERR_INPUT, "cage edge (%d,%d) is shared by %d faces (non-manifold)", h[i].a, h[i].b, j - i);
            break;
        }
        m->ev[2 * ne] = m->fv[4 * h[i].f + h[i].k];
        m->ev[2 * ne + 1] = m->fv[4 * h[i].f + (h[i].k + 1) % 4];
        m->ef[2 * ne] = h[i].f;
        m->efk[2 * ne] = h[i].k;
        m->fe[4 * h[i].f + h[i].k] = ne;
        if (j - i == 2) {
            int f2 = h[i + 1].f, k2 = h[i + 1].k;
            if (m->fv[4 * f2 + k2] != m->ev[2 * ne + 1]) {
                st = cc_fail(e, SB_ERR_INPUT, "cage faces %d and %d are inconsistently oriented", h[i].f, f2);
                break;
            }
            m->ef[2 * ne + 1] = f2;
            m->efk[2 * ne + 1] = k2;
            m->fe[4 * f2 + k2] = ne;
        } else {
            m->ef[2 * ne + 1] = -1;
            m->efk[2 * ne + 1] = -1;
            nbe[h[i].a]++;
            nbe[h[i].b]++;
        }
        m->val[h[i].a]++;
        m->val[h[i].b]++;
        ne++;
        i = j;
    }
    free(h);
    m->ne = ne;
    for (int v = 0; v < nv && !st; v++) {
        if (m->val[v] == 0) st = cc_fail(e, SB_ERR_INPUT, "cage vertex %d belongs to no face", v);
        else if (nbe[v] != 0 && nbe[v] != 2)
            st = cc_fail(e, SB_ERR_INPUT, "cage vertex %d has %d boundary edges (non-manifold vertex)", v, nbe[v]);
        m->bnd[v] = nbe[v] ? 1 : 0;
    }
    free(nbe);
    if (st) return st;
    /* vertex -> faces and vertex -> edges (CSR) */
    for (int i = 0; i < nh; i++) m->vfo[m->fv[i] + 1]++;
    for (int v = 0; v < nv; v++) m->vfo[v + 1] += m->vfo[v];
    m->ve = malloc((size_t)2 * ne * sizeof *m->ve);
    int *fill = calloc((size_t)nv, sizeof *fill);
    if (!m->ve || !fill) {
        free(fill);
        return cc_fail(e, SB_ERR_NOMEM, "out of memory building cage topology");
    }
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 4; k++) {
            int v = m->fv[4 * f + k];
            m->vf[m->vfo[v] + fill[v]++] = f;
        }
    for (int v = 0; v < nv; v++) m->veo[v + 1] = m->veo[v] + m->val[v];
    memset(fill, 0, (size_t)nv * sizeof *fill);
    for (int d = 0; d < ne; d++)
        for (int s = 0; s < 2; s++) {
            int v = m->ev[2 * d + s];
            m->ve[m->veo[v] + fill[v]++] = d;
        }
    free(fill);
    return SB_OK;
}

int cc_face_corner(const cc_mesh *m, int f, int v)
{
    for (int k = 0; k < 4; k++)
        if (m->fv[4 * f + k] == v) return k;
    return -1;
}

int cc_mesh_extract(const cc_mesh *m, int n, const int *faces, cc_mesh *out, int *vmap, int *inv, cc_err *e)
{
    int *map = vmap ? vmap : malloc((size_t)m->nv * sizeof *map);
    int *old = malloc((size_t)4 * n * sizeof *old);
    if (!map || !old) {
        if (!vmap) free(map);
        free(old);
        return cc_fail(e, SB_ERR_NOMEM, "out of memory extracting a sub-cage");
    }
    for (int v = 0; v < m->nv; v++) map[v] = -1;
    int nv = 0;
    for (int a = 0; a < n; a++)
        for (int k = 0; k < 4; k++) {
            int v = m->fv[4 * faces[a] + k];
            if (map[v] < 0) {
                map[v] = nv;
                old[nv++] = v;
            }
        }
    int st = cc_mesh_alloc(out, nv, n, m->grid != NULL);
    if (!st) {
        for (int a = 0; a < n; a++) {
            int f = faces[a];
            for (int k = 0; k < 4; k++) out->fv[4 * a + k] = map[m->fv[4 * f + k]];
            out->dom[a] = m->dom[f];
            if (m->cell) {
                out->cell[2 * a] = m->cell[2 * f];
                out->cell[2 * a + 1] = m->cell[2 * f + 1];
            }
        }
        for (int i = 0; i < nv; i++) {
            out->st[2 * i] = m->st[2 * old[i]];
            out->st[2 * i + 1] = m->st[2 * old[i] + 1];
            if (m->grid) {
                out->grid[2 * i] = m->grid[2 * old[i]];
                out->grid[2 * i + 1] = m->grid[2 * old[i] + 1];
            }
        }
        st = cc_mesh_topology(out, e);
    } else {
        cc_fail(e, st, "cannot allocate a sub-cage of %d faces", n);
    }
    if (inv && !st) memcpy(inv, old, (size_t)nv * sizeof *old);
    if (!vmap) free(map);
    free(old);
    if (st) cc_mesh_free(out);
    return st;
}
