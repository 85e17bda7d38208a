/* sb_contact_points.c — the list of contact sample points a method builds
 * (sb_contact_points.h). */
#include "sb_contact_points.h"
#include "sb_common.h"

#include <stdlib.h>
#include <string.h>

int sb_contact_points_add(sb_contact_points *cp, int k, const int *dof, const double *w, double area, double s,
                          double t)
{
    int nt = cp->off ? cp->off[cp->n] : 0;
    if (cp->n + 1 > cp->cap_p || !cp->off) {
        int nc = cp->cap_p ? 2 * cp->cap_p : 256;
        int *off = realloc(cp->off, (size_t)(nc + 1) * sizeof *off);
        if (off) cp->off = off;
        double *ar = realloc(cp->area, (size_t)nc * sizeof *ar);
        if (ar) cp->area = ar;
        double *st = realloc(cp->st, (size_t)2 * nc * sizeof *st);
        if (st) cp->st = st;
        if (!off || !ar || !st) return SB_ERR_NOMEM;
        if (cp->cap_p == 0) cp->off[0] = 0;
        cp->cap_p = nc;
    }
    if (nt + k > cp->cap_t) {
        int nc = cp->cap_t ? cp->cap_t : 1024;
        while (nc < nt + k) nc *= 2;
        int *d = realloc(cp->dof, (size_t)nc * sizeof *d);
        if (d) cp->dof = d;
        double *ww = realloc(cp->w, (size_t)nc * sizeof *ww);
        if (ww) cp->w = ww;
        if (!d || !ww) return SB_ERR_NOMEM;
        cp->cap_t = nc;
    }
    memcpy(cp->dof + nt, dof, (size_t)k * sizeof *dof);
    memcpy(cp->w + nt, w, (size_t)k * sizeof *w);
    cp->area[cp->n] = area;
    cp->st[2 * cp->n] = s;
    cp->st[2 * cp->n + 1] = t;
    cp->n++;
    cp->off[cp->n] = nt + k;
    return SB_OK;
}

int sb_contact_points_add_tri(sb_contact_points *cp, int a, int b, int c)
{
    if (cp->nt == cp->cap_tri) {
        int nc = cp->cap_tri ? 2 * cp->cap_tri : 512;
        int *t = realloc(cp->tri, (size_t)3 * nc * sizeof *t);
        if (!t) return SB_ERR_NOMEM;
        cp->tri = t;
        cp->cap_tri = nc;
    }
    cp->tri[3 * cp->nt] = a;
    cp->tri[3 * cp->nt + 1] = b;
    cp->tri[3 * cp->nt + 2] = c;
    cp->nt++;
    return SB_OK;
}

int sb_contact_grid_triangles(sb_contact_points *cp, const int *map, int ns, int nt)
{
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) {
            const int a = map[j * (ns + 1) + i], b = map[j * (ns + 1) + i + 1];
            const int c = map[(j + 1) * (ns + 1) + i + 1], d = map[(j + 1) * (ns + 1) + i];
            if (a < 0 || b < 0 || c < 0 || d < 0) continue;
            int rc = (i + j) % 2 == 0
                         ? sb_contact_points_add_tri(cp, a, b, c) || sb_contact_points_add_tri(cp, a, c, d)
                         : sb_contact_points_add_tri(cp, a, b, d) || sb_contact_points_add_tri(cp, b, c, d);
            if (rc) return SB_ERR_NOMEM;
        }
    return SB_OK;
}

void sb_contact_points_free(sb_contact_points *cp)
{
    if (!cp) return;
    free(cp->tri);
    free(cp->off); free(cp->dof); free(cp->w); free(cp->area); free(cp->st);
    memset(cp, 0, sizeof *cp);
}

void sb_contact_points_eval(const sb_contact_points *cp, int p, const double *x, double xp[3])
{
    xp[0] = xp[1] = xp[2] = 0.0;
    for (int a = cp->off[p]; a < cp->off[p + 1]; a++)
        for (int c = 0; c < 3; c++) xp[c] += cp->w[a] * x[cp->dof[a] + c];
}
