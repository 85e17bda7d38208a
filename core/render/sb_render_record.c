/* sb_render_record.c — from a record to a picture: the discretization is
 * rebuilt from what the record keeps (scene text, method, --res, --levels,
 * method.* parameters; as `shellbench inspect` does), asked for its surface
 * at the recorded final state (sb_method_type.surface), and rendered.
 *
 * What each method draws:
 *   bhem         its Hermite patches in Bézier form, traced exactly;
 *   rmtr         its regular Catmull–Clark faces as Bézier patches (the exact
 *                limit surface), traced exactly;
 *   any method with a `surface` op returning triangles (linear_fem) those
 *                triangles, traced directly;
 *   any other    a triangulation of eval_points on a grid of 8 points per
 *                element side inside the domain (stated in the picture's
 *                description).
 * --step K draws the method's own triangles of step K when the record has
 * them (/steps/mesh: linear_fem, adaptive_sqrt3, whose mesh changes), else
 * the recorded sample grid of step K (a triangulation of /steps/sample_pos,
 * 21 x 21 points by default).  The final state of an adaptive run, whose
 * mesh the method cannot rebuild from the scene, is the last row of
 * /steps/mesh. */
#include "sb_render.h"
#include "sb_obstacle.h"
#include "sb_context.h"
#include "sb_geometry.h"
#include "sb_method.h"
#include "sb_output.h"
#include "sb_record.h"
#include "sb_sysinfo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct rebuilt {
    sb_scene scene;
    sb_context ctx;
    const sb_method_type *mt;
    void *state;
    int have_scene, have_ctx, created;
} rebuilt;

static void rebuilt_free(rebuilt *b)
{
    if (b->created) b->mt->destroy(b->state);
    free(b->state);
    if (b->have_ctx) sb_context_free(&b->ctx);
    if (b->have_scene) sb_scene_free(&b->scene);
    memset(b, 0, sizeof *b);
}

/* o's obstacle array holds every obstacle a scene can have */
_Static_assert(SB_RENDER_MAX_OBSTACLES >= SB_SCENE_MAX_OBSTACLES,
               "sb_render_options must have room for every obstacle of a scene");

/* Every obstacle of the scene (docs/contact.md) at its pose of `step`:
 * x_world = c + R (y - c) + f t (sb_pose_at, the motion factor f of the
 * step's ramp) applied to the rest-frame geometry. */
int sb_render_scene_obstacles(const sb_scene *sc, int step, sb_render_options *o, double **mesh_verts)
{
    *mesh_verts = NULL;
    size_t nmv = 0;
    int left_out = 0;
    for (int i = 0; i < sc->n_obstacles; i++)
        if (sc->obstacles[i].kind == SB_OBST_MESH) nmv += (size_t)sc->obstacles[i].nv;
    if (nmv && !(*mesh_verts = malloc(nmv * 3 * sizeof(double)))) return -1;
    double *mv = *mesh_verts;
    for (int i = 0; i < sc->n_obstacles; i++) {
        if (o->n_obstacles >= SB_RENDER_MAX_OBSTACLES) { left_out++; continue; }   /* only after the caller's own */
        const sb_obstacle_spec *ob = &sc->obstacles[i];
        sb_pose P;
        sb_pose_at(ob, sb_obstacle_motion_factor(sc, ob, step), &P);
        sb_obstacle *r = &o->obstacles[o->n_obstacles++];
        memset(r, 0, sizeof *r);
        switch (ob->kind) {
        case SB_OBST_SPHERE:
            r->kind = SB_OBSTACLE_SPHERE;
            sb_pose_apply(&P, ob->center, r->c);
            r->r = ob->radius;
            break;
        case SB_OBST_BOX: {
            double c[3];
            sb_pose_apply(&P, ob->center, c);
            r->kind = SB_OBSTACLE_BOX;
            for (int k = 0; k < 3; k++) { r->lo[k] = c[k] - ob->half[k]; r->hi[k] = c[k] + ob->half[k]; }
            r->rotated = ob->rot_angle != 0.0;
            memcpy(r->R, P.R, sizeof r->R);
            break;
        }
        case SB_OBST_CAPSULE:
            r->kind = SB_OBSTACLE_CAPSULE;
            sb_pose_apply(&P, ob->a, r->a);
            sb_pose_apply(&P, ob->b, r->b);
            r->r = ob->radius;
            break;
        case SB_OBST_PLANE:
            r->kind = SB_OBSTACLE_PLANE;
            sb_pose_apply(&P, ob->point, r->c);
            sb_pose_rotate(&P, ob->normal, r->n);
            break;
        case SB_OBST_MESH:
            r->kind = SB_OBSTACLE_MESH;
            for (int v = 0; v < ob->nv; v++) sb_pose_apply(&P, ob->verts + 3 * v, mv + 3 * v);
            r->verts = mv;
            r->nv = ob->nv;
            r->tris = ob->tris;
            r->nt = ob->nt;
            mv += 3 * ob->nv;
            break;
        }
    }
    return left_out;
}

