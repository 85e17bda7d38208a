/* sb_contact.c — the contact term of the incremental potential: IPC log
 * barrier on the sample points' distances to the obstacles, lagged friction
 * as a dissipative potential, and the step filter (sb_contact.h). */
#include "sb_contact.h"
#include "sb_obstacle.h"
#include "sb_self.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct mesh_cache {
    double *vw;              /* 3 nv: vertices in the world at the current step */
    double lo[3], hi[3];     /* their bounding box */
} mesh_cache;

typedef struct fric_pair {
    int p;                   /* sample point */
    double ml;               /* mu * lambda: friction force bound (N) */
    double T[6];             /* 3 x 2 tangent basis, row-major (T[2 i + k]) */
    double base[3];          /* x_p^n + delta: where the point would be if it stuck to the obstacle */
} fric_pair;

struct sb_contact {
    const sb_scene *sc;
    sb_contact_points pts;
    sb_pose pose[SB_SCENE_MAX_OBSTACLES], pose_prev[SB_SCENE_MAX_OBSTACLES];
    mesh_cache mesh[SB_SCENE_MAX_OBSTACLES];
    double dhat, kappa, eps_u, filter;
    fric_pair *fr;
    int n_fr, cap_fr;
    /* Hessian scatter: per point, the value-array positions of its
     * (3k)^2 block entries (upper triangle; -1 below), found once, on the
     * point's first assembly, for the pattern hpat */
    const sb_pattern *hpat;
    long **hpos;
    sb_self *self;           /* self-contact (contact.self), NULL without */
};

/* IPC barrier, Li et al. 2020 Eq. (6): b = -(d - dhat)^2 ln(d / dhat) on (0, dhat) */
double sb_barrier(double d, double dhat, double *db, double *ddb)
{
    if (d >= dhat) {
        if (db) *db = 0;
        if (ddb) *ddb = 0;
        return 0;
    }
    const double e = d - dhat, L = log(d / dhat);
    if (db) *db = -2 * e * L - e * e / d;
    if (ddb) *ddb = -2 * L - 4 * e / d + e * e / (d * d);
    return -e * e * L;
}

/* IPC friction mollifier, Li et al. 2020 Eq. (16) (eps = eps_v h):
 * f0(y) = -y^3/(3 eps^2) + y^2/eps + eps/3 for y < eps, y beyond;
 * f1 = f0' = -y^2/eps^2 + 2y/eps resp. 1 */
double sb_friction_f0(double y, double eps, double *f1, double *df1)
{
    if (y >= eps) {
        if (f1) *f1 = 1;
        if (df1) *df1 = 0;
        return y;
    }
    if (f1) *f1 = -y * y / (eps * eps) + 2 * y / eps;
    if (df1) *df1 = -2 * y / (eps * eps) + 2 / eps;
    return -y * y * y / (3 * eps * eps) + y * y / eps + eps / 3;
}

int sb_contact_create(const sb_scene *sc, sb_contact_points *pts, sb_contact **out)
{
    *out = NULL;
    sb_contact *c = calloc(1, sizeof *c);
    if (!c) return SB_ERR_NOMEM;
    c->sc = sc;
    c->pts = *pts;
    memset(pts, 0, sizeof *pts);
    c->dhat = sc->contact.dhat;
    c->kappa = sc->contact.kappa;
    c->filter = sc->contact.filter;
    for (int o = 0; o < sc->n_obstacles; o++) {
        sb_pose_at(&sc->obstacles[o], 0.0, &c->pose[o]);
        c->pose_prev[o] = c->pose[o];
        if (sc->obstacles[o].kind == SB_OBST_MESH) {
            c->mesh[o].vw = malloc((size_t)3 * sc->obstacles[o].nv * sizeof(double));
            if (!c->mesh[o].vw) { sb_contact_free(c); return SB_ERR_NOMEM; }
        }
    }
    *out = c;
    return SB_OK;
}

