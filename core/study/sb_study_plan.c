/* sb_study_plan.c — a study's runs: scenes x methods x solvers x variants x
 * resolutions (x starts on scenes with several solutions), each with its
 * record path and parameters.  "dofs" targets become, per scene, method and
 * level count, the resolution whose dof count is nearest in ratio; the
 * counts come from setting the method up (sb_study_dofs.c), never from a
 * formula, so every registered method is sized the same way. */
#include "sb_study_parse.h"
#include "sb_study_int.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sb_plan_free(sb_plan *plan)
{
    free(plan->runs);
    memset(plan, 0, sizeof *plan);
}

static sb_plan_run *plan_push(sb_plan *p)
{
    if (p->n == p->cap) {
        int nc = p->cap ? 2 * p->cap : 64;
        sb_plan_run *nr = realloc(p->runs, (size_t)nc * sizeof *nr);
        if (!nr) return NULL;
        p->runs = nr;
        p->cap = nc;
    }
    sb_plan_run *r = &p->runs[p->n++];
    memset(r, 0, sizeof *r);
    return r;
}

int sb_study_n_variants(const sb_study *st)
{
    int n = 1;
    for (int q = 0; q < st->n_vary; q++) n *= st->n_values[q];
    return n;
}

/* value index of varied parameter q in variant v */
static int variant_value(const sb_study *st, int v, int q)
{
    for (int k = st->n_vary - 1; k > q; k--) v /= st->n_values[k];
    return v % st->n_values[q];
}

void sb_plan_config_label(const sb_study *st, const sb_plan_run *r, char *buf, size_t len)
{
    const sb_study_solver *so = &st->solvers[r->solver];
    size_t u = (size_t)snprintf(buf, len, "%s/%s%s%s", st->methods[r->method].name, so->name, so->linear[0] ? "+" : "",
                                so->linear);
    if (so->levels > 1 && u < len) u += (size_t)snprintf(buf + u, len - u, " L%d", so->levels);
    for (int q = 0; q < st->n_vary && u < len; q++) {
        const char *k = strchr(st->vary_key[q], '.');
        u += (size_t)snprintf(buf + u, len - u, " %s=%s", k ? k + 1 : st->vary_key[q], st->vary_value[q][variant_value(st, r->variant, q)]);
    }
}

void sb_plan_refused_path(const char *out, char *buf, size_t len)
{
    snprintf(buf, len, "%s.refused", out);
}

/* file-name safe copy: [A-Za-z0-9.-] kept, anything else '_' */
static void safe_name(const char *s, char *out, size_t len)
{
    size_t i = 0;
    for (; *s && i + 1 < len; s++) out[i++] = (isalnum((unsigned char)*s) || *s == '.' || *s == '-') ? *s : '_';
    out[i] = 0;
}

static int add_sets(sb_plan_run *r, const sb_study_sets *s)
{
    const int cap = (int)(sizeof r->sets / sizeof r->sets[0]);
    for (int i = 0; i < s->n; i++) {
        if (r->n_sets >= cap) return -1;
        snprintf(r->sets[r->n_sets++], SB_STUDY_SET_LEN, "%s", s->kv[i]);
    }
    return 0;
}

