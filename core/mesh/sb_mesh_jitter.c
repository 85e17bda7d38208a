/* sb_mesh_jitter.c — irregular meshes: random displacement of the interior
 * vertices and Lawson's edge flips to a Delaunay triangulation (sb_mesh.h).
 *
 * Jitter.  Vertex v moves by amp (h_s u_1, h_t u_2) in (s,t), u_i uniform on
 * [-1, 1) from a GSL generator (gsl_rng_mt19937 seeded with the run's seed;
 * two draws per movable vertex in vertex order, so a seed fixes the mesh),
 * h_s / h_t the shortest nonzero |ds| / |dt| of its edges (sb_rng_alloc,
 * core/base/sb_gsl.h).  Boundary,
 * pinned and seam vertices stay.  A displacement that leaves any triangle
 * with less than a quarter of its (s,t) area, or of its area in xi, is
 * halved, for the vertices of that triangle, until no triangle is that thin
 * (at most 40 rounds).  Both areas: the triangles are straight in xi, and on
 * an annulus sector (xi not affine in (s,t)) a vertex moved inside its (s,t)
 * cells can cross the straight chord of its neighbours in xi (issue 21: an
 * inverted triangle at 359.9 deg, --res 8, and Newton's line search failed at
 * once); where the domain map is affine the two tests agree.
 *
 * Delaunay.  An interior edge is flipped when the two angles opposite it,
 * measured in material coordinates xi, sum to more than pi (Lawson 1977);
 * sweeps repeat until no edge flips.  A flip that would invert a triangle in
 * (s,t) or xi is skipped; seam edges are never flipped. */
#include "sb_mesh.h"
#include "sb_geometry.h"

#include "sb_gsl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The one place the mesh layer draws random numbers (sb_gsl.h's factory:
 * GSL's error policy, the generator named and seeded). */
static int draw_offsets(int n, const unsigned char *movable, unsigned long seed, double *u, const char **name)
{
    char err[256];
    gsl_rng *r = sb_rng_alloc("mt19937", seed, err, sizeof err);
    if (!r) return SB_ERR_NOMEM;
    for (int v = 0; v < n; v++) {
        if (!movable[v]) { u[2 * v] = u[2 * v + 1] = 0.0; continue; }
        u[2 * v] = 2.0 * gsl_rng_uniform(r) - 1.0;
        u[2 * v + 1] = 2.0 * gsl_rng_uniform(r) - 1.0;
    }
    if (name) *name = gsl_rng_name(r);   /* static string owned by GSL */
    gsl_rng_free(r);
    return SB_OK;
}

static double area2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
}

static void xi_of(const sb_scene *sc, const double *st, double *xi);

/* twice the xi area of the triangle with corner coordinates p (6 values) */
static double area2_xi(const sb_scene *sc, const double *p)
{
    double x[6];
    for (int k = 0; k < 3; k++) xi_of(sc, p + 2 * k, x + 2 * k);
    return area2(x, x + 2, x + 4);
}

