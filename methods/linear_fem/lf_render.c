/* lf_render.c — linear_fem's surface for rendering: its triangles
 * themselves (the discretization is piecewise linear, so they are its exact
 * surface), with the reference positions and the (s,t) of every corner for
 * strain colours (core/render/sb_surface.h). */
#include "lf.h"
#include "sb_surface.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int lf_surface(void *state, int level, const double *x, sb_surface *out)
{
    lf_state *S = state;
    if (level < 0 || level >= S->n_levels) return SB_ERR_INPUT;
    const lf_level *L = &S->lv[level];
    const sb_mesh *m = &L->mesh;
    if (sb_surface_alloc_tris(out, m->nv, m->nt, 1, 1) ||
        !(out->tri_st = malloc((size_t)(m->nt ? m->nt : 1) * 6 * sizeof(double))))
        return SB_ERR_NOMEM;
    /* positions are the first 3 nv dofs (lf.h: dof 3 v + c; edge directors follow) */
    memcpy(out->vert, x, (size_t)m->nv * 3 * sizeof(double));
    memcpy(out->vert_ref, L->x_ref, (size_t)m->nv * 3 * sizeof(double));
    memcpy(out->vert_st, m->st, (size_t)m->nv * 2 * sizeof(double));
    memcpy(out->tri, m->tri, (size_t)m->nt * 3 * sizeof(int));
    memcpy(out->tri_st, m->tri_st, (size_t)m->nt * 6 * sizeof(double));
    snprintf(out->what, sizeof out->what, "%d triangles of the linear_fem mesh (exact)", m->nt);
    return SB_OK;
}
