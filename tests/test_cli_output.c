/* test_cli_output.c — issue 28 items 2-4: output safety.  Records, XDMF
 * sidecars, checkpoints and plots are written only to new paths or regular
 * files; /dev/null is like none; FIFOs, devices and symbolic links are
 * refused with a sentence and left as they were; an output that cannot be
 * created is found before any work; a second run on the same --out is
 * refused naming the first one's pid, and the lock a killed run leaves is
 * taken over. */
#include "cli_sh.h"
#include "sb_common.h"
#include "sb_output.h"
#include "sb_test.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char tmpdir[256], err[8192], out[1 << 16];

#define QUICK "run --scene trampoline --method bhem --solver tr --res 4 --quiet"

static int is_fifo(const char *p) { struct stat st; return lstat(p, &st) == 0 && S_ISFIFO(st.st_mode); }
static int is_link(const char *p) { struct stat st; return lstat(p, &st) == 0 && S_ISLNK(st.st_mode); }
static int is_chr(const char *p) { struct stat st; return lstat(p, &st) == 0 && S_ISCHR(st.st_mode); }

SB_TEST(null_device_is_none)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    /* as root, this replaced /dev/null with a regular file */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s " QUICK " --out /dev/null --summary json", root, bin), 0);
    CHECK(is_chr("/dev/null"));
    CHECK_MSG(strstr(out, "\"file\": null"), "%s", out);
    CHECK(access("/dev/null.lock", F_OK) != 0 && access("/dev/null.partial", F_OK) != 0);
    sb_output_kind k;
    CHECK(sb_output_check("/dev/null", "record", &k, err, sizeof err) == SB_OK && k == SB_OUTPUT_DISCARD);
    /* another device is refused (checked, never written) */
    CHECK(sb_output_check("/dev/zero", "record", &k, err, sizeof err) == SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "character device"), "%s", err);
    CHECK(sb_output_check(tmpdir, "record", &k, err, sizeof err) == SB_ERR_INPUT && strstr(err, "directory"));
    /* --resume needs a real record path */
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out /dev/null --resume", root, bin), 2);
}

SB_TEST(fifo_and_symlink_outputs_refused)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char fifo[512], target[512], link[512], xdmf_fifo[512], plink[600], rec[512];
    snprintf(fifo, sizeof fifo, "%s/fifo.h5", tmpdir);
    CHECK(mkfifo(fifo, 0644) == 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, fifo), 2);
    CHECK_MSG(strstr(err, "FIFO") && strstr(err, fifo), "%s", err);
    CHECK(is_fifo(fifo));
    /* a symbolic link, even to a regular file: refused, link and target untouched */
    snprintf(target, sizeof target, "%s/target.h5", tmpdir);
    snprintf(link, sizeof link, "%s/link.h5", tmpdir);
    FILE *f = fopen(target, "w");
    CHECK(f && fputs("precious", f) >= 0);
    if (f) fclose(f);
    CHECK(symlink(target, link) == 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, link), 2);
    CHECK_MSG(strstr(err, "symbolic link"), "%s", err);
    CHECK(is_link(link));
    CHECK_EQ_INT(sb_sh(out, sizeof out, NULL, 0, "cat %s", target), 0);
    CHECK(strcmp(out, "precious") == 0);
    /* the sidecar and the checkpoint paths are checked too */
    snprintf(rec, sizeof rec, "%s/side.h5", tmpdir);
    snprintf(xdmf_fifo, sizeof xdmf_fifo, "%s/side.xdmf", tmpdir);
    CHECK(mkfifo(xdmf_fifo, 0644) == 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, rec), 2);
    CHECK_MSG(strstr(err, "XDMF sidecar") && strstr(err, "FIFO"), "%s", err);
    CHECK(is_fifo(xdmf_fifo) && access(rec, F_OK) != 0);
    /* and the time-series sidecar (RUN.steps.xdmf) */
    snprintf(rec, sizeof rec, "%s/series.h5", tmpdir);
    snprintf(xdmf_fifo, sizeof xdmf_fifo, "%s/series.steps.xdmf", tmpdir);
    CHECK(symlink(target, xdmf_fifo) == 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, rec), 2);
    CHECK_MSG(strstr(err, "time-series sidecar") && strstr(err, "symbolic link"), "%s", err);
    CHECK(is_link(xdmf_fifo) && access(rec, F_OK) != 0);
    snprintf(rec, sizeof rec, "%s/ck.h5", tmpdir);
    snprintf(plink, sizeof plink, "%s.partial", rec);
    CHECK(symlink(target, plink) == 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, rec), 2);
    CHECK_MSG(strstr(err, "checkpoint") && strstr(err, "symbolic link"), "%s", err);
    CHECK(is_link(plink));
    /* a regular file is replaced as before, and the lock is gone afterwards */
    snprintf(rec, sizeof rec, "%s/ok.h5", tmpdir);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "echo old > %s", rec), 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, rec), 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "h5dump -H %s", rec), 0);
    char lock[600];
    snprintf(lock, sizeof lock, "%s.lock", rec);
    CHECK(access(lock, F_OK) != 0);
}

