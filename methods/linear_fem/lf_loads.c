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
 * rotation about the unit axis a of the section's cross-edge tangent (the
 * vector bhem_loads.c tracks, so both methods load the same potential), in a
 * branch frame (ub, e2 = a x ub) re-centred before each step:
 * theta = theta_b + atan2(e2.N, ub.N).  The section at a boundary edge is
 * the face of its triangle rotated about the edge t = e/|e| by the director
 * angle (sigma phi with edge directors, else 0); its outward tangent is the
 * face normal u rotated by alpha = director + pi/2:
 *   |u| D = N(alpha) = cos(alpha) u + sin(alpha) (e x u)/|e|.
 * (Tracking the section's normal instead gives a different 3D potential whose
 * planar roll-up loses stability at ~1.6 pi with edge directors; tracking the
 * face normal alone adds a spurious twisting mode.  Both were tried.)
 * Derivatives, with omega = (X q - Y p)/r^2 (p = ub, q = e2, X = p.N, Y = q.N):
 *   dtheta = omega . dN,
 *   d2theta = dN^T Theta dN + omega . d2N,
 *   Theta = (2XY (p p^T - q q^T) + (Y^2 - X^2)(p q^T + q p^T)) / r^4,
 *   dN = [cos(alpha) I + sin(alpha) [e]x/l] du + sin(alpha) (-[u]x - g e^T/l)/l de
 *        + (cos(alpha) g - sin(alpha) u) dalpha,   g = (e x u)/l, l = |e|,
 * and with s = omega . g = e.(u x omega)/l:
 *   omega.d2N: (u,e) sin(alpha) s_ue, (e,e) sin(alpha) s_ee,
 *   (alpha,alpha) -omega.(cos(alpha) u + sin(alpha) g),
 *   (alpha,u) cos(alpha) s_u - sin(alpha) omega, (alpha,e) cos(alpha) s_e. */
#include "sb_vec3.h"
#include "lf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


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
    const double an = sqrt(sb_dot3(ld->vec, ld->vec));
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
            q->weight = sqrt(sb_dot3(ed, ed));
            memcpy(q->axis, ax, sizeof ax);
            /* reference section tangent: the outward in-plane normal of the edge, t x N */
            double N[3];
            for (int c = 0; c < 3; c++) ed[c] /= q->weight;
            sb_cross3(ed, L->tri[q->tri].ref.normal, N);
            const double aN = sb_dot3(N, ax);
            double ub[3] = { N[0] - aN * ax[0], N[1] - aN * ax[1], N[2] - aN * ax[2] };
            const double l = sqrt(sb_dot3(ub, ub));
            if (!(l > 1e-9))
                return lf_fail(S, SB_ERR_INPUT, "loads[%d]: end-moment axis is parallel to the cross-edge tangent on \"%s\"",
                               k, pt->name);
            for (int c = 0; c < 3; c++) q->ub[c] = ub[c] / l;
            sb_cross3(q->axis, q->ub, q->e2);
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
                sb_mesh_lump_line_load(m, tmp, ne, ld->vec, b);
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

/* theta(N) of one moment edge at (u, e, alpha): value, gradient over
 * (u, -, e) in g9 and d/dalpha in *ga, Hessian blocks in H9 (9 x 9), the
 * (alpha, u|e) column in Ha9 and d2/dalpha2 in *Haa. */
