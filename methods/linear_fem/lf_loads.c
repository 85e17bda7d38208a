/* lf_loads.c — loads and mass of linear_fem.
 *
 * Dead loads as consistent nodal forces of the linear basis (exact integrals
 * of N_I f over the reference triangles and edges): gravity rho g A/3 per
 * corner, dead pressure p N A/3 per corner (N the reference face normal),
 * line loads f l/2 per end of every boundary edge on the part, point loads at
 * their vertex or split by the barycentric coordinates of the point.
 * Follower pressure: the enclosed-volume potential -p det(p0,p1,p2)/6 per
 * triangle (lf_element.c; the same potential as sb_shell_ext.c).
 * Mass: consistent rho A/12 (1 + delta_ij) per triangle and component, or
 * row-sum lumped rho A/3 (method.mass); edge directors carry no mass.
 *
 * End moment (conservative, sb_scene.h: E = -m int theta dGamma): theta is the
 * rotation about the unit axis a of the face normal u of the boundary
 * triangle, theta = theta_b + atan2(e2.u, ub.u) in a branch frame (ub, e2 =
 * a x ub) re-centred before each step (as bhem_loads.c does for its cross
 * tangent).  With edge directors the moment acts on the midedge normal: when
 * the edge is parallel to a its normal is the face normal rotated by sigma phi
 * about a, so theta gains +-phi (exact for the edge-parallel axes of the
 * roll-up scenes; for other axes the face normal alone is used). */
#include "lf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static int is_dead(const sb_load *ld)
{
    return ld->kind == SB_LOAD_GRAVITY || ld->kind == SB_LOAD_LINE || ld->kind == SB_LOAD_POINT ||
           (ld->kind == SB_LOAD_PRESSURE && !ld->follower);
}

static int cmp_mq(const void *a, const void *b)
{
    const lf_mq *x = a, *y = b;
    return (x->tri > y->tri) - (x->tri < y->tri);
}

static int moment_points(lf_state *S, lf_level *L, int k, lf_mq *out, int *tmp)
{
    const sb_load *ld = &S->scene->loads[k];
    const sb_mesh *m = &L->mesh;
    const double an = sqrt(dot3(ld->vec, ld->vec));
    if (!(an > 0.0)) return lf_fail(S, SB_ERR_INPUT, "loads[%d]: end-moment axis is the zero vector", k);
    const double ax[3] = { ld->vec[0] / an, ld->vec[1] / an, ld->vec[2] / an };
    int n = 0;
    for (int p = 0; p < ld->n_parts; p++) {
        const sb_part *pt = &ld->parts[p];
        if (pt->kind != SB_PART_EDGE) return lf_fail(S, SB_ERR_INPUT, "loads[%d]: an end moment needs edge parts", k);
        const int ne = sb_mesh_part_edges(m, pt, tmp);
        if (ne <= 0) return lf_fail(S, SB_ERR_INPUT, "loads[%d]: edge \"%s\" has no boundary edge in the mesh", k, pt->name);
        for (int j = 0; j < ne; j++, n++) {
            if (!out) continue;
            const int e = tmp[j];
            lf_mq *q = &out[n];
            memset(q, 0, sizeof *q);
            q->tri = m->edge_t[2 * e];
            q->slot = m->edge_k[2 * e];
            q->edge = e;
            q->load = k;
            const double *Xa = m->X + 3 * m->edge_v[2 * e], *Xb = m->X + 3 * m->edge_v[2 * e + 1];
            double ed[3];
            for (int c = 0; c < 3; c++) ed[c] = Xb[c] - Xa[c];
            q->weight = sqrt(dot3(ed, ed));
            memcpy(q->axis, ax, sizeof ax);
            const double ta = dot3(ed, ax) / q->weight;
            q->phi_sign = S->edge_dofs && fabs(ta) > 1.0 - 1e-9 ? (ta > 0 ? 1.0 : -1.0) : 0.0;
            const double *N = L->tri[q->tri].ref.normal, aN = dot3(N, ax);
            double ub[3] = { N[0] - aN * ax[0], N[1] - aN * ax[1], N[2] - aN * ax[2] };
            const double l = sqrt(dot3(ub, ub));
            if (!(l > 1e-9))
                return lf_fail(S, SB_ERR_INPUT, "loads[%d]: end-moment axis is parallel to the surface normal on \"%s\"",
                               k, pt->name);
            for (int c = 0; c < 3; c++) q->ub[c] = ub[c] / l;
            cross3(q->axis, q->ub, q->e2);
        }
    }
    return n;
}

