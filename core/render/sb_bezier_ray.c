/* sb_bezier_ray.c — ray–patch intersection by subdivision and by
 * subdivision with Newton's method (BHEM paper §5.1), and the min-heap of
 * sub-patches they share with Bézier clipping (sb_bezier_clip.c). */
#include "sb_bezier_ray.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const sb_isect_names[] = { "subdivision", "newton", "clipping", "clipping-dfs", NULL };

int sb_isect_find(const char *name)
{
    for (int k = 0; sb_isect_names[k]; k++)
        if (!strcmp(name, sb_isect_names[k])) return k;
    return -1;
}

/* ---- the workspace: a pool of regions and a binary min-heap of indices --- */

sb_bezier_ws *sb_bezier_ws_new(void) { return calloc(1, sizeof(sb_bezier_ws)); }

void sb_bezier_ws_free(sb_bezier_ws *ws)
{
    if (!ws) return;
    free(ws->pool);
    free(ws->heap);
    free(ws->freel);
    free(ws);
}

sb_isect_counts *sb_bezier_ws_counts(sb_bezier_ws *ws) { return &ws->counts; }

void sb_bez_reset(sb_bezier_ws *ws) { ws->n_heap = ws->n_free = ws->n_used = 0; }

int sb_bez_new(sb_bezier_ws *ws)
{
    if (ws->n_free > 0) return ws->freel[--ws->n_free];
    if (ws->n_used == ws->cap) {
        int cap = ws->cap ? 2 * ws->cap : 256;
        sb_bez_region *p = realloc(ws->pool, (size_t)cap * sizeof *p);
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

void sb_bez_release(sb_bezier_ws *ws, int idx) { ws->freel[ws->n_free++] = idx; }

void sb_bez_push(sb_bezier_ws *ws, int idx)
{
    int *h = ws->heap, i = ws->n_heap++;
    const double k = ws->pool[idx].key;
    while (i > 0) {
        int p = (i - 1) / 2;
        if (ws->pool[h[p]].key <= k) break;
        h[i] = h[p];
        i = p;
    }
    h[i] = idx;
}

int sb_bez_pop(sb_bezier_ws *ws)
{
    if (ws->n_heap == 0) return -1;
    int *h = ws->heap, top = h[0], last = h[--ws->n_heap], n = ws->n_heap, i = 0;
    const double k = ws->pool[last].key;
    for (;;) {
        int c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && ws->pool[h[c + 1]].key < ws->pool[h[c]].key) c++;
        if (ws->pool[h[c]].key >= k) break;
        h[i] = h[c];
        i = c;
    }
    if (n > 0) h[i] = last;
    return top;
}

/* ---- helpers ------------------------------------------------------------- */

static double box_extent(const double lo[3], const double hi[3])
{
    return fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
}

/* Push the sub-patch Q over [u0,u1]x[v0,v1] if the ray enters its box before
 * `limit`.  Returns -1 on out of memory. */
static int push_region(sb_bezier_ws *ws, const double *Q, double u0, double u1, double v0, double v1,
                       const sb_ray *r, double tmax, double limit)
{
    double lo[3], hi[3], t0, t1;
    ws->counts.splits++;
    sb_bezier_bounds(Q, lo, hi);
    if (!sb_ray_box(r, lo, hi, tmax, &t0, &t1) || !(t0 < limit)) return 0;
    int k = sb_bez_new(ws);
    if (k < 0) return -1;
    sb_bez_region *R = &ws->pool[k];
    memcpy(R->P, Q, sizeof R->P);
    R->u0 = u0; R->u1 = u1; R->v0 = v0; R->v1 = v1;
    R->key = t0;
    sb_bez_push(ws, k);
    return 0;
}

/* Fig. 10a: split at the midpoint into four. R is copied first: the pool may move. */
static int split_mid(sb_bezier_ws *ws, const sb_bez_region *Rp, const sb_ray *r, double tmax, double limit)
{
    sb_bez_region R = *Rp;
    double A[SB_BEZ_N], B[SB_BEZ_N], Q[SB_BEZ_N];
    const double um = 0.5 * (R.u0 + R.u1), vm = 0.5 * (R.v0 + R.v1);
    sb_bezier_split_u(R.P, 0.5, A, B);
    sb_bezier_split_v(A, 0.5, Q, A);
    if (push_region(ws, Q, R.u0, um, R.v0, vm, r, tmax, limit)) return -1;
    if (push_region(ws, A, R.u0, um, vm, R.v1, r, tmax, limit)) return -1;
    sb_bezier_split_v(B, 0.5, Q, B);
    if (push_region(ws, Q, um, R.u1, R.v0, vm, r, tmax, limit)) return -1;
    if (push_region(ws, B, um, R.u1, vm, R.v1, r, tmax, limit)) return -1;
    return 0;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* 3x3 inverse (columns c0, c1, c2) into Ji (row-major); returns det. */
static double inverse3(const double c0[3], const double c1[3], const double c2[3], double Ji[9])
{
    /* rows of the inverse are the cross products of the columns over det */
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

#define NEWTON_ITERS 8

/* Newton's method on F(a,b,tau) = x(a,b) - o - tau d over the sub-patch Q
 * (local parameters a, b), from its centre.  Returns 1 when it converges
 * (|F| <= tol) with (a,b) in [0,1]^2; Ji is then J^-1 at the root.  A run
 * that does not contract (a step in (a,b) longer than half the previous one
 * after the second, or an iterate far outside the sub-patch) is abandoned
 * early: it would not converge inside the sub-patch within the fixed
 * number of iterations (our safeguard; the paper fixes only the count). */
static int newton(const double *Q, const sb_ray *r, double tol, double *a, double *b, double *tau, double Ji[9])
{
    double x[3], xa[3], xb[3], F[3], md[3] = { -r->d[0], -r->d[1], -r->d[2] };
    double A = 0.5, B = 0.5, prev = INFINITY;
    sb_bezier_eval(Q, A, B, x, NULL, NULL);
    double T = (x[0] - r->o[0]) * r->d[0] + (x[1] - r->o[1]) * r->d[1] + (x[2] - r->o[2]) * r->d[2];
    for (int it = 0; it <= NEWTON_ITERS; it++) {
        sb_bezier_eval(Q, A, B, x, xa, xb);
        for (int c = 0; c < 3; c++) F[c] = x[c] - r->o[c] - T * r->d[c];
        if (inverse3(xa, xb, md, Ji) == 0.0) return 0;
        if (sqrt(dot3(F, F)) <= tol) {
            if (A < 0.0 || A > 1.0 || B < 0.0 || B > 1.0) return 0;
            *a = A; *b = B; *tau = T;
            return 1;
        }
        if (it == NEWTON_ITERS) break;
        const double dA = dot3(Ji, F), dB = dot3(Ji + 3, F);
        A -= dA;
        B -= dB;
        T -= dot3(Ji + 6, F);
        const double step = fabs(dA) + fabs(dB);
        if (!(A > -0.5 && A < 1.5 && B > -0.5 && B < 1.5)) return 0;   /* left the neighbourhood */
        if (it >= 2 && step > 0.5 * prev) return 0;                    /* not contracting */
        prev = step;
    }
    return 0;
}

/* Half-width h (local parameters, infinity norm) of a square around the
 * root (a,b) of the sub-patch Q inside which it is the only root.
 * Newton–Kantorovich-type argument (our derivation; the paper does not say
 * how large the abandoned neighbourhood is): with beta >= |J(r)^-1| and
 * gamma a Lipschitz constant of J over the (convex) sub-patch,
 * F(z) = J(r)(z - r) + E, |E| <= gamma/2 |z - r|^2, so F(z) != 0 for
 * 0 < |z - r| < 2/(beta gamma).  A root z with (a,b) within h of r has
 * |tau_z - tau_r| <= (L_a + L_b) h (|d| = 1), so |z - r| <= h sqrt(2 + (L_a + L_b)^2). */
static double unique_radius(const double *Q, const double Ji[9])
{
    double L[2], M[3];
    sb_bezier_derivative_bounds(Q, L, M);
    double beta = 0;
    for (int k = 0; k < 9; k++) beta += Ji[k] * Ji[k];
    beta = sqrt(beta);   /* Frobenius >= spectral norm */
    const double gamma = sqrt((M[0] + M[1]) * (M[0] + M[1]) + (M[1] + M[2]) * (M[1] + M[2]));
    if (gamma * beta == 0.0) return 1.0;   /* F is affine: the root is unique in the sub-patch */
    const double rho = 2.0 / (beta * gamma);
    return 0.9 * rho / sqrt(2.0 + (L[0] + L[1]) * (L[0] + L[1]));
}

/* Fig. 10b: abandon the square [a-h,a+h]x[b-h,b+h] of R and push the (up to
 * eight) rectangles of R around it. */
static int split_around(sb_bezier_ws *ws, const sb_bez_region *Rp, double a, double b, double h, const sb_ray *r,
                        double tmax, double limit)
{
    sb_bez_region R = *Rp;
    const double tiny = 1e-9;
    double ca[4] = { 0, fmax(0.0, a - h), fmin(1.0, a + h), 1 }, cb[4] = { 0, fmax(0.0, b - h), fmin(1.0, b + h), 1 };
    if (ca[1] < tiny) ca[1] = 0;
    if (ca[2] > 1 - tiny) ca[2] = 1;
    if (cb[1] < tiny) cb[1] = 0;
    if (cb[2] > 1 - tiny) cb[2] = 1;
    const double wu = R.u1 - R.u0, wv = R.v1 - R.v0;
    double Q[SB_BEZ_N];
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            if (i == 1 && j == 1) continue;   /* the abandoned neighbourhood */
            if (!(ca[i + 1] > ca[i]) || !(cb[j + 1] > cb[j])) continue;
            sb_bezier_sub(R.P, ca[i], ca[i + 1], cb[j], cb[j + 1], Q);
            if (push_region(ws, Q, R.u0 + wu * ca[i], R.u0 + wu * ca[i + 1], R.v0 + wv * cb[j], R.v0 + wv * cb[j + 1], r,
                            tmax, limit))
                return -1;
        }
    return 0;
}

/* Subdivision (newton = 0) and subdivision + Newton (newton = 1). */
static int heap_intersect(int use_newton, const double *P, const double *lo, const double *hi, const sb_ray *r,
                          double tmax, double eps, sb_bezier_ws *ws, sb_patch_hit *hit)
{
    double blo[3], bhi[3], t0, t1;
    if (!lo || !hi) {
        sb_bezier_bounds(P, blo, bhi);
        lo = blo;
        hi = bhi;
    }
    if (!sb_ray_box(r, lo, hi, tmax, &t0, &t1)) return 0;
    sb_bez_reset(ws);
    int k = sb_bez_new(ws);
    if (k < 0) return -1;
    sb_bez_region *R0 = &ws->pool[k];
    memcpy(R0->P, P, sizeof R0->P);
    R0->u0 = R0->v0 = 0.0;
    R0->u1 = R0->v1 = 1.0;
    R0->key = t0;
    sb_bez_push(ws, k);

    int found = 0;
    double best = tmax, limit = tmax;   /* limit: regions entering at or after it cannot hold a closer root */
    long budget = SB_BEZ_BUDGET;
    const double ntol = 1e-3 * eps;
    int idx;
    while ((idx = sb_bez_pop(ws)) >= 0) {
        sb_bez_region *R = &ws->pool[idx];
        ws->counts.regions++;
        if (!(R->key < limit)) { sb_bez_release(ws, idx); break; }   /* heap min past tau_opt: done */
        if (--budget < 0) { ws->counts.budget++; sb_bez_release(ws, idx); break; }
        double rlo[3], rhi[3];
        sb_bezier_bounds(R->P, rlo, rhi);
        if (box_extent(rlo, rhi) <= eps || (R->u1 - R->u0 < 1e-13 && R->v1 - R->v0 < 1e-13)) {
            /* converged sub-patch: its centre is within eps of the root */
            double x[3];
            sb_bezier_eval(R->P, 0.5, 0.5, x, NULL, NULL);
            double t = fmax(R->key, (x[0] - r->o[0]) * r->d[0] + (x[1] - r->o[1]) * r->d[1] + (x[2] - r->o[2]) * r->d[2]);
            if (t > r->tmin && t < best) {
                best = t;
                hit->t = t;
                hit->u = 0.5 * (R->u0 + R->u1);
                hit->v = 0.5 * (R->v0 + R->v1);
                found = 1;
                limit = best - eps;
            }
            sb_bez_release(ws, idx);
            if (!use_newton) break;   /* the heap order makes it the first hit (§5.1) */
            continue;
        }
        if (use_newton) {
            double a, b, tau, Ji[9];
            ws->counts.newton++;
            if (newton(R->P, r, ntol, &a, &b, &tau, Ji) && tau > r->tmin && tau < best + eps) {
                ws->counts.newton_roots++;
                if (tau < best) {
                    best = tau;
                    hit->t = tau;
                    hit->u = R->u0 + a * (R->u1 - R->u0);
                    hit->v = R->v0 + b * (R->v1 - R->v0);
                    found = 1;
                    limit = best - eps;
                }
                const double h = unique_radius(R->P, Ji);
                if (h >= 0.02) {
                    ws->counts.excluded++;
                    int rc = h >= 1.0 ? 0 : split_around(ws, R, a, b, h, r, tmax, limit);
                    sb_bez_release(ws, idx);
                    if (rc) return -1;
                    continue;
                }
            }
        }
        int rc = split_mid(ws, R, r, tmax, limit);
        sb_bez_release(ws, idx);
        if (rc) return -1;
    }
    return found;
}

int sb_bezier_intersect(sb_isect_kind kind, const double *P, const double *lo, const double *hi, const sb_ray *r,
                        double tmax, double eps, sb_bezier_ws *ws, sb_patch_hit *hit)
{
    ws->counts.calls++;
    int rc;
    switch (kind) {
    case SB_ISECT_SUBDIVISION: rc = heap_intersect(0, P, lo, hi, r, tmax, eps, ws, hit); break;
    case SB_ISECT_NEWTON: rc = heap_intersect(1, P, lo, hi, r, tmax, eps, ws, hit); break;
    case SB_ISECT_CLIPPING:
    case SB_ISECT_CLIPPING_DFS: {
        double t0, t1;
        double blo[3], bhi[3];
        if (!lo || !hi) {
            sb_bezier_bounds(P, blo, bhi);
            lo = blo;
            hi = bhi;
        }
        rc = !sb_ray_box(r, lo, hi, tmax, &t0, &t1) ? 0
             : kind == SB_ISECT_CLIPPING ? sb_bezier_clip_intersect(P, r, tmax, eps, ws, hit)
                                         : sb_bezier_clip_dfs_intersect(P, r, tmax, eps, ws, hit);
        break;
    }
    default: rc = 0;
    }
    if (rc > 0) ws->counts.hits++;
    return rc;
}
