/* sb_study_check.c — the study file's rules and the checks that need the
 * whole file: every parameter assignment is tried against the parameter
 * tables of every (method, solver) pair it reaches, and combinations that
 * can never run are refused, all before any run (docs/study.md). */
#include "sb_study_parse.h"

#include <stdio.h>
#include <string.h>

int sb_study_applicable(const sb_study *st, int m, int s, char *why, size_t len)
{
    const sb_method_type *mt = st->methods[m].type;
    const sb_study_solver *so = &st->solvers[s];
    const char *w = NULL;
    if ((so->type->flags & SB_SOLVER_NEEDS_HIERARCHY) && !(mt->flags & SB_METHOD_HIERARCHY))
        w = "needs a level hierarchy (prolongation, restriction, projection), which the method does not provide";
    else if (so->levels > 1 && !(mt->flags & SB_METHOD_HIERARCHY))
        w = "runs on several levels, and the method has no hierarchy";
    else if (!(mt->flags & SB_METHOD_POTENTIAL) && !(so->type->flags & SB_SOLVER_SINGLE_STEP))
        w = "needs an energy potential, and the method's forces are not one";
    if (w && why) snprintf(why, len, "solver %s %s (method %s)", so->name, w, mt->name);
    return w == NULL;
}

int sb_study_rule_matches(const sb_study *st, int k, int i, int m, int s)
{
    const sb_study_rule *r = &st->rules[k];
    if (r->scene >= 0 && i >= 0 && r->scene != i) return 0;
    if (r->method >= 0 && m >= 0 && r->method != m) return 0;
    if (r->solver >= 0 && s >= 0 && st->solvers[r->solver].type != st->solvers[s].type) return 0;
    if (r->levels > 0 && s >= 0 && st->solvers[s].levels != r->levels) return 0;
    return 1;
}

/* index of the entry named `name` in the study's scenes / methods / solvers */
static int scene_index(const sb_study *st, const char *name)
{
    for (int i = 0; i < st->n_scenes; i++) if (!strcmp(st->scenes[i].name, name) || !strcmp(st->scenes[i].arg, name)) return i;
    return -1;
}
static int method_index(const sb_study *st, const char *name)
{
    for (int i = 0; i < st->n_methods; i++) if (!strcmp(st->methods[i].name, name)) return i;
    return -1;
}
static int solver_index(const sb_study *st, const char *name)
{
    for (int i = 0; i < st->n_solvers; i++) if (!strcmp(st->solvers[i].name, name)) return i;
    return -1;
}

