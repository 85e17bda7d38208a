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
    w->n_obstacles = o->n_obstacles;
    w->obstacles = o->obstacles;
    w->ground = o->ground;
    double zmin = w->lo[2];
    for (int i = 0; i < w->n_obstacles; i++) {
        const sb_obstacle *ob = &w->obstacles[i];
        zmin = fmin(zmin, ob->kind == SB_OBSTACLE_SPHERE ? ob->c[2] - ob->r : ob->lo[2]);
    }
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

static int hit_sphere(const sb_obstacle *ob, const sb_ray *r, double tmax, double *t)
{
    double oc[3] = { r->o[0] - ob->c[0], r->o[1] - ob->c[1], r->o[2] - ob->c[2] };
    const double b = oc[0] * r->d[0] + oc[1] * r->d[1] + oc[2] * r->d[2];
    const double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - ob->r * ob->r;
    const double disc = b * b - c;
    if (disc < 0) return 0;
    const double sq = sqrt(disc);
    double t0 = -b - sq;
    if (!(t0 > r->tmin)) t0 = -b + sq;
    if (!(t0 > r->tmin && t0 < tmax)) return 0;
    *t = t0;
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
        if (ob->kind == SB_OBSTACLE_SPHERE) {
            for (int c = 0; c < 3; c++) h->n[c] = (h->p[c] - ob->c[c]) / ob->r;
        } else {
            /* the face whose plane the point is nearest */
            double best = INFINITY;
            for (int c = 0; c < 3; c++) {
                const double dl = fabs(h->p[c] - ob->lo[c]), dh = fabs(h->p[c] - ob->hi[c]);
                if (dl < best) { best = dl; h->n[0] = h->n[1] = h->n[2] = 0; h->n[c] = -1; }
                if (dh < best) { best = dh; h->n[0] = h->n[1] = h->n[2] = 0; h->n[c] = 1; }
            }
        }
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
    for (int i = 0; i < w->n_obstacles; i++) {
        const sb_obstacle *ob = &w->obstacles[i];
        double t, t1;
        int hit = ob->kind == SB_OBSTACLE_SPHERE ? hit_sphere(ob, r, tm, &t) : sb_ray_box(r, ob->lo, ob->hi, tm, &t, &t1);
        if (hit && ob->kind == SB_OBSTACLE_BOX && !(t > r->tmin)) hit = 0;   /* origin inside the box */
        if (!hit) continue;
        if (any) return 1;
        tm = t;
        h->kind = SB_HIT_OBSTACLE;
        h->prim = i;
        h->t = t;
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
