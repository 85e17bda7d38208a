/* sb_study_json.c — the study file (docs/study.md "Study files"): parsed
 * with the scene parser's context (sb_scene_json.h), so that every error
 * reads "FILE:LINE:COL: at /json/pointer: what is wrong", and validated
 * completely before anything runs: names, parameter keys and values against
 * the tables of every method and solver they reach, and combinations that
 * cannot run.  The sections are parsed here, the cross-checks in
 * sb_study_check.c. */
#include "sb_output.h"
#include "sb_study_parse.h"
#include "sb_krylov.h"   /* sb_linear_names */

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_FILE_BYTES (4u << 20)

/* "set": {"key": number | string, ...} into "key=value" assignments; keys
 * must start with one of the allowed prefixes ("run.", "solver.", "method.") */
int sbs_parse_sets(sbj_ctx *c, const json_t *obj, const char *key, const char *const *prefixes,
                   sb_study_sets *out)
{
    json_t *o;
    int r = sbj_get_object(c, obj, key, 0, &o);
    if (r || !o) return r;
    size_t mark = sbj_push(c, key);
    const char *k;
    json_t *v;
    json_object_foreach(o, k, v) {
        int ok = 0;
        for (const char *const *p = prefixes; *p; p++) ok |= strncmp(k, *p, strlen(*p)) == 0;
        if (!ok) {
            char list[128] = "";
            for (const char *const *p = prefixes; *p; p++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s\"%s*\"", p == prefixes ? "" : ", ", *p);
            r = sbj_fail(c, k, 1, "parameter \"%.80s\" cannot be set here (allowed: %s)", k, list);
            break;
        }
        if (out->n >= SB_STUDY_MAX_SETS) { r = sbj_fail(c, k, 1, "too many parameters (at most %d)", SB_STUDY_MAX_SETS); break; }
        char val[256];
        if (json_is_number(v)) snprintf(val, sizeof val, "%.15g", json_number_value(v));
        else if (json_is_string(v) && json_string_length(v) < 200) snprintf(val, sizeof val, "%s", json_string_value(v));
        else { r = sbj_fail(c, k, 0, "must be a number or a choice name, got %s", sbj_type_name(v)); break; }
        if (strlen(k) >= SB_NAME_LEN) { r = sbj_fail(c, k, 1, "parameter name too long"); break; }
        snprintf(out->kv[out->n++], SB_STUDY_SET_LEN, "%s=%s", k, val);
    }
    sbj_pop(c, mark);
    return r;
}

/* Array `key` of positive integers, strictly increasing, at most max. */
int sbs_parse_longs(sbj_ctx *c, const json_t *obj, const char *key, long lo, long hi, int max, long *out, int *n)
{
    json_t *a, *v;
    int r = sbj_get_array(c, obj, key, 0, 1, &a);
    *n = 0;
    if (r || !a) return r;
    if (json_array_size(a) > (size_t)max) return sbj_fail(c, key, 0, "at most %d entries, got %zu", max, json_array_size(a));
    size_t mark = sbj_push(c, key), i;
    json_array_foreach(a, i, v) {
        char tok[32];
        snprintf(tok, sizeof tok, "%zu", i);
        double x = json_is_number(v) ? json_number_value(v) : NAN;
        if (!json_is_number(v) || x != floor(x) || x < (double)lo || x > (double)hi) {
            r = sbj_fail(c, tok, 0, "must be an integer in [%ld, %ld], got %s", lo, hi,
                         json_is_number(v) ? "a number outside or a fraction" : sbj_type_name(v));
            break;
        }
        out[i] = (long)x;
        if (i > 0 && out[i] <= out[i - 1]) { r = sbj_fail(c, tok, 0, "must be larger than the entry before (increasing)"); break; }
        (*n)++;
    }
    sbj_pop(c, mark);
    return r;
}

