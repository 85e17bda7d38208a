/* test_cli_help.c — issue 28 "A CLI that explains itself": --version, help
 * for every command, `list params` with every --set key, its default, range
 * and meaning, `list scenes` with descriptions, and the progress line: live
 * on a terminal (a pseudo-terminal here) at most four times a second,
 * nothing off a terminal unless --progress. */
#define _XOPEN_SOURCE 700
#include "cli_sh.h"
#include "sb_method.h"
#include "sb_record.h"
#include "sb_solver.h"
#include "sb_test.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char err[8192], out[1 << 17];

SB_TEST(version_and_help)
{
    const char *bin = sb_test_bin();
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s --version", bin), 0);
    char fmt[64];
    snprintf(fmt, sizeof fmt, "record format %s %d", SB_RECORD_FORMAT_NAME, SB_RECORD_FORMAT_VERSION);
    CHECK_MSG(strncmp(out, "shellbench ", 11) == 0 && strstr(out, fmt), "%s", out);
    const char *cmds[] = { "run", "sweep", "check", "report", "inspect", "list" };
    const char *opts[] = { "--res N", "--scenes", "/dev/stdin", "--plot", "material state", "params" };
    for (int i = 0; i < 6; i++) {
        CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s help %s", bin, cmds[i]), 0);
        CHECK_MSG(strstr(out, "usage: shellbench") && strstr(out, cmds[i]) && strstr(out, opts[i]), "help %s: %s", cmds[i], out);
        char again[sizeof out];
        memcpy(again, out, sizeof out);
        CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s %s --help", bin, cmds[i]), 0);
        CHECK(strcmp(again, out) == 0);
    }
    /* every option `run` parses is in its help */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s help run", bin), 0);
    const char *run_opts[] = { "--scene", "--method", "--solver", "--res", "--levels", "--set", "--out", "--summary",
                               "--samples", "--resume", "--stop-after-steps", "--quiet", "--progress", "--no-progress" };
    for (int i = 0; i < 14; i++) CHECK_MSG(strstr(out, run_opts[i]), "help run lacks %s", run_opts[i]);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s help", bin), 0);
    CHECK(strstr(out, "exit codes") && strstr(out, "docs/cli.md"));
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s help frobnicate", bin), 2);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s report --format", bin), 2);
    CHECK_MSG(strstr(err, "--format needs a value"), "%s", err);
}

SB_TEST(list_params_every_key)
{
    const char *bin = sb_test_bin();
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s list params", bin), 0);
    int keys = 0;
    /* every declared key, with its meaning, is listed */
    for (const sb_param_def *d = sb_solve_params; d->name; d++, keys++) {
        char key[96];
        snprintf(key, sizeof key, "run.%s ", d->name);
        CHECK_MSG(strstr(out, key) && d->help && strlen(d->help) > 10 && strstr(out, d->help), "%s", key);
    }
    for (int i = 0; i < sb_solver_count(); i++)
        for (const sb_param_def *d = sb_solver_at(i)->params; d && d->name; d++, keys++)
            CHECK_MSG(d->help && strlen(d->help) > 10 && strstr(out, d->help), "solver %s: %s has no meaning",
                      sb_solver_at(i)->name, d->name);
    for (int i = 0; i < sb_method_count(); i++)
        for (const sb_param_def *d = sb_method_at(i)->params; d && d->name; d++, keys++)
            CHECK_MSG(d->help && strlen(d->help) > 5 && strstr(out, d->help), "method %s: %s has no meaning",
                      sb_method_at(i)->name, d->name);
    CHECK(keys > 50);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s list params bhem", bin), 0);
    CHECK_MSG(strstr(out, "method.cells_t") && strstr(out, "int [0, 4096]") && !strstr(out, "run.gtol"), "%s", out);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s list params tr", bin), 0);
    CHECK_MSG(strstr(out, "solver.trs") && strstr(out, "dogleg") && strstr(out, "{dogleg|stcg}"), "%s", out);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s list params run", bin), 0);
    CHECK_MSG(strstr(out, "run.max_memory") && strstr(out, "run.gtol "), "%s", out);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s list params nosuch", bin), 2);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s list scenes", bin), 0);
    CHECK_MSG(strstr(out, "trampoline ") && strstr(out, "'Trampoline'") && strstr(out, "plate_clamped ") &&
              strstr(out, "Timoshenko"), "%s", out);
}

