/* bhem_impulse.c — bhem's own collision pipeline (contact.model = "impulse",
 * docs/contact.md), BHEM paper (Ni, Chen et al.) §5.2 and §6.2.
 *
 * Detection (§6.2, first paragraph: "point-to-surface intersection
 * detection ... through sampling strategies"):
 *   - capsules (needles) and meshes: points on the collider against the
 *     moving Hermite patches, by the dynamic ray–patch intersection of §5.2
 *     (core/contact/sb_patch_ccd.h) in the patches' exact Bézier form
 *     (Eq. 22).  A mesh gives its vertices (as the paper does); a capsule a
 *     sampling of its surface: both poles, rings of 8 points at polar angles
 *     30 and 60 degrees on each cap and rings of 8 along the shaft at most
 *     2 radii apart (the paper's needle scene samples its collider too,
 *     Table 2: 3.6k sample points; its exact pattern is not given —
 *     assumption).
 *   - spheres, planes, boxes and capsules: the cloth's midsurface sampled
 *     uniformly (contact.samples points per patch side, as the barrier's
 *     sample points) against the collider's exact shape, point by point
 *     (sb_obstacle_toi; §6.2 "the midsurface is uniformly sampled"), and
 *     against the triangles of meshes (sb_ccd_point_triangle: vertices
 *     alone let a coarse mesh's faces pass through the cloth).
 *   Obstacles move rigidly: an obstacle point goes linearly from its pose at
 *   t_n to its pose at t_{n+1} (exact for translations, the chord of a
 *   rotation — assumption); a cloth point is followed in the obstacle's rest
 *   frame the same way.
 *
 * Response (§6.2, second and third paragraphs): every collision found at
 * (patch e, local (u, v)) with the normal n of the patch at the time of
 * impact, oriented towards the side the obstacle came from, becomes a
 * constraint linear in the generalized coordinates q of the step's end,
 *   n . x(u, v; q) >= n . p(t_{n+1}) + delta,      delta = 1e-4 m,
 * with n pointing away from the obstacle (zero restitution: the contact
 * point does not move towards the obstacle after the time of impact, [BFA02];
 * plus the push-out of 1e-4 "opposite the normal direction").  All
 * constraints of a step are met together by the impulses of least change
 * in the kinetic-energy metric of the mass lumped per node, W (lumped_mass;
 * linear momentum is conserved, [HVTG08]):
 *   q = q_hat + W^-1 J^T lambda,   (J W^-1 J^T) lambda = b - J q_hat
 * with lambda >= 0 (repulsive impulses only, complementary to the
 * constraints: a linear complementarity problem solved by projected
 * Gauss–Seidel — the paper says only "in a least-square sense"; this is
 * our reading for many simultaneous contacts of one needle tip, whose
 * constraints are nearly dependent).  Friction (Coulomb cone, §6.2):
 * after the normal solve, each contact's tangential slip relative to the
 * obstacle is reduced by mu times the normal displacement the impulse
 * produced there (at most to zero), as one more linear constraint along the
 * slip, and normal and tangential constraints are solved together again.
 * The run's velocity (q - q_n)/dt then carries the impulse.  Detection is
 * repeated on the corrected step with the constraints accumulated, at most
 * BHEM_IMP_PASSES times; a step still colliding then is counted in
 * unresolved_steps (recorded, never silent).  Constrained (Dirichlet) dofs
 * do not move. */
#include "bhem.h"
#include "sb_bezier.h"
#include "sb_impulse.h"
#include "sb_obstacle.h"
#include "sb_patch_ccd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BHEM_IMP_DELTA 1e-4     /* push-out (m), BHEM §6.2 "10^-4 in practice" */
#define BHEM_IMP_EPS 1e-7       /* CCD tolerance (m) */
#define BHEM_IMP_PASSES 8       /* detection passes per step */
#define BHEM_IMP_MAXROWS 1500   /* constraints per step before the step is left unresolved */

typedef struct imp_opoint { int ob; double y[3]; } imp_opoint;   /* obstacle point, rest frame */

typedef struct imp_row {
    int e;
    double th1, th2;     /* patch point */
    double d[3];         /* constraint direction (unit) */
    double b;            /* target d . x(th; q) */
    double mu;           /* friction of the obstacle (normal rows) */
    double rel[3];       /* the obstacle point's displacement over the step (normal rows) */
    int tangent;         /* 1: a friction row */
    int pid;             /* the colliding point (obstacle points first, then cloth points) */
    int jm[BHEM_NB];     /* J_r: node-kinds m (dofs 3m + c) and basis values N_a at (th1, th2) */
    double jw[BHEM_NB];
} imp_row;