int sb_plan_finish_run(const sb_study *st, sb_plan_run *r, char *err, size_t errlen)
{
    const sb_study_scene *sc = &st->scenes[r->scene];
    const sb_study_solver *so = &st->solvers[r->solver];
    char vpart[256] = "", spart[64] = "", dpart[64] = "", lpart[16] = "", linpart[2 * SB_NAME_LEN] = "";
    for (int q = 0; q < st->n_vary; q++) {
        char kv[2 * SB_NAME_LEN], safe[2 * SB_NAME_LEN];
        const char *k = strchr(st->vary_key[q], '.');
        snprintf(kv, sizeof kv, "%s%s", k ? k + 1 : st->vary_key[q], st->vary_value[q][variant_value(st, r->variant, q)]);
        safe_name(kv, safe, sizeof safe);
        snprintf(vpart + strlen(vpart), sizeof vpart - strlen(vpart), "-%s", safe);
    }
    if (r->start > 0) snprintf(spart, sizeof spart, "-s%ld", sc->seeds[r->start - 1]);
    if (r->dt > 0) snprintf(dpart, sizeof dpart, "-dt%.6g", r->dt);
    if (so->levels > 1) snprintf(lpart, sizeof lpart, "-l%d", so->levels);
    if (so->linear[0]) {
        char safe[SB_NAME_LEN];
        safe_name(so->linear, safe, sizeof safe);
        snprintf(linpart, sizeof linpart, "+%s", safe);   /* METHOD-lsnewton+pcg-mg-l2-r8.h5 */
    }
    if (snprintf(r->out, sizeof r->out, "%s/%s/%s-%s%s%s%s-r%d%s%s.h5", st->records, sc->name, st->methods[r->method].name,
                 so->name, linpart, lpart, vpart, r->res, spart, dpart) >= (int)sizeof r->out) {
        snprintf(err, errlen, "record path too long under %s", st->records);
        return SB_ERR_INPUT;
    }
    /* parameters: the study's, the method's, the solver's, the variant's,
     * the matching rules' (later ones win), then the start's */
    r->n_sets = 0;
    int bad = add_sets(r, &st->sets) || add_sets(r, &st->methods[r->method].sets) || add_sets(r, &so->sets);
    for (int q = 0; q < st->n_vary && !bad; q++) {
        sb_study_sets one = { 1, { "" } };
        snprintf(one.kv[0], SB_STUDY_SET_LEN, "%s=%s", st->vary_key[q], st->vary_value[q][variant_value(st, r->variant, q)]);
        bad = add_sets(r, &one);
    }
    for (int k = 0; k < st->n_rules && !bad; k++)
        if (sb_study_rule_matches(st, k, r->scene, r->method, r->solver)) bad = add_sets(r, &st->rules[k].sets);
    if (!bad && r->start > 0) {
        sb_study_sets two = { 2, { "", "" } };
        snprintf(two.kv[0], SB_STUDY_SET_LEN, "run.perturb=%.17g", sc->perturb);
        snprintf(two.kv[1], SB_STUDY_SET_LEN, "run.seed=%ld", sc->seeds[r->start - 1]);
        bad = add_sets(r, &two);
    }
    if (bad) {
        snprintf(err, errlen, "too many parameter assignments for one run of %s", sc->name);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

/* The resolutions of (scene i, method m, solver s): the last matching
 * rule's, else the study's; dofs targets become resolutions. */
static int resolutions(const sb_study *st, sb_dofs_cache *cache, int i, int m, int s, int *res, long *dofs, int *n,
                       char *refused, size_t rlen, char *err, size_t errlen)
{
    const long *list = st->n_res ? st->res : st->dofs;
    int nl = st->n_res ? st->n_res : st->n_dofs, by_dofs = st->n_dofs > 0;
    for (int k = 0; k < st->n_rules; k++)
        if (sb_study_rule_matches(st, k, i, m, s) && (st->rules[k].n_res || st->rules[k].n_dofs)) {
            by_dofs = st->rules[k].n_dofs > 0;
            list = by_dofs ? st->rules[k].dofs : st->rules[k].res;
            nl = by_dofs ? st->rules[k].n_dofs : st->rules[k].n_res;
        }
    *n = 0;
    refused[0] = 0;
    for (int k = 0; k < nl; k++) {
        int r = 0;
        long d = 0;
        char why[512] = "";
        /* a dofs target: the resolution the method's solvers share when the
         * one valid for the most levels any of them uses is within a factor
         * 1.5 of the target (solvers compare at equal dofs); else each level
         * count its own, a multilevel one only within a factor 2 */
        int rc;
        if (by_dofs) {
            int L = 1, rl = 0;
            long dl = 0;
            char w2[512];
            for (int q = 0; q < st->n_solvers; q++)
                if (sb_study_applicable(st, m, q, NULL, 0) && st->solvers[q].levels > L) L = st->solvers[q].levels;
            int rcl = L > 1 ? sb_study_res_for_dofs(st, cache, i, m, L, list[k], &rl, &dl, w2, sizeof w2) : 1;
            if (rcl < 0) {
                snprintf(err, errlen, "%s", w2);
                return rcl;
            }
            if (rcl == 0 && fabs(log((double)dl / (double)list[k])) <= log(1.5)) {
                rc = 0, r = rl, d = dl;
            } else {
                const int lv = st->solvers[s].levels;
                rc = sb_study_res_for_dofs(st, cache, i, m, lv, list[k], &r, &d, why, sizeof why);
                if (rc == 0 && lv > 1 && fabs(log((double)d / (double)list[k])) > log(2.0)) {
                    snprintf(why, sizeof why, "method %s on scene %s: no resolution within a factor 2 of %ld dofs allows "
                             "%d levels (nearest: res %d, %ld dofs)", st->methods[m].name, st->scenes[i].name, list[k], lv, r, d);
                    rc = 1;
                }
            }
        } else {
            rc = sb_study_dofs_at(st, cache, i, m, st->solvers[s].levels, (int)list[k], &d, why, sizeof why);
        }
        if (!by_dofs) r = (int)list[k];
        if (rc < 0) {
            snprintf(err, errlen, "%s", why);
            return rc;
        }
        if (rc > 0) {          /* refused: kept as the reason */
            if (!refused[0]) snprintf(refused, rlen, "%s", why);
            if (by_dofs) continue;
            d = 0;
        }
        int dup = 0;
        for (int q = 0; q < *n; q++) dup |= res[q] == r;
        if (dup) continue;
        res[*n] = rc > 0 ? -r : r;   /* negative: refused at this resolution */
        dofs[*n] = d;
        (*n)++;
    }
    return SB_OK;
}

static int rule_skip(const sb_study *st, int i, int m, int s, const char **why)
{
    for (int k = 0; k < st->n_rules; k++)
        if (st->rules[k].skip[0] && sb_study_rule_matches(st, k, i, m, s)) {
            *why = st->rules[k].skip;
            return 1;
        }
    return 0;
}

int sb_study_plan(const sb_study *st, sb_plan *plan, char *err, size_t errlen)
{
    memset(plan, 0, sizeof *plan);
    plan->n_variants = sb_study_n_variants(st);
    sb_dofs_cache cache;
    sb_dofs_cache_init(&cache);
    int rc = SB_OK;
    for (int i = 0; i < st->n_scenes && !rc; i++)
        for (int m = 0; m < st->n_methods && !rc; m++)
            for (int s = 0; s < st->n_solvers && !rc; s++)
                for (int v = 0; v < plan->n_variants && !rc; v++) {
                    char why[512] = "";
                    const char *skip = NULL;
                    sb_plan_state state = SB_PLAN_RUN;
                    int res[SB_STUDY_MAX_RES], n = 0;
                    long dofs[SB_STUDY_MAX_RES];
                    if (rule_skip(st, i, m, s, &skip)) {
                        state = SB_PLAN_SKIP;
                        snprintf(why, sizeof why, "%s", skip);
                    } else if (!sb_study_applicable(st, m, s, why, sizeof why)) {
                        state = SB_PLAN_NOT_APPLICABLE;
                    } else {
                        char refused[512];
                        rc = resolutions(st, &cache, i, m, s, res, dofs, &n, refused, sizeof refused, err, errlen);
                        if (rc) break;
                        if (n == 0) {
                            state = SB_PLAN_REFUSED;
                            snprintf(why, sizeof why, "%s", refused);
                        }
                    }
                    if (state != SB_PLAN_RUN) {   /* one entry says why the configuration has no runs */
                        sb_plan_run *r = plan_push(plan);
                        if (!r) { rc = SB_ERR_NOMEM; break; }
                        r->scene = i, r->method = m, r->solver = s, r->variant = v, r->state = state;
                        r->levels = st->solvers[s].levels;
                        snprintf(r->why, sizeof r->why, "%s", why);
                        continue;
                    }
                    const sb_study_scene *sc = &st->scenes[i];
                    int starts = 1 + sc->n_seeds;   /* the unperturbed start and one per seed */
                    if (st->kind == SB_STUDY_DT_STABILITY) starts = 1;
                    for (int k = 0; k < n && !rc; k++)
                        for (int t = 0; t < starts && !rc; t++) {
                            sb_plan_run *r = plan_push(plan);
                            if (!r) { rc = SB_ERR_NOMEM; break; }
                            r->scene = i, r->method = m, r->solver = s, r->variant = v, r->start = t;
                            r->res = abs(res[k]);
                            r->levels = st->solvers[s].levels;
                            r->dofs = dofs[k];
                            if (res[k] < 0) {
                                r->state = SB_PLAN_REFUSED;
                                sb_study_dofs_at(st, &cache, i, m, r->levels, r->res, &r->dofs, r->why, sizeof r->why);
                            }
                            rc = sb_plan_finish_run(st, r, err, errlen);
                        }
                }
    sb_dofs_cache_free(&cache);
    /* sizing set methods up at every size (1.2 GB at 1e6 dofs): give the
     * freed pages back before runs are forked from this process */
    sb_release_free_memory();
    if (rc) {
        if (rc == SB_ERR_NOMEM) snprintf(err, errlen, "out of memory planning the study");
        sb_plan_free(plan);
    }
    return rc;
}
