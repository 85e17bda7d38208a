/* sb_scene_probes.c — the "time", "probes" and "reference" sections.
 *
 *   "time": {"mode": "quasi_static", "steps": n}
 *         | {"mode": "dynamic", "dt": s, "steps": n, "rayleigh": {"alpha": 1/s, "beta": s}}
 *   "probes": [{"name": "tip", "at": [xi1, xi2],
 *               "expected": {"component": "x"|"y"|"z"|"norm"|"vector",
 *                            "value": m (or [ux, uy, uz] for "vector"),
 *                            "tol": relative}}]
 *   "reference": {"type": "none"|"probes"|"file", "file": path, "note": text}
 *
 * Expected values are displacements (x - X) at the final step. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sb_scene_json.h"

#define MAX_STEPS 1000000L

int sbj_parse_time(sbj_ctx *c, const json_t *root, sb_time_spec *t)
{
    static const char *const modes[] = { "quasi_static", "dynamic", NULL };
    static const char *const k_qs[] = { "mode", "steps", NULL };
    static const char *const k_dyn[] = { "mode", "dt", "steps", "rayleigh", NULL };
    static const char *const k_ray[] = { "alpha", "beta", NULL };
    json_t *o, *ray;
    int mode = 0, r;
    long steps = 0;

    if ((r = sbj_get_object(c, root, "time", 1, &o))) return r;
    memset(t, 0, sizeof *t);
    size_t mark = sbj_push(c, "time");
    if ((r = sbj_get_choice(c, o, "mode", 1, modes, &mode))) goto out;
    t->mode = mode ? SB_TIME_DYNAMIC : SB_TIME_QUASI_STATIC;
    if ((r = sbj_check_keys(c, o, mode ? k_dyn : k_qs))) goto out;
    if ((r = sbj_get_int(c, o, "steps", 1, 1, MAX_STEPS, &steps))) goto out;
    t->steps = (int)steps;
    if (t->mode == SB_TIME_QUASI_STATIC) goto out;
    if ((r = sbj_get_number(c, o, "dt", 1, &t->dt, NULL))) goto out;
    if ((r = sbj_require_positive(c, "dt", t->dt))) goto out;
    if ((r = sbj_get_object(c, o, "rayleigh", 0, &ray)) || !ray) goto out;
    size_t m2 = sbj_push(c, "rayleigh");
    /* Bender & Deul Eq. (20): D = alpha M + beta K, both >= 0 */
    if (!(r = sbj_check_keys(c, ray, k_ray)) &&
        !(r = sbj_get_number(c, ray, "alpha", 0, &t->rayleigh_alpha, NULL)) &&
        !(r = sbj_require_nonneg(c, "alpha", t->rayleigh_alpha)) &&
        !(r = sbj_get_number(c, ray, "beta", 0, &t->rayleigh_beta, NULL)))
        r = sbj_require_nonneg(c, "beta", t->rayleigh_beta);
    sbj_pop(c, m2);
out:
    sbj_pop(c, mark);
    return r;
}

static int parse_expected(sbj_ctx *c, const json_t *o, sb_probe *p)
{
    static const char *const keys[] = { "component", "value", "tol", NULL };
    static const char *const comps[] = { "x", "y", "z", "norm", "vector", NULL };
    json_t *e;
    int comp = 0, r = sbj_get_object(c, o, "expected", 0, &e);
    if (r || !e) return r;
    size_t mark = sbj_push(c, "expected");
    if ((r = sbj_check_keys(c, e, keys)) || (r = sbj_get_choice(c, e, "component", 1, comps, &comp)))
        goto out;
    p->expected_component = comp == 4 ? -1 : comp;
    if (comp == 4) {
        if ((r = sbj_get_vec(c, e, "value", 1, 3, p->expected, NULL))) goto out;
    } else {
        if ((r = sbj_get_number(c, e, "value", 1, &p->expected[0], NULL))) goto out;
        if (comp == 3 && (r = sbj_require_nonneg(c, "value", p->expected[0]))) goto out;
    }
    if ((r = sbj_get_number(c, e, "tol", 1, &p->tol, NULL))) goto out;
    if (!(p->tol > 0 && p->tol <= 1)) {
        r = sbj_fail(c, "tol", 0, "relative tolerance must be in (0, 1], got %g", p->tol);
        goto out;
    }
    p->has_expected = 1;
out:
    sbj_pop(c, mark);
    return r;
}