int lf_loads_build(lf_state *S, lf_level *L)
{
    const sb_scene *sc = S->scene;
    const sb_mesh *m = &L->mesh;
    const int nl = sc->n_loads, nd = L->n_dofs;
    L->load_vec = calloc((size_t)(nl ? nl : 1) * (size_t)nd, sizeof(double));
    L->f_ext = calloc((size_t)nd, sizeof(double));
    L->tri_mq = calloc((size_t)L->nt + 1, sizeof(int));
    int *tmp = malloc(sizeof(int) * (size_t)(m->ne + m->nv + 1));
    if (!L->load_vec || !L->f_ext || !L->tri_mq || !tmp) { free(tmp); return SB_ERR_NOMEM; }
    int rc = SB_OK, n_mq = 0;
    for (int k = 0; k < nl && rc == SB_OK; k++) {
        const sb_load *ld = &sc->loads[k];
        double *b = L->load_vec + (size_t)k * nd;
        if (ld->kind == SB_LOAD_GRAVITY || (ld->kind == SB_LOAD_PRESSURE && !ld->follower)) {
            for (int t = 0; t < L->nt; t++) {
                const lf_tri *T = &L->tri[t];
                double f[3];
                for (int c = 0; c < 3; c++)
                    f[c] = (ld->kind == SB_LOAD_GRAVITY ? S->mat.density * ld->vec[c] : ld->value * T->ref.normal[c]) *
                           T->ref.dA / 3.0;
                for (int i = 0; i < 3; i++)
                    for (int c = 0; c < 3; c++) b[3 * T->v[i] + c] += f[c];
            }
        } else if (ld->kind == SB_LOAD_LINE) {
            for (int p = 0; p < ld->n_parts && rc == SB_OK; p++) {
                if (ld->parts[p].kind != SB_PART_EDGE) { rc = lf_fail(S, SB_ERR_INPUT, "loads[%d]: a line load needs edge parts", k); break; }
                const int ne = sb_mesh_part_edges(m, &ld->parts[p], tmp);
                if (ne <= 0) { rc = lf_fail(S, SB_ERR_INPUT, "loads[%d]: edge \"%s\" has no boundary edge in the mesh", k, ld->parts[p].name); break; }
                for (int j = 0; j < ne; j++) {
                    const int a = m->edge_v[2 * tmp[j]], bb = m->edge_v[2 * tmp[j] + 1];
                    double ed[3];
                    for (int c = 0; c < 3; c++) ed[c] = m->X[3 * bb + c] - m->X[3 * a + c];
                    const double l = sqrt(dot3(ed, ed));
                    for (int c = 0; c < 3; c++) {
                        b[3 * a + c] += 0.5 * l * ld->vec[c];
                        b[3 * bb + c] += 0.5 * l * ld->vec[c];
                    }
                }
            }
        } else if (ld->kind == SB_LOAD_POINT) {
            for (int p = 0; p < ld->n_parts && rc == SB_OK; p++) {
                const sb_part *pt = &ld->parts[p];
                if (pt->kind != SB_PART_POINT) { rc = lf_fail(S, SB_ERR_INPUT, "loads[%d]: a point load needs point parts", k); break; }
                double w[3];
                const int t = sb_mesh_locate(m, &L->loc, pt->st[0], pt->st[1], w);
                if (t < 0) { rc = lf_fail(S, SB_ERR_INPUT, "loads[%d]: point \"%s\" lies outside the mesh", k, pt->name); break; }
                for (int i = 0; i < 3; i++)
                    for (int c = 0; c < 3; c++) b[3 * m->tri[3 * t + i] + c] += w[i] * ld->vec[c];
            }
        } else if (ld->kind == SB_LOAD_END_MOMENT) {
            const int n = moment_points(S, L, k, NULL, tmp);
            if (n < 0) rc = n;
            else n_mq += n;
        }
    }
    if (rc == SB_OK && n_mq) {
        L->mq = malloc(sizeof(lf_mq) * (size_t)n_mq);
        if (!L->mq) rc = SB_ERR_NOMEM;
        int n = 0;
        for (int k = 0; k < nl && rc == SB_OK; k++)
            if (sc->loads[k].kind == SB_LOAD_END_MOMENT) {
                const int c = moment_points(S, L, k, L->mq + n, tmp);
                if (c < 0) rc = c;
                else n += c;
            }
        if (rc == SB_OK) {
            qsort(L->mq, (size_t)n_mq, sizeof(lf_mq), cmp_mq);
            L->n_mq = n_mq;
            for (int i = 0; i < n_mq; i++) L->tri_mq[L->mq[i].tri + 1]++;
            for (int t = 0; t < L->nt; t++) L->tri_mq[t + 1] += L->tri_mq[t];
        }
    }
    free(tmp);
    if (rc) return rc;
    lf_loads_update(S, L);
    return SB_OK;
}

