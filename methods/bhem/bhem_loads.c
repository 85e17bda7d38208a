/* bhem_loads.c — consistent mass matrix (BHEM Eq. 20), generalized forces of
 * dead loads (Eq. 19 terms: areal gravity / dead pressure, line loads along
 * edges, point loads by Eq. 21) and the conservative end moment. */
#include "bhem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int is_dead(const sb_load *ld)
{
    return ld->kind == SB_LOAD_GRAVITY || ld->kind == SB_LOAD_LINE || ld->kind == SB_LOAD_POINT ||
           (ld->kind == SB_LOAD_PRESSURE && !ld->follower);
}

/* ---- edge segments ------------------------------------------------------ */

/* One grid segment of an edge part: the patch it bounds and its side. */
typedef struct seg { int elem; int const_t; double fixed_th; } seg;

/* Calls back for every grid segment of an edge part (both orientations).
 * A segment is charged once, to the active patch on its "upper" side if
 * there is one, else to the patch below. */
static int for_segments(bhem_state *S, bhem_level *L, const sb_part *pt, int idx,
                        int (*fn)(bhem_state *, bhem_level *, const seg *, void *), void *ud)
{
    const double tol = 1e-9;
    int const_t = fabs(pt->st0[1] - pt->st1[1]) < tol;
    double c = const_t ? pt->st0[1] * L->n2 : pt->st0[0] * L->n1;
    int k = (int)lround(c), nalong = const_t ? L->n1 : L->n2, ncross = const_t ? L->n2 : L->n1;
    if (fabs(c - k) > 1e-6)
        return bhem_fail(S, SB_ERR_INPUT, "load %d: edge \"%s\" does not lie on a grid line of the %dx%d patch grid",
                         idx, pt->name, L->n1, L->n2);
    double lo = const_t ? pt->st0[0] : pt->st0[1], hi = const_t ? pt->st1[0] : pt->st1[1];
    int count = 0;
    for (int a = 0; a < nalong; a++) {
        double u0 = (double)a / nalong, u1 = (double)(a + 1) / nalong;
        if (u0 < lo - tol || u1 > hi + tol) continue;
        int e = -1;
        double th = 0.0;
        for (int side = 0; side < 2 && e < 0; side++) {
            int kk = side == 0 ? k : k - 1;          /* cell above (th = 0) or below (th = 1) */
            if (kk < 0 || kk >= ncross) continue;
            int cell = const_t ? a + L->n1 * kk : kk + L->n1 * a;
            e = L->cell_elem[cell];
            th = side == 0 ? 0.0 : 1.0;
        }
        if (e < 0) continue;
        seg sg = { e, const_t, th };
        int rc = fn(S, L, &sg, ud);
        if (rc) return rc;
        count++;
    }
    if (!count)
        return bhem_fail(S, SB_ERR_INPUT, "load %d: edge \"%s\" covers no patch side of the %dx%d grid",
                         idx, pt->name, L->n1, L->n2);
    return SB_OK;
}

/* Basis at Gauss point g of a segment; returns the reference arc length
 * weight (Gauss weight * h_along * |X_,along|). */
static double seg_point(const bhem_level *L, const seg *sg, int g, double *N, double *N1, double *N2)
{
    double gx[BHEM_NQ1], gw[BHEM_NQ1], qe[BHEM_NED];
    bhem_gauss_rule(gx, gw);
    double th1 = sg->const_t ? gx[g] : sg->fixed_th, th2 = sg->const_t ? sg->fixed_th : gx[g];
    bhem_basis_eval(th1, th2, L->hs, L->ht, N, N1, N2, NULL, NULL, NULL);
    bhem_gather(L, sg->elem, L->x_ref, qe);
    const double *Na = sg->const_t ? N1 : N2;
    double Xa[3] = { 0, 0, 0 };
    for (int I = 0; I < BHEM_NB; I++)
        for (int c = 0; c < 3; c++) Xa[c] += Na[I] * qe[3 * I + c];
    return gw[g] * (sg->const_t ? L->hs : L->ht) * sqrt(Xa[0] * Xa[0] + Xa[1] * Xa[1] + Xa[2] * Xa[2]);
}

typedef struct line_ud { double *b; const double *f; } line_ud;

/* line load: b_I += int N_I t dGamma (BHEM Eq. 19, boundary term), 4-point Gauss */
static int line_seg(bhem_state *S, bhem_level *L, const seg *sg, void *ud)
{
    (void)S;
    line_ud *u = ud;
    double N[BHEM_NB], N1[BHEM_NB], N2[BHEM_NB];
    const int *d = L->elem_dofs + (size_t)sg->elem * BHEM_NED;
    for (int g = 0; g < BHEM_NQ1; g++) {
        double w = seg_point(L, sg, g, N, N1, N2);
        for (int I = 0; I < BHEM_NB; I++)
            for (int c = 0; c < 3; c++) u->b[d[3 * I + c]] += N[I] * u->f[c] * w;
    }
    return SB_OK;
}

