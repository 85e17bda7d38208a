/* sb_self.c — self-contact of the sampled surface: the barrier on the
 * point–triangle and edge–edge pairs of a per-step candidate set, its step
 * filter and its measurements (sb_self.h, docs/contact.md). */
#include "sb_self.h"
#include "sb_self_geom.h"
#include "sb_hash.h"
#include "sb_contact.h"
#include "sb_obstacle.h"
#include "sb_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct sb_self {
    const sb_contact_points *P;
    int np, nt, ne;
    int *edge;                /* 2 ne: point indices, edge[2e] < edge[2e+1] */
    double *rest2;            /* ne: squared rest length */
    double dhat, kappa, filter, margin;
    double *x0;               /* 3 np: sample points at the start of the step */
    double *xp, *dp;          /* 3 np: scratch (current points, step) */
    int *pt, npt, cap_pt;     /* candidate point–triangle pairs (p, t) */
    int *ee, nee, cap_ee;     /* candidate edge–edge pairs (e, f), e < f */
    /* candidate search scratch */
    double radius;
    int cur;
    int nomem;
};

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static int cmp_long(const void *a, const void *b)
{
    const long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

static void eval_points(const sb_self *s, const double *x, double *out)
{
    for (int p = 0; p < s->np; p++) sb_contact_points_eval(s->P, p, x, out + 3 * p);
}

static int push_pair(int **arr, int *n, int *cap, int a, int b)
{
    if (*n == *cap) {
        int nc = *cap ? 2 * *cap : 1024;
        int *q = realloc(*arr, (size_t)2 * nc * sizeof *q);
        if (!q) return SB_ERR_NOMEM;
        *arr = q;
        *cap = nc;
    }
    (*arr)[2 * *n] = a;
    (*arr)[2 * *n + 1] = b;
    (*n)++;
    return SB_OK;
}

static double pt_distance(const sb_self *s, const double *X, int p, int t)
{
    const int *v = s->P->tri + 3 * t;
    double x[12];
    memcpy(x, X + 3 * p, 3 * sizeof(double));
    for (int k = 0; k < 3; k++) memcpy(x + 3 + 3 * k, X + 3 * v[k], 3 * sizeof(double));
    return sqrt(sb_typed_dist2(sb_pt_type(x, x + 3, x + 6, x + 9), x, NULL, NULL));
}

static double ee_distance(const sb_self *s, const double *X, int e, int f)
{
    const int *a = s->edge + 2 * e, *b = s->edge + 2 * f;
    return sb_self_segment_distance(X + 3 * a[0], X + 3 * a[1], X + 3 * b[0], X + 3 * b[1]);
}

/* ---- candidate search (spatial hash) ----------------------------------- */

typedef struct cand_ctx { sb_self *s; const double *X; int q; double dmin; int keep; } cand_ctx;

static int cand_pt(void *data, int t)
{
    cand_ctx *C = data;
    sb_self *s = C->s;
    const int *v = s->P->tri + 3 * t, p = C->q;
    if (v[0] == p || v[1] == p || v[2] == p) return 0;      /* incident */
    const double d = pt_distance(s, C->X, p, t);
    C->dmin = fmin(C->dmin, d);
    if (d < s->radius && C->keep && push_pair(&s->pt, &s->npt, &s->cap_pt, p, t)) return 1;
    return 0;
}

static int cand_ee(void *data, int f)
{
    cand_ctx *C = data;
    sb_self *s = C->s;
    const int e = C->q;
    if (f <= e) return 0;                                   /* each pair once */
    const int *a = s->edge + 2 * e, *b = s->edge + 2 * f;
    if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) return 0;
    const double d = ee_distance(s, C->X, e, f);
    C->dmin = fmin(C->dmin, d);
    if (d < s->radius && C->keep && push_pair(&s->ee, &s->nee, &s->cap_ee, e, f)) return 1;
    return 0;
}

/* all non-incident pairs within radius at the points X (3 np) into the
 * candidate lists (keep = 1), and the smallest distance found */