static int parse_targets(sbj_ctx *c, const json_t *root, sb_study *st)
{
    json_t *a, *v;
    int r = sbj_get_array(c, root, "targets", 0, 1, &a);
    if (r) return r;
    if (!a) {   /* the error targets */
        st->n_targets = 2;
        st->targets[0] = 1e-2;
        st->targets[1] = 1e-3;
        return SB_OK;
    }
    if (json_array_size(a) > SB_STUDY_MAX_TARGETS)
        return sbj_fail(c, "targets", 0, "at most %d error targets", SB_STUDY_MAX_TARGETS);
    size_t mark = sbj_push(c, "targets"), i;
    json_array_foreach(a, i, v) {
        char tok[32];
        snprintf(tok, sizeof tok, "%zu", i);
        double x = json_is_number(v) ? json_number_value(v) : NAN;
        if (!(x > 0 && x < 1)) { r = sbj_fail(c, tok, 0, "an error target must be a number in (0, 1)"); break; }
        if (i > 0 && !(x < st->targets[i - 1])) { r = sbj_fail(c, tok, 0, "targets must decrease (coarse to fine)"); break; }
        st->targets[st->n_targets++] = x;
    }
    sbj_pop(c, mark);
    return r;
}

static int parse_scene(sbj_ctx *c, const json_t *o, sb_study *st, size_t idx)
{
    static const char *const keys[] = { "scene", "solution", "error", "reference", "starts", NULL };
    static const char *const sol[] = { "unique", "multiple", NULL };
    static const char *const errk[] = { "probe", "field_rms", "field_max", NULL };
    static const char *const kstarts[] = { "perturb", "seeds", NULL };
    sb_study_scene *s = &st->scenes[idx];
    char msg[2048];
    int r;
    json_t *so;
    if (json_is_string(o)) {   /* "trampoline" = {"scene": "trampoline"} */
        json_t *wrap = json_pack("{sO}", "scene", o);
        r = wrap ? parse_scene(c, wrap, st, idx) : SB_ERR_NOMEM;
        json_decref(wrap);
        return r;
    }
    if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "a scene entry must be a name or an object, got %s", sbj_type_name(o));
    if ((r = sbj_check_keys(c, o, keys))) return r;
    if ((r = sbj_get_string(c, o, "scene", 1, s->arg, sizeof s->arg, NULL))) return r;
    if (sb_scene_resolve(s->arg, s->path, sizeof s->path))
        return sbj_fail(c, "scene", 0, "scene \"%s\" not found (neither a file nor a name in bench/scenes)", s->arg);
    s->scene = calloc(1, sizeof *s->scene);
    if (!s->scene) return sbj_fail(c, "scene", 0, "out of memory");
    if (sb_scene_load(s->path, s->scene, msg, sizeof msg)) {
        free(s->scene);
        s->scene = NULL;
        return sbj_fail(c, "scene", 0, "the scene file is not valid: %s", msg);
    }
    snprintf(s->name, sizeof s->name, "%s", s->scene->name);
    for (int k = 0; k < (int)idx; k++)
        if (strcmp(st->scenes[k].name, s->name) == 0)
            return sbj_fail(c, "scene", 0, "scene \"%s\" is listed twice (entries %d and %zu)", s->name, k, idx);
    /* the reference: the study's, else the scene's file reference */
    char ref[1024] = "";
    int has_ref = 0;
    if ((r = sbj_get_string(c, o, "reference", 0, ref, sizeof ref, &has_ref))) return r;
    if (has_ref) snprintf(s->reference, sizeof s->reference, "%s", ref);
    else if (s->scene->reference.kind == SB_REF_FILE) snprintf(s->reference, sizeof s->reference, "%s", s->scene->reference.file);
    int n_expected = 0;
    for (int p = 0; p < s->scene->n_probes; p++) n_expected += s->scene->probes[p].has_expected;
    /* what the scene is ranked by: analytic probes where the scene has
     * them, else the field error against the reference record */
    int e = n_expected ? 0 : s->reference[0] ? 1 : 3;
    if ((r = sbj_get_choice(c, o, "error", 0, errk, &e))) return r;
    if (e == 0 && !n_expected) return sbj_fail(c, "error", 0, "scene %s has no probe with an expected value", s->name);
    if ((e == 1 || e == 2) && !s->reference[0])
        return sbj_fail(c, "error", 0, "a field error needs a reference record: give \"reference\" or a scene "
                        "with reference {\"type\": \"file\"} (shellbench reference %s)", s->name);
    s->error = (sb_error_kind)e;
    /* unique or not: analytic references are for unique solutions; for the
     * rest the study must say (a wrong default would rank methods by their
     * distance to one arbitrary local minimum) */
    int sk = -1;
    if ((r = sbj_get_choice(c, o, "solution", 0, sol, &sk))) return r;
    if (sk < 0) {
        if (!n_expected)
            return sbj_fail(c, NULL, 0, "scene %s has no analytic reference: say \"solution\": \"unique\" or "
                            "\"multiple\" (nonconvex scenes are not ranked by distance to one local minimum)", s->name);
        sk = 0;
    }
    s->solution = (sb_solution_kind)sk;
    if (s->solution == SB_SOLUTION_UNIQUE && s->error == SB_ERRKIND_NONE)
        return sbj_fail(c, NULL, 0, "scene %s is \"unique\" but has nothing to measure the error against: give "
                        "\"reference\" (shellbench reference %s) or make it \"multiple\"", s->name, s->name);
    if ((r = sbj_get_object(c, o, "starts", 0, &so))) return r;
    if (so) {
        size_t mark = sbj_push(c, "starts");
        if (!(r = sbj_check_keys(c, so, kstarts)) && !(r = sbj_get_number(c, so, "perturb", 1, &s->perturb, NULL)) &&
            !(r = sbj_require_positive(c, "perturb", s->perturb)))
            r = sbs_parse_longs(c, so, "seeds", 0, 2147483647L, SB_STUDY_MAX_SEEDS, s->seeds, &s->n_seeds);
        if (!r && s->n_seeds == 0) r = sbj_fail(c, NULL, 0, "missing required key \"seeds\"");
        sbj_pop(c, mark);
        if (r) return r;
    }
    return SB_OK;
}

