/* test_regress_safety.c — issue 37 items 1, 2, 8 and 10: what the commands
 * write and read is checked before any work.
 *
 *   links    regress refuses a report, history, baseline (--update-baseline),
 *            picture or history plot that is a symbolic link, exit 2 before
 *            any run, and leaves link and target as they were
 *   FIFOs    report --study, sweep --study, regress --suite, --baseline and
 *            --history given a FIFO are refused at once (not hung), with a
 *            sentence naming the option and the path
 *   outputs  regress --history DIR/, --out FILE; a study whose records
 *            directory cannot be made; render --out nodir/x.png; report
 *            --plot nodir/x.png: refused before the work (exit 2)
 *   locks    digest refuses a record whose lock a writer holds; a sweep
 *            refuses a record whose .lock is a symbolic link before any run;
 *            the lock files a killed regress leaves are removed by the next
 *            one, and a second regress on the same records is refused;
 *            sb_output_lock_clear_stale removes only a lock nobody holds.
 * Every command that could hang runs under `timeout`; nothing here depends on
 * how fast the machine is. */
#include "cli_sh.h"
#include "sb_common.h"
#include "sb_output.h"
#include "sb_test.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char tmpdir[256], out[1 << 17], err[16384];

static int is_link(const char *p) { struct stat st; return lstat(p, &st) == 0 && S_ISLNK(st.st_mode); }
static int exists(const char *p) { struct stat st; return lstat(p, &st) == 0; }

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static int file_is(const char *path, const char *text)
{
    char buf[256];
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    return !strcmp(buf, text);
}

/* a one-case suite (trampoline, bhem, lsnewton at res) with records in DIR/rec */
static void suite(const char *dir, int res, char *path, size_t len)
{
    char text[1024];
    snprintf(path, len, "%s/suite.json", dir);
    snprintf(text, sizeof text, "{\"study\": \"tiny\", \"records\": \"%s/rec\", \"scenes\": [{\"scene\": \"trampoline\", "
             "\"solution\": \"unique\"}], \"methods\": [\"bhem\"], \"solvers\": [\"lsnewton\"], \"res\": [%d]}\n", dir, res);
    write_file(path, text);
}

static void subdir(const char *name, char *path, size_t len)
{
    snprintf(path, len, "%s/%s", tmpdir, name);
    mkdir(path, 0777);
}

/* number of files under dir whose name ends in suffix (depth <= 5) */
static int count_files(const char *dir, const char *suffix, int depth)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char p[1024];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat st;
        if (lstat(p, &st)) continue;
        size_t L = strlen(e->d_name), s = strlen(suffix);
        if (L >= s && !strcmp(e->d_name + L - s, suffix)) n++;
        if (S_ISDIR(st.st_mode) && depth > 0) n += count_files(p, suffix, depth - 1);
    }
    closedir(d);
    return n;
}

/* `timeout 600` (here and below) only stops a hang (the FIFO and lock cases): generous, so that a heavily
 * loaded machine (load average 25-45 seen under 7 parallel builds) never turns slowness into a failure */
#define REGRESS "cd %s && timeout 600 %s regress --repeat 2 --quiet --no-confirm"

