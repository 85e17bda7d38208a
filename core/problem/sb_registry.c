/* sb_registry.c — the methods and solvers a run can name. */
#include "sb_method.h"
#include "sb_solver.h"

#include <string.h>

extern const sb_method_type sb_method_subdiv;
extern const sb_method_type sb_method_bhem;
extern const sb_method_type sb_method_linear_fem;
extern const sb_method_type sb_method_adaptive_sqrt3;
extern const sb_method_type sb_fixture_membrane;
extern const sb_method_type sb_fixture_rosenbrock;
extern const sb_method_type sb_fixture_quadratic;
extern const sb_method_type sb_fixture_saddle;
extern const sb_method_type sb_fixture_chain;

static const sb_method_type *const methods[] = {
    &sb_method_subdiv,
    &sb_method_bhem,
    &sb_method_linear_fem,
    &sb_method_adaptive_sqrt3,
    &sb_fixture_membrane,
    &sb_fixture_rosenbrock,
    &sb_fixture_quadratic,
    &sb_fixture_saddle,
    &sb_fixture_chain,
};

extern const sb_solver_type sb_solver_tr;
extern const sb_solver_type sb_solver_lsnewton;
extern const sb_solver_type sb_solver_damped;
extern const sb_solver_type sb_solver_linearized;
extern const sb_solver_type sb_solver_rmtr;

static const sb_solver_type *const solvers[] = {
    &sb_solver_tr,
    &sb_solver_lsnewton,
    &sb_solver_damped,
    &sb_solver_linearized,
    &sb_solver_rmtr,
};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

int sb_method_count(void) { return COUNT(methods); }
const sb_method_type *sb_method_at(int i) { return i >= 0 && i < COUNT(methods) ? methods[i] : NULL; }
const sb_method_type *sb_method_find(const char *name)
{
    for (int i = 0; i < COUNT(methods); i++)
        if (strcmp(methods[i]->name, name) == 0) return methods[i];
    return NULL;
}

int sb_solver_count(void) { return COUNT(solvers); }
const sb_solver_type *sb_solver_at(int i) { return i >= 0 && i < COUNT(solvers) ? solvers[i] : NULL; }
const sb_solver_type *sb_solver_find(const char *name)
{
    for (int i = 0; i < COUNT(solvers); i++)
        if (strcmp(solvers[i]->name, name) == 0) return solvers[i];
    return NULL;
}
