/* a3_sqrt3.c — sqrt3 refinement and coarsening (sqrt3 paper §5.1-5.2);
 * the operations, the generation rule and the representation: a3_sqrt3.h. */
#include "a3_sqrt3.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEPTH 64

/* ---- storage ---------------------------------------------------------------- */

static int grow(void **p, int *cap, int need, size_t size)
{
    if (need <= *cap) return SB_OK;
    int c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    void *q = realloc(*p, (size_t)c * size);
    if (!q) return SB_ERR_NOMEM;
    *p = q;
    *cap = c;
    return SB_OK;
}

static int new_vertex(a3_forest *F, double s, double t, int gen, int bnd, const int par[3], const double w[3])
{
    if (F->nv + 1 > F->cap_v) {
        const int c = F->cap_v ? 2 * F->cap_v : 64;
        double *st = realloc(F->st, sizeof(double) * 2 * (size_t)c);
        if (!st) return -1;
        F->st = st;
        int *vr = realloc(F->vref, sizeof(int) * (size_t)c);
        if (!vr) return -1;
        F->vref = vr;
        int *vg = realloc(F->vgen, sizeof(int) * (size_t)c);
        if (!vg) return -1;
        F->vgen = vg;
        unsigned char *vb = realloc(F->vbnd, (size_t)c);
        if (!vb) return -1;
        F->vbnd = vb;
        int *vp = realloc(F->vpar, sizeof(int) * 3 * (size_t)c);
        if (!vp) return -1;
        F->vpar = vp;
        double *vw = realloc(F->vw, sizeof(double) * 3 * (size_t)c);
        if (!vw) return -1;
        F->vw = vw;
        F->cap_v = c;
    }
    const int v = F->nv++;
    F->st[2 * v] = s;
    F->st[2 * v + 1] = t;
    F->vref[v] = 0;
    F->vgen[v] = gen;
    F->vbnd[v] = (unsigned char)bnd;
    for (int k = 0; k < 3; k++) {
        F->vpar[3 * v + k] = par ? par[k] : -1;
        F->vw[3 * v + k] = par ? w[k] : 0.0;
    }
    return v;
}

static int new_tri(a3_forest *F, int a, int b, int c, int gen, int mate)
{
    if (grow((void **)&F->t, &F->cap_t, F->nt + 1, sizeof *F->t)) return -1;
    a3_ftri *T = &F->t[F->nt];
    T->v[0] = a;
    T->v[1] = b;
    T->v[2] = c;
    T->gen = gen;
    T->mate = (signed char)mate;
    T->alive = 0;
    T->child_op = -1;
    return F->nt++;
}

/* ---- edge hash -------------------------------------------------------------- */

static long long ekey(int a, int b) { return a < b ? ((long long)a << 32) | (unsigned)b : ((long long)b << 32) | (unsigned)a; }

static unsigned long long hmix(long long k)
{
    unsigned long long x = (unsigned long long)k * 0x9E3779B97F4A7C15ULL;
    return x ^ (x >> 29);
}

static int hslot(const a3_forest *F, long long k)
{
    unsigned long long i = hmix(k) & (unsigned long long)(F->hcap - 1);
    while (F->hkey[i] != -1 && F->hkey[i] != k) i = (i + 1) & (unsigned long long)(F->hcap - 1);
    return (int)i;
}

static int hgrow(a3_forest *F)
{
    if (2 * (F->hused + 1) <= F->hcap) return SB_OK;
    const int oc = F->hcap;
    long long *ok = F->hkey;
    int *ov = F->hval;
    F->hcap = oc ? 2 * oc : 1024;
    F->hkey = malloc(sizeof(long long) * (size_t)F->hcap);
    F->hval = malloc(sizeof(int) * 2 * (size_t)F->hcap);
    if (!F->hkey || !F->hval) { free(ok); free(ov); return SB_ERR_NOMEM; }
    for (int i = 0; i < F->hcap; i++) F->hkey[i] = -1;
    F->hused = 0;
    for (int i = 0; i < oc; i++)
        if (ok[i] != -1 && (ov[2 * i] >= 0 || ov[2 * i + 1] >= 0)) {
            const int s = hslot(F, ok[i]);
            F->hkey[s] = ok[i];
            F->hval[2 * s] = ov[2 * i];
            F->hval[2 * s + 1] = ov[2 * i + 1];
            F->hused++;
        }
    free(ok);
    free(ov);
    return SB_OK;
}

