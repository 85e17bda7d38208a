/* sb_inspect.c — rebuild a record's discretization and evaluate its state
 * (see sb_inspect.h).  Data flow as in a run, without a solver: record ->
 * scene -> method -> material state -> table. */
#include "sb_inspect.h"
#include "sb_context.h"
#include "sb_memory.h"
#include "sb_record.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the material state of a record already read (su) */
static int material_of(const char *path, const sb_record_setup *su, sb_material_state *ms, char *err, size_t errlen)
{
        int rc;
    sb_scene scene;
    memset(&scene, 0, sizeof scene);
    sb_context ctx;
    void *state = NULL;
    int created = 0, have_ctx = 0;
    const sb_method_type *mt = sb_method_find(su->method);
    char msg[1024];
    if (!mt) {
        rc = SB_ERR_INPUT;
        snprintf(err, errlen, "%s: method \"%s\" is not in this build", path, su->method);
        goto done;
    }
    if (!mt->material_state) {
        rc = SB_ERR_UNSUPPORTED;
        snprintf(err, errlen, "%s: method %s cannot report its material state", path, mt->name);
        goto done;
    }
    if ((rc = sb_scene_parse_string(su->scene_json, su->scene_path, &scene, msg, sizeof msg))) {
        snprintf(err, errlen, "%s: its scene does not parse: %s", path, msg);
        goto done;
    }
    if ((rc = sb_context_init(&ctx))) {
        snprintf(err, errlen, "%s: cannot set up a context", path);
        goto done;
    }
    have_ctx = 1;
    if (sb_paramset_add(&ctx.params, "method", mt->params)) {
        rc = SB_ERR_INTERNAL;
        snprintf(err, errlen, "%s: too many parameters", path);
        goto done;
    }
    for (int i = 0; i < su->n_sets; i++)
        if ((rc = sb_paramset_set(&ctx.params, su->sets[i], msg, sizeof msg))) {
            snprintf(err, errlen, "%s: parameter %s: %s", path, su->sets[i], msg);
            goto done;
        }
    if (!(state = calloc(1, mt->state_size))) {
        rc = SB_ERR_NOMEM;
        snprintf(err, errlen, "%s: out of memory", path);
        goto done;
    }
    sb_method_config cfg = { su->res, su->levels > 0 ? su->levels : 1, &ctx.params, &ctx, su->res_t };
    /* a record's sizes are input like any other: what cannot fit is refused before create() */
    sb_memory_run mr = { 0, 0, 0, 2, 0, SB_SUPERNODES_CHOLMOD, 0, 0 };
    double bytes;
    char what[600];
    snprintf(what, sizeof what, "%s: method %s at res %d with %d levels", path, mt->name, su->res, cfg.levels);
    if ((rc = sb_memory_check_method(mt, &scene, &cfg, &mr, 0, what, &bytes, err, errlen))) goto done;
    rc = mt->create(state, &scene, &cfg);
    created = 1;
    if (rc) {
        snprintf(err, errlen, "%s: method %s: %s", path, mt->name, ctx.err[0] ? ctx.err : "set-up failed");
        goto done;
    }
    const int F = mt->n_levels(state) - 1;
    if (mt->n_dofs(state, F) != su->n_x) {
        rc = SB_ERR_INPUT;
        snprintf(err, errlen, "%s: /final/x has %d dofs, the rebuilt discretization %d", path, su->n_x,
                 mt->n_dofs(state, F));
        goto done;
    }
    rc = mt->material_state(state, F, su->x, ms);
    if (rc) snprintf(err, errlen, "%s: some quadrature points of the state could not be evaluated", path);
done:
    if (created) mt->destroy(state);
    free(state);
    if (have_ctx) sb_context_free(&ctx);
    sb_scene_free(&scene);
    return rc;
}

int sb_inspect_material(const char *path, sb_material_state *ms, char *err, size_t errlen)
{
    sb_record_setup su;
    int rc = sb_record_read_setup(path, &su, err, errlen);
    if (!rc) rc = material_of(path, &su, ms, err, errlen);
    sb_record_setup_free(&su);
    return rc;
}

int sb_inspect_report(int n_files, char **files, const char *format, FILE *out, FILE *err)
{
    const int csv = format && !strcmp(format, "csv");
    if (csv)
        fprintf(out, "file,scene,method,solver,dofs,levels,status,status_code,steps_done,points,soft_membrane,soft_section,"
                     "soft_area_fraction,max_E11,max_E22,max_E12,min_rel_eig,below_reference,below_reference_area_fraction\n");
    else
        fprintf(out, "| file | dofs | status | points | softening (membrane) | area fraction | "
                     "softening (section) | max E11 | max E22 | max E12 | energy below reference (area fraction) |\n"
                     "|---|--:|---|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    int bad = 0;
    for (int i = 0; i < n_files; i++) {
        sb_material_state ms;
        sb_record_setup su;
        char e[1536];
        if (sb_record_read_setup(files[i], &su, e, sizeof e) || material_of(files[i], &su, &ms, e, sizeof e)) {
            sb_escape_print(err, "shellbench inspect: %s", e);
            sb_record_setup_free(&su);
            bad++;
            continue;
        }
        const double frac = ms.area > 0 ? ms.soft_area / ms.area : 0.0;
        const double below = ms.area > 0 ? ms.below_reference_area / ms.area : 0.0;
        char fe[1024];
        sb_escape_copy(files[i], fe, sizeof fe);   /* the file name as given, terminal-safe */
        if (csv)
            fprintf(out, "%s,%s,%s,%s,%d,%d,%s,%d,%d,%ld,%ld,%ld,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,%.6g\n", fe, su.scene, su.method,
                    su.solver, su.n_x, su.levels, sb_record_status_name(su.status), su.status, su.steps_done, ms.points, ms.soft_membrane,
                    ms.soft_section, frac, ms.max_strain[0], ms.max_strain[1], ms.max_strain[2], ms.min_rel_eig,
                    ms.below_reference, below);
        else
            fprintf(out, "| %s | %d | %s | %ld | %ld | %.3g | %ld | %.3g | %.3g | %.3g | %ld (%.3g) |\n", fe, su.n_x,
                    sb_record_status_name(su.status),
                    ms.points, ms.soft_membrane, frac, ms.soft_section, ms.max_strain[0], ms.max_strain[1],
                    ms.max_strain[2], ms.below_reference, below);
        sb_record_setup_free(&su);
    }
    return bad;
}
