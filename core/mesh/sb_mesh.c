/* sb_mesh.c — storage, edge adjacency, invariants and edge flips of the
 * shared triangle mesh (sb_mesh.h). */
#include "sb_mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sb_mesh_init(sb_mesh *m) { memset(m, 0, sizeof *m); }

void sb_mesh_free(sb_mesh *m)
{
    free(m->st); free(m->xi); free(m->X); free(m->vgen); free(m->vflag);
    free(m->tri); free(m->tri_st); free(m->tri_edge); free(m->tgen);
    free(m->edge_v); free(m->edge_t); free(m->edge_k); free(m->edge_part);
    memset(m, 0, sizeof *m);
}

static int grow(void **p, size_t elem, int n)
{
    void *q = realloc(*p, elem * (size_t)(n > 0 ? n : 1));
    if (!q) return SB_ERR_NOMEM;
    *p = q;
    return SB_OK;
}

int sb_mesh_reserve(sb_mesh *m, int nv, int nt, int ne)
{
    int rc = SB_OK;
    if (nv > m->cap_v) {
        rc |= grow((void **)&m->st, 2 * sizeof(double), nv);
        rc |= grow((void **)&m->xi, 2 * sizeof(double), nv);
        rc |= grow((void **)&m->X, 3 * sizeof(double), nv);
        rc |= grow((void **)&m->vgen, sizeof(int), nv);
        rc |= grow((void **)&m->vflag, 1, nv);
        if (rc) return SB_ERR_NOMEM;
        m->cap_v = nv;
    }
    if (nt > m->cap_t) {
        rc |= grow((void **)&m->tri, 3 * sizeof(int), nt);
        rc |= grow((void **)&m->tri_st, 6 * sizeof(double), nt);
        rc |= grow((void **)&m->tri_edge, 3 * sizeof(int), nt);
        rc |= grow((void **)&m->tgen, sizeof(int), nt);
        if (rc) return SB_ERR_NOMEM;
        m->cap_t = nt;
    }
    if (ne > m->cap_e) {
        rc |= grow((void **)&m->edge_v, 2 * sizeof(int), ne);
        rc |= grow((void **)&m->edge_t, 2 * sizeof(int), ne);
        rc |= grow((void **)&m->edge_k, 2 * sizeof(int), ne);
        rc |= grow((void **)&m->edge_part, sizeof(unsigned), ne);
        if (rc) return SB_ERR_NOMEM;
        m->cap_e = ne;
    }
    return SB_OK;
}

int sb_mesh_copy(const sb_mesh *s, sb_mesh *d)
{
    sb_mesh_init(d);
    if (sb_mesh_reserve(d, s->nv, s->nt, s->ne)) { sb_mesh_free(d); return SB_ERR_NOMEM; }
    d->nv = s->nv; d->nt = s->nt; d->ne = s->ne;
    memcpy(d->st, s->st, 2 * sizeof(double) * (size_t)s->nv);
    memcpy(d->xi, s->xi, 2 * sizeof(double) * (size_t)s->nv);
    memcpy(d->X, s->X, 3 * sizeof(double) * (size_t)s->nv);
    memcpy(d->vgen, s->vgen, sizeof(int) * (size_t)s->nv);
    memcpy(d->vflag, s->vflag, (size_t)s->nv);
    memcpy(d->tri, s->tri, 3 * sizeof(int) * (size_t)s->nt);
    memcpy(d->tri_st, s->tri_st, 6 * sizeof(double) * (size_t)s->nt);
    memcpy(d->tri_edge, s->tri_edge, 3 * sizeof(int) * (size_t)s->nt);
    memcpy(d->tgen, s->tgen, sizeof(int) * (size_t)s->nt);
    memcpy(d->edge_v, s->edge_v, 2 * sizeof(int) * (size_t)s->ne);
    memcpy(d->edge_t, s->edge_t, 2 * sizeof(int) * (size_t)s->ne);
    memcpy(d->edge_k, s->edge_k, 2 * sizeof(int) * (size_t)s->ne);
    memcpy(d->edge_part, s->edge_part, sizeof(unsigned) * (size_t)s->ne);
    d->slit = s->slit;
    return SB_OK;
}

