/* sb_scene_contact.c — the "obstacles" and "contact" sections of a scene
 * (docs/contact.md): analytic obstacles (sphere, plane, box, capsule) and
 * triangle meshes from Wavefront OBJ files relative to the scene file, each
 * static or moving by a ramped rigid motion (as moving boundaries are), with
 * a Coulomb friction coefficient; and the barrier's parameters.  A scene
 * without "obstacles" has no contact at all (and no cost). */
#include "sb_scene_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_RAMP 1000000L

static int unit_vec(sbj_ctx *c, const json_t *o, const char *key, int required, double a[3], int *present)
{
    int has = 0, r = sbj_get_vec(c, o, key, required, 3, a, &has);
    if (present) *present = has || required;
    if (r || !(has || required)) return r;
    double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(n > 0)) return sbj_fail(c, key, 0, "must be a nonzero vector");
    for (int k = 0; k < 3; k++) a[k] /= n;
    return SB_OK;
}

static int parse_motion(sbj_ctx *c, const json_t *o, const sb_time_spec *tm, sb_obstacle_spec *ob)
{
    static const char *const keys[] = { "translation", "rotation", "ramp_steps", "schedule", NULL };
    static const char *const rkeys[] = { "axis", "center", "angle", NULL };
    json_t *m, *rot;
    int r = sbj_get_object(c, o, "motion", 0, &m);
    if (r || !m) return r;
    size_t mark = sbj_push(c, "motion");
    int has_t = 0, has_s = 0;
    long ramp = 0;
    if ((r = sbj_check_keys(c, m, keys)) || (r = sbj_get_vec(c, m, "translation", 0, 3, ob->translation, &has_t)) ||
        (r = sbj_get_object(c, m, "rotation", 0, &rot)))
        goto out;
    if (rot) {
        double deg = 0;
        size_t m2 = sbj_push(c, "rotation");
        if (!(r = sbj_check_keys(c, rot, rkeys)) && !(r = unit_vec(c, rot, "axis", 1, ob->rot_axis, NULL)) &&
            !(r = sbj_get_vec(c, rot, "center", 0, 3, ob->rot_center, NULL)) &&
            !(r = sbj_get_number(c, rot, "angle", 1, &deg, NULL))) {
            if (!(fabs(deg) <= 3600)) r = sbj_fail(c, "angle", 0, "must be in [-3600, 3600] degrees, got %g", deg);
            ob->rot_angle = deg * SBJ_DEG;
        }
        sbj_pop(c, m2);
        if (r) goto out;
    }
    if (!has_t && !rot) {
        r = sbj_fail(c, NULL, 0, "a motion needs \"translation\" and/or \"rotation\"");
        goto out;
    }
    if ((r = sbj_get_int(c, m, "ramp_steps", 0, 0, MAX_RAMP, &ramp))) goto out;
    ob->ramp_steps = (int)ramp;
    if ((r = sbj_parse_schedule(c, m, tm, &ob->schedule, &has_s))) goto out;
    if (has_s && json_object_get(m, "ramp_steps")) {
        r = sbj_fail(c, "schedule", 1, "\"schedule\" and \"ramp_steps\" exclude each other (the schedule sets the timing)");
        goto out;
    }
    ob->moving = 1;
out:
    sbj_pop(c, mark);
    return r;
}

/* the directory of the scene file, for OBJ paths */
static void scene_dir(const char *file, char *dir, size_t len)
{
    const char *slash = strrchr(file, '/');
    if (!slash) snprintf(dir, len, ".");
    else snprintf(dir, len, "%.*s", (int)(slash - file), file);
}

static int parse_mesh(sbj_ctx *c, const json_t *o, sb_obstacle_spec *ob)
{
    int r = sbj_get_string(c, o, "file", 1, ob->file, sizeof ob->file, NULL);
    if (r) return r;
    if (!ob->file[0]) return sbj_fail(c, "file", 0, "must name an OBJ file");
    char path[1200], dir[600], msg[900];
    if (ob->file[0] == '/') snprintf(path, sizeof path, "%s", ob->file);
    else {
        scene_dir(c->file, dir, sizeof dir);
        snprintf(path, sizeof path, "%s/%s", dir, ob->file);
    }
    if (sb_obj_read(path, &ob->verts, &ob->nv, &ob->tris, &ob->nt, msg, sizeof msg))
        return sbj_fail(c, "file", 0, "%s", msg);
    return SB_OK;
}