static int search(sb_self *s, const double *X, double radius, int keep, double *dmin)
{
    s->radius = radius;
    if (keep) s->npt = s->nee = 0;
    double mean = 0;
    for (int e = 0; e < s->ne; e++) mean += sqrt(s->rest2[e]);
    mean = s->ne ? mean / s->ne : radius;
    const double cell = fmax(mean, radius);
    const int nb = s->nt > s->ne ? s->nt : s->ne;
    double *box = malloc((size_t)6 * (nb ? nb : 1) * sizeof *box);
    int *ids = malloc((size_t)(nb ? nb : 1) * sizeof *ids), *stamp = calloc((size_t)(nb ? nb : 1), sizeof *stamp);
    sb_idlist L = { 0, 0, NULL };
    cand_ctx C = { s, X, 0, INFINITY, keep };
    sb_hash h;
    memset(&h, 0, sizeof h);
    int rc = box && ids && stamp ? SB_OK : SB_ERR_NOMEM, mark = 0;
    if (rc) goto out;
    for (int i = 0; i < nb; i++) ids[i] = i;
    /* points against triangles (boxes grown by the radius) */
    for (int t = 0; t < s->nt; t++)
        for (int a = 0; a < 3; a++) {
            const int *v = s->P->tri + 3 * t;
            box[6 * t + a] = fmin(X[3 * v[0] + a], fmin(X[3 * v[1] + a], X[3 * v[2] + a])) - radius;
            box[6 * t + 3 + a] = fmax(X[3 * v[0] + a], fmax(X[3 * v[1] + a], X[3 * v[2] + a])) + radius;
        }
    if (sb_hash_build(&h, s->nt, ids, box, cell)) rc = SB_ERR_NOMEM;
    for (int p = 0; p < s->np && !rc; p++) {
        const double q[6] = { X[3 * p], X[3 * p + 1], X[3 * p + 2], X[3 * p], X[3 * p + 1], X[3 * p + 2] };
        C.q = p;
        if (sb_hash_visit(&h, q, stamp, ++mark, &L, cand_pt, &C)) rc = SB_ERR_NOMEM;
    }
    if (rc) goto out_hash;
    /* edges against edges */
    for (int e = 0; e < s->ne; e++)
        for (int a = 0; a < 3; a++) {
            const int *v = s->edge + 2 * e;
            box[6 * e + a] = fmin(X[3 * v[0] + a], X[3 * v[1] + a]) - radius;
            box[6 * e + 3 + a] = fmax(X[3 * v[0] + a], X[3 * v[1] + a]) + radius;
        }
    if (sb_hash_build(&h, s->ne, ids, box, cell)) rc = SB_ERR_NOMEM;
    for (int e = 0; e < s->ne && !rc; e++) {
        double q[6];
        for (int a = 0; a < 3; a++) { q[a] = box[6 * e + a] + radius; q[3 + a] = box[6 * e + 3 + a] - radius; }
        C.q = e;
        if (sb_hash_visit(&h, q, stamp, ++mark, &L, cand_ee, &C)) rc = SB_ERR_NOMEM;
    }
out_hash:   /* the edge hash reused the triangle hash's arrays */
    sb_hash_free(&h);
out:
    free(box);
    free(ids);
    free(stamp);
    free(L.v);
    if (dmin) *dmin = C.dmin;
    return rc;
}

/* ---- creation ------------------------------------------------------------ */

void sb_self_free(sb_self *s)
{
    if (!s) return;
    free(s->edge); free(s->rest2); free(s->x0); free(s->xp); free(s->dp); free(s->pt); free(s->ee);
    free(s);
}