void sb_contact_free(sb_contact *c)
{
    if (!c) return;
    sb_self_free(c->self);
    for (int o = 0; o < SB_SCENE_MAX_OBSTACLES; o++) free(c->mesh[o].vw);
    if (c->hpos)
        for (int p = 0; p < c->pts.n; p++) free(c->hpos[p]);
    free(c->hpos);
    sb_contact_points_free(&c->pts);
    free(c->fr);
    free(c);
}

int sb_contact_n_points(const sb_contact *c) { return c->pts.n; }

int sb_contact_self_setup(sb_contact *c, const double *xref, char *why, size_t why_size)
{
    return sb_self_create(&c->pts, xref, c->dhat, c->kappa, c->filter, &c->self, why, why_size);
}

sb_self *sb_contact_self(sb_contact *c) { return c->self; }
const sb_contact_points *sb_contact_points_of(const sb_contact *c) { return &c->pts; }

void sb_contact_pattern_changed(sb_contact *c)
{
    if (c->hpos)
        for (int q = 0; q < c->pts.n; q++) { free(c->hpos[q]); c->hpos[q] = NULL; }
    c->hpat = NULL;
}

static void update_meshes(sb_contact *c)
{
    const sb_scene *sc = c->sc;
    for (int o = 0; o < sc->n_obstacles; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        if (ob->kind != SB_OBST_MESH) continue;
        mesh_cache *m = &c->mesh[o];
        for (int k = 0; k < 3; k++) { m->lo[k] = INFINITY; m->hi[k] = -INFINITY; }
        for (int v = 0; v < ob->nv; v++) {
            sb_pose_apply(&c->pose[o], ob->verts + 3 * v, m->vw + 3 * v);
            for (int k = 0; k < 3; k++) {
                m->lo[k] = fmin(m->lo[k], m->vw[3 * v + k]);
                m->hi[k] = fmax(m->hi[k], m->vw[3 * v + k]);
            }
        }
    }
}

static int near_box(const double lo[3], const double hi[3], const double x[3], double r)
{
    for (int k = 0; k < 3; k++)
        if (x[k] < lo[k] - r || x[k] > hi[k] + r) return 0;
    return 1;
}

/* Visit every point–obstacle (–triangle) pair of point x within reach
 * dmax: fn(data, o, d, g, H) with world derivatives; returns 1 when a pair
 * has d <= 0 (inside / on the surface), else 0.  Pose = c->pose or the
 * given array. */
typedef void (*pair_fn)(void *data, int o, double d, const double g[3], const double H[9]);

static int visit_pairs(const sb_contact *c, const sb_pose *poses, const double x[3], double dmax, int want_h,
                       pair_fn fn, void *data)
{
    const sb_scene *sc = c->sc;
    int inside = 0;
    for (int o = 0; o < sc->n_obstacles; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        double g[3], H[9];
        if (ob->kind != SB_OBST_MESH) {
            double d = sb_obstacle_phi(ob, &poses[o], x, g, want_h ? H : NULL);
            if (d <= 0) inside = 1;
            else if (d < dmax) fn(data, o, d, g, want_h ? H : NULL);
            continue;
        }
        const mesh_cache *m = &c->mesh[o];
        if (!near_box(m->lo, m->hi, x, dmax)) continue;
        for (int t = 0; t < ob->nt; t++) {
            const int *tv = ob->tris + 3 * t;
            const double *a = m->vw + 3 * tv[0], *b = m->vw + 3 * tv[1], *cc = m->vw + 3 * tv[2];
            double lo[3], hi[3];
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(a[k], fmin(b[k], cc[k]));
                hi[k] = fmax(a[k], fmax(b[k], cc[k]));
            }
            if (!near_box(lo, hi, x, dmax)) continue;
            double d = sb_point_triangle_distance(x, a, b, cc, g, want_h ? H : NULL);
            if (d <= 0) inside = 1;
            else if (d < dmax) fn(data, o, d, g, want_h ? H : NULL);
        }
    }
    return inside;
}

/* ---- friction lag ------------------------------------------------------ */

