/* cc_contact.c — contact sample points of the subdivision discretization
 * (docs/contact.md): a uniform grid of (n per_side + 1)^2 points in the grid
 * parameter (s,t) (n elements per side on the level), each expressed through
 * the limit basis of the face that contains it, x = sum_I N_I q_I (exact,
 * RMTR paper §5.2, cc_face_basis): the barrier's chain rule runs through
 * these weights.  Area per point: |x_u x x_v| / per_side^2 at the reference
 * control points (a midpoint-like rule; boundary points get a full cell's
 * share — assumption).  The surface between the points (self-contact):
 * each grid cell whose four corners are points, cut into two triangles
 * along alternating diagonals. */
#include "cc.h"
#include "cc_method.h"
#include "sb_contact_points.h"

#include <math.h>
#include <stdlib.h>

int cc_contact_points(void *state, int level, int per_side, sb_contact_points *cp)
{
    const cc_state *S = state;
    const cc_level *L = &S->lv[level];
    const int ns = (S->n_coarse << level) * per_side, nt = (S->nt_coarse << level) * per_side;
    int idx[CC_MAX_BASIS], dof[CC_MAX_BASIS], k, f;
    double W[6 * CC_MAX_BASIS], w[CC_MAX_BASIS], u, v;
    cc_err e = { "" };
    int *map = malloc((size_t)(ns + 1) * (nt + 1) * sizeof *map);
    if (!map) return SB_ERR_NOMEM;
    for (int j = 0; j <= nt; j++)
        for (int i = 0; i <= ns; i++) {
            const double s = (double)i / ns, t = (double)j / nt;
            map[j * (ns + 1) + i] = -1;
            if (cc_level_locate(L, s, t, &f, &u, &v)) continue;   /* outside an L-shaped domain */
            int rc = cc_face_basis(L->mesh, f, u, v, &k, idx, W, CC_MAX_BASIS, &e);
            if (rc) { free(map); return cc_state_fail(S, rc, "%s", e.msg); }
            map[j * (ns + 1) + i] = cp->n;
            double xu[3] = { 0, 0, 0 }, xv[3] = { 0, 0, 0 };
            int m = 0;
            for (int a = 0; a < k; a++) {
                for (int c = 0; c < 3; c++) {
                    xu[c] += W[k + a] * L->X[3 * idx[a] + c];
                    xv[c] += W[2 * k + a] * L->X[3 * idx[a] + c];
                }
                if (W[a] == 0.0) continue;
                dof[m] = 3 * idx[a];
                w[m++] = W[a];
            }
            double nrm[3] = { xu[1] * xv[2] - xu[2] * xv[1], xu[2] * xv[0] - xu[0] * xv[2], xu[0] * xv[1] - xu[1] * xv[0] };
            const double area = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]) / ((double)per_side * per_side);
            if ((rc = sb_contact_points_add(cp, m, dof, w, area, s, t))) { free(map); return rc; }
        }
    int rc = sb_contact_grid_triangles(cp, map, ns, nt);
    free(map);
    return rc;
}