struct bhem_impulse {
    int n_op;
    imp_opoint *op;
    int n_sp;
    int *sp_e;           /* cloth sample points: patch and local coordinates */
    double *sp_th;
    double *winv;        /* n_dofs: inverse lumped nodal mass per dof, 0 for constrained dofs */
    sb_patch_ccd_ws *ws;
    double *P0, *P1, *box;   /* patches at x0 and x1 (Bézier), swept boxes */
    int n_rows, cap_rows;
    imp_row *rows;
    double *Y;           /* cap_rows x n: W^-1 J_r^T */
    double *xhat;
};

void bhem_impulse_free(struct bhem_impulse *I)
{
    if (!I) return;
    free(I->op);
    free(I->sp_e);
    free(I->sp_th);
    free(I->winv);
    sb_patch_ccd_ws_free(I->ws);
    free(I->P0);
    free(I->P1);
    free(I->box);
    free(I->rows);
    free(I->Y);
    free(I->xhat);
    free(I);
}

static int add_op(struct bhem_impulse *I, int *cap, int ob, const double y[3])
{
    if (I->n_op == *cap) {
        int nc = *cap ? 2 * *cap : 256;
        imp_opoint *p = realloc(I->op, (size_t)nc * sizeof *p);
        if (!p) return SB_ERR_NOMEM;
        I->op = p;
        *cap = nc;
    }
    I->op[I->n_op].ob = ob;
    memcpy(I->op[I->n_op].y, y, 3 * sizeof(double));
    I->n_op++;
    return SB_OK;
}

/* the capsule sampling described at the top: poles, cap rings, shaft rings */
static int sample_capsule(struct bhem_impulse *I, int *cap, int ob, const sb_obstacle_spec *o)
{
    double ax[3] = { o->b[0] - o->a[0], o->b[1] - o->a[1], o->b[2] - o->a[2] };
    const double len = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]), r = o->radius;
    if (len > 0) for (int c = 0; c < 3; c++) ax[c] /= len;
    else { ax[0] = 0; ax[1] = 0; ax[2] = 1; }
    /* e1, e2 perpendicular to the axis */
    double h[3] = { 1, 0, 0 };
    if (fabs(ax[0]) > 0.9) { h[0] = 0; h[1] = 1; }
    double e1[3] = { ax[1] * h[2] - ax[2] * h[1], ax[2] * h[0] - ax[0] * h[2], ax[0] * h[1] - ax[1] * h[0] };
    double n1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int c = 0; c < 3; c++) e1[c] /= n1;
    double e2[3] = { ax[1] * e1[2] - ax[2] * e1[1], ax[2] * e1[0] - ax[0] * e1[2], ax[0] * e1[1] - ax[1] * e1[0] };
    const int around = 8;
    for (int end = 0; end < 2; end++) {   /* end 0: cap at b (pointing along +ax), 1: at a */
        const double *ctr = end == 0 ? o->b : o->a, sg = end == 0 ? 1.0 : -1.0;
        double y[3];
        for (int c = 0; c < 3; c++) y[c] = ctr[c] + sg * r * ax[c];
        if (add_op(I, cap, ob, y)) return SB_ERR_NOMEM;
        for (int ring = 1; ring <= 2; ring++) {
            const double pol = ring * M_PI / 6;   /* 30 and 60 degrees from the pole */
            for (int k = 0; k < around; k++) {
                const double az = 2 * M_PI * (k + 0.5 * ring) / around;
                for (int c = 0; c < 3; c++)
                    y[c] = ctr[c] + r * (sg * cos(pol) * ax[c] + sin(pol) * (cos(az) * e1[c] + sin(az) * e2[c]));
                if (add_op(I, cap, ob, y)) return SB_ERR_NOMEM;
            }
        }
    }
    const int rings = 1 + (int)ceil(len / (2 * r));
    for (int q = 0; q <= rings; q++) {
        const double s = len * q / rings;
        for (int k = 0; k < around; k++) {
            const double az = 2 * M_PI * (k + 0.5 * (q % 2)) / around;
            double y[3];
            for (int c = 0; c < 3; c++) y[c] = o->a[c] + s * ax[c] + r * (cos(az) * e1[c] + sin(az) * e2[c]);
            if (add_op(I, cap, ob, y)) return SB_ERR_NOMEM;
        }
    }
    return SB_OK;
}