typedef struct lag_data {
    sb_contact *c;
    int p;
    double x[3], a;
    int fail;
} lag_data;

static void lag_pair(void *data, int o, double d, const double g[3], const double H[9])
{
    (void)H;
    lag_data *L = data;
    sb_contact *c = L->c;
    const double mu = c->sc->obstacles[o].friction;
    if (mu <= 0) return;
    double db;
    sb_barrier(d, c->dhat, &db, NULL);
    const double lambda = -c->kappa * L->a * db;   /* the normal force of the barrier at x_n */
    if (!(lambda > 0)) return;
    if (c->n_fr == c->cap_fr) {
        int nc = c->cap_fr ? 2 * c->cap_fr : 256;
        fric_pair *q = realloc(c->fr, (size_t)nc * sizeof *q);
        if (!q) { L->fail = 1; return; }
        c->fr = q;
        c->cap_fr = nc;
    }
    fric_pair *F = &c->fr[c->n_fr++];
    F->p = L->p;
    F->ml = mu * lambda;
    /* tangent basis of the lagged normal n = grad d (IPC §5: T from the
     * closest-point normal at the lagged state) */
    double t1[3], t2[3];
    const double *n = g;
    int k = fabs(n[0]) < fabs(n[1]) ? (fabs(n[0]) < fabs(n[2]) ? 0 : 2) : (fabs(n[1]) < fabs(n[2]) ? 1 : 2);
    double e[3] = { 0, 0, 0 };
    e[k] = 1;
    t1[0] = n[1] * e[2] - n[2] * e[1];
    t1[1] = n[2] * e[0] - n[0] * e[2];
    t1[2] = n[0] * e[1] - n[1] * e[0];
    double s = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (int i = 0; i < 3; i++) t1[i] /= s;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
    for (int i = 0; i < 3; i++) { F->T[2 * i] = t1[i]; F->T[2 * i + 1] = t2[i]; }
    /* delta: the motion of the obstacle's material point at x_n over the
     * step (pose_prev -> pose): the slip is measured relative to it */
    double y[3], x1[3];
    sb_pose_inverse(&c->pose_prev[o], L->x, y);
    sb_pose_apply(&c->pose[o], y, x1);
    for (int i = 0; i < 3; i++) F->base[i] = x1[i];
}

int sb_contact_begin_step(sb_contact *c, int step, double dt, const double *x_n)
{
    const sb_scene *sc = c->sc;
    for (int o = 0; o < sc->n_obstacles; o++) {
        sb_pose_at(&sc->obstacles[o], sb_obstacle_motion_factor(sc, &sc->obstacles[o], step - 1), &c->pose_prev[o]);
        sb_pose_at(&sc->obstacles[o], sb_obstacle_motion_factor(sc, &sc->obstacles[o], step), &c->pose[o]);
    }
    c->n_fr = 0;
    c->eps_u = sc->contact.eps_v * dt;   /* IPC: eps_v h, a displacement */
    int any_mu = 0;
    for (int o = 0; o < sc->n_obstacles; o++) any_mu |= sc->obstacles[o].friction > 0;
    if (!(dt > 0) || !any_mu) { update_meshes(c); return SB_OK; }
    /* lag at x_n against the obstacles where they were at t_n */
    sb_pose cur[SB_SCENE_MAX_OBSTACLES];
    memcpy(cur, c->pose, sizeof cur);
    memcpy(c->pose, c->pose_prev, sizeof cur);
    update_meshes(c);
    memcpy(c->pose, cur, sizeof cur);
    lag_data L = { c, 0, { 0, 0, 0 }, 0, 0 };
    for (int p = 0; p < c->pts.n && !L.fail; p++) {
        L.p = p;
        L.a = c->pts.area[p];
        sb_contact_points_eval(&c->pts, p, x_n, L.x);
        visit_pairs(c, c->pose_prev, L.x, c->dhat, 0, lag_pair, &L);
    }
    update_meshes(c);
    return L.fail ? SB_ERR_NOMEM : SB_OK;
}

