/* sb_mesh_domain.c — triangulations of the scene domains (sb_mesh.h).
 *
 * Grid.  The grid parameter square (s,t) in [0,1]^2 is cut into n_s x n_t
 * cells by lines that are uniform in s and in t, except on an L-shape: there
 * the line of each notch edge (notch_s at s = c) is a grid line, with
 * round(n c) uniform cells on one side and the rest uniform on the other (as
 * the rmtr method cuts its cage), so the notch is exact at every resolution
 * n >= 2 and survives 1-to-4 refinement.  A cell belongs to the mesh when its
 * centre lies in the domain (sb_domain_contains_st).  Rectangles and
 * L-shapes map (s,t) affinely onto the bounding box; an annulus sector is cut
 * along its radius (s, n_s cells) and its angle (t, n_t cells) and its
 * triangles are straight in xi between vertices on the arcs (a polygonal
 * annulus that converges to the curved one under refinement).
 *
 * Patterns (corners v00, v10, v11, v01 of cell (i, j), counter-clockwise):
 *   regular    diagonal v00-v11 in every cell
 *   alternate  diagonal v00-v11 when i + j is even, v10-v01 when odd
 *   crossed    a vertex at the cell centre (cell_centre: the (s,t) midpoint,
 *              on an annulus a point inside the straight quadrilateral), four
 *              triangles around it
 *   jitter     alternate, then sb_mesh_jitter (interior vertices displaced,
 *              Delaunay flips)
 *
 * Identification.  Vertices whose reference positions coincide (within 1e-9
 * of the size of the surface) are merged: a closed annulus or cylinder gets
 * one seam, an annulus with r_in = 0 one centre vertex; triangles that lose a
 * corner to the merge are dropped.  Merged vertices are pinned (SB_MESH_V_SEAM).
 * Slits (docs/scene_format.md "Closed surfaces and slits", the rule of
 * bhem_detect_periodic): when a boundary condition other than free, or a
 * load, names an edge of a seam (s = 0 or 1, t = 0 or 1: start / end of a
 * full annulus, left / right of a full cylinder), a vertex on one lip is
 * never merged with one on the other: the seam stays open, its two edges keep
 * their own conditions, and sb_mesh.slit says so.  (A point where the lips
 * meet another identification, the centre of a disc, is still merged through
 * the vertices between them.) */
#include "sb_mesh.h"
#include "sb_geometry.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const sb_mesh_pattern_names[] = { "alternate", "regular", "crossed", "jitter", NULL };

