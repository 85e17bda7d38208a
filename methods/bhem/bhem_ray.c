/* bhem_ray.c — bhem's surface for rendering: every Hermite patch in its
 * exact Bézier form (BHEM paper §5, Eq. 22), so `shellbench render` traces
 * rays against the patches themselves with the paper's ray–patch algorithms
 * (core/render/sb_bezier_ray.h). */
#include "bhem.h"
#include "sb_bezier.h"
#include "sb_surface.h"

#include <stdio.h>

/* the 4 x 4 generalized coordinates of patch e (local I = 4 corner + kind,
 * corner = p + 2q; derivatives w.r.t. the patch coordinate theta, bhem.h)
 * as Bézier control points */
void bhem_patch_bezier(const bhem_level *L, int e, const double *x, double *P)
{
    double qe[BHEM_NED], H[4][4][3];
    bhem_gather(L, e, x, qe);
    for (int corner = 0; corner < 4; corner++)
        for (int kind = 0; kind < 4; kind++)
            for (int c = 0; c < 3; c++) H[corner][kind][c] = qe[3 * (4 * corner + kind) + c];
    sb_hermite_to_bezier(H, P);
}

int bhem_surface(void *state, int level, const double *x, sb_surface *out)
{
    bhem_state *S = state;
    if (level < 0 || level >= S->n_levels) return bhem_fail(S, SB_ERR_INPUT, "no level %d", level);
    const bhem_level *L = &S->lv[level];
    if (sb_surface_alloc_patches(out, L->n_elems, 1)) return SB_ERR_NOMEM;
    for (int e = 0; e < L->n_elems; e++) {
        bhem_patch_bezier(L, e, x, out->patch + (size_t)e * SB_BEZ_N);
        bhem_patch_bezier(L, e, L->x_ref, out->patch_ref + (size_t)e * SB_BEZ_N);
        const int c = L->elem_cell[e], i = c % L->n1, j = c / L->n1;
        double *b = out->patch_st + 4 * e;
        b[0] = i * L->hs;
        b[1] = (i + 1) * L->hs;
        b[2] = j * L->ht;
        b[3] = (j + 1) * L->ht;
    }
    snprintf(out->what, sizeof out->what, "%d bicubic Hermite patches in Bézier form (exact)", L->n_elems);
    return SB_OK;
}