/* ---- energy ------------------------------------------------------------ */

typedef struct acc_data {
    const sb_contact *c;
    double a, e;
    double G[3], B[9];
    int want_h;
} acc_data;

static void acc_pair(void *data, int o, double d, const double g[3], const double H[9])
{
    (void)o;
    acc_data *A = data;
    double db, ddb, k = A->c->kappa * A->a;
    A->e += k * sb_barrier(d, A->c->dhat, &db, &ddb);
    /* chain rule: grad = k b'(d) grad d, Hess = k (b'' grad d grad d^T + b' Hess d) */
    for (int i = 0; i < 3; i++) A->G[i] += k * db * g[i];
    if (A->want_h)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) A->B[3 * i + j] += k * (ddb * g[i] * g[j] + db * H[3 * i + j]);
}

/* the value-array positions of point p's block (upper entries; -1 for the
 * lower ones), cached per point for the pattern of H; NULL when out of
 * memory, *bad = 1 when an entry is outside the pattern (a method bug) */
static const long *block_positions(sb_contact *c, int p, const sb_matrix *H, int *bad)
{
    const sb_contact_points *P = &c->pts;
    if (c->hpat != H->pat) {   /* another pattern: forget the cache */
        if (c->hpos)
            for (int q = 0; q < P->n; q++) { free(c->hpos[q]); c->hpos[q] = NULL; }
        c->hpat = H->pat;
    }
    if (!c->hpos && !(c->hpos = calloc((size_t)P->n, sizeof *c->hpos))) return NULL;
    if (c->hpos[p]) return c->hpos[p];
    const int k = P->off[p + 1] - P->off[p], m = 3 * k;
    long *pos = malloc((size_t)m * m * sizeof *pos);
    if (!pos) return NULL;
    for (int a = 0; a < k; a++)
        for (int i = 0; i < 3; i++)
            for (int b = 0; b < k; b++)
                for (int j = 0; j < 3; j++) {
                    const int gi = P->dof[P->off[p] + a] + i, gj = P->dof[P->off[p] + b] + j;
                    long q = -1;
                    if (gi <= gj && (q = sb_pattern_find(H->pat, gi, gj)) < 0) *bad = 1;
                    pos[(3 * a + i) * m + 3 * b + j] = q;
                }
    return c->hpos[p] = pos;
}

/* g += W^T G and H += W^T B W for point p: x_p = sum_a w_a q_a.  Returns 1
 * on a coupling outside the method's pattern (a method bug), -1 out of memory. */
static int scatter(sb_contact *c, int p, const double G[3], const double *B, double *g, sb_matrix *H)
{
    const sb_contact_points *P = &c->pts;
    const int o = P->off[p], k = P->off[p + 1] - o, m = 3 * k;
    if (g)
        for (int a = 0; a < k; a++)
            for (int i = 0; i < 3; i++) g[P->dof[o + a] + i] += P->w[o + a] * G[i];
    if (!H || !B) return 0;
    int bad = 0;
    const long *pos = block_positions(c, p, H, &bad);
    if (!pos) return -1;
    if (bad) return 1;
    for (int a = 0; a < k; a++)
        for (int b = 0; b < k; b++) {
            const double ww = P->w[o + a] * P->w[o + b];
            if (ww == 0) continue;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    const long q = pos[(3 * a + i) * m + 3 * b + j];
                    if (q >= 0) H->val[q] += ww * B[3 * i + j];   /* upper triangle, once */
                }
        }
    return 0;
}

