/* sb_contact_mesh.c — contact sample points of a triangle mesh
 * (docs/contact.md; sb_contact_mesh.h): the points of the n-fold barycentric
 * subdivision of every triangle (n = per_side), each a linear combination of
 * at most the three vertices of one triangle, x_p = sum_k lambda_k q_v(k): the
 * vertices (one term), n - 1 points on each edge (two terms, owned by the
 * edge) and the (n - 1)(n - 2)/2 interior points of each triangle (three
 * terms).  per_side = 1 gives the vertices alone.  Areas: the lumped areas of
 * the sub-triangulation (each sub-triangle of area A/n^2 gives a third to each
 * of its corners: interior points 2A/n^2, edge points A/n^2 per adjacent
 * triangle, vertices A/(3 n^2) per adjacent triangle), so they sum to the
 * reference area.  Used by linear_fem and adaptive_sqrt3 (whose mesh, and so
 * whose points, change with every adaptation). */
#include "sb_contact_mesh.h"
#include "sb_common.h"

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

int sb_contact_points_mesh(const sb_mesh *m, int per_side, sb_contact_points *cp)
{
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
    return rc;
}
