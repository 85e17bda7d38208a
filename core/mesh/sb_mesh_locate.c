/* sb_mesh_locate.c — point location in (s,t) by a bucket grid: every
 * triangle is listed in the buckets its (s,t) bounding box overlaps (about
 * one triangle per bucket), a query tests the triangles of one bucket. */
#include "sb_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int bucket(double u, int n)
{
    int i = (int)floor(u * n);
    return i < 0 ? 0 : i >= n ? n - 1 : i;
}

int sb_mesh_locator_build(const sb_mesh *m, sb_mesh_locator *L)
{
    memset(L, 0, sizeof *L);
    int nb = (int)ceil(sqrt((double)m->nt));
    if (nb < 1) nb = 1;
    if (nb > 4096) nb = 4096;
    L->nb_s = L->nb_t = nb;
    const long nbk = (long)nb * nb;
    L->ptr = calloc((size_t)nbk + 1, sizeof(int));
    if (!L->ptr) return SB_ERR_NOMEM;
    for (int pass = 0; pass < 2; pass++) {
        int *fill = NULL;
        if (pass == 1) {
            for (long b = 0; b < nbk; b++) L->ptr[b + 1] += L->ptr[b];
            L->tri = malloc(sizeof(int) * (size_t)(L->ptr[nbk] + 1));
            fill = malloc(sizeof(int) * (size_t)nbk);
            if (!L->tri || !fill) { free(fill); sb_mesh_locator_free(L); return SB_ERR_NOMEM; }
            memcpy(fill, L->ptr, sizeof(int) * (size_t)nbk);
        }
        for (int t = 0; t < m->nt; t++) {
            const double *p = m->tri_st + 6 * t;
            double lo[2] = { fmin(p[0], fmin(p[2], p[4])), fmin(p[1], fmin(p[3], p[5])) };
            double hi[2] = { fmax(p[0], fmax(p[2], p[4])), fmax(p[1], fmax(p[3], p[5])) };
            const double pad = 1e-9;
            for (int j = bucket(lo[1] - pad, nb); j <= bucket(hi[1] + pad, nb); j++)
                for (int i = bucket(lo[0] - pad, nb); i <= bucket(hi[0] + pad, nb); i++) {
                    const long b = i + (long)nb * j;
                    if (pass == 0) L->ptr[b + 1]++;
                    else L->tri[fill[b]++] = t;
                }
        }
        free(fill);
    }
    return SB_OK;
}

void sb_mesh_locator_free(sb_mesh_locator *L)
{
    free(L->ptr);
    free(L->tri);
    memset(L, 0, sizeof *L);
}

/* barycentric coordinates of (s,t) in triangle t (corner coordinates) */
static void bary_of(const sb_mesh *m, int t, double s, double u, double b[3])
{
    const double *p = m->tri_st + 6 * t;
    const double d = (p[2] - p[0]) * (p[5] - p[1]) - (p[4] - p[0]) * (p[3] - p[1]);
    b[1] = ((s - p[0]) * (p[5] - p[1]) - (p[4] - p[0]) * (u - p[1])) / d;
    b[2] = ((p[2] - p[0]) * (u - p[1]) - (s - p[0]) * (p[3] - p[1])) / d;
    b[0] = 1.0 - b[1] - b[2];
}

int sb_mesh_locate(const sb_mesh *m, const sb_mesh_locator *L, double s, double t, double bary[3])
{
    if (!(s >= -1e-9 && s <= 1 + 1e-9 && t >= -1e-9 && t <= 1 + 1e-9)) return -1;
    const long b = bucket(s, L->nb_s) + (long)L->nb_s * bucket(t, L->nb_t);
    int best = -1;
    double best_min = -INFINITY, bb[3];
    for (int k = L->ptr[b]; k < L->ptr[b + 1]; k++) {
        const int tr = L->tri[k];
        bary_of(m, tr, s, t, bb);
        const double mn = fmin(bb[0], fmin(bb[1], bb[2]));
        if (mn > best_min) {
            best_min = mn;
            best = tr;
            memcpy(bary, bb, sizeof bb);
            if (mn >= 0) break;
        }
    }
    if (best < 0 || best_min < -1e-9) return -1;
    double sum = 0;
    for (int k = 0; k < 3; k++) {
        bary[k] = fmax(bary[k], 0.0);
        sum += bary[k];
    }
    for (int k = 0; k < 3; k++) bary[k] /= sum;
    return best;
}