double sb_mesh_tri_area_st(const sb_mesh *m, int t)
{
    const double *p = m->tri_st + 6 * t;
    return 0.5 * ((p[2] - p[0]) * (p[5] - p[1]) - (p[4] - p[0]) * (p[3] - p[1]));
}

/* ---- edges ------------------------------------------------------------- */

typedef struct half { int lo, hi, from, t, k; } half;

static int cmp_half(const void *a, const void *b)
{
    const half *x = a, *y = b;
    if (x->lo != y->lo) return x->lo < y->lo ? -1 : 1;
    if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
    return x->t < y->t ? -1 : x->t > y->t;
}

int sb_mesh_build_edges(sb_mesh *m)
{
    const int nh = 3 * m->nt;
    half *h = malloc(sizeof(half) * (size_t)(nh ? nh : 1));
    if (!h) return SB_ERR_NOMEM;
    for (int t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            const int a = m->tri[3 * t + (k + 1) % 3], b = m->tri[3 * t + (k + 2) % 3];
            half *x = &h[3 * t + k];
            x->lo = a < b ? a : b;
            x->hi = a < b ? b : a;
            x->from = a;
            x->t = t;
            x->k = k;
        }
    qsort(h, (size_t)nh, sizeof *h, cmp_half);
    int ne = 0;
    for (int i = 0; i < nh;) {
        int j = i + 1;
        while (j < nh && h[j].lo == h[i].lo && h[j].hi == h[i].hi) j++;
        if (j - i > 2 || (j - i == 2 && h[i].from == h[i + 1].from)) { free(h); return SB_ERR_INPUT; }
        ne++;
        i = j;
    }
    if (sb_mesh_reserve(m, m->nv, m->nt, ne)) { free(h); return SB_ERR_NOMEM; }
    m->ne = 0;
    for (int i = 0; i < nh;) {
        int j = i + 1;
        while (j < nh && h[j].lo == h[i].lo && h[j].hi == h[i].hi) j++;
        const int e = m->ne++;
        const half *a = &h[i];
        m->edge_v[2 * e] = a->from;
        m->edge_v[2 * e + 1] = a->from == a->lo ? a->hi : a->lo;
        m->edge_t[2 * e] = a->t;
        m->edge_k[2 * e] = a->k;
        m->tri_edge[3 * a->t + a->k] = e;
        if (j - i == 2) {
            m->edge_t[2 * e + 1] = h[i + 1].t;
            m->edge_k[2 * e + 1] = h[i + 1].k;
            m->tri_edge[3 * h[i + 1].t + h[i + 1].k] = e;
        } else {
            m->edge_t[2 * e + 1] = -1;
            m->edge_k[2 * e + 1] = -1;
        }
        m->edge_part[e] = 0;
        i = j;
    }
    free(h);
    for (int v = 0; v < m->nv; v++) m->vflag[v] &= (unsigned char)~SB_MESH_V_BOUNDARY;
    for (int e = 0; e < m->ne; e++)
        if (m->edge_t[2 * e + 1] < 0) {
            m->vflag[m->edge_v[2 * e]] |= SB_MESH_V_BOUNDARY;
            m->vflag[m->edge_v[2 * e + 1]] |= SB_MESH_V_BOUNDARY;
        }
    return SB_OK;
}

#define FAIL(...) do { if (msg) snprintf(msg, len, __VA_ARGS__); return SB_ERR_INTERNAL; } while (0)

