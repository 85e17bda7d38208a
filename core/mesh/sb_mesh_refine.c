/* sb_mesh_refine.c — nested 1-to-4 refinement (sb_mesh.h): every triangle is
 * split at its edge midpoints (taken in the triangle's own corner (s,t), so
 * seams refine correctly), the new vertices get their reference positions
 * from the chart, and the map coarse -> fine is kept for transfer operators.
 * In the grid parameter the fine mesh tiles every coarse triangle exactly, so
 * piecewise-linear functions of the coarse mesh are piecewise linear on the
 * fine mesh (nested spaces). */
#include "sb_mesh.h"

#include <stdlib.h>
#include <string.h>

void sb_mesh_refinement_free(sb_mesh_refinement *r)
{
    free(r->edge_half);
    free(r->edge_parent);
    free(r->edge_tri);
    free(r->edge_corner);
    memset(r, 0, sizeof *r);
}

int sb_mesh_refine4(const sb_mesh *c, const sb_scene *sc, sb_mesh *f, sb_mesh_refinement *r)
{
    sb_mesh_init(f);
    memset(r, 0, sizeof *r);
    const int nvc = c->nv, nec = c->ne, ntc = c->nt;
    int rc = sb_mesh_reserve(f, nvc + nec, 4 * ntc, 0);
    if (rc) return rc;
    f->nv = nvc + nec;
    f->nt = 4 * ntc;
    f->slit = c->slit;
    memcpy(f->st, c->st, sizeof(double) * 2 * (size_t)nvc);
    memcpy(f->vgen, c->vgen, sizeof(int) * (size_t)nvc);
    for (int v = 0; v < nvc; v++) f->vflag[v] = c->vflag[v] & (SB_MESH_V_PINNED | SB_MESH_V_SEAM);
    for (int e = 0; e < nec; e++) {
        const int v = nvc + e;
        int g = 0;
        f->vflag[v] = 0;
        for (int j = 0; j < 2; j++) {
            const int t = c->edge_t[2 * e + j];
            if (t < 0) continue;
            const int k = c->edge_k[2 * e + j];
            const double *a = c->tri_st + 6 * t + 2 * ((k + 1) % 3), *b = c->tri_st + 6 * t + 2 * ((k + 2) % 3);
            const double ms = 0.5 * (a[0] + b[0]), mt = 0.5 * (a[1] + b[1]);
            if (j == 0) {
                f->st[2 * v] = ms;
                f->st[2 * v + 1] = mt;
            } else if (ms != f->st[2 * v] || mt != f->st[2 * v + 1]) {
                f->vflag[v] |= SB_MESH_V_SEAM | SB_MESH_V_PINNED;
            }
            if (c->tgen[t] + 1 > g) g = c->tgen[t] + 1;
        }
        f->vgen[v] = g;
    }
    sb_mesh_set_geometry(f, sc);
    for (int t = 0; t < ntc; t++) {
        const int *v = c->tri + 3 * t;
        const double *p = c->tri_st + 6 * t;
        const int m[3] = { nvc + c->tri_edge[3 * t], nvc + c->tri_edge[3 * t + 1], nvc + c->tri_edge[3 * t + 2] };
        double pm[3][2];
        for (int i = 0; i < 3; i++) {
            const double *a = p + 2 * ((i + 1) % 3), *b = p + 2 * ((i + 2) % 3);
            pm[i][0] = 0.5 * (a[0] + b[0]);
            pm[i][1] = 0.5 * (a[1] + b[1]);
        }
        /* children (v0,m2,m1), (m2,v1,m0), (m1,m0,v2), (m0,m1,m2) */
        const int cv[4][3] = { { v[0], m[2], m[1] }, { m[2], v[1], m[0] }, { m[1], m[0], v[2] }, { m[0], m[1], m[2] } };
        const double *cp[4][3] = { { p, pm[2], pm[1] }, { pm[2], p + 2, pm[0] }, { pm[1], pm[0], p + 4 },
                                   { pm[0], pm[1], pm[2] } };
        for (int ch = 0; ch < 4; ch++) {
            const int tf = 4 * t + ch;
            for (int k = 0; k < 3; k++) {
                f->tri[3 * tf + k] = cv[ch][k];
                f->tri_st[6 * tf + 2 * k] = cp[ch][k][0];
                f->tri_st[6 * tf + 2 * k + 1] = cp[ch][k][1];
            }
            f->tgen[tf] = c->tgen[t] + 1;
        }
    }
    if ((rc = sb_mesh_build_edges(f))) { sb_mesh_free(f); return rc == SB_ERR_INPUT ? SB_ERR_INTERNAL : rc; }
    sb_mesh_tag_boundary(f, sc);
    r->nv_c = nvc;
    r->ne_c = nec;
    r->nt_c = ntc;
    r->edge_half = malloc(sizeof(int) * 2 * (size_t)nec);
    r->edge_parent = malloc(sizeof(int) * (size_t)f->ne);
    r->edge_tri = malloc(sizeof(int) * (size_t)f->ne);
    r->edge_corner = malloc(sizeof(int) * (size_t)f->ne);
    if (!r->edge_half || !r->edge_parent || !r->edge_tri || !r->edge_corner) {
        sb_mesh_refinement_free(r);
        sb_mesh_free(f);
        return SB_ERR_NOMEM;
    }
    for (int e = 0; e < f->ne; e++) {
        int a = f->edge_v[2 * e], b = f->edge_v[2 * e + 1];
        r->edge_parent[e] = r->edge_tri[e] = r->edge_corner[e] = -1;
        if (a >= nvc && b >= nvc) {
            /* joins the midpoints of two edges of the coarse triangle: parallel to the third */
            const int tc = f->edge_t[2 * e] / 4;
            int jm = -1, km = -1;
            for (int i = 0; i < 3; i++) {
                if (c->tri_edge[3 * tc + i] == a - nvc) jm = i;
                if (c->tri_edge[3 * tc + i] == b - nvc) km = i;
            }
            r->edge_tri[e] = tc;
            r->edge_corner[e] = (jm >= 0 && km >= 0) ? 3 - jm - km : -1;
            continue;
        }
        const int vo = a < nvc ? a : b, ce = (a < nvc ? b : a) - nvc;
        r->edge_parent[e] = ce;
        r->edge_half[2 * ce + (c->edge_v[2 * ce] == vo ? 0 : 1)] = e;
    }
    return SB_OK;
}
