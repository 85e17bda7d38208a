/* sb_scene_domain.c — the "domain" and "geometry" sections of a scene file,
 * boundary parts ("on" edge names / "at" material points) and material
 * points.  Angles are degrees in JSON and radians in memory. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sb_geometry.h"
#include "sb_scene_json.h"

/* An angle range [a0, a1] in degrees: a0 < a1, a1 - a0 <= 360, and when
 * lo_hi is given lo <= a0 and a1 <= hi (strict when strict = 1). */
static int angle_range(sbj_ctx *c, const json_t *obj, const char *key, const double *lo_hi,
                       int strict, double out[2])
{
    double a[2];
    int r = sbj_get_vec(c, obj, key, 1, 2, a, NULL);
    if (r) return r;
    if (!(a[0] < a[1]))
        return sbj_fail(c, key, 0, "angle range is reversed or empty: [%g, %g] degrees", a[0], a[1]);
    if (a[1] - a[0] > 360)
        return sbj_fail(c, key, 0, "angle range spans %g degrees, more than 360", a[1] - a[0]);
    if (fabs(a[0]) > 720 || fabs(a[1]) > 720)
        return sbj_fail(c, key, 0, "angles must lie in [-720, 720] degrees, got [%g, %g]", a[0], a[1]);
    if (lo_hi && (strict ? !(a[0] > lo_hi[0] && a[1] < lo_hi[1]) : !(a[0] >= lo_hi[0] && a[1] <= lo_hi[1])))
        return sbj_fail(c, key, 0, "must lie in %s%g, %g%s degrees, got [%g, %g]", strict ? "(" : "[",
                        lo_hi[0], lo_hi[1], strict ? ")" : "]", a[0], a[1]);
    out[0] = a[0] * SBJ_DEG;
    out[1] = a[1] * SBJ_DEG;
    return SB_OK;
}

static int positive_vec2(sbj_ctx *c, const json_t *obj, const char *key, double out[2])
{
    int r = sbj_get_vec(c, obj, key, 1, 2, out, NULL);
    if (r) return r;
    for (int k = 0; k < 2; k++) {
        if (!(out[k] > 0)) {
            size_t mark = sbj_push(c, key);
            char tok[16];
            snprintf(tok, sizeof tok, "%d", k);
            r = sbj_fail(c, tok, 0, "must be > 0, got %g", out[k]);
            sbj_pop(c, mark);
            return r;
        }
    }
    return SB_OK;
}

static int parse_domain_body(sbj_ctx *c, const json_t *dom, sb_domain *d)
{
    static const char *const kinds[] = { "rectangle", "l_shape", "annulus_sector", NULL };
    static const char *const corners[] = { "00", "10", "11", "01", NULL };  /* = SB_CORNER_* */
    static const char *const k_rect[] = { "type", "origin", "size", NULL };
    static const char *const k_l[] = { "type", "origin", "size", "notch", "notch_corner", NULL };
    static const char *const k_ann[] = { "type", "center", "r_in", "r_out", "theta", NULL };
    int kind = 0, r;

    if ((r = sbj_get_choice(c, dom, "type", 1, kinds, &kind))) return r;
    d->kind = (sb_domain_kind)kind;
    if (d->kind == SB_DOMAIN_ANNULUS_SECTOR) {
        if ((r = sbj_check_keys(c, dom, k_ann))) return r;
        if ((r = sbj_get_vec(c, dom, "center", 0, 2, d->center, NULL))) return r;
        if ((r = sbj_get_number(c, dom, "r_in", 1, &d->r_in, NULL))) return r;
        if ((r = sbj_require_nonneg(c, "r_in", d->r_in))) return r;
        if ((r = sbj_get_number(c, dom, "r_out", 1, &d->r_out, NULL))) return r;
        if (!(d->r_out > d->r_in))
            return sbj_fail(c, "r_out", 0, "must be greater than r_in = %g, got %g", d->r_in, d->r_out);
        return angle_range(c, dom, "theta", NULL, 0, d->theta);
    }
    if ((r = sbj_check_keys(c, dom, d->kind == SB_DOMAIN_L_SHAPE ? k_l : k_rect))) return r;
    if ((r = sbj_get_vec(c, dom, "origin", 0, 2, d->origin, NULL))) return r;
    if ((r = positive_vec2(c, dom, "size", d->size))) return r;
    if (d->kind != SB_DOMAIN_L_SHAPE) return SB_OK;
    if ((r = positive_vec2(c, dom, "notch", d->notch))) return r;
    for (int k = 0; k < 2; k++)
        if (!(d->notch[k] < d->size[k]))
            return sbj_fail(c, "notch", 0, "notch [%g, %g] must be smaller than size [%g, %g]",
                            d->notch[0], d->notch[1], d->size[0], d->size[1]);
    return sbj_get_choice(c, dom, "notch_corner", 1, corners, &d->notch_corner);
}

