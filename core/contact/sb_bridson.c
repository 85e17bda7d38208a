/* sb_bridson.c — one step of Bridson, Fedkiw & Anderson 2002's collision
 * response (sb_bridson.h): proximity impulses with friction, up to five
 * passes of continuous collision detection resolved by impulses, then rigid
 * impact zones until no collision is left.
 *
 * The system.  The cloth's vertices come first (object 0, masses given,
 * Dirichlet vertices infinite), then the vertices of every mesh obstacle
 * (object 1 + o, infinite mass, positions from the obstacle's poses at t_n
 * and t_{n+1}, so their velocity is the obstacle's).  Triangles and edges of
 * all objects are listed with their object; a pair is tested when it joins
 * the cloth with an obstacle, or the cloth with itself (contact.self) and
 * the two primitives share no vertex.  Analytic obstacles (sphere,
 * half-space, box, capsule) are tested per cloth vertex by their signed
 * distance (proximity) and the closed-form time of impact sb_obstacle_toi
 * (CCD), in the obstacle's frame at t_{n+1} (the vertex's start carried by
 * the obstacle's motion over the step: exact for translations, first order
 * for rotations).
 *
 * The impulse of a pair.  Its relative velocity is vrel = sum_k c_k v_k (-
 * the obstacle's velocity for an analytic obstacle) with c = (1, -w_a, -w_b,
 * -w_c) for a point and the closest point w of a triangle, and
 * c = (1 - s, s, -(1 - t), -t) for the closest points of two edges (Bridson
 * §7.1).  Asking for a change J of vrel, the vertices get
 *   dv_k = c_k m_k^-1 J / sum_j c_j^2 m_j^-1,
 * the mass-weighted form of Bridson's I~ = 2 I / (1 + sum w^2) (§7.1, which
 * is this with equal masses); vertices of infinite mass do not move.
 * J = dv_N n + dv_T: the normal part brings vrel.n up to a target (proximity:
 * 0.1 (h - d)/dt, Bridson §7.2's repulsion cap; collision: the velocity that
 * leaves the pair 0.1 h apart at t_{n+1} along n), the tangential part is
 * Coulomb friction dv_T = -min(mu dv_N / |v_T|, 1) v_T (Bridson §7.2).
 * mu is the obstacle's friction; self-contact is frictionless (the scene
 * format has no cloth–cloth coefficient).
 *
 * Impact zones (Bridson §7.4).  Union–find over the cloth vertices plus one
 * node per obstacle.  Each pass merges the nodes of every pair still
 * colliding; a zone of finite masses moves rigidly with its linear and
 * angular momentum (sb_rigid_zone); a zone that holds an obstacle moves with
 * that obstacle (its infinite mass fixes the rigid motion); a zone that holds
 * Dirichlet vertices (infinite mass, no obstacle) translates with their mean
 * velocity (our choice: no momentum can be conserved against a prescribed
 * motion).  At most 100 passes; a collision left then is counted in
 * unresolved_steps. */
#include "sb_bridson.h"
#include "sb_hash.h"
#include "sb_self_geom.h"
#include "sb_obstacle.h"
#include "sb_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { CCD_PASSES = 5, ZONE_PASSES = 100 };

typedef struct sys {
    int nv, n, nt, ne, nobj;          /* cloth vertices, all vertices, triangles, edges, objects */
    double *x0, *v, *w;               /* 3n, 3n, n */
    int *vobj, *tri, *tobj, *edge, *eobj;
    double *tbox, *ebox;              /* swept boxes, 6 per primitive */
    int *tstamp, *estamp, mark;
    sb_hash *th, *eh;                /* per object */
    sb_idlist cand;
    int *ids;
    double h, dt, cell, delta;
    int self;
    const sb_scene *sc;
    sb_pose P0[SB_SCENE_MAX_OBSTACLES], P1[SB_SCENE_MAX_OBSTACLES];
    int *parent;                      /* union-find over nv + n_obstacles nodes */
    int hits;                         /* collisions found in the current pass */
    int resolve;                      /* 1: resolve hits by impulses; 0: merge them into zones */
    sb_impulse_stats *st;
} sys;

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static int normalize(double n[3])
{
    double l = sqrt(dot3(n, n));
    if (!(l > 0) || !isfinite(l)) return 0;
    for (int i = 0; i < 3; i++) n[i] /= l;
    return 1;
}

