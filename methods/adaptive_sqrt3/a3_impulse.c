/* a3_impulse.c — adaptive_sqrt3's collision handling (contact.model =
 * "impulse"): Bender & Deul §6 use Bridson, Fedkiw & Anderson 2002's
 * proximity and collision impulses with friction, CCD and rigid impact zones
 * (sb_bridson_respond) on the current (adapted) mesh, with the method's own
 * lumped hybrid-Voronoi vertex masses (Alg. 1, Eq. 3) and infinite mass
 * (inverse 0) for every vertex with a constrained dof (Dirichlet and
 * moving-boundary vertices). */
#include "a3.h"
#include "sb_bridson.h"

#include <stdlib.h>

int a3_impulse_response(void *state, const sb_scene *scene, double dt, double t1, const double *x0, double *x1,
                        sb_impulse_stats *st)
{
    a3_state *S = state;
    double *w = malloc((size_t)(S->nv + 1) * sizeof *w);
    if (!w) return SB_ERR_NOMEM;
    for (int v = 0; v < S->nv; v++) w[v] = S->mass[v] > 0 ? 1.0 / S->mass[v] : 0.0;
    for (int k = 0; k < S->n_con; k++) w[S->con_dofs[k] / 3] = 0.0;
    const sb_bridson_mesh m = { S->nv, S->nt, S->mesh.tri, w };
    int rc = sb_bridson_respond(&m, scene, dt, t1, x0, x1, st);
    free(w);
    return rc;
}
