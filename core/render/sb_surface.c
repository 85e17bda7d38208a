/* sb_surface.c — allocation and bounds of a render surface (sb_surface.h). */
#include "sb_surface.h"
#include "sb_bezier.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int sb_surface_alloc_patches(sb_surface *s, int n, int with_ref)
{
    free(s->patch);
    free(s->patch_ref);
    free(s->patch_st);
    s->patch = s->patch_ref = s->patch_st = NULL;
    s->n_patches = 0;
    if (n <= 0) return n < 0 ? -1 : 0;
    s->patch = malloc((size_t)n * SB_BEZ_N * sizeof(double));
    s->patch_st = malloc((size_t)n * 4 * sizeof(double));
    if (with_ref) s->patch_ref = malloc((size_t)n * SB_BEZ_N * sizeof(double));
    if (!s->patch || !s->patch_st || (with_ref && !s->patch_ref)) return -1;
    s->n_patches = n;
    return 0;
}

int sb_surface_alloc_tris(sb_surface *s, int nv, int nt, int with_ref, int with_st)
{
    free(s->vert); free(s->vert_ref); free(s->vert_st); free(s->tri); free(s->tri_st);
    s->vert = s->vert_ref = s->vert_st = s->tri_st = NULL;
    s->tri = NULL;
    s->n_verts = s->n_tris = 0;
    if (nv < 0 || nt < 0) return -1;
    s->vert = malloc((size_t)(nv ? nv : 1) * 3 * sizeof(double));
    s->tri = malloc((size_t)(nt ? nt : 1) * 3 * sizeof(int));
    if (with_ref) s->vert_ref = malloc((size_t)(nv ? nv : 1) * 3 * sizeof(double));
    if (with_st) s->vert_st = malloc((size_t)(nv ? nv : 1) * 2 * sizeof(double));
    if (!s->vert || !s->tri || (with_ref && !s->vert_ref) || (with_st && !s->vert_st)) return -1;
    s->n_verts = nv;
    s->n_tris = nt;
    return 0;
}

void sb_surface_free(sb_surface *s)
{
    free(s->patch); free(s->patch_ref); free(s->patch_st);
    free(s->vert); free(s->vert_ref); free(s->vert_st); free(s->tri); free(s->tri_st);
    memset(s, 0, sizeof *s);
}

int sb_surface_bounds(const sb_surface *s, double lo[3], double hi[3])
{
    for (int c = 0; c < 3; c++) { lo[c] = INFINITY; hi[c] = -INFINITY; }
    const long np = 16L * s->n_patches;
    for (long k = 0; k < np; k++)
        for (int c = 0; c < 3; c++) {
            const double x = s->patch[3 * k + c];
            if (!isfinite(x)) return -1;
            lo[c] = fmin(lo[c], x);
            hi[c] = fmax(hi[c], x);
        }
    for (long t = 0; t < 3L * s->n_tris; t++) {
        const int v = s->tri[t];
        if (v < 0 || v >= s->n_verts) return -1;
        for (int c = 0; c < 3; c++) {
            const double x = s->vert[3 * v + c];
            if (!isfinite(x)) return -1;
            lo[c] = fmin(lo[c], x);
            hi[c] = fmax(hi[c], x);
        }
    }
    return lo[0] <= hi[0] ? 0 : -1;
}