/* ---- union-find ---------------------------------------------------------- */
static int uf_find(int *p, int i)
{
    while (p[i] != i) { p[i] = p[p[i]]; i = p[i]; }
    return i;
}
static void uf_union(int *p, int a, int b)
{
    a = uf_find(p, a);
    b = uf_find(p, b);
    if (a != b) p[a < b ? b : a] = a < b ? a : b;
}
/* the union-find node of system vertex i: itself for the cloth, its obstacle otherwise */
static int node_of(const sys *S, int i) { return i < S->nv ? i : S->nv + S->vobj[i] - 1; }

/* ---- the impulse of one pair ---------------------------------------------- */
/* vrel = sum c_k v_idx[k] - vb; bring vrel.n up to vn_target with friction mu */
static int apply_impulse(sys *S, int k, const int *idx, const double *c, const double n[3], const double vb[3],
                         double vn_target, double mu)
{
    double vrel[3], den = 0;
    for (int i = 0; i < 3; i++) vrel[i] = vb ? -vb[i] : 0.0;
    for (int j = 0; j < k; j++) {
        for (int i = 0; i < 3; i++) vrel[i] += c[j] * S->v[3 * idx[j] + i];
        den += c[j] * c[j] * S->w[idx[j]];
    }
    const double vn = dot3(vrel, n);
    if (!(vn < vn_target) || !(den > 0)) return 0;
    const double dvn = vn_target - vn;
    double vt[3], J[3];
    for (int i = 0; i < 3; i++) vt[i] = vrel[i] - vn * n[i];
    const double lt = sqrt(dot3(vt, vt));
    const double f = lt > 0 ? fmin(mu * dvn / lt, 1.0) : 0.0;   /* Bridson §7.2 friction */
    for (int i = 0; i < 3; i++) J[i] = dvn * n[i] - f * vt[i];
    for (int j = 0; j < k; j++)
        for (int i = 0; i < 3; i++) S->v[3 * idx[j] + i] += c[j] * S->w[idx[j]] * J[i] / den;
    return 1;
}

/* the obstacle index of mesh object b (b >= 1) */
static int mesh_obstacle(const sb_scene *sc, int b)
{
    for (int o = 0, k = 0; o < sc->n_obstacles; o++)
        if (sc->obstacles[o].kind == SB_OBST_MESH && ++k == b) return o;
    return -1;
}

static double pair_mu(const sys *S, int k, const int *idx)
{
    for (int j = 0; j < k; j++)
        if (S->vobj[idx[j]] > 0) return S->sc->obstacles[mesh_obstacle(S->sc, S->vobj[idx[j]])].friction;
    return 0.0;
}

/* ---- set-up ----------------------------------------------------------------- */
static int cmp_edge(const void *a, const void *b)
{
    const int *x = a, *y = b;
    return x[0] != y[0] ? (x[0] > y[0]) - (x[0] < y[0]) : (x[1] > y[1]) - (x[1] < y[1]);
}