static int edge_add(a3_forest *F, int a, int b, int t)
{
    if (hgrow(F)) return SB_ERR_NOMEM;
    const long long k = ekey(a, b);
    const int s = hslot(F, k);
    if (F->hkey[s] == -1) {
        F->hkey[s] = k;
        F->hval[2 * s] = F->hval[2 * s + 1] = -1;
        F->hused++;
    }
    if (F->hval[2 * s] < 0) F->hval[2 * s] = t;
    else if (F->hval[2 * s + 1] < 0) F->hval[2 * s + 1] = t;
    else return SB_ERR_INTERNAL;   /* a third triangle on an edge */
    return SB_OK;
}

static void edge_del(a3_forest *F, int a, int b, int t)
{
    const int s = hslot(F, ekey(a, b));
    if (F->hkey[s] == -1) return;
    if (F->hval[2 * s] == t) F->hval[2 * s] = -1;
    else if (F->hval[2 * s + 1] == t) F->hval[2 * s + 1] = -1;
}

int a3_forest_across(const a3_forest *F, int a, int b, int t)
{
    if (!F->hcap) return -1;
    const int s = hslot(F, ekey(a, b));
    if (F->hkey[s] == -1) return -1;
    const int x = F->hval[2 * s], y = F->hval[2 * s + 1];
    return x == t ? y : y == t ? x : -1;
}

static int tri_on(a3_forest *F, int t)
{
    a3_ftri *T = &F->t[t];
    T->alive = 1;
    for (int k = 0; k < 3; k++) {
        F->vref[T->v[k]]++;
        int rc = edge_add(F, T->v[(k + 1) % 3], T->v[(k + 2) % 3], t);
        if (rc) return rc;
    }
    return SB_OK;
}

static void tri_off(a3_forest *F, int t)
{
    a3_ftri *T = &F->t[t];
    T->alive = 0;
    for (int k = 0; k < 3; k++) {
        F->vref[T->v[k]]--;
        edge_del(F, T->v[(k + 1) % 3], T->v[(k + 2) % 3], t);
    }
}

/* the triangle across edge k (opposite corner k) of t */
static int nbr(const a3_forest *F, int t, int k)
{
    const a3_ftri *T = &F->t[t];
    return a3_forest_across(F, T->v[(k + 1) % 3], T->v[(k + 2) % 3], t);
}

/* ---- applying and undoing operations ------------------------------------------ */

static int op_apply(a3_forest *F, int k)
{
    a3_op *o = &F->op[k];
    for (int i = 0; i < o->n_in; i++) tri_off(F, o->in[i]);
    for (int i = 0; i < o->n_out; i++) {
        int rc = tri_on(F, o->out[i]);
        if (rc) return rc;
    }
    o->applied = 1;
    return SB_OK;
}

static int op_undo(a3_forest *F, int k)
{
    a3_op *o = &F->op[k];
    for (int i = 0; i < o->n_out; i++) tri_off(F, o->out[i]);
    for (int i = 0; i < o->n_in; i++) {
        int rc = tri_on(F, o->in[i]);
        if (rc) return rc;
    }
    o->applied = 0;
    return SB_OK;
}

static int new_op(a3_forest *F, int kind)
{
    if (grow((void **)&F->op, &F->cap_op, F->nop + 1, sizeof *F->op)) return -1;
    a3_op *o = &F->op[F->nop];
    memset(o, 0, sizeof *o);
    o->kind = kind;
    return F->nop++;
}

/* the generation rule for triangle t against its alive neighbours */
static int rule_ok(const a3_forest *F, int t)
{
    for (int k = 0; k < 3; k++) {
        const int n = nbr(F, t, k);
        if (n >= 0 && abs(F->t[n].gen - F->t[t].gen) > 1) return 0;
    }
    return 1;
}

static int refine(a3_forest *F, int t, int depth);

