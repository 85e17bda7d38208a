/* bench_rmtr_setup.h — the set-up the rmtr method's benches share
 * (bench_cond.c, bench_mgstrip.c): a scene by name or path, and a context
 * holding the run's, a solver's and the rmtr method's parameter tables. */
#ifndef BENCH_RMTR_SETUP_H
#define BENCH_RMTR_SETUP_H

#include "sb_context.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <stdio.h>

/* 0, or 2 with a message naming the tool, the scene and why */
static int bench_load_scene(const char *tool, const char *name, sb_scene *sc)
{
    char path[1024], err[2048] = "";
    if (sb_scene_resolve(name, path, sizeof path)) {
        fprintf(stderr, "%s: no bundled scene or scene file named %s\n", tool, name);
        return 2;
    }
    if (sb_scene_load(path, sc, err, sizeof err)) {
        fprintf(stderr, "%s: cannot load scene %s: %s\n", tool, name, err);
        return 2;
    }
    return 0;
}

static void bench_add_params(sb_context *ctx, const sb_method_type *mt, const sb_solver_type *st)
{
    sb_paramset_add(&ctx->params, "run", sb_solve_params);
    sb_paramset_add(&ctx->params, "solver", st->params);
    sb_paramset_add(&ctx->params, "method", mt->params);
}

#endif