static int sys_build(sys *S, const sb_bridson_mesh *m, const sb_scene *sc, double dt, double t1, const double *x0,
                     const double *x1)
{
    const int step = (int)lround(t1 / dt);
    S->sc = sc;
    S->dt = dt;
    S->h = sc->contact.dhat;
    S->delta = 0.1 * S->h;
    S->self = sc->contact.self;
    S->nv = m->nv;
    S->nobj = 1;
    int n = m->nv, nt = m->nt;
    for (int o = 0; o < sc->n_obstacles; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        sb_pose_at(ob, sb_obstacle_motion_factor(sc, ob, step - 1), &S->P0[o]);
        sb_pose_at(ob, sb_obstacle_motion_factor(sc, ob, step), &S->P1[o]);
        if (ob->kind == SB_OBST_MESH) { n += ob->nv; nt += ob->nt; S->nobj++; }
    }
    S->n = n;
    S->nt = nt;
    S->x0 = malloc((size_t)3 * n * sizeof(double));
    S->v = malloc((size_t)3 * n * sizeof(double));
    S->w = malloc((size_t)n * sizeof(double));
    S->vobj = malloc((size_t)n * sizeof(int));
    S->tri = malloc((size_t)(3 * nt + 1) * sizeof(int));
    S->tobj = malloc((size_t)(nt + 1) * sizeof(int));
    int *pairs = malloc((size_t)(6 * nt + 1) * sizeof(int));
    S->parent = malloc((size_t)(m->nv + sc->n_obstacles + 1) * sizeof(int));
    if (!S->x0 || !S->v || !S->w || !S->vobj || !S->tri || !S->tobj || !pairs || !S->parent) { free(pairs); return SB_ERR_NOMEM; }
    for (int i = 0; i < m->nv; i++) {
        for (int c = 0; c < 3; c++) {
            S->x0[3 * i + c] = x0[3 * i + c];
            S->v[3 * i + c] = (x1[3 * i + c] - x0[3 * i + c]) / dt;
        }
        S->w[i] = m->inv_mass[i];
        S->vobj[i] = 0;
    }
    if (m->nt) memcpy(S->tri, m->tri, (size_t)3 * m->nt * sizeof(int));
    for (int t = 0; t < m->nt; t++) S->tobj[t] = 0;
    for (int b = 1, vo = m->nv, to = m->nt; b < S->nobj; b++) {
        const sb_obstacle_spec *ob = &sc->obstacles[mesh_obstacle(sc, b)];
        const int o = mesh_obstacle(sc, b);
        for (int i = 0; i < ob->nv; i++) {
            double a[3], e[3];
            sb_pose_apply(&S->P0[o], ob->verts + 3 * i, a);
            sb_pose_apply(&S->P1[o], ob->verts + 3 * i, e);
            for (int c = 0; c < 3; c++) {
                S->x0[3 * (vo + i) + c] = a[c];
                S->v[3 * (vo + i) + c] = (e[c] - a[c]) / dt;
            }
            S->w[vo + i] = 0.0;
            S->vobj[vo + i] = b;
        }
        for (int t = 0; t < ob->nt; t++) {
            for (int k = 0; k < 3; k++) S->tri[3 * (to + t) + k] = vo + ob->tris[3 * t + k];
            S->tobj[to + t] = b;
        }
        vo += ob->nv;
        to += ob->nt;
    }
    /* unique edges of all triangles (an edge belongs to one object) */
    for (int t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            int a = S->tri[3 * t + k], b = S->tri[3 * t + (k + 1) % 3];
            pairs[6 * t + 2 * k] = a < b ? a : b;
            pairs[6 * t + 2 * k + 1] = a < b ? b : a;
        }
    qsort(pairs, (size_t)3 * nt, 2 * sizeof(int), cmp_edge);
    int ne = 0;
    for (int k = 0; k < 3 * nt; k++)
        if (ne == 0 || pairs[2 * k] != pairs[2 * (ne - 1)] || pairs[2 * k + 1] != pairs[2 * (ne - 1) + 1]) {
            pairs[2 * ne] = pairs[2 * k];
            pairs[2 * ne + 1] = pairs[2 * k + 1];
            ne++;
        }
    S->edge = pairs;
    S->ne = ne;
    S->eobj = malloc((size_t)(ne + 1) * sizeof(int));
    S->tbox = malloc((size_t)(6 * nt + 1) * sizeof(double));
    S->ebox = malloc((size_t)(6 * ne + 1) * sizeof(double));
    S->tstamp = calloc((size_t)nt + 1, sizeof(int));
    S->estamp = calloc((size_t)ne + 1, sizeof(int));
    S->th = calloc((size_t)S->nobj, sizeof(sb_hash));
    S->eh = calloc((size_t)S->nobj, sizeof(sb_hash));
    S->ids = malloc((size_t)(nt + ne + 1) * sizeof(int));
    if (!S->eobj || !S->tbox || !S->ebox || !S->tstamp || !S->estamp || !S->th || !S->eh || !S->ids) return SB_ERR_NOMEM;
    for (int e = 0; e < ne; e++) S->eobj[e] = S->vobj[S->edge[2 * e]];
    /* cell size: the cloth's mean edge length (Teschner §5), at least 2 h */
    double L = 0;
    int cnt = 0;
    for (int e = 0; e < ne; e++)
        if (S->eobj[e] == 0) {
            double d[3];
            for (int c = 0; c < 3; c++) d[c] = S->x0[3 * S->edge[2 * e + 1] + c] - S->x0[3 * S->edge[2 * e] + c];
            L += sqrt(dot3(d, d));
            cnt++;
        }
    S->cell = fmax(cnt ? L / cnt : 0.0, 2 * S->h);
    if (!(S->cell > 0)) S->cell = 1.0;
    return SB_OK;
}

