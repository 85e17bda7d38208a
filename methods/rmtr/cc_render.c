/* cc_render.c — the rmtr method's surface for rendering.  A regular
 * Catmull–Clark face (four interior vertices of valence 4) is a uniform
 * bicubic B-spline patch of its 4x4 control points, i.e. exactly a Bézier
 * patch after the basis change (sb_bspline_to_bezier); every domain face of
 * the structured cages the scenes build is regular (the ghost ring, §5.2.1),
 * so the limit surface is rendered exactly.  A cage with an irregular domain
 * face (extraordinary vertex) is refused with SB_ERR_UNSUPPORTED and the
 * renderer falls back to a tessellation of eval_points. */
#include "cc_method.h"
#include "sb_bezier.h"
#include "sb_surface.h"

#include <math.h>
#include <stdio.h>

/* Reorder a 4x4 net given with u along fv0->fv1, v along fv0->fv3 so that
 * its u runs along +s and v along +t (the material frame's first direction
 * is d/ds, sb_shell.h). */
static void orient(const cc_mesh *m, int f, const double *in, double *out)
{
    const int *c = m->fv + 4 * f;
    const double du[2] = { m->st[2 * c[1]] - m->st[2 * c[0]], m->st[2 * c[1] + 1] - m->st[2 * c[0] + 1] };
    const double dv[2] = { m->st[2 * c[3]] - m->st[2 * c[0]], m->st[2 * c[3] + 1] - m->st[2 * c[0] + 1] };
    const int swap = fabs(du[0]) < fabs(du[1]);   /* old u runs along t */
    /* new u = +s: from old u (no swap) or old v (swap); flips by sign */
    const int flip_a = swap ? dv[0] < 0 : du[0] < 0;
    const int flip_b = swap ? du[1] < 0 : dv[1] < 0;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const int a = flip_a ? 3 - i : i, b = flip_b ? 3 - j : j;   /* along the old direction of s, t */
            const int oi = swap ? b : a, oj = swap ? a : b;
            for (int k = 0; k < 3; k++) out[3 * (i + 4 * j) + k] = in[3 * (oi + 4 * oj) + k];
        }
}

int cc_surface(void *state, int level, const double *x, sb_surface *out)
{
    cc_state *S = state;
    if (level < 0 || level >= S->nlev) return cc_state_fail(S, SB_ERR_INPUT, "no level %d", level);
    const cc_level *L = &S->lv[level];
    const cc_mesh *m = L->mesh;
    const int ne = L->quad.ne;
    for (int e = 0; e < ne; e++)
        if (!cc_face_regular(m, L->quad.face[e]))
            return cc_state_fail(S, SB_ERR_UNSUPPORTED,
                                 "face %d of level %d is not a regular patch (extraordinary or boundary vertex)",
                                 L->quad.face[e], level);
    if (sb_surface_alloc_patches(out, ne, 1)) return SB_ERR_NOMEM;
    for (int e = 0; e < ne; e++) {
        const int f = L->quad.face[e];
        int idx[16];
        if (cc_face_gather16(m, f, idx)) return cc_state_fail(S, SB_ERR_INTERNAL, "inconsistent regular face %d", f);
        double B[SB_BEZ_N], Bref[SB_BEZ_N], P[SB_BEZ_N];
        for (int a = 0; a < 16; a++)
            for (int c = 0; c < 3; c++) {
                B[3 * a + c] = x[3 * idx[a] + c];
                Bref[3 * a + c] = L->X[3 * idx[a] + c];
            }
        sb_bspline_to_bezier(B, P);
        orient(m, f, P, out->patch + (size_t)e * SB_BEZ_N);
        sb_bspline_to_bezier(Bref, P);
        orient(m, f, P, out->patch_ref + (size_t)e * SB_BEZ_N);
        /* the (s,t) box: the limit of the control parameters at the corners
         * (the cage's st are spline control values, cc.h) */
        for (int a = 0; a < 16; a++) {
            B[3 * a] = m->st[2 * idx[a]];
            B[3 * a + 1] = m->st[2 * idx[a] + 1];
            B[3 * a + 2] = 0;
        }
        sb_bspline_to_bezier(B, P);
        orient(m, f, P, Bref);
        double *b = out->patch_st + 4 * e;
        b[0] = Bref[0];
        b[1] = Bref[3 * 15];
        b[2] = Bref[1];
        b[3] = Bref[3 * 15 + 1];
    }
    snprintf(out->what, sizeof out->what,
             "%d regular Catmull-Clark faces as bicubic Bézier patches (exact limit surface)", ne);
    return SB_OK;
}
