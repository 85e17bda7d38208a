/* sb_study_dofs.c — how many dofs a method has on a scene at a resolution,
 * found by setting the method up (create, count, destroy; nothing is
 * assembled or solved), and the resolution nearest a dofs target.  Before
 * a method is set up its memory estimate (the `estimate` op, sb_memory.h)
 * is checked against run.max_memory as the study sets it (else the
 * machine's physical memory) and the index limits: a resolution over them
 * is refused with the estimate's sentence and never built, so that
 * `sweep --study --plan` only estimates such runs.
 *
 * Search: two accepted resolutions give a model sqrt(dofs) ~ a res + b
 * (structured methods have dofs ~ (res + c)^2: rmtr 3 (res + 3)^2, bhem
 * 12 (res + 1)^2 on a square); the resolutions around the model's answer
 * are then set up for real and the nearest accepted one in ratio is taken.
 * The model only chooses where to look: the answer is always a measured
 * count. */
#include "sb_study_int.h"
#include "sb_context.h"
#include "sb_memory.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sb_dofs_cache_init(sb_dofs_cache *c) { memset(c, 0, sizeof *c); }

void sb_dofs_cache_free(sb_dofs_cache *c)
{
    free(c->e);
    memset(c, 0, sizeof *c);
}

/* the method.* assignments that reach (scene i, method m): the scene's
 * bundled ones for the method first ("methods": {"M": {"set": ...}}), then
 * the study's, as `run` applies them (sb_run.c: the scene's, then --set),
 * so that sizing measures the discretization the run builds (issue 40: a
 * scene bundling method.adaptive=0 was sized on adaptive_sqrt3's base mesh) */
static int method_sets(const sb_study *st, int i, int m, sb_paramset *ps, char *why, size_t len)
{
    const sb_scene_method *sm = st->scenes[i].scene ? sb_scene_method_find(st->scenes[i].scene, st->methods[m].name) : NULL;
    for (int j = 0; sm && j < sm->n_sets; j++)
        if (strncmp(sm->sets[j], "method.", 7) == 0 && sb_paramset_set(ps, sm->sets[j], why, len)) return SB_ERR_INPUT;
    const sb_study_sets *lists[2 + SB_STUDY_MAX_RULES];
    int nl = 0;
    lists[nl++] = &st->sets;
    lists[nl++] = &st->methods[m].sets;
    for (int k = 0; k < st->n_rules; k++)
        if (sb_study_rule_matches(st, k, i, m, -1)) lists[nl++] = &st->rules[k].sets;
    for (int l = 0; l < nl; l++)
        for (int j = 0; j < lists[l]->n; j++)
            if (strncmp(lists[l]->kv[j], "method.", 7) == 0 && sb_paramset_set(ps, lists[l]->kv[j], why, len))
                return SB_ERR_INPUT;
    return SB_OK;
}

/* run.max_memory (GB) as the study's, the method's and the matching rules'
 * assignments set it (the last wins); 0: the machine's physical memory */
static double memory_limit(const sb_study *st, int i, int m)
{
    const sb_study_sets *lists[2 + SB_STUDY_MAX_RULES];
    int nl = 0;
    double gb = 0;
    lists[nl++] = &st->sets;
    lists[nl++] = &st->methods[m].sets;
    for (int k = 0; k < st->n_rules; k++)
        if (sb_study_rule_matches(st, k, i, m, -1)) lists[nl++] = &st->rules[k].sets;
    for (int l = 0; l < nl; l++)
        for (int j = 0; j < lists[l]->n; j++)
            if (strncmp(lists[l]->kv[j], "run.max_memory=", 15) == 0) gb = atof(lists[l]->kv[j] + 15);
    return gb > 0 ? gb * 1e9 : 0;
}

