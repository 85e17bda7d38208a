/* sb_study_reference.c — `shellbench reference SCENE`: compute and store a
 * scene's reference record (docs/study.md "References").
 *
 *   shellbench reference SCENE [--method M] [--solver S] [--res N | --dofs N] [--levels L]
 *                        [--set key=value]... [--samples N] [--out FILE.h5] [--no-check] [--force]
 *
 * Default: the finest practical run of the most accurate method, converged
 * to a tight tolerance: method bhem (C1 bicubic Hermite patches: the smallest
 * errors per dof of the registered methods in results/accuracy/report.md;
 * the first registered method when bhem is not), the resolution nearest
 * 12,000 dofs, solver rmtr on 3 levels for a method with a hierarchy (tr
 * otherwise), run.gtol = 1e-8.  A second run at half the resolution
 * (--no-check: none) measures the reference's own convergence: the field
 * difference between the two, which bounds the coarser run's error and, for
 * an order p >= 2 method, exceeds the reference's by 2^p - 1 >= 3.
 *
 * Writes OUT (results/references/SCENE.h5), OUT-check.h5 and OUT.json (the
 * provenance: command, configuration, self-check), and says how a scene
 * points at it. */
#include "sb_output.h"
#include "sb_study_int.h"
#include "sb_geometry.h"
#include "sb_record.h"
#include "sb_reference.h"
#include "sb_run.h"
#include "sb_sysinfo.h"

#include <errno.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define REF_DOFS 12000
#define REF_GTOL "run.gtol=1e-8"

/* path of `target` relative to directory `from` (both made absolute) */
static void relative_path(const char *from_dir, const char *target, char *out, size_t len)
{
    char a[PATH_MAX], b[PATH_MAX], tdir[PATH_MAX];
    snprintf(tdir, sizeof tdir, "%s", target);
    char *slash = strrchr(tdir, '/');
    const char *base = slash ? slash + 1 : target;
    if (slash) *slash = 0;
    else snprintf(tdir, sizeof tdir, ".");
    if (!realpath(from_dir, a) || !realpath(tdir, b)) {
        snprintf(out, len, "%s", target);
        return;
    }
    size_t common = 0, i = 0;
    while (a[i] && a[i] == b[i]) {
        if (a[i] == '/') common = i;
        i++;
    }
    if (!a[i] && (b[i] == '/' || !b[i])) common = i;
    if (!b[i] && a[i] == '/') common = i;
    out[0] = 0;
    for (const char *p = a + common; *p; p++)
        if (*p == '/') snprintf(out + strlen(out), len - strlen(out), "../");
    const char *rest = b + common;
    if (*rest == '/') rest++;
    snprintf(out + strlen(out), len - strlen(out), "%.900s%s%.200s", rest, *rest ? "/" : "", base);
}

static int run_at(const char *scene, const char *method, const char *solver, int res, int levels, const char *const *sets,
                  int n_sets, int samples, const char *out, int makes_reference)
{
    sb_run_request q;
    memset(&q, 0, sizeof q);
    q.scene = scene, q.method = method, q.solver = solver, q.res = res, q.levels = levels, q.out = out;
    q.sets = sets, q.n_sets = n_sets, q.sample_n = samples, q.resume = 1;
    q.makes_reference = makes_reference;   /* the scene's reference is this run's output, replaced */
    return sb_run_execute(&q, stdout, stderr, NULL);
}

