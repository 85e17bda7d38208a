/* sb_scene_loads.c — the "loads" and "boundary" arrays of a scene file.
 * Units: acceleration m/s^2, pressure Pa, line force N/m, point force N,
 * end moment N m/m, translations m, rotation angles degrees (radians in
 * memory).  Ramp semantics: see sb_load_factor() in sb_scene.c. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sb_geometry.h"
#include "sb_scene_json.h"

#define MAX_RAMP 1000000L

static int unit_axis(sbj_ctx *c, const json_t *obj, const char *key, double a[3])
{
    int r = sbj_get_vec(c, obj, key, 1, 3, a, NULL);
    if (r) return r;
    double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(n > 0)) return sbj_fail(c, key, 0, "axis must be a nonzero vector");
    for (int k = 0; k < 3; k++) a[k] /= n;
    return SB_OK;
}

static int parse_load(sbj_ctx *c, const json_t *o, const sb_domain *d, sb_load *ld)
{
    static const char *const kinds[] = { "gravity", "pressure", "line", "point", "end_moment", NULL };
    static const char *const k_grav[] = { "type", "acceleration", "ramp_steps", NULL };
    static const char *const k_pres[] = { "type", "pressure", "follower", "ramp_steps", NULL };
    static const char *const k_line[] = { "type", "on", "force_per_length", "ramp_steps", NULL };
    static const char *const k_point[] = { "type", "at", "force", "ramp_steps", NULL };
    static const char *const k_mom[] = { "type", "on", "moment_per_length", "axis", "ramp_steps", NULL };
    static const char *const *const keys[] = { k_grav, k_pres, k_line, k_point, k_mom };
    int kind = 0, r;
    long ramp = 0;

    if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "must be an object, got %s", sbj_type_name(o));
    memset(ld, 0, sizeof *ld);
    if ((r = sbj_get_choice(c, o, "type", 1, kinds, &kind))) return r;
    ld->kind = (sb_load_kind)kind;
    if ((r = sbj_check_keys(c, o, keys[kind]))) return r;
    if ((r = sbj_get_int(c, o, "ramp_steps", 0, 0, MAX_RAMP, &ramp))) return r;
    ld->ramp_steps = (int)ramp;
    switch (ld->kind) {
    case SB_LOAD_GRAVITY:
        return sbj_get_vec(c, o, "acceleration", 1, 3, ld->vec, NULL);
    case SB_LOAD_PRESSURE:
        if ((r = sbj_get_number(c, o, "pressure", 1, &ld->value, NULL))) return r;
        return sbj_get_bool(c, o, "follower", &ld->follower);
    case SB_LOAD_LINE:
        if ((r = sbj_parse_parts(c, o, d, 1, 0, ld->parts, &ld->n_parts))) return r;
        return sbj_get_vec(c, o, "force_per_length", 1, 3, ld->vec, NULL);
    case SB_LOAD_POINT:
        if ((r = sbj_parse_parts(c, o, d, 0, 1, ld->parts, &ld->n_parts))) return r;
        return sbj_get_vec(c, o, "force", 1, 3, ld->vec, NULL);
    case SB_LOAD_END_MOMENT:
        if ((r = sbj_parse_parts(c, o, d, 1, 0, ld->parts, &ld->n_parts))) return r;
        if ((r = sbj_get_number(c, o, "moment_per_length", 1, &ld->value, NULL))) return r;
        return unit_axis(c, o, "axis", ld->vec);
    }
    return SB_OK;
}

static int sbj_parse_loads_item(sbj_ctx *c, const json_t *o, sb_scene *sc, size_t i)
{
    return parse_load(c, o, &sc->domain, &sc->loads[i]);
}

int sbj_parse_loads(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    return sbj_parse_list(c, root, "loads", "loads", SB_SCENE_MAX_LOADS, sbj_parse_loads_item, sc, &sc->n_loads);
}

/* "components": a non-empty subset of "xyz" -> bit mask (default all). */
static int parse_components(sbj_ctx *c, const json_t *o, unsigned *mask)
{
    char s[8];
    int present, r = sbj_get_string(c, o, "components", 0, s, sizeof s, &present);
    *mask = 7;
    if (r) return r;
    if (!present) return SB_OK;
    *mask = 0;
    if (!s[0]) return sbj_fail(c, "components", 0, "must be a non-empty subset of \"xyz\", got \"\"");
    for (const char *p = s; *p; p++) {
        unsigned bit = *p == 'x' ? 1u : *p == 'y' ? 2u : *p == 'z' ? 4u : 0u;
        if (!bit || (*mask & bit))
            return sbj_fail(c, "components", 0, "must be a non-empty subset of \"xyz\" without repeats, got \"%s\"", s);
        *mask |= bit;
    }
    return SB_OK;
}