static int parse_method(sbj_ctx *c, const json_t *o, sb_study *st, const char *name)
{
    static const char *const keys[] = { "method", "set", NULL };
    static const char *const pre[] = { "method.", NULL };
    if (st->n_methods >= SB_STUDY_MAX_METHODS) return sbj_fail(c, NULL, 0, "too many methods (at most %d)", SB_STUDY_MAX_METHODS);
    sb_study_method *m = &st->methods[st->n_methods];
    memset(m, 0, sizeof *m);
    int r;
    if (o) {
        if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "a method entry must be a name or an object, got %s", sbj_type_name(o));
        if ((r = sbj_check_keys(c, o, keys)) || (r = sbj_get_string(c, o, "method", 1, m->name, sizeof m->name, NULL))) return r;
    } else {
        snprintf(m->name, sizeof m->name, "%s", name);
    }
    m->type = sb_method_find(m->name);
    if (!m->type) return sbj_fail(c, o ? "method" : NULL, 0, "unknown method \"%s\" (see `shellbench list methods`)", m->name);
    for (int k = 0; k < st->n_methods; k++)
        if (st->methods[k].type == m->type) return sbj_fail(c, o ? "method" : NULL, 0, "method \"%s\" is listed twice", m->name);
    if (o && (r = sbs_parse_sets(c, o, "set", pre, &m->sets))) return r;
    st->n_methods++;
    return SB_OK;
}