static int failf(char *err, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int failf(char *err, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (err && len) vsnprintf(err, len, fmt, ap);
    va_end(ap);
    return SB_ERR_INPUT;
}

/* grid lines 0 = u_0 < ... < u_n = 1, with a line at c (0 < c < 1) when has_c */
static int grid_lines(int n, int has_c, double c, double *u)
{
    if (!has_c) {
        for (int i = 0; i <= n; i++) u[i] = (double)i / n;
        return SB_OK;
    }
    if (n < 2) return SB_ERR_INPUT;
    int lo = (int)lround(n * c);
    if (lo < 1) lo = 1;
    if (lo > n - 1) lo = n - 1;
    for (int i = 0; i <= lo; i++) u[i] = c * i / lo;
    for (int i = lo + 1; i <= n; i++) u[i] = c + (1.0 - c) * (i - lo) / (n - lo);
    u[lo] = c;
    u[n] = 1.0;
    return SB_OK;
}

void sb_mesh_set_geometry(sb_mesh *m, const sb_scene *sc)
{
    for (int v = 0; v < m->nv; v++) {
        sb_jet2 d;
        sb_jet3 X;
        sb_domain_map(&sc->domain, m->st[2 * v], m->st[2 * v + 1], &d);
        sb_chart_eval(&sc->chart, &sc->domain, d.x, &X);
        m->xi[2 * v] = d.x[0];
        m->xi[2 * v + 1] = d.x[1];
        memcpy(m->X + 3 * v, X.x, sizeof X.x);
    }
}

void sb_mesh_tag_boundary(sb_mesh *m, const sb_scene *sc)
{
    const char *const *names = sb_domain_part_names(sc->domain.kind);
    for (int e = 0; e < m->ne; e++) {
        m->edge_part[e] = 0;
        if (m->edge_t[2 * e + 1] >= 0) continue;
        for (int p = 0; names[p]; p++) {
            sb_part part;
            if (sb_domain_edge_part(&sc->domain, names[p], &part)) continue;
            /* both corners of the edge (corner coordinates of its triangle) */
            const int t = m->edge_t[2 * e], k = m->edge_k[2 * e];
            const double *a = m->tri_st + 6 * t + 2 * ((k + 1) % 3), *b = m->tri_st + 6 * t + 2 * ((k + 2) % 3);
            int on = sb_part_contains_st(&part, a[0], a[1], 1e-9) && sb_part_contains_st(&part, b[0], b[1], 1e-9);
            if (on) m->edge_part[e] |= 1u << p;
        }
    }
}

typedef struct vkey { double x; int v; } vkey;
static int cmp_vkey(const void *a, const void *b)
{
    const vkey *p = a, *q = b;
    return p->x < q->x ? -1 : p->x > q->x ? 1 : (p->v > q->v) - (p->v < q->v);
}

/* Does a bc (other than free) or a load name an edge on the seam of direction
 * dir (s = 0 / 1 when dir = 0, t = 0 / 1 when dir = 1)?  As bhem_grid.c. */
static int part_on_seam(const sb_part *p, int dir)
{
    return p->kind == SB_PART_EDGE && p->st0[dir] == p->st1[dir] && (p->st0[dir] == 0.0 || p->st0[dir] == 1.0);
}

static unsigned seams_named(const sb_scene *sc)
{
    unsigned mask = 0;
    for (int dir = 0; dir < 2; dir++) {
        for (int b = 0; b < sc->n_bcs; b++)
            for (int k = 0; k < sc->bcs[b].n_parts && sc->bcs[b].kind != SB_BC_FREE; k++)
                if (part_on_seam(&sc->bcs[b].parts[k], dir)) mask |= 1u << dir;
        for (int l = 0; l < sc->n_loads; l++)
            for (int k = 0; k < sc->loads[l].n_parts; k++)
                if (part_on_seam(&sc->loads[l].parts[k], dir)) mask |= 1u << dir;
    }
    return mask;
}

/* vertices a, b on the two lips of a seam in one of the directions of mask */
static unsigned across_lips(const sb_mesh *m, int a, int b, unsigned mask)
{
    unsigned hit = 0;
    for (int dir = 0; dir < 2; dir++) {
        if (!(mask & (1u << dir))) continue;
        const double u = m->st[2 * a + dir], w = m->st[2 * b + dir];
        if ((u == 0.0 && w == 1.0) || (u == 1.0 && w == 0.0)) hit |= 1u << dir;
    }
    return hit;
}

/* merge vertices with coincident reference positions, except across the lips
 * of the seams in keep_open (sets m->slit); compact */
static int merge_coincident(sb_mesh *m, unsigned keep_open)
{
    const int nv = m->nv;
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], m->X[3 * v + c]);
            hi[c] = fmax(hi[c], m->X[3 * v + c]);
        }
    const double tol = 1e-9 * sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
    vkey *k = malloc(sizeof(vkey) * (size_t)nv);
    int *rep = malloc(sizeof(int) * (size_t)nv), *newid = malloc(sizeof(int) * (size_t)nv);
    if (!k || !rep || !newid) { free(k); free(rep); free(newid); return SB_ERR_NOMEM; }
    for (int v = 0; v < nv; v++) {
        k[v].x = m->X[3 * v];
        k[v].v = v;
        rep[v] = v;
    }
    qsort(k, (size_t)nv, sizeof *k, cmp_vkey);
    for (int i = 0; i < nv; i++)
        for (int j = i + 1; j < nv && k[j].x - k[i].x <= tol; j++) {
            const double *a = m->X + 3 * k[i].v, *b = m->X + 3 * k[j].v;
            double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
            if (d > tol) continue;
            const unsigned lips = across_lips(m, k[i].v, k[j].v, keep_open);
            if (lips) { m->slit |= lips; continue; }
            int ri = k[i].v, rj = k[j].v;
            while (rep[ri] != ri) ri = rep[ri];
            while (rep[rj] != rj) rj = rep[rj];
            if (ri == rj) continue;
            if (ri < rj) rep[rj] = ri; else rep[ri] = rj;
        }
    int merged = 0;
    for (int v = 0; v < nv; v++) {
        int r = v;
        while (rep[r] != r) r = rep[r];
        rep[v] = r;
        if (r != v) {
            merged = 1;
            m->vflag[r] |= SB_MESH_V_SEAM | SB_MESH_V_PINNED;
        }
    }
    free(k);
    if (!merged) { free(rep); free(newid); return SB_OK; }
    /* remap triangles, drop those that lost a corner */
    int nt = 0;
    for (int t = 0; t < m->nt; t++) {
        int a = rep[m->tri[3 * t]], b = rep[m->tri[3 * t + 1]], c = rep[m->tri[3 * t + 2]];
        if (a == b || b == c || c == a) continue;
        m->tri[3 * nt] = a; m->tri[3 * nt + 1] = b; m->tri[3 * nt + 2] = c;
        memmove(m->tri_st + 6 * nt, m->tri_st + 6 * t, 6 * sizeof(double));
        m->tgen[nt] = m->tgen[t];
        nt++;
    }
    m->nt = nt;
    for (int v = 0; v < nv; v++) newid[v] = -1;
    for (int i = 0; i < 3 * nt; i++) newid[m->tri[i]] = 0;
    int n = 0;
    for (int v = 0; v < nv; v++) {
        if (newid[v] < 0) continue;
        newid[v] = n;
        memmove(m->st + 2 * n, m->st + 2 * v, 2 * sizeof(double));
        memmove(m->xi + 2 * n, m->xi + 2 * v, 2 * sizeof(double));
        memmove(m->X + 3 * n, m->X + 3 * v, 3 * sizeof(double));
        m->vgen[n] = m->vgen[v];
        m->vflag[n] = m->vflag[v];
        n++;
    }
    m->nv = n;
    for (int i = 0; i < 3 * nt; i++) m->tri[i] = newid[m->tri[i]];
    free(rep);
    free(newid);
    return SB_OK;
}