/* The metric of the impulses: the lumped nodal mass m_I = sum_J M^IJ over
 * the value functions J of Eq. 20 = int rho h Phi^I (the value functions
 * sum to one), the same for the four kinds of a node: a point impulse j at
 * (u, v) acts on the patch's 16 control values through the generalized
 * force Phi^I j of Eq. 21, dq_I = Phi^I j / m_I, which conserves linear
 * momentum exactly (sum_I m_I dq_I over the values = j).  The consistent
 * M^-1 was tried and rejected: it spreads a point impulse into the twist
 * dofs of far nodes (55 times the local position response at the free
 * corners of the needle cloth), which tore the cloth (strain over 100 %)
 * within five steps of the first contact. */
static int lumped_mass(const bhem_state *S, const bhem_level *L, struct bhem_impulse *I)
{
    double *m = calloc((size_t)L->n_nodes, sizeof(double));
    I->winv = calloc((size_t)L->n_dofs, sizeof(double));
    if (!m || !I->winv) { free(m); return SB_ERR_NOMEM; }
    for (int e = 0; e < L->n_elems; e++)
        for (int q = 0; q < BHEM_NQP; q++) {
            const double *N = L->qb[q].N, w = S->mat.density * L->ref[(size_t)e * BHEM_NQP + q].dA;
            for (int a = 0; a < BHEM_NB; a++)
                if (a % 4 == 0) m[L->elem_dofs[(size_t)e * BHEM_NED + 3 * a] / 12] += w * N[a];
        }
    for (int d = 0; d < L->n_dofs; d++) I->winv[d] = m[d / 12] > 0 ? 1.0 / m[d / 12] : 0.0;
    for (int k = 0; k < L->dir.n; k++) I->winv[L->dir.dofs[k]] = 0.0;
    free(m);
    return SB_OK;
}

static int impulse_setup(bhem_state *S, const sb_scene *sc, struct bhem_impulse **out)
{
    const bhem_level *L = &S->lv[S->n_levels - 1];
    struct bhem_impulse *I = calloc(1, sizeof *I);
    if (!I) return SB_ERR_NOMEM;
    int cap = 0, rc = SB_OK, analytic = 0;   /* analytic: the cloth's sample points are needed */
    for (int o = 0; o < sc->n_obstacles && !rc; o++) {
        const sb_obstacle_spec *ob = &sc->obstacles[o];
        if (ob->kind == SB_OBST_MESH) {
            for (int v = 0; v < ob->nv && !rc; v++) rc = add_op(I, &cap, o, ob->verts + 3 * v);
            analytic = 1;   /* the cloth's points against its triangles too */
        } else {
            analytic = 1;
            if (ob->kind == SB_OBST_CAPSULE) rc = sample_capsule(I, &cap, o, ob);
        }
    }
    if (!rc && analytic) {   /* the midsurface sampled uniformly: contact.samples per patch side */
        const int ps = sc->contact.samples, ns = L->n1 * ps, nt = L->n2 * ps;
        I->sp_e = malloc(sizeof(int) * (size_t)(ns + 1) * (nt + 1));
        I->sp_th = malloc(sizeof(double) * 2 * (size_t)(ns + 1) * (nt + 1));
        if (!I->sp_e || !I->sp_th) rc = SB_ERR_NOMEM;
        for (int j = 0; j <= nt && !rc; j++)
            for (int i = 0; i <= ns; i++) {
                double th1, th2;
                const int e = bhem_locate(L, (double)i / ns, (double)j / nt, &th1, &th2);
                if (e < 0) continue;
                I->sp_e[I->n_sp] = e;
                I->sp_th[2 * I->n_sp] = th1;
                I->sp_th[2 * I->n_sp + 1] = th2;
                I->n_sp++;
            }
    }
    if (!rc) rc = lumped_mass(S, L, I);
    if (!rc) {
        I->ws = sb_patch_ccd_ws_new();
        I->P0 = malloc(sizeof(double) * SB_BEZ_N * (size_t)L->n_elems);
        I->P1 = malloc(sizeof(double) * SB_BEZ_N * (size_t)L->n_elems);
        I->box = malloc(sizeof(double) * 6 * (size_t)L->n_elems);
        I->xhat = malloc(sizeof(double) * (size_t)L->n_dofs);
        if (!I->ws || !I->P0 || !I->P1 || !I->box || !I->xhat) rc = SB_ERR_NOMEM;
    }
    if (rc) { bhem_impulse_free(I); return rc; }
    *out = I;
    return SB_OK;
}