typedef struct mq_ud { int load; int count_only; int n; double axis[3]; } mq_ud;

static int moment_seg(bhem_state *S, bhem_level *L, const seg *sg, void *ud)
{
    mq_ud *u = ud;
    if (u->count_only) { u->n += BHEM_NQ1; return SB_OK; }
    double N[BHEM_NB], N1[BHEM_NB], N2[BHEM_NB], qe[BHEM_NED];
    bhem_gather(L, sg->elem, L->x_ref, qe);
    for (int g = 0; g < BHEM_NQ1; g++) {
        bhem_mq *m = &L->mq[u->n++];
        memset(m, 0, sizeof *m);
        m->elem = sg->elem;
        m->load = u->load;
        m->weight = seg_point(L, sg, g, N, N1, N2);
        memcpy(m->dN, sg->const_t ? N2 : N1, sizeof m->dN);     /* cross-edge derivative */
        memcpy(m->axis, u->axis, sizeof m->axis);
        double d[3] = { 0, 0, 0 };
        for (int I = 0; I < BHEM_NB; I++)
            for (int c = 0; c < 3; c++) d[c] += m->dN[I] * qe[3 * I + c];
        double ad = d[0] * m->axis[0] + d[1] * m->axis[1] + d[2] * m->axis[2];
        double ub[3] = { d[0] - ad * m->axis[0], d[1] - ad * m->axis[1], d[2] - ad * m->axis[2] };
        double l = sqrt(ub[0] * ub[0] + ub[1] * ub[1] + ub[2] * ub[2]);
        double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(l > 1e-9 * dl))
            return bhem_fail(S, SB_ERR_INPUT, "load %d: end-moment axis is parallel to the cross-edge tangent", u->load);
        for (int c = 0; c < 3; c++) m->ub[c] = ub[c] / l;
        m->e2[0] = m->axis[1] * m->ub[2] - m->axis[2] * m->ub[1];
        m->e2[1] = m->axis[2] * m->ub[0] - m->axis[0] * m->ub[2];
        m->e2[2] = m->axis[0] * m->ub[1] - m->axis[1] * m->ub[0];
        m->theta_b = 0.0;
    }
    return SB_OK;
}

static int cmp_mq(const void *a, const void *b)
{
    const bhem_mq *x = a, *y = b;
    return (x->elem > y->elem) - (x->elem < y->elem);
}

