/* sb_render_field.c — the colour fields of a rendered surface, evaluated at
 * a hit through the shared Kirchhoff–Love kernel (sb_shell.h), so a picture
 * shows the strains the method's energy sees:
 *   curvature  mean curvature H = (e G - 2 f F + g E) / (2 (E G - F^2)) of the
 *              current surface (first and second fundamental forms; signed
 *              with the surface's own normal x_u x x_v);
 *   strain     membrane Green–Lagrange strain A = (a - abar)/2 in the local
 *              warp/weft frame (sb_shell_strains); its larger principal
 *              value, the stretch (< 0 where the membrane is compressed in
 *              every direction).  Not the principal value of largest
 *              magnitude: that jumps between the two where tension and
 *              compression are about equal, which a uniaxially pulled cloth
 *              is;
 *   softening  the smallest relative eigenvalue of the membrane tangent
 *              d2e/dA2 through the thickness (sb_shell_section_stability);
 *              negative where the law softens (what `shellbench inspect`
 *              counts as soft_membrane).
 * Patches use the Bézier basis in (u,v); triangles the linear basis in the
 * grid parameter (s,t) of their vertices, with zero second derivatives (their
 * bending strain is zero: softening on triangles is the membrane's). */
#include "sb_render_world.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int sb_field_check(const sb_surface *s, const sb_material *mat, sb_color_kind kind, char *err, size_t errlen)
{
    if (kind == SB_COLOR_NONE || kind == SB_COLOR_CURVATURE) return 0;
    if (!mat) {
        snprintf(err, errlen, "--color %s needs the scene's material", sb_color_names[kind]);
        return -1;
    }
    if ((s->n_patches && !s->patch_ref) || (s->n_tris && (!s->vert_ref || (!s->vert_st && !s->tri_st)))) {
        snprintf(err, errlen, "--color %s needs the reference surface (and, for triangles, their grid parameters), "
                 "which this surface does not carry", sb_color_names[kind]);
        return -1;
    }
    return 0;
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* mean curvature from the jet x_1, x_2, x_11, x_12, x_22 (BHEM paper Eq. 3-4 forms) */
static int mean_curvature(const double y[5][3], double *H)
{
    double n[3];
    cross3(y[0], y[1], n);
    const double l = sqrt(dot3(n, n));
    if (!(l > 1e-300)) return -1;
    for (int c = 0; c < 3; c++) n[c] /= l;
    const double E = dot3(y[0], y[0]), F = dot3(y[0], y[1]), G = dot3(y[1], y[1]);
    const double e = dot3(y[2], n), f = dot3(y[3], n), g = dot3(y[4], n);
    const double det = E * G - F * F;
    if (!(det > 0)) return -1;
    *H = (e * G - 2.0 * f * F + g * E) / (2.0 * det);
    return isfinite(*H) ? 0 : -1;
}

/* the larger principal value of the symmetric (A11, A22, A12) */
static double principal(const double A[3])
{
    const double m = 0.5 * (A[0] + A[1]), r = sqrt(0.25 * (A[0] - A[1]) * (A[0] - A[1]) + A[2] * A[2]);
    return m + r;
}

static int from_strains(sb_world *w, sb_color_kind kind, const sb_shell_basis *b, const double *q, const double *qref,
                        double *val)
{
    sb_shell_ref ref;
    double A[3], B[3];
    if (sb_shell_ref_init_basis(&ref, b, qref, w->mat->warp_angle, 1.0)) return -1;
    if (sb_shell_strains(&ref, b, q, w->shell, A, B)) return -1;
    if (kind == SB_COLOR_STRAIN) {
        *val = principal(A);
        return isfinite(*val) ? 0 : -1;
    }
    double lm, ls;
    if (sb_shell_section_stability(w->mat, A, B, &lm, &ls)) return -1;
    *val = lm;
    return 0;
}

int sb_field_at(sb_world *w, sb_color_kind kind, int hit_kind, int prim, double u, double v, double *val)
{
    const sb_surface *s = w->s;
    if (hit_kind == SB_HIT_PATCH) {
        double W[6][16];
        sb_bezier_basis(u, v, W);
        const double *q = s->patch + (size_t)prim * SB_BEZ_N;
        sb_shell_basis b = { 16, W[0], W[1], W[2], W[3], W[4], W[5] };
        if (kind == SB_COLOR_CURVATURE) {
            double y[5][3];
            memset(y, 0, sizeof y);
            for (int I = 0; I < 16; I++)
                for (int r = 0; r < 5; r++)
                    for (int c = 0; c < 3; c++) y[r][c] += W[r + 1][I] * q[3 * I + c];
            return mean_curvature(y, val);
        }
        return from_strains(w, kind, &b, q, s->patch_ref + (size_t)prim * SB_BEZ_N, val);
    }
    if (hit_kind != SB_HIT_TRIANGLE) return -1;
    const int *T = s->tri + 3 * prim;
    if (kind == SB_COLOR_CURVATURE) {
        if (!w->vcurv) return -1;
        *val = (1.0 - u - v) * w->vcurv[T[0]] + u * w->vcurv[T[1]] + v * w->vcurv[T[2]];
        return 0;
    }
    /* linear basis in (s,t): dN/d(s,t) = dN/d(b1,b2) J^-1, J = d(s,t)/d(b1,b2) */
    const double *p0, *p1, *p2;
    if (s->tri_st) {
        p0 = s->tri_st + 6 * prim;
        p1 = p0 + 2;
        p2 = p0 + 4;
    } else {
        p0 = s->vert_st + 2 * T[0];
        p1 = s->vert_st + 2 * T[1];
        p2 = s->vert_st + 2 * T[2];
    }
    const double j11 = p1[0] - p0[0], j12 = p2[0] - p0[0], j21 = p1[1] - p0[1], j22 = p2[1] - p0[1];
    const double det = j11 * j22 - j12 * j21;
    if (!(fabs(det) > 1e-300)) return -1;
    /* inverse of [[j11, j12], [j21, j22]] */
    const double i11 = j22 / det, i12 = -j12 / det, i21 = -j21 / det, i22 = j11 / det;
    const double db1[3] = { -1, 1, 0 }, db2[3] = { -1, 0, 1 };
    double N[3] = { 1.0 - u - v, u, v }, Ns[3], Nt[3], Z[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; k++) {
        Ns[k] = db1[k] * i11 + db2[k] * i21;
        Nt[k] = db1[k] * i12 + db2[k] * i22;
    }
    double q[9], qref[9];
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < 3; c++) {
            q[3 * k + c] = s->vert[3 * T[k] + c];
            qref[3 * k + c] = s->vert_ref[3 * T[k] + c];
        }
    sb_shell_basis b = { 3, N, Ns, Nt, Z, Z, Z };
    return from_strains(w, kind, &b, q, qref, val);
}