int sbj_parse_domain(sbj_ctx *c, const json_t *root, sb_domain *d)
{
    json_t *dom;
    int r = sbj_get_object(c, root, "domain", 1, &dom);
    if (r) return r;
    memset(d, 0, sizeof *d);
    size_t mark = sbj_push(c, "domain");
    r = parse_domain_body(c, dom, d);
    sbj_pop(c, mark);
    return r;
}

static int parse_geometry_body(sbj_ctx *c, const json_t *g, sb_chart *ch)
{
    static const char *const kinds[] = { "plane", "cylinder", "sphere", NULL };
    static const char *const k_plane[] = { "type", NULL };
    static const char *const k_cyl[] = { "type", "radius", "angle", "length", NULL };
    static const char *const k_sph[] = { "type", "radius", "polar", "azimuth", NULL };
    static const double polar_lim[2] = { 0, 180 };
    int kind = 0, r;

    if ((r = sbj_get_choice(c, g, "type", 1, kinds, &kind))) return r;
    ch->kind = (sb_chart_kind)kind;
    if (ch->kind == SB_CHART_PLANE) return sbj_check_keys(c, g, k_plane);
    if ((r = sbj_check_keys(c, g, ch->kind == SB_CHART_CYLINDER ? k_cyl : k_sph))) return r;
    if ((r = sbj_get_number(c, g, "radius", 1, &ch->radius, NULL))) return r;
    if ((r = sbj_require_positive(c, "radius", ch->radius))) return r;
    if (ch->kind == SB_CHART_CYLINDER) {
        if ((r = angle_range(c, g, "angle", NULL, 0, ch->angle))) return r;
        if ((r = sbj_get_number(c, g, "length", 1, &ch->length, NULL))) return r;
        return sbj_require_positive(c, "length", ch->length);
    }
    /* the sphere chart is singular at the poles (a_1 = 0): keep them out */
    if ((r = angle_range(c, g, "polar", polar_lim, 1, ch->polar))) return r;
    return angle_range(c, g, "azimuth", NULL, 0, ch->azimuth);
}

int sbj_parse_geometry(sbj_ctx *c, const json_t *root, const sb_domain *d, sb_chart *ch)
{
    json_t *g;
    (void)d;
    memset(ch, 0, sizeof *ch);
    ch->kind = SB_CHART_PLANE;               /* default when "geometry" is absent */
    int r = sbj_get_object(c, root, "geometry", 0, &g);
    if (r || !g) return r;
    size_t mark = sbj_push(c, "geometry");
    r = parse_geometry_body(c, g, ch);
    sbj_pop(c, mark);
    return r;
}

int sbj_parse_point(sbj_ctx *c, const json_t *v, const sb_domain *d, double xi[2], double st[2])
{
    int r = sbj_vec_value(c, v, 2, xi);
    if (r) return r;
    if (sb_domain_unmap(d, xi, st) != 0) {
        int in_notch = 0;
        if (d->kind == SB_DOMAIN_L_SHAPE) {
            double s = (xi[0] - d->origin[0]) / d->size[0], t = (xi[1] - d->origin[1]) / d->size[1];
            in_notch = s >= 0 && s <= 1 && t >= 0 && t <= 1;
        }
        return sbj_fail(c, NULL, 0, "point (%g, %g) lies outside the domain%s", xi[0], xi[1],
                        in_notch ? " (inside the removed notch)" : "");
    }
    return SB_OK;
}