/* scene and (when with_method) the method of the record su */
static int rebuild(const char *path, const sb_record_setup *su, int with_method, rebuilt *b, char *err, size_t errlen)
{
    memset(b, 0, sizeof *b);
    char msg[1024];
    if (sb_scene_parse_string(su->scene_json, su->scene_path, &b->scene, msg, sizeof msg)) {
        snprintf(err, errlen, "%s: its scene does not parse: %s", path, msg);
        return SB_ERR_INPUT;
    }
    b->have_scene = 1;
    if (!with_method) return SB_OK;
    b->mt = sb_method_find(su->method);
    if (!b->mt) {
        snprintf(err, errlen, "%s: method \"%s\" is not in this build, so its surface cannot be rebuilt", path,
                 su->method);
        return SB_ERR_INPUT;
    }
    if (sb_context_init(&b->ctx)) {
        snprintf(err, errlen, "%s: cannot set up a context", path);
        return SB_ERR_INTERNAL;
    }
    b->have_ctx = 1;
    if (sb_paramset_add(&b->ctx.params, "method", b->mt->params)) {
        snprintf(err, errlen, "%s: too many parameters", path);
        return SB_ERR_INTERNAL;
    }
    for (int i = 0; i < su->n_sets; i++)
        if (sb_paramset_set(&b->ctx.params, su->sets[i], msg, sizeof msg)) {
            snprintf(err, errlen, "%s: parameter %s: %s", path, su->sets[i], msg);
            return SB_ERR_INPUT;
        }
    if (!(b->state = calloc(1, b->mt->state_size))) {
        snprintf(err, errlen, "%s: out of memory", path);
        return SB_ERR_NOMEM;
    }
    sb_method_config cfg = { su->res, su->levels > 0 ? su->levels : 1, &b->ctx.params, &b->ctx, su->res_t };
    int rc = b->mt->create(b->state, &b->scene, &cfg);
    b->created = 1;
    if (rc) {
        snprintf(err, errlen, "%s: method %s cannot be rebuilt: %s", path, b->mt->name,
                 b->ctx.err[0] ? b->ctx.err : "set-up failed");
        return rc < 0 ? rc : SB_ERR_INPUT;
    }
    const int F = b->mt->n_levels(b->state) - 1;
    if (b->mt->n_dofs(b->state, F) != su->n_x) {
        snprintf(err, errlen, "%s: /final/x has %d dofs, the rebuilt discretization %d", path, su->n_x,
                 b->mt->n_dofs(b->state, F));
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

/* Triangles over an n x n grid of (s,t) inside the domain (the layout of
 * the record's sample grid): st filled, tri written; returns the counts. */
static int grid_triangles(const sb_domain *d, int n, sb_surface *s)
{
    int *idx = malloc((size_t)n * n * sizeof *idx);
    if (!idx || sb_surface_alloc_tris(s, n * n, 2 * (n - 1) * (n - 1), 1, 1)) {
        free(idx);
        return -1;
    }
    int m = 0, nt = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const double st[2] = { (double)i / (n - 1), (double)j / (n - 1) };
            idx[j * n + i] = sb_domain_contains_st(d, st[0], st[1]) ? m : -1;
            if (idx[j * n + i] >= 0) {
                s->vert_st[2 * m] = st[0];
                s->vert_st[2 * m + 1] = st[1];
                m++;
            }
        }
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            const int a = idx[j * n + i], b = idx[j * n + i + 1], c = idx[(j + 1) * n + i], e = idx[(j + 1) * n + i + 1];
            if (a < 0 || b < 0 || c < 0 || e < 0) continue;
            if (!sb_domain_contains_st(d, (i + 0.5) / (n - 1), (j + 0.5) / (n - 1))) continue;
            int *T = s->tri + 3 * nt;
            T[0] = a; T[1] = b; T[2] = e; T[3] = a; T[4] = e; T[5] = c;
            nt += 2;
        }
    free(idx);
    s->n_verts = m;
    s->n_tris = nt;
    return 0;
}