static void sys_free(sys *S)
{
    free(S->x0); free(S->v); free(S->w); free(S->vobj); free(S->tri); free(S->tobj); free(S->edge); free(S->eobj);
    free(S->tbox); free(S->ebox); free(S->tstamp); free(S->estamp); free(S->ids); free(S->parent);
    for (int b = 0; S->th && b < S->nobj; b++) sb_hash_free(&S->th[b]);
    for (int b = 0; S->eh && b < S->nobj; b++) sb_hash_free(&S->eh[b]);
    free(S->th); free(S->eh); free(S->cand.v);
}

/* ---- broad phase ------------------------------------------------------------ */
/* swept box of vertices idx[0..k) over the step, inflated by h */
static void swept_box(const sys *S, int k, const int *idx, double *box)
{
    for (int c = 0; c < 3; c++) { box[c] = INFINITY; box[3 + c] = -INFINITY; }
    for (int j = 0; j < k; j++)
        for (int c = 0; c < 3; c++) {
            double a = S->x0[3 * idx[j] + c], b = a + S->dt * S->v[3 * idx[j] + c];
            box[c] = fmin(box[c], fmin(a, b) - S->h);
            box[3 + c] = fmax(box[3 + c], fmax(a, b) + S->h);
        }
}

static int hash_build(sys *S)
{
    for (int t = 0; t < S->nt; t++) swept_box(S, 3, S->tri + 3 * t, S->tbox + 6 * t);
    for (int e = 0; e < S->ne; e++) swept_box(S, 2, S->edge + 2 * e, S->ebox + 6 * e);
    for (int b = 0; b < S->nobj; b++) {
        int k = 0;
        for (int t = 0; t < S->nt; t++)
            if (S->tobj[t] == b) S->ids[k++] = t;
        if (sb_hash_build(&S->th[b], k, S->ids, S->tbox, S->cell)) return SB_ERR_NOMEM;
        k = 0;
        for (int e = 0; e < S->ne; e++)
            if (S->eobj[e] == b) S->ids[k++] = e;
        if (sb_hash_build(&S->eh[b], k, S->ids, S->ebox, S->cell)) return SB_ERR_NOMEM;
    }
    return SB_OK;
}

/* ---- narrow phase: proximity at x0 (Bridson §7.1-7.2) ----------------------- */
static int prox_vt(sys *S, int p, int t)
{
    const int *f = S->tri + 3 * t;
    double w[3], q[3], n[3];
    const double d = sb_closest_point_triangle(S->x0 + 3 * p, S->x0 + 3 * f[0], S->x0 + 3 * f[1], S->x0 + 3 * f[2], w);
    if (!(d < S->h)) return 0;
    for (int c = 0; c < 3; c++) {
        q[c] = w[0] * S->x0[3 * f[0] + c] + w[1] * S->x0[3 * f[1] + c] + w[2] * S->x0[3 * f[2] + c];
        n[c] = S->x0[3 * p + c] - q[c];
    }
    if (!normalize(n)) return 0;   /* on the triangle: CCD's case */
    const int idx[4] = { p, f[0], f[1], f[2] };
    const double cw[4] = { 1, -w[0], -w[1], -w[2] };
    return apply_impulse(S, 4, idx, cw, n, NULL, 0.1 * (S->h - d) / S->dt, pair_mu(S, 4, idx));
}

static int prox_ee(sys *S, int e1, int e2)
{
    const int *a = S->edge + 2 * e1, *b = S->edge + 2 * e2;
    double s, t, n[3];
    const double d = sb_closest_segments(S->x0 + 3 * a[0], S->x0 + 3 * a[1], S->x0 + 3 * b[0], S->x0 + 3 * b[1], &s, &t);
    if (!(d < S->h)) return 0;
    /* end points of either edge are the point–triangle pairs' business */
    if (s <= 0 || s >= 1 || t <= 0 || t >= 1) return 0;
    for (int c = 0; c < 3; c++)
        n[c] = (1 - s) * S->x0[3 * a[0] + c] + s * S->x0[3 * a[1] + c] - (1 - t) * S->x0[3 * b[0] + c] - t * S->x0[3 * b[1] + c];
    if (!normalize(n)) return 0;
    const int idx[4] = { a[0], a[1], b[0], b[1] };
    const double cw[4] = { 1 - s, s, -(1 - t), -t };
    return apply_impulse(S, 4, idx, cw, n, NULL, 0.1 * (S->h - d) / S->dt, pair_mu(S, 4, idx));
}