/* neighbours of t (all, or all but edge `skip`) raised to at least gen g */
static int raise_neighbours(a3_forest *F, int t, int g, int skip, int depth)
{
    for (int k = 0; k < 3; k++) {
        if (k == skip) continue;
        for (int guard = 0; guard < 8; guard++) {
            if (!F->t[t].alive) return 0;
            const int n = nbr(F, t, k);
            if (n < 0 || F->t[n].gen >= g) break;
            int rc = refine(F, n, depth + 1);
            if (rc <= 0) return rc;
        }
        const int n = nbr(F, t, k);
        if (n >= 0 && F->t[n].gen < g) return 0;
    }
    return F->t[t].alive ? 1 : 0;
}

static int do_split(a3_forest *F, int t, int depth)
{
    const int g = F->t[t].gen;
    if (g >= F->max_gen) return 0;
    int rc = raise_neighbours(F, t, g, -1, depth);
    if (rc <= 0) return rc;
    int k = F->t[t].child_op;
    if (k < 0) {
        const int *v = F->t[t].v;
        const double s = (F->st[2 * v[0]] + F->st[2 * v[1]] + F->st[2 * v[2]]) / 3.0;
        const double tt = (F->st[2 * v[0] + 1] + F->st[2 * v[1] + 1] + F->st[2 * v[2] + 1]) / 3.0;
        const double w3[3] = { 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0 };
        const int m = new_vertex(F, s, tt, g + 1, 0, v, w3);
        if (m < 0 || (k = new_op(F, A3_OP_SPLIT)) < 0) return SB_ERR_NOMEM;
        v = F->t[t].v;
        const int a = v[0], b = v[1], c = v[2];
        const int c0 = new_tri(F, a, b, m, g + 1, 2), c1 = new_tri(F, b, c, m, g + 1, 2), c2 = new_tri(F, c, a, m, g + 1, 2);
        if (c0 < 0 || c1 < 0 || c2 < 0) return SB_ERR_NOMEM;
        a3_op *o = &F->op[k];
        o->n_in = 1; o->in[0] = t;
        o->n_out = 3; o->out[0] = c0; o->out[1] = c1; o->out[2] = c2;
        o->n_vnew = 1; o->vnew[0] = m;
        F->t[t].child_op = k;
    }
    rc = op_apply(F, k);
    return rc ? rc : 1;
}

static int do_bsplit(a3_forest *F, int t, int depth)
{
    const int g = F->t[t].gen, km = F->t[t].mate;
    if (g + 3 > F->max_gen) return 0;
    int rc = raise_neighbours(F, t, g + 1, km, depth);
    if (rc <= 0) return rc;
    int k = F->t[t].child_op;
    if (k < 0) {
        const int *v = F->t[t].v;
        const int m = v[km], a = v[(km + 1) % 3], b = v[(km + 2) % 3];
        const double *sa = F->st + 2 * a, *sb = F->st + 2 * b;
        const int par[3] = { a, b, a };
        const double w1[3] = { 2.0 / 3.0, 1.0 / 3.0, 0.0 }, w2[3] = { 1.0 / 3.0, 2.0 / 3.0, 0.0 };
        const int p1 = new_vertex(F, sa[0] + (sb[0] - sa[0]) / 3.0, sa[1] + (sb[1] - sa[1]) / 3.0, g + 2, 1, par, w1);
        if (p1 < 0) return SB_ERR_NOMEM;
        sa = F->st + 2 * a;
        sb = F->st + 2 * b;
        const int p2 = new_vertex(F, sa[0] + 2.0 * (sb[0] - sa[0]) / 3.0, sa[1] + 2.0 * (sb[1] - sa[1]) / 3.0, g + 2, 1, par, w2);
        if (p1 < 0 || p2 < 0 || (k = new_op(F, A3_OP_BSPLIT)) < 0) return SB_ERR_NOMEM;
        /* Fig. 5: left (a, p1, m) and right (p2, b, m) at g + 2 with mates
         * (m, a) and (b, m); middle (p1, p2, m) at g + 3 */
        const int l = new_tri(F, a, p1, m, g + 2, 1), c = new_tri(F, p1, p2, m, g + 3, -1), r = new_tri(F, p2, b, m, g + 2, 0);
        if (l < 0 || c < 0 || r < 0) return SB_ERR_NOMEM;
        a3_op *o = &F->op[k];
        o->n_in = 1; o->in[0] = t;
        o->n_out = 3; o->out[0] = l; o->out[1] = c; o->out[2] = r;
        o->n_vnew = 2; o->vnew[0] = p1; o->vnew[1] = p2;
        F->t[t].child_op = k;
    }
    rc = op_apply(F, k);
    return rc ? rc : 1;
}

