/* sb_render_world.c — the traced world: the surface's patches and
 * triangles in one BVH, analytic obstacles and the ground plane. */
#include "sb_render_world.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm3(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static int vertex_normals(const sb_surface *s, double *vn)
{
    memset(vn, 0, (size_t)s->n_verts * 3 * sizeof *vn);
    for (int t = 0; t < s->n_tris; t++) {
        const int *T = s->tri + 3 * t;
        const double *a = s->vert + 3 * T[0], *b = s->vert + 3 * T[1], *c = s->vert + 3 * T[2];
        double e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++) { e1[k] = b[k] - a[k]; e2[k] = c[k] - a[k]; }
        cross3(e1, e2, n);   /* area-weighted */
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) vn[3 * T[v] + k] += n[k];
    }
    for (int v = 0; v < s->n_verts; v++) {
        double l = norm3(vn + 3 * v);
        if (l > 0) for (int k = 0; k < 3; k++) vn[3 * v + k] /= l;
    }
    return 0;
}

static void cross_unit(const double a[3], const double b[3], double c[3])
{
    cross3(a, b, c);
    const double l = norm3(c);
    if (l > 0) for (int k = 0; k < 3; k++) c[k] /= l;
}

/* Copy the obstacles, resolve each plane's drawn square (centred at the foot
 * of the perpendicular from the surface's centre, in-plane axes u, v) and
 * put the mesh obstacles' triangles into a BVH.  0 or -1 (out of memory). */
static int setup_obstacles(sb_world *w, const sb_render_options *o)
{
    w->n_obstacles = o->n_obstacles < SB_RENDER_MAX_OBSTACLES ? o->n_obstacles : SB_RENDER_MAX_OBSTACLES;
    int nmt = 0;
    for (int i = 0; i < w->n_obstacles; i++) {
        sb_obstacle *ob = &w->obstacles[i];
        *ob = o->obstacles[i];
        if (ob->kind == SB_OBSTACLE_MESH) nmt += ob->nt;
        if (ob->kind != SB_OBSTACLE_PLANE) continue;
        double *n = ob->n, *u = w->plane_u[i], *v = w->plane_v[i];
        const double ln = norm3(n);
        if (ln > 0) for (int c = 0; c < 3; c++) n[c] /= ln;
        const double h = (w->centre[0] - ob->c[0]) * n[0] + (w->centre[1] - ob->c[1]) * n[1] + (w->centre[2] - ob->c[2]) * n[2];
        for (int c = 0; c < 3; c++) ob->c[c] = w->centre[c] - h * n[c];
        /* u: across the coordinate axis least aligned with n */
        int k = 0;
        for (int c = 1; c < 3; c++) if (fabs(n[c]) < fabs(n[k])) k = c;
        double e[3] = { 0, 0, 0 };
        e[k] = 1;
        cross_unit(n, e, u);
        cross_unit(n, u, v);
        if (!(ob->extent > 0)) ob->extent = 1.3 * w->radius;
    }
    if (!nmt) return 0;
    w->mtri_obst = malloc((size_t)nmt * sizeof(int));
    w->mtri_tri = malloc((size_t)nmt * sizeof(int));
    w->mlo = malloc((size_t)nmt * 3 * sizeof(double));
    w->mhi = malloc((size_t)nmt * 3 * sizeof(double));
    if (!w->mtri_obst || !w->mtri_tri || !w->mlo || !w->mhi) return -1;
    for (int i = 0; i < w->n_obstacles; i++) {
        const sb_obstacle *ob = &w->obstacles[i];
        if (ob->kind != SB_OBSTACLE_MESH) continue;
        for (int t = 0; t < ob->nt; t++) {
            const int j = w->n_mtri++;
            w->mtri_obst[j] = i;
            w->mtri_tri[j] = t;
            for (int c = 0; c < 3; c++) { w->mlo[3 * j + c] = INFINITY; w->mhi[3 * j + c] = -INFINITY; }
            for (int k = 0; k < 3; k++)
                for (int c = 0; c < 3; c++) {
                    const double x = ob->verts[3 * ob->tris[3 * t + k] + c];
                    w->mlo[3 * j + c] = fmin(w->mlo[3 * j + c], x);
                    w->mhi[3 * j + c] = fmax(w->mhi[3 * j + c], x);
                }
        }
    }
    return sb_bvh_build(&w->mbvh, w->n_mtri, w->mlo, w->mhi, 4) ? -1 : 0;
}