int sb_self_create(const sb_contact_points *pts, const double *xref, double dhat, double kappa, double filter,
                   sb_self **out, char *why, size_t why_size)
{
    *out = NULL;
    if (pts->nt == 0) {
        snprintf(why, why_size, "the method does not triangulate its contact sample points, which self-contact "
                 "needs for its point–triangle and edge–edge pairs");
        return SB_ERR_UNSUPPORTED;
    }
    sb_self *s = calloc(1, sizeof *s);
    if (!s) return SB_ERR_NOMEM;
    s->P = pts;
    s->np = pts->n;
    s->nt = pts->nt;
    s->dhat = dhat;
    s->kappa = kappa;
    s->filter = filter;
    s->margin = 4 * dhat;
    long *key = malloc((size_t)3 * s->nt * sizeof *key);
    s->x0 = malloc((size_t)3 * s->np * sizeof *s->x0);
    s->xp = malloc((size_t)3 * s->np * sizeof *s->xp);
    s->dp = malloc((size_t)3 * s->np * sizeof *s->dp);
    if (!key || !s->x0 || !s->xp || !s->dp) { free(key); sb_self_free(s); return SB_ERR_NOMEM; }
    /* the edges: each triangle side once */
    for (int t = 0; t < s->nt; t++)
        for (int k = 0; k < 3; k++) {
            long a = pts->tri[3 * t + k], b = pts->tri[3 * t + (k + 1) % 3];
            key[3 * t + k] = a < b ? a * s->np + b : b * s->np + a;
        }
    qsort(key, (size_t)3 * s->nt, sizeof *key, cmp_long);
    int ne = 0;
    for (int i = 0; i < 3 * s->nt; i++)
        if (i == 0 || key[i] != key[i - 1]) key[ne++] = key[i];
    s->ne = ne;
    s->edge = malloc((size_t)2 * ne * sizeof *s->edge);
    s->rest2 = malloc((size_t)ne * sizeof *s->rest2);
    if (!s->edge || !s->rest2) { free(key); sb_self_free(s); return SB_ERR_NOMEM; }
    eval_points(s, xref, s->xp);
    for (int e = 0; e < ne; e++) {
        s->edge[2 * e] = (int)(key[e] / s->np);
        s->edge[2 * e + 1] = (int)(key[e] % s->np);
        const double L = dist3(s->xp + 3 * s->edge[2 * e], s->xp + 3 * s->edge[2 * e + 1]);
        s->rest2[e] = L * L;
    }
    free(key);
    /* the rest state must not touch itself: every non-incident pair at least
       2 dhat apart (half of it leaves room for bending and compression) */
    double dmin = INFINITY;
    int rc = search(s, s->xp, 2 * dhat, 0, &dmin);
    if (rc) { sb_self_free(s); return rc; }
    if (dmin < 2 * dhat) {
        snprintf(why, why_size, "contact.dhat = %g m is not below half the smallest rest distance %g m between "
                 "sample primitives that share no vertex (the rest state would touch itself); use dhat < %g m or "
                 "fewer contact.samples", dhat, dmin, 0.5 * dmin);
        sb_self_free(s);
        return SB_ERR_UNSUPPORTED;
    }
    *out = s;
    return SB_OK;
}

/* ---- per step ------------------------------------------------------------ */

int sb_self_begin_step(sb_self *s, const double *x0, const double *xhat)
{
    eval_points(s, x0, s->x0);
    double move = 0;
    if (xhat) {
        eval_points(s, xhat, s->xp);
        for (int p = 0; p < s->np; p++) move = fmax(move, dist3(s->xp + 3 * p, s->x0 + 3 * p));
    }
    /* assumption: room for four times the inertial prediction's motion, at least 8 dhat */
    s->margin = fmax(8 * s->dhat, 4 * move);
    return search(s, s->x0, s->dhat + s->margin, 1, NULL);
}

int sb_self_n_pairs(const sb_self *s) { return s->npt + s->nee; }
double sb_self_margin(const sb_self *s) { return s->margin; }

void sb_self_pair_points(const sb_self *s, int k, int pts[4])
{
    if (k < s->npt) {
        const int *v = s->P->tri + 3 * s->pt[2 * k + 1];
        pts[0] = s->pt[2 * k];
        pts[1] = v[0]; pts[2] = v[1]; pts[3] = v[2];
        return;
    }
    k -= s->npt;
    const int *a = s->edge + 2 * s->ee[2 * k], *b = s->edge + 2 * s->ee[2 * k + 1];
    pts[0] = a[0]; pts[1] = a[1]; pts[2] = b[0]; pts[3] = b[1];
}

/* ---- energy -------------------------------------------------------------- */

#define MAXD 256   /* distinct term dofs of one pair */