static int parse_methods(sbj_ctx *c, const json_t *root, sb_study *st)
{
    json_t *a = json_object_get(root, "methods"), *v;
    if (!a) return sbj_fail(c, NULL, 0, "missing required key \"methods\"");
    size_t mark = sbj_push(c, "methods"), i;
    int r = SB_OK;
    if (json_is_string(a) && strcmp(json_string_value(a), "all") == 0) {
        /* every registered discretization (not the test fixtures) */
        for (int k = 0; k < sb_method_count() && !r; k++)
            if (!(sb_method_at(k)->flags & SB_METHOD_TEST_FIXTURE)) r = parse_method(c, NULL, st, sb_method_at(k)->name);
        if (!r && st->n_methods == 0) r = sbj_fail(c, NULL, 0, "\"all\": no discretization is registered");
    } else if (!json_is_array(a) || json_array_size(a) == 0) {
        r = sbj_fail(c, NULL, 0, "must be \"all\" or a non-empty array of method names / objects");
    } else {
        json_array_foreach(a, i, v) {
            size_t m2 = sbj_push_index(c, i);
            if (json_is_string(v) && strcmp(json_string_value(v), "all") == 0)
                r = sbj_fail(c, NULL, 0, "\"all\" stands alone: \"methods\": \"all\"");
            else r = parse_method(c, json_is_string(v) ? NULL : v, st, json_is_string(v) ? json_string_value(v) : "");
            sbj_pop(c, m2);
            if (r) break;
        }
    }
    sbj_pop(c, mark);
    return r;
}

static int parse_solver(sbj_ctx *c, const json_t *o, sb_study *st, const char *name)
{
    static const char *const keys[] = { "solver", "levels", "linear", "set", NULL };
    static const char *const pre[] = { "solver.", "run.", NULL };
    if (st->n_solvers >= SB_STUDY_MAX_SOLVERS) return sbj_fail(c, NULL, 0, "too many solvers (at most %d)", SB_STUDY_MAX_SOLVERS);
    sb_study_solver *s = &st->solvers[st->n_solvers];
    memset(s, 0, sizeof *s);
    long levels = 0;
    int r;
    if (o) {
        if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "a solver entry must be a name or an object, got %s", sbj_type_name(o));
        if ((r = sbj_check_keys(c, o, keys)) || (r = sbj_get_string(c, o, "solver", 1, s->name, sizeof s->name, NULL))) return r;
        if ((r = sbj_get_int(c, o, "levels", 0, 1, SB_MAX_LEVELS, &levels))) return r;
        if ((r = sbj_get_string(c, o, "linear", 0, s->linear, sizeof s->linear, NULL))) return r;
        if (s->linear[0]) {
            int known = 0;
            for (int k = 0; sb_linear_names[k]; k++) known |= !strcmp(sb_linear_names[k], s->linear);
            if (!known) return sbj_fail(c, "linear", 0, "unknown linear solver \"%s\" (cholmod, pcg-jacobi, pcg-mg, pcg-amg)", s->linear);
        }
    } else {
        snprintf(s->name, sizeof s->name, "%s", name);
    }
    s->type = sb_solver_find(s->name);
    if (!s->type) return sbj_fail(c, o ? "solver" : NULL, 0, "unknown solver \"%s\" (see `shellbench list solvers`)", s->name);
    int hier = (s->type->flags & SB_SOLVER_NEEDS_HIERARCHY) != 0;
    if (levels == 0) levels = hier ? 2 : 1;
    if (hier && levels < 2) return sbj_fail(c, "levels", 0, "solver %s needs at least 2 levels", s->name);
    s->levels = (int)levels;
    for (int k = 0; k < st->n_solvers; k++)
        if (st->solvers[k].type == s->type && st->solvers[k].levels == s->levels && !strcmp(st->solvers[k].linear, s->linear))
            return sbj_fail(c, o ? "solver" : NULL, 0, "solver \"%s\" with %d level%s%s%s is listed twice", s->name, s->levels,
                            s->levels > 1 ? "s" : "", s->linear[0] ? " and linear solver " : "", s->linear);
    if (o && (r = sbs_parse_sets(c, o, "set", pre, &s->sets))) return r;
    if (s->linear[0]) {
        for (int k = 0; k < s->sets.n; k++)
            if (!strncmp(s->sets.kv[k], "solver.linear=", 14))
                return sbj_fail(c, "linear", 0, "given twice: as \"linear\" and in \"set\" (keep \"linear\")");
        if (s->sets.n >= SB_STUDY_MAX_SETS) return sbj_fail(c, "linear", 0, "too many parameters for one solver entry");
        char kv[SB_STUDY_SET_LEN];
        snprintf(kv, sizeof kv, "solver.linear=%s", s->linear);
        memcpy(s->sets.kv[s->sets.n++], kv, sizeof kv);
    }
    st->n_solvers++;
    return SB_OK;
}