/* position x(th; q) of patch e and the basis values */
static void patch_point(const bhem_level *L, int e, double th1, double th2, const double *q, double x[3],
                        double N[BHEM_NB])
{
    bhem_basis_eval(th1, th2, L->hs, L->ht, N, NULL, NULL, NULL, NULL, NULL);
    x[0] = x[1] = x[2] = 0;
    for (int a = 0; a < BHEM_NB; a++) {
        const int d = L->elem_dofs[(size_t)e * BHEM_NED + 3 * a];
        for (int c = 0; c < 3; c++) x[c] += N[a] * q[d + c];
    }
}

static double row_apply(const imp_row *r, const double *q)
{
    double v = 0;
    for (int a = 0; a < BHEM_NB; a++) {
        const double *qa = q + 3 * r->jm[a];
        v += r->jw[a] * (r->d[0] * qa[0] + r->d[1] * qa[1] + r->d[2] * qa[2]);
    }
    return v;
}

static int add_row(const bhem_level *L, struct bhem_impulse *I, const imp_row *r)
{
    const int n = L->n_dofs;
    if (I->n_rows == I->cap_rows) {
        int nc = I->cap_rows ? 2 * I->cap_rows : 64;
        imp_row *p = realloc(I->rows, (size_t)nc * sizeof *p);
        if (!p) return SB_ERR_NOMEM;
        I->rows = p;
        double *Y = realloc(I->Y, (size_t)nc * n * sizeof(double));
        if (!Y) return SB_ERR_NOMEM;
        I->Y = Y;
        I->cap_rows = nc;
    }
    /* a point hit again near the same place of the same patch replaces its
     * earlier constraint of the same kind */
    int at = I->n_rows;
    for (int k = 0; k < I->n_rows; k++) {
        const imp_row *o = &I->rows[k];
        if (o->pid == r->pid && o->tangent == r->tangent && o->e == r->e &&
            fabs(o->th1 - r->th1) + fabs(o->th2 - r->th2) < 0.1) { at = k; break; }
    }
    imp_row *R = &I->rows[at];
    *R = *r;
    /* Y_r = W^-1 J_r^T, J_r = d^T [N_a I_3]_a (16 control values) */
    double *Yr = I->Y + (size_t)at * n, N[BHEM_NB], x[3];
    patch_point(L, r->e, r->th1, r->th2, I->xhat, x, N);
    memset(Yr, 0, sizeof(double) * n);
    for (int a = 0; a < BHEM_NB; a++) {
        const int d = L->elem_dofs[(size_t)r->e * BHEM_NED + 3 * a];
        R->jm[a] = d / 3;
        R->jw[a] = N[a];
        for (int c = 0; c < 3; c++) Yr[d + c] += N[a] * r->d[c] * I->winv[d + c];
    }
    if (at == I->n_rows) I->n_rows++;
    return SB_OK;
}

/* The normal rows are inequalities J_r q >= b_r with repulsive impulses
 * lambda_r >= 0 and complementarity (a contact that separates takes no
 * impulse, [HVTG08]); friction rows are equalities.  With q = q_hat +
 * sum_r lambda_r Y_r this is the LCP  A lambda >= c, lambda >= 0,
 * lambda . (A lambda - c) = 0,  A = J W^-1 J^T,  c = b - J q_hat,
 * solved by projected Gauss–Seidel (A is positive semidefinite with a
 * positive diagonal; dependent constraints of one needle tip are harmless),
 * until no multiplier changes the constraint values by more than 1e-3 delta
 * (at most BHEM_IMP_SWEEPS sweeps; what is left is seen by the next
 * detection pass). */