/* g += W^T G, H += W^T Hp W over the four points' terms (upper triangle) */
static int scatter_pair(const sb_self *s, const int pts[4], const double G[12], const double *Hp, double *g,
                        sb_matrix *H)
{
    const sb_contact_points *P = s->P;
    int D[MAXD], m = 0;
    double W[4][MAXD];
    for (int u = 0; u < 4; u++)
        for (int a = P->off[pts[u]]; a < P->off[pts[u] + 1]; a++) {
            int k = 0;
            while (k < m && D[k] != P->dof[a]) k++;
            if (k == m) {
                if (m == MAXD) return SB_ERR_INTERNAL;
                D[m] = P->dof[a];
                for (int v = 0; v < 4; v++) W[v][m] = 0;
                m++;
            }
            W[u][k] += P->w[a];
        }
    if (g)
        for (int k = 0; k < m; k++)
            for (int u = 0; u < 4; u++)
                if (W[u][k] != 0)
                    for (int i = 0; i < 3; i++) g[D[k] + i] += W[u][k] * G[3 * u + i];
    if (!H || !Hp) return SB_OK;
    /* T[u][l] = sum_v W[v][l] Hp[u][v] (3x3 blocks), then B_kl = sum_u W[u][k] T[u][l] */
    double *T = malloc((size_t)4 * m * 9 * sizeof *T);
    if (!T) return SB_ERR_NOMEM;
    for (int u = 0; u < 4; u++)
        for (int l = 0; l < m; l++)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    double t = 0;
                    for (int v = 0; v < 4; v++) t += W[v][l] * Hp[12 * (3 * u + i) + 3 * v + j];
                    T[((u * m + l) * 3 + i) * 3 + j] = t;
                }
    const sb_pattern *pat = H->pat;
    int rc = SB_OK;
    for (int k = 0; k < m && !rc; k++)
        for (int l = 0; l < m && !rc; l++) {
            if (D[k] > D[l]) continue;
            for (int j = 0; j < 3; j++) {
                const long pos = sb_pattern_find(pat, D[k], D[l] + j);
                if (pos < 0) { rc = SB_ERR_INTERNAL; break; }
                for (int i = 0; i < 3; i++) {
                    if (D[k] + i > D[l] + j) break;
                    if (pat->rowind[pos + i] != D[k] + i) { rc = SB_ERR_INTERNAL; break; }
                    double b = 0;
                    for (int u = 0; u < 4; u++) b += W[u][k] * T[((u * m + l) * 3 + i) * 3 + j];
                    H->val[pos + i] += b;
                }
            }
        }
    free(T);
    return rc;
}

/* the barrier of one pair: value, gradient G (12) and Hessian Hp (144) in
 * the four points' positions x (12); 0 beyond dhat, INFINITY at contact */
static double pair_energy(const sb_self *s, int k, const double x[12], double *G, double *Hp, int *active)
{
    const int is_pt = k < s->npt;
    *active = 0;
    /* cheap rejection: the two primitives' boxes more than dhat apart on an axis */
    const int na = is_pt ? 1 : 2;
    for (int a = 0; a < 3; a++) {
        double lo1 = x[a], hi1 = x[a], lo2 = x[3 * na + a], hi2 = x[3 * na + a];
        for (int u = 1; u < na; u++) { lo1 = fmin(lo1, x[3 * u + a]); hi1 = fmax(hi1, x[3 * u + a]); }
        for (int u = na + 1; u < 4; u++) { lo2 = fmin(lo2, x[3 * u + a]); hi2 = fmax(hi2, x[3 * u + a]); }
        if (lo1 > hi2 + s->dhat || lo2 > hi1 + s->dhat) return 0.0;
    }
    const sb_dist_type type = is_pt ? sb_pt_type(x, x + 3, x + 6, x + 9) : sb_ee_type(x, x + 3, x + 6, x + 9);
    double g2[12], H2[144];
    double d2 = sb_typed_dist2(type, x, NULL, NULL);
    if (d2 >= s->dhat * s->dhat) return 0.0;
    if (!(d2 > 0)) return INFINITY;
    d2 = sb_typed_dist2(type, x, g2, Hp ? H2 : NULL);
    *active = 1;
    const sb_contact_points *P = s->P;
    int pts[4];
    sb_self_pair_points(s, k, pts);
    /* weight: the point's reference area (point–triangle); the mean of the
       four endpoints' areas (edge–edge) — assumption */
    const double a = is_pt ? P->area[pts[0]]
                           : 0.25 * (P->area[pts[0]] + P->area[pts[1]] + P->area[pts[2]] + P->area[pts[3]]);
    const double kap = s->kappa * a;
    const double d = sqrt(d2);
    double db, ddb;
    const double b = sb_barrier(d, s->dhat, &db, &ddb);   /* IPC Eq. (6) */
    /* chain rule through d = sqrt(d2): grad d = g2 / (2d),
       Hess d = H2 / (2d) - g2 g2^T / (4 d^3) */
    double gb[12], Hb[144];
    for (int p = 0; p < 12; p++) gb[p] = kap * db * g2[p] / (2 * d);
    if (Hp)
        for (int p = 0; p < 12; p++)
            for (int q = 0; q < 12; q++) {
                const double gd = g2[p] * g2[q] / (4 * d2);
                const double hd = H2[12 * p + q] / (2 * d) - g2[p] * g2[q] / (4 * d2 * d);
                Hb[12 * p + q] = kap * (ddb * gd + db * hd);
            }
    if (is_pt) {
        if (G) memcpy(G, gb, sizeof gb);
        if (Hp) memcpy(Hp, Hb, sizeof Hb);
        return kap * b;
    }
    /* edge–edge: mollified, m b (IPC §4.3), product rule */
    const int e = s->ee[2 * (k - s->npt)], f = s->ee[2 * (k - s->npt) + 1];
    const double eps_x = 1e-3 * s->rest2[e] * s->rest2[f];
    double gm[12], Hm[144];
    const double mo = sb_ee_mollifier(x, eps_x, G ? gm : NULL, Hp ? Hm : NULL);
    if (G)
        for (int p = 0; p < 12; p++) G[p] = mo * gb[p] + kap * b * gm[p];
    if (Hp)
        for (int p = 0; p < 12; p++)
            for (int q = 0; q < 12; q++)
                Hp[12 * p + q] = mo * Hb[12 * p + q] + gm[p] * gb[q] + gb[p] * gm[q] + kap * b * Hm[12 * p + q];
    return kap * mo * b;
}