SB_TEST(plot_outputs)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char rec[512], p[600];
    snprintf(rec, sizeof rec, "%s/plotme.h5", tmpdir);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "cd %s && %s " QUICK " --out %s", root, bin, rec), 0);
    snprintf(p, sizeof p, "%s/plot.png", tmpdir);
    CHECK(mkfifo(p, 0644) == 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s report --plot %s %s", bin, p, rec), 2);
    CHECK_MSG(strstr(err, "FIFO") && out[0] == 0 && is_fifo(p), "%s", err);
    snprintf(p, sizeof p, "%s/plot.gif", tmpdir);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s report --plot %s %s", bin, p, rec), 2);
    CHECK_MSG(strstr(err, ".png, .svg or .jpg") && access(p, F_OK) != 0, "%s", err);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s report --plot /dev/null %s", bin, rec), 0);
    CHECK(is_chr("/dev/null") && strstr(out, "| trampoline |"));
    /* --plot x.jpg writes a JPEG (or says why not) */
    snprintf(p, sizeof p, "%s/plot.jpg", tmpdir);
    int ec = sb_sh(out, sizeof out, err, sizeof err, "%s report --plot %s %s", bin, p, rec);
    if (ec == 0) {
        unsigned char m[3] = { 0 };
        FILE *f = fopen(p, "rb");
        CHECK(f && fread(m, 1, 3, f) == 3 && m[0] == 0xFF && m[1] == 0xD8 && m[2] == 0xFF);
        if (f) fclose(f);
    } else {
        CHECK_MSG(ec == 3 && strstr(err, "plot") && access(p, F_OK) != 0, "exit %d: %s", ec, err);
    }
    /* a plot that cannot be made is an error (3), the table is still written */
    snprintf(p, sizeof p, "%s/plot.png", tmpdir);
    unlink(p);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "SB_GNUPLOT=/nonexistent/gnuplot %s report --plot %s %s", bin, p,
                       rec), 3);
    CHECK(strstr(out, "| trampoline |") && strstr(err, "not installed"));
}

/* item 3: an output that cannot be created is found before any work */
SB_TEST(unwritable_output_found_before_work)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char file[512];
    snprintf(file, sizeof file, "%s/plainfile", tmpdir);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "touch %s", file), 0);
    /* drooping at 1,083 dofs would take seconds: the refusal comes first */
    int ec = sb_sh(NULL, 0, err, sizeof err, "cd %s && %s run --scene drooping --method rmtr --solver tr --res 16 "
                   "--out %s/sub/r.h5", root, bin, file);
    CHECK_EQ_INT(ec, 2);
    CHECK_MSG(strstr(err, "not a directory") && !strstr(err, "step 1"), "%s", err);
    if (geteuid() != 0) {   /* permissions do not bind root */
        char ro[512];
        snprintf(ro, sizeof ro, "%s/ro", tmpdir);
        CHECK(mkdir(ro, 0555) == 0);
        ec = sb_sh(NULL, 0, err, sizeof err, "cd %s && %s run --scene drooping --method rmtr --solver tr --res 16 "
                   "--out %s/r.h5", root, bin, ro);
        CHECK_EQ_INT(ec, 2);
        CHECK_MSG(strstr(err, "lock file") && !strstr(err, "step 1"), "%s", err);
    }
}

