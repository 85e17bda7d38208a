/* bhem_contact.c — contact sample points of the Hermite discretization
 * (docs/contact.md): a uniform grid of (n1 per_side + 1) x (n2 per_side + 1)
 * points in the grid parameter (s,t), each expressed through the basis of
 * the patch that contains it, x(s,t) = sum_I N_I q_I (BHEM Eq. 16): the
 * barrier's chain rule runs through these weights.  Area per point:
 * |x_s x x_t| hs ht / per_side^2 at the reference (a midpoint-like rule;
 * boundary points get a full cell's share — assumption).  The surface
 * between the points (self-contact): each grid cell whose four corners are
 * points, cut into two triangles along alternating diagonals. */
#include "bhem.h"
#include "sb_contact_points.h"

#include <math.h>
#include <stdlib.h>

int bhem_contact_points(void *state, int level, int per_side, sb_contact_points *cp)
{
    const bhem_state *S = state;
    const bhem_level *L = &S->lv[level];
    const int ns = L->n1 * per_side, nt = L->n2 * per_side;
    double N[BHEM_NB], N1[BHEM_NB], N2[BHEM_NB], w[BHEM_NB];
    int dof[BHEM_NB];
    int *map = malloc((size_t)(ns + 1) * (nt + 1) * sizeof *map);
    if (!map) return SB_ERR_NOMEM;
    for (int j = 0; j <= nt; j++)
        for (int i = 0; i <= ns; i++) {
            const double s = (double)i / ns, t = (double)j / nt;
            double th1, th2;
            const int e = bhem_locate(L, s, t, &th1, &th2);
            map[j * (ns + 1) + i] = e < 0 ? -1 : cp->n;
            if (e < 0) continue;                       /* outside an L-shaped domain */
            bhem_basis_eval(th1, th2, L->hs, L->ht, N, N1, N2, NULL, NULL, NULL);
            double xs[3] = { 0, 0, 0 }, xt[3] = { 0, 0, 0 };
            int k = 0;
            for (int I = 0; I < BHEM_NB; I++) {
                const int d = L->elem_dofs[(size_t)e * BHEM_NED + 3 * I];
                for (int c = 0; c < 3; c++) {
                    xs[c] += N1[I] * L->x_ref[d + c];
                    xt[c] += N2[I] * L->x_ref[d + c];
                }
                if (N[I] == 0.0) continue;
                dof[k] = d;
                w[k++] = N[I];
            }
            double nrm[3] = { xs[1] * xt[2] - xs[2] * xt[1], xs[2] * xt[0] - xs[0] * xt[2], xs[0] * xt[1] - xs[1] * xt[0] };
            const double area = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]) / ((double)ns * nt);
            int rc = sb_contact_points_add(cp, k, dof, w, area, s, t);
            if (rc) { free(map); return rc; }
        }
    int rc = sb_contact_grid_triangles(cp, map, ns, nt);
    free(map);
    return rc;
}