int bhem_loads_build(bhem_state *S, bhem_level *L)
{
    const sb_scene *sc = S->scene;
    int nl = sc->n_loads, nd = L->n_dofs;
    L->load_vec = calloc((size_t)(nl ? nl : 1) * (size_t)nd, sizeof(double));
    L->f_ext = calloc((size_t)nd, sizeof(double));
    L->elem_mq = calloc((size_t)L->n_elems + 1, sizeof(int));
    if (!L->load_vec || !L->f_ext || !L->elem_mq) return SB_ERR_NOMEM;
    int n_mq = 0, rc;
    for (int k = 0; k < nl; k++) {
        const sb_load *ld = &sc->loads[k];
        double *b = L->load_vec + (size_t)k * nd;
        if (ld->kind == SB_LOAD_GRAVITY || (ld->kind == SB_LOAD_PRESSURE && !ld->follower)) {
            /* gravity: f = rho g (rho areal, sb_scene.h); dead pressure: f = p nbar (BHEM §4.3) */
            for (int e = 0; e < L->n_elems; e++) {
                const int *d = L->elem_dofs + (size_t)e * BHEM_NED;
                for (int q = 0; q < BHEM_NQP; q++) {
                    const sb_shell_ref *r = &L->ref[(size_t)e * BHEM_NQP + q];
                    double f[3];
                    for (int c = 0; c < 3; c++)
                        f[c] = ld->kind == SB_LOAD_GRAVITY ? S->mat.density * ld->vec[c] : ld->value * r->normal[c];
                    for (int I = 0; I < BHEM_NB; I++)
                        for (int c = 0; c < 3; c++) b[d[3 * I + c]] += L->qb[q].N[I] * f[c] * r->dA;
                }
            }
        } else if (ld->kind == SB_LOAD_LINE) {
            line_ud u = { b, ld->vec };
            for (int p = 0; p < ld->n_parts; p++) {
                if (ld->parts[p].kind != SB_PART_EDGE)
                    return bhem_fail(S, SB_ERR_INPUT, "load %d: a line load needs edge parts", k);
                if ((rc = for_segments(S, L, &ld->parts[p], k, line_seg, &u))) return rc;
            }
        } else if (ld->kind == SB_LOAD_POINT) {
            for (int p = 0; p < ld->n_parts; p++) {
                const sb_part *pt = &ld->parts[p];
                if (pt->kind != SB_PART_POINT)
                    return bhem_fail(S, SB_ERR_INPUT, "load %d: a point load needs point parts", k);
                double th1, th2, N[BHEM_NB];
                int e = bhem_locate(L, pt->st[0], pt->st[1], &th1, &th2);
                if (e < 0) return bhem_fail(S, SB_ERR_INPUT, "load %d: point \"%s\" lies outside the domain", k, pt->name);
                bhem_basis_eval(th1, th2, L->hs, L->ht, N, NULL, NULL, NULL, NULL, NULL);
                const int *d = L->elem_dofs + (size_t)e * BHEM_NED;
                for (int I = 0; I < BHEM_NB; I++)      /* BHEM Eq. (21) */
                    for (int c = 0; c < 3; c++) b[d[3 * I + c]] += N[I] * ld->vec[c];
            }
        } else if (ld->kind == SB_LOAD_END_MOMENT) {
            mq_ud u = { k, 1, 0, { 0, 0, 0 } };
            for (int p = 0; p < ld->n_parts; p++) {
                if (ld->parts[p].kind != SB_PART_EDGE)
                    return bhem_fail(S, SB_ERR_INPUT, "load %d: an end moment needs edge parts", k);
                if ((rc = for_segments(S, L, &ld->parts[p], k, moment_seg, &u))) return rc;
            }
            n_mq += u.n;
        }
    }
    if (n_mq) {
        L->mq = malloc(sizeof(bhem_mq) * (size_t)n_mq);
        if (!L->mq) return SB_ERR_NOMEM;
        int n = 0;
        for (int k = 0; k < nl; k++) {
            const sb_load *ld = &sc->loads[k];
            if (ld->kind != SB_LOAD_END_MOMENT) continue;
            double an = sqrt(ld->vec[0] * ld->vec[0] + ld->vec[1] * ld->vec[1] + ld->vec[2] * ld->vec[2]);
            if (!(an > 0.0)) return bhem_fail(S, SB_ERR_INPUT, "load %d: end-moment axis is the zero vector", k);
            mq_ud u = { k, 0, n, { ld->vec[0] / an, ld->vec[1] / an, ld->vec[2] / an } };
            for (int p = 0; p < ld->n_parts; p++)
                if ((rc = for_segments(S, L, &ld->parts[p], k, moment_seg, &u))) return rc;
            n = u.n;
        }
        qsort(L->mq, (size_t)n_mq, sizeof(bhem_mq), cmp_mq);
        L->n_mq = n_mq;
        for (int i = 0; i < n_mq; i++) L->elem_mq[L->mq[i].elem + 1]++;
        for (int e = 0; e < L->n_elems; e++) L->elem_mq[e + 1] += L->elem_mq[e];
    }
    bhem_loads_update(S, L);
    return SB_OK;
}

/* f_ext = sum_k factor_k b_k over the dead loads (E_ext = -f_ext . x) */
void bhem_loads_update(bhem_state *S, bhem_level *L)
{
    const sb_scene *sc = S->scene;
    memset(L->f_ext, 0, sizeof(double) * (size_t)L->n_dofs);
    for (int k = 0; k < sc->n_loads; k++)
        if (is_dead(&sc->loads[k]) && S->load_factor[k] != 0.0)
            sb_axpy(L->n_dofs, S->load_factor[k], L->load_vec + (size_t)k * L->n_dofs, L->f_ext);
}

/* BHEM Eq. (20): M^IJ = int rho N_I N_J dA (rho areal), 4x4 Gauss (§6.1); the
 * same scalar block for each of the three components. */
int bhem_mass(bhem_state *S, bhem_level *L, sb_matrix *M)
{
    int qrc = bhem_level_ensure_quadrature(S, L);
    if (qrc) return qrc;
    double *Me = S->Ke;
    for (int e = 0; e < L->n_elems; e++) {
        memset(Me, 0, sizeof(double) * BHEM_NED * BHEM_NED);
        for (int q = 0; q < BHEM_NQP; q++) {
            const double *N = L->qb[q].N;
            double w = S->mat.density * L->ref[(size_t)e * BHEM_NQP + q].dA;
            for (int I = 0; I < BHEM_NB; I++)
                for (int J = 0; J < BHEM_NB; J++) {
                    double m = w * N[I] * N[J];
                    for (int c = 0; c < 3; c++) Me[(3 * I + c) * BHEM_NED + 3 * J + c] += m;
                }
        }
        sb_matrix_add_element(M, e, Me);
    }
    return SB_OK;
}