static int parse_obstacle(sbj_ctx *c, const json_t *o, sb_scene *sc, size_t i)
{
    static const char *const kinds[] = { "sphere", "plane", "box", "capsule", "mesh", NULL };
    static const char *const k_sph[] = { "type", "name", "friction", "motion", "center", "radius", NULL };
    static const char *const k_pla[] = { "type", "name", "friction", "motion", "point", "normal", NULL };
    static const char *const k_box[] = { "type", "name", "friction", "motion", "center", "half_extents", NULL };
    static const char *const k_cap[] = { "type", "name", "friction", "motion", "from", "to", "radius", NULL };
    static const char *const k_msh[] = { "type", "name", "friction", "motion", "file", NULL };
    static const char *const *const keys[] = { k_sph, k_pla, k_box, k_cap, k_msh };
    sb_obstacle_spec *ob = &sc->obstacles[i];
    int kind = 0, r, has = 0;
    if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "must be an object, got %s", sbj_type_name(o));
    memset(ob, 0, sizeof *ob);
    if ((r = sbj_get_choice(c, o, "type", 1, kinds, &kind))) return r;
    ob->kind = (sb_obstacle_shape)kind;
    if ((r = sbj_check_keys(c, o, keys[kind]))) return r;
    snprintf(ob->name, sizeof ob->name, "%s_%zu", kinds[kind], i);
    if ((r = sbj_get_string(c, o, "name", 0, ob->name, sizeof ob->name, &has))) return r;
    if (has && !sbj_valid_name(ob->name))
        return sbj_fail(c, "name", 0, "must be 1..%d characters from [A-Za-z0-9_.-], got \"%s\"", SB_NAME_LEN - 1,
                        ob->name);
    if ((r = sbj_get_number(c, o, "friction", 0, &ob->friction, NULL))) return r;
    if (!(ob->friction >= 0 && ob->friction <= 100))
        return sbj_fail(c, "friction", 0, "must be a coefficient in [0, 100], got %g", ob->friction);
    switch (ob->kind) {
    case SB_OBST_SPHERE:
        if ((r = sbj_get_vec(c, o, "center", 1, 3, ob->center, NULL)) ||
            (r = sbj_get_number(c, o, "radius", 1, &ob->radius, NULL)) ||
            (r = sbj_require_positive(c, "radius", ob->radius)))
            return r;
        break;
    case SB_OBST_PLANE:
        if ((r = sbj_get_vec(c, o, "point", 1, 3, ob->point, NULL)) || (r = unit_vec(c, o, "normal", 1, ob->normal, NULL)))
            return r;
        break;
    case SB_OBST_BOX:
        if ((r = sbj_get_vec(c, o, "center", 1, 3, ob->center, NULL)) ||
            (r = sbj_get_vec(c, o, "half_extents", 1, 3, ob->half, NULL)))
            return r;
        for (int k = 0; k < 3; k++)
            if (!(ob->half[k] > 0))
                return sbj_fail(c, "half_extents", 0, "must be three positive lengths, got [%g, %g, %g]", ob->half[0],
                                ob->half[1], ob->half[2]);
        break;
    case SB_OBST_CAPSULE: {
        if ((r = sbj_get_vec(c, o, "from", 1, 3, ob->a, NULL)) || (r = sbj_get_vec(c, o, "to", 1, 3, ob->b, NULL)) ||
            (r = sbj_get_number(c, o, "radius", 1, &ob->radius, NULL)) ||
            (r = sbj_require_positive(c, "radius", ob->radius)))
            return r;
        double L = 0;
        for (int k = 0; k < 3; k++) L += (ob->b[k] - ob->a[k]) * (ob->b[k] - ob->a[k]);
        if (!(L > 0)) return sbj_fail(c, "to", 0, "must differ from \"from\" (a capsule needs an axis)");
        break;
    }
    case SB_OBST_MESH:
        if ((r = parse_mesh(c, o, ob))) return r;
        break;
    }
    return parse_motion(c, o, &sc->time, ob);
}