int sb_mesh_check(const sb_mesh *m, char *msg, size_t len)
{
    if (m->nv < 3 || m->nt < 1 || m->ne < 3) FAIL("mesh has %d vertices, %d triangles, %d edges", m->nv, m->nt, m->ne);
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        for (int k = 0; k < 3; k++)
            if (v[k] < 0 || v[k] >= m->nv) FAIL("triangle %d: vertex %d out of range", t, v[k]);
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) FAIL("triangle %d repeats a vertex", t);
        if (!(sb_mesh_tri_area_st(m, t) > 0)) FAIL("triangle %d has non-positive (s,t) area", t);
        for (int k = 0; k < 3; k++) {
            const int e = m->tri_edge[3 * t + k];
            if (e < 0 || e >= m->ne) FAIL("triangle %d: edge %d out of range", t, e);
            const int j = m->edge_t[2 * e] == t ? 0 : m->edge_t[2 * e + 1] == t ? 1 : -1;
            if (j < 0) FAIL("triangle %d: edge %d does not list it", t, e);
            if (m->edge_k[2 * e + j] != k) FAIL("triangle %d: edge %d has the wrong opposite corner", t, e);
            const int a = v[(k + 1) % 3], b = v[(k + 2) % 3];
            const int ea = m->edge_v[2 * e + j], eb = m->edge_v[2 * e + 1 - j];
            if (ea != a || eb != b) FAIL("triangle %d: edge %d runs the wrong way", t, e);
        }
    }
    for (int e = 0; e < m->ne; e++) {
        const int t0 = m->edge_t[2 * e], t1 = m->edge_t[2 * e + 1];
        if (t0 < 0 || t0 >= m->nt || t1 >= m->nt || t1 == t0) FAIL("edge %d: bad triangles %d, %d", e, t0, t1);
        if (m->tri_edge[3 * t0 + m->edge_k[2 * e]] != e) FAIL("edge %d: not in its first triangle", e);
        if (t1 >= 0 && m->tri_edge[3 * t1 + m->edge_k[2 * e + 1]] != e) FAIL("edge %d: not in its second triangle", e);
        if (t1 < 0 && !((m->vflag[m->edge_v[2 * e]] & SB_MESH_V_BOUNDARY) &&
                        (m->vflag[m->edge_v[2 * e + 1]] & SB_MESH_V_BOUNDARY)))
            FAIL("boundary edge %d has a vertex without the boundary flag", e);
    }
    /* Euler-type count: every triangle side is one half of an edge */
    long halves = 0;
    for (int e = 0; e < m->ne; e++) halves += m->edge_t[2 * e + 1] >= 0 ? 2 : 1;
    if (halves != 3L * m->nt) FAIL("edges cover %ld triangle sides, expected %d", halves, 3 * m->nt);
    return SB_OK;
}

/* ---- flips ------------------------------------------------------------- */

/* corner st of vertex v in triangle t (NULL if v is not a corner) */
static const double *corner_st(const sb_mesh *m, int t, int v)
{
    for (int k = 0; k < 3; k++)
        if (m->tri[3 * t + k] == v) return m->tri_st + 6 * t + 2 * k;
    return NULL;
}

static double orient(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
}

/* quad a, d, b, c (counter-clockwise) of interior edge e = a->b in t0 */
typedef struct quad { int t0, t1, k0, k1, a, b, c, d; const double *sa, *sb, *sc, *sd; } quad;

static int edge_quad(const sb_mesh *m, int e, quad *q)
{
    q->t0 = m->edge_t[2 * e];
    q->t1 = m->edge_t[2 * e + 1];
    if (q->t1 < 0) return SB_ERR_INPUT;
    q->k0 = m->edge_k[2 * e];
    q->k1 = m->edge_k[2 * e + 1];
    const int *T0 = m->tri + 3 * q->t0, *T1 = m->tri + 3 * q->t1;
    q->c = T0[q->k0];
    q->a = T0[(q->k0 + 1) % 3];
    q->b = T0[(q->k0 + 2) % 3];
    q->d = T1[q->k1];
    q->sa = corner_st(m, q->t0, q->a);
    q->sb = corner_st(m, q->t0, q->b);
    q->sc = corner_st(m, q->t0, q->c);
    q->sd = corner_st(m, q->t1, q->d);
    const double *a1 = corner_st(m, q->t1, q->a), *b1 = corner_st(m, q->t1, q->b);
    if (!a1 || !b1 || a1[0] != q->sa[0] || a1[1] != q->sa[1] || b1[0] != q->sb[0] || b1[1] != q->sb[1])
        return SB_ERR_INPUT;   /* seam: the two triangles use different (s,t) charts */
    return SB_OK;
}

