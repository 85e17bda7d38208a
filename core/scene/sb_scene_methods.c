/* sb_scene_methods.c — the scene's "resolution" and its optional per-method
 * "methods" section: the resolution (and the method.* settings) at which
 * each discretization is bundled with the scene.
 *
 * A scene's expected probe values are a contract: every method that supports
 * the scene passes them at its bundled resolution (issue 27, docs/trust.md).
 * Methods of different order need different resolutions for the same
 * tolerance (linear triangles need 64 x 64 on a clamped plate where Hermite
 * elements need 4 x 4), so a scene may say, per method,
 *
 *   "methods": {"linear_fem": {"resolution": 64},
 *               "rmtr": {"resolution": [16, 16], "set": {"method.beta_rule": "scaled"}}}
 *
 * "resolution" replaces the scene's own when --res is absent; "set" holds
 * method.* parameters applied before the command line's --set (which wins).
 * Only method.* keys: a scene describes the problem and how each
 * discretization is bundled with it, never how a solver is run.  Method
 * names and keys are checked against the registry when a run starts (the
 * scene layer does not know the methods), naming the scene file. */
#include "sb_scene_json.h"

#include <stdio.h>
#include <string.h>

int sbj_parse_resolution(sbj_ctx *c, const json_t *obj, const char *key, int *res, int *res_t)
{
    json_t *rv = json_object_get(obj, key);
    if (!rv) return SB_OK;
    if (json_is_array(rv)) {
        /* [N, M]: N elements along s, M along t (strips, annuli; --res NxM) */
        double nm[2];
        size_t mark = sbj_push(c, key);
        int r = sbj_vec_value(c, rv, 2, nm);
        for (int k = 0; k < 2 && !r; k++)
            if (!(nm[k] >= 1 && nm[k] <= SB_SCENE_MAX_RESOLUTION && nm[k] == (long)nm[k]))
                r = sbj_fail(c, NULL, 0, "[N, M] must hold two integers in [1, %d], got [%g, %g]",
                             (int)SB_SCENE_MAX_RESOLUTION, nm[0], nm[1]);
        sbj_pop(c, mark);
        if (r) return r;
        *res = (int)nm[0];
        *res_t = nm[1] != nm[0] ? (int)nm[1] : 0;
        return SB_OK;
    }
    long v = 0;
    int r = sbj_get_int(c, obj, key, 0, 1, SB_SCENE_MAX_RESOLUTION, &v);
    if (r) return r;
    *res = (int)v;
    *res_t = 0;
    return SB_OK;
}

static int parse_set(sbj_ctx *c, const json_t *set, sb_scene_method *m)
{
    const char *key;
    json_t *v;
    json_object_foreach((json_t *)set, key, v) {
        if (m->n_sets >= SB_SCENE_MAX_METHOD_SETS)
            return sbj_fail(c, key, 1, "at most %d settings per method", SB_SCENE_MAX_METHOD_SETS);
        if (strncmp(key, "method.", 7) != 0 || !sbj_valid_name(key + 7))
            return sbj_fail(c, key, 1, "a scene sets only method.* parameters (method.NAME), got \"%s\"", key);
        char val[64];
        if (json_is_string(v)) snprintf(val, sizeof val, "%s", json_string_value(v));
        else if (json_is_integer(v)) snprintf(val, sizeof val, "%lld", (long long)json_integer_value(v));
        else if (json_is_real(v)) snprintf(val, sizeof val, "%.17g", json_real_value(v));
        else if (json_is_boolean(v)) snprintf(val, sizeof val, "%d", json_is_true(v) ? 1 : 0);
        else return sbj_fail(c, key, 0, "must be a number, a string or a boolean, got %s", sbj_type_name(v));
        if (!sbj_valid_name(val) && !json_is_number(v))
            return sbj_fail(c, key, 0, "must be 1..%d characters from [A-Za-z0-9_.-], got \"%s\"", SB_NAME_LEN - 1,
                            val);
        int n = snprintf(m->sets[m->n_sets], sizeof m->sets[0], "%s=%s", key, val);
        if (n < 0 || (size_t)n >= sizeof m->sets[0]) return sbj_fail(c, key, 1, "setting too long");
        m->n_sets++;
    }
    return SB_OK;
}

int sbj_parse_methods(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    json_t *ms = NULL;
    int r = sbj_get_object(c, root, "methods", 0, &ms);
    if (r || !ms) return r;
    size_t mark = sbj_push(c, "methods");
    const char *name;
    json_t *v;
    json_object_foreach(ms, name, v) {
        if (sc->n_methods >= SB_SCENE_MAX_METHODS) {
            r = sbj_fail(c, name, 1, "at most %d methods", SB_SCENE_MAX_METHODS);
            break;
        }
        if (!sbj_valid_name(name)) {
            r = sbj_fail(c, name, 1, "a method name is 1..%d characters from [A-Za-z0-9_.-]", SB_NAME_LEN - 1);
            break;
        }
        if (!json_is_object(v)) {
            r = sbj_fail(c, name, 0, "must be an object {\"resolution\": ..., \"set\": {...}}, got %s", sbj_type_name(v));
            break;
        }
        sb_scene_method *m = &sc->methods[sc->n_methods];
        memset(m, 0, sizeof *m);
        snprintf(m->method, sizeof m->method, "%s", name);
        size_t inner = sbj_push(c, name);
        static const char *const keys[] = { "resolution", "set", NULL };
        json_t *set = NULL;
        if (!(r = sbj_check_keys(c, v, keys)) && !(r = sbj_parse_resolution(c, v, "resolution", &m->res, &m->res_t)) &&
            !(r = sbj_get_object(c, v, "set", 0, &set)) && set) {
            size_t s = sbj_push(c, "set");
            r = parse_set(c, set, m);
            sbj_pop(c, s);
        }
        sbj_pop(c, inner);
        if (r) break;
        sc->n_methods++;
    }
    sbj_pop(c, mark);
    return r;
}

const sb_scene_method *sb_scene_method_find(const sb_scene *sc, const char *method)
{
    for (int i = 0; i < sc->n_methods; i++)
        if (!strcmp(sc->methods[i].method, method)) return &sc->methods[i];
    return NULL;
}

void sb_scene_bundled_res(const sb_scene *sc, const char *method, int *res, int *res_t)
{
    const sb_scene_method *m = method ? sb_scene_method_find(sc, method) : NULL;
    if (m && m->res > 0) {
        *res = m->res;
        *res_t = m->res_t;
    } else {
        *res = sc->default_res > 0 ? sc->default_res : 8;
        *res_t = sc->default_res_t;
    }
}
