/* test_cli.c — the command-line contract: list, check, run (summary JSON,
 * exit codes, refusal of impossible combinations), report, HDF5 readable by
 * h5dump.  Runs the built binary (SB_BIN). */
#include "sb_test.h"

#include <jansson.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

static char tmpdir[256];

/* run a shell command, capture stdout into buf; returns the exit status */
static int sh(char *buf, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int sh(char *buf, size_t len, const char *fmt, ...)
{
    char cmd[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    FILE *p = popen(cmd, "r");
    if (!p) return -1;
    size_t n = buf ? fread(buf, 1, len - 1, p) : 0;
    if (buf) buf[n] = 0;
    else { char tmp[4096]; while (fread(tmp, 1, sizeof tmp, p) > 0) {} }
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static int have_binary(void) { return access(sb_test_bin(), X_OK) == 0; }

SB_TEST(list_names_methods_and_solvers)
{
    static char out[65536];
    CHECK(have_binary());
    CHECK_EQ_INT(sh(out, sizeof out, "%s list solvers", sb_test_bin()), 0);
    const char *solvers[] = { "tr", "lsnewton", "damped", "linearized", "rmtr" };
    for (int i = 0; i < 5; i++) CHECK_MSG(strstr(out, solvers[i]) != NULL, "solver %s not listed", solvers[i]);
    CHECK_EQ_INT(sh(out, sizeof out, "%s list methods", sb_test_bin()), 0);
    CHECK(strstr(out, "fixture_membrane") != NULL);
    CHECK(strstr(out, "TEST FIXTURE") != NULL);
    CHECK_EQ_INT(sh(out, sizeof out, "%s list scenes", sb_test_bin()), 0);
    CHECK(strstr(out, "trampoline") != NULL);
    CHECK_EQ_INT(sh(NULL, 0, "%s list nonsense 2>/dev/null", sb_test_bin()), 2);
    CHECK_EQ_INT(sh(NULL, 0, "%s frobnicate 2>/dev/null", sb_test_bin()), 2);
}

SB_TEST(check_bundled_scenes_ok)
{
    static char out[65536];
    CHECK_EQ_INT(sh(out, sizeof out, "cd %s && %s check bench/scenes/*.json", sb_test_root(), sb_test_bin()), 0);
    CHECK(strstr(out, ": ok") != NULL);
}

SB_TEST(check_bad_scene_exit_2)
{
    static char out[65536];
    /* errors on stderr (stdout is for results) */
    CHECK_EQ_INT(sh(out, sizeof out, "cd %s && %s check tests/scenes_bad/poisson_out_of_range.json 2>/dev/null", sb_test_root(), sb_test_bin()), 2);
    CHECK(out[0] == 0);
    CHECK_EQ_INT(sh(out, sizeof out, "cd %s && %s check tests/scenes_bad/poisson_out_of_range.json 2>&1 >/dev/null", sb_test_root(), sb_test_bin()), 2);
    CHECK(strstr(out, "poisson_out_of_range.json:") != NULL);
    CHECK(strstr(out, "at /material/poisson") != NULL);
}

SB_TEST(run_summary_json_contract)
{
    static char out[1 << 16];
    int ec = sh(out, sizeof out, "cd %s && %s run --scene tests/scenes/membrane_dynamic.json --method fixture_membrane "
                "--solver lsnewton --res 8 --out %s/run.h5 --summary json --quiet", sb_test_root(), sb_test_bin(), tmpdir);
    CHECK_EQ_INT(ec, 0);
    json_error_t e;
    json_t *o = json_loads(out, 0, &e);
    CHECK_MSG(o != NULL, "summary is not JSON: %s", e.text);
    if (!o) return;
    const char *keys[] = { "scene", "method", "solver", "dofs", "status", "reason", "iterations", "work_units", "seconds", "probes", "error" };
    for (int i = 0; i < 11; i++) CHECK_MSG(json_object_get(o, keys[i]) != NULL, "missing key %s", keys[i]);
    CHECK(strcmp(json_string_value(json_object_get(o, "status")), "converged") == 0);
    CHECK(json_number_value(json_object_get(json_object_get(o, "work_units"), "assembly")) > 0);
    CHECK(json_object_get(json_object_get(o, "seconds"), "total") != NULL);
    CHECK(json_object_get(json_object_get(o, "seconds"), "factorize") != NULL);
    json_t *c = json_object_get(json_object_get(o, "probes"), "center");
    CHECK(json_array_size(json_object_get(c, "position")) == 3);
    CHECK(json_array_size(json_object_get(c, "displacement")) == 3);
    CHECK(json_number_value(json_array_get(json_object_get(c, "displacement"), 2)) < 0);   /* gravity pulls down */
    json_decref(o);
    /* the record is readable by h5dump */
    CHECK_EQ_INT(sh(NULL, 0, "h5dump -H %s/run.h5 >/dev/null 2>&1", tmpdir), 0);
    struct stat sbuf;
    CHECK(stat("/dev/null", &sbuf) == 0);
}

SB_TEST(every_solver_writes_a_record_and_report_works)
{
    static char out[1 << 16];
    const char *solvers[] = { "tr", "lsnewton", "damped", "linearized", "rmtr" };
    char files[2048] = "";
    for (int i = 0; i < 5; i++) {
        int ec = sh(NULL, 0, "cd %s && %s run --scene tests/scenes/membrane_dynamic.json --method fixture_membrane "
                    "--solver %s --res 8 --levels %d --out %s/%s.h5 --quiet 2>/dev/null", sb_test_root(), sb_test_bin(),
                    solvers[i], i == 4 ? 2 : 1, tmpdir, solvers[i]);
        CHECK_MSG(ec == 0 || ec == 1, "%s exit %d", solvers[i], ec);
        CHECK_EQ_INT(sh(NULL, 0, "h5dump -H %s/%s.h5 >/dev/null 2>&1", tmpdir, solvers[i]), 0);
        char one[300];
        snprintf(one, sizeof one, " %s/%s.h5", tmpdir, solvers[i]);
        strcat(files, one);
    }
    CHECK_EQ_INT(sh(out, sizeof out, "%s report --plot %s/g.png %s", sb_test_bin(), tmpdir, files), 0);
    for (int i = 0; i < 5; i++) CHECK_MSG(strstr(out, solvers[i]) != NULL, "report lacks %s", solvers[i]);
    CHECK(strstr(out, "| scene") != NULL || strstr(out, "|scene") != NULL);
    FILE *f = fopen(strcat(strcpy(out, tmpdir), "/g.png"), "rb");
    CHECK(f != NULL);
    if (f) {
        unsigned char m[4] = { 0 };
        CHECK(fread(m, 1, 4, f) == 4 && m[1] == 'P' && m[2] == 'N' && m[3] == 'G');
        fclose(f);
    }
    CHECK_EQ_INT(sh(out, sizeof out, "%s report --format csv %s", sb_test_bin(), files), 0);
    CHECK(strstr(out, "scene,") != NULL);
}

SB_TEST(usage_and_input_errors_exit_2)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    CHECK_EQ_INT(sh(NULL, 0, "%s run 2>/dev/null", bin), 2);
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene nowhere --method fixture_membrane --solver tr 2>/dev/null", root, bin), 2);
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene trampoline --method nosuch --solver tr 2>/dev/null", root, bin), 2);
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene trampoline --method fixture_membrane --solver nosuch 2>/dev/null", root, bin), 2);
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene trampoline --method fixture_membrane --solver tr --res -3 2>/dev/null", root, bin), 2);
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene trampoline --method fixture_membrane --solver tr --set x 2>/dev/null", root, bin), 2);
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene trampoline --method fixture_membrane --solver tr --bogus 2>/dev/null", root, bin), 2);
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene trampoline --method fixture_membrane --solver tr --samples 1 2>/dev/null", root, bin), 2);
    /* the run's own options: out of range or not a number, refused with the key named */
    static char why[4096];
    CHECK_EQ_INT(sh(why, sizeof why, "cd %s && %s run --scene trampoline --method fixture_membrane --solver tr "
                    "--set run.perturb=-1 2>&1", root, bin), 2);
    CHECK(strstr(why, "run.perturb") != NULL);
    CHECK_EQ_INT(sh(why, sizeof why, "cd %s && %s run --scene trampoline --method fixture_membrane --solver tr "
                    "--set run.checkpoint=abc 2>&1", root, bin), 2);
    CHECK(strstr(why, "run.checkpoint") != NULL);
    CHECK_EQ_INT(sh(why, sizeof why, "cd %s && %s run --scene trampoline --method fixture_membrane --solver tr "
                    "--set run.seed=1.5 2>&1", root, bin), 2);
    CHECK(strstr(why, "run.seed") != NULL);
    /* impossible combination: refused before any work, naming both sides */
    static char err[4096];
    CHECK_EQ_INT(sh(err, sizeof err, "cd %s && %s run --scene tests/scenes/fixture_static.json --method fixture_quadratic "
                    "--solver rmtr --levels 2 2>&1", root, bin), 2);
    CHECK(strstr(err, "rmtr") != NULL && strstr(err, "fixture_quadratic") != NULL);
    /* report on a file that is not a record */
    CHECK_EQ_INT(sh(NULL, 0, "%s report %s/tests/scenes/fixture_static.json 2>/dev/null >/dev/null", bin, root), 2);
    /* an unwritable output path is an input error and leaves no partial file */
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene tests/scenes/fixture_static.json --method fixture_quadratic "
                    "--solver tr --out /proc/nope/x.h5 --quiet 2>/dev/null", root, bin), 2);
}