/* the lowest point of the surface (z0) and the obstacles: the ground goes under it */
static double obstacles_zmin(const sb_world *w, double z0)
{
    double z = z0;
    for (int i = 0; i < w->n_obstacles; i++) {
        const sb_obstacle *ob = &w->obstacles[i];
        switch (ob->kind) {
        case SB_OBSTACLE_SPHERE: z = fmin(z, ob->c[2] - ob->r); break;
        case SB_OBSTACLE_CAPSULE: z = fmin(z, fmin(ob->a[2], ob->b[2]) - ob->r); break;
        case SB_OBSTACLE_BOX:
            for (int k = 0; k < 8; k++) {   /* corners */
                double y[3], m[3], zz;
                for (int c = 0; c < 3; c++) {
                    y[c] = (k >> c) & 1 ? ob->hi[c] : ob->lo[c];
                    m[c] = 0.5 * (ob->lo[c] + ob->hi[c]);
                }
                zz = ob->rotated ? m[2] + ob->R[6] * (y[0] - m[0]) + ob->R[7] * (y[1] - m[1]) + ob->R[8] * (y[2] - m[2]) : y[2];
                z = fmin(z, zz);
            }
            break;
        case SB_OBSTACLE_PLANE:
            z = fmin(z, ob->c[2] - ob->extent * (fabs(w->plane_u[i][2]) + fabs(w->plane_v[i][2])));
            break;
        case SB_OBSTACLE_MESH:
            for (int t = 0; t < ob->nt; t++)
                for (int k = 0; k < 3; k++) z = fmin(z, ob->verts[3 * ob->tris[3 * t + k] + 2]);
            break;
        }
    }
    return z;
}

int sb_world_build(sb_world *w, const sb_surface *s, const sb_material *mat, const sb_render_options *o,
                   char *err, size_t errlen)
{
    memset(w, 0, sizeof *w);
    w->s = s;
    w->mat = mat;
    w->isect = o->isect;
    if (sb_surface_bounds(s, w->lo, w->hi)) {
        snprintf(err, errlen, "the surface is empty or has non-finite coordinates");
        return SB_ERR_INPUT;
    }
    double diag = 0;
    for (int c = 0; c < 3; c++) {
        w->centre[c] = 0.5 * (w->lo[c] + w->hi[c]);
        diag += (w->hi[c] - w->lo[c]) * (w->hi[c] - w->lo[c]);
    }
    diag = sqrt(diag);
    if (!(diag > 0)) diag = 1.0;
    w->radius = 0.5 * diag;
    w->eps = (o->eps_rel > 0 ? o->eps_rel : 1e-6) * diag;
    const int np = s->n_patches, n = s->n_patches + s->n_tris;
    w->plo = malloc((size_t)(n ? n : 1) * 3 * sizeof(double));
    w->phi = malloc((size_t)(n ? n : 1) * 3 * sizeof(double));
    w->ws = sb_bezier_ws_new();
    w->shell = sb_shell_work_new();
    if (s->n_verts) w->vnormal = malloc((size_t)s->n_verts * 3 * sizeof(double));
    if (!w->plo || !w->phi || !w->ws || !w->shell || (s->n_verts && !w->vnormal)) goto nomem;
    for (int p = 0; p < np; p++) sb_bezier_bounds(s->patch + (size_t)p * SB_BEZ_N, w->plo + 3 * p, w->phi + 3 * p);
    for (int t = 0; t < s->n_tris; t++) {
        double *lo = w->plo + 3 * (np + t), *hi = w->phi + 3 * (np + t);
        for (int c = 0; c < 3; c++) { lo[c] = INFINITY; hi[c] = -INFINITY; }
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 3; c++) {
                const double x = s->vert[3 * s->tri[3 * t + k] + c];
                lo[c] = fmin(lo[c], x);
                hi[c] = fmax(hi[c], x);
            }
    }
    if (sb_bvh_build(&w->bvh, n, w->plo, w->phi, np ? 1 : 4)) goto nomem;
    if (s->n_verts) vertex_normals(s, w->vnormal);
    if (o->color == SB_COLOR_CURVATURE && s->n_tris) {
        if (!(w->vcurv = malloc((size_t)s->n_verts * sizeof(double)))) goto nomem;
        if (sb_field_vertex_curvature(s, w->vnormal, w->vcurv)) goto nomem;
    }
    w->ground = o->ground;
    if (setup_obstacles(w, o)) goto nomem;
    const double zmin = obstacles_zmin(w, w->lo[2]);
    w->ground_z = zmin - 0.03 * diag;
    /* grid lines at a round spacing, about 8 cells over the diagonal */
    w->grid = pow(10.0, floor(log10(diag / 8.0)));
    if (diag / w->grid > 40) w->grid *= 5;
    else if (diag / w->grid > 16) w->grid *= 2;
    return SB_OK;