/* t odd with an interior mate edge: flip it with its mate triangle */
static int do_flip(a3_forest *F, int t, int depth)
{
    const int g = F->t[t].gen, km = F->t[t].mate;
    if (g + 1 > F->max_gen) return 0;
    for (int guard = 0; guard < 4; guard++) {
        if (!F->t[t].alive) return 0;
        const int p = nbr(F, t, km);
        if (p < 0) return 0;
        const a3_ftri *P = &F->t[p];
        if (P->gen == g && P->mate >= 0 && nbr(F, p, P->mate) == t) {
            int k = F->t[t].child_op;
            if (k < 0 || F->op[k].kind != A3_OP_FLIP) {
                const int *v = F->t[t].v;
                const int m0 = v[km], a = v[(km + 1) % 3], b = v[(km + 2) % 3], m1 = P->v[(int)P->mate];
                if ((k = new_op(F, A3_OP_FLIP)) < 0) return SB_ERR_NOMEM;
                const int n0 = new_tri(F, a, m1, m0, g + 1, -1), n1 = new_tri(F, b, m0, m1, g + 1, -1);
                if (n0 < 0 || n1 < 0) return SB_ERR_NOMEM;
                a3_op *o = &F->op[k];
                o->n_in = 2; o->in[0] = t; o->in[1] = p;
                o->n_out = 2; o->out[0] = n0; o->out[1] = n1;
                F->t[t].child_op = F->t[p].child_op = k;
            }
            int rc = op_apply(F, k);
            return rc ? rc : 1;
        }
        if (P->gen < g) {
            int rc = refine(F, p, depth + 1);   /* the mate's region catches up (§5.1) */
            if (rc <= 0) return rc;
            continue;
        }
        return 0;
    }
    return 0;
}

static int refine(a3_forest *F, int t, int depth)
{
    if (depth > MAX_DEPTH || !F->t[t].alive) return 0;
    const a3_ftri *T = &F->t[t];
    if (T->gen % 2 == 0) return do_split(F, t, depth);
    if (T->mate < 0) return 0;
    if (nbr(F, t, T->mate) < 0) return do_bsplit(F, t, depth);
    return do_flip(F, t, depth);
}

int a3_forest_refine(a3_forest *F, int t)
{
    if (t < 0 || t >= F->nt) return 0;
    return refine(F, t, 0);
}

/* ---- coarsening --------------------------------------------------------------- */

int a3_forest_coarsen(a3_forest *F, int k)
{
    if (k < 0 || k >= F->nop) return 0;
    a3_op *o = &F->op[k];
    if (!o->applied || o->kind == A3_OP_FLIP) return 0;
    int undone[3], nu = 0, rc;
    /* flip back the flips that consumed the outputs (their products must be alive) */
    for (int i = 0; i < o->n_out; i++) {
        const int c = o->out[i];
        if (F->t[c].alive) continue;
        const int f = F->t[c].child_op;
        int ok = f >= 0 && F->op[f].applied && F->op[f].kind == A3_OP_FLIP;
        for (int j = 0; ok && j < F->op[f].n_out; j++) ok = F->t[F->op[f].out[j]].alive;
        if (!ok) goto restore;
        if ((rc = op_undo(F, f))) return rc;
        undone[nu++] = f;
    }
    if ((rc = op_undo(F, k))) return rc;
    /* the generation rule around everything revived */
    int ok = rule_ok(F, o->in[0]);
    for (int i = 0; ok && i < nu; i++)
        for (int j = 0; ok && j < F->op[undone[i]].n_in; j++) {
            const int x = F->op[undone[i]].in[j];
            ok = !F->t[x].alive || rule_ok(F, x);
        }
    if (ok) return 1;
    if ((rc = op_apply(F, k))) return rc;
restore:
    for (int i = nu - 1; i >= 0; i--)
        if ((rc = op_apply(F, undone[i]))) return rc;
    return 0;
}

int a3_forest_refine_all(a3_forest *F)
{
    for (int pass = 0; pass < 4 * F->max_gen + 8; pass++) {
        int changed = 0;
        const int nt = F->nt;
        for (int t = 0; t < nt; t++) {
            if (!F->t[t].alive || F->t[t].gen >= F->max_gen) continue;
            int rc = refine(F, t, 0);
            if (rc < 0) return rc;
            changed |= rc;
        }
        if (!changed) return SB_OK;
    }
    return SB_OK;
}

