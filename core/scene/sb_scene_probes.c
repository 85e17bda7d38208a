/* sb_scene_probes.c — the "time", "probes" and "reference" sections.
 *
 *   "time": {"mode": "quasi_static", "steps": n}
 *         | {"mode": "dynamic", "dt": s, "steps": n, "rayleigh": {"alpha": 1/s, "beta": s}}
 *   "probes": [{"name": "tip", "at": [xi1, xi2], "on": edge (optional: the lip of a slit),
 *               "expected": {"component": "x"|"y"|"z"|"norm"|"vector",
 *                            "value": m (or [ux, uy, uz] for "vector"),
 *                            "tol": relative}}]
 *             ("expected" may also be an array of such objects, one per component)
 *   "reference": {"type": "none"|"probes"|"file", "file": path, "note": text}
 *
 * Expected values are displacements (x - X) at the final step. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "sb_scene_json.h"
#include "sb_geometry.h"

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

static const char *const check_components[] = { "x", "y", "z", "norm", "vector", NULL };

/* One {"component", "value", "tol"} object into check k of p. */
static int parse_check(sbj_ctx *c, const json_t *e, sb_probe *p, int k)
{
    static const char *const keys[] = { "component", "value", "tol", NULL };
    sb_probe_check *ck = &p->checks[k];
    int comp = 0, r;
    if (!json_is_object(e)) return sbj_fail(c, NULL, 0, "must be an object, got %s", sbj_type_name(e));
    if ((r = sbj_check_keys(c, e, keys)) || (r = sbj_get_choice(c, e, "component", 1, check_components, &comp)))
        return r;
    ck->component = comp == 4 ? -1 : comp;
    for (int j = 0; j < k; j++)
        if (p->checks[j].component == ck->component)
            return sbj_fail(c, "component", 0, "component \"%s\" is expected twice for this probe (also check %d)",
                            check_components[comp], j);
    if (comp == 4) {
        if ((r = sbj_get_vec(c, e, "value", 1, 3, ck->value, NULL))) return r;
        if (ck->value[0] == 0 && ck->value[1] == 0 && ck->value[2] == 0)
            return sbj_fail(c, "value", 0, "a relative tolerance needs a non-zero expected vector");
    } else {
        if ((r = sbj_get_number(c, e, "value", 1, &ck->value[0], NULL))) return r;
        if (comp == 3 && (r = sbj_require_nonneg(c, "value", ck->value[0]))) return r;
        if (ck->value[0] == 0)
            return sbj_fail(c, "value", 0, "a relative tolerance needs a non-zero expected value "
                            "(expect the vector, or another component)");
    }
    if ((r = sbj_get_number(c, e, "tol", 1, &ck->tol, NULL))) return r;
    if (!(ck->tol > 0 && ck->tol <= 1))
        return sbj_fail(c, "tol", 0, "relative tolerance must be in (0, 1], got %g", ck->tol);
    return SB_OK;
}

/* "expected": one check object, or an array of 1..SB_PROBE_MAX_CHECKS of them
 * (several components of one probe) */
static int parse_expected(sbj_ctx *c, const json_t *o, sb_probe *p)
{
    json_t *e = json_object_get(o, "expected");
    if (!e) return SB_OK;
    size_t mark = sbj_push(c, "expected");
    int r = SB_OK;
    if (json_is_array(e)) {
        size_t n = json_array_size(e);
        if (n < 1 || n > SB_PROBE_MAX_CHECKS)
            r = sbj_fail(c, NULL, 0, "must hold 1 to %d expected values, got %zu", SB_PROBE_MAX_CHECKS, n);
        for (size_t k = 0; k < n && !r; k++) {
            size_t m2 = sbj_push_index(c, k);
            r = parse_check(c, json_array_get(e, k), p, (int)k);
            sbj_pop(c, m2);
            if (!r) p->n_checks = (int)k + 1;
        }
    } else if (json_is_object(e)) {
        r = parse_check(c, e, p, 0);
        if (!r) p->n_checks = 1;
    } else {
        r = sbj_fail(c, NULL, 0, "must be an object or an array of objects, got %s", sbj_type_name(e));
    }
    if (!r) {
        const sb_probe_check *first = &p->checks[0];
        p->has_expected = 1;
        p->expected_component = first->component;
        for (int k = 0; k < 3; k++) p->expected[k] = first->value[k];
        p->tol = first->tol;
    }
    sbj_pop(c, mark);
    return r;
}