int sb_self_energy(sb_self *s, const double *x, double *e, double *g, sb_matrix *H)
{
    eval_points(s, x, s->xp);
    double sum = 0, G[12], Hp[144];
    const int n = s->npt + s->nee;
    for (int k = 0; k < n; k++) {
        int pts[4], active;
        sb_self_pair_points(s, k, pts);
        double X[12];
        for (int u = 0; u < 4; u++) memcpy(X + 3 * u, s->xp + 3 * pts[u], 3 * sizeof(double));
        const double v = pair_energy(s, k, X, g ? G : NULL, H ? Hp : NULL, &active);
        if (!active) continue;
        if (!isfinite(v)) { *e = INFINITY; return SB_NONFINITE; }
        sum += v;
        int rc = scatter_pair(s, pts, G, H ? Hp : NULL, g, H);
        if (rc) return rc;
    }
    *e += sum;
    return SB_OK;
}

/* ---- step filter --------------------------------------------------------- */

double sb_self_step_bound(sb_self *s, const double *x, const double *d)
{
    eval_points(s, x, s->xp);
    eval_points(s, d, s->dp);
    /* the margin: |x_p - x0_p + alpha d_p| <= margin / 2 */
    const double r = 0.5 * s->margin;
    double alpha = 1.0;
    for (int p = 0; p < s->np; p++) {
        const double *dp = s->dp + 3 * p;
        double e[3], ed = 0, ee = 0, dd = 0;
        for (int a = 0; a < 3; a++) {
            e[a] = s->xp[3 * p + a] - s->x0[3 * p + a];
            ed += e[a] * dp[a];
            ee += e[a] * e[a];
            dd += dp[a] * dp[a];
        }
        if (!(dd > 0)) continue;
        const double disc = ed * ed + dd * fmax(0.0, r * r - ee);
        const double ap = (-ed + sqrt(disc)) / dd;
        alpha = fmin(alpha, fmax(0.0, ap));
    }
    /* continuous collision of the candidate pairs along the step */
    double toi = 2.0;
    for (int k = 0; k < s->npt + s->nee; k++) {
        int pts[4];
        sb_self_pair_points(s, k, pts);
        const double *X[4];
        double Y[4][3];
        int moving = 0;
        for (int u = 0; u < 4; u++) {
            X[u] = s->xp + 3 * pts[u];
            for (int a = 0; a < 3; a++) {
                Y[u][a] = X[u][a] + s->dp[3 * pts[u] + a];
                moving |= s->dp[3 * pts[u] + a] != 0;
            }
        }
        if (!moving) continue;
        /* the swept boxes of the two primitives apart on an axis: no impact
           (every point of a primitive stays in the box of its vertices' paths) */
        const int na = k < s->npt ? 1 : 2;
        int apart = 0;
        for (int a = 0; a < 3 && !apart; a++) {
            double lo1 = INFINITY, hi1 = -INFINITY, lo2 = INFINITY, hi2 = -INFINITY;
            for (int u = 0; u < 4; u++) {
                const double l = fmin(X[u][a], Y[u][a]), h = fmax(X[u][a], Y[u][a]);
                if (u < na) { lo1 = fmin(lo1, l); hi1 = fmax(hi1, h); }
                else { lo2 = fmin(lo2, l); hi2 = fmax(hi2, h); }
            }
            apart = lo1 > hi2 || lo2 > hi1;
        }
        if (apart) continue;
        const double t = k < s->npt ? sb_ccd_point_triangle(X[0], Y[0], X[1], Y[1], X[2], Y[2], X[3], Y[3])
                                    : sb_ccd_edge_edge(X[0], Y[0], X[1], Y[1], X[2], Y[2], X[3], Y[3]);
        toi = fmin(toi, t);
    }
    if (toi <= 1.0) alpha = fmin(alpha, s->filter * toi);
    return alpha;
}

