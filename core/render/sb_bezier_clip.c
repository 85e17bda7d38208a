/* sb_bezier_clip.c — ray–patch intersection by Bézier clipping (Nishita,
 * Sederberg & Kakimoto, SIGGRAPH 1990), the comparison method of the BHEM
 * paper's Table 1.
 *
 * The patch is written in an orthonormal frame of the ray (e1, e2 normal to
 * d, e3 = d), so the ray is the axis q1 = q2 = 0 and q3 is the ray parameter.
 * Clipping in u: L is the mean direction of the patch's v-edges projected on
 * the (q1,q2) plane, D_ij the signed distance of control point ij to the line
 * through the ray along L; D(u,v) = sum B_i(u) B_j(v) D_ij vanishes at the
 * intersection, and by the convex-hull property of the points (i/3, D_ij) it
 * can vanish only for u in the interval where that hull meets D = 0.  The
 * sub-patch over that interval replaces the patch; then v likewise.  When
 * neither clip removes 20 % of its range the patch is split in half across
 * its longer side (NSK90 §4).  Regions are taken smallest depth first from the same
 * min-heap as the subdivision algorithms (key: smallest q3 of the control
 * points), so the search for the first hit stops as theirs does. */
#include "sb_bezier_ray.h"

#include <math.h>
#include <string.h>

/* Interval of x in [0,1] where the convex hull of (i/3, y) over the columns'
 * extreme values ymin[i], ymax[i] meets y = 0; returns 0 if it does not. */
static int hull_interval(const double ymin[4], const double ymax[4], double *c0, double *c1)
{
    double px[8], py[8];
    for (int i = 0; i < 4; i++) {
        px[2 * i] = px[2 * i + 1] = i / 3.0;
        py[2 * i] = ymin[i];
        py[2 * i + 1] = ymax[i];
    }
    double lo = INFINITY, hi = -INFINITY;
    for (int a = 0; a < 8; a++) {
        if (py[a] == 0.0) { lo = fmin(lo, px[a]); hi = fmax(hi, px[a]); }
        for (int b = a + 1; b < 8; b++) {
            if ((py[a] < 0.0 && py[b] > 0.0) || (py[a] > 0.0 && py[b] < 0.0)) {
                const double x = px[a] + (px[b] - px[a]) * (-py[a]) / (py[b] - py[a]);
                lo = fmin(lo, x);
                hi = fmax(hi, x);
            }
        }
    }
    if (!(lo <= hi)) return 0;
    /* guard against round-off in the distances: never clip a root away */
    *c0 = fmax(0.0, lo - 1e-9);
    *c1 = fmin(1.0, hi + 1e-9);
    return 1;
}

/* Clip interval of the sub-patch Q (ray frame) in u (dir 0) or v (dir 1). */
static int clip_interval(const double *Q, int dir, double *c0, double *c1)
{
    /* line direction: mean of the edges along the other parameter */
    double L[2];
    if (dir == 0) {
        L[0] = Q[3 * 12] - Q[0] + Q[3 * 15] - Q[3 * 3];
        L[1] = Q[3 * 12 + 1] - Q[1] + Q[3 * 15 + 1] - Q[3 * 3 + 1];
    } else {
        L[0] = Q[3 * 3] - Q[0] + Q[3 * 15] - Q[3 * 12];
        L[1] = Q[3 * 3 + 1] - Q[1] + Q[3 * 15 + 1] - Q[3 * 12 + 1];
    }
    double n = hypot(L[0], L[1]);
    double nx = 1.0, ny = 0.0;
    if (n > 0.0 && isfinite(n)) { nx = -L[1] / n; ny = L[0] / n; }
    double ymin[4] = { INFINITY, INFINITY, INFINITY, INFINITY }, ymax[4] = { -INFINITY, -INFINITY, -INFINITY, -INFINITY };
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const double *q = Q + 3 * (i + 4 * j);
            const double D = nx * q[0] + ny * q[1];
            const int col = dir == 0 ? i : j;
            if (D < ymin[col]) ymin[col] = D;
            if (D > ymax[col]) ymax[col] = D;
        }
    return hull_interval(ymin, ymax, c0, c1);
}

/* seq: NULL = best-first (key: the smallest ray parameter of the control
 * points); else depth first (key: minus a running count, so the heap pops
 * the region pushed last, a stack). */
static int push(sb_bezier_ws *ws, const double *Q, double u0, double u1, double v0, double v1, double limit, long *seq)
{
    double kmin = Q[2];
    for (int k = 1; k < 16; k++) kmin = fmin(kmin, Q[3 * k + 2]);
    ws->counts.splits++;
    if (!(kmin < limit)) return 0;
    int idx = sb_bez_new(ws);
    if (idx < 0) return -1;
    sb_bez_region *R = &ws->pool[idx];
    memcpy(R->P, Q, sizeof R->P);
    R->u0 = u0; R->u1 = u1; R->v0 = v0; R->v1 = v1;
    R->key = seq ? -(double)++*seq : kmin;
    sb_bez_push(ws, idx);
    return 0;
}

/* textbook = 0: best-first with first-hit pruning (the search stops when the
 * heap's smallest ray parameter passes the best root, and sub-patches behind
 * it are never pushed); textbook = 1: Bézier clipping as NSK90 state it and
 * most implementations do it: depth first, every root in (tmin, tmax) found,
 * the smallest kept (only tmax, the caller's nearest hit so far, prunes). */