int sb_study_cmd_reference(int argc, char **argv)
{
    const char *scene_arg = NULL, *method = NULL, *solver = NULL, *out_arg = NULL;
    const char *sets[64];
    int n_sets = 0, res = 0, levels = 0, samples = 21, check = 1, force = 0;
    long dofs = REF_DOFS;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        long x = 0;
        char *end = NULL;
        if (v) x = strtol(v, &end, 10);
        int num = v && end != v && !*end && x > 0 && x < 100000000;
        if (!strcmp(a, "--method") && v) method = v, i++;
        else if (!strcmp(a, "--solver") && v) solver = v, i++;
        else if (!strcmp(a, "--out") && v) out_arg = v, i++;
        else if (!strcmp(a, "--res") && num) res = (int)x, i++;
        else if (!strcmp(a, "--dofs") && num) dofs = x, i++;
        else if (!strcmp(a, "--levels") && num && x <= SB_MAX_LEVELS) levels = (int)x, i++;
        else if (!strcmp(a, "--samples") && num && x >= 2 && x <= 2001) samples = (int)x, i++;
        else if (!strcmp(a, "--set") && v && n_sets < 60) sets[n_sets++] = v, i++;
        else if (!strcmp(a, "--no-check")) check = 0;
        else if (!strcmp(a, "--force")) force = 1;
        else if (a[0] != '-' && !scene_arg) scene_arg = a;
        else {
            sb_escape_print(stderr, "shellbench reference: unknown option, bad or missing value: \"%s\"", a);
            fprintf(stderr, "usage: shellbench reference SCENE [--method M] [--solver S] [--res N | --dofs N] [--levels L]\n"
                            "                            [--set key=value]... [--samples N] [--out FILE.h5] [--no-check] [--force]\n");
            return 2;
        }
    }
    if (!scene_arg) {
        fprintf(stderr, "shellbench reference: which scene? (shellbench reference SCENE ...)\n");
        return 2;
    }
    sb_study *st = calloc(1, sizeof *st);
    if (!st) return 3;
    int rc = 2;
    char msg[2048], out[1024], check_out[1100], prov[1100];
    sb_study_scene *sc = &st->scenes[0];
    snprintf(sc->arg, sizeof sc->arg, "%s", scene_arg);
    sc->scene = calloc(1, sizeof *sc->scene);
    if (!sc->scene) {
        fprintf(stderr, "shellbench reference: out of memory\n");
        goto out;
    }
    if (sb_scene_resolve(scene_arg, sc->path, sizeof sc->path)) {
        sb_escape_print(stderr, "shellbench reference: scene \"%s\" not found: no such file, and no bench/scenes/%s.json "
                        "(looked in the current directory, under $SB_ROOT and beside the program; try `shellbench list "
                        "scenes`)", scene_arg, scene_arg);
        goto out;
    }
    if (sb_scene_load(sc->path, sc->scene, msg, sizeof msg)) {
        sb_escape_print(stderr, "shellbench reference: scene \"%s\": %s", scene_arg, msg);
        goto out;
    }
    st->n_scenes = 1;
    snprintf(sc->name, sizeof sc->name, "%s", sc->scene->name);
    /* the method: bhem, else the first registered discretization */
    const sb_method_type *mt = method ? sb_method_find(method) : sb_method_find("bhem");
    for (int k = 0; !mt && !method && k < sb_method_count(); k++)
        if (!(sb_method_at(k)->flags & SB_METHOD_TEST_FIXTURE)) mt = sb_method_at(k);
    if (!mt) {
        sb_escape_print(stderr, "shellbench reference: unknown method \"%s\" (see `shellbench list methods`)", method ? method : "");
        goto out;
    }
    if (!solver) solver = (mt->flags & SB_METHOD_HIERARCHY) ? "rmtr" : "tr";
    const sb_solver_type *stype = sb_solver_find(solver);
    if (!stype) {
        sb_escape_print(stderr, "shellbench reference: unknown solver \"%s\" (see `shellbench list solvers`)", solver);
        goto out;
    }
    if (!levels) levels = (stype->flags & SB_SOLVER_NEEDS_HIERARCHY) ? 3 : 1;
    st->n_methods = 1;
    snprintf(st->methods[0].name, sizeof st->methods[0].name, "%s", mt->name);
    st->methods[0].type = mt;
    for (int k = 0; k < n_sets && st->methods[0].sets.n < SB_STUDY_MAX_SETS; k++)
        snprintf(st->methods[0].sets.kv[st->methods[0].sets.n++], SB_STUDY_SET_LEN, "%s", sets[k]);
    /* the resolution: given, or the one nearest the dofs target */
    long got = 0;
    sb_dofs_cache cache;
    sb_dofs_cache_init(&cache);
    int r2 = res ? sb_study_dofs_at(st, &cache, 0, 0, levels, res, &got, msg, sizeof msg)
                 : sb_study_res_for_dofs(st, &cache, 0, 0, levels, dofs, &res, &got, msg, sizeof msg);
    sb_dofs_cache_free(&cache);
    if (r2) {
        sb_escape_print(stderr, "shellbench reference: %s", msg);
        goto out;
    }
    /* a tight tolerance unless one is given */
    int has_gtol = 0;
    for (int k = 0; k < n_sets; k++) has_gtol |= strncmp(sets[k], "run.gtol=", 9) == 0;
    if (!has_gtol) sets[n_sets++] = REF_GTOL;
    if (out_arg) snprintf(out, sizeof out, "%s", out_arg);
    else snprintf(out, sizeof out, "results/references/%s.h5", sc->name);
    size_t ol = strlen(out);
    snprintf(check_out, sizeof check_out, "%.*s-check.h5", (int)(ol > 3 && !strcmp(out + ol - 3, ".h5") ? ol - 3 : ol), out);
    snprintf(prov, sizeof prov, "%.*s.json", (int)(ol > 3 && !strcmp(out + ol - 3, ".h5") ? ol - 3 : ol), out);
    if (!force && access(out, F_OK) == 0) {
        sb_escape_print(stderr, "shellbench reference: %s exists (--force replaces it; scenes and studies may point at it)", out);
        goto out;
    }
    if (force) {   /* and their checkpoints: a replaced reference starts afresh */
        char part[1200];
        unlink(out), unlink(check_out);
        snprintf(part, sizeof part, "%s.partial", out), unlink(part);
        snprintf(part, sizeof part, "%s.partial", check_out), unlink(part);
    }
    sb_escape_print(stdout, "reference of %s: %s/%s on %d level%s, res %d (%ld dofs), %s -> %s", sc->name, mt->name, solver, levels,
           levels > 1 ? "s" : "", res, got, REF_GTOL, out);
    fflush(stdout);
    int code = run_at(sc->path, mt->name, solver, res, levels, sets, n_sets, samples, out, 1);
    if (code != 0) {
        fprintf(stderr, "shellbench reference: the reference run %s (exit %d): no reference written%s\n",
                code == 1 ? "did not converge" : "failed", code, code == 1 ? " (its record is left for inspection)" : "");
        if (code == 1) {
            char keep[1100];
            snprintf(keep, sizeof keep, "%s.not-converged.h5", out);
            sb_output_kind kind;
            char msg[1400] = "the path is the null device";
            if (sb_output_check(keep, "record", &kind, msg, sizeof msg) || kind == SB_OUTPUT_DISCARD)
                sb_escape_print(stderr, "shellbench reference: %s kept where it is: %s", out, msg);
            else
                rename(out, keep);
        }
        rc = code == 2 ? 2 : 1;
        goto out;
    }
    /* the self-check at half the resolution */
    double crms = NAN, cmax = NAN;
    int cres = res / 2;
    long cdofs = 0;
    if (check && cres >= 1) {
        int lv = levels;
        while (lv > 1 && cres % (1 << (lv - 1))) lv--;
        if (stype->flags & SB_SOLVER_NEEDS_HIERARCHY && lv < 2) lv = 2;
        code = run_at(sc->path, mt->name, solver, cres, lv, sets, n_sets, samples, check_out, 0);
        if (code == 2 && (lv > 1 || strcmp(solver, "tr"))) {
            /* the method refuses the hierarchy at half the resolution: the
             * check is about the discretization, so single-level TR will do */
            fprintf(stderr, "shellbench reference: the self-check with %s on %d levels was refused; "
                            "running it with tr on 1 level\n", solver, lv);
            code = run_at(sc->path, mt->name, "tr", cres, 1, sets, n_sets, samples, check_out, 0);
        }
        if (code == 0) {
            int n = 0;
            double *grid = NULL, *pos = NULL;
            sb_refrec ref, chk;
            if (sb_record_read_samples(check_out, &n, &grid, &pos, msg, sizeof msg) == SB_OK &&
                sb_refrec_load(out, sc->name, sc->scene->json_text, n, grid, &ref, msg, sizeof msg) == SB_OK) {
                if (sb_refrec_load(check_out, sc->name, sc->scene->json_text, n, grid, &chk, msg, sizeof msg) == SB_OK) {
                    sb_field_error(n, chk.pos, ref.pos, sb_domain_diameter(&sc->scene->domain), &crms, &cmax);
                    cdofs = chk.dofs;
                    sb_refrec_free(&chk);
                }
                sb_refrec_free(&ref);
            }
            if (!isfinite(crms)) fprintf(stderr, "shellbench reference: warning: self-check not evaluated: %s\n", msg);
            free(grid);
            free(pos);
        } else {
            fprintf(stderr, "shellbench reference: warning: the self-check run at res %d %s (exit %d): no self-check\n", cres,
                    code == 1 ? "did not converge" : code == 2 ? "was refused" : "failed", code);
        }
    }
    /* provenance */
    json_t *o = json_object(), *jsets = json_array();
    for (int k = 0; k < n_sets; k++) json_array_append_new(jsets, json_string(sets[k]));
    char cmd[2048] = "shellbench reference", when[32], build[64];
    for (int k = 0; k < argc; k++) snprintf(cmd + strlen(cmd), sizeof cmd - strlen(cmd), " %s", argv[k]);
    sb_sysinfo_now_iso(when, sizeof when);
    sb_sysinfo_build_id(build, sizeof build);
    json_object_set_new(o, "scene", json_string(sc->name));
    json_object_set_new(o, "scene_file", json_string(sc->path));
    json_object_set_new(o, "record", json_string(out));
    json_object_set_new(o, "command", json_string(cmd));
    json_object_set_new(o, "method", json_string(mt->name));
    json_object_set_new(o, "solver", json_string(solver));
    json_object_set_new(o, "levels", json_integer(levels));
    json_object_set_new(o, "res", json_integer(res));
    json_object_set_new(o, "dofs", json_integer(got));
    json_object_set_new(o, "samples", json_integer(samples));
    json_object_set_new(o, "set", jsets);
    json_object_set_new(o, "written", json_string(when));
    json_object_set_new(o, "build", json_string(build));
    json_t *ck = json_object();
    json_object_set_new(ck, "record", check ? json_string(check_out) : json_null());
    json_object_set_new(ck, "res", json_integer(check ? cres : 0));
    json_object_set_new(ck, "dofs", json_integer(cdofs));
    json_object_set_new(ck, "rms", isfinite(crms) ? json_real(crms) : json_null());
    json_object_set_new(ck, "max", isfinite(cmax) ? json_real(cmax) : json_null());
    json_object_set_new(ck, "note", json_string("field difference / diameter between this run at half the resolution and the "
                                                "reference: bounds the coarser run's error; the reference's is smaller by "
                                                "2^p - 1 >= 3 for an order p >= 2 method (on a scene with a unique solution)"));
    json_object_set_new(o, "self_check", ck);
    if (json_dump_file(o, prov, JSON_INDENT(2) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(6)))
        sb_escape_print(stderr, "shellbench reference: warning: cannot write %s", prov);
    json_decref(o);
    char scene_dir[600], rel[1200];
    snprintf(scene_dir, sizeof scene_dir, "%s", sc->path);
    char *slash = strrchr(scene_dir, '/');
    if (slash) *slash = 0;
    else snprintf(scene_dir, sizeof scene_dir, ".");
    relative_path(scene_dir, out, rel, sizeof rel);
    sb_escape_print(stdout, "reference written: %s (%ld dofs), provenance %s", out, got, prov);
    if (isfinite(crms)) printf("self-check at res %d (%ld dofs): field difference RMS %.3g, max %.3g of the diameter\n", cres, cdofs, crms, cmax);
    sb_escape_print(stdout, "point the scene at it: \"reference\": {\"type\": \"file\", \"file\": \"%s\"}", rel);
    rc = 0;
out:
    sb_study_free(st);
    free(st);
    return rc;
}