static int parse_rule(sbj_ctx *c, const json_t *o, sb_study *st)
{
    static const char *const keys[] = { "scene", "method", "solver", "levels", "set", "res", "dofs", "skip", NULL };
    static const char *const pre[] = { "run.", "solver.", "method.", NULL };
    sb_study_rule *r = &st->rules[st->n_rules];
    memset(r, 0, sizeof *r);
    r->scene = r->method = r->solver = -1;
    char name[512];
    int has, rc;
    if (!json_is_object(o)) return sbj_fail(c, NULL, 0, "a rule must be an object, got %s", sbj_type_name(o));
    if ((rc = sbj_check_keys(c, o, keys))) return rc;
    if ((rc = sbj_get_string(c, o, "scene", 0, name, sizeof name, &has))) return rc;
    if (has && (r->scene = scene_index(st, name)) < 0) return sbj_fail(c, "scene", 0, "scene \"%s\" is not in this study", name);
    if ((rc = sbj_get_string(c, o, "method", 0, name, sizeof name, &has))) return rc;
    if (has && (r->method = method_index(st, name)) < 0) return sbj_fail(c, "method", 0, "method \"%s\" is not in this study", name);
    if ((rc = sbj_get_string(c, o, "solver", 0, name, sizeof name, &has))) return rc;
    if (has && (r->solver = solver_index(st, name)) < 0) return sbj_fail(c, "solver", 0, "solver \"%s\" is not in this study", name);
    if ((rc = sbj_get_int(c, o, "levels", 0, 1, SB_MAX_LEVELS, &r->levels))) return rc;
    if (r->levels > 0) {
        int any = 0;
        for (int s = 0; s < st->n_solvers; s++)
            any |= st->solvers[s].levels == r->levels && (r->solver < 0 || st->solvers[s].type == st->solvers[r->solver].type);
        if (!any) return sbj_fail(c, "levels", 0, "no solver of this study runs on %ld levels", r->levels);
    }
    if ((rc = sbs_parse_sets(c, o, "set", pre, &r->sets))) return rc;
    if ((rc = sbs_parse_longs(c, o, "res", 1, 4096, SB_STUDY_MAX_RES, r->res, &r->n_res))) return rc;
    if ((rc = sbs_parse_longs(c, o, "dofs", 1, 100000000L, SB_STUDY_MAX_RES, r->dofs, &r->n_dofs))) return rc;
    if (r->n_res && r->n_dofs) return sbj_fail(c, "dofs", 1, "give \"res\" or \"dofs\", not both");
    if ((rc = sbj_get_string(c, o, "skip", 0, r->skip, sizeof r->skip, &has))) return rc;
    if (has && !r->skip[0]) return sbj_fail(c, "skip", 0, "say why the runs are skipped");
    if (has && (r->sets.n || r->n_res || r->n_dofs)) return sbj_fail(c, "skip", 1, "a rule that skips runs sets nothing else");
    if (!has && !r->sets.n && !r->n_res && !r->n_dofs) return sbj_fail(c, NULL, 0, "the rule does nothing (give \"set\", \"res\", \"dofs\" or \"skip\")");
    if (r->method >= 0 && r->solver >= 0) {
        char why[512];
        for (int s = 0; s < st->n_solvers; s++)
            if (st->solvers[s].type == st->solvers[r->solver].type && !sb_study_applicable(st, r->method, s, why, sizeof why))
                return sbj_fail(c, "solver", 0, "impossible combination: %s", why);
    }
    st->n_rules++;
    return SB_OK;
}

int sbs_parse_rules(sbj_ctx *c, const json_t *root, sb_study *st)
{
    json_t *a, *v;
    int r = sbj_get_array(c, root, "rules", 0, 0, &a);
    if (r || !a) return r;
    if (json_array_size(a) > SB_STUDY_MAX_RULES) return sbj_fail(c, "rules", 0, "at most %d rules", SB_STUDY_MAX_RULES);
    size_t mark = sbj_push(c, "rules"), i;
    json_array_foreach(a, i, v) {
        size_t m2 = sbj_push_index(c, i);
        r = parse_rule(c, v, st);
        sbj_pop(c, m2);
        if (r) break;
    }
    sbj_pop(c, mark);
    return r;
}

/* Try the assignments of `sets` (found at pointer c->ptr + "/set") on the
 * parameter tables of method m and solver s. */
static int try_sets(sbj_ctx *c, const sb_study *st, const sb_study_sets *sets, int m, int s, const char *member)
{
    for (int i = 0; i < sets->n; i++) {
        sb_paramset ps;
        char msg[512];
        sb_paramset_init(&ps);
        sb_paramset_add(&ps, "run", sb_solve_params);
        sb_paramset_add(&ps, "solver", st->solvers[s].type->params);
        sb_paramset_add(&ps, "method", st->methods[m].type->params);
        if (sb_paramset_set(&ps, sets->kv[i], msg, sizeof msg)) {
            char key[SB_NAME_LEN];
            snprintf(key, sizeof key, "%.*s", (int)strcspn(sets->kv[i], "="), sets->kv[i]);
            size_t mark = member ? sbj_push(c, member) : strlen(c->ptr);
            int r = sbj_fail(c, key, 0, "%s (with method %s and solver %s)", msg, st->methods[m].name, st->solvers[s].name);
            sbj_pop(c, mark);
            return r;
        }
    }
    return SB_OK;
}

/* The sets at c->ptr/member against every applicable (method, solver) pair
 * with method in [m0, m1) and solver in [s0, s1). */
static int check_sets(sbj_ctx *c, const sb_study *st, const sb_study_sets *sets, const char *member,
                      int m0, int m1, int s0, int s1)
{
    for (int m = m0; m < m1; m++)
        for (int s = s0; s < s1; s++) {
            if (!sb_study_applicable(st, m, s, NULL, 0)) continue;
            int r = try_sets(c, st, sets, m, s, member);
            if (r) return r;
        }
    return SB_OK;
}