static int clip_search(int textbook, const double *P, const sb_ray *r, double tmax, double eps, sb_bezier_ws *ws,
                       sb_patch_hit *hit)
{
    long seq_store = 0, *seq = textbook ? &seq_store : NULL;
    /* the ray frame */
    double e1[3], e2[3];
    const double *d = r->d;
    if (fabs(d[0]) < 0.6) { e1[0] = 0; e1[1] = d[2]; e1[2] = -d[1]; }   /* e_x x d */
    else { e1[0] = -d[2]; e1[1] = 0; e1[2] = d[0]; }                      /* e_y x d */
    double n = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int c = 0; c < 3; c++) e1[c] /= n;
    e2[0] = d[1] * e1[2] - d[2] * e1[1];
    e2[1] = d[2] * e1[0] - d[0] * e1[2];
    e2[2] = d[0] * e1[1] - d[1] * e1[0];
    double Q[SB_BEZ_N];
    for (int k = 0; k < 16; k++) {
        const double p[3] = { P[3 * k] - r->o[0], P[3 * k + 1] - r->o[1], P[3 * k + 2] - r->o[2] };
        Q[3 * k] = p[0] * e1[0] + p[1] * e1[1] + p[2] * e1[2];
        Q[3 * k + 1] = p[0] * e2[0] + p[1] * e2[1] + p[2] * e2[2];
        Q[3 * k + 2] = p[0] * d[0] + p[1] * d[1] + p[2] * d[2];
    }
    sb_bez_reset(ws);
    if (push(ws, Q, 0, 1, 0, 1, tmax, seq)) return -1;
    int found = 0;
    double best = tmax, limit = tmax;
    long budget = SB_BEZ_BUDGET;
    int idx;
    while ((idx = sb_bez_pop(ws)) >= 0) {
        sb_bez_region R = ws->pool[idx];
        sb_bez_release(ws, idx);
        ws->counts.regions++;
        if (!textbook && !(R.key < limit)) break;
        if (--budget < 0) { ws->counts.budget++; break; }
        double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
        for (int k = 0; k < 16; k++)
            for (int c = 0; c < 3; c++) {
                lo[c] = fmin(lo[c], R.P[3 * k + c]);
                hi[c] = fmax(hi[c], R.P[3 * k + c]);
            }
        if (lo[0] > 0.0 || hi[0] < 0.0 || lo[1] > 0.0 || hi[1] < 0.0 || hi[2] <= r->tmin) continue;
        if (fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2])) <= eps ||
            (R.u1 - R.u0 < 1e-13 && R.v1 - R.v0 < 1e-13)) {
            double x[3];
            sb_bezier_eval(R.P, 0.5, 0.5, x, NULL, NULL);
            const double t = x[2];
            if (t > r->tmin && t < best) {
                best = t;
                hit->t = t;
                hit->u = 0.5 * (R.u0 + R.u1);
                hit->v = 0.5 * (R.v0 + R.v1);
                found = 1;
                if (!textbook) limit = best - eps;
            }
            continue;
        }
        /* clip in u, then in v (each clip applied, however small); when
         * neither removed 20 % of its range, split in half across the
         * longer side instead (NSK90 §4) */
        double frac[2] = { 1, 1 };
        int dead = 0;
        for (int dir = 0; dir < 2 && !dead; dir++) {
            double c0, c1;
            ws->counts.clips++;
            if (!clip_interval(R.P, dir, &c0, &c1)) { dead = 1; break; }
            frac[dir] = c1 - c0;
            if (c0 <= 0.0 && c1 >= 1.0) continue;
            const double w0 = dir == 0 ? R.u0 : R.v0, w = dir == 0 ? R.u1 - R.u0 : R.v1 - R.v0;
            if (dir == 0) {
                sb_bezier_sub(R.P, c0, c1, 0, 1, R.P);
                R.u0 = w0 + c0 * w;
                R.u1 = w0 + c1 * w;
            } else {
                sb_bezier_sub(R.P, 0, 1, c0, c1, R.P);
                R.v0 = w0 + c0 * w;
                R.v1 = w0 + c1 * w;
            }
        }
        if (dead) continue;
        if (frac[0] > 0.8 && frac[1] > 0.8) {
            /* the longer side in the ray's projection plane */
            double lu = 0, lv = 0;
            for (int k = 0; k < 4; k++) {
                const double *a = R.P + 3 * (4 * k), *b = R.P + 3 * (4 * k + 3), *c = R.P + 3 * k, *e = R.P + 3 * (k + 12);
                lu = fmax(lu, hypot(b[0] - a[0], b[1] - a[1]));
                lv = fmax(lv, hypot(e[0] - c[0], e[1] - c[1]));
            }
            double A[SB_BEZ_N], B[SB_BEZ_N];
            if (lu >= lv) {
                const double um = 0.5 * (R.u0 + R.u1);
                sb_bezier_split_u(R.P, 0.5, A, B);
                if (push(ws, A, R.u0, um, R.v0, R.v1, limit, seq) || push(ws, B, um, R.u1, R.v0, R.v1, limit, seq)) return -1;
            } else {
                const double vm = 0.5 * (R.v0 + R.v1);
                sb_bezier_split_v(R.P, 0.5, A, B);
                if (push(ws, A, R.u0, R.u1, R.v0, vm, limit, seq) || push(ws, B, R.u0, R.u1, vm, R.v1, limit, seq)) return -1;
            }
            continue;
        }
        if (push(ws, R.P, R.u0, R.u1, R.v0, R.v1, limit, seq)) return -1;
    }
    return found;
}

int sb_bezier_clip_intersect(const double *P, const sb_ray *r, double tmax, double eps, sb_bezier_ws *ws,
                             sb_patch_hit *hit)
{
    return clip_search(0, P, r, tmax, eps, ws, hit);
}

int sb_bezier_clip_dfs_intersect(const double *P, const sb_ray *r, double tmax, double eps, sb_bezier_ws *ws,
                                 sb_patch_hit *hit)
{
    return clip_search(1, P, r, tmax, eps, ws, hit);
}