/* item 1: regress writes through no symbolic link */
SB_TEST(regress_refuses_links)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char d[300], s[400], target[400], o[400], link[500], rec[400];
    subdir("links", d, sizeof d);
    suite(d, 4, s, sizeof s);
    snprintf(target, sizeof target, "%s/v", d);
    snprintf(rec, sizeof rec, "%s/rec", d);
    write_file(target, "precious");
    /* the report: mkdir o; ln -s ../v o/report.md */
    snprintf(o, sizeof o, "%s/o", d);
    mkdir(o, 0777);
    snprintf(link, sizeof link, "%s/report.md", o);
    CHECK(symlink("../v", link) == 0);
    int ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s/b.json --update-baseline "
                   "--history %s/h.csv --out %s", root, bin, s, d, d, o);
    CHECK_MSG(ec == 2 && strstr(err, "--out") && strstr(err, link) && strstr(err, "symbolic link"), "exit %d: %s", ec, err);
    CHECK(is_link(link) && file_is(target, "precious") && !exists(rec));
    unlink(link);
    /* the history: appended through the link before */
    snprintf(link, sizeof link, "%s/h.csv", d);
    CHECK(symlink("v", link) == 0);
    ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s/b.json --update-baseline "
               "--history %s --out %s", root, bin, s, d, link, o);
    CHECK_MSG(ec == 2 && strstr(err, "--history") && strstr(err, "symbolic link"), "exit %d: %s", ec, err);
    CHECK(is_link(link) && file_is(target, "precious") && !exists(rec));
    unlink(link);
    /* the baseline to write: the link was replaced before */
    snprintf(link, sizeof link, "%s/b.json", d);
    CHECK(symlink("v", link) == 0);
    ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s --update-baseline "
               "--history %s/h.csv --out %s", root, bin, s, link, d, o);
    CHECK_MSG(ec == 2 && strstr(err, "--baseline") && strstr(err, "symbolic link"), "exit %d: %s", ec, err);
    CHECK(is_link(link) && file_is(target, "precious") && !exists(rec));
    unlink(link);
    /* the picture of the scene and the case's history plot */
    const char *figs[] = { "final-trampoline.png", "history-trampoline_bhem-lsnewton-r4.png",
                           "history-trampoline_bhem-lsnewton-r4.svg" };
    for (int k = 0; k < 3; k++) {
        snprintf(link, sizeof link, "%s/%s", o, figs[k]);
        CHECK(symlink("../v", link) == 0);
        ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s/b.json --update-baseline "
                   "--history %s/h.csv --out %s", root, bin, s, d, d, o);
        CHECK_MSG(ec == 2 && strstr(err, figs[k]) && strstr(err, "symbolic link"), "%s: exit %d: %s", figs[k], ec, err);
        CHECK(is_link(link) && file_is(target, "precious") && !exists(rec));
        unlink(link);
    }
    /* with none of them a link, the same command works */
    ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s/b.json --update-baseline "
               "--history %s/h.csv --out %s", root, bin, s, d, d, o);
    CHECK_MSG(ec == 0, "exit %d: %s", ec, err);
    CHECK(file_is(target, "precious"));
}

/* item 2: a FIFO given as an input is refused at once */
SB_TEST(fifo_inputs_refused_at_once)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char d[300], s[400], fifo[400];
    subdir("fifo", d, sizeof d);
    suite(d, 4, s, sizeof s);
    snprintf(fifo, sizeof fifo, "%s/f", d);
    CHECK(mkfifo(fifo, 0644) == 0);
    struct { const char *cmd, *opt; } c[] = {
        { "report --study %s", "--study" },
        { "sweep --study %s", "--study" },
        { "regress --suite %s --baseline /nonexistent.json --update-baseline --no-history --out %s/o", "--suite" },
        { "regress --suite %s/suite.json --baseline %s --out %s/o --no-history", "--baseline" },
        { "regress --suite %s/suite.json --baseline %s/none.json --update-baseline --history %s --out %s/o", "--history" },
    };
    for (size_t k = 0; k < sizeof c / sizeof *c; k++) {
        char args[2000];
        if (k < 2) snprintf(args, sizeof args, c[k].cmd, fifo);
        else if (k == 2) snprintf(args, sizeof args, c[k].cmd, fifo, d);
        else if (k == 3) snprintf(args, sizeof args, c[k].cmd, d, fifo, d);
        else snprintf(args, sizeof args, c[k].cmd, d, d, fifo, d);
        /* before: blocked until `timeout` (exit 124) */
        int ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && timeout 600 %s %s", root, bin, args);
        CHECK_MSG(ec == 2 && strstr(err, c[k].opt) && strstr(err, fifo) && strstr(err, "FIFO"), "%s: exit %d: %s",
                  args, ec, err);
    }
    CHECK(!exists(d) || access(fifo, F_OK) == 0);
    char rec[400];
    snprintf(rec, sizeof rec, "%s/rec", d);
    CHECK_MSG(!exists(rec), "a run was made");
    /* the reader itself: regular files only, a missing file named */
    FILE *f = sb_input_open(fifo, "study file", err, sizeof err);
    CHECK(!f && strstr(err, "FIFO"));
    f = sb_input_open("/nonexistent/x.json", "study file", err, sizeof err);
    CHECK(!f && strstr(err, "/nonexistent/x.json") && strstr(err, "No such file"));
    f = sb_input_open(s, "study file", err, sizeof err);
    CHECK(f != NULL);
    if (f) fclose(f);
}