/* ---- conservative end moment ---------------------------------------------
 * Potential E = -m int theta dGamma (sb_scene.h), theta the rotation angle of
 * the cross-edge tangent d = x_,cross about the unit axis a.  With the branch
 * frame (ub, e2 = a x ub) in the plane normal to a, X = ub.d, Y = e2.d and
 *   theta = theta_b + atan2(Y, X),
 * continuous through any number of turns as long as the branch is re-centred
 * (bhem_moment_rebranch) before each step and one step rotates less than pi.
 * Derivatives: dtheta/dd = (X e2 - Y ub)/r^2, r^2 = X^2 + Y^2, and
 * d2theta/dd2 = (2XY (ub ub^T - e2 e2^T) + (Y^2 - X^2)(ub e2^T + e2 ub^T)) / r^4. */
double bhem_moment_element(bhem_state *S, bhem_level *L, int e, const double *qe, double *ge, double *Ke)
{
    double E = 0.0;
    for (int k = L->elem_mq[e]; k < L->elem_mq[e + 1]; k++) {
        const bhem_mq *m = &L->mq[k];
        double mw = S->load_factor[m->load] * S->scene->loads[m->load].value * m->weight;
        if (mw == 0.0) continue;
        double d[3] = { 0, 0, 0 };
        for (int I = 0; I < BHEM_NB; I++)
            for (int c = 0; c < 3; c++) d[c] += m->dN[I] * qe[3 * I + c];
        double X = m->ub[0] * d[0] + m->ub[1] * d[1] + m->ub[2] * d[2];
        double Y = m->e2[0] * d[0] + m->e2[1] * d[1] + m->e2[2] * d[2];
        double r2 = X * X + Y * Y;
        if (!(r2 > 0.0)) return NAN;
        E -= mw * (m->theta_b + atan2(Y, X));
        if (ge) {
            double gd[3];
            for (int c = 0; c < 3; c++) gd[c] = -mw * (X * m->e2[c] - Y * m->ub[c]) / r2;
            for (int I = 0; I < BHEM_NB; I++)
                for (int c = 0; c < 3; c++) ge[3 * I + c] += m->dN[I] * gd[c];
        }
        if (Ke) {
            double Hd[9], r4 = r2 * r2;
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    Hd[3 * a + b] = -mw * (2.0 * X * Y * (m->ub[a] * m->ub[b] - m->e2[a] * m->e2[b]) +
                                           (Y * Y - X * X) * (m->ub[a] * m->e2[b] + m->e2[a] * m->ub[b])) / r4;
            for (int I = 0; I < BHEM_NB; I++)
                for (int J = 0; J < BHEM_NB; J++) {
                    double w = m->dN[I] * m->dN[J];
                    if (w == 0.0) continue;
                    for (int a = 0; a < 3; a++)
                        for (int b = 0; b < 3; b++) Ke[(3 * I + a) * BHEM_NED + 3 * J + b] += w * Hd[3 * a + b];
                }
        }
    }
    return E;
}

void bhem_moment_rebranch(bhem_state *S, bhem_level *L, const double *x)
{
    double qe[BHEM_NED];
    (void)S;
    for (int k = 0; k < L->n_mq; k++) {
        bhem_mq *m = &L->mq[k];
        bhem_gather(L, m->elem, x, qe);
        double d[3] = { 0, 0, 0 };
        for (int I = 0; I < BHEM_NB; I++)
            for (int c = 0; c < 3; c++) d[c] += m->dN[I] * qe[3 * I + c];
        double X = m->ub[0] * d[0] + m->ub[1] * d[1] + m->ub[2] * d[2];
        double Y = m->e2[0] * d[0] + m->e2[1] * d[1] + m->e2[2] * d[2];
        double r = sqrt(X * X + Y * Y);
        if (!(r > 0.0) || !isfinite(r)) continue;       /* keep the old branch */
        double th = m->theta_b + atan2(Y, X);
        for (int c = 0; c < 3; c++) m->ub[c] = (X * m->ub[c] + Y * m->e2[c]) / r;
        m->e2[0] = m->axis[1] * m->ub[2] - m->axis[2] * m->ub[1];
        m->e2[1] = m->axis[2] * m->ub[0] - m->axis[0] * m->ub[2];
        m->e2[2] = m->axis[0] * m->ub[1] - m->axis[1] * m->ub[0];
        m->theta_b = th;
    }
}