nomem:
    snprintf(err, errlen, "out of memory building the render world (%d primitives)", n);
    sb_world_free(w);
    return SB_ERR_NOMEM;
}

void sb_world_free(sb_world *w)
{
    sb_bvh_free(&w->bvh);
    free(w->plo);
    free(w->phi);
    free(w->vnormal);
    free(w->vcurv);
    sb_bvh_free(&w->mbvh);
    free(w->mtri_obst);
    free(w->mtri_tri);
    free(w->mlo);
    free(w->mhi);
    sb_bezier_ws_free(w->ws);
    if (w->shell) sb_shell_work_free(w->shell);
    memset(w, 0, sizeof *w);
}

/* BVH leaf test of one primitive */
static int hit_prim(void *ctx, int prim, const sb_ray *r, double *tmax)
{
    sb_world *w = ctx;
    const sb_surface *s = w->s;
    if (prim < s->n_patches) {
        sb_patch_hit ph;
        int rc = sb_bezier_intersect(w->isect, s->patch + (size_t)prim * SB_BEZ_N, w->plo + 3 * prim,
                                     w->phi + 3 * prim, r, *tmax, w->eps, w->ws, &ph);
        if (rc <= 0) return rc;
        *tmax = ph.t;
        w->cur->kind = SB_HIT_PATCH;
        w->cur->prim = prim;
        w->cur->t = ph.t;
        w->cur->u = ph.u;
        w->cur->v = ph.v;
        return 1;
    }
    const int t = prim - s->n_patches;
    const int *T = s->tri + 3 * t;
    double tt, b1, b2;
    w->tri_tests++;
    if (!sb_ray_triangle(r, s->vert + 3 * T[0], s->vert + 3 * T[1], s->vert + 3 * T[2], *tmax, &tt, &b1, &b2))
        return 0;
    *tmax = tt;
    w->cur->kind = SB_HIT_TRIANGLE;
    w->cur->prim = t;
    w->cur->t = tt;
    w->cur->u = b1;
    w->cur->v = b2;
    return 1;
}

/* BVH leaf test of one mesh-obstacle triangle */
static int hit_mtri(void *ctx, int prim, const sb_ray *r, double *tmax)
{
    sb_world *w = ctx;
    const sb_obstacle *ob = &w->obstacles[w->mtri_obst[prim]];
    const int *T = ob->tris + 3 * w->mtri_tri[prim];
    double tt, b1, b2;
    w->tri_tests++;
    if (!sb_ray_triangle(r, ob->verts + 3 * T[0], ob->verts + 3 * T[1], ob->verts + 3 * T[2], *tmax, &tt, &b1, &b2))
        return 0;
    *tmax = tt;
    w->cur->kind = SB_HIT_OBSTACLE;
    w->cur->prim = w->mtri_obst[prim];
    w->cur->tri = w->mtri_tri[prim];
    w->cur->t = tt;
    return 1;
}