#define BHEM_IMP_SWEEPS 2000
static int solve_rows(const bhem_level *L, struct bhem_impulse *I, double *q)
{
    const int k = I->n_rows, n = L->n_dofs;
    memcpy(q, I->xhat, sizeof(double) * n);
    if (k == 0) return SB_OK;
    double *A = malloc(sizeof(double) * (size_t)k * k), *c = malloc(sizeof(double) * 2 * (size_t)k), *lam = c + k;
    if (!A || !c) { free(A); free(c); return SB_ERR_NOMEM; }
    for (int r = 0; r < k; r++) {
        c[r] = I->rows[r].b - row_apply(&I->rows[r], I->xhat);
        lam[r] = 0.0;
        for (int t = 0; t <= r; t++)
            A[(size_t)r * k + t] = A[(size_t)t * k + r] = row_apply(&I->rows[r], I->Y + (size_t)t * n);
    }
    for (int sweep = 0; sweep < BHEM_IMP_SWEEPS; sweep++) {
        double change = 0.0;
        for (int r = 0; r < k; r++) {
            const double arr = A[(size_t)r * k + r];
            if (!(arr > 0)) continue;
            double res = c[r];
            for (int t = 0; t < k; t++) res -= A[(size_t)r * k + t] * lam[t];
            double nl = lam[r] + res / arr;
            if (!I->rows[r].tangent && nl < 0) nl = 0;
            change = fmax(change, fabs(nl - lam[r]) * arr);
            lam[r] = nl;
        }
        if (change <= 1e-3 * BHEM_IMP_DELTA) break;
    }
    for (int r = 0; r < k; r++) {
        if (lam[r] == 0.0) continue;
        const double *Yr = I->Y + (size_t)r * n;
        for (int i = 0; i < n; i++) q[i] += lam[r] * Yr[i];
    }
    free(A);
    free(c);
    return SB_OK;
}

static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Bézier patches of x1 and their boxes swept from x0 (P0 filled by the caller) */
static void sweep_boxes(const bhem_level *L, struct bhem_impulse *I, const double *x1)
{
    for (int e = 0; e < L->n_elems; e++) {
        double *P1 = I->P1 + (size_t)e * SB_BEZ_N, lo[3], hi[3], l2[3], h2[3];
        bhem_patch_bezier(L, e, x1, P1);
        sb_bezier_bounds(I->P0 + (size_t)e * SB_BEZ_N, lo, hi);
        sb_bezier_bounds(P1, l2, h2);
        for (int c = 0; c < 3; c++) {
            I->box[6 * e + c] = fmin(lo[c], l2[c]) - BHEM_IMP_EPS;
            I->box[6 * e + 3 + c] = fmax(hi[c], h2[c]) + BHEM_IMP_EPS;
        }
    }
}

/* A cloth point X0 -> X1 against the triangles of mesh obstacle o (all
 * moving linearly between the poses): the first time of impact by the
 * point–triangle CCD of Provot / Bridson et al. (sb_ccd_point_triangle);
 * normal of the triangle at that time, oriented towards the side the point
 * came from; the contact point carried to t_{n+1} with the triangle's mean
 * vertex motion.  Updates *best (time), *bo, n, c, rel when earlier. */
static void mesh_toi(const sb_obstacle_spec *ob, const sb_pose *P0, const sb_pose *P1, const double X0[3],
                     const double X1[3], sb_impulse_stats *st, double *best, int *bo, int o, double n[3], double c[3],
                     double rel[3])
{
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) { lo[k] = fmin(X0[k], X1[k]); hi[k] = fmax(X0[k], X1[k]); }
    for (int f = 0; f < ob->nt; f++) {
        double v0[3][3], v1[3][3], tlo[3], thi[3];
        for (int a = 0; a < 3; a++) {
            sb_pose_apply(P0, ob->verts + 3 * ob->tris[3 * f + a], v0[a]);
            sb_pose_apply(P1, ob->verts + 3 * ob->tris[3 * f + a], v1[a]);
        }
        for (int k = 0; k < 3; k++) {
            tlo[k] = fmin(fmin(fmin(v0[0][k], v0[1][k]), fmin(v0[2][k], v1[0][k])), fmin(v1[1][k], v1[2][k]));
            thi[k] = fmax(fmax(fmax(v0[0][k], v0[1][k]), fmax(v0[2][k], v1[0][k])), fmax(v1[1][k], v1[2][k]));
        }
        if (hi[0] < tlo[0] || hi[1] < tlo[1] || hi[2] < tlo[2] || lo[0] > thi[0] || lo[1] > thi[1] || lo[2] > thi[2])
            continue;
        st->ccd_tests++;
        const double t = sb_ccd_point_triangle(X0, X1, v0[0], v1[0], v0[1], v1[1], v0[2], v1[2]);
        if (!(t <= 1.0) || t >= *best) continue;
        double a[3], b[3], cc[3], e1[3], e2[3], nn[3], mv[3], w[3];
        for (int k = 0; k < 3; k++) {
            a[k] = v0[0][k] + t * (v1[0][k] - v0[0][k]);
            b[k] = v0[1][k] + t * (v1[1][k] - v0[1][k]);
            cc[k] = v0[2][k] + t * (v1[2][k] - v0[2][k]);
            e1[k] = b[k] - a[k];
            e2[k] = cc[k] - a[k];
            mv[k] = ((v1[0][k] - v0[0][k]) + (v1[1][k] - v0[1][k]) + (v1[2][k] - v0[2][k])) / 3.0;
            w[k] = (X1[k] - X0[k]) - mv[k];   /* the point's motion relative to the triangle */
        }
        cross3(e1, e2, nn);
        const double l = sqrt(dot3(nn, nn));
        if (!(l > 0)) continue;
        const double sg = dot3(nn, w) > 0 ? -1.0 : 1.0;   /* towards the side the point came from */
        *best = t;
        *bo = o;
        for (int k = 0; k < 3; k++) {
            n[k] = sg * nn[k] / l;
            c[k] = X0[k] + t * (X1[k] - X0[k]) + (1.0 - t) * mv[k];
            rel[k] = mv[k];
        }
    }
}