/* f_ext = sum_k factor_k b_k over the dead loads (E_ext = -f_ext . (x - x_ref)) */
void lf_loads_update(lf_state *S, lf_level *L)
{
    const sb_scene *sc = S->scene;
    memset(L->f_ext, 0, sizeof(double) * (size_t)L->n_dofs);
    for (int k = 0; k < sc->n_loads; k++)
        if (is_dead(&sc->loads[k]) && S->load_factor[k] != 0.0)
            sb_axpy(L->n_dofs, S->load_factor[k], L->load_vec + (size_t)k * L->n_dofs, L->f_ext);
}

int lf_mass(lf_state *S, lf_level *L, sb_matrix *M)
{
    const int n = lf_ned(S);
    double *Me = S->Ke;
    for (int t = 0; t < L->nt; t++) {
        memset(Me, 0, sizeof(double) * (size_t)n * n);
        const double m = S->mat.density * L->tri[t].ref.dA;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double v = S->lumped ? (i == j ? m / 3.0 : 0.0) : m * (i == j ? 2.0 : 1.0) / 12.0;
                for (int c = 0; c < 3; c++) Me[(3 * i + c) * n + 3 * j + c] = v;
            }
        sb_matrix_add_element(M, t, Me);
    }
    return SB_OK;
}

/* theta(u) = atan2(e2.u, ub.u) and its derivatives w.r.t. u (bhem_loads.c form) */
double lf_moment_energy(lf_state *S, lf_level *L, int t, const double *qe, double *ge, double *Ke)
{
    double E = 0.0;
    const int n = lf_ned(S);
    for (int k = L->tri_mq[t]; k < L->tri_mq[t + 1]; k++) {
        const lf_mq *q = &L->mq[k];
        const double mw = S->load_factor[q->load] * S->scene->loads[q->load].value * q->weight;
        if (mw == 0.0) continue;
        const double *p0 = qe, *p1 = qe + 3, *p2 = qe + 6;
        double a1[3], a2[3], u[3];
        for (int c = 0; c < 3; c++) {
            a1[c] = p1[c] - p0[c];
            a2[c] = p2[c] - p0[c];
        }
        cross3(a1, a2, u);
        const double X = dot3(q->ub, u), Y = dot3(q->e2, u), r2 = X * X + Y * Y;
        if (!(r2 > 0.0)) return NAN;
        const double phi = q->phi_sign != 0.0 ? q->phi_sign * qe[18 + q->slot] : 0.0;
        E -= mw * (q->theta_b + atan2(Y, X) + phi);
        if (!ge && !Ke) continue;
        double g9[9] = { 0 }, H81[81];
        for (int c = 0; c < 3; c++) g9[c] = -mw * (X * q->e2[c] - Y * q->ub[c]) / r2;
        if (Ke) {
            memset(H81, 0, sizeof H81);
            const double r4 = r2 * r2;
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    H81[9 * a + b] = -mw * (2.0 * X * Y * (q->ub[a] * q->ub[b] - q->e2[a] * q->e2[b]) +
                                            (Y * Y - X * X) * (q->ub[a] * q->e2[b] + q->e2[a] * q->ub[b])) / r4;
        }
        lf_dep dep[3];
        lf_dep_normal(&dep[0], qe, 0, 1, 2);
        dep[1].kind = dep[2].kind = LF_DEP_CONST;
        lf_chain(dep, g9, Ke ? H81 : NULL, n, ge, Ke);
        if (ge && q->phi_sign != 0.0) ge[18 + q->slot] -= mw * q->phi_sign;
    }
    return E;
}

void lf_moment_rebranch(lf_state *S, lf_level *L, const double *x)
{
    double qe[LF_NED_MAX];
    for (int k = 0; k < L->n_mq; k++) {
        lf_mq *q = &L->mq[k];
        lf_gather(S, L, q->tri, x, qe);
        double a1[3], a2[3], u[3];
        for (int c = 0; c < 3; c++) {
            a1[c] = qe[3 + c] - qe[c];
            a2[c] = qe[6 + c] - qe[c];
        }
        cross3(a1, a2, u);
        const double X = dot3(q->ub, u), Y = dot3(q->e2, u), r = sqrt(X * X + Y * Y);
        if (!(r > 0.0) || !isfinite(r)) continue;
        const double th = q->theta_b + atan2(Y, X);
        for (int c = 0; c < 3; c++) q->ub[c] = (X * q->ub[c] + Y * q->e2[c]) / r;
        cross3(q->axis, q->ub, q->e2);
        q->theta_b = th;
    }
}