static int parse_solvers(sbj_ctx *c, const json_t *root, sb_study *st)
{
    json_t *a = json_object_get(root, "solvers"), *v;
    if (!a) return sbj_fail(c, NULL, 0, "missing required key \"solvers\"");
    size_t mark = sbj_push(c, "solvers"), i;
    int r = SB_OK;
    if (json_is_string(a) && strcmp(json_string_value(a), "all") == 0) {
        for (int k = 0; k < sb_solver_count() && !r; k++) r = parse_solver(c, NULL, st, sb_solver_at(k)->name);
    } else if (!json_is_array(a) || json_array_size(a) == 0) {
        r = sbj_fail(c, NULL, 0, "must be \"all\" or a non-empty array of solver names / objects");
    } else {
        json_array_foreach(a, i, v) {
            size_t m2 = sbj_push_index(c, i);
            r = parse_solver(c, json_is_string(v) ? NULL : v, st, json_is_string(v) ? json_string_value(v) : "");
            sbj_pop(c, m2);
            if (r) break;
        }
    }
    sbj_pop(c, mark);
    return r;
}

static int parse_vary(sbj_ctx *c, const json_t *root, sb_study *st)
{
    static const char *const pre[] = { "run.", "solver.", "method.", NULL };
    json_t *o;
    int r = sbj_get_object(c, root, "vary", 0, &o);
    if (r || !o) return r;
    size_t mark = sbj_push(c, "vary");
    const char *k;
    json_t *a;
    json_object_foreach(o, k, a) {
        int ok = 0;
        for (const char *const *p = pre; *p; p++) ok |= strncmp(k, *p, strlen(*p)) == 0;
        if (!ok || strlen(k) >= SB_NAME_LEN) { r = sbj_fail(c, k, 1, "\"%.80s\" is no parameter key (run.*, solver.*, method.*)", k); break; }
        if (st->n_vary >= SB_STUDY_MAX_VARY) { r = sbj_fail(c, k, 1, "at most %d varied parameters", SB_STUDY_MAX_VARY); break; }
        if (!json_is_array(a) || json_array_size(a) < 1 || json_array_size(a) > SB_STUDY_MAX_VALUES) {
            r = sbj_fail(c, k, 0, "must be an array of 1 to %d values", SB_STUDY_MAX_VALUES);
            break;
        }
        int q = st->n_vary++;
        snprintf(st->vary_key[q], SB_NAME_LEN, "%s", k);
        size_t i;
        json_t *v;
        size_t m2 = sbj_push(c, k);
        json_array_foreach(a, i, v) {
            char tok[32];
            snprintf(tok, sizeof tok, "%zu", i);
            if (json_is_number(v)) snprintf(st->vary_value[q][i], SB_NAME_LEN, "%.15g", json_number_value(v));
            else if (json_is_string(v) && json_string_length(v) < SB_NAME_LEN) snprintf(st->vary_value[q][i], SB_NAME_LEN, "%s", json_string_value(v));
            else { r = sbj_fail(c, tok, 0, "must be a number or a choice name"); break; }
            for (size_t j = 0; j < i; j++)
                if (!strcmp(st->vary_value[q][j], st->vary_value[q][i])) { r = sbj_fail(c, tok, 0, "value listed twice"); break; }
            if (r) break;
            st->n_values[q]++;
        }
        sbj_pop(c, m2);
        if (r) break;
    }
    sbj_pop(c, mark);
    return r;
}