/* the fallback: eval_points on a grid of 8 points per element side */
static int tessellate(rebuilt *b, const sb_record_setup *su, sb_surface *s, char *err, size_t errlen, const char *path)
{
    const sb_method_type *mt = b->mt;
    if (!mt->eval_points) {
        snprintf(err, errlen, "%s: method %s can neither give its surface nor evaluate points", path, mt->name);
        return SB_ERR_INPUT;
    }
    const int F = mt->n_levels(b->state) - 1;
    int res = su->res > 0 ? su->res : (b->scene.default_res > 0 ? b->scene.default_res : 8);
    int n = 8 * res + 1;
    if (n < 65) n = 65;
    if (n > 1025) n = 1025;
    double *x0 = malloc((size_t)su->n_x * sizeof *x0);
    if (!x0 || grid_triangles(&b->scene.domain, n, s)) {
        free(x0);
        snprintf(err, errlen, "%s: out of memory tessellating the surface", path);
        return SB_ERR_NOMEM;
    }
    mt->initial(b->state, F, x0);
    int rc = mt->eval_points(b->state, F, su->x, s->n_verts, s->vert_st, s->vert);
    if (!rc) rc = mt->eval_points(b->state, F, x0, s->n_verts, s->vert_st, s->vert_ref);
    free(x0);
    if (rc) {
        snprintf(err, errlen, "%s: method %s cannot evaluate its surface: %s", path, mt->name,
                 b->ctx.err[0] ? b->ctx.err : "eval_points failed");
        return SB_ERR_INPUT;
    }
    snprintf(s->what, sizeof s->what, "%d triangles over a %dx%d grid of evaluated points (no surface op)", s->n_tris,
             n, n);
    return SB_OK;
}

/* the recorded sample grid of `step` as triangles */
static int step_surface(const char *path, int step, sb_surface *s, char *err, size_t errlen)
{
    sb_record_samples rs;
    int rc = sb_record_read_step_samples(path, step, &rs, err, errlen);
    if (rc) return rc == SB_ERR_NOMEM ? rc : SB_ERR_INPUT;
    if (rs.n_tris == 0 || sb_surface_alloc_tris(s, rs.n, rs.n_tris, 1, 1)) {
        if (rs.n_tris == 0) snprintf(err, errlen, "%s has no sample-grid triangles to draw", path);
        else snprintf(err, errlen, "out of memory reading %s", path);
        rc = rs.n_tris == 0 ? SB_ERR_INPUT : SB_ERR_NOMEM;
        sb_record_samples_free(&rs);
        return rc;
    }
    memcpy(s->vert, rs.pos, (size_t)rs.n * 3 * sizeof(double));
    memcpy(s->vert_ref, rs.ref, (size_t)rs.n * 3 * sizeof(double));
    memcpy(s->vert_st, rs.st, (size_t)rs.n * 2 * sizeof(double));
    memcpy(s->tri, rs.tris, (size_t)rs.n_tris * 3 * sizeof(int));
    snprintf(s->what, sizeof s->what, "%d triangles over the recorded sample grid of step %d (%d points)", rs.n_tris,
             step, rs.n);
    sb_record_samples_free(&rs);
    return SB_OK;
}

/* the method's own triangles of row `step` of /steps/mesh (sb_record_mesh.c) */
static int mesh_surface(const char *path, int step, sb_surface *s, char *err, size_t errlen)
{
    sb_mesh_topo t;
    double *pos = NULL;
    int rc = sb_record_read_step_mesh(path, step, &t, &pos, err, errlen);
    if (rc) return rc == SB_ERR_NOMEM ? rc : SB_ERR_INPUT;
    if (t.nt == 0 || sb_surface_alloc_tris(s, t.nv, t.nt, 1, 1)) {
        if (t.nt == 0) snprintf(err, errlen, "%s: the recorded mesh of step %d has no triangles", path, step);
        else snprintf(err, errlen, "out of memory reading %s", path);
        rc = t.nt == 0 ? SB_ERR_INPUT : SB_ERR_NOMEM;
    } else {
        memcpy(s->vert, pos, (size_t)t.nv * 3 * sizeof(double));
        memcpy(s->vert_ref, t.ref, (size_t)t.nv * 3 * sizeof(double));
        memcpy(s->vert_st, t.st, (size_t)t.nv * 2 * sizeof(double));
        memcpy(s->tri, t.tri, (size_t)t.nt * 3 * sizeof(int));
        snprintf(s->what, sizeof s->what, "%d triangles of the method's recorded mesh of step %d (%d vertices, exact)",
                 t.nt, step, t.nv);
    }
    free(pos);
    free(t.tri);
    free(t.ref);
    free(t.st);
    return rc;
}