/* ---- a probe on a slit's lips (docs/scene_format.md "probes") --------- */

/* Whether a boundary condition (other than free) or a load names an edge
 * of the seam in direction dir (s = 0 / 1 when dir = 0, t = 0 / 1 when
 * dir = 1): then a method keeps the seam open (a slit, the rule of
 * bhem_detect_periodic and core/mesh's merge_coincident). */
static int seam_named(const sb_scene *sc, int dir)
{
    for (int b = 0; b < sc->n_bcs; b++)
        for (int k = 0; k < sc->bcs[b].n_parts && sc->bcs[b].kind != SB_BC_FREE; k++) {
            const sb_part *q = &sc->bcs[b].parts[k];
            if (q->kind == SB_PART_EDGE && q->st0[dir] == q->st1[dir] && (q->st0[dir] == 0.0 || q->st0[dir] == 1.0))
                return 1;
        }
    for (int l = 0; l < sc->n_loads; l++)
        for (int k = 0; k < sc->loads[l].n_parts; k++) {
            const sb_part *q = &sc->loads[l].parts[k];
            if (q->kind == SB_PART_EDGE && q->st0[dir] == q->st1[dir] && (q->st0[dir] == 0.0 || q->st0[dir] == 1.0))
                return 1;
        }
    return 0;
}