/* One detection pass along x0 -> x1: the earliest collision of every
 * obstacle point and every cloth sample point becomes a normal row.
 * Returns the number of collisions found (< 0: error). */
static int detect(const bhem_state *S, const sb_scene *sc, struct bhem_impulse *I, const sb_pose *pose0,
                  const sb_pose *pose1, const double *x0, const double *x1, sb_impulse_stats *st, imp_row *found,
                  int max_found)
{
    const bhem_level *L = &S->lv[S->n_levels - 1];
    int nf = 0;
    sweep_boxes(L, I, x1);
    /* obstacle points against the moving patches (§5.2) */
    for (int k = 0; k < I->n_op; k++) {
        const imp_opoint *op = &I->op[k];
        double p0[3], p1[3], lo[3], hi[3];
        sb_pose_apply(&pose0[op->ob], op->y, p0);
        sb_pose_apply(&pose1[op->ob], op->y, p1);
        for (int c = 0; c < 3; c++) { lo[c] = fmin(p0[c], p1[c]); hi[c] = fmax(p0[c], p1[c]); }
        sb_ccd_hit best = { 2.0, 0, 0 };
        int be = -1;
        for (int e = 0; e < L->n_elems; e++) {
            const double *B = I->box + 6 * e;
            if (hi[0] < B[0] || hi[1] < B[1] || hi[2] < B[2] || lo[0] > B[3] || lo[1] > B[4] || lo[2] > B[5]) continue;
            sb_ccd_hit h;
            st->ccd_tests++;
            int rc = sb_patch_ccd(I->P0 + (size_t)e * SB_BEZ_N, I->P1 + (size_t)e * SB_BEZ_N, p0, p1, BHEM_IMP_EPS,
                                  I->ws, &h);
            if (rc < 0) return SB_ERR_NOMEM;
            if (rc && h.t < best.t) { best = h; be = e; }
        }
        if (be < 0) continue;
        if (nf == max_found) return nf;
        /* normal of the patch at the time of impact, towards the side the point came from */
        double Pt[SB_BEZ_N], x[3], xu[3], xv[3], n[3], X0[3], X1[3], N[BHEM_NB];
        const double *A = I->P0 + (size_t)be * SB_BEZ_N, *B = I->P1 + (size_t)be * SB_BEZ_N;
        for (int i = 0; i < SB_BEZ_N; i++) Pt[i] = A[i] + best.t * (B[i] - A[i]);
        sb_bezier_eval(Pt, best.u, best.v, x, xu, xv);
        cross3(xu, xv, n);
        patch_point(L, be, best.u, best.v, x0, X0, N);
        patch_point(L, be, best.u, best.v, x1, X1, N);
        double w[3], rel[3];
        for (int c = 0; c < 3; c++) { rel[c] = p1[c] - p0[c]; w[c] = rel[c] - (X1[c] - X0[c]); }
        double nn = sqrt(dot3(n, n));
        if (!(nn > 0)) { for (int c = 0; c < 3; c++) n[c] = w[c]; nn = sqrt(dot3(n, n)); }
        if (!(nn > 0)) continue;   /* no relative motion and no normal: nothing to resolve */
        for (int c = 0; c < 3; c++) n[c] /= nn;
        double side = -dot3(n, w);   /* the point approaches against n_s: n_s . w < 0 */
        if (fabs(side) < 1e-14) { double g[3] = { p0[0] - X0[0], p0[1] - X0[1], p0[2] - X0[2] }; side = dot3(n, g); }
        const double sg = side >= 0 ? 1.0 : -1.0;
        imp_row *r = &found[nf++];
        memset(r, 0, sizeof *r);
        r->pid = k;
        r->e = be;
        r->th1 = best.u;
        r->th2 = best.v;
        for (int c = 0; c < 3; c++) { r->d[c] = -sg * n[c]; r->rel[c] = rel[c]; }
        /* the surface stays delta behind the point: (-n_s) . x = (-n_s) . p1 + delta */
        r->b = dot3(r->d, p1) + BHEM_IMP_DELTA;
        r->mu = sc->obstacles[op->ob].friction;
    }
    /* cloth sample points against the exact analytic shapes */
    sb_pose id;
    memset(&id, 0, sizeof id);
    id.R[0] = id.R[4] = id.R[8] = 1.0;
    for (int k = 0; k < I->n_sp; k++) {
        double X0[3], X1[3], N[BHEM_NB];
        const int e = I->sp_e[k];
        patch_point(L, e, I->sp_th[2 * k], I->sp_th[2 * k + 1], x0, X0, N);
        patch_point(L, e, I->sp_th[2 * k], I->sp_th[2 * k + 1], x1, X1, N);
        double best = 2.0, bn[3] = { 0, 0, 0 }, bc[3] = { 0, 0, 0 }, brel[3] = { 0, 0, 0 };
        int bo = -1;
        for (int o = 0; o < sc->n_obstacles; o++) {
            const sb_obstacle_spec *ob = &sc->obstacles[o];
            if (ob->kind == SB_OBST_MESH) {
                mesh_toi(ob, &pose0[o], &pose1[o], X0, X1, st, &best, &bo, o, bn, bc, brel);
                continue;
            }
            double y0[3], y1[3], d[3], t;
            sb_pose_inverse(&pose0[o], X0, y0);
            sb_pose_inverse(&pose1[o], X1, y1);
            for (int c = 0; c < 3; c++) d[c] = y1[c] - y0[c];
            st->ccd_tests++;
            t = sb_obstacle_phi(ob, &id, y0, NULL, NULL) <= 0 ? 0.0 : sb_obstacle_toi(ob, &id, y0, d);
            if (!(t <= 1.0) || t >= best) continue;
            double ys[3], g[3];
            for (int c = 0; c < 3; c++) ys[c] = y0[c] + t * d[c];
            sb_obstacle_phi(ob, &id, ys, g, NULL);
            best = t;
            bo = o;
            sb_pose_rotate(&pose1[o], g, bn);        /* outward normal at t_{n+1} */
            sb_pose_apply(&pose1[o], ys, bc);        /* the contact point carried to t_{n+1} */
            double c0[3];
            sb_pose_apply(&pose0[o], ys, c0);
            for (int c = 0; c < 3; c++) brel[c] = bc[c] - c0[c];
        }
        if (bo < 0) continue;
        if (nf == max_found) return nf;
        const double nn = sqrt(dot3(bn, bn));
        if (!(nn > 0)) continue;
        imp_row *r = &found[nf++];
        memset(r, 0, sizeof *r);
        r->pid = I->n_op + k;
        r->e = e;
        r->th1 = I->sp_th[2 * k];
        r->th2 = I->sp_th[2 * k + 1];
        for (int c = 0; c < 3; c++) { r->d[c] = bn[c] / nn; r->rel[c] = brel[c]; }
        r->b = dot3(r->d, bc) + BHEM_IMP_DELTA;   /* delta outside the collider */
        r->mu = sc->obstacles[bo].friction;
    }
    return nf;
}

