/* test_cli_sweep.c — issue 28 "Sweeps, reports and records": a sweep is
 * validated as a whole before its first run (empty lists, unknown names,
 * scenes that do not parse, resolutions out of range or too large, --set
 * keys a run does not know, two runs on one record: exit 2, nothing run);
 * a scene given as a path writes its records into --dir by its name; a run
 * without --res records the resolution it used; --resume reports skipped
 * runs as skipped; impossible combinations are left out and named. */
#include "cli_sh.h"
#include "sb_sweep.h"
#include "sb_test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256], err[8192], out[1 << 16];

static int count_files(const char *dir)
{
    char buf[64];
    if (sb_sh(buf, sizeof buf, NULL, 0, "ls -A %s 2>/dev/null | wc -l", dir) != 0) return -1;
    return atoi(buf);
}

/* a sweep that must be refused before any run: exit 2, the message, no record */
static void refused(sb_test_state *T, const char *args, const char *want)
{
    char dir[512];
    static int k;
    snprintf(dir, sizeof dir, "%s/refused%d", tmpdir, k++);
    int ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep %s --dir %s", sb_test_root(), sb_test_bin(), args, dir);
    CHECK_MSG(ec == 2, "sweep %s: exit %d", args, ec);
    CHECK_MSG(strstr(err, want) != NULL, "sweep %s: want \"%s\" in: %s", args, want, err);
    CHECK_MSG(count_files(dir) <= 0 && !strstr(out, "converged"), "sweep %s ran something: %s", args, out);
}

SB_TEST(validated_before_the_first_run)
{
    const char *ok = "--scenes trampoline --methods bhem --solvers tr --res 4";
    (void)ok;
    refused(T, "--scenes '' --methods bhem --solvers tr --res 4", "--scenes: an empty list");
    refused(T, "--scenes trampoline --methods bhem --solvers tr --res ,", "--res: an empty list or an empty item");
    refused(T, "--scenes trampoline --methods bhem, --solvers tr --res 4", "--methods: an empty list or an empty item");
    refused(T, "--scenes trampoline --methods bhem,nosuch --solvers tr --res 4", "unknown method \"nosuch\"");
    refused(T, "--scenes trampoline --methods bhem --solvers tr,nosuch --res 4", "unknown solver \"nosuch\"");
    refused(T, "--scenes trampoline --methods bhem --solvers tr --res 4,abc", "\"abc\" is not a resolution");
    refused(T, "--scenes trampoline --methods bhem --solvers tr --res 4,4097", "1 to 4096");
    refused(T, "--scenes trampoline --methods bhem --solvers tr --res 4 --levels 1,9", "--levels");
    refused(T, "--scenes trampoline,tests/scenes_bad/poisson_out_of_range.json --methods bhem --solvers tr --res 4",
            "at /material/poisson");
    refused(T, "--scenes trampoline,nowhere --methods bhem --solvers tr --res 4", "scene \"nowhere\" not found");
    /* a key one method knows and the other does not */
    refused(T, "--scenes trampoline --methods bhem,rmtr --solvers tr --res 4 --set method.cells_t=8",
            "unknown parameter \"method.cells_t\"");
    /* a resolution the method cannot coarsen, or too large for the memory limit */
    refused(T, "--scenes trampoline --methods bhem --solvers rmtr --levels 2 --res 4,5", "cannot be coarsened");
    refused(T, "--scenes trampoline --methods bhem --solvers tr --res 4,128 --set run.max_memory=0.5", "needs about");
    /* two runs on one record: trampoline's own resolution is 16 */
    refused(T, "--scenes trampoline --methods bhem --solvers tr --res 0,16", "would write the same record");
    refused(T, "--scenes trampoline,bench/scenes/trampoline.json --methods bhem --solvers tr --res 4",
            "would write the same record");
    /* nothing possible at all */
    refused(T, "--scenes trampoline --methods fixture_quadratic --solvers rmtr --levels 2", "no run is possible");
}