/* analytic obstacle o and cloth vertex p: the vertex's start carried by the
 * obstacle's motion (z0) and the obstacle's velocity there */
static void carried(const sys *S, int o, const double x[3], double z0[3], double vb[3])
{
    double y[3];
    sb_pose_inverse(&S->P0[o], x, y);
    sb_pose_apply(&S->P1[o], y, z0);
    for (int c = 0; c < 3; c++) vb[c] = (z0[c] - x[c]) / S->dt;
}

static int prox_analytic(sys *S, int p, int o)
{
    const sb_obstacle_spec *ob = &S->sc->obstacles[o];
    double g[3], z0[3], vb[3];
    const double d = sb_obstacle_phi(ob, &S->P0[o], S->x0 + 3 * p, g, NULL);
    if (!(d < S->h) || !normalize(g)) return 0;
    carried(S, o, S->x0 + 3 * p, z0, vb);
    return apply_impulse(S, 1, &p, (const double[]){ 1.0 }, g, vb, 0.1 * (S->h - d) / S->dt, ob->friction);
}

/* ---- narrow phase: continuous collisions (Bridson §6.1, §7.3) --------------- */
static void at_time(const sys *S, int i, double t, double x[3])
{
    for (int c = 0; c < 3; c++) x[c] = S->x0[3 * i + c] + t * S->dt * S->v[3 * i + c];
}

/* a hit: merge (zone passes) or resolve with the impulse that leaves the pair
 * delta apart along n at t_{n+1}: s0 + dt vrel.n >= delta, s0 = the signed
 * start gap along n (n oriented to make it >= 0, or against vrel when the
 * pair starts in contact) */
static int hit(sys *S, int k, const int *idx, const double *cw, double n[3])
{
    S->hits++;
    if (!S->resolve) {
        for (int j = 1; j < k; j++) uf_union(S->parent, node_of(S, idx[0]), node_of(S, idx[j]));
        return 1;
    }
    double s0 = 0, vn = 0, L = 0;
    for (int j = 0; j < k; j++) {
        s0 += cw[j] * dot3(S->x0 + 3 * idx[j], n);
        vn += cw[j] * dot3(S->v + 3 * idx[j], n);
        for (int c = 0; c < 3; c++) L = fmax(L, fabs(S->x0[3 * idx[j] + c] - S->x0[3 * idx[0] + c]));
    }
    if (s0 < -1e-12 * L || (fabs(s0) <= 1e-12 * L && vn > 0)) {
        for (int c = 0; c < 3; c++) n[c] = -n[c];
        s0 = -s0;
    }
    s0 = fmax(s0, 0.0);
    int r = apply_impulse(S, k, idx, cw, n, NULL, (S->delta - s0) / S->dt, pair_mu(S, k, idx));
    S->st->ccd_hits += r;
    return r;
}

static int ccd_vt(sys *S, int p, int t)
{
    const int *f = S->tri + 3 * t;
    double P[4][2][3];
    const int idx[4] = { p, f[0], f[1], f[2] };
    for (int j = 0; j < 4; j++) { at_time(S, idx[j], 0, P[j][0]); at_time(S, idx[j], 1, P[j][1]); }
    S->st->ccd_tests++;
    const double tc = sb_ccd_point_triangle(P[0][0], P[0][1], P[1][0], P[1][1], P[2][0], P[2][1], P[3][0], P[3][1]);
    if (!(tc <= 1)) return 0;
    double x[4][3], w[3], n[3], e1[3], e2[3];
    for (int j = 0; j < 4; j++) at_time(S, idx[j], tc, x[j]);
    sb_closest_point_triangle(x[0], x[1], x[2], x[3], w);
    for (int c = 0; c < 3; c++) { e1[c] = x[2][c] - x[1][c]; e2[c] = x[3][c] - x[1][c]; }
    cross3(e1, e2, n);
    if (!normalize(n)) {   /* a collapsed triangle: the start's closest direction */
        for (int c = 0; c < 3; c++)
            n[c] = P[0][0][c] - w[0] * P[1][0][c] - w[1] * P[2][0][c] - w[2] * P[3][0][c];
        if (!normalize(n)) return 0;
    }
    const double cw[4] = { 1, -w[0], -w[1], -w[2] };
    return hit(S, 4, idx, cw, n);
}