/* contact.model ("barrier" | "impulse") and contact.self (boolean) */
static int parse_model(sbj_ctx *c, const json_t *o, sb_contact_spec *cs)
{
    const json_t *m = json_object_get(o, "model");
    if (m) {
        const char *s = json_is_string(m) ? json_string_value(m) : NULL;
        if (s && !strcmp(s, "barrier"))
            cs->model = SB_CONTACT_BARRIER;
        else if (s && !strcmp(s, "impulse"))
            cs->model = SB_CONTACT_IMPULSE;
        else
            return sbj_fail(c, "model", 0, "must be \"barrier\" or \"impulse\"");
    }
    const json_t *se = json_object_get(o, "self");
    if (se) {
        if (!json_is_boolean(se)) return sbj_fail(c, "self", 0, "must be true or false");
        cs->self = json_is_true(se);
    }
    return SB_OK;
}

static int parse_contact(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    static const char *const keys[] = { "dhat", "kappa", "eps_v", "samples", "filter", "model", "self", NULL };
    json_t *o;
    int r = sbj_get_object(c, root, "contact", 0, &o);
    if (r) return r;
    sb_contact_spec *cs = &sc->contact;
    /* defaults (docs/contact.md): 1 mm activation distance; kappa such that
     * a cloth of the scene's areal density at rest under 1 g sits at about
     * dhat/10 (-b'(dhat/10) = 12.2 dhat, IPC Eq. 6); eps_v 1 mm/s; 3 x 3
     * sample points per element; a step may take 90% of its time of impact */
    cs->dhat = 1e-3;
    cs->kappa = 0;
    cs->eps_v = 1e-3;
    cs->samples = 3;
    cs->filter = 0.9;
    cs->model = SB_CONTACT_BARRIER;
    cs->self = 0;
    if (o && sc->n_obstacles == 0)
        return sbj_fail(c, "contact", 1, "a \"contact\" section needs \"obstacles\"");
    if (o) {
        long smp = cs->samples;
        size_t mark = sbj_push(c, "contact");
        if (!(r = sbj_check_keys(c, o, keys)) && !(r = sbj_get_number(c, o, "dhat", 0, &cs->dhat, NULL)) &&
            !(r = sbj_require_positive(c, "dhat", cs->dhat)) && !(r = sbj_get_number(c, o, "kappa", 0, &cs->kappa, NULL)) &&
            !(r = sbj_require_nonneg(c, "kappa", cs->kappa)) && !(r = sbj_get_number(c, o, "eps_v", 0, &cs->eps_v, NULL)) &&
            !(r = sbj_require_positive(c, "eps_v", cs->eps_v)) &&
            !(r = sbj_get_int(c, o, "samples", 0, 1, 16, &smp)) &&
            !(r = sbj_get_number(c, o, "filter", 0, &cs->filter, NULL))) {
            cs->samples = (int)smp;
            if (!(cs->filter > 0 && cs->filter < 1))
                r = sbj_fail(c, "filter", 0, "must be a fraction in (0, 1), got %g", cs->filter);
        }
        if (!r) r = parse_model(c, o, cs);
        sbj_pop(c, mark);
        if (r) return r;
    }
    if (cs->kappa == 0) cs->kappa = 10.0 * sc->material.density * 9.81 / cs->dhat;
    return SB_OK;
}

int sbj_parse_obstacles(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    int r = sbj_parse_list(c, root, "obstacles", "obstacles", SB_SCENE_MAX_OBSTACLES, parse_obstacle, sc,
                           &sc->n_obstacles);
    if (r) {
        /* the failing item may hold a mesh already */
        if (sc->n_obstacles < SB_SCENE_MAX_OBSTACLES) sc->n_obstacles++;
        return r;
    }
    return parse_contact(c, root, sc);
}

void sbj_free_obstacles(sb_scene *sc)
{
    for (int i = 0; i < sc->n_obstacles && i < SB_SCENE_MAX_OBSTACLES; i++) {
        free(sc->obstacles[i].verts);
        free(sc->obstacles[i].tris);
        sc->obstacles[i].verts = NULL;
        sc->obstacles[i].tris = NULL;
    }
}