int sbs_check(sbj_ctx *c, const json_t *root, sb_study *st)
{
    char why[512];
    int r;
    /* every method runs with some solver, every solver with some method */
    for (int m = 0; m < st->n_methods; m++) {
        int any = 0;
        for (int s = 0; s < st->n_solvers; s++) any |= sb_study_applicable(st, m, s, why, sizeof why);
        if (!any) {
            size_t mark = sbj_push(c, "methods");
            if (json_is_array(json_object_get(root, "methods"))) sbj_push_index(c, (size_t)m);
            r = sbj_fail(c, NULL, 0, "impossible combination: no solver of the study can run method %s (%s)", st->methods[m].name, why);
            sbj_pop(c, mark);
            return r;
        }
    }
    for (int s = 0; s < st->n_solvers; s++) {
        int any = 0;
        for (int m = 0; m < st->n_methods; m++) any |= sb_study_applicable(st, m, s, why, sizeof why);
        if (!any) {
            size_t mark = sbj_push(c, "solvers");
            if (json_is_array(json_object_get(root, "solvers"))) sbj_push_index(c, (size_t)s);
            r = sbj_fail(c, NULL, 0, "impossible combination: no method of the study can be run by solver %s (%s)", st->solvers[s].name, why);
            sbj_pop(c, mark);
            return r;
        }
    }
    /* parameters: where each set can take effect */
    if ((r = check_sets(c, st, &st->sets, "set", 0, st->n_methods, 0, st->n_solvers))) return r;
    if (json_is_array(json_object_get(root, "methods")))
        for (int m = 0; m < st->n_methods; m++) {
            size_t mark = sbj_push(c, "methods");
            sbj_push_index(c, (size_t)m);
            r = check_sets(c, st, &st->methods[m].sets, "set", m, m + 1, 0, st->n_solvers);
            sbj_pop(c, mark);
            if (r) return r;
        }
    if (json_is_array(json_object_get(root, "solvers")))
        for (int s = 0; s < st->n_solvers; s++) {
            size_t mark = sbj_push(c, "solvers");
            sbj_push_index(c, (size_t)s);
            r = check_sets(c, st, &st->solvers[s].sets, "set", 0, st->n_methods, s, s + 1);
            sbj_pop(c, mark);
            if (r) return r;
        }
    for (int q = 0; q < st->n_vary; q++)
        for (int v = 0; v < st->n_values[q]; v++) {
            sb_study_sets one = { 1, { "" } };
            snprintf(one.kv[0], SB_STUDY_SET_LEN, "%s=%s", st->vary_key[q], st->vary_value[q][v]);
            size_t mark = sbj_push(c, "vary");
            r = check_sets(c, st, &one, NULL, 0, st->n_methods, 0, st->n_solvers);
            sbj_pop(c, mark);
            if (r) return r;
        }
    for (int k = 0; k < st->n_rules; k++) {
        const sb_study_rule *ru = &st->rules[k];
        size_t mark = sbj_push(c, "rules");
        sbj_push_index(c, (size_t)k);
        r = SB_OK;
        for (int m = 0; m < st->n_methods && !r; m++)
            for (int s = 0; s < st->n_solvers && !r; s++)
                if (sb_study_rule_matches(st, k, -1, m, s) && sb_study_applicable(st, m, s, NULL, 0))
                    r = try_sets(c, st, &ru->sets, m, s, "set");
        sbj_pop(c, mark);
        if (r) return r;
    }
    if (st->kind == SB_STUDY_DT_STABILITY) {
        for (int i = 0; i < st->n_scenes; i++)
            if (st->scenes[i].scene->time.mode != SB_TIME_DYNAMIC) {
                size_t mark = sbj_push(c, "scenes");
                sbj_push_index(c, (size_t)i);
                r = sbj_fail(c, NULL, 0, "a dt study needs dynamic scenes; %s is quasi-static", st->scenes[i].name);
                sbj_pop(c, mark);
                return r;
            }
        if (st->n_vary) return sbj_fail(c, "vary", 1, "a dt study varies dt only");
    }
    return SB_OK;
}