static int ccd_ee(sys *S, int e1, int e2)
{
    const int *a = S->edge + 2 * e1, *b = S->edge + 2 * e2;
    const int idx[4] = { a[0], a[1], b[0], b[1] };
    double P[4][2][3];
    for (int j = 0; j < 4; j++) { at_time(S, idx[j], 0, P[j][0]); at_time(S, idx[j], 1, P[j][1]); }
    S->st->ccd_tests++;
    const double tc = sb_ccd_edge_edge(P[0][0], P[0][1], P[1][0], P[1][1], P[2][0], P[2][1], P[3][0], P[3][1]);
    if (!(tc <= 1)) return 0;
    double x[4][3], s, t, n[3], u[3], q[3];
    for (int j = 0; j < 4; j++) at_time(S, idx[j], tc, x[j]);
    sb_closest_segments(x[0], x[1], x[2], x[3], &s, &t);
    for (int c = 0; c < 3; c++) { u[c] = x[1][c] - x[0][c]; q[c] = x[3][c] - x[2][c]; }
    cross3(u, q, n);
    if (!(dot3(n, n) > 1e-12 * dot3(u, u) * dot3(q, q)) || !normalize(n)) {
        /* parallel edges: the start's closest direction, else normal to the
           edge against the relative velocity */
        for (int c = 0; c < 3; c++)
            n[c] = (1 - s) * P[0][0][c] + s * P[1][0][c] - (1 - t) * P[2][0][c] - t * P[3][0][c];
        if (!normalize(n)) {
            double vr[3], uu = dot3(u, u);
            for (int c = 0; c < 3; c++)
                vr[c] = (1 - s) * S->v[3 * idx[0] + c] + s * S->v[3 * idx[1] + c] - (1 - t) * S->v[3 * idx[2] + c] - t * S->v[3 * idx[3] + c];
            double k = uu > 0 ? dot3(vr, u) / uu : 0;
            for (int c = 0; c < 3; c++) n[c] = -(vr[c] - k * u[c]);
            if (!normalize(n)) return 0;
        }
    }
    const double cw[4] = { 1 - s, s, -(1 - t), -t };
    return hit(S, 4, idx, cw, n);
}

static int ccd_analytic(sys *S, int p, int o)
{
    const sb_obstacle_spec *ob = &S->sc->obstacles[o];
    double z0[3], vb[3], x1[3], d[3], q[3], n[3];
    carried(S, o, S->x0 + 3 * p, z0, vb);
    at_time(S, p, 1, x1);
    for (int c = 0; c < 3; c++) d[c] = x1[c] - z0[c];
    S->st->ccd_tests++;
    const double phi0 = sb_obstacle_phi(ob, &S->P1[o], z0, n, NULL);
    if (phi0 <= 0) {
        /* the vertex starts inside (a vertex an adaptation placed on a chord
           through the solid, or an unresolved earlier step): pushed out along
           the gradient to delta at t_{n+1}; in the zone passes a hit only
           while its end stays inside */
        if (!S->resolve) {
            if (sb_obstacle_phi(ob, &S->P1[o], x1, NULL, NULL) > 0) return 0;
            S->hits++;
            uf_union(S->parent, p, S->nv + o);
            return 1;
        }
        if (!normalize(n)) return 0;
        S->hits++;
        int r = apply_impulse(S, 1, &p, (const double[]){ 1.0 }, n, vb, (S->delta - phi0) / S->dt, ob->friction);
        S->st->ccd_hits += r;
        return r;
    }
    const double tc = sb_obstacle_toi(ob, &S->P1[o], z0, d);
    if (!(tc <= 1)) return 0;
    S->hits++;
    if (!S->resolve) {
        uf_union(S->parent, p, S->nv + o);
        return 1;
    }
    for (int c = 0; c < 3; c++) q[c] = z0[c] + tc * d[c];
    sb_obstacle_phi(ob, &S->P1[o], q, n, NULL);
    if (!normalize(n)) return 0;
    /* the supporting plane at q: s0 + dt vrel.n >= delta keeps the whole
       segment outside the convex solid */
    double s0 = 0;
    for (int c = 0; c < 3; c++) s0 += (z0[c] - q[c]) * n[c];
    int r = apply_impulse(S, 1, &p, (const double[]){ 1.0 }, n, vb, (S->delta - fmax(s0, 0.0)) / S->dt, ob->friction);
    S->st->ccd_hits += r;
    return r;
}

