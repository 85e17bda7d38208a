/* lf_contact.c — contact sample points of the triangle discretization
 * (docs/contact.md): the n-fold barycentric subdivision points of the
 * level's mesh with lumped areas, shared with adaptive_sqrt3
 * (core/contact/sb_contact_mesh.c).
 * The surface between the points (self-contact): the n^2 sub-triangles of
 * every triangle, counter-clockwise like the triangle. */
#include "lf.h"
#include "sb_contact_mesh.h"

/* index of lattice point (i, j) (barycentric (n-i-j, i, j)/n) of triangle t
 * in the point numbering above: vertices, then n-1 points per edge from
 * edge_v[2e], then the interior points triangle by triangle */
static int lattice_index(const sb_mesh *m, int n, int t, int i, int j)
{
    const int *v = m->tri + 3 * t;
    if (i == 0 && j == 0) return v[0];
    if (i == n) return v[1];
    if (j == n) return v[2];
    int e, from, k;
    if (j == 0) { e = m->tri_edge[3 * t + 2]; from = v[0]; k = i; }            /* edge v0 -> v1 */
    else if (i + j == n) { e = m->tri_edge[3 * t]; from = v[1]; k = j; }       /* edge v1 -> v2 */
    else if (i == 0) { e = m->tri_edge[3 * t + 1]; from = v[2]; k = n - j; }   /* edge v2 -> v0 */
    else {
        int q = 0;   /* interior, in the order of the loop in lf_contact_points */
        for (int a = 1; a < i; a++) q += n - 1 - a;
        q += j - 1;
        return m->nv + m->ne * (n - 1) + t * ((n - 1) * (n - 2) / 2) + q;
    }
    const int pos = m->edge_v[2 * e] == from ? k : n - k;
    return m->nv + e * (n - 1) + pos - 1;
}

static int lf_sub_triangles(const sb_mesh *m, int n, sb_contact_points *cp)
{
    for (int t = 0; t < m->nt; t++)
        for (int i = 0; i < n; i++)
            for (int j = 0; i + j < n; j++) {
                int rc = sb_contact_points_add_tri(cp, lattice_index(m, n, t, i, j), lattice_index(m, n, t, i + 1, j),
                                                   lattice_index(m, n, t, i, j + 1));
                if (!rc && i + j < n - 1)
                    rc = sb_contact_points_add_tri(cp, lattice_index(m, n, t, i + 1, j),
                                                   lattice_index(m, n, t, i + 1, j + 1),
                                                   lattice_index(m, n, t, i, j + 1));
                if (rc) return rc;
            }
    return SB_OK;
}

int lf_contact_points(void *state, int level, int per_side, sb_contact_points *cp)
{
    const lf_state *S = state;
    const sb_mesh *m = &S->lv[level].mesh;
    const int n = per_side > 0 ? per_side : 1;
    int rc = sb_contact_points_mesh(m, per_side, cp);
    if (!rc) rc = lf_sub_triangles(m, n, cp);
    return rc;
}
