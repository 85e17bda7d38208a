/* lf_impulse.c — linear_fem's impulse-based collision response
 * (contact.model = "impulse", sb_method.h impulse_response): Bender & Deul
 * §6 / Bridson, Fedkiw & Anderson 2002 on the finest level's triangles
 * through sb_bridson_respond, with the lumped vertex masses rho A / 3 per
 * adjacent triangle (the row sums of either mass matrix, lf_loads.c) and
 * infinite mass (inverse 0) for every vertex with a constrained position
 * dof (Dirichlet and moving-boundary vertices).  Edge-director dofs
 * (dofs 3 nv + e) are left as the step made them. */
#include "lf.h"
#include "sb_bridson.h"

#include <stdlib.h>

int lf_impulse_response(void *state, const sb_scene *scene, double dt, double t1, const double *x0, double *x1,
                        sb_impulse_stats *st)
{
    lf_state *S = state;
    const lf_level *L = &S->lv[S->n_levels - 1];
    double *w = calloc((size_t)L->nv + 1, sizeof *w);
    if (!w) return SB_ERR_NOMEM;
    for (int t = 0; t < L->nt; t++)
        for (int k = 0; k < 3; k++) w[L->tri[t].v[k]] += S->mat.density * L->tri[t].ref.dA / 3.0;
    for (int v = 0; v < L->nv; v++) w[v] = w[v] > 0 ? 1.0 / w[v] : 0.0;
    for (int k = 0; k < L->dir.n; k++)
        if (L->dir.dofs[k] < 3 * L->nv) w[L->dir.dofs[k] / 3] = 0.0;
    const sb_bridson_mesh m = { L->nv, L->nt, L->mesh.tri, w };
    int rc = sb_bridson_respond(&m, scene, dt, t1, x0, x1, st);
    free(w);
    return rc;
}