/* pair filter: across objects only with the cloth; within the cloth only
 * with contact.self and no shared vertex */
static int tri_ok(const sys *S, int p, int t)
{
    const int a = S->vobj[p], b = S->tobj[t];
    if (a == b) {
        if (a != 0 || !S->self) return 0;
        const int *f = S->tri + 3 * t;
        return p != f[0] && p != f[1] && p != f[2];
    }
    return a == 0 || b == 0;
}
static int edge_ok(const sys *S, int e1, int e2)
{
    const int a = S->eobj[e1], b = S->eobj[e2];
    if (a == b) {
        if (a != 0 || !S->self || e2 <= e1) return 0;
        const int *u = S->edge + 2 * e1, *v = S->edge + 2 * e2;
        return u[0] != v[0] && u[0] != v[1] && u[1] != v[0] && u[1] != v[1];
    }
    return a == 0 || b == 0;
}

/* One sweep over all candidate pairs: mode 0 proximity, 1 CCD. */
static int sweep(sys *S, int mode)
{
    int rc = hash_build(S);
    if (rc) return rc;
    double box[6];
    /* point–triangle: cloth vertices against every object's triangles, obstacle vertices against the cloth's */
    for (int p = 0; p < S->n; p++) {
        if (p < S->nv) {
            /* analytic obstacles */
            for (int o = 0; o < S->sc->n_obstacles; o++)
                if (S->sc->obstacles[o].kind != SB_OBST_MESH && (mode == 0 ? prox_analytic(S, p, o) : ccd_analytic(S, p, o)))
                    S->st->proximity_impulses += mode == 0;
        }
        swept_box(S, 1, &p, box);
        for (int b = 0; b < S->nobj; b++) {
            if (S->vobj[p] != 0 && b != 0) continue;
            if (sb_hash_query(&S->th[b], box, S->tstamp, ++S->mark, &S->cand)) return SB_ERR_NOMEM;
            S->st->broad_queries++;
            S->st->broad_candidates += S->cand.n;
            for (int k = 0; k < S->cand.n; k++) {
                const int t = S->cand.v[k];
                if (!tri_ok(S, p, t)) continue;
                if (mode == 0) S->st->proximity_impulses += prox_vt(S, p, t);
                else ccd_vt(S, p, t);
            }
        }
    }
    /* edge–edge: cloth edges against every object's edges */
    for (int e = 0; e < S->ne; e++) {
        if (S->eobj[e] != 0) continue;
        for (int b = 0; b < S->nobj; b++) {
            if (sb_hash_query(&S->eh[b], S->ebox + 6 * e, S->estamp, ++S->mark, &S->cand)) return SB_ERR_NOMEM;
            S->st->broad_queries++;
            S->st->broad_candidates += S->cand.n;
            for (int k = 0; k < S->cand.n; k++) {
                const int f = S->cand.v[k];
                if (!edge_ok(S, e, f)) continue;
                if (mode == 0) S->st->proximity_impulses += prox_ee(S, e, f);
                else ccd_ee(S, e, f);
            }
        }
    }
    return SB_OK;
}