int sb_contact_energy(sb_contact *c, const double *x, double *f, double *g, sb_matrix *H)
{
    const sb_contact_points *P = &c->pts;
    double e = 0;
    int rc;
    acc_data A = { c, 0, 0, { 0 }, { 0 }, H != NULL };
    for (int p = 0; p < P->n; p++) {
        double xp[3];
        sb_contact_points_eval(P, p, x, xp);
        A.a = P->area[p];
        A.e = 0;
        memset(A.G, 0, sizeof A.G);
        memset(A.B, 0, sizeof A.B);
        if (visit_pairs(c, c->pose, xp, c->dhat, H != NULL, acc_pair, &A)) {
            *f = INFINITY;
            return SB_NONFINITE;
        }
        if (A.e == 0 && A.G[0] == 0 && A.G[1] == 0 && A.G[2] == 0) continue;
        e += A.e;
        if ((rc = scatter(c, p, A.G, H ? A.B : NULL, g, H))) return rc < 0 ? SB_ERR_NOMEM : SB_ERR_INTERNAL;
    }
    /* lagged friction (IPC Eq. 14-16): D = mu lambda f0(|u|), u = T^T (x_p - base) */
    for (int k = 0; k < c->n_fr; k++) {
        const fric_pair *F = &c->fr[k];
        double xp[3], u[2] = { 0, 0 }, w[3];
        sb_contact_points_eval(P, F->p, x, xp);
        for (int i = 0; i < 3; i++) w[i] = xp[i] - F->base[i];
        for (int i = 0; i < 3; i++) { u[0] += F->T[2 * i] * w[i]; u[1] += F->T[2 * i + 1] * w[i]; }
        const double y = sqrt(u[0] * u[0] + u[1] * u[1]);
        double f1, df1;
        e += F->ml * sb_friction_f0(y, c->eps_u, &f1, &df1);
        /* f1(y)/y and (f1'(y) y - f1(y)) / y^3, continuous at y = 0 for y < eps */
        const double a = y < c->eps_u ? -y / (c->eps_u * c->eps_u) + 2 / c->eps_u : 1 / y;
        const double b = y < c->eps_u ? (y > 0 ? -1 / (c->eps_u * c->eps_u * y) : 0) : -1 / (y * y * y);
        double G[3], B[9], M[4];
        for (int i = 0; i < 3; i++) G[i] = F->ml * a * (F->T[2 * i] * u[0] + F->T[2 * i + 1] * u[1]);
        M[0] = F->ml * (a + b * u[0] * u[0]);
        M[1] = M[2] = F->ml * b * u[0] * u[1];
        M[3] = F->ml * (a + b * u[1] * u[1]);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double s = 0;
                for (int r = 0; r < 2; r++)
                    for (int q = 0; q < 2; q++) s += F->T[2 * i + r] * M[2 * r + q] * F->T[2 * j + q];
                B[3 * i + j] = s;
            }
        if ((rc = scatter(c, F->p, G, H ? B : NULL, g, H))) return rc < 0 ? SB_ERR_NOMEM : SB_ERR_INTERNAL;
    }
    /* self-contact (sb_self.h) */
    if (c->self && (rc = sb_self_energy(c->self, x, &e, g, H))) {
        if (rc == SB_NONFINITE) *f = INFINITY;
        return rc;
    }
    *f += e;
    return isfinite(e) ? SB_OK : SB_NONFINITE;
}

/* ---- step filter --------------------------------------------------------- */