int sb_render_record(const sb_render_request *rq, sb_render_stats *st, char *info, size_t infolen, char *err,
                     size_t errlen)
{
    const char *path = rq->record;
    /* the output is checked before any work: a refused path costs nothing */
    sb_output_kind out_kind;
    if (sb_output_check(rq->out, "image", &out_kind, err, errlen)) return SB_ERR_INPUT;
    if (out_kind != SB_OUTPUT_DISCARD && sb_output_check_file_dir(rq->out, "image", 1, err, errlen)) return SB_ERR_INPUT;
    sb_record_setup su;
    sb_record_summary sum;
    memset(&sum, 0, sizeof sum);
    int rc = sb_record_read_setup(path, &su, err, errlen);
    if (rc) return rc == SB_ERR_NOMEM ? rc : SB_ERR_INPUT;
    rc = sb_record_read_summary(path, &sum, err, errlen);
    if (rc) {
        sb_record_setup_free(&su);
        return rc == SB_ERR_NOMEM ? rc : SB_ERR_INPUT;
    }
    rebuilt b;
    sb_surface surf;
    memset(&surf, 0, sizeof surf);
    sb_image img = { 0, 0, NULL };
    /* the method's own triangles per step (/steps/mesh), when the record has them */
    int mesh_rows = 0;
    const int has_mesh = sb_record_has_mesh_series(path, &mesh_rows) && mesh_rows > 0;
    rc = rebuild(path, &su, rq->step < 0, &b, err, errlen);
    int from_mesh = -1;   /* the row of /steps/mesh drawn, -1 none */
    if (rc && rq->step < 0 && has_mesh) {
        /* an adaptive method's final mesh is not the one it rebuilds from the
         * scene: the recorded mesh of the last step is drawn */
        rebuilt_free(&b);
        rc = rebuild(path, &su, 0, &b, err, errlen);
        from_mesh = mesh_rows - 1;
    } else if (rq->step >= 0 && has_mesh) {
        from_mesh = rq->step;
    }
    if (!rc) {
        if (from_mesh >= 0) {
            rc = mesh_surface(path, from_mesh, &surf, err, errlen);
        } else if (rq->step >= 0) {
            rc = step_surface(path, rq->step, &surf, err, errlen);
        } else if (b.mt->surface) {
            rc = b.mt->surface(b.state, b.mt->n_levels(b.state) - 1, su.x, &surf);
            if (rc == SB_ERR_UNSUPPORTED) {
                sb_surface_free(&surf);
                rc = tessellate(&b, &su, &surf, err, errlen, path);
            } else if (rc) {
                snprintf(err, errlen, "%s: method %s cannot give its surface: %s", path, b.mt->name,
                         b.ctx.err[0] ? b.ctx.err : "surface op failed");
                rc = rc == SB_ERR_NOMEM ? rc : SB_ERR_INPUT;
            }
        } else {
            rc = tessellate(&b, &su, &surf, err, errlen, path);
        }
    }
    sb_material mat;
    int have_mat = 0;
    if (!rc && rq->opt.color != SB_COLOR_NONE && rq->opt.color != SB_COLOR_CURVATURE) {
        char msg[512];
        if (sb_material_init_msg(&mat, &b.scene.material, 0, msg, sizeof msg)) {
            snprintf(err, errlen, "%s: the scene's material: %s", path, msg);
            rc = SB_ERR_INPUT;
        } else {
            have_mat = 1;
        }
    }
    sb_render_options o = rq->opt;
    if (!rc) {
        /* labels: what, which state, how it ended */
        if (!o.title[0])
        {   /* the resolution as given: r8, or r8x12 for --res 8x12 */
            char res[32];
            if (su.res_t > 0 && su.res_t != su.res) snprintf(res, sizeof res, "r%dx%d", su.res, su.res_t);
            else snprintf(res, sizeof res, "r%d", su.res);
            snprintf(o.title, sizeof o.title, "%s | %s %s | %s", sum.scene, sum.method, res, sum.solver);
        }
        if (!o.subtitle[0]) {
            const int step = rq->step >= 0 ? rq->step : sum.steps;
            char state[96];
            if (sum.status == 0) snprintf(state, sizeof state, "converged");
            else if (sum.status == SB_STATUS_UNFINISHED) snprintf(state, sizeof state, "CHECKPOINT, run unfinished");
            else snprintf(state, sizeof state, "NOT converged (%s)", sum.reason_name);
            /* a checkpoint (.partial) draws the last saved state, not a final one */
            char size[64];
            /* a recorded mesh: its own size at that step (an adaptive mesh changes it) */
            if (from_mesh >= 0) snprintf(size, sizeof size, "%d vertices, %d triangles", surf.n_verts, surf.n_tris);
            else snprintf(size, sizeof size, "%ld dofs", sum.dofs);
            snprintf(o.subtitle, sizeof o.subtitle, "%s %d/%d | %s | %s",
                     rq->step >= 0 ? "step" : sum.status == SB_STATUS_UNFINISHED ? "saved, step" : "final, step", step,
                     sum.steps_planned, state, size);
        }
        /* every obstacle of the scene: o has room for all of them unless the
           caller's request brought obstacles of its own (the CLI's never does) */
        double *mesh_verts = NULL;
        const int own = o.n_obstacles;
        const int left_out = sb_render_scene_obstacles(&b.scene, rq->step >= 0 ? rq->step : sum.steps, &o, &mesh_verts);
        if (left_out < 0) {
            snprintf(err, errlen, "%s: out of memory placing the scene's mesh obstacles", path);
            rc = SB_ERR_NOMEM;
        } else if (left_out > 0) {
            snprintf(err, errlen, "%s: the request's %d obstacles leave room for only %d of the scene's %d (at most %d)",
                     path, own, SB_RENDER_MAX_OBSTACLES - own, b.scene.n_obstacles, SB_RENDER_MAX_OBSTACLES);
            rc = SB_ERR_INPUT;
        } else {
            rc = sb_render_surface(&surf, have_mat ? &mat : NULL, &o, &img, st, err, errlen);
        }
        free(mesh_verts);
        if (rc && !strstr(err, path)) {
            char tmp[1024];
            snprintf(tmp, sizeof tmp, "%s", err);
            snprintf(err, errlen, "%s: %s", path, tmp);
        }
    }
    if (!rc) {
        char build[64], desc[512], param[512];
        sb_sysinfo_build_id(build, sizeof build);
        snprintf(desc, sizeof desc, "%s; ray-patch intersection: %s", surf.what, sb_isect_names[o.isect]);
        snprintf(param, sizeof param, "%dx%d, %d samples per pixel (%s), colour %s, camera azimuth %g elevation %g zoom %g",
                 o.width, o.height, o.spp, SB_RENDER_SAMPLES, sb_color_names[o.color], o.azimuth, o.elevation, o.zoom);
        char software[128];
        snprintf(software, sizeof software, "shellbench render (build %s)", build);
        const char *key[] = { "Title", "Source", "Description", "Comment", "Software" };
        const char *val[] = { o.title, path, desc, param, software };
        if (sb_image_write_png(&img, rq->out, 5, key, val, err, errlen)) rc = SB_ERR_IO;
        if (!rc && info)
            snprintf(info, infolen, "%s: %dx%d, %d spp, %s, %s intersection, %.2f s%s", rq->out, o.width, o.height,
                     o.spp, surf.what, surf.n_patches ? sb_isect_names[o.isect] : "triangle",
                     st ? st->seconds : 0.0,
                     sum.status == SB_STATUS_UNFINISHED && rq->step < 0
                         ? "; a checkpoint of an unfinished run: the state after its last saved step, labelled CHECKPOINT"
                         : "");
    }
    sb_image_free(&img);
    sb_surface_free(&surf);
    rebuilt_free(&b);
    sb_record_summary_free(&sum);
    sb_record_setup_free(&su);
    return rc;
}

int sb_render_record_png(const char *path, const char *out, int w, int h, char *err, size_t errlen)
{
    sb_render_request rq;
    memset(&rq, 0, sizeof rq);
    sb_render_options_default(&rq.opt);
    rq.record = path;
    rq.out = out;
    rq.step = -1;
    rq.opt.width = w > 0 ? w : 320;
    rq.opt.height = h > 0 ? h : 240;
    rq.opt.spp = 8;
    return sb_render_record(&rq, NULL, NULL, 0, err, errlen);
}
