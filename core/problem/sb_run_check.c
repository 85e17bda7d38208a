/* sb_run_check.c — whether a method, a solver and a level count fit
 * together, and a run's parameter set: shared by `run` (sb_run.c) and the
 * up-front validation of a sweep (sb_sweep.c), so both refuse the same
 * requests with the same sentences. */
#include "sb_run.h"
#include "sb_obstacle.h"
#include "sb_solver.h"

#include <stdio.h>

int sb_run_combination_check(const sb_method_type *mt, const sb_solver_type *st, int levels, char *err, size_t errlen)
{
    if ((st->flags & SB_SOLVER_NEEDS_HIERARCHY) && mt->adapt) {
        snprintf(err, errlen, "solver %s needs a fixed level hierarchy, but method %s changes its mesh during a run "
                 "(adaptive)", st->name, mt->name);
        return SB_ERR_UNSUPPORTED;
    }
    if ((st->flags & SB_SOLVER_NEEDS_HIERARCHY) && !(mt->flags & SB_METHOD_HIERARCHY)) {
        snprintf(err, errlen, "solver %s needs a level hierarchy (prolongation, restriction, projection), but method %s "
                 "provides none", st->name, mt->name);
        return SB_ERR_UNSUPPORTED;
    }
    if ((st->flags & SB_SOLVER_NEEDS_HIERARCHY) && levels < 2) {
        snprintf(err, errlen, "solver %s needs at least 2 levels, but --levels is %d", st->name, levels);
        return SB_ERR_UNSUPPORTED;
    }
    if (levels > 1 && !(mt->flags & SB_METHOD_HIERARCHY)) {
        snprintf(err, errlen, "--levels %d asks for a hierarchy, but method %s has none", levels, mt->name);
        return SB_ERR_UNSUPPORTED;
    }
    if (levels < 1 || levels > SB_MAX_LEVELS) {
        snprintf(err, errlen, "--levels must be in [1, %d], got %d", SB_MAX_LEVELS, levels);
        return SB_ERR_INPUT;
    }
    if (!(mt->flags & SB_METHOD_POTENTIAL) && !(st->flags & SB_SOLVER_SINGLE_STEP)) {
        snprintf(err, errlen, "method %s has no energy potential (lagged forces); solver %s needs one: use linearized",
                 mt->name, st->name);
        return SB_ERR_UNSUPPORTED;
    }
    return SB_OK;
}

/* What a scene asks of a method that only some methods can honour, refused
 * before any work with a sentence naming the scene key: a moving boundary's
 * "derivative" prescribes nodal first derivatives, which are generalized
 * coordinates of Hermite elements only (BHEM paper §4.2); a triangle or
 * subdivision method has no such coordinate to hold. */
int sb_run_scene_method_check(const sb_scene *sc, const sb_method_type *mt, char *err, size_t errlen)
{
    static const char *const names[] = { "", "s", "t", "st" };
    for (int b = 0; b < sc->n_bcs; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind == SB_BC_MOVING && bc->derivative && !(mt->flags & SB_METHOD_NODAL_DERIVATIVES)) {
            snprintf(err, errlen, "%s: boundary %d asks for \"derivative\": \"%s\" (prescribed nodal first "
                     "derivatives), but method %s has no derivatives among its generalized coordinates; only a "
                     "Hermite method (bhem) can honour this key", sc->path[0] ? sc->path : sc->name, b,
                     names[bc->derivative & 3u], mt->name);
            return SB_ERR_UNSUPPORTED;
        }
    }
    return SB_OK;
}

int sb_run_paramset(sb_paramset *ps, const sb_method_type *mt, const sb_solver_type *st, int n_sets,
                    const char *const *sets, char *err, size_t errlen)
{
    if (sb_paramset_add(ps, "run", sb_solve_params) || sb_paramset_add(ps, "solver", st->params) ||
        sb_paramset_add(ps, "method", mt->params)) {
        snprintf(err, errlen, "internal error: too many parameters");
        return SB_ERR_INTERNAL;
    }
    for (int i = 0; i < n_sets; i++)
        if (sb_paramset_set(ps, sets[i], err, errlen)) {
            sb_escape_controls(err, errlen);
            return SB_ERR_INPUT;
        }
    return SB_OK;
}

/* The scene's "methods" section names registered methods and their own
 * method.* parameters with valid values (the scene layer cannot check that:
 * it does not know the methods), and its reference surface does not start
 * inside an obstacle (sb_obstacles_start_check). */
int sb_run_scene_methods_check(const sb_scene *sc, char *err, size_t errlen)
{
    for (int i = 0; i < sc->n_methods; i++) {
        const sb_scene_method *m = &sc->methods[i];
        const sb_method_type *mt = sb_method_find(m->method);
        if (!mt) {
            snprintf(err, errlen, "%s: \"methods\" names \"%s\", which is not a method of this build (see `shellbench "
                     "list methods`)", sc->path, m->method);
            return SB_ERR_INPUT;
        }
        sb_paramset ps;
        sb_paramset_init(&ps);
        if (sb_paramset_add(&ps, "method", mt->params)) {
            snprintf(err, errlen, "internal error: too many parameters");
            return SB_ERR_INTERNAL;
        }
        for (int k = 0; k < m->n_sets; k++) {
            char msg[512];
            if (sb_paramset_set(&ps, m->sets[k], msg, sizeof msg)) {
                sb_escape_controls(msg, sizeof msg);
                snprintf(err, errlen, "%s: \"methods\"/\"%s\"/\"set\": %s", sc->path, m->method, msg);
                return SB_ERR_INPUT;
            }
        }
    }
    /* a cloth that starts inside an obstacle (docs/contact.md "The start"):
       refused here, by `check` and before a run's work, with the obstacle
       and the point named */
    char why[1024];
    const int in = sb_obstacles_start_check(sc, why, sizeof why);
    if (in < 0) {
        snprintf(err, errlen, "out of memory");
        return SB_ERR_NOMEM;
    }
    if (in > 0) {
        snprintf(err, errlen, "scene %s: %s", sc->name, why);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}