/* run.checkpoint: a run killed mid-way leaves OUT.partial, a readable record
 * with status 2 "unfinished (checkpoint)" and the iterations so far; a run
 * that finishes to the same path removes the stale checkpoint. */
SB_TEST(killed_run_leaves_a_readable_checkpoint)
{
    static char out[1 << 14];
    char rec[512], partial[600];
    snprintf(rec, sizeof rec, "%s/ck.h5", tmpdir);
    snprintf(partial, sizeof partial, "%s.partial", rec);
    pid_t pid = fork();
    if (pid == 0) {   /* drooping, 1,083 dofs, single-level TR: hundreds of iterations */
        if (chdir(sb_test_root()) == 0)
            execl(sb_test_bin(), sb_test_bin(), "run", "--scene", "drooping", "--method", "rmtr", "--solver", "tr",
                  "--res", "16", "--out", rec, "--set", "run.checkpoint=0.01", "--quiet", (char *)NULL);
        _exit(127);
    }
    CHECK(pid > 0);
    if (pid <= 0) return;
    int seen = 0, status = 0;
    for (int i = 0; i < 30000 && !seen; i++) {    /* until the run ends, at most 10 minutes: load only slows it */
        seen = access(partial, R_OK) == 0;
        if (!seen) {
            if (waitpid(pid, &status, WNOHANG) == pid) { pid = 0; break; }   /* ended without a checkpoint */
            usleep(20000);
        }
    }
    if (pid > 0) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
    }
    CHECK_MSG(seen, "no checkpoint %s appeared while the run went on", partial);
    CHECK_MSG(access(rec, F_OK) != 0, "the killed run wrote its final record %s", rec);
    CHECK_EQ_INT(sh(out, sizeof out, "%s report --format csv %s", sb_test_bin(), partial), 0);
    CHECK_MSG(strstr(out, "unfinished (checkpoint),2,checkpoint") != NULL, "checkpoint row: %s", out);
    /* its iterations: those of the step under way (TR's history so far) */
    const char *row = strchr(out, '\n');
    int steps = -1, its = -1;
    CHECK(row && sscanf(row + 1, "drooping,rmtr,tr,1083,1,%d,%d,", &steps, &its) == 2);
    CHECK_MSG(steps >= 0 && its >= 1, "checkpoint: %d steps, %d iterations", steps, its);
    static char md[1 << 14];
    CHECK_EQ_INT(sh(md, sizeof md, "%s report %s", sb_test_bin(), partial), 0);
    CHECK(strstr(md, "| drooping | rmtr | tr | 1083 |") != NULL);
    /* checkpoints do not touch the numbers: one after every iteration gives the same run as none */
    static char a[1 << 14], b[1 << 14];
    for (int k = 0; k < 2; k++)
        CHECK_EQ_INT(sh(k ? b : a, sizeof a, "cd %s && %s run --scene trampoline --method rmtr --solver rmtr --res 8 "
                        "--levels 2 --out %s/det%d.h5 --set run.checkpoint=%s --summary json 2>/dev/null "
                        "| grep -E '^  \"(f|gnorm|iterations|work_units)\":' -A2", sb_test_root(), sb_test_bin(),
                        tmpdir, k, k ? "1e-9" : "0"), 0);
    CHECK_MSG(a[0] && strcmp(a, b) == 0, "without checkpoints: %s; with: %s", a, b);
    /* a finished run to the same path replaces it */
    /* (8 x 8: at 4 x 4 the paper's penalty leaves the fixed edges 8 % of the sag: penalty_violated) */
    CHECK_EQ_INT(sh(NULL, 0, "cd %s && %s run --scene trampoline --method rmtr --solver tr --res 8 --out %s "
                    "--set run.checkpoint=0 --quiet 2>/dev/null", sb_test_root(), sb_test_bin(), rec), 0);
    CHECK(access(rec, R_OK) == 0);
    CHECK_MSG(access(partial, F_OK) != 0, "stale checkpoint %s left beside the record", partial);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_cli_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(list_names_methods_and_solvers), SB_CASE(check_bundled_scenes_ok), SB_CASE(check_bad_scene_exit_2),
        SB_CASE(run_summary_json_contract), SB_CASE(every_solver_writes_a_record_and_report_works),
        SB_CASE(usage_and_input_errors_exit_2), SB_CASE(killed_run_leaves_a_readable_checkpoint), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
