/* lf_contact.c — contact sample points of the triangle discretization
 * (docs/contact.md): the points of the n-fold barycentric subdivision of
 * every triangle (n = per_side), each a linear combination of at most the
 * three vertices of one triangle, x_p = sum_k lambda_k q_v(k): the vertices
 * (one term), n - 1 points on each edge (two terms, owned by the edge) and
 * the (n - 1)(n - 2)/2 interior points of each triangle (three terms).
 * per_side = 1 gives the vertices alone.  Areas: the lumped areas of the
 * sub-triangulation (each sub-triangle of area A/n^2 gives a third to each of
 * its corners: interior points 2A/n^2, edge points A/n^2 per adjacent
 * triangle, vertices A/(3 n^2) per adjacent triangle), so they sum to the
 * reference area.  The surface between the points (self-contact): the n^2
 * sub-triangles of every triangle, counter-clockwise like the triangle. */
#include "lf.h"
#include "sb_contact_points.h"

#include <math.h>
#include <stdlib.h>

static double tri_area(const sb_mesh *m, int t)
{
    const int *v = m->tri + 3 * t;
    double a[3], b[3];
    for (int c = 0; c < 3; c++) {
        a[c] = m->X[3 * v[1] + c] - m->X[3 * v[0] + c];
        b[c] = m->X[3 * v[2] + c] - m->X[3 * v[0] + c];
    }
    double n[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

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
    const double n2 = (double)n * n;
    double *area = calloc((size_t)m->nv, sizeof *area);
    if (!area) return SB_ERR_NOMEM;
    for (int t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) area[m->tri[3 * t + k]] += tri_area(m, t) / (3.0 * n2);
    int rc = SB_OK;
    /* vertices */
    for (int v = 0; v < m->nv && !rc; v++) {
        const int dof = 3 * v;
        const double w = 1.0;
        rc = sb_contact_points_add(cp, 1, &dof, &w, area[v], m->st[2 * v], m->st[2 * v + 1]);
    }
    free(area);
    /* edge points, owned by the edge */
    for (int e = 0; e < m->ne && !rc && n > 1; e++) {
        const int a = m->edge_v[2 * e], b = m->edge_v[2 * e + 1];
        double A = 0;
        for (int s = 0; s < 2; s++)
            if (m->edge_t[2 * e + s] >= 0) A += tri_area(m, m->edge_t[2 * e + s]);
        for (int i = 1; i < n && !rc; i++) {
            const double u = (double)i / n;
            const int dof[2] = { 3 * a, 3 * b };
            const double w[2] = { 1 - u, u };
            rc = sb_contact_points_add(cp, 2, dof, w, A / n2, (1 - u) * m->st[2 * a] + u * m->st[2 * b],
                                       (1 - u) * m->st[2 * a + 1] + u * m->st[2 * b + 1]);
        }
    }
    /* interior points */
    for (int t = 0; t < m->nt && !rc && n > 2; t++) {
        const int *v = m->tri + 3 * t;
        const double A = tri_area(m, t);
        for (int i = 1; i < n && !rc; i++)
            for (int j = 1; i + j < n && !rc; j++) {
                const double l1 = (double)i / n, l2 = (double)j / n, l0 = 1 - l1 - l2;
                const int dof[3] = { 3 * v[0], 3 * v[1], 3 * v[2] };
                const double w[3] = { l0, l1, l2 };
                rc = sb_contact_points_add(cp, 3, dof, w, 2 * A / n2,
                                           l0 * m->st[2 * v[0]] + l1 * m->st[2 * v[1]] + l2 * m->st[2 * v[2]],
                                           l0 * m->st[2 * v[0] + 1] + l1 * m->st[2 * v[1] + 1] + l2 * m->st[2 * v[2] + 1]);
            }
    }
    if (!rc) rc = lf_sub_triangles(m, n, cp);
    return rc;
}
