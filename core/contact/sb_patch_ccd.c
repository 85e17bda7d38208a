/* sb_patch_ccd.c — point against moving Bézier patch, BHEM paper §5.2
 * (see sb_patch_ccd.h for the algorithm). */
#include "sb_patch_ccd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct region {
    double Ca[SB_BEZ_N], Cb[SB_BEZ_N];   /* control points relative to the point at ta and at tb */
    double u0, u1, v0, v1, ta, tb;
} region;

struct sb_patch_ccd_ws {
    region *pool;
    int *heap, *freel;
    int cap, n_heap, n_free, n_used;
    sb_patch_ccd_counts counts;
};

#define CCD_BUDGET 100000   /* regions one search may take */
#define NEWTON_ITERS 8

sb_patch_ccd_ws *sb_patch_ccd_ws_new(void) { return calloc(1, sizeof(sb_patch_ccd_ws)); }

void sb_patch_ccd_ws_free(sb_patch_ccd_ws *ws)
{
    if (!ws) return;
    free(ws->pool);
    free(ws->heap);
    free(ws->freel);
    free(ws);
}

sb_patch_ccd_counts *sb_patch_ccd_ws_counts(sb_patch_ccd_ws *ws) { return &ws->counts; }

static int region_new(sb_patch_ccd_ws *ws)
{
    if (ws->n_free > 0) return ws->freel[--ws->n_free];
    if (ws->n_used == ws->cap) {
        int cap = ws->cap ? 2 * ws->cap : 128;
        region *p = realloc(ws->pool, (size_t)cap * sizeof *p);
        if (!p) return -1;
        ws->pool = p;
        int *h = realloc(ws->heap, (size_t)cap * sizeof *h);
        if (!h) return -1;
        ws->heap = h;
        int *f = realloc(ws->freel, (size_t)cap * sizeof *f);
        if (!f) return -1;
        ws->freel = f;
        ws->cap = cap;
    }
    return ws->n_used++;
}

/* binary min-heap on ta (the region's earliest feasible time, §5.1's tau_min) */
static void heap_push(sb_patch_ccd_ws *ws, int idx)
{
    int *h = ws->heap, i = ws->n_heap++;
    const double k = ws->pool[idx].ta;
    while (i > 0) {
        int p = (i - 1) / 2;
        if (ws->pool[h[p]].ta <= k) break;
        h[i] = h[p];
        i = p;
    }
    h[i] = idx;
}

static int heap_pop(sb_patch_ccd_ws *ws)
{
    if (ws->n_heap == 0) return -1;
    int *h = ws->heap, top = h[0], last = h[--ws->n_heap], n = ws->n_heap, i = 0;
    const double k = ws->pool[last].ta;
    for (;;) {
        int c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && ws->pool[h[c + 1]].ta < ws->pool[h[c]].ta) c++;
        if (ws->pool[h[c]].ta >= k) break;
        h[i] = h[c];
        i = c;
    }
    if (n > 0) h[i] = last;
    return top;
}

/* The union over i of {s : alpha_i + s beta_i >= 0} is the complement of
 * one open gap (R, L) of the real line (Eq. 28: a union of half-lines);
 * *R >= *L means no gap. */
static void half_line_gap(const double *alpha, const double *beta, int n, double *R, double *L)
{
    double r = -INFINITY, l = INFINITY;
    for (int i = 0; i < n; i++) {
        if (beta[i] > 0) l = fmin(l, -alpha[i] / beta[i]);          /* s >= -alpha/beta */
        else if (beta[i] < 0) r = fmax(r, alpha[i] / -beta[i]);     /* s <= alpha/(-beta) */
        else if (alpha[i] >= 0) { *R = INFINITY; *L = -INFINITY; return; }   /* all s */
    }
    *R = r;
    *L = l;
}

