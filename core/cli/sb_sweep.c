/* sb_sweep.c — planning and validating a sweep before its first run
 * (sb_sweep.h). */
#include "sb_sweep.h"
#include "sb_context.h"
#include "sb_memory.h"
#include "sb_output.h"
#include "sb_run.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define FAIL(...) do { snprintf(err, errlen, __VA_ARGS__); goto fail; } while (0)

/* The directory exists and is writable, or can be made (sb_output.h). */
static int check_dir(const char *dir, char *err, size_t errlen)
{
    char msg[1800];
    if (sb_output_check_dir(dir, "records", msg, sizeof msg) == SB_OK) return SB_OK;
    snprintf(err, errlen, "sweep: %s", msg);
    return SB_ERR_INPUT;
}

/* One (method, solver, levels) with its parameters; SB_OK, SB_ERR_UNSUPPORTED
 * (left out), or an error. */
static int check_pair(const sb_method_type *mt, const sb_solver_type *st, int levels, const sb_sweep_axes *ax,
                      sb_context *ctx, char *err, size_t errlen)
{
    int rc = sb_run_combination_check(mt, st, levels, err, errlen);
    if (rc) return rc;
    sb_paramset_init(&ctx->params);
    rc = sb_run_paramset(&ctx->params, mt, st, ax->n_sets, ax->sets, err, errlen);
    return rc ? SB_ERR_INPUT : SB_OK;
}

static void note_left_out(sb_sweep_plan *plan, const char *why)
{
    size_t u = strlen(plan->left_out);
    if (strstr(plan->left_out, why)) return;   /* the same combination for another scene or resolution */
    plan->n_left_out++;
    if (u + strlen(why) + 3 < sizeof plan->left_out)
        snprintf(plan->left_out + u, sizeof plan->left_out - u, "%s%s", u ? "; " : "", why);
}

