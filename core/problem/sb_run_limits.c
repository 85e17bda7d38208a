/* sb_run_limits.c — the sizes a run asks for, checked before any work: the
 * resolution (at most SB_SCENE_MAX_RESOLUTION per side, the scene file's
 * limit too), and the memory the discretization, its matrices, the Cholesky
 * factor and the record will take (sb_memory.h) against run.max_memory or
 * the machine's physical memory.  A method with an estimate op is measured
 * before it is created; one without (the test fixtures) right after
 * create(), from its dof counts, before the problem's matrices exist. */
#include "sb_memory.h"
#include "sb_run_state.h"
#include "sb_linsolve.h"
#include "sb_params.h"

#include <string.h>

/* The resolution the run uses: --res, else the scene's "resolution"; the
 * sample grid's size. */
int sb_run_resolve_res(run_state *R, const sb_run_request *req)
{
    if (req->res < 0 || req->res > SB_SCENE_MAX_RESOLUTION) {
        fprintf(R->err, "shellbench: --res %d is out of range: a resolution is 1 to %d elements per side (0 or "
                        "absent: the scene's own, %d for %s)\n", req->res, SB_SCENE_MAX_RESOLUTION,
                R->scene.default_res, R->scene.name);
        return SB_EXIT_INPUT;
    }
    /* without --res: the resolution the scene bundles this method at ("methods"), else its own */
    int bundled, bundled_t;
    sb_scene_bundled_res(&R->scene, R->mt->name, &bundled, &bundled_t);
    R->res = req->res > 0 ? req->res : bundled;
    /* --res NxM, or the scene's "resolution": [N, M] without --res (a method
     * that takes square resolutions only refuses the first, and gets N x N for
     * the second) */
    if (req->res_t < 0 || req->res_t > SB_SCENE_MAX_RESOLUTION) {
        fprintf(R->err, "shellbench: --res %dx%d is out of range: 1 to %d elements per side\n", req->res, req->res_t,
                SB_SCENE_MAX_RESOLUTION);
        return SB_EXIT_INPUT;
    }
    if (req->res_t > 0 && !(R->mt->flags & SB_METHOD_RES_ST)) {
        fprintf(R->err, "shellbench: --res %dx%d: method %s takes the same number of elements along s and t\n",
                req->res, req->res_t, R->mt->name);
        return SB_EXIT_INPUT;
    }
    R->res_t = req->res_t > 0 ? req->res_t
             : (req->res <= 0 && (R->mt->flags & SB_METHOD_RES_ST)) ? bundled_t : 0;
    if (R->n_grid < 2 || R->n_grid > SB_RUN_MAX_SAMPLES) {
        fprintf(R->err, "shellbench: --samples %d is out of range: the sample grid has 2 to %d points per side\n",
                R->n_grid, SB_RUN_MAX_SAMPLES);
        return SB_EXIT_INPUT;
    }
    return -1;
}

static void run_size(const run_state *R, sb_memory_run *mr)
{
    mr->dynamic = R->scene.time.mode == SB_TIME_DYNAMIC;
    mr->steps = R->scene.time.steps;
    mr->n_probes = R->scene.n_probes;
    mr->sample_n = R->n_grid;
    mr->multilevel = (R->stype->flags & SB_SOLVER_NEEDS_HIERARCHY) != 0;
    mr->supernodes = sb_param_int_or(&R->ctx.params, "run.supernodes", SB_SUPERNODES_CHOLMOD);
    mr->lifts = !(R->stype->flags & SB_SOLVER_SINGLE_STEP) && !(R->mt->flags & SB_METHOD_PENALTY_BCS) &&
                sb_memory_scene_lifts(&R->scene, &R->ctx.params);
    /* solver.linear = pcg-mg: no finest factor (sb_memory.h) */
    const char *lin = sb_param_choice(&R->ctx.params, "solver.linear");
    mr->krylov_mg = lin && !strcmp(lin, "pcg-mg");
}

/* "--res 8" or "--res 8x4096": the resolution as the user gave it */
static void res_text(const run_state *R, char *buf, size_t len)
{
    if (R->res_t > 0 && R->res_t != R->res) snprintf(buf, len, "%dx%d", R->res, R->res_t);
    else snprintf(buf, len, "%d", R->res);
}

static int check(run_state *R, const sb_method_size *sz)
{
    sb_memory_run mr;
    sb_memory_estimate est;
    char what[160], msg[1024];
    run_size(R, &mr);
    sb_memory_estimate_run(sz, &mr, &est);
    R->mem_estimate = est.bytes;
    char rs[32];
    res_text(R, rs, sizeof rs);
    snprintf(what, sizeof what, "method %s on scene %s at --res %s with %d level%s", R->mt->name, R->scene.name,
             rs, sz->levels, sz->levels > 1 ? "s" : "");
    double limit = sb_param(&R->ctx.params, "run.max_memory") * 1e9;
    if (sb_memory_check(sz, &est, limit, what, msg, sizeof msg)) {
        fprintf(R->err, "shellbench: %s\n", msg);
        return SB_EXIT_INPUT;
    }
    return -1;
}

/* Before the method is created: its estimate op. */
int sb_run_check_memory(run_state *R, int levels)
{
    if (!R->mt->estimate) return -1;   /* measured after create (sb_run_check_created) */
    sb_method_config cfg = { R->res, levels, &R->ctx.params, &R->ctx, R->res_t };
    sb_memory_run mr;
    char what[160], msg[1400];
    run_size(R, &mr);
    char rs[32];
    res_text(R, rs, sizeof rs);
    snprintf(what, sizeof what, "method %s on scene %s at --res %s with %d level%s", R->mt->name, R->scene.name,
             rs, levels, levels > 1 ? "s" : "");
    if (sb_memory_check_method(R->mt, &R->scene, &cfg, &mr, sb_param(&R->ctx.params, "run.max_memory") * 1e9, what,
                               &R->mem_estimate, msg, sizeof msg)) {
        fprintf(R->err, "shellbench: %s\n", msg);
        return SB_EXIT_INPUT;
    }
    return -1;
}

/* After create() of a method without an estimate op: its dof counts, with
 * a 3 x 3 node stencil and 4-node elements assumed. */
int sb_run_check_created(run_state *R)
{
    if (R->mt->estimate) return -1;
    sb_method_size sz;
    memset(&sz, 0, sizeof sz);
    sz.levels = R->mt->n_levels(R->ms);
    if (sz.levels < 1 || sz.levels > SB_MAX_LEVELS) return -1;   /* sb_problem_create reports it */
    sz.bs = R->mt->block_size ? R->mt->block_size(R->ms, sz.levels - 1) : 1;
    if (sz.bs < 1) sz.bs = 1;
    sz.nodes_per_element = 4;
    sz.stencil = 9;
    for (int l = 0; l < sz.levels; l++) {
        sz.nodes[l] = (double)R->mt->n_dofs(R->ms, l) / sz.bs;
        sz.elements[l] = sz.nodes[l];
    }
    return check(R, &sz);
}