/* Friction (§6.2, Coulomb cone): for every normal row with mu > 0, the slip of
 * the contact point relative to the obstacle over the step, s_t, is reduced
 * by mu |normal displacement the impulse produced| (at most to zero), one
 * row along the slip.  xn: the normal-only solution. */
static int friction_rows(const bhem_level *L, struct bhem_impulse *I, int n_normal, const double *x0,
                         const double *xn)
{
    for (int k = 0; k < n_normal; k++) {
        const imp_row r = I->rows[k];
        if (r.tangent || !(r.mu > 0)) continue;
        double X0[3], Xn[3], Xh[3], N[BHEM_NB], D[3];
        patch_point(L, r.e, r.th1, r.th2, x0, X0, N);
        patch_point(L, r.e, r.th1, r.th2, xn, Xn, N);
        patch_point(L, r.e, r.th1, r.th2, I->xhat, Xh, N);
        for (int c = 0; c < 3; c++) D[c] = Xn[c] - X0[c] - r.rel[c];
        const double dn = dot3(D, r.d);
        double Dt[3] = { D[0] - dn * r.d[0], D[1] - dn * r.d[1], D[2] - dn * r.d[2] };
        const double slip = sqrt(dot3(Dt, Dt));
        if (!(slip > 1e-12)) continue;
        double J[3] = { Xn[0] - Xh[0], Xn[1] - Xh[1], Xn[2] - Xh[2] };
        const double jn = fabs(dot3(J, r.d));
        const double keep = fmax(0.0, 1.0 - r.mu * jn / slip);
        imp_row t = r;
        t.tangent = 1;
        for (int c = 0; c < 3; c++) t.d[c] = Dt[c] / slip;
        t.b = dot3(t.d, Xn) - (1.0 - keep) * slip;
        int rc = add_row(L, I, &t);
        if (rc) return rc;
    }
    return SB_OK;
}