/* ---- impact zones (Bridson §7.4) --------------------------------------------- */
static int zones_apply(sys *S, const int *dirty)
{
    const int nv = S->nv, nob = S->sc->n_obstacles;
    int *members = malloc((size_t)(nv + 1) * sizeof(int));
    double *zx = malloc((size_t)(3 * nv + 3) * sizeof(double)), *zv = malloc((size_t)(3 * nv + 3) * sizeof(double));
    double *zm = malloc((size_t)(nv + 1) * sizeof(double));
    if (!members || !zx || !zv || !zm) { free(members); free(zx); free(zv); free(zm); return SB_ERR_NOMEM; }
    for (int r = 0; r < nv + nob; r++) {
        if (uf_find(S->parent, r) != r || !dirty[r]) continue;
        int k = 0, ninf = 0, obst = r >= nv ? r - nv : -1;
        double vinf[3] = { 0, 0, 0 };
        for (int o = 0; o < nob && obst < 0; o++)
            if (uf_find(S->parent, nv + o) == r) obst = o;
        for (int i = 0; i < nv; i++) {
            if (uf_find(S->parent, i) != r) continue;
            if (S->w[i] > 0) members[k++] = i;
            else {
                ninf++;
                for (int c = 0; c < 3; c++) vinf[c] += S->v[3 * i + c];
            }
        }
        if (k == 0) continue;
        S->st->impact_zones++;
        if (obst >= 0) {            /* moves with the obstacle */
            for (int j = 0; j < k; j++) {
                double z0[3], vb[3];
                carried(S, obst, S->x0 + 3 * members[j], z0, vb);
                for (int c = 0; c < 3; c++) S->v[3 * members[j] + c] = vb[c];
            }
        } else if (ninf > 0) {      /* translates with its prescribed vertices */
            for (int j = 0; j < k; j++)
                for (int c = 0; c < 3; c++) S->v[3 * members[j] + c] = vinf[c] / ninf;
        } else {                    /* rigid, with its momenta */
            double vc[3], om[3];
            for (int j = 0; j < k; j++) {
                zm[j] = 1.0 / S->w[members[j]];
                for (int c = 0; c < 3; c++) {
                    zx[3 * j + c] = S->x0[3 * members[j] + c];
                    zv[3 * j + c] = S->v[3 * members[j] + c];
                }
            }
            sb_rigid_zone(k, zx, zv, zm, S->dt, vc, om);
            for (int j = 0; j < k; j++)
                for (int c = 0; c < 3; c++) S->v[3 * members[j] + c] = zv[3 * j + c];
        }
    }
    free(members); free(zx); free(zv); free(zm);
    return SB_OK;
}

int sb_bridson_respond(const sb_bridson_mesh *m, const sb_scene *sc, double dt, double t1, const double *x0,
                       double *x1, sb_impulse_stats *st)
{
    for (int i = 0; i < 3 * m->nv; i++)
        if (!isfinite(x1[i]) || !isfinite(x0[i])) return SB_NONFINITE;
    if (!(dt > 0)) return SB_ERR_INPUT;
    sys S;
    memset(&S, 0, sizeof S);
    S.st = st;
    int rc = sys_build(&S, m, sc, dt, t1, x0, x1);
    /* 1. proximity impulses with friction at x0 */
    if (!rc) rc = sweep(&S, 0);
    /* 2. up to five passes of CCD, each hit resolved by an impulse */
    S.resolve = 1;
    int clean = 0;
    for (int pass = 0; !rc && pass < CCD_PASSES; pass++) {
        S.hits = 0;
        st->ccd_iterations++;
        rc = sweep(&S, 1);
        if (!rc && S.hits == 0) { clean = 1; break; }
    }
    /* 3. rigid impact zones until collision-free */
    if (!rc && !clean) {
        const int nn = S.nv + sc->n_obstacles;
        int *dirty = calloc((size_t)nn + 1, sizeof(int)), *prev = malloc((size_t)(nn + 1) * sizeof(int));
        if (!dirty || !prev) rc = SB_ERR_NOMEM;
        for (int i = 0; i < nn && !rc; i++) S.parent[i] = i;
        S.resolve = 0;
        for (int pass = 0; !rc && pass < ZONE_PASSES; pass++) {
            S.hits = 0;
            for (int i = 0; i < nn; i++) prev[i] = uf_find(S.parent, i);
            rc = sweep(&S, 1);
            if (rc) break;
            if (S.hits == 0) { clean = 1; break; }
            /* the zones that grew in this pass are made rigid (anew) */
            int grew = 0;
            for (int i = 0; i < nn; i++) dirty[i] = 0;
            for (int i = 0; i < nn; i++)
                if (uf_find(S.parent, i) != prev[i]) {
                    dirty[uf_find(S.parent, i)] = 1;
                    grew = 1;
                }
            if (!grew) break;   /* collisions inside zones that cannot move otherwise: unresolved */
            rc = zones_apply(&S, dirty);
        }
        free(dirty);
        free(prev);
    }
    if (!rc) {
        if (!clean) st->unresolved_steps++;
        for (int i = 0; i < 3 * m->nv; i++) x1[i] = S.x0[i] + dt * S.v[i];
    }
    sys_free(&S);
    return rc;
}