/* item 8: outputs that cannot be written are found before the work */
SB_TEST(outputs_checked_before_work)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char d[300], s[400], file[400], rec[400], hdir[400];
    subdir("outs", d, sizeof d);
    suite(d, 4, s, sizeof s);
    snprintf(file, sizeof file, "%s/plain", d);
    write_file(file, "x");
    snprintf(rec, sizeof rec, "%s/rec", d);
    snprintf(hdir, sizeof hdir, "%s/hdir", d);
    mkdir(hdir, 0777);
    /* regress --history DIR/: refused before any run (before: exit 3 after every run) */
    int ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s/b.json --update-baseline "
                   "--history %s/ --out %s/o", root, bin, s, d, hdir, d);
    CHECK_MSG(ec == 2 && strstr(err, "--history") && strstr(err, "directory"), "exit %d: %s", ec, err);
    CHECK(!exists(rec));
    /* regress --out FILE */
    ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s/b.json --update-baseline "
               "--history %s/h.csv --out %s", root, bin, s, d, d, file);
    CHECK_MSG(ec == 2 && strstr(err, "--out") && strstr(err, file) && strstr(err, "not a directory"), "exit %d: %s", ec, err);
    CHECK(!exists(rec) && file_is(file, "x"));
    /* a study whose records directory cannot be made (under a regular file):
     * refused before the first run (before: exit 3 after trying every run) */
    char study[400], text[1024];
    snprintf(study, sizeof study, "%s/study.json", d);
    snprintf(text, sizeof text, "{\"study\": \"s\", \"records\": \"%s/rec\", \"scenes\": [{\"scene\": \"trampoline\", "
             "\"solution\": \"unique\"}], \"methods\": [\"bhem\"], \"solvers\": [\"lsnewton\", \"tr\"], \"res\": [4]}\n", file);
    write_file(study, text);
    ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && timeout 600 %s sweep --study %s", root, bin, study);
    CHECK_MSG(ec == 2 && strstr(err, "not a directory") && strstr(err, "nothing was run") && !strstr(out, "[1/"),
              "exit %d: %s%s", ec, out, err);
    /* render --out nodir/x.png, report --plot nodir/x.png: before the render, before gnuplot */
    char r[400];
    snprintf(r, sizeof r, "%s/r.h5", d);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s run --scene trampoline --method bhem --solver tr --res 4 "
                       "--quiet --out %s", root, bin, r), 0);
    ec = sb_sh(out, sizeof out, err, sizeof err, "%s render %s --out %s/nodir/x.png", bin, r, d);
    CHECK_MSG(ec == 2 && strstr(err, "nodir") && strstr(err, "does not exist"), "exit %d: %s", ec, err);
    ec = sb_sh(out, sizeof out, err, sizeof err, "%s render %s --out %s/x.png", bin, r, file);
    CHECK_MSG(ec == 2 && strstr(err, "not a directory"), "exit %d: %s", ec, err);
    ec = sb_sh(out, sizeof out, err, sizeof err, "%s report --plot %s/nodir/x.png %s", bin, d, r);
    CHECK_MSG(ec == 2 && strstr(err, "nodir") && strstr(err, "does not exist") && !strstr(err, "gnuplot"), "exit %d: %s",
              ec, err);
    /* the library checks themselves */
    CHECK(sb_output_check_dir(file, "records", err, sizeof err) == SB_ERR_INPUT && strstr(err, "not a directory"));
    snprintf(text, sizeof text, "%s/new/deeper", d);
    CHECK(sb_output_check_dir(text, "records", err, sizeof err) == SB_OK);   /* made when needed */
    snprintf(text, sizeof text, "%s/new/x.png", d);
    CHECK(sb_output_check_file_dir(text, "image", 1, err, sizeof err) == SB_ERR_INPUT && strstr(err, "does not exist"));
    CHECK(sb_output_check_file_dir(text, "image", 0, err, sizeof err) == SB_OK);
}

/* item 10: locks */
SB_TEST(digest_respects_the_lock)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char r[400];
    snprintf(r, sizeof r, "%s/locked.h5", tmpdir);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s run --scene trampoline --method bhem --solver tr --res 4 "
                       "--quiet --out %s", root, bin, r), 0);
    struct stat a, b;
    CHECK(stat(r, &a) == 0);
    /* a writer holds the record's lock (as a run does while it writes) */
    sb_output_lock lk;
    CHECK_EQ_INT(sb_output_lock_take(&lk, r, err, sizeof err), SB_OK);
    int ec = sb_sh(out, sizeof out, err, sizeof err, "%s digest %s", bin, r);
    char want[64];
    snprintf(want, sizeof want, "process %ld", (long)getpid());
    CHECK_MSG(ec == 2 && strstr(err, "being written") && strstr(err, want), "exit %d: %s", ec, err);
    CHECK(stat(r, &b) == 0 && a.st_ino == b.st_ino && a.st_size == b.st_size && a.st_mtime == b.st_mtime);
    sb_output_lock_release(&lk);
    /* free again: digested, and its lock file gone */
    ec = sb_sh(out, sizeof out, err, sizeof err, "%s digest %s", bin, r);
    CHECK_MSG(ec == 0, "exit %d: %s", ec, err);
    char lock[500];
    snprintf(lock, sizeof lock, "%s.lock", r);
    CHECK(!exists(lock));
}