int sb_mesh_jitter(sb_mesh *m, const sb_scene *sc, double amp, unsigned long seed, const char **rng_name)
{
    const int nv = m->nv, nt = m->nt;
    double *h = malloc(sizeof(double) * 2 * (size_t)nv), *d = malloc(sizeof(double) * 2 * (size_t)nv);
    double *st0 = malloc(sizeof(double) * 6 * (size_t)nt), *vst0 = malloc(sizeof(double) * 2 * (size_t)nv);
    double *a0 = malloc(sizeof(double) * 2 * (size_t)nt);   /* (s,t) and xi areas */
    unsigned char *mov = malloc((size_t)nv);
    int rc = SB_OK;
    if (!h || !d || !st0 || !vst0 || !a0 || !mov) { rc = SB_ERR_NOMEM; goto done; }
    for (int v = 0; v < nv; v++) {
        h[2 * v] = h[2 * v + 1] = INFINITY;
        mov[v] = !(m->vflag[v] & (SB_MESH_V_BOUNDARY | SB_MESH_V_PINNED | SB_MESH_V_SEAM));
    }
    for (int t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            const double *p = m->tri_st + 6 * t + 2 * k, *q = m->tri_st + 6 * t + 2 * ((k + 1) % 3);
            const int a = m->tri[3 * t + k], b = m->tri[3 * t + (k + 1) % 3];
            for (int c = 0; c < 2; c++) {
                double l = fabs(q[c] - p[c]);
                if (l > 1e-12) {
                    h[2 * a + c] = fmin(h[2 * a + c], l);
                    h[2 * b + c] = fmin(h[2 * b + c], l);
                }
            }
        }
    if ((rc = draw_offsets(nv, mov, seed, d, rng_name))) goto done;
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 2; c++) d[2 * v + c] = isfinite(h[2 * v + c]) ? amp * h[2 * v + c] * d[2 * v + c] : 0.0;
    memcpy(st0, m->tri_st, sizeof(double) * 6 * (size_t)nt);
    memcpy(vst0, m->st, sizeof(double) * 2 * (size_t)nv);
    for (int t = 0; t < nt; t++) {
        a0[t] = area2(st0 + 6 * t, st0 + 6 * t + 2, st0 + 6 * t + 4);
        a0[nt + t] = area2_xi(sc, st0 + 6 * t);
    }
    for (int round = 0; round <= 40; round++) {
        for (int t = 0; t < nt; t++)
            for (int k = 0; k < 3; k++) {
                const int v = m->tri[3 * t + k];
                m->tri_st[6 * t + 2 * k] = st0[6 * t + 2 * k] + d[2 * v];
                m->tri_st[6 * t + 2 * k + 1] = st0[6 * t + 2 * k + 1] + d[2 * v + 1];
            }
        int bad = 0;
        for (int t = 0; t < nt; t++) {
            const double *p = m->tri_st + 6 * t;
            if (area2(p, p + 2, p + 4) >= 0.25 * a0[t] && area2_xi(sc, p) >= 0.25 * a0[nt + t]) continue;
            bad++;
            for (int k = 0; k < 3; k++) {
                const int v = m->tri[3 * t + k];
                d[2 * v] *= 0.5;
                d[2 * v + 1] *= 0.5;
            }
        }
        if (!bad) break;
        if (round == 40) { memcpy(m->tri_st, st0, sizeof(double) * 6 * (size_t)nt); memset(d, 0, sizeof(double) * 2 * (size_t)nv); }
    }
    for (int v = 0; v < nv; v++) {
        m->st[2 * v] = vst0[2 * v] + d[2 * v];
        m->st[2 * v + 1] = vst0[2 * v + 1] + d[2 * v + 1];
    }
    sb_mesh_set_geometry(m, sc);
    rc = sb_mesh_delaunay(m, sc);
    if (rc > 0) rc = SB_OK;
done:
    free(h); free(d); free(st0); free(vst0); free(a0); free(mov);
    return rc;
}

/* angle at p between q - p and r - p */
static double angle_at(const double *p, const double *q, const double *r)
{
    const double a[2] = { q[0] - p[0], q[1] - p[1] }, b[2] = { r[0] - p[0], r[1] - p[1] };
    return atan2(fabs(a[0] * b[1] - a[1] * b[0]), a[0] * b[0] + a[1] * b[1]);
}

static void xi_of(const sb_scene *sc, const double *st, double *xi)
{
    sb_jet2 j;
    sb_domain_map(&sc->domain, st[0], st[1], &j);
    xi[0] = j.x[0];
    xi[1] = j.x[1];
}

/* corner (s,t) of vertex v in triangle t */
static const double *cst(const sb_mesh *m, int t, int v)
{
    for (int k = 0; k < 3; k++)
        if (m->tri[3 * t + k] == v) return m->tri_st + 6 * t + 2 * k;
    return NULL;
}

int sb_mesh_delaunay(sb_mesh *m, const sb_scene *sc)
{
    int flips = 0;
    for (int sweep = 0; sweep < 1000; sweep++) {
        int changed = 0;
        for (int e = 0; e < m->ne; e++) {
            if (m->edge_t[2 * e + 1] < 0 || !sb_mesh_flip_valid(m, e)) continue;
            const int t0 = m->edge_t[2 * e], t1 = m->edge_t[2 * e + 1];
            const int a = m->edge_v[2 * e], b = m->edge_v[2 * e + 1];
            const int c = sb_mesh_edge_opp(m, e, 0), d = sb_mesh_edge_opp(m, e, 1);
            double xa[2], xb[2], xc[2], xd[2];
            xi_of(sc, cst(m, t0, a), xa);
            xi_of(sc, cst(m, t0, b), xb);
            xi_of(sc, cst(m, t0, c), xc);
            xi_of(sc, cst(m, t1, d), xd);
            if (angle_at(xc, xa, xb) + angle_at(xd, xa, xb) <= M_PI + 1e-12) continue;
            /* the new triangles (a, d, c) and (b, c, d) must keep xi orientation */
            if (area2(xa, xd, xc) <= 0 || area2(xb, xc, xd) <= 0) continue;
            if (sb_mesh_flip(m, e)) continue;
            flips++;
            changed = 1;
        }
        if (!changed) break;
    }
    return flips;
}