static int parse_rotation(sbj_ctx *c, const json_t *o, sb_bc *bc)
{
    static const char *const keys[] = { "axis", "center", "angle", NULL };
    json_t *rot;
    double deg = 0;
    int r = sbj_get_object(c, o, "rotation", 0, &rot);
    if (r || !rot) return r;
    size_t mark = sbj_push(c, "rotation");
    if (!(r = sbj_check_keys(c, rot, keys)) && !(r = unit_axis(c, rot, "axis", bc->rot_axis)) &&
        !(r = sbj_get_vec(c, rot, "center", 0, 3, bc->rot_center, NULL)) &&
        !(r = sbj_get_number(c, rot, "angle", 1, &deg, NULL))) {
        if (!(fabs(deg) <= 3600)) r = sbj_fail(c, "angle", 0, "must be in [-3600, 3600] degrees, got %g", deg);
        bc->rot_angle = deg * SBJ_DEG;
    }
    sbj_pop(c, mark);
    return r;
}

/* "derivative": "s" | "t" | "st" — which nodal first derivatives a moving
 * condition prescribes (the BHEM paper's Neumann constraints at nodes, §4.2:
 * the umbrella of Fig. 5 moves its ribs by "jointly controlling nodal
 * positions and their first-order derivatives").  clamp_tangent already
 * prescribes both, so the two keys exclude each other. */
static int parse_derivative(sbj_ctx *c, const json_t *o, sb_bc *bc)
{
    static const char *const dirs[] = { "s", "t", "st", NULL };
    int which = -1, r;
    if (!json_object_get(o, "derivative")) return SB_OK;
    if ((r = sbj_get_choice(c, o, "derivative", 1, dirs, &which))) return r;
    if (bc->clamp_tangent)
        return sbj_fail(c, "derivative", 0, "\"derivative\" and \"clamp_tangent\" exclude each other "
                        "(clamp_tangent already prescribes both first derivatives)");
    bc->derivative = (unsigned)which + 1u;   /* "s" 1, "t" 2, "st" 3 */
    return SB_OK;
}

/* "slide": {"to": [x, y], "stiffness": k} on a moving condition with one
 * point in "at" and no "on" (docs/scene_format.md "Sliding pins"). */
#define MAX_PIN_STIFFNESS 1e15
static int parse_slide(sbj_ctx *c, const json_t *o, const sb_domain *d, sb_bc *bc)
{
    static const char *const keys[] = { "to", "stiffness", NULL };
    json_t *sl;
    int r = sbj_get_object(c, o, "slide", 0, &sl);
    if (r || !sl) return r;
    if (bc->n_parts != 1 || bc->parts[0].kind != SB_PART_POINT)
        return sbj_fail(c, "slide", 1, "a sliding pin needs exactly one point in \"at\" and no \"on\" (got %d %s%s)",
                        bc->n_parts, bc->n_parts == 1 && bc->parts[0].kind != SB_PART_POINT ? "edge" : "part",
                        bc->n_parts == 1 ? "" : "s");
    if (bc->clamp_tangent || bc->derivative)
        return sbj_fail(c, "slide", 1, "\"slide\" and \"%s\" exclude each other (a sliding pin holds the "
                        "position only)", bc->clamp_tangent ? "clamp_tangent" : "derivative");
    size_t mark = sbj_push(c, "slide");
    json_t *to = json_object_get(sl, "to");
    if (!(r = sbj_check_keys(c, sl, keys))) {
        if (!to) r = sbj_fail(c, NULL, 0, "missing required key \"to\" (the material point the pin slides to)");
        else {
            size_t m2 = sbj_push(c, "to");
            r = sbj_parse_point(c, to, d, bc->slide_xi, bc->slide_st);
            sbj_pop(c, m2);
        }
    }
    if (!r) r = sbj_get_number(c, sl, "stiffness", 1, &bc->slide_stiffness, NULL);
    if (!r && !(bc->slide_stiffness > 0.0 && bc->slide_stiffness <= MAX_PIN_STIFFNESS))
        r = sbj_fail(c, "stiffness", 0, "must be in (0, %g] N/m, got %g", MAX_PIN_STIFFNESS, bc->slide_stiffness);
    /* the pin runs along the straight segment in (s, t): every point of it
       must lie in the domain (an L-shape's notch may cut it) */
    for (int k = 1; !r && k < 64; k++) {
        const double f = k / 64.0;
        const double st[2] = { bc->parts[0].st[0] + f * (bc->slide_st[0] - bc->parts[0].st[0]),
                               bc->parts[0].st[1] + f * (bc->slide_st[1] - bc->parts[0].st[1]) };
        if (!sb_domain_contains_st(d, st[0], st[1]))
            r = sbj_fail(c, "to", 0, "the pin's path from (%g, %g) to (%g, %g) leaves the domain", bc->parts[0].xi[0],
                         bc->parts[0].xi[1], bc->slide_xi[0], bc->slide_xi[1]);
    }
    sbj_pop(c, mark);
    bc->slide = r == SB_OK;
    return r;
}