/* The centre vertex of a crossed cell [s0,s1] x [t0,t1].  The triangles are
 * straight in xi and, for location and interpolation, in (s,t): the centre
 * must lie inside the cell in (s,t) and inside the straight quadrilateral of
 * its corners in xi.  Where the domain map is affine the (s,t) midpoint does
 * both.  On an annulus sector (s radial, t angular, cell [r0,r1] x dtheta) the
 * (s,t) midpoint lies at radius (r0 + r1)/2 while the outer chord of the cell
 * passes the mid-angle ray at r1 cos(dtheta/2): for cells wider than
 * 2 acos((r0 + r1)/(2 r1)) (28.7 deg for the outer row r 0.9375..1 of an
 * r 0.5..1 annulus cut into 8) the outer triangle inverted, the rest Hessian
 * was indefinite and Newton's line search failed at once (issue 21).  The
 * centre now sits on the mid-angle ray at the radius of the corners' mean
 * ((r0 + r1)/2 cos(dtheta/2), the best point in xi), raised to a quarter of
 * the way from the inner arc r0 (where the (s,t) cell begins) to the outer
 * chord when the mean falls below that.  Returns 1 when no point lies in both
 * (r1 cos(dtheta/2) <= r0, up to a margin): the caller refuses the mesh. */
static int cell_centre(const sb_domain *d, double s0, double s1, double t0, double t1, double st[2])
{
    st[0] = 0.5 * (s0 + s1);
    st[1] = 0.5 * (t0 + t1);
    if (d->kind != SB_DOMAIN_ANNULUS_SECTOR) return 0;
    const double dr = d->r_out - d->r_in, r0 = d->r_in + s0 * dr, r1 = d->r_in + s1 * dr;
    const double half = 0.5 * (t1 - t0) * (d->theta[1] - d->theta[0]);
    const double chord = r1 * cos(half);                /* the outer chord on the mid-angle ray */
    const double mean = 0.5 * (r0 + r1) * cos(half);    /* the corners' mean */
    if (!(chord > r0 + 1e-2 * (r1 - r0))) return 1;
    st[0] = (fmax(mean, r0 + 0.25 * (chord - r0)) - d->r_in) / dr;
    return 0;
}