static int parse_edges(sbj_ctx *c, const json_t *on, const sb_domain *d, sb_part *parts, int *n)
{
    static const char *const kind_name[] = { "rectangle", "l_shape", "annulus_sector" };
    int r = SB_OK;
    size_t mark = sbj_push(c, "on"), i;
    json_t *e;
    json_array_foreach(on, i, e) {
        char tok[32];
        snprintf(tok, sizeof tok, "%zu", i);
        if (!json_is_string(e)) { r = sbj_fail(c, tok, 0, "must be a part name (string), got %s", sbj_type_name(e)); break; }
        const char *name = json_string_value(e);
        if (*n >= SB_SCENE_MAX_PARTS) { r = sbj_fail(c, tok, 0, "too many parts (at most %d)", SB_SCENE_MAX_PARTS); break; }
        if (sb_domain_edge_part(d, name, &parts[*n]) != SB_OK) {
            char list[200];
            size_t k = 0;
            const char *const *names = sb_domain_part_names(d->kind);
            list[0] = '\0';
            for (int j = 0; names[j]; j++)
                k += (size_t)snprintf(list + k, sizeof list - k, "%s%s", j ? ", " : "", names[j]);
            r = sbj_fail(c, tok, 0, "unknown part \"%.40s\" for a %s domain (expected one of: %s)", name,
                         kind_name[d->kind], list);
            break;
        }
        for (int j = 0; j < *n; j++)
            if (parts[j].kind == SB_PART_EDGE && strcmp(parts[j].name, name) == 0) {
                r = sbj_fail(c, tok, 0, "part \"%s\" is listed twice", name);
                break;
            }
        if (r) break;
        (*n)++;
    }
    sbj_pop(c, mark);
    return r;
}

static int parse_points(sbj_ctx *c, const json_t *at, const sb_domain *d, sb_part *parts, int *n)
{
    /* "at": [x, y] (one point) or [[x, y], ...] */
    int single = json_is_array(at) && json_array_size(at) > 0 && json_is_number(json_array_get(at, 0));
    size_t count = single ? 1 : json_array_size(at), mark = sbj_push(c, "at");
    int r = SB_OK;
    for (size_t i = 0; i < count && !r; i++) {
        size_t m2 = single ? 0 : sbj_push_index(c, i);
        if (*n >= SB_SCENE_MAX_PARTS) {
            r = sbj_fail(c, NULL, 0, "too many parts (at most %d)", SB_SCENE_MAX_PARTS);
        } else {
            sb_part *p = &parts[*n];
            memset(p, 0, sizeof *p);
            p->kind = SB_PART_POINT;
            r = sbj_parse_point(c, single ? at : json_array_get(at, i), d, p->xi, p->st);
            if (!r) {
                snprintf(p->name, sizeof p->name, "point_%d", *n);
                (*n)++;
            }
        }
        if (!single) sbj_pop(c, m2);
    }
    sbj_pop(c, mark);
    return r;
}

int sbj_parse_parts(sbj_ctx *c, const json_t *obj, const sb_domain *d, int edges_ok, int points_ok,
                    sb_part *parts, int *n_parts)
{
    json_t *on = NULL, *at = NULL;
    int r;
    *n_parts = 0;
    if (edges_ok && (r = sbj_get_array(c, obj, "on", 0, 1, &on))) return r;
    if (points_ok && (r = sbj_get_array(c, obj, "at", 0, 1, &at))) return r;
    if (!on && !at) {
        if (edges_ok && points_ok)
            return sbj_fail(c, NULL, 0, "missing required key \"on\" (edge names) or \"at\" (material points)");
        return sbj_fail(c, NULL, 0, "missing required key \"%s\"", edges_ok ? "on" : "at");
    }
    if (on && (r = parse_edges(c, on, d, parts, n_parts))) return r;
    if (at && (r = parse_points(c, at, d, parts, n_parts))) return r;
    return SB_OK;
}