SB_TEST(sweep_refuses_linked_lock)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char d[300], study[400], text[1024], lock[600], rdir[500];
    subdir("swlock", d, sizeof d);
    snprintf(study, sizeof study, "%s/study.json", d);
    snprintf(text, sizeof text, "{\"study\": \"s\", \"records\": \"%s/rec\", \"scenes\": [{\"scene\": \"trampoline\", "
             "\"solution\": \"unique\"}], \"methods\": [\"bhem\"], \"solvers\": [\"lsnewton\", \"tr\"], \"res\": [4]}\n", d);
    write_file(study, text);
    snprintf(rdir, sizeof rdir, "%s/rec", d);
    mkdir(rdir, 0777);
    snprintf(rdir, sizeof rdir, "%s/rec/trampoline", d);
    mkdir(rdir, 0777);
    snprintf(lock, sizeof lock, "%s/bhem-tr-r4.h5.lock", rdir);
    CHECK(symlink("/dev/null", lock) == 0);
    int ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && timeout 600 %s sweep --study %s", root, bin, study);
    CHECK_MSG(ec == 2 && strstr(err, lock) && strstr(err, "symbolic link") && count_files(rdir, ".h5", 0) == 0,
              "exit %d: %s%s", ec, out, err);
    CHECK(is_link(lock));
    /* the list sweep's own pre-check too */
    char dir2[400], lock2[600];
    snprintf(dir2, sizeof dir2, "%s/list", d);
    mkdir(dir2, 0777);
    snprintf(lock2, sizeof lock2, "%s/trampoline-bhem-tr-r4-l1.h5.lock", dir2);
    CHECK(symlink("/dev/null", lock2) == 0);
    ec = sb_sh(out, sizeof out, err, sizeof err, "cd %s && timeout 600 %s sweep --scenes trampoline --methods bhem "
               "--solvers lsnewton,tr --res 4 --dir %s --quiet", root, bin, dir2);
    CHECK_MSG(ec == 2 && strstr(err, "symbolic link") && count_files(dir2, ".h5", 0) == 0, "exit %d: %s%s", ec, out, err);
    CHECK(is_link(lock2));
}