/* pin vertices at the scene's point parts (bcs and loads) */
static void pin_points(sb_mesh *m, const sb_scene *sc)
{
    for (int b = 0; b < sc->n_bcs; b++)
        for (int p = 0; p < sc->bcs[b].n_parts; p++) {
            int v = sb_mesh_point_vertex(m, &sc->bcs[b].parts[p]);
            if (v >= 0) m->vflag[v] |= SB_MESH_V_PINNED;
        }
    for (int l = 0; l < sc->n_loads; l++)
        for (int p = 0; p < sc->loads[l].n_parts; p++) {
            int v = sb_mesh_point_vertex(m, &sc->loads[l].parts[p]);
            if (v >= 0) m->vflag[v] |= SB_MESH_V_PINNED;
        }
}

int sb_mesh_from_domain(const sb_scene *sc, const sb_mesh_spec *spec, sb_mesh *m, const char **rng_name,
                        char *err, size_t errlen)
{
    sb_mesh_init(m);
    if (rng_name) *rng_name = NULL;
    const int ns = spec->n_s, nt = spec->n_t;
    if (ns < 1 || nt < 1 || ns > 8192 || nt > 8192 || (long)ns * nt > 4000000L)
        return failf(err, errlen, "a %d x %d grid of cells is out of range (1 to 8192 per side, 4 million cells)", ns, nt);
    if ((int)spec->pattern < 0 || spec->pattern > SB_MESH_JITTER)
        return failf(err, errlen, "unknown mesh pattern %d", (int)spec->pattern);
    if (spec->pattern == SB_MESH_JITTER && !(spec->jitter >= 0.0 && spec->jitter <= 0.45))
        return failf(err, errlen, "jitter %g is out of range: it must lie in [0, 0.45] of the cell size", spec->jitter);
    double s01[2], t01[2];
    int notch = sb_domain_notch_st(&sc->domain, s01, t01);
    double cs = notch ? (s01[0] > 0 ? s01[0] : s01[1]) : 0, ct = notch ? (t01[0] > 0 ? t01[0] : t01[1]) : 0;
    double *su = malloc(sizeof(double) * (size_t)(ns + 1)), *tu = malloc(sizeof(double) * (size_t)(nt + 1));
    int *vid = malloc(sizeof(int) * (size_t)(ns + 1) * (size_t)(nt + 1));
    unsigned char *cell = malloc((size_t)ns * (size_t)nt);
    int rc = SB_OK;
    if (!su || !tu || !vid || !cell) { rc = SB_ERR_NOMEM; goto done; }
    if (grid_lines(ns, notch, cs, su) || grid_lines(nt, notch, ct, tu)) {
        rc = failf(err, errlen, "an L-shaped domain needs at least 2 cells along each side (got %d x %d)", ns, nt);
        goto done;
    }
    int ncell = 0;
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) {
            cell[i + ns * j] = (unsigned char)sb_domain_contains_st(&sc->domain, 0.5 * (su[i] + su[i + 1]),
                                                                   0.5 * (tu[j] + tu[j + 1]));
            ncell += cell[i + ns * j];
        }
    if (!ncell) { rc = failf(err, errlen, "no cell of the %d x %d grid lies in the domain", ns, nt); goto done; }
    const int crossed = spec->pattern == SB_MESH_CROSSED;
    /* A disc (annulus with r_in = 0): the cells at s = 0 are triangles (v00 =
     * v01, the centre) and one of their two triangles is dropped; the kept one
     * carries the centre's corner coordinates, (0, t0) with the diagonal
     * v00-v11, (0, t1) with v10-v01.  The last cell keeps (0, 1) so that its
     * edge along `end` lies on `end` in (s,t) too (a slit disc's lip, a bc on
     * the end of a disc sector), every other cell (0, t0). */
    const int disc = sc->domain.kind == SB_DOMAIN_ANNULUS_SECTOR && sc->domain.r_in == 0.0;
    const int nvmax = (ns + 1) * (nt + 1) + (crossed ? ncell : 0), ntmax = (crossed ? 4 : 2) * ncell;
    if ((rc = sb_mesh_reserve(m, nvmax, ntmax, 0))) goto done;
    m->nv = 0;
    for (int j = 0; j <= nt; j++)
        for (int i = 0; i <= ns; i++) {
            int act = 0;
            for (int dj = -1; dj <= 0 && !act; dj++)
                for (int di = -1; di <= 0 && !act; di++) {
                    int ci = i + di, cj = j + dj;
                    act = ci >= 0 && ci < ns && cj >= 0 && cj < nt && cell[ci + ns * cj];
                }
            vid[i + (ns + 1) * j] = act ? m->nv : -1;
            if (!act) continue;
            m->st[2 * m->nv] = su[i];
            m->st[2 * m->nv + 1] = tu[j];
            m->vgen[m->nv] = 0;
            m->vflag[m->nv] = 0;
            m->nv++;
        }
    m->nt = 0;
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) {
            if (!cell[i + ns * j]) continue;
            const int v00 = vid[i + (ns + 1) * j], v10 = vid[i + 1 + (ns + 1) * j];
            const int v11 = vid[i + 1 + (ns + 1) * (j + 1)], v01 = vid[i + (ns + 1) * (j + 1)];
            int T[4][3], n = 0;
            if (crossed) {
                const int c = m->nv++;
                if (cell_centre(&sc->domain, su[i], su[i + 1], tu[j], tu[j + 1], m->st + 2 * c)) {
                    rc = failf(err, errlen, "method.mesh = crossed: the annulus cells of %.3g deg by %.3g are too wide "
                               "in angle for a centre vertex inside both the (s,t) cell and its straight "
                               "quadrilateral (raise method.cells_t or use another pattern)",
                               (tu[j + 1] - tu[j]) * (sc->domain.theta[1] - sc->domain.theta[0]) * 180 / M_PI,
                               (su[i + 1] - su[i]) * (sc->domain.r_out - sc->domain.r_in));
                    goto done;
                }
                m->vgen[c] = 0;
                m->vflag[c] = 0;
                int q[4] = { v00, v10, v11, v01 };
                for (int k = 0; k < 4; k++) {
                    T[n][0] = q[k]; T[n][1] = q[(k + 1) % 4]; T[n][2] = c;
                    n++;
                }
            } else if (disc && i == 0 ? j < nt - 1 : spec->pattern == SB_MESH_REGULAR || ((i + j) % 2 == 0)) {
                T[0][0] = v00; T[0][1] = v10; T[0][2] = v11;
                T[1][0] = v00; T[1][1] = v11; T[1][2] = v01;
                n = 2;
            } else {
                T[0][0] = v00; T[0][1] = v10; T[0][2] = v01;
                T[1][0] = v10; T[1][1] = v11; T[1][2] = v01;
                n = 2;
            }
            for (int k = 0; k < n; k++) {
                const int t = m->nt++;
                for (int c = 0; c < 3; c++) {
                    m->tri[3 * t + c] = T[k][c];
                    m->tri_st[6 * t + 2 * c] = m->st[2 * T[k][c]];
                    m->tri_st[6 * t + 2 * c + 1] = m->st[2 * T[k][c] + 1];
                }
                m->tgen[t] = 0;
            }
        }
    sb_mesh_set_geometry(m, sc);
    if ((rc = merge_coincident(m, seams_named(sc)))) goto done;
    if (m->nt < 1) { rc = failf(err, errlen, "the %d x %d grid leaves no triangle after identifying seams", ns, nt); goto done; }
    if ((rc = sb_mesh_build_edges(m))) {
        if (rc == SB_ERR_INPUT)
            failf(err, errlen, "the %d x %d triangulation is not a manifold after identifying coincident vertices "
                  "(the chart maps distinct grid lines onto one curve)", ns, nt);
        goto done;
    }
    sb_mesh_tag_boundary(m, sc);
    pin_points(m, sc);
    if (spec->pattern == SB_MESH_JITTER) {
        rc = sb_mesh_jitter(m, sc, spec->jitter, spec->seed, rng_name);
        if (rc < 0) { failf(err, errlen, "jittering the mesh failed (status %d)", rc); goto done; }
        rc = SB_OK;
    }
done:
    free(su); free(tu); free(vid); free(cell);
    if (rc) sb_mesh_free(m);
    return rc;
}