static double edge_normal_angle(const lf_mq *q, const double u[3], const double e[3], double alpha, double *g9,
                                double *ga, double *H9, double *Ha9, double *Haa)
{
    const double l = sqrt(sb_dot3(e, e)), ca = cos(alpha), sa = sin(alpha);
    double gv[3], N[3];
    sb_cross3(e, u, gv);
    for (int c = 0; c < 3; c++) {
        gv[c] /= l;
        N[c] = ca * u[c] + sa * gv[c];
    }
    const double *p = q->ub, *qq = q->e2;
    const double X = sb_dot3(p, N), Y = sb_dot3(qq, N), r2 = X * X + Y * Y;
    const double th = atan2(Y, X);
    if (!g9) return th;
    double om[3];
    for (int c = 0; c < 3; c++) om[c] = (X * qq[c] - Y * p[c]) / r2;
    /* J = dN/d(u, e, alpha): 3 x 7 (column-major blocks Ju, Je, Ja) */
    double Ju[9], Je[9], Ja[3];
    const double eh[3] = { e[0] / l, e[1] / l, e[2] / l };
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            const double Ex = (i == j) ? 0.0 : (((i + 1) % 3 == j) ? -e[3 - i - j] : e[3 - i - j]);   /* [e]x_ij */
            const double Ux = (i == j) ? 0.0 : (((i + 1) % 3 == j) ? -u[3 - i - j] : u[3 - i - j]);   /* [u]x_ij */
            Ju[3 * i + j] = ca * (i == j) + sa * Ex / l;
            Je[3 * i + j] = sa * (-Ux - gv[i] * eh[j]) / l;
        }
        Ja[i] = ca * gv[i] - sa * u[i];
    }
    memset(g9, 0, 9 * sizeof *g9);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            g9[j] += om[i] * Ju[3 * i + j];
            g9[6 + j] += om[i] * Je[3 * i + j];
        }
    *ga = sb_dot3(om, Ja);
    if (!H9) return th;
    double Th[9];
    const double r4 = r2 * r2;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            Th[3 * a + b] = (2.0 * X * Y * (p[a] * p[b] - qq[a] * qq[b]) + (Y * Y - X * X) * (p[a] * qq[b] + qq[a] * p[b])) / r4;
    /* J^T Theta J over (u, e, alpha) */
    double J[3][7];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            J[i][j] = Ju[3 * i + j];
            J[i][3 + j] = Je[3 * i + j];
        }
        J[i][6] = Ja[i];
    }
    double TJ[3][7], K[7][7];
    for (int i = 0; i < 3; i++)
        for (int b = 0; b < 7; b++) TJ[i][b] = Th[3 * i] * J[0][b] + Th[3 * i + 1] * J[1][b] + Th[3 * i + 2] * J[2][b];
    for (int a = 0; a < 7; a++)
        for (int b = 0; b < 7; b++) K[a][b] = J[0][a] * TJ[0][b] + J[1][a] * TJ[1][b] + J[2][a] * TJ[2][b];
    /* omega . d2N through s = e.(u x omega)/l */
    double uxo[3], oxe[3];
    sb_cross3(u, om, uxo);
    sb_cross3(om, e, oxe);
    const double E = sb_dot3(e, uxo), s = E / l;
    double s_u[3], s_e[3], s_ue[9], s_ee[9];
    for (int c = 0; c < 3; c++) {
        s_u[c] = oxe[c] / l;
        s_e[c] = uxo[c] / l - E * e[c] / (l * l * l);
    }
    const double l3 = l * l * l, l5 = l3 * l * l;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double Ox = (i == j) ? 0.0 : (((i + 1) % 3 == j) ? -om[3 - i - j] : om[3 - i - j]);   /* [omega]x_ij */
            s_ue[3 * i + j] = Ox / l - oxe[i] * e[j] / l3;
            s_ee[3 * i + j] = -(uxo[i] * e[j] + uxo[j] * e[i]) / l3 - E * (i == j) / l3 + 3.0 * E * e[i] * e[j] / l5;
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            K[i][3 + j] += sa * s_ue[3 * i + j];
            K[3 + j][i] += sa * s_ue[3 * i + j];
            K[3 + i][3 + j] += sa * s_ee[3 * i + j];
        }
    K[6][6] += -(ca * sb_dot3(om, u) + sa * s);
    for (int c = 0; c < 3; c++) {
        const double au = ca * s_u[c] - sa * om[c], ae = ca * s_e[c];
        K[6][c] += au; K[c][6] += au;
        K[6][3 + c] += ae; K[3 + c][6] += ae;
    }
    memset(H9, 0, 81 * sizeof *H9);
    for (int a = 0; a < 6; a++) {
        const int ia = a < 3 ? a : a + 3;
        for (int b = 0; b < 6; b++) H9[9 * ia + (b < 3 ? b : b + 3)] = K[a][b];
        Ha9[ia] = K[6][a];
    }
    for (int c = 3; c < 6; c++) Ha9[c] = 0.0;
    *Haa = K[6][6];
    return th;
}