static int parse_bc(sbj_ctx *c, const json_t *o, const sb_domain *d, const sb_time_spec *tm, sb_bc *bc)
{
    static const char *const kinds[] = { "fixed", "clamped", "symmetry", "moving", "free", NULL };
    static const char *const k_fixed[] = { "type", "on", "at", "components", NULL };
    static const char *const k_clamp[] = { "type", "on", "at", NULL };
    static const char *const k_sym[] = { "type", "on", "normal", NULL };
    static const char *const k_mov[] = { "type", "on", "at", "components", "translation", "rotation",
                                         "ramp_steps", "schedule", "clamp_tangent", "derivative", "slide", NULL };
    static const char *const k_free[] = { "type", "on", NULL };
    static const char *const *const keys[] = { k_fixed, k_clamp, k_sym, k_mov, k_free };
    static const char *const axes[] = { "x", "y", "z", NULL };
    int kind = 0, r;

    if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "must be an object, got %s", sbj_type_name(o));
    memset(bc, 0, sizeof *bc);
    bc->components = 7;
    if ((r = sbj_get_choice(c, o, "type", 1, kinds, &kind))) return r;
    bc->kind = (sb_bc_kind)kind;
    if ((r = sbj_check_keys(c, o, keys[kind]))) return r;
    int points_ok = bc->kind == SB_BC_FIXED || bc->kind == SB_BC_CLAMPED || bc->kind == SB_BC_MOVING;
    if ((r = sbj_parse_parts(c, o, d, 1, points_ok, bc->parts, &bc->n_parts))) return r;
    switch (bc->kind) {
    case SB_BC_FIXED:
        return parse_components(c, o, &bc->components);
    case SB_BC_SYMMETRY:
        return sbj_get_choice(c, o, "normal", 1, axes, &bc->axis);
    case SB_BC_MOVING: {
        long ramp = 0;
        int has_t = 0;
        if ((r = parse_components(c, o, &bc->components))) return r;
        if ((r = sbj_get_vec(c, o, "translation", 0, 3, bc->translation, &has_t))) return r;
        if ((r = parse_rotation(c, o, bc))) return r;
        if (!has_t && !json_object_get(o, "rotation") && !json_object_get(o, "slide"))
            return sbj_fail(c, NULL, 0, "a moving boundary needs \"translation\", \"rotation\" and/or \"slide\"");
        if ((r = sbj_get_int(c, o, "ramp_steps", 0, 0, MAX_RAMP, &ramp))) return r;
        bc->ramp_steps = (int)ramp;
        int has_s = 0;
        if ((r = sbj_parse_schedule(c, o, tm, &bc->schedule, &has_s))) return r;
        if (has_s && json_object_get(o, "ramp_steps"))
            return sbj_fail(c, "schedule", 1, "\"schedule\" and \"ramp_steps\" exclude each other (the schedule sets the timing)");
        if ((r = sbj_get_bool(c, o, "clamp_tangent", &bc->clamp_tangent))) return r;
        if ((r = parse_derivative(c, o, bc))) return r;
        return parse_slide(c, o, d, bc);
    }
    case SB_BC_CLAMPED:
    case SB_BC_FREE:
        break;
    }
    return SB_OK;
}

static int sbj_parse_boundary_item(sbj_ctx *c, const json_t *o, sb_scene *sc, size_t i)
{
    return parse_bc(c, o, &sc->domain, &sc->time, &sc->bcs[i]);
}

int sbj_parse_boundary(sbj_ctx *c, const json_t *root, sb_scene *sc)
{
    return sbj_parse_list(c, root, "boundary", "boundary conditions", SB_SCENE_MAX_BCS, sbj_parse_boundary_item, sc, &sc->n_bcs);
}