/* Runs argv with stderr on a pseudo-terminal; its output into buf. */
static int run_on_pty(char *const argv[], char *buf, size_t len, double *seconds)
{
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    if (m < 0 || grantpt(m) || unlockpt(m)) return -1;
    const char *name = ptsname(m);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    pid_t pid = fork();
    if (pid == 0) {
        int s = open(name, O_RDWR | O_NOCTTY);
        int null = open("/dev/null", O_WRONLY);
        if (s < 0 || null < 0 || chdir(sb_test_root())) _exit(127);
        dup2(s, 2);
        dup2(null, 1);
        close(m);
        execv(argv[0], argv);
        _exit(127);
    }
    size_t n = 0;
    for (;;) {
        ssize_t r = read(m, buf + n, len - 1 - n);
        if (r > 0) n += (size_t)r;
        else if (r < 0 && errno == EINTR) continue;
        else break;   /* EIO once the child's end is closed */
        if (n + 1 >= len) break;
    }
    buf[n] = 0;
    int st;
    waitpid(pid, &st, 0);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    *seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    close(m);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static int count(const char *s, const char *what)
{
    int n = 0;
    for (const char *p = strstr(s, what); p; p = strstr(p + 1, what)) n++;
    return n;
}

SB_TEST(progress_line)
{
    const char *bin = sb_test_bin();
    /* drooping at 147 dofs, single-level TR: about a second of iterations (at 4 x 4 the paper's penalty
     * leaves the fixed corner more than run.penalty_tol of the sag: not judged here, docs/trust.md) */
    char *const args[] = { (char *)bin, "run", "--scene", "drooping", "--method", "rmtr", "--solver", "tr", "--res", "4",
                           "--out", "none", "--set", "run.penalty_tol=0", NULL };
    double secs = 0;
    int ec = run_on_pty(args, out, sizeof out, &secs);
    CHECK_EQ_INT(ec, 0);
    int updates = count(out, "\033[K");
    CHECK_MSG(updates >= 1 && strstr(out, "drooping/rmtr/tr step ") && strstr(out, ", iteration ") &&
              strstr(out, "|g| = ") && strstr(out, "radius ") && strstr(out, " iterations, "),
              "no progress line on a terminal (%d updates in %.1f s):\n%s", updates, secs, out);
    /* at most four a second (cleared lines count too: one per step line, one at the end) */
    CHECK_MSG(updates <= 2 * (4.0 * secs + 1) + 12, "%d updates in %.1f s", updates, secs);
    CHECK(strstr(out, "step 5/5: ") != NULL);   /* the step lines are still there */
    /* off a terminal: nothing unless asked */
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s run --scene drooping --method rmtr --solver tr --res 4 --out none "
                       "--set run.penalty_tol=0",
                       sb_test_root(), bin), 0);
    CHECK_MSG(!strstr(err, ", iteration ") && !strstr(err, "\033["), "%s", err);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s run --scene drooping --method rmtr --solver tr --res 4 --out none "
                       "--set run.penalty_tol=0 --progress --quiet", sb_test_root(), bin), 0);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    int lines = count(err, ", iteration ");
    CHECK_MSG(lines >= 1 && lines <= secs + 2 && !strstr(err, "\033[") && !strstr(err, "\r"), "%d lines in %.1f s: %s",
              lines, secs, err);
    /* --quiet on a terminal: no line */
    char *const quiet[] = { (char *)bin, "run", "--scene", "drooping", "--method", "rmtr", "--solver", "tr", "--res", "4",
                            "--out", "none", "--quiet", "--set", "run.penalty_tol=0", NULL };
    CHECK_EQ_INT(run_on_pty(quiet, out, sizeof out, &secs), 0);
    CHECK_MSG(!strstr(out, ", iteration "), "%s", out);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(version_and_help), SB_CASE(list_params_every_key), SB_CASE(progress_line), SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