int a3_forest_coarsen_all(a3_forest *F)
{
    for (int pass = 0; pass < 4 * F->max_gen + 8; pass++) {
        int changed = 0;
        for (int k = F->nop - 1; k >= 0; k--) {
            if (!F->op[k].applied || F->op[k].kind == A3_OP_FLIP) continue;
            int rc = a3_forest_coarsen(F, k);
            if (rc < 0) return rc;
            changed |= rc;
        }
        if (!changed) break;
    }
    return SB_OK;
}

/* ---- checkpoints ------------------------------------------------------------------ */

enum { A3_BLOB_MAGIC = 0x53513301, A3_BLOB_HEAD = 6, A3_V_INTS = 5, A3_T_INTS = 7, A3_OP_INTS = 12 };

int a3_forest_save(const a3_forest *F, sb_blob *b)
{
    memset(b, 0, sizeof *b);
    const long ni = A3_BLOB_HEAD + (long)A3_V_INTS * F->nv + (long)A3_T_INTS * F->nt + (long)A3_OP_INTS * F->nop;
    const long nd = 5L * F->nv;
    if (ni > 0x7fffffffL || nd > 0x7fffffffL) return SB_ERR_NOMEM;
    b->ints = malloc(sizeof(int) * (size_t)ni);
    b->dbls = malloc(sizeof(double) * (size_t)(nd ? nd : 1));
    if (!b->ints || !b->dbls) { sb_blob_free(b); return SB_ERR_NOMEM; }
    b->n_int = (int)ni;
    b->n_dbl = (int)nd;
    int *p = b->ints;
    *p++ = A3_BLOB_MAGIC; *p++ = F->nv; *p++ = F->nt; *p++ = F->nop; *p++ = F->nt0; *p++ = F->max_gen;
    for (int v = 0; v < F->nv; v++) {
        *p++ = F->vgen[v];
        *p++ = F->vbnd[v];
        for (int k = 0; k < 3; k++) *p++ = F->vpar[3 * v + k];
    }
    for (int t = 0; t < F->nt; t++) {
        const a3_ftri *T = &F->t[t];
        *p++ = T->v[0]; *p++ = T->v[1]; *p++ = T->v[2];
        *p++ = T->gen; *p++ = T->mate; *p++ = T->alive; *p++ = T->child_op;
    }
    for (int k = 0; k < F->nop; k++) {
        const a3_op *o = &F->op[k];
        *p++ = o->kind; *p++ = o->applied; *p++ = o->n_in; *p++ = o->n_out; *p++ = o->n_vnew;
        *p++ = o->in[0]; *p++ = o->in[1]; *p++ = o->out[0]; *p++ = o->out[1]; *p++ = o->out[2];
        *p++ = o->vnew[0]; *p++ = o->vnew[1];
    }
    memcpy(b->dbls, F->st, sizeof(double) * 2 * (size_t)F->nv);
    memcpy(b->dbls + 2 * (size_t)F->nv, F->vw, sizeof(double) * 3 * (size_t)F->nv);
    return SB_OK;
}

static int in_range(int i, int lo, int hi) { return i >= lo && i < hi; }