static double dist3p(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Whether the chart closes the surface across the seam in direction dir:
 * the two edges map onto the same curve (33 points compared, within 1e-9
 * of the tangents' size, as bhem_detect_periodic does). */
static int seam_closes(const sb_scene *sc, int dir)
{
    enum { NS = 33 };
    double scale = 0;
    sb_jet3 A, B;
    for (int k = 0; k < NS; k++) {
        const double u = (double)k / (NS - 1);
        sb_geometry_eval_st(sc, dir == 0 ? 0.5 : u, dir == 0 ? u : 0.5, &A);
        scale = fmax(scale, sqrt(A.d1[0] * A.d1[0] + A.d1[1] * A.d1[1] + A.d1[2] * A.d1[2]) +
                                sqrt(A.d2[0] * A.d2[0] + A.d2[1] * A.d2[1] + A.d2[2] * A.d2[2]));
    }
    if (!(scale > 0) || !isfinite(scale)) return 0;
    for (int k = 0; k < NS; k++) {
        const double u = (double)k / (NS - 1);
        if (dir == 0) {
            sb_geometry_eval_st(sc, 0.0, u, &A);
            sb_geometry_eval_st(sc, 1.0, u, &B);
        } else {
            sb_geometry_eval_st(sc, u, 0.0, &A);
            sb_geometry_eval_st(sc, u, 1.0, &B);
        }
        if (dist3p(A.x, B.x) > 1e-9 * scale) return 0;
    }
    return 1;
}

/* A probe point on a slit lies on two lips (the coincident edges of a
 * closed surface's seam kept open by a condition), which move apart: it is
 * ambiguous unless "on" names its lip.  "on" (an edge name of the domain)
 * must name an edge the point lies on; on a slit, the named lip's side is
 * taken (st moved across the seam).  A point where the seam collapses (the
 * centre of a disc, merged by every method) is not ambiguous. */
static int resolve_probe_lip(sbj_ctx *c, const json_t *o, const sb_scene *sc, sb_probe *p)
{
    json_t *on = json_object_get(o, "on");
    const sb_domain *d = &sc->domain;
    sb_part part;
    int have_on = on != NULL;
    if (have_on) {
        if (!json_is_string(on))
            return sbj_fail(c, "on", 0, "must be an edge name (string), got %s", sbj_type_name(on));
        if (sb_domain_edge_part(d, json_string_value(on), &part) != SB_OK) {
            char list[200];
            size_t k = 0;
            const char *const *names = sb_domain_part_names(d->kind);
            list[0] = '\0';
            for (int j = 0; names[j]; j++)
                k += (size_t)snprintf(list + k, sizeof list - k, "%s%s", j ? ", " : "", names[j]);
            return sbj_fail(c, "on", 0, "unknown edge \"%.40s\" (expected one of: %s)", json_string_value(on), list);
        }
    }
    const double tol = 1e-12;
    for (int dir = 0; dir < 2; dir++) {
        const double u = p->st[dir];
        if (!(fabs(u) <= tol || fabs(u - 1) <= tol)) continue;
        if (!seam_closes(sc, dir)) continue;
        if (!seam_named(sc, dir)) {
            /* a closed seam (merged): both edges are one curve; "on" may name either */
            if (have_on && part.st0[dir] == part.st1[dir] && (part.st0[dir] == 0.0 || part.st0[dir] == 1.0)) {
                p->st[dir] = part.st0[dir];
                return SB_OK;
            }
            continue;
        }
        /* a point where the lips meet (the chart does not move across the
           seam there: all of its other parameter maps to one point, e.g. a
           disc's centre) is merged by every method: not ambiguous */
        sb_jet3 J;
        sb_geometry_eval_st(sc, p->st[0], p->st[1], &J);
        const double *along = dir == 0 ? J.d2 : J.d1, *across = dir == 0 ? J.d1 : J.d2;
        if (sqrt(across[0] * across[0] + across[1] * across[1] + across[2] * across[2]) <=
            1e-9 * sqrt(along[0] * along[0] + along[1] * along[1] + along[2] * along[2]))
            continue;
        const char *const *names = sb_domain_part_names(d->kind);
        char lo[SB_NAME_LEN] = "", hi[SB_NAME_LEN] = "";
        for (int j = 0; names[j]; j++) {
            sb_part q;
            if (sb_domain_edge_part(d, names[j], &q) || q.st0[dir] != q.st1[dir]) continue;
            if (q.st0[dir] == 0.0) snprintf(lo, sizeof lo, "%s", names[j]);
            if (q.st0[dir] == 1.0) snprintf(hi, sizeof hi, "%s", names[j]);
        }
        if (!have_on)
            return sbj_fail(c, "at", 0,
                            "probe \"%s\" at (%g, %g) lies on both lips of a slit: edges \"%s\" and \"%s\" of "
                            "the closed surface coincide there, but a condition or load names one of them, so "
                            "they are kept apart and move apart; say which lip the probe reads with \"on\": "
                            "\"%s\" or \"on\": \"%s\"", p->name, p->xi[0], p->xi[1], lo, hi, lo, hi);
        if (part.st0[dir] == part.st1[dir] && (part.st0[dir] == 0.0 || part.st0[dir] == 1.0)) {
            p->st[dir] = part.st0[dir];   /* the named lip's side of the seam */
            return SB_OK;
        }
    }
    if (have_on && !sb_part_contains_st(&part, p->st[0], p->st[1], 1e-9))
        return sbj_fail(c, "on", 0, "probe \"%s\" at (%g, %g) does not lie on edge \"%s\"", p->name, p->xi[0],
                        p->xi[1], part.name);
    return SB_OK;
}

static int parse_probe(sbj_ctx *c, const json_t *o, const sb_scene *sc, sb_probe *p)
{
    static const char *const keys[] = { "name", "at", "on", "expected", NULL };
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
    if ((r = resolve_probe_lip(c, o, sc, p))) return r;
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
        /* not beside the scene (a copied scene, one read from a pipe): a
         * relative path may also name a file of the project, e.g. the
         * bundled scenes' "results/references/NAME.h5" (docs/scene_format.md) */
        struct stat fst;
        char proj[sizeof ref->file];
        if (!r && file[0] != '/' && stat(ref->file, &fst) != 0 && sb_project_file(file, proj, sizeof proj) == SB_OK)
            snprintf(ref->file, sizeof ref->file, "%s", proj);
    }
out:
    sbj_pop(c, mark);
    return r;
}
