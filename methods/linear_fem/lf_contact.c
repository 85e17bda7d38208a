/* lf_contact.c — contact sample points of the triangle discretization
 * (docs/contact.md): its vertices (x_p = q_v, one term of weight 1), each
 * standing for a third of the reference area of its triangles (lumped).
 * per_side is not used: between vertices a piecewise-linear surface has no
 * further degrees of freedom to sample (assumption; edges and faces are not
 * tested against the obstacles). */
#include "lf.h"
#include "sb_contact_points.h"

#include <math.h>
#include <stdlib.h>

int lf_contact_points(void *state, int level, int per_side, sb_contact_points *cp)
{
    (void)per_side;
    const lf_state *S = state;
    const sb_mesh *m = &S->lv[level].mesh;
    double *area = calloc((size_t)m->nv, sizeof *area);
    if (!area) return SB_ERR_NOMEM;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        double a[3], b[3];
        for (int c = 0; c < 3; c++) {
            a[c] = m->X[3 * v[1] + c] - m->X[3 * v[0] + c];
            b[c] = m->X[3 * v[2] + c] - m->X[3 * v[0] + c];
        }
        double n[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
        double A = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) area[v[k]] += A / 3.0;
    }
    int rc = SB_OK;
    for (int v = 0; v < m->nv && !rc; v++) {
        const int dof = 3 * v;
        const double w = 1.0;
        rc = sb_contact_points_add(cp, 1, &dof, &w, area[v], m->st[2 * v], m->st[2 * v + 1]);
    }
    free(area);
    return rc;
}
