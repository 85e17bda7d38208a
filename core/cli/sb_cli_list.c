/* sb_cli_list.c — `shellbench list [scenes|methods|solvers|params [NAME]]`
 * (sb_cli.h): what this build has, from the registries and the declared
 * parameter tables, so the listing never drifts from the code. */
#include "sb_cli.h"
#include "sb_method.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>

static int list_scenes(const char *indent)
{
    char path[1024], msg[1024];
    int bad = 0;
    if (sb_scene_resolve("trampoline", path, sizeof path) != 0) {
        fprintf(stderr, "shellbench list: the bundled scenes (bench/scenes) are not found\n");
        return 2;
    }
    char *slash = strrchr(path, '/');
    if (slash) *slash = 0;
    struct dirent **names;
    int n = scandir(path, &names, NULL, alphasort);
    for (int i = 0; i < n; i++) {
        size_t l = strlen(names[i]->d_name);
        if (l > 5 && strcmp(names[i]->d_name + l - 5, ".json") == 0) {
            char file[2048];
            sb_scene sc;
            snprintf(file, sizeof file, "%s/%s", path, names[i]->d_name);
            if (sb_scene_load(file, &sc, msg, sizeof msg) == SB_OK) {
                char d[sizeof sc.description];
                printf("%s%-24.*s %s\n", indent, (int)(l - 5), names[i]->d_name,
                       sc.description[0] ? sb_escape_copy(sc.description, d, sizeof d) : "(no description)");
                sb_scene_free(&sc);
            } else {
                printf("%s%-24.*s (does not parse: %s)\n", indent, (int)(l - 5), names[i]->d_name, msg);
                bad = 1;
            }
        }
        free(names[i]);
    }
    if (n >= 0) free(names);
    return bad ? 2 : 0;
}

/* default and range (or choices) of a declared parameter */
static void param_line(const char *prefix, const sb_param_def *d)
{
    char key[SB_NAME_LEN + 16], def[64], range[160];
    snprintf(key, sizeof key, "%s.%s", prefix, d->name);
    if (d->kind == SB_PARAM_CHOICE) {
        snprintf(def, sizeof def, "%s", d->choices[(int)d->def]);
        size_t u = 0;
        range[0] = 0;
        for (int i = 0; d->choices[i] && u + 2 < sizeof range; i++)
            u += (size_t)snprintf(range + u, sizeof range - u, "%s%s", i ? "|" : "{", d->choices[i]);
        if (u + 2 < sizeof range) strcat(range, "}");
    } else {
        snprintf(def, sizeof def, d->kind == SB_PARAM_INT ? "%.0f" : "%g", d->def);
        snprintf(range, sizeof range, d->kind == SB_PARAM_INT ? "%s[%.0f, %.0f]" : "%s[%g, %g]",
                 d->kind == SB_PARAM_INT ? "int " : "", d->lo, d->hi);
    }
    printf("  %-28s %-10s %-24s %s\n", key, def, range, d->help ? d->help : "");
}

static void param_table(const char *title, const char *prefix, const sb_param_def *defs)
{
    printf("%s\n", title);
    if (!defs || !defs->name) {
        printf("  (no parameters)\n");
        return;
    }
    for (const sb_param_def *d = defs; d->name; d++) param_line(prefix, d);
}

static int list_params(const char *which)
{
    char title[256];
    int found = 0;
    printf("  %-28s %-10s %-24s %s\n", "KEY (--set KEY=VALUE)", "DEFAULT", "RANGE", "MEANING");
    if (!which || !strcmp(which, "run")) {
        param_table("run (every run):", "run", sb_solve_params);
        found = 1;
    }
    for (int i = 0; i < sb_solver_count(); i++) {
        const sb_solver_type *s = sb_solver_at(i);
        if (which && strcmp(which, s->name)) continue;
        snprintf(title, sizeof title, "solver %s:", s->name);
        param_table(title, "solver", s->params);
        found = 1;
    }
    for (int i = 0; i < sb_method_count(); i++) {
        const sb_method_type *m = sb_method_at(i);
        if (which && strcmp(which, m->name)) continue;
        snprintf(title, sizeof title, "method %s:", m->name);
        param_table(title, "method", m->params);
        found = 1;
    }
    if (!found) {
        char e[64];
        fprintf(stderr, "shellbench list params: \"%s\" is neither run, a method nor a solver (see `shellbench list`)\n",
                sb_escape_copy(which, e, sizeof e));
        return 2;
    }
    return 0;
}

int sb_cli_list(int argc, char **argv)
{
    const char *what = argc > 0 ? argv[0] : "all";
    int all = strcmp(what, "all") == 0, rc = 0;
    if (!strcmp(what, "params")) {
        if (argc > 2) {
            fprintf(stderr, "shellbench list params: one name at most (run, a method or a solver)\n");
            return 2;
        }
        return list_params(argc > 1 ? argv[1] : NULL);
    }
    if ((!all && strcmp(what, "scenes") && strcmp(what, "methods") && strcmp(what, "solvers")) || argc > 1) {
        char e[64];
        fprintf(stderr, "shellbench list: unknown category \"%s\" (scenes, methods, solvers, params [NAME])\n",
                sb_escape_copy(argc > 1 ? argv[1] : what, e, sizeof e));
        return 2;
    }
    if (all || !strcmp(what, "scenes")) {
        if (all) printf("scenes:\n");
        rc = list_scenes(all ? "  " : "");
    }
    if (all || !strcmp(what, "methods")) {
        if (all) printf("methods:\n");
        for (int i = 0; i < sb_method_count(); i++) {
            const sb_method_type *m = sb_method_at(i);
            printf("%s%-20s %s%s\n", all ? "  " : "", m->name, m->description,
                   (m->flags & SB_METHOD_HIERARCHY) ? " [hierarchy]" : "");
        }
    }
    if (all || !strcmp(what, "solvers")) {
        if (all) printf("solvers:\n");
        for (int i = 0; i < sb_solver_count(); i++) {
            const sb_solver_type *s = sb_solver_at(i);
            printf("%s%-20s %s\n", all ? "  " : "", s->name, s->description);
        }
    }
    return rc;
}
