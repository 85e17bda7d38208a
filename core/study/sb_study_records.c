/* sb_study_records.c — is the record at a planned run's path that run's?
 * (docs/study.md "Records that are not the plan's")
 *
 * A study finds its records by path (RECORDS/SCENE/METHOD-SOLVER-rN.h5), so
 * a record copied or renamed into another run's place would count as that
 * run: a drape record at trampoline/bhem-lsnewton-r4.h5 was skipped by
 * `sweep` and ranked by `report` as the trampoline's.  Every record found is
 * checked against the plan: its scene (name, and the problem: the scene
 * texts compared as sb_scene_same_problem does for references), method,
 * solver, resolution and level count. */
#include "sb_study_int.h"
#include "sb_record.h"
#include "sb_reference.h"

#include <string.h>

int sb_study_record_check(const sb_study *st, const sb_plan_run *r, char *why, size_t len)
{
    sb_record_setup su;
    char msg[1536], field[256];
    int rc = sb_record_read_identity(r->out, &su, msg, sizeof msg);   /* digests keep no /final/x */
    if (rc) {
        snprintf(why, len, "%s", msg);
        return rc;
    }
    const sb_study_scene *sc = &st->scenes[r->scene];
    const char *method = st->methods[r->method].name, *solver = st->solvers[r->solver].name;
    char what[600] = "";
    if (strcmp(su.scene, sc->name)) {
        snprintf(what, sizeof what, "its scene is %s, the plan's %s", su.scene, sc->name);
    } else if (r->dt <= 0 && sc->scene &&
               sb_scene_same_problem(su.scene_json, sc->scene->json_text, field, sizeof field) != 1) {
        /* (a dt study's runs use the scene with their own step: their text differs by design) */
        snprintf(what, sizeof what, "its scene %s is another problem than the study's %s (%s differs)", su.scene,
                 sc->path, field[0] ? field : "the scene text");
    } else if (strcmp(su.method, method)) {
        snprintf(what, sizeof what, "its method is %s, the plan's %s", su.method, method);
    } else if (strcmp(su.solver, solver)) {
        snprintf(what, sizeof what, "its solver is %s, the plan's %s", su.solver, solver);
    } else if (su.res != 0 && su.res != r->res) {   /* 0: an older build's record, which kept no resolution */
        snprintf(what, sizeof what, "its resolution is %d, the plan's %d", su.res, r->res);
    } else if (su.levels != r->levels) {
        snprintf(what, sizeof what, "it has %d level%s, the plan's run %d", su.levels, su.levels == 1 ? "" : "s",
                 r->levels);
    } else {
        /* the linear solver, where the plan names one (a solver entry's
         * "linear", a "set" or "vary"): the last assignment wins */
        const char *planned = NULL;
        for (int k = 0; k < r->n_sets; k++)
            if (!strncmp(r->sets[k], "solver.linear=", 14)) planned = r->sets[k] + 14;
        const char *got = su.linear[0] ? su.linear : "cholmod";
        if (planned && strcmp(planned, got))
            snprintf(what, sizeof what, "its linear solver is %s, the plan's %s", got, planned);
    }
    sb_record_setup_free(&su);
    if (!what[0]) return SB_OK;
    snprintf(why, len, "%s is not the record of the planned run (%s): a record copied or renamed into its place; "
             "move it away, and the run is made again", r->out, what);
    return SB_ERR_INPUT;
}