int sb_study_dofs_at(const sb_study *st, sb_dofs_cache *c, int i, int m, int levels, int res, long *dofs,
                     char *why, size_t len)
{
    for (int k = 0; k < c->n; k++) {
        const sb_dofs_entry *e = &c->e[k];
        if (e->scene == i && e->method == m && e->levels == levels && e->res == res) {
            *dofs = e->dofs;
            snprintf(why, len, "%s", e->why);
            return e->dofs > 0 ? 0 : 1;
        }
    }
    const sb_method_type *mt = st->methods[m].type;
    sb_context ctx;
    if (sb_context_init(&ctx)) {
        snprintf(why, len, "out of memory");
        return SB_ERR_NOMEM;
    }
    int rc = sb_paramset_add(&ctx.params, "method", mt->params);
    if (!rc) rc = method_sets(st, i, m, &ctx.params, why, len);
    if (rc) {
        sb_context_free(&ctx);
        return SB_ERR_INPUT;
    }
    void *ms = calloc(1, mt->state_size);
    long d = 0;
    char msg[1400] = "";
    if (!ms) {
        sb_context_free(&ctx);
        snprintf(why, len, "out of memory");
        return SB_ERR_NOMEM;
    }
    sb_method_config cfg = { res, levels, &ctx.params, &ctx, 0 };
    /* the memory estimate before anything is built (a run too large for the
     * memory limit or for the index limits is refused here, as `run` would
     * refuse it, without setting the method up) */
    const sb_scene *scn = st->scenes[i].scene;
    sb_memory_run mr = { scn->time.mode == SB_TIME_DYNAMIC, scn->time.steps, scn->n_probes, 21, levels > 1, SB_SUPERNODES_CHOLMOD, 0, 0 };
    char what[300];
    double bytes = 0;
    snprintf(what, sizeof what, "method %s on scene %s at res %d with %d level%s", mt->name, st->scenes[i].name, res,
             levels, levels > 1 ? "s" : "");
    int crc = sb_memory_check_method(mt, scn, &cfg, &mr, memory_limit(st, i, m), what, &bytes, msg, sizeof msg);
    const int set_up = crc == SB_OK;
    if (set_up) crc = mt->create(ms, scn, &cfg);
    else crc = SB_ERR_INPUT;   /* refused at this resolution, the estimate's sentence in msg */
    if (crc == SB_OK) d = mt->n_dofs(ms, mt->n_levels(ms) - 1);
    else if (!msg[0]) snprintf(msg, sizeof msg, "method %s on scene %s at res %d with %d level%s: %s", mt->name, st->scenes[i].name, res,
                  levels, levels > 1 ? "s" : "", ctx.err[0] ? ctx.err : "set-up failed");
    if (set_up) mt->destroy(ms);
    free(ms);
    sb_context_free(&ctx);
    if (crc != SB_OK && crc != SB_ERR_INPUT && crc != SB_ERR_UNSUPPORTED) {
        snprintf(why, len, "%s", msg);
        return SB_ERR_INTERNAL;
    }
    if (c->n == c->cap) {
        int nc = c->cap ? 2 * c->cap : 32;
        sb_dofs_entry *ne = realloc(c->e, (size_t)nc * sizeof *ne);
        if (!ne) return SB_ERR_NOMEM;
        c->e = ne;
        c->cap = nc;
    }
    sb_dofs_entry *e = &c->e[c->n++];
    e->scene = i, e->method = m, e->levels = levels, e->res = res, e->dofs = d;
    snprintf(e->why, sizeof e->why, "%s", msg);
    *dofs = d;
    snprintf(why, len, "%s", msg);
    return d > 0 ? 0 : 1;
}

#define RES_MAX 4096

int sb_study_res_for_dofs(const sb_study *st, sb_dofs_cache *c, int i, int m, int levels, long target, int *res,
                          long *dofs, char *why, size_t len)
{
    /* two accepted single-level resolutions for the model */
    int r1 = 0, r2 = 0, rc;
    long d1 = 0, d2 = 0, d;
    char first_no[400] = "";
    for (int r = 2; r <= 64 && !r2; r++) {
        rc = sb_study_dofs_at(st, c, i, m, 1, r, &d, why, len);
        if (rc < 0) return rc;
        if (rc > 0) {
            if (!first_no[0]) snprintf(first_no, sizeof first_no, "%s", why);
            continue;
        }
        if (!r1) r1 = r, d1 = d;
        else if (d > d1) r2 = r, d2 = d;
    }
    if (!r2) {
        snprintf(why, len, "%s", first_no[0] ? first_no : "no resolution up to 64 is accepted");
        return 1;
    }
    double a = (sqrt((double)d2) - sqrt((double)d1)) / (r2 - r1), b = sqrt((double)d1) - a * r1;
    double rs = a > 0 ? (sqrt((double)target) - b) / a : r1;
    int center = (int)lround(rs);
    if (center < 1) center = 1;
    if (center > RES_MAX) center = RES_MAX;
    int best = 0;
    long best_d = 0;
    double best_q = INFINITY;
    /* dofs grow with the resolution: from the model's answer, walk up while
     * the accepted counts stay below the target and down while they stay
     * above it; the nearest in ratio is among the first accepted count on
     * each side of the target.  Each count is a set-up (at 1e6 dofs about
     * a second and 1 GB), so the walk stops at the first crossing instead
     * of setting up every resolution of the window (issue 42: the plan of
     * scaling_large.json took 24 s).  Widen until something is accepted:
     * 3, then 12, then 40 either side. */
    static const int widths[] = { 3, 12, 40 };
    for (int w = 0; w < 3 && !best; w++)
        for (int dir = 1; dir >= -1; dir -= 2) {
            for (int r = dir > 0 ? center : center - 1; dir > 0 ? r <= center + widths[w] : r >= center - widths[w];
                 r += dir) {
                if (r < 1 || r > RES_MAX) continue;
                rc = sb_study_dofs_at(st, c, i, m, levels, r, &d, why, len);
                if (rc < 0) return rc;
                if (rc > 0) continue;
                double q = fabs(log((double)d / (double)target));
                if (q < best_q - 1e-12 || (fabs(q - best_q) <= 1e-12 && r < best)) best_q = q, best = r, best_d = d;
                if (dir > 0 ? d >= target : d <= target) break;   /* crossed: further counts are farther */
            }
        }
    if (!best) {
        snprintf(why, len, "method %s on scene %s: no resolution near %d (%ld dofs) is accepted with %d level%s",
                 st->methods[m].name, st->scenes[i].name, center, target, levels, levels > 1 ? "s" : "");
        return 1;
    }
    *res = best;
    *dofs = best_d;
    why[0] = 0;
    return 0;
}