int sb_sweep_validate(const sb_sweep_axes *ax, sb_sweep_plan *plan, char *err, size_t errlen)
{
    memset(plan, 0, sizeof *plan);
    sb_scene *scenes = NULL;
    int n_loaded = 0, have_ctx = 0;
    sb_context ctx;
    char e1[256], msg[1400];
    if (ax->n_scenes <= 0) FAIL("sweep: no scene given (--scenes A,B)");
    if (ax->n_methods <= 0) FAIL("sweep: no method given (--methods M,N)");
    if (ax->n_solvers <= 0) FAIL("sweep: no solver given (--solvers S,T)");
    if (ax->n_res <= 0) FAIL("sweep: no resolution given (--res N,M)");
    if (ax->n_levels <= 0) FAIL("sweep: no level count given (--levels L,M)");
    for (int i = 0; i < ax->n_methods; i++)
        if (!sb_method_find(ax->methods[i]))
            FAIL("sweep: unknown method \"%s\" (see `shellbench list methods`)", sb_escape_copy(ax->methods[i], e1, sizeof e1));
    for (int i = 0; i < ax->n_solvers; i++)
        if (!sb_solver_find(ax->solvers[i]))
            FAIL("sweep: unknown solver \"%s\" (see `shellbench list solvers`)", sb_escape_copy(ax->solvers[i], e1, sizeof e1));
    for (int i = 0; i < ax->n_res; i++)
        if (ax->res[i] < 0 || ax->res[i] > SB_SCENE_MAX_RESOLUTION)
            FAIL("sweep: resolution %d is out of range: 1 to %d elements per side (0: the scene's own)", ax->res[i],
                 SB_SCENE_MAX_RESOLUTION);
    for (int i = 0; i < ax->n_levels; i++)
        if (ax->levels[i] < 1 || ax->levels[i] > SB_MAX_LEVELS)
            FAIL("sweep: level count %d is out of range: 1 to %d", ax->levels[i], SB_MAX_LEVELS);
    const char *dir = ax->dir && *ax->dir ? ax->dir : "results/sweep";
    if (check_dir(dir, err, errlen)) goto fail;

    /* every scene parses (a path writes its records by the scene's name) */
    scenes = calloc((size_t)ax->n_scenes, sizeof *scenes);
    if (!scenes) FAIL("sweep: out of memory");
    for (int i = 0; i < ax->n_scenes; i++, n_loaded++) {
        char path[1024];
        if (sb_scene_resolve(ax->scenes[i], path, sizeof path))
            FAIL("sweep: scene \"%s\" not found (neither a file nor a name in bench/scenes; try `shellbench list "
                 "scenes`)", sb_escape_copy(ax->scenes[i], e1, sizeof e1));
        if (sb_scene_load(path, &scenes[i], msg, sizeof msg)) FAIL("sweep: %s", msg);
    }

    size_t cap = (size_t)ax->n_scenes * ax->n_methods * ax->n_solvers * ax->n_res * ax->n_levels;
    if (cap > 100000) FAIL("sweep: %zu runs are more than this command plans at once (100000)", cap);
    plan->items = calloc(cap, sizeof *plan->items);
    if (!plan->items || sb_context_init(&ctx)) FAIL("sweep: out of memory");
    have_ctx = 1;
    for (int a = 0; a < ax->n_scenes; a++)
        for (int b = 0; b < ax->n_methods; b++)
            for (int d = 0; d < ax->n_solvers; d++)
                for (int e = 0; e < ax->n_res; e++)
                    for (int f = 0; f < ax->n_levels; f++) {
                        const sb_method_type *mt = sb_method_find(ax->methods[b]);
                        const sb_solver_type *st = sb_solver_find(ax->solvers[d]);
                        const sb_scene *sc = &scenes[a];
                        int levels = ax->levels[f], rc = check_pair(mt, st, levels, ax, &ctx, msg, sizeof msg);
                        if (!rc) rc = sb_run_scene_method_check(sc, mt, msg, sizeof msg);
                        int res = ax->res[e], res_t_unused;
                        if (res <= 0) sb_scene_bundled_res(sc, mt->name, &res, &res_t_unused);
                        if (rc == SB_ERR_UNSUPPORTED) {
                            char why[2100];
                            snprintf(why, sizeof why, "%s/%s l%d: %s", mt->name, st->name, levels, msg);
                            note_left_out(plan, why);
                            continue;
                        }
                        if (rc) FAIL("sweep: %s with method %s and solver %s: %s", sc->name, mt->name, st->name, msg);
                        /* sizes: resolution, divisibility, memory (the method's estimate) */
                        sb_method_config cfg = { res, levels, &ctx.params, &ctx, 0 };
                        sb_memory_run mr = { sc->time.mode == SB_TIME_DYNAMIC, sc->time.steps, sc->n_probes,
                                             ax->sample_n > 0 ? ax->sample_n : 21,
                                             (st->flags & SB_SOLVER_NEEDS_HIERARCHY) != 0, SB_SUPERNODES_CHOLMOD, 0, 0 };
                        char what[300];
                        double bytes;
                        snprintf(what, sizeof what, "sweep: method %s on scene %s at --res %d with %d level%s", mt->name,
                                 sc->name, res, levels, levels > 1 ? "s" : "");
                        if (sb_memory_check_method(mt, sc, &cfg, &mr, sb_param(&ctx.params, "run.max_memory") * 1e9,
                                                   what, &bytes, err, errlen))
                            goto fail;
                        sb_sweep_item *it = &plan->items[plan->n];
                        it->scene = ax->scenes[a];
                        snprintf(it->scene_name, sizeof it->scene_name, "%s", sc->name);
                        it->method = mt->name;
                        it->solver = st->name;
                        it->res = res;
                        it->levels = levels;
                        if (snprintf(it->out, sizeof it->out, "%s/%s-%s-%s-r%d-l%d.h5", dir, sc->name, mt->name,
                                     st->name, res, levels) >= (int)sizeof it->out)
                            FAIL("sweep: output path in %s too long", dir);
                        for (int k = 0; k < plan->n; k++)
                            if (strcmp(plan->items[k].out, it->out) == 0)
                                FAIL("sweep: two runs would write the same record %s (scenes \"%s\" and \"%s\" are both "
                                     "named %s, or a resolution is listed twice)", it->out,
                                     plan->items[k].scene, it->scene, sc->name);
                        sb_output_kind kind;
                        if (sb_output_check(it->out, "record", &kind, msg, sizeof msg) || kind == SB_OUTPUT_DISCARD)
                            FAIL("sweep: %s", kind == SB_OUTPUT_DISCARD ? "a record path is the null device" : msg);
                        if (sb_output_check_lockfile(it->out, msg, sizeof msg)) FAIL("sweep: %s", msg);
                        plan->n++;
                    }
    if (plan->n == 0) FAIL("sweep: no run is possible: %s", plan->left_out);
    sb_context_free(&ctx);
    for (int i = 0; i < n_loaded; i++) sb_scene_free(&scenes[i]);
    free(scenes);
    return SB_OK;
fail:
    if (have_ctx) sb_context_free(&ctx);
    for (int i = 0; i < n_loaded; i++) sb_scene_free(&scenes[i]);
    free(scenes);
    sb_sweep_plan_free(plan);
    sb_escape_controls(err, errlen);
    return SB_ERR_INPUT;
}

void sb_sweep_plan_free(sb_sweep_plan *plan)
{
    free(plan->items);
    memset(plan, 0, sizeof *plan);
}