int sb_mesh_flip_valid(const sb_mesh *m, int e)
{
    quad q;
    if (edge_quad(m, e, &q)) return 0;
    return orient(q.sa, q.sd, q.sc) > 0 && orient(q.sb, q.sc, q.sd) > 0;
}

/* replace triangle `from` by `to` (corner kk) in the slots of edge e */
static void reattach(sb_mesh *m, int e, int from, int to, int kk)
{
    const int j = m->edge_t[2 * e] == from ? 0 : 1;
    m->edge_t[2 * e + j] = to;
    m->edge_k[2 * e + j] = kk;
}

int sb_mesh_flip(sb_mesh *m, int e)
{
    quad q;
    if (edge_quad(m, e, &q)) return SB_ERR_INPUT;
    const int t0 = q.t0, t1 = q.t1;
    /* old edges: in t0 = (c, a, b), opposite a: bc, opposite b: ca;
     * in t1 = (d, b, a), opposite b: ad, opposite a: db */
    const int e_bc = m->tri_edge[3 * t0 + (q.k0 + 1) % 3], e_ca = m->tri_edge[3 * t0 + (q.k0 + 2) % 3];
    const int e_ad = m->tri_edge[3 * t1 + (q.k1 + 1) % 3], e_db = m->tri_edge[3 * t1 + (q.k1 + 2) % 3];
    double sa[2] = { q.sa[0], q.sa[1] }, sb[2] = { q.sb[0], q.sb[1] };
    double sc[2] = { q.sc[0], q.sc[1] }, sd[2] = { q.sd[0], q.sd[1] };
    /* new t0 = (a, d, c), new t1 = (b, c, d); the flipped edge is opposite corner 0 in both */
    int *T0 = m->tri + 3 * t0, *T1 = m->tri + 3 * t1;
    T0[0] = q.a; T0[1] = q.d; T0[2] = q.c;
    T1[0] = q.b; T1[1] = q.c; T1[2] = q.d;
    double *S0 = m->tri_st + 6 * t0, *S1 = m->tri_st + 6 * t1;
    S0[0] = sa[0]; S0[1] = sa[1]; S0[2] = sd[0]; S0[3] = sd[1]; S0[4] = sc[0]; S0[5] = sc[1];
    S1[0] = sb[0]; S1[1] = sb[1]; S1[2] = sc[0]; S1[3] = sc[1]; S1[4] = sd[0]; S1[5] = sd[1];
    int *E0 = m->tri_edge + 3 * t0, *E1 = m->tri_edge + 3 * t1;
    E0[0] = e; E0[1] = e_ca; E0[2] = e_ad;
    E1[0] = e; E1[1] = e_db; E1[2] = e_bc;
    m->edge_v[2 * e] = q.d;          /* d -> c in the new t0 */
    m->edge_v[2 * e + 1] = q.c;
    m->edge_k[2 * e] = 0;
    m->edge_k[2 * e + 1] = 0;
    reattach(m, e_ca, t0, t0, 1);
    reattach(m, e_ad, t1, t0, 2);
    reattach(m, e_db, t1, t1, 1);
    reattach(m, e_bc, t0, t1, 2);
    return SB_OK;
}

int sb_mesh_vertex_triangles(const sb_mesh *m, int **ptr, int **idx)
{
    int *p = calloc((size_t)m->nv + 1, sizeof(int)), *x = malloc(sizeof(int) * (size_t)(3 * m->nt + 1));
    if (!p || !x) { free(p); free(x); return SB_ERR_NOMEM; }
    for (int i = 0; i < 3 * m->nt; i++) p[m->tri[i] + 1]++;
    for (int v = 0; v < m->nv; v++) p[v + 1] += p[v];
    int *fill = malloc(sizeof(int) * (size_t)(m->nv + 1));
    if (!fill) { free(p); free(x); return SB_ERR_NOMEM; }
    memcpy(fill, p, sizeof(int) * (size_t)m->nv);
    for (int t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) x[fill[m->tri[3 * t + k]]++] = t;
    free(fill);
    *ptr = p;
    *idx = x;
    return SB_OK;
}