/* Surface point and normal of a hit found by the traversal. */
static void finish_hit(sb_world *w, const sb_ray *r, sb_hit *h)
{
    const sb_surface *s = w->s;
    if (h->kind == SB_HIT_PATCH) {
        const double *P = s->patch + (size_t)h->prim * SB_BEZ_N;
        double xu[3], xv[3];
        sb_bezier_eval(P, h->u, h->v, h->p, xu, xv);
        cross3(xu, xv, h->n);
        double l = norm3(h->n);
        if (!(l > 1e-300)) {
            /* a collapsed point of the patch: the normal a little inside */
            sb_bezier_eval(P, 0.5 + 0.99 * (h->u - 0.5), 0.5 + 0.99 * (h->v - 0.5), h->p, xu, xv);
            cross3(xu, xv, h->n);
            l = norm3(h->n);
        }
        if (l > 1e-300) for (int c = 0; c < 3; c++) h->n[c] /= l;
        else for (int c = 0; c < 3; c++) h->n[c] = -r->d[c];
        return;
    }
    for (int c = 0; c < 3; c++) h->p[c] = r->o[c] + h->t * r->d[c];
    if (h->kind == SB_HIT_TRIANGLE) {
        const int *T = s->tri + 3 * h->prim;
        const double b0 = 1.0 - h->u - h->v;
        for (int c = 0; c < 3; c++)
            h->n[c] = b0 * w->vnormal[3 * T[0] + c] + h->u * w->vnormal[3 * T[1] + c] + h->v * w->vnormal[3 * T[2] + c];
        double l = norm3(h->n);
        if (!(l > 1e-300)) {
            const double *a = s->vert + 3 * T[0], *b = s->vert + 3 * T[1], *cc = s->vert + 3 * T[2];
            double e1[3], e2[3];
            for (int c = 0; c < 3; c++) { e1[c] = b[c] - a[c]; e2[c] = cc[c] - a[c]; }
            cross3(e1, e2, h->n);
            l = norm3(h->n);
        }
        if (l > 1e-300) for (int c = 0; c < 3; c++) h->n[c] /= l;
    } else if (h->kind == SB_HIT_OBSTACLE) {
        const sb_obstacle *ob = &w->obstacles[h->prim];
        if (ob->kind == SB_OBSTACLE_MESH) {
            /* flat: the face normal */
            const int *T = ob->tris + 3 * h->tri;
            const double *a = ob->verts + 3 * T[0], *b = ob->verts + 3 * T[1], *cc = ob->verts + 3 * T[2];
            double e1[3], e2[3];
            for (int c = 0; c < 3; c++) { e1[c] = b[c] - a[c]; e2[c] = cc[c] - a[c]; }
            cross_unit(e1, e2, h->n);
        }   /* analytic obstacles: the normal came with the hit */
    } else {
        h->n[0] = h->n[1] = 0;
        h->n[2] = 1;
    }
}

int sb_world_intersect(sb_world *w, const sb_ray *r, double tmax, int any, sb_hit *h)
{
    h->kind = SB_HIT_NONE;
    double tm = tmax;
    w->cur = h;
    int rc = sb_bvh_intersect(&w->bvh, r, &tm, any, hit_prim, w);
    if (rc < 0) return -1;
    if (rc > 0 && any) return 1;
    if (w->n_mtri) {
        rc = sb_bvh_intersect(&w->mbvh, r, &tm, any, hit_mtri, w);
        if (rc < 0) return -1;
        if (rc > 0 && any) return 1;
    }
    for (int i = 0; i < w->n_obstacles; i++) {
        double t, n[3];
        if (!sb_ray_obstacle(&w->obstacles[i], w->plane_u[i], w->plane_v[i], r, tm, &t, n)) continue;
        if (any) return 1;
        tm = t;
        h->kind = SB_HIT_OBSTACLE;
        h->prim = i;
        h->t = t;
        memcpy(h->n, n, sizeof n);
    }
    if (!any && w->ground && r->d[2] < 0 && r->o[2] > w->ground_z) {
        const double t = (w->ground_z - r->o[2]) / r->d[2];
        if (t > r->tmin && t < tm) {
            h->kind = SB_HIT_GROUND;
            h->t = t;
            tm = t;
        }
    }
    if (h->kind == SB_HIT_NONE) return 0;
    finish_hit(w, r, h);
    return 1;
}