SB_TEST(path_scenes_resolutions_and_resume)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char dir[512], rec[700], rec16[700];
    snprintf(dir, sizeof dir, "%s/sweep", tmpdir);
    int ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --scenes tests/scenes/membrane_dynamic.json,"
                   "trampoline --methods bhem --solvers tr,rmtr --levels 1,2 --res 4 --dir %s", root, bin, dir);
    CHECK_MSG(ec == 0, "exit %d: %s %s", ec, out, err);
    /* a path scene: by its name in DIR, never DIR/tests/scenes/... */
    snprintf(rec, sizeof rec, "%s/membrane_dynamic-bhem-tr-r4-l1.h5", dir);
    CHECK_MSG(access(rec, R_OK) == 0, "%s missing: %s", rec, out);
    snprintf(rec16, sizeof rec16, "%s/tests", dir);
    CHECK(access(rec16, F_OK) != 0);
    /* rmtr with one level is left out and named; the rest ran: 2 scenes x (tr l1, tr l2, rmtr l2) */
    CHECK_MSG(strstr(err, "1 combination left out: bhem/rmtr l1: solver rmtr needs at least 2 levels"), "%s", err);
    CHECK_MSG(strstr(out, "6 runs in") && strstr(out, "6 converged"), "%s", out);
    /* --resume: recorded runs are skipped and said to be */
    struct stat before, after;
    CHECK(stat(rec, &before) == 0);
    ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --scenes tests/scenes/membrane_dynamic.json --methods "
               "bhem --solvers tr --res 4,8 --dir %s --resume", root, bin, dir);
    CHECK_EQ_INT(ec, 0);
    CHECK_MSG(strstr(out, "membrane_dynamic-bhem-tr-r4-l1.h5") && strstr(out, "skipped (recorded: converged)") &&
              strstr(out, "membrane_dynamic-bhem-tr-r8-l1.h5") && strstr(out, "1 converged, 0 not converged, 1 skipped"),
              "%s", out);
    CHECK(stat(rec, &after) == 0 && after.st_mtime == before.st_mtime && after.st_ino == before.st_ino);
    /* without --res: the scene's own resolution, in the name and in the record */
    ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --scenes trampoline --methods bhem --solvers tr --dir %s "
               "--set run.max_iter=2", root, bin, dir);
    CHECK(ec == 0 || ec == 1);
    snprintf(rec16, sizeof rec16, "%s/trampoline-bhem-tr-r16-l1.h5", dir);
    CHECK_MSG(access(rec16, R_OK) == 0, "%s", out);
    /* res, parameters: before validation, potential_change, res_t (docs/trust.md) */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s report --format csv %s | tail -n 1 | rev | cut -d, -f4,5 | rev",
                       bin, rec16), 0);
    CHECK_MSG(strncmp(out, "16,run.max_iter=2", 17) == 0, "res, parameters: %s", out);
    /* and a single run without --res likewise (it recorded res = 0, named ...-r0-...) */
    char auto_dir[600];
    snprintf(auto_dir, sizeof auto_dir, "%s/auto", tmpdir);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "mkdir -p %s && cd %s && %s run --scene %s/bench/scenes/trampoline.json "
                       "--method bhem --solver tr --set run.max_iter=1 --quiet", auto_dir, auto_dir, bin, root), 1);
    CHECK_EQ_INT(sb_sh(out, sizeof out, NULL, 0, "ls %s/results/runs", auto_dir), 0);
    CHECK_MSG(strstr(out, "trampoline-bhem-tr-r16-l1.h5"), "%s", out);
}

SB_TEST(validate_api)
{
    const char *scenes[] = { "trampoline" }, *methods[] = { "bhem", "rmtr" }, *solvers[] = { "tr", "rmtr" };
    const int res[] = { 0, 8 }, levels[] = { 1, 2 };
    char dir[512];
    snprintf(dir, sizeof dir, "%s/api", tmpdir);
    sb_sweep_axes ax = { 1, scenes, 2, methods, 2, solvers, 2, res, 2, levels, 0, NULL, dir, 0 };
    sb_sweep_plan plan;
    CHECK_EQ_INT(sb_sweep_validate(&ax, &plan, err, sizeof err), SB_OK);
    /* 2 methods x (tr l1, tr l2, rmtr l2) x res {16, 8} */
    CHECK_EQ_INT(plan.n, 12);
    CHECK_EQ_INT(plan.n_left_out, 2);
    CHECK(plan.n > 0 && plan.items[0].res == 16 && strcmp(plan.items[0].scene_name, "trampoline") == 0);
    CHECK(plan.n > 0 && strstr(plan.items[0].out, "/api/trampoline-bhem-tr-r16-l1.h5"));
    sb_sweep_plan_free(&plan);
    CHECK(access(dir, F_OK) != 0);   /* validation has no side effects */
    ax.n_scenes = 0;
    CHECK_EQ_INT(sb_sweep_validate(&ax, &plan, err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "no scene") && plan.n == 0 && plan.items == NULL);
    ax.n_scenes = 1;
    ax.dir = "/proc/version/sub";
    CHECK_EQ_INT(sb_sweep_validate(&ax, &plan, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "not a directory"), "%s", err);
}

/* issue 37 item 13: `sweep --strict` counted a validation failure (exit 5:
 * converged, a probe out of tolerance) as "failed" */
SB_TEST(strict_counts_validation_failures_apart)
{
    char dir[512];
    snprintf(dir, sizeof dir, "%s/strict", tmpdir);
    /* bhem on 2 x 2 patches of the clamped plate: converged, validation failed */
    int ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --scenes plate_clamped --methods bhem --solvers tr "
                   "--res 2 --strict --dir %s", sb_test_root(), sb_test_bin(), dir);
    CHECK_EQ_INT(ec, 5);
    CHECK_MSG(strstr(out, "validation failed") && strstr(out, "0 failed, 1 validation failed"), "%s", out);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_cli_sweep_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(validated_before_the_first_run), SB_CASE(path_scenes_resolutions_and_resume), SB_CASE(validate_api),
        SB_CASE(strict_counts_validation_failures_apart), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