double sb_contact_step_bound(sb_contact *c, const double *x, const double *d)
{
    const sb_scene *sc = c->sc;
    const sb_contact_points *P = &c->pts;
    double tmin = 2.0;
    for (int p = 0; p < P->n; p++) {
        double xp[3], dp[3], x1[3];
        sb_contact_points_eval(P, p, x, xp);
        sb_contact_points_eval(P, p, d, dp);
        if (dp[0] == 0 && dp[1] == 0 && dp[2] == 0) continue;
        for (int k = 0; k < 3; k++) x1[k] = xp[k] + dp[k];
        for (int o = 0; o < sc->n_obstacles; o++) {
            const sb_obstacle_spec *ob = &sc->obstacles[o];
            if (ob->kind != SB_OBST_MESH) {
                tmin = fmin(tmin, sb_obstacle_toi(ob, &c->pose[o], xp, dp));
                continue;
            }
            const mesh_cache *m = &c->mesh[o];
            double lo[3], hi[3];
            for (int k = 0; k < 3; k++) { lo[k] = fmin(xp[k], x1[k]); hi[k] = fmax(xp[k], x1[k]); }
            int overlap = 1;
            for (int k = 0; k < 3; k++) overlap &= lo[k] <= m->hi[k] && hi[k] >= m->lo[k];
            if (!overlap) continue;
            for (int t = 0; t < ob->nt; t++) {
                const int *tv = ob->tris + 3 * t;
                const double *a = m->vw + 3 * tv[0], *b = m->vw + 3 * tv[1], *cc = m->vw + 3 * tv[2];
                int sep = 0;
                for (int k = 0; k < 3; k++)
                    sep |= hi[k] < fmin(a[k], fmin(b[k], cc[k])) || lo[k] > fmax(a[k], fmax(b[k], cc[k]));
                if (sep) continue;
                /* the obstacle holds its pose during a step's iterations: a static triangle */
                tmin = fmin(tmin, sb_ccd_point_triangle(xp, x1, a, a, b, b, cc, cc));
            }
        }
    }
    double a = tmin <= 1.0 ? c->filter * tmin : 1.0;
    if (c->self) a = fmin(a, sb_self_step_bound(c->self, x, d));
    return a;
}

typedef struct meas_data { double dmin; int active; } meas_data;

static void meas_pair(void *data, int o, double d, const double g[3], const double H[9])
{
    (void)o; (void)g; (void)H;
    meas_data *M = data;
    M->dmin = fmin(M->dmin, d);
}

void sb_contact_measure(sb_contact *c, const double *x, sb_contact_report *r)
{
    const sb_contact_points *P = &c->pts;
    memset(r, 0, sizeof *r);
    r->points = P->n;
    r->min_distance = INFINITY;
    for (int p = 0; p < P->n; p++) {
        double xp[3];
        sb_contact_points_eval(P, p, x, xp);
        meas_data M = { INFINITY, 0 };
        r->inside += visit_pairs(c, c->pose, xp, INFINITY, 0, meas_pair, &M);
        r->min_distance = fmin(r->min_distance, M.dmin);
        if (M.dmin < c->dhat) r->active++;
    }
    /* the surface between the points: each sample triangle against each
       analytic obstacle (sb_obstacle_triangle_depth), counted when the
       obstacle reaches deeper than dhat into it while its corners are all
       outside (a corner inside is counted above) */
    r->between_obstacle = -1;
    r->between = P->nt > 0 ? 0 : -1;
    for (int t = 0; t < P->nt; t++) {
        double xa[3], xb[3], xc[3];
        sb_contact_points_eval(P, P->tri[3 * t], x, xa);
        sb_contact_points_eval(P, P->tri[3 * t + 1], x, xb);
        sb_contact_points_eval(P, P->tri[3 * t + 2], x, xc);
        for (int o = 0; o < c->sc->n_obstacles; o++) {
            const sb_obstacle_spec *ob = &c->sc->obstacles[o];
            /* deeper than dhat: the chord between points resting on a curved
               obstacle dips into it by about h^2 / (8 R), a discretization
               error the barrier's own scale covers; a needle between the
               points pierces (INFINITY) */
            if (ob->kind == SB_OBST_MESH || !(sb_obstacle_triangle_depth(ob, &c->pose[o], xa, xb, xc) > c->dhat))
                continue;
            if (sb_obstacle_phi(ob, &c->pose[o], xa, NULL, NULL) <= 0 || sb_obstacle_phi(ob, &c->pose[o], xb, NULL, NULL) <= 0 ||
                sb_obstacle_phi(ob, &c->pose[o], xc, NULL, NULL) <= 0)
                continue;
            if (r->between_obstacle < 0) r->between_obstacle = o;
            r->between++;
            break;
        }
    }
    r->self_min_distance = INFINITY;
    if (c->self) {
        sb_self_report s;
        if (sb_self_measure(c->self, x, &s) == SB_OK) {
            r->self_pairs = s.pairs;
            r->self_active = s.active;
            r->self_min_distance = s.min_distance;
            r->self_crossings = s.crossings;
            r->self_max_move = s.max_move;
        } else r->self_crossings = -1;
    }
}