int sb_patch_ccd_times(const double *Ca, const double *Cb, double tol, double *t0, double *t1)
{
    double gR[6], gL[6], al[16], be[16];
    for (int k = 0; k < 3; k++) {
        /* max_ij c_k(s) >= -tol: union of {c_ij,k(s) + tol >= 0} */
        for (int i = 0; i < 16; i++) {
            al[i] = Ca[3 * i + k] + tol;
            be[i] = Cb[3 * i + k] - Ca[3 * i + k];
        }
        half_line_gap(al, be, 16, &gR[2 * k], &gL[2 * k]);
        /* min_ij c_k(s) <= tol: union of {tol - c_ij,k(s) >= 0} */
        for (int i = 0; i < 16; i++) {
            al[i] = tol - Ca[3 * i + k];
            be[i] = -(Cb[3 * i + k] - Ca[3 * i + k]);
        }
        half_line_gap(al, be, 16, &gR[2 * k + 1], &gL[2 * k + 1]);
    }
    /* earliest s in [0,1] in no open gap (greedy: jump over every gap containing s) */
    double s = 0.0;
    for (int changed = 1, it = 0; changed && it < 16; it++) {
        changed = 0;
        for (int g = 0; g < 6; g++)
            if (gR[g] < s && s < gL[g]) { s = gL[g]; changed = 1; }
    }
    if (!(s <= 1.0)) return 0;
    double e = 1.0;
    for (int changed = 1, it = 0; changed && it < 16; it++) {
        changed = 0;
        for (int g = 0; g < 6; g++)
            if (gR[g] < e && e < gL[g]) { e = gR[g]; changed = 1; }
    }
    if (!(e >= s)) return 0;
    *t0 = s;
    *t1 = e;
    return 1;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* 3x3 inverse of the matrix with columns c0, c1, c2 into Ji (row-major); returns det */
static double inverse3(const double c0[3], const double c1[3], const double c2[3], double Ji[9])
{
    double r0[3] = { c1[1] * c2[2] - c1[2] * c2[1], c1[2] * c2[0] - c1[0] * c2[2], c1[0] * c2[1] - c1[1] * c2[0] };
    double r1[3] = { c2[1] * c0[2] - c2[2] * c0[1], c2[2] * c0[0] - c2[0] * c0[2], c2[0] * c0[1] - c2[1] * c0[0] };
    double r2[3] = { c0[1] * c1[2] - c0[2] * c1[1], c0[2] * c1[0] - c0[0] * c1[2], c0[0] * c1[1] - c0[1] * c1[0] };
    const double det = dot3(c0, r0);
    if (det == 0.0 || !isfinite(det)) return 0.0;
    for (int k = 0; k < 3; k++) {
        Ji[k] = r0[k] / det;
        Ji[3 + k] = r1[k] / det;
        Ji[6 + k] = r2[k] / det;
    }
    return det;
}

/* Newton's method on F(a, b, s) = Ca(a,b) + s (Cb(a,b) - Ca(a,b)) = 0 (Eq. 25 = Eq. 26
 * in the point's frame) from the centre of the region; 1 with (a, b, s) in
 * [0,1]^3 when |F| <= tol.  A run that leaves the neighbourhood of the region
 * or stops contracting is abandoned (our safeguard; the paper fixes only the
 * number of iterations). */
static int newton(const region *R, double tol, double *a, double *b, double *s)
{
    double A = 0.5, B = 0.5, S = 0.5, prev = INFINITY;
    for (int it = 0; it <= NEWTON_ITERS; it++) {
        double xa[3], xau[3], xav[3], xb[3], xbu[3], xbv[3], F[3], cu[3], cv[3], cs[3], Ji[9];
        sb_bezier_eval(R->Ca, A, B, xa, xau, xav);
        sb_bezier_eval(R->Cb, A, B, xb, xbu, xbv);
        for (int c = 0; c < 3; c++) {
            F[c] = xa[c] + S * (xb[c] - xa[c]);
            cu[c] = xau[c] + S * (xbu[c] - xau[c]);
            cv[c] = xav[c] + S * (xbv[c] - xav[c]);
            cs[c] = xb[c] - xa[c];
        }
        if (sqrt(dot3(F, F)) <= tol) {
            if (A < 0.0 || A > 1.0 || B < 0.0 || B > 1.0 || S < 0.0 || S > 1.0) return 0;
            *a = A; *b = B; *s = S;
            return 1;
        }
        if (it == NEWTON_ITERS || inverse3(cu, cv, cs, Ji) == 0.0) return 0;
        const double dA = dot3(Ji, F), dB = dot3(Ji + 3, F), dS = dot3(Ji + 6, F);
        A -= dA;
        B -= dB;
        S -= dS;
        const double step = fabs(dA) + fabs(dB) + fabs(dS);
        if (!(A > -0.5 && A < 1.5 && B > -0.5 && B < 1.5 && S > -0.5 && S < 1.5)) return 0;
        if (it >= 2 && step > 0.5 * prev) return 0;
        prev = step;
    }
    return 0;
}

static void bounds2(const double *Ca, const double *Cb, double lo[3], double hi[3])
{
    double l2[3], h2[3];
    sb_bezier_bounds(Ca, lo, hi);
    sb_bezier_bounds(Cb, l2, h2);
    for (int k = 0; k < 3; k++) {
        lo[k] = fmin(lo[k], l2[k]);
        hi[k] = fmax(hi[k], h2[k]);
    }
}

/* Restrict region R (control points Ca, Cb given over [ta, tb]) to the
 * feasible times of Eq. 27 and push it if it can enter before `limit`.
 * Returns -1 on out of memory. */
static int push_region(sb_patch_ccd_ws *ws, const double *Ca, const double *Cb, double u0, double u1, double v0,
                       double v1, double ta, double tb, double tol, double limit)
{
    double s0, s1;
    if (!sb_patch_ccd_times(Ca, Cb, tol, &s0, &s1)) return 0;
    const double t0 = ta + s0 * (tb - ta), t1 = ta + s1 * (tb - ta);
    if (!(t0 < limit)) return 0;
    int k = region_new(ws);
    if (k < 0) return -1;
    region *R = &ws->pool[k];
    for (int i = 0; i < SB_BEZ_N; i++) {
        const double d = Cb[i] - Ca[i];
        R->Ca[i] = Ca[i] + s0 * d;
        R->Cb[i] = Ca[i] + s1 * d;
    }
    R->u0 = u0; R->u1 = u1; R->v0 = v0; R->v1 = v1;
    R->ta = t0;
    R->tb = t1;
    heap_push(ws, k);
    return 0;
}

int sb_patch_ccd(const double *P0, const double *P1, const double p0[3], const double p1[3], double eps,
                 sb_patch_ccd_ws *ws, sb_ccd_hit *hit)
{
    ws->counts.calls++;
    ws->n_heap = ws->n_free = ws->n_used = 0;
    const double tol = 0.5 * eps;   /* the AABB test is inflated by eps/2: touching counts */
    {
        double Ca[SB_BEZ_N], Cb[SB_BEZ_N];
        for (int i = 0; i < 16; i++)
            for (int c = 0; c < 3; c++) {
                Ca[3 * i + c] = P0[3 * i + c] - p0[c];
                Cb[3 * i + c] = P1[3 * i + c] - p1[c];
            }
        if (push_region(ws, Ca, Cb, 0, 1, 0, 1, 0, 1, tol, INFINITY)) return -1;
    }
    int found = 0;
    double best = INFINITY;   /* tau_opt: the earliest root found by Newton */
    long budget = CCD_BUDGET;
    int idx;
    while ((idx = heap_pop(ws)) >= 0) {
        region R = ws->pool[idx];   /* a copy: the pool may move below */
        ws->freel[ws->n_free++] = idx;
        ws->counts.regions++;
        if (!(R.ta < best)) break;   /* no region left can enter before tau_opt */
        if (--budget < 0) {          /* conservative: a collision at the region's earliest time */
            ws->counts.budget++;
            hit->t = R.ta;
            hit->u = 0.5 * (R.u0 + R.u1);
            hit->v = 0.5 * (R.v0 + R.v1);
            found = 1;
            break;
        }
        double lo[3], hi[3];
        bounds2(R.Ca, R.Cb, lo, hi);
        const double ext = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
        if (ext <= eps) {
            /* converged region: the point is within eps of the swept sub-patch
             * from ta on; a Newton root inside its time span is the same
             * contact, located more precisely */
            if (!(found && best <= R.tb)) {
                hit->t = R.ta;
                hit->u = 0.5 * (R.u0 + R.u1);
                hit->v = 0.5 * (R.v0 + R.v1);
                found = 1;
            }
            break;
        }
        double a, b, s;
        ws->counts.newton++;
        if (newton(&R, 1e-3 * eps, &a, &b, &s)) {
            const double t = R.ta + s * (R.tb - R.ta);
            ws->counts.newton_roots++;
            if (t < best) {
                best = t;
                hit->t = t;
                hit->u = R.u0 + a * (R.u1 - R.u0);
                hit->v = R.v0 + b * (R.v1 - R.v0);
                found = 1;
            }
            if (!(R.ta < best)) continue;
        }
        /* motion of the control points over [ta, tb] against the size of the patch */
        double mot = 0.0, plo[3], phi[3];
        for (int i = 0; i < SB_BEZ_N; i++) mot = fmax(mot, fabs(R.Cb[i] - R.Ca[i]));
        sb_bezier_bounds(R.Ca, plo, phi);
        const double size = fmax(phi[0] - plo[0], fmax(phi[1] - plo[1], phi[2] - plo[2]));
        int rc = 0;
        if (mot > size && R.tb > R.ta) {   /* split in time */
            double Cm[SB_BEZ_N];
            const double tm = 0.5 * (R.ta + R.tb);
            for (int i = 0; i < SB_BEZ_N; i++) Cm[i] = 0.5 * (R.Ca[i] + R.Cb[i]);
            rc = push_region(ws, R.Ca, Cm, R.u0, R.u1, R.v0, R.v1, R.ta, tm, tol, best);
            if (!rc) rc = push_region(ws, Cm, R.Cb, R.u0, R.u1, R.v0, R.v1, tm, R.tb, tol, best);
        } else {                            /* De Casteljau into four in (u, v) */
            double A0[SB_BEZ_N], B0[SB_BEZ_N], A1[SB_BEZ_N], B1[SB_BEZ_N], Q0[SB_BEZ_N], Q1[SB_BEZ_N];
            const double um = 0.5 * (R.u0 + R.u1), vm = 0.5 * (R.v0 + R.v1);
            sb_bezier_split_u(R.Ca, 0.5, A0, B0);
            sb_bezier_split_u(R.Cb, 0.5, A1, B1);
            sb_bezier_split_v(A0, 0.5, Q0, A0);
            sb_bezier_split_v(A1, 0.5, Q1, A1);
            rc = push_region(ws, Q0, Q1, R.u0, um, R.v0, vm, R.ta, R.tb, tol, best);
            if (!rc) rc = push_region(ws, A0, A1, R.u0, um, vm, R.v1, R.ta, R.tb, tol, best);
            sb_bezier_split_v(B0, 0.5, Q0, B0);
            sb_bezier_split_v(B1, 0.5, Q1, B1);
            if (!rc) rc = push_region(ws, Q0, Q1, um, R.u1, R.v0, vm, R.ta, R.tb, tol, best);
            if (!rc) rc = push_region(ws, B0, B1, um, R.u1, vm, R.v1, R.ta, R.tb, tol, best);
        }
        if (rc) return -1;
    }
    if (found) ws->counts.hits++;
    return found;
}