/* ---- measurement ----------------------------------------------------------- */

typedef struct cross_ctx { const sb_self *s; int e; int count; } cross_ctx;

static int cross_tri(void *data, int t)
{
    cross_ctx *C = data;
    const sb_self *s = C->s;
    const int *v = s->P->tri + 3 * t, *a = s->edge + 2 * C->e;
    for (int i = 0; i < 3; i++)
        if (v[i] == a[0] || v[i] == a[1]) return 0;
    const double *X = s->xp;
    const int hit = sb_segment_triangle_intersect(X + 3 * a[0], X + 3 * a[1], X + 3 * v[0], X + 3 * v[1], X + 3 * v[2]);
    C->count += hit;
    return 0;
}

int sb_self_measure(sb_self *s, const double *x, sb_self_report *r)
{
    memset(r, 0, sizeof *r);
    r->pairs = s->npt + s->nee;
    r->min_distance = INFINITY;
    eval_points(s, x, s->xp);
    for (int p = 0; p < s->np; p++) r->max_move = fmax(r->max_move, dist3(s->xp + 3 * p, s->x0 + 3 * p));
    for (int k = 0; k < s->npt; k++) {
        const double d = pt_distance(s, s->xp, s->pt[2 * k], s->pt[2 * k + 1]);
        r->min_distance = fmin(r->min_distance, d);
        r->active += d < s->dhat;
    }
    for (int k = 0; k < s->nee; k++) {
        const double d = ee_distance(s, s->xp, s->ee[2 * k], s->ee[2 * k + 1]);
        r->min_distance = fmin(r->min_distance, d);
        r->active += d < s->dhat;
    }
    /* every edge against every triangle, hashed (no candidate set) */
    double *box = malloc((size_t)6 * (s->nt ? s->nt : 1) * sizeof *box);
    int *ids = malloc((size_t)(s->nt ? s->nt : 1) * sizeof *ids), *stamp = calloc((size_t)(s->nt ? s->nt : 1), sizeof *stamp);
    sb_idlist L = { 0, 0, NULL };
    int rc = box && ids && stamp ? SB_OK : SB_ERR_NOMEM;
    double mean = 0;
    for (int e = 0; e < s->ne; e++) mean += sqrt(s->rest2[e]);
    mean /= s->ne;
    for (int t = 0; t < s->nt && !rc; t++) {
        ids[t] = t;
        for (int a = 0; a < 3; a++) {
            const int *v = s->P->tri + 3 * t;
            box[6 * t + a] = fmin(s->xp[3 * v[0] + a], fmin(s->xp[3 * v[1] + a], s->xp[3 * v[2] + a]));
            box[6 * t + 3 + a] = fmax(s->xp[3 * v[0] + a], fmax(s->xp[3 * v[1] + a], s->xp[3 * v[2] + a]));
        }
    }
    sb_hash h;
    memset(&h, 0, sizeof h);
    if (!rc && sb_hash_build(&h, s->nt, ids, box, mean > 0 ? mean : 1.0)) rc = SB_ERR_NOMEM;
    if (!rc) {
        cross_ctx C = { s, 0, 0 };
        for (int e = 0; e < s->ne && !rc; e++) {
            const int *a = s->edge + 2 * e;
            double q[6];
            for (int k = 0; k < 3; k++) {
                q[k] = fmin(s->xp[3 * a[0] + k], s->xp[3 * a[1] + k]);
                q[3 + k] = fmax(s->xp[3 * a[0] + k], s->xp[3 * a[1] + k]);
            }
            C.e = e;
            if (sb_hash_visit(&h, q, stamp, e + 1, &L, cross_tri, &C) < 0) rc = SB_ERR_NOMEM;
        }
        r->crossings = C.count;
    }
    sb_hash_free(&h);
    free(box);
    free(ids);
    free(stamp);
    free(L.v);
    return rc;
}