/* ---- separation after a change of mesh ---------------------------------- */

/* Points of a new mesh (sb_problem_rebuild after an adaptation) that are
 * inside an obstacle or closer than `target`: each is pushed out along the
 * obstacle's distance gradient by the missing distance, moving all the
 * free vertices of its combination by the same vector (the weights sum to
 * one, so the point moves by it), pass after pass until no point is closer
 * than target (at most 50 passes).  Poses of step `step`.  Analytic
 * obstacles by their signed distance (also inside); mesh obstacles only for
 * points at a distance in (0, target) (a point on a triangle has no side).
 * A point is pushed to 1.01 target, so that rounding does not leave it just
 * short of target for another pass.  *moved: pushes (a point pushed in two
 * passes counts twice); returns the points still closer than target. */
typedef struct sep_data { double d, g[3]; } sep_data;

static void sep_pair(void *data, int o, double d, const double g[3], const double H[9])
{
    (void)o; (void)H;
    sep_data *S = data;
    if (d < S->d) {
        S->d = d;
        memcpy(S->g, g, sizeof S->g);
    }
}

int sb_contact_separate(sb_contact *c, int step, double *x, const unsigned char *fixed, double target, int *moved)
{
    const sb_scene *sc = c->sc;
    const sb_contact_points *P = &c->pts;
    for (int o = 0; o < sc->n_obstacles; o++)
        sb_pose_at(&sc->obstacles[o], sb_obstacle_motion_factor(sc, &sc->obstacles[o], step), &c->pose[o]);
    update_meshes(c);
    *moved = 0;
    int left = 0;
    for (int pass = 0; pass < 50; pass++) {
        left = 0;
        for (int p = 0; p < P->n; p++) {
            double xp[3];
            sb_contact_points_eval(P, p, x, xp);
            sep_data S = { INFINITY, { 0, 0, 0 } };
            for (int o = 0; o < sc->n_obstacles; o++) {
                const sb_obstacle_spec *ob = &sc->obstacles[o];
                if (ob->kind == SB_OBST_MESH) continue;
                double g[3], d = sb_obstacle_phi(ob, &c->pose[o], xp, g, NULL);
                sep_pair(&S, o, d, g, NULL);
            }
            /* mesh triangles (and analytic obstacles again) within reach, at d > 0 */
            sep_data Sm = { INFINITY, { 0, 0, 0 } };
            (void)visit_pairs(c, c->pose, xp, target, 0, sep_pair, &Sm);
            if (Sm.d < S.d) S = Sm;
            if (!(S.d < target)) continue;
            double gn = sqrt(S.g[0] * S.g[0] + S.g[1] * S.g[1] + S.g[2] * S.g[2]);
            if (!(gn > 0)) { left++; continue; }
            const double s = (1.01 * target - S.d) / gn;
            int free_terms = 0;
            for (int k = P->off[p]; k < P->off[p + 1]; k++) {
                const int dof = P->dof[k];
                if (fixed && (fixed[dof] || fixed[dof + 1] || fixed[dof + 2])) continue;
                for (int i = 0; i < 3; i++) x[dof + i] += s * S.g[i] / gn;
                free_terms++;
            }
            if (free_terms) (*moved)++;
            left++;
        }
        if (!left) break;
    }
    /* the points still closer than target after the last pass */
    left = 0;
    for (int p = 0; p < P->n; p++) {
        double xp[3];
        sb_contact_points_eval(P, p, x, xp);
        meas_data M = { INFINITY, 0 };
        left += visit_pairs(c, c->pose, xp, target, 0, meas_pair, &M) || M.dmin < target;
    }
    return left;
}

/* ---- moving obstacles against the step's start ---------------------------- */