static int parse_dt(sbj_ctx *c, const json_t *root, sb_study *st)
{
    static const char *const keys[] = { "max", "min", "descent", "bisections", "steps", "max_iter", NULL };
    json_t *o;
    int r = sbj_get_object(c, root, "dt", st->kind == SB_STUDY_DT_STABILITY, &o);
    if (r) return r;
    if (o && st->kind != SB_STUDY_DT_STABILITY) return sbj_fail(c, "dt", 1, "\"dt\" belongs to a study of kind \"dt_stability\"");
    if (!o) return SB_OK;
    sb_study_dt *d = &st->dt;
    long b = 6, steps = 5, mi = 1000;
    int has_descent = 0;
    d->dt_max = 1.0;
    d->dt_min = 1e-3;
    d->descent = 0;
    size_t mark = sbj_push(c, "dt");
    if (!(r = sbj_check_keys(c, o, keys)) && !(r = sbj_get_number(c, o, "max", 0, &d->dt_max, NULL)) &&
        !(r = sbj_require_positive(c, "max", d->dt_max)) && !(r = sbj_get_number(c, o, "min", 0, &d->dt_min, NULL)) &&
        !(r = sbj_require_positive(c, "min", d->dt_min)) && !(r = sbj_get_int(c, o, "bisections", 0, 0, 30, &b)) &&
        !(r = sbj_get_int(c, o, "steps", 0, 1, 100000, &steps)) && !(r = sbj_get_int(c, o, "max_iter", 0, 1, 100000000, &mi))) {
        if (!(d->dt_min < d->dt_max)) r = sbj_fail(c, "min", 0, "must be smaller than max = %g", d->dt_max);
        else if (!(r = sbj_get_number(c, o, "descent", 0, &d->descent, &has_descent)) && has_descent &&
                 !(d->descent > 1.5)) r = sbj_fail(c, "descent", 0, "must be a factor above 1.5 (each failing probe below "
                                                   "the cap divides dt by it until dt = min)");
    }
    if (!r && !(d->descent > 0)) d->descent = d->dt_max / d->dt_min;
    sbj_pop(c, mark);
    d->bisections = (int)b;
    d->steps = (int)steps;
    d->max_iter = (int)mi;
    return r;
}

static int parse_root(sbj_ctx *c, const json_t *root, sb_study *st, const char *records_override)
{
    static const char *const keys[] = { "study", "description", "kind", "records", "samples", "targets", "scenes",
                                        "methods", "solvers", "res", "dofs", "set", "vary", "rules", "dt", NULL };
    static const char *const kinds[] = { "accuracy", "dt_stability", NULL };
    static const char *const pre_all[] = { "run.", "solver.", "method.", NULL };
    int r, kind = 0;
    long samples = 21;
    json_t *a, *v;
    if ((r = sbj_check_keys(c, root, keys))) return r;
    if ((r = sbj_get_string(c, root, "study", 1, st->name, sizeof st->name, NULL))) return r;
    if (!sbj_valid_name(st->name)) return sbj_fail(c, "study", 0, "must be 1..%d characters from [A-Za-z0-9_.-]", SB_NAME_LEN - 1);
    if ((r = sbj_get_string(c, root, "description", 0, st->description, sizeof st->description, NULL))) return r;
    if ((r = sbj_get_choice(c, root, "kind", 0, kinds, &kind))) return r;
    st->kind = (sb_study_kind)kind;
    snprintf(st->records, sizeof st->records, "results/studies/%s", st->name);
    if ((r = sbj_get_string(c, root, "records", 0, st->records, sizeof st->records, NULL))) return r;
    if (records_override) snprintf(st->records, sizeof st->records, "%s", records_override);
    if (!st->records[0]) return sbj_fail(c, "records", 0, "must not be empty");
    if ((r = sbj_get_int(c, root, "samples", 0, 2, 2001, &samples))) return r;
    st->samples = (int)samples;
    if ((r = parse_targets(c, root, st))) return r;
    if ((r = sbj_get_array(c, root, "scenes", 1, 1, &a))) return r;
    if (json_array_size(a) > SB_STUDY_MAX_SCENES) return sbj_fail(c, "scenes", 0, "at most %d scenes", SB_STUDY_MAX_SCENES);
    size_t mark = sbj_push(c, "scenes"), i;
    json_array_foreach(a, i, v) {
        size_t m2 = sbj_push_index(c, i);
        r = parse_scene(c, v, st, i);
        sbj_pop(c, m2);
        st->n_scenes += st->scenes[i].scene != NULL;
        if (r) break;
    }
    sbj_pop(c, mark);
    if (r) return r;
    if ((r = parse_methods(c, root, st)) || (r = parse_solvers(c, root, st))) return r;
    if ((r = sbs_parse_longs(c, root, "res", 1, 4096, SB_STUDY_MAX_RES, st->res, &st->n_res))) return r;
    if ((r = sbs_parse_longs(c, root, "dofs", 1, 100000000L, SB_STUDY_MAX_RES, st->dofs, &st->n_dofs))) return r;
    if (st->n_res && st->n_dofs) return sbj_fail(c, "dofs", 1, "give \"res\" or \"dofs\", not both");
    if (!st->n_res && !st->n_dofs) return sbj_fail(c, NULL, 0, "missing \"dofs\" (targets, per method the nearest resolution) or \"res\"");
    if ((r = sbs_parse_sets(c, root, "set", pre_all, &st->sets))) return r;
    if ((r = parse_vary(c, root, st))) return r;
    if ((r = parse_dt(c, root, st))) return r;
    if ((r = sbs_parse_rules(c, root, st))) return r;
    return sbs_check(c, root, st);
}