double lf_moment_energy(lf_state *S, lf_level *L, int t, const double *qe, double *ge, double *Ke)
{
    double E = 0.0;
    const int n = lf_ned(S);
    for (int k = L->tri_mq[t]; k < L->tri_mq[t + 1]; k++) {
        const lf_mq *q = &L->mq[k];
        const double mw = S->load_factor[q->load] * S->scene->loads[q->load].value * q->weight;
        if (mw == 0.0) continue;
        const int sa = (q->slot + 1) % 3, sb = (q->slot + 2) % 3;
        double P[9], e[3], u[3];
        memcpy(P, qe, sizeof P);
        for (int c = 0; c < 3; c++) e[c] = qe[3 * sb + c] - qe[3 * sa + c];
        {
            double a1[3], a2[3];
            for (int c = 0; c < 3; c++) {
                a1[c] = qe[3 + c] - qe[c];
                a2[c] = qe[6 + c] - qe[c];
            }
            sb_cross3(a1, a2, u);
        }
        /* the triangle runs the edge in the edge's own orientation (it is edge_t[0]): sigma = +1 */
        const int dphi = S->edge_dofs ? 18 + q->slot : -1;
        const double alpha = (dphi >= 0 ? qe[dphi] : 0.0) + 0.5 * M_PI;   /* the section's tangent D */
        const int need = ge || Ke;
        double g9[9], ga = 0.0, H9[81], Ha9[9], Haa = 0.0;
        const double th = edge_normal_angle(q, u, e, alpha, need ? g9 : NULL, &ga, Ke ? H9 : NULL, Ha9, &Haa);
        if (!isfinite(th)) return NAN;
        E -= mw * (q->theta_b + th);
        if (!need) continue;
        for (int i = 0; i < 9; i++) g9[i] *= -mw;
        if (Ke) for (int i = 0; i < 81; i++) H9[i] *= -mw;
        lf_dep dep[3];
        lf_dep_normal(&dep[0], P, 0, 1, 2);
        dep[1].kind = LF_DEP_CONST;
        lf_dep_edge(&dep[2], sa, sb);
        lf_chain(dep, g9, Ke ? H9 : NULL, n, ge, Ke);
        if (dphi < 0) continue;
        if (ge) ge[dphi] -= mw * ga;
        if (Ke) {
            /* alpha column: chain d2theta/dalpha d(u, e) to the points */
            double G[9];
            memset(G, 0, sizeof G);
            double h9[9];
            for (int i = 0; i < 9; i++) h9[i] = -mw * Ha9[i];
            lf_chain(dep, h9, NULL, 0, G, NULL);
            for (int a = 0; a < 9; a++) {
                Ke[dphi * n + a] += G[a];
                Ke[a * n + dphi] += G[a];
            }
            Ke[dphi * n + dphi] += -mw * Haa;
        }
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
        sb_cross3(a1, a2, u);
        /* the edge normal N (see lf_moment_energy) */
        const int sa = (q->slot + 1) % 3, sb = (q->slot + 2) % 3;
        const double alpha = (S->edge_dofs ? qe[18 + q->slot] : 0.0) + 0.5 * M_PI;
        double e[3], g[3];
        for (int c = 0; c < 3; c++) e[c] = qe[3 * sb + c] - qe[3 * sa + c];
        sb_cross3(e, u, g);
        const double l = sqrt(sb_dot3(e, e));
        for (int c = 0; c < 3; c++) u[c] = cos(alpha) * u[c] + sin(alpha) * g[c] / l;
        const double X = sb_dot3(q->ub, u), Y = sb_dot3(q->e2, u), r = sqrt(X * X + Y * Y);
        if (!(r > 0.0) || !isfinite(r)) continue;
        const double th = q->theta_b + atan2(Y, X);
        for (int c = 0; c < 3; c++) q->ub[c] = (X * q->ub[c] + Y * q->e2[c]) / r;
        sb_cross3(q->axis, q->ub, q->e2);
        q->theta_b = th;
    }
}