/* item 4: one writer per record */
SB_TEST(second_writer_refused_and_stale_lock_recovered)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char rec[512], lock[600];
    snprintf(rec, sizeof rec, "%s/shared.h5", tmpdir);
    snprintf(lock, sizeof lock, "%s.lock", rec);
    pid_t pid = fork();
    if (pid == 0) {   /* a run of some seconds: drooping, 1,083 dofs, single-level TR */
        if (chdir(root) == 0)
            execl(bin, bin, "run", "--scene", "drooping", "--method", "rmtr", "--solver", "tr", "--res", "16", "--out",
                  rec, "--quiet", (char *)NULL);
        _exit(127);
    }
    CHECK(pid > 0);
    if (pid <= 0) return;
    int seen = 0, status;
    for (int i = 0; i < 60000 && !seen; i++) {   /* its lock appears at once, before the method is built; the
                                                   bound (10 minutes) only stops a hang on a heavily loaded machine */
        seen = access(lock, F_OK) == 0;
        if (!seen) usleep(10000);
    }
    CHECK_MSG(seen, "no lock %s", lock);
    int ec = sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, rec);
    int still = waitpid(pid, &status, WNOHANG) == 0;
    if (still) {   /* the first run was still going: the second must have been refused, naming it */
        char want[64];
        snprintf(want, sizeof want, "process %ld", (long)pid);
        CHECK_EQ_INT(ec, 2);
        CHECK_MSG(strstr(err, want) && strstr(err, "being written"), "%s", err);
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        CHECK_MSG(access(lock, F_OK) == 0, "a killed run's lock file stays behind (stale)");
    }
    CHECK_MSG(still, "the first run ended before the second started; the test needs it running");
    /* the stale lock of the dead process does not block the next run */
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s " QUICK " --out %s", root, bin, rec), 0);
    CHECK(access(rec, R_OK) == 0 && access(lock, F_OK) != 0);
    /* in one process: the lock is exclusive per open, and released */
    sb_output_lock a, b;
    CHECK_EQ_INT(sb_output_lock_take(&a, rec, err, sizeof err), SB_OK);
    CHECK_EQ_INT(sb_output_lock_take(&b, rec, err, sizeof err), SB_ERR_INPUT);
    char want[64];
    snprintf(want, sizeof want, "process %ld", (long)getpid());
    CHECK_MSG(strstr(err, want), "%s", err);
    sb_output_lock_release(&a);
    CHECK(access(lock, F_OK) != 0);
    CHECK_EQ_INT(sb_output_lock_take(&b, rec, err, sizeof err), SB_OK);
    sb_output_lock_release(&b);
    /* a lock file that is a symbolic link is not followed */
    CHECK(symlink("/dev/null", lock) == 0);
    CHECK_EQ_INT(sb_output_lock_take(&a, rec, err, sizeof err), SB_ERR_INPUT);
    CHECK(is_link(lock));
    unlink(lock);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_cli_out_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(null_device_is_none), SB_CASE(fifo_and_symlink_outputs_refused), SB_CASE(plot_outputs),
        SB_CASE(unwritable_output_found_before_work), SB_CASE(second_writer_refused_and_stale_lock_recovered), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "chmod -R u+w %s; rm -rf %s", tmpdir, tmpdir);
    if (system(cmd)) {}
    return rc;
}