int sb_study_parse_string(const char *text, const char *file, const char *records_override, sb_study *st,
                          char *err, size_t errlen)
{
    memset(st, 0, sizeof *st);
    snprintf(st->path, sizeof st->path, "%s", file);
    size_t len = strlen(text);
    sbj_ctx c = { text, len, file, err, errlen, "" };
    json_error_t jerr;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY, &jerr);
    if (!root) {
        snprintf(err, errlen, "%s:%d:%d: at /: invalid JSON: %s", file, jerr.line > 0 ? jerr.line : 1,
                 jerr.column > 0 ? jerr.column : 1, jerr.text);
        return SB_ERR_INPUT;
    }
    int r = json_is_object(root) ? parse_root(&c, root, st, records_override)
                                 : sbj_fail(&c, NULL, 0, "a study must be a JSON object, got %s", sbj_type_name(root));
    json_decref(root);
    if (r) sb_study_free(st);
    return r;
}

int sb_study_load(const char *path, const char *records_override, sb_study *st, char *err, size_t errlen)
{
    memset(st, 0, sizeof *st);
    char why[1200];
    FILE *f = sb_input_open(path, "study file", why, sizeof why);
    if (!f) {
        snprintf(err, errlen, "%s:1:1: at /: %s", path, why);
        return SB_ERR_IO;
    }
    char *buf = malloc(MAX_FILE_BYTES + 1);
    size_t n = buf ? fread(buf, 1, MAX_FILE_BYTES + 1, f) : 0;
    fclose(f);
    if (!buf) { snprintf(err, errlen, "%s:1:1: at /: out of memory", path); return SB_ERR_NOMEM; }
    if (n > MAX_FILE_BYTES || memchr(buf, 0, n)) {
        free(buf);
        snprintf(err, errlen, "%s:1:1: at /: %s", path, n > MAX_FILE_BYTES ? "file too large" : "the file contains a NUL byte");
        return SB_ERR_INPUT;
    }
    buf[n] = 0;
    int r = sb_study_parse_string(buf, path, records_override, st, err, errlen);
    free(buf);
    return r;
}

void sb_study_free(sb_study *st)
{
    if (!st) return;
    for (int i = 0; i < SB_STUDY_MAX_SCENES; i++)
        if (st->scenes[i].scene) {
            sb_scene_free(st->scenes[i].scene);
            free(st->scenes[i].scene);
            st->scenes[i].scene = NULL;
        }
    st->n_scenes = 0;
}