/* 1 when nobody holds the lock file's flock (its writer is gone) */
static int lock_free(const char *path)
{
    int fd = open(path, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return 1;
    int ok = flock(fd, LOCK_EX | LOCK_NB) == 0;
    close(fd);
    return ok;
}

/* the first lock file under dir (depth <= 4), or "" */
static void find_lock(const char *dir, int depth, char *buf, size_t len)
{
    DIR *dd = opendir(dir);
    if (!dd) return;
    struct dirent *e;
    while (!buf[0] && (e = readdir(dd))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char p[1024];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        size_t L = strlen(e->d_name);
        if (L > 5 && !strcmp(e->d_name + L - 5, ".lock")) snprintf(buf, len, "%s", p);
        else if (depth > 0) find_lock(p, depth - 1, buf, len);
    }
    closedir(dd);
}

SB_TEST(killed_regress_leaves_no_lock_behind)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char d[300], s[400], rec[400], base[400], o[400], h[400];
    subdir("killed", d, sizeof d);
    suite(d, 8, s, sizeof s);
    snprintf(rec, sizeof rec, "%s/rec", d);
    snprintf(base, sizeof base, "%s/b.json", d);
    snprintf(o, sizeof o, "%s/o", d);
    snprintf(h, sizeof h, "%s/h.csv", d);
    pid_t pid = fork();
    if (pid == 0) {
        if (chdir(root) == 0) {
            int devnull = open("/dev/null", O_WRONLY);
            if (devnull >= 0) dup2(devnull, STDOUT_FILENO), dup2(devnull, STDERR_FILENO);
            execl(bin, bin, "regress", "--suite", s, "--baseline", base, "--update-baseline", "--history", h, "--out", o,
                  "--repeat", "8", "--quiet", (char *)NULL);
        }
        _exit(127);
    }
    CHECK(pid > 0);
    if (pid <= 0) return;
    /* wait for a run's lock, then kill regress (its runs die with it) */
    char lock[1024] = "";
    int status;
    /* bounded by regress itself ending (waitpid below), else 10 minutes: a loaded machine only makes it slower */
    for (int i = 0; i < 120000 && !lock[0]; i++) {
        find_lock(rec, 4, lock, sizeof lock);
        if (!lock[0]) usleep(5000);
        if (waitpid(pid, &status, WNOHANG) == pid) { pid = 0; break; }
    }
    CHECK_MSG(lock[0] && pid > 0, "no run's lock seen under %s while regress ran", rec);
    if (pid > 0) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        for (int i = 0; i < 60000 && !lock_free(lock); i++) usleep(10000);   /* the run dies with its parent (10 min bound) */
        CHECK_MSG(lock_free(lock), "the run of the killed regress still holds %s", lock);
    }
    /* and a stale lock of some earlier invocation's later round, with a dead pid in it */
    char old[600], olddir[500];
    snprintf(olddir, sizeof olddir, "%s/rep7/trampoline", rec);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "mkdir -p %s", olddir), 0);
    snprintf(old, sizeof old, "%s/bhem-lsnewton-r8.h5.lock", olddir);
    write_file(old, "999999999\n");
    /* while another invocation holds the records, a second one is refused */
    sb_output_lock lk;
    CHECK_EQ_INT(sb_output_lock_take(&lk, rec, err, sizeof err), SB_OK);
    int ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s --update-baseline --history %s "
                   "--out %s", root, bin, s, base, h, o);
    CHECK_MSG(ec == 2 && strstr(err, "being written"), "exit %d: %s", ec, err);
    sb_output_lock_release(&lk);
    /* the next invocation reclaims the stale locks: none is left behind */
    ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s --update-baseline --history %s "
               "--out %s", root, bin, s, base, h, o);
    CHECK_MSG(ec == 0, "exit %d: %s", ec, err);
    char left[1024] = "";
    find_lock(rec, 4, left, sizeof left);
    CHECK_MSG(!left[0], "lock left behind: %s", left);
    char reclock[500];
    snprintf(reclock, sizeof reclock, "%s.lock", rec);
    CHECK(!exists(reclock));
    /* a live writer's lock in the records is not taken from it */
    char live[500];
    snprintf(live, sizeof live, "%s/rep1/trampoline/bhem-lsnewton-r8.h5", rec);
    CHECK_EQ_INT(sb_output_lock_take(&lk, live, err, sizeof err), SB_OK);
    ec = sb_sh(out, sizeof out, err, sizeof err, REGRESS " --suite %s --baseline %s --update-baseline --history %s "
               "--out %s", root, bin, s, base, h, o);
    CHECK_MSG(ec == 2 && strstr(err, "being written"), "exit %d: %s", ec, err);
    sb_output_lock_release(&lk);
}

/* the library side: a stale lock file is removed, a held one is not, a linked one is refused */
SB_TEST(stale_lock_helpers)
{
    char rec[400], lock[500];
    snprintf(rec, sizeof rec, "%s/stale.h5", tmpdir);
    snprintf(lock, sizeof lock, "%s.lock", rec);
    write_file(lock, "999999999\n");   /* a writer that is gone */
    CHECK_EQ_INT(sb_output_check_lockfile(rec, err, sizeof err), SB_OK);
    CHECK_EQ_INT(sb_output_lock_clear_stale(rec, err, sizeof err), SB_OK);
    CHECK(!exists(lock));
    CHECK_EQ_INT(sb_output_lock_clear_stale(rec, err, sizeof err), SB_OK);   /* none: nothing to do */
    sb_output_lock lk;
    CHECK_EQ_INT(sb_output_lock_take(&lk, rec, err, sizeof err), SB_OK);
    char want[64];
    snprintf(want, sizeof want, "process, %ld", (long)getpid());
    CHECK_EQ_INT(sb_output_lock_clear_stale(rec, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "being written") && strstr(err, want), "%s", err);
    CHECK(exists(lock));
    sb_output_lock_release(&lk);
    CHECK(symlink("/dev/null", lock) == 0);
    CHECK_EQ_INT(sb_output_check_lockfile(rec, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "symbolic link") && strstr(err, lock), "%s", err);
    CHECK_EQ_INT(sb_output_lock_clear_stale(rec, err, sizeof err), SB_ERR_INPUT);
    CHECK(is_link(lock));
    unlink(lock);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_regress_safety_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(regress_refuses_links), SB_CASE(fifo_inputs_refused_at_once), SB_CASE(outputs_checked_before_work),
        SB_CASE(digest_respects_the_lock), SB_CASE(sweep_refuses_linked_lock), SB_CASE(stale_lock_helpers),
        SB_CASE(killed_regress_leaves_no_lock_behind),
        SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