/* ---- per-vertex mean curvature of a triangle mesh ----------------------- */

typedef struct edge_key { int a, b; } edge_key;
static int cmp_edge(const void *x, const void *y)
{
    const edge_key *p = x, *q = y;
    return p->a != q->a ? (p->a < q->a ? -1 : 1) : (p->b < q->b ? -1 : p->b > q->b);
}

/* Meyer et al. 2003: K(x_i) = 1/(2 A_i) sum_j (cot alpha_ij + cot beta_ij)(x_j - x_i)
 * = 2 H n (A_i: a third of the adjacent triangles' area); H_i = K.n_i / 2
 * (K accumulates half the cotangent sums, so H_i = K.n_i / (2 A_i) below).
 * Boundary vertices (on an edge of one triangle) take the mean of their
 * interior neighbours. */
int sb_field_vertex_curvature(const sb_surface *s, const double *vnormal, double *curv)
{
    const int nv = s->n_verts, nt = s->n_tris;
    double *K = calloc((size_t)nv * 3, sizeof *K), *area = calloc((size_t)nv, sizeof *area);
    edge_key *ed = malloc((size_t)(nt ? nt : 1) * 3 * sizeof *ed);
    unsigned char *bnd = calloc((size_t)(nv ? nv : 1), 1);
    if (!K || !area || !ed || !bnd) {
        free(K); free(area); free(ed); free(bnd);
        return -1;
    }
    for (int t = 0; t < nt; t++) {
        const int *T = s->tri + 3 * t;
        for (int k = 0; k < 3; k++) {
            const int i = T[k], j = T[(k + 1) % 3], o = T[(k + 2) % 3];
            const double *xi = s->vert + 3 * i, *xj = s->vert + 3 * j, *xo = s->vert + 3 * o;
            /* the angle at o faces edge (i,j) */
            double a[3], b[3], c[3];
            for (int m = 0; m < 3; m++) { a[m] = xi[m] - xo[m]; b[m] = xj[m] - xo[m]; }
            cross3(a, b, c);
            const double sn = sqrt(dot3(c, c)), cs = dot3(a, b);
            const double cot = sn > 1e-300 ? cs / sn : 0.0;
            for (int m = 0; m < 3; m++) {
                K[3 * i + m] += 0.5 * cot * (xj[m] - xi[m]);
                K[3 * j + m] += 0.5 * cot * (xi[m] - xj[m]);
            }
            if (k == 0) for (int m = 0; m < 3; m++) area[T[m]] += sn / 6.0;
            ed[3 * t + k].a = i < j ? i : j;
            ed[3 * t + k].b = i < j ? j : i;
        }
    }
    qsort(ed, (size_t)nt * 3, sizeof *ed, cmp_edge);
    for (long e = 0; e < 3L * nt;) {
        long f = e + 1;
        while (f < 3L * nt && ed[f].a == ed[e].a && ed[f].b == ed[e].b) f++;
        if (f - e == 1) bnd[ed[e].a] = bnd[ed[e].b] = 1;
        e = f;
    }
    for (int v = 0; v < nv; v++)
        curv[v] = area[v] > 0 ? dot3(K + 3 * v, vnormal + 3 * v) / (2.0 * area[v]) : 0.0;
    /* boundary: mean of interior neighbours */
    double *sum = K;   /* reuse: sum in [3v], count in [3v+1] */
    memset(sum, 0, (size_t)nv * 3 * sizeof *sum);
    for (int t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            const int i = s->tri[3 * t + k], j = s->tri[3 * t + (k + 1) % 3];
            if (bnd[i] && !bnd[j]) { sum[3 * i] += curv[j]; sum[3 * i + 1] += 1; }
            if (bnd[j] && !bnd[i]) { sum[3 * j] += curv[i]; sum[3 * j + 1] += 1; }
        }
    for (int v = 0; v < nv; v++)
        if (bnd[v]) curv[v] = sum[3 * v + 1] > 0 ? sum[3 * v] / sum[3 * v + 1] : 0.0;
    free(K); free(area); free(ed); free(bnd);
    return 0;
}
