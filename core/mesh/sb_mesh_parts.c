/* sb_mesh_parts.c — the scene's boundary parts on a mesh: the vertices and
 * boundary edges of a named edge part, the vertex at a point part.  Tests
 * use the triangles' corner coordinates, so parts on either side of a seam
 * are found. */
#include "sb_mesh.h"
#include "sb_geometry.h"

#include <math.h>
#include <stdlib.h>

#define PART_TOL 1e-9

int sb_mesh_point_vertex(const sb_mesh *m, const sb_part *p)
{
    if (p->kind != SB_PART_POINT) return -1;
    for (int t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            const double *c = m->tri_st + 6 * t + 2 * k;
            if (sb_part_contains_st(p, c[0], c[1], PART_TOL)) return m->tri[3 * t + k];
        }
    return -1;
}

int sb_mesh_part_vertices(const sb_mesh *m, const sb_part *p, int *out)
{
    if (p->kind == SB_PART_POINT) {
        int v = sb_mesh_point_vertex(m, p);
        if (v < 0) return 0;
        if (out) out[0] = v;
        return 1;
    }
    unsigned char *on = calloc((size_t)m->nv + 1, 1);
    if (!on) return SB_ERR_NOMEM;
    for (int t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            const double *c = m->tri_st + 6 * t + 2 * k;
            if (sb_part_contains_st(p, c[0], c[1], PART_TOL)) on[m->tri[3 * t + k]] = 1;
        }
    int n = 0;
    for (int v = 0; v < m->nv; v++)
        if (on[v]) {
            if (out) out[n] = v;
            n++;
        }
    free(on);
    return n;
}

int sb_mesh_part_edges(const sb_mesh *m, const sb_part *p, int *out)
{
    if (p->kind != SB_PART_EDGE) return 0;
    int n = 0;
    for (int e = 0; e < m->ne; e++) {
        if (m->edge_t[2 * e + 1] >= 0) continue;
        const int t = m->edge_t[2 * e], k = m->edge_k[2 * e];
        const double *a = m->tri_st + 6 * t + 2 * ((k + 1) % 3), *b = m->tri_st + 6 * t + 2 * ((k + 2) % 3);
        if (!sb_part_contains_st(p, a[0], a[1], PART_TOL) || !sb_part_contains_st(p, b[0], b[1], PART_TOL)) continue;
        if (out) out[n] = e;
        n++;
    }
    return n;
}

void sb_mesh_lump_line_load(const sb_mesh *m, const int *edges, int ne, const double vec[3], double *b)
{
    for (int j = 0; j < ne; j++) {
        const int a = m->edge_v[2 * edges[j]], bb = m->edge_v[2 * edges[j] + 1];
        double ed[3];
        for (int c = 0; c < 3; c++) ed[c] = m->X[3 * bb + c] - m->X[3 * a + c];
        const double l = sqrt(ed[0] * ed[0] + ed[1] * ed[1] + ed[2] * ed[2]);
        for (int c = 0; c < 3; c++) {
            b[3 * a + c] += 0.5 * l * vec[c];
            b[3 * bb + c] += 0.5 * l * vec[c];
        }
    }
}