int a3_forest_load(a3_forest *F, const sb_blob *b, char *msg, size_t len)
{
    const int *p = b->ints;
    if (b->n_int < A3_BLOB_HEAD || p[0] != A3_BLOB_MAGIC || p[1] < 0 || p[2] < 0 || p[3] < 0) {
        snprintf(msg, len, "not a sqrt3 forest of this build");
        return SB_ERR_INPUT;
    }
    const int nv = p[1], nt = p[2], nop = p[3];
    if (p[4] != F->nt0 || p[5] != F->max_gen || nv < F->nv || nt < F->nt0 ||
        (long)b->n_int != A3_BLOB_HEAD + (long)A3_V_INTS * nv + (long)A3_T_INTS * nt + (long)A3_OP_INTS * nop ||
        (long)b->n_dbl != 5L * nv) {
        snprintf(msg, len, "a forest of another base mesh or max generation (%d base triangles, g_max %d; this run: %d, %d)",
                 p[4], p[5], F->nt0, F->max_gen);
        return SB_ERR_INPUT;
    }
    /* validated before anything is changed */
    const int *pv = p + A3_BLOB_HEAD, *pt = pv + A3_V_INTS * nv, *po = pt + A3_T_INTS * nt;
    for (int v = 0; v < nv; v++) {
        const int *q = pv + A3_V_INTS * v;
        if (q[0] < 0 || !in_range(q[1], 0, 2) || !in_range(q[2], -1, nv) || !in_range(q[3], -1, nv) || !in_range(q[4], -1, nv)) {
            snprintf(msg, len, "vertex %d of the forest is malformed", v);
            return SB_ERR_INPUT;
        }
    }
    for (int t = 0; t < nt; t++) {
        const int *q = pt + A3_T_INTS * t;
        if (!in_range(q[0], 0, nv) || !in_range(q[1], 0, nv) || !in_range(q[2], 0, nv) || q[3] < 0 ||
            !in_range(q[4], -1, 3) || !in_range(q[5], 0, 2) || !in_range(q[6], -1, nop)) {
            snprintf(msg, len, "triangle %d of the forest is malformed", t);
            return SB_ERR_INPUT;
        }
    }
    for (int k = 0; k < nop; k++) {
        const int *q = po + A3_OP_INTS * k;
        int ok = in_range(q[0], 0, 3) && in_range(q[1], 0, 2) && in_range(q[2], 0, 3) && in_range(q[3], 0, 4) &&
                 in_range(q[4], 0, 3);
        for (int i = 0; ok && i < q[2]; i++) ok = in_range(q[5 + i], 0, nt);
        for (int i = 0; ok && i < q[3]; i++) ok = in_range(q[7 + i], 0, nt);
        for (int i = 0; ok && i < q[4]; i++) ok = in_range(q[10 + i], 0, nv);
        if (!ok) {
            snprintf(msg, len, "operation %d of the forest is malformed", k);
            return SB_ERR_INPUT;
        }
    }
    const int nt0 = F->nt0, max_gen = F->max_gen;
    a3_forest_free(F);
    F->nt0 = nt0;
    F->max_gen = max_gen;
    for (int v = 0; v < nv; v++) {
        const int *q = pv + A3_V_INTS * v;
        const double *st = b->dbls + 2 * (size_t)v, *w = b->dbls + 2 * (size_t)nv + 3 * (size_t)v;
        if (new_vertex(F, st[0], st[1], q[0], q[1], q + 2, w) < 0) goto nomem;
    }
    for (int t = 0; t < nt; t++) {
        const int *q = pt + A3_T_INTS * t;
        const int k = new_tri(F, q[0], q[1], q[2], q[3], q[4]);
        if (k < 0) goto nomem;
        F->t[k].child_op = q[6];
    }
    for (int k = 0; k < nop; k++) {
        const int *q = po + A3_OP_INTS * k;
        const int j = new_op(F, q[0]);
        if (j < 0) goto nomem;
        a3_op *o = &F->op[j];
        o->applied = q[1]; o->n_in = q[2]; o->n_out = q[3]; o->n_vnew = q[4];
        o->in[0] = q[5]; o->in[1] = q[6]; o->out[0] = q[7]; o->out[1] = q[8]; o->out[2] = q[9];
        o->vnew[0] = q[10]; o->vnew[1] = q[11];
    }
    /* alive triangles in record order: vertex use counts and the edge map as the run had them */
    for (int t = 0; t < nt; t++) {
        if (!pt[A3_T_INTS * t + 5]) continue;
        int rc = tri_on(F, t);
        if (rc == SB_ERR_NOMEM) goto nomem;
        if (rc) {
            snprintf(msg, len, "the alive triangles of the forest are not a manifold mesh");
            return SB_ERR_INPUT;
        }
    }
    if (a3_forest_check(F, msg, len)) return SB_ERR_INPUT;
    return SB_OK;
nomem:
    snprintf(msg, len, "out of memory restoring the sqrt3 forest");
    return SB_ERR_NOMEM;
}

/* ---- set-up, checks, export ----------------------------------------------------- */

void a3_forest_free(a3_forest *F)
{
    free(F->t); free(F->op); free(F->st); free(F->vref); free(F->vgen); free(F->vbnd); free(F->vpar); free(F->vw);
    free(F->hkey); free(F->hval);
    memset(F, 0, sizeof *F);
}