static int parse_probe(sbj_ctx *c, const json_t *o, const sb_scene *sc, sb_probe *p)
{
    static const char *const keys[] = { "name", "at", "expected", NULL };
    json_t *at;
    int r;
    if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "must be an object, got %s", sbj_type_name(o));
    memset(p, 0, sizeof *p);
    if ((r = sbj_check_keys(c, o, keys))) return r;
    if ((r = sbj_get_string(c, o, "name", 1, p->name, sizeof p->name, NULL))) return r;
    if (!sbj_valid_name(p->name))
        return sbj_fail(c, "name", 0, "must be 1..%d characters from [A-Za-z0-9_.-], got \"%s\"",
                        SB_NAME_LEN - 1, p->name);
    for (int i = 0; i < sc->n_probes; i++)
        if (strcmp(sc->probes[i].name, p->name) == 0)
            return sbj_fail(c, "name", 0, "duplicate probe name \"%s\" (also probe %d)", p->name, i);
    if (!(at = json_object_get(o, "at"))) return sbj_fail(c, NULL, 0, "missing required key \"at\"");
    size_t mark = sbj_push(c, "at");
    r = sbj_parse_point(c, at, &sc->domain, p->xi, p->st);
    sbj_pop(c, mark);
    if (r) return r;
    return parse_expected(c, o, p);
}

static int sbj_parse_probes_item(sbj_ctx *c, const json_t *o, sb_scene *sc, size_t i)
{
    return parse_probe(c, o, sc, &sc->probes[i]);
}

int sbj_parse_probes(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    return sbj_parse_list(c, root, "probes", "probes", SB_SCENE_MAX_PROBES, sbj_parse_probes_item, sc, &sc->n_probes);
}

int sbj_parse_reference(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    static const char *const kinds[] = { "none", "probes", "file", NULL };
    static const char *const k_none[] = { "type", "note", NULL };
    static const char *const k_file[] = { "type", "file", "note", NULL };
    sb_reference *ref = &sc->reference;
    json_t *o;
    int kind = 0, n_expected = 0, r;

    for (int i = 0; i < sc->n_probes; i++) n_expected += sc->probes[i].has_expected;
    memset(ref, 0, sizeof *ref);
    /* absent: probes with "expected" make it a probe reference */
    ref->kind = n_expected ? SB_REF_PROBES : SB_REF_NONE;
    if ((r = sbj_get_object(c, root, "reference", 0, &o)) || !o) return r;
    size_t mark = sbj_push(c, "reference");
    if ((r = sbj_get_choice(c, o, "type", 1, kinds, &kind))) goto out;
    ref->kind = kind == 0 ? SB_REF_NONE : kind == 1 ? SB_REF_PROBES : SB_REF_FILE;
    if ((r = sbj_check_keys(c, o, kind == 2 ? k_file : k_none))) goto out;
    if ((r = sbj_get_string(c, o, "note", 0, ref->note, sizeof ref->note, NULL))) goto out;
    if (ref->kind == SB_REF_PROBES && n_expected == 0) {
        r = sbj_fail(c, "type", 0, "reference \"probes\" needs at least one probe with \"expected\"");
        goto out;
    }
    if (ref->kind == SB_REF_FILE) {
        char file[sizeof ref->file];
        if ((r = sbj_get_string(c, o, "file", 1, file, sizeof file, NULL))) goto out;
        if (!file[0]) { r = sbj_fail(c, "file", 0, "must not be empty"); goto out; }
        /* relative paths are relative to the scene file's directory */
        const char *slash = strrchr(sc->path, '/');
        int dir = (file[0] != '/' && slash) ? (int)(slash - sc->path) : 0;
        int n = dir ? snprintf(ref->file, sizeof ref->file, "%.*s/%s", dir, sc->path, file)
                    : snprintf(ref->file, sizeof ref->file, "%s", file);
        if (n < 0 || (size_t)n >= sizeof ref->file)
            r = sbj_fail(c, "file", 0, "resolved path is too long (at most %zu bytes)", sizeof ref->file - 1);
    }
out:
    sbj_pop(c, mark);
    return r;
}