int bhem_impulse_response(void *state, const sb_scene *sc, double dt, double t1, const double *x0, double *x1,
                          sb_impulse_stats *st)
{
    bhem_state *S = state;
    const bhem_level *L = &S->lv[S->n_levels - 1];
    int rc;
    if (!S->imp && (rc = impulse_setup(S, sc, &S->imp))) return bhem_fail(S, rc, "impulse response set-up failed");
    struct bhem_impulse *I = S->imp;
    if (I->n_op == 0 && I->n_sp == 0) return SB_OK;
    /* the obstacles' poses at t_n and t_{n+1} */
    const int step = dt > 0 ? (int)lround(t1 / dt) : 1;
    sb_pose pose0[SB_SCENE_MAX_OBSTACLES], pose1[SB_SCENE_MAX_OBSTACLES];
    for (int o = 0; o < sc->n_obstacles; o++) {
        sb_pose_at(&sc->obstacles[o], sb_obstacle_motion_factor(sc, &sc->obstacles[o], step - 1), &pose0[o]);
        sb_pose_at(&sc->obstacles[o], sb_obstacle_motion_factor(sc, &sc->obstacles[o], step), &pose1[o]);
    }
    const int n = L->n_dofs;
    for (int e = 0; e < L->n_elems; e++) bhem_patch_bezier(L, e, x0, I->P0 + (size_t)e * SB_BEZ_N);
    memcpy(I->xhat, x1, sizeof(double) * n);
    I->n_rows = 0;
    const int maxf = I->n_op + I->n_sp;
    imp_row *found = malloc(sizeof(imp_row) * (size_t)(maxf > 0 ? maxf : 1));
    double *xn = malloc(sizeof(double) * (size_t)n);
    if (!found || !xn) { free(found); free(xn); return bhem_fail(S, SB_ERR_NOMEM, "out of memory (impulse response)"); }
    int resolved = 0;
    rc = SB_OK;
    for (int pass = 0; pass < BHEM_IMP_PASSES; pass++) {
        int nf = detect(S, sc, I, pose0, pose1, x0, x1, st, found, maxf);
        if (nf < 0) { rc = nf; break; }
        if (nf == 0) { resolved = 1; break; }
        st->ccd_iterations++;
        st->ccd_hits += nf;
        if (I->n_rows + 2 * nf > BHEM_IMP_MAXROWS) break;
        /* normal rows first (the friction rows of the previous pass are rebuilt) */
        int keep = 0;
        for (int r = 0; r < I->n_rows; r++)
            if (!I->rows[r].tangent) {
                if (keep != r) {
                    I->rows[keep] = I->rows[r];
                    memcpy(I->Y + (size_t)keep * n, I->Y + (size_t)r * n, sizeof(double) * n);
                }
                keep++;
            }
        I->n_rows = keep;
        for (int k = 0; k < nf && !rc; k++) rc = add_row(L, I, &found[k]);
        if (!rc) rc = solve_rows(L, I, xn);
        const int n_normal = I->n_rows;
        st->proximity_impulses += nf;
        if (!rc) rc = friction_rows(L, I, n_normal, x0, xn);
        if (!rc) rc = I->n_rows > n_normal ? solve_rows(L, I, x1) : (memcpy(x1, xn, sizeof(double) * n), SB_OK);
        if (rc) break;
    }
    free(found);
    free(xn);
    if (rc) return bhem_fail(S, rc, "impulse response failed");
    if (!resolved) st->unresolved_steps++;
    return SB_OK;
}