int a3_forest_init(a3_forest *F, const sb_mesh *m, int max_gen)
{
    memset(F, 0, sizeof *F);
    F->max_gen = max_gen;
    for (int v = 0; v < m->nv; v++)
        if (m->vflag[v] & SB_MESH_V_SEAM) return SB_ERR_UNSUPPORTED;
    for (int v = 0; v < m->nv; v++)
        if (new_vertex(F, m->st[2 * v], m->st[2 * v + 1], 0, (m->vflag[v] & SB_MESH_V_BOUNDARY) != 0, NULL, NULL) < 0)
            return SB_ERR_NOMEM;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        const int k = new_tri(F, v[0], v[1], v[2], 0, -1);
        if (k < 0) return SB_ERR_NOMEM;
        int rc = tri_on(F, k);
        if (rc) return rc;
    }
    F->nt0 = m->nt;
    return SB_OK;
}

int a3_forest_check(const a3_forest *F, char *msg, size_t len)
{
    for (int t = 0; t < F->nt; t++) {
        const a3_ftri *T = &F->t[t];
        if (!T->alive) continue;
        for (int k = 0; k < 3; k++) {
            const int a = T->v[(k + 1) % 3], b = T->v[(k + 2) % 3];
            const int s = hslot(F, ekey(a, b));
            if (F->hkey[s] == -1 || (F->hval[2 * s] != t && F->hval[2 * s + 1] != t)) {
                snprintf(msg, len, "triangle %d: edge (%d,%d) missing from the edge map", t, a, b);
                return -1;
            }
            const int n = nbr(F, t, k);
            if (n >= 0 && abs(F->t[n].gen - T->gen) > 1) {
                snprintf(msg, len, "triangles %d (gen %d) and %d (gen %d) share an edge: generation difference > 1", t,
                         T->gen, n, F->t[n].gen);
                return -1;
            }
            if (n < 0 && !(F->vbnd[a] && F->vbnd[b])) {
                snprintf(msg, len, "triangle %d: edge (%d,%d) has one triangle but is not on the boundary", t, a, b);
                return -1;
            }
        }
    }
    return 0;
}

int a3_forest_mesh(const a3_forest *F, const sb_scene *sc, sb_mesh *m, int **vmap_out)
{
    int *newid = malloc(sizeof(int) * (size_t)(F->nv ? F->nv : 1));
    int *vmap = malloc(sizeof(int) * (size_t)(F->nv ? F->nv : 1));
    if (!newid || !vmap) { free(newid); free(vmap); return SB_ERR_NOMEM; }
    int nv = 0, nt = 0;
    for (int v = 0; v < F->nv; v++) {
        newid[v] = F->vref[v] > 0 ? nv : -1;
        if (F->vref[v] > 0) vmap[nv++] = v;
    }
    for (int t = 0; t < F->nt; t++) nt += F->t[t].alive;
    sb_mesh_free(m);
    sb_mesh_init(m);
    int rc = sb_mesh_reserve(m, nv, nt, 3 * nt);
    if (rc) { free(newid); free(vmap); return rc; }
    m->nv = nv;
    for (int i = 0; i < nv; i++) {
        m->st[2 * i] = F->st[2 * vmap[i]];
        m->st[2 * i + 1] = F->st[2 * vmap[i] + 1];
        m->vgen[i] = F->vgen[vmap[i]];
        m->vflag[i] = 0;
    }
    nt = 0;
    for (int t = 0; t < F->nt; t++) {
        if (!F->t[t].alive) continue;
        for (int k = 0; k < 3; k++) {
            const int v = newid[F->t[t].v[k]];
            m->tri[3 * nt + k] = v;
            m->tri_st[6 * nt + 2 * k] = m->st[2 * v];
            m->tri_st[6 * nt + 2 * k + 1] = m->st[2 * v + 1];
        }
        m->tgen[nt++] = F->t[t].gen;
    }
    m->nt = nt;
    free(newid);
    sb_mesh_set_geometry(m, sc);
    if ((rc = sb_mesh_build_edges(m))) { free(vmap); return rc; }
    sb_mesh_tag_boundary(m, sc);
    *vmap_out = vmap;
    return SB_OK;
}