/* The barrier sees the obstacles at t_{n+1} only; an obstacle that moves
 * through a sample point within the step would leave it on the other side
 * unseen.  Each point at x_n is held still and the obstacle's motion over
 * the step is swept against it (sb_obstacle_sweep: the segment of the
 * point's relative motion in the obstacle's frame, exact for translations,
 * chords within dhat/100 for rotations).  The earliest touch over all
 * points and moving obstacles is reported; returns the number of points
 * touched. */
int sb_contact_sweep_check(const sb_contact *c, int step, const double *x_n, sb_contact_sweep_hit *hit)
{
    const sb_scene *sc = c->sc;
    const sb_contact_points *P = &c->pts;
    int n_hit = 0;
    memset(hit, 0, sizeof *hit);
    hit->when = 2.0;
    hit->point = hit->obstacle = -1;
    if (step < 1) return 0;
    for (int o = 0; o < sc->n_obstacles; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        const double fa = sb_obstacle_motion_factor(sc, ob, step - 1), fb = sb_obstacle_motion_factor(sc, ob, step);
        if (fa == fb) continue;
        for (int p = 0; p < P->n; p++) {
            double xp[3];
            sb_contact_points_eval(P, p, x_n, xp);
            const double t = sb_obstacle_sweep(ob, fa, fb, xp, 0.01 * c->dhat);
            if (!(t <= 1)) continue;
            n_hit++;
            if (t < hit->when) {
                hit->when = t;
                hit->point = p;
                hit->obstacle = o;
                memcpy(hit->x, xp, sizeof hit->x);
                hit->st[0] = P->st ? P->st[2 * p] : NAN;
                hit->st[1] = P->st ? P->st[2 * p + 1] : NAN;
                sb_pose B;
                sb_pose_at(ob, fb, &B);
                hit->ends_inside = ob->kind != SB_OBST_MESH && sb_obstacle_phi(ob, &B, xp, NULL, NULL) <= 0;
            }
        }
    }
    return n_hit;
}

/* The first sample point at x inside an analytic obstacle, or on a mesh
 * obstacle's triangle, in the obstacles' poses of step `step`: returns the
 * number of such points and describes the first in *hit (when = 0). */
int sb_contact_inside_check(const sb_contact *c, int step, const double *x, sb_contact_sweep_hit *hit)
{
    const sb_scene *sc = c->sc;
    const sb_contact_points *P = &c->pts;
    int n_in = 0;
    memset(hit, 0, sizeof *hit);
    hit->when = 2.0;
    hit->point = hit->obstacle = -1;
    for (int o = 0; o < sc->n_obstacles; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        sb_pose A;
        sb_pose_at(ob, sb_obstacle_motion_factor(sc, ob, step), &A);
        for (int p = 0; p < P->n; p++) {
            double xp[3], d;
            sb_contact_points_eval(P, p, x, xp);
            if (ob->kind != SB_OBST_MESH) d = sb_obstacle_phi(ob, &A, xp, NULL, NULL);
            else {
                double y[3];
                sb_pose_inverse(&A, xp, y);
                d = INFINITY;
                for (int f = 0; f < ob->nt && d > 0; f++) {
                    const double *a = ob->verts + 3 * ob->tris[3 * f], *b = ob->verts + 3 * ob->tris[3 * f + 1],
                                 *cc = ob->verts + 3 * ob->tris[3 * f + 2];
                    int out = 0;   /* only a triangle whose box holds y can have it on it */
                    for (int i = 0; i < 3; i++)
                        out |= y[i] < fmin(a[i], fmin(b[i], cc[i])) || y[i] > fmax(a[i], fmax(b[i], cc[i]));
                    if (!out) d = fmin(d, sb_point_triangle_distance(y, a, b, cc, NULL, NULL));
                }
            }
            if (!(d <= 0)) continue;
            if (n_in++ == 0) {
                hit->when = 0;
                hit->point = p;
                hit->obstacle = o;
                hit->ends_inside = 1;
                memcpy(hit->x, xp, sizeof hit->x);
                hit->st[0] = P->st ? P->st[2 * p] : NAN;
                hit->st[1] = P->st ? P->st[2 * p + 1] : NAN;
            }
        }
    }
    return n_in;
}
