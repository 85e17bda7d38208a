/* test_digest.c — `shellbench digest` (core/record/sb_record_digest.c,
 * docs/reproducibility.md "Committed records"): a digest reads as the same
 * run in every report (the CSV report of a dynamic run byte for byte), is
 * sealed and smaller, says what it dropped when render asks for it, and a
 * study thumbnail of a digest without its state keeps the picture drawn from
 * it before; its larger datasets are stored compressed and bit for bit
 * equal, and a digest from before compression is rewritten once;
 * checkpoints, non-records and bad options are refused. */
#include "sb_test.h"
#include "cli_sh.h"
#include "sb_record.h"
#include "sb_record_io.h"
#include "sb_render.h"
#include "sb_study_fig.h"

#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

static long size_of(const char *dir, const char *name)
{
    char p[1100];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return stat(p, &st) == 0 ? (long)st.st_size : -1;
}

/* a dynamic run (per-step surfaces kept) into tmpdir/NAME */
static int make_record(const char *name, const char *extra)
{
    return sb_sh(NULL, 0, NULL, 0, "cd %s && %s run --scene tests/scenes/membrane_dynamic.json --method fixture_membrane "
                 "--solver lsnewton --res 4 --out %s/%s --quiet %s", sb_test_root(), sb_test_bin(), tmpdir, name, extra);
}

SB_TEST(a_digest_reports_as_the_same_run)
{
    static char before[16384], after[16384], err[4096], out[4096];
    CHECK_EQ_INT(make_record("a.h5", ""), 0);
    CHECK_EQ_INT(make_record("b.h5", ""), 0);
    CHECK_EQ_INT(sb_sh(before, sizeof before, NULL, 0, "cd %s && %s report --format csv a.h5", tmpdir, sb_test_bin()), 0);
    const long full = size_of(tmpdir, "a.h5");
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s digest a.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strstr(out, "a.h5: ") != NULL);
    CHECK_EQ_INT(sb_sh(after, sizeof after, NULL, 0, "cd %s && %s report --format csv a.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strcmp(before, after) == 0);
    CHECK(size_of(tmpdir, "a.h5") < full);
    /* keeps its state: render works; a second digest changes nothing */
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "cd %s && %s render a.h5 --out a.png --size 40x30 --spp 1 --quiet", tmpdir,
                       sb_test_bin()), 0);
    const long once = size_of(tmpdir, "a.h5");
    CHECK_EQ_INT(sb_sh(out, sizeof out, NULL, 0, "cd %s && %s digest a.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strstr(out, "already a digest") != NULL);
    CHECK_EQ_INT(size_of(tmpdir, "a.h5"), once);
    /* a digest that keeps its state is slimmed by --drop-state (once): the
     * same report, smaller, and render names the dropped state */
    CHECK_EQ_INT(sb_sh(before, sizeof before, NULL, 0, "cd %s && %s report --format csv a.h5", tmpdir, sb_test_bin()), 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, NULL, 0, "cd %s && %s digest --drop-state a.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strstr(out, "already a digest") == NULL);
    CHECK_EQ_INT(sb_sh(after, sizeof after, NULL, 0, "cd %s && %s report --format csv a.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strcmp(before, after) == 0);
    CHECK(size_of(tmpdir, "a.h5") < once);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s render a.h5 --out a2.png --quiet", tmpdir, sb_test_bin()), 2);
    CHECK(strstr(err, "digest") && strstr(err, "/final/x"));
    const long slim = size_of(tmpdir, "a.h5");
    CHECK_EQ_INT(sb_sh(out, sizeof out, NULL, 0, "cd %s && %s digest --drop-state a.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strstr(out, "already a digest") != NULL);
    CHECK_EQ_INT(size_of(tmpdir, "a.h5"), slim);
    /* without its state: the same report, and render says why it cannot draw */
    CHECK_EQ_INT(sb_sh(before, sizeof before, NULL, 0, "cd %s && %s report --format csv b.h5", tmpdir, sb_test_bin()), 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "cd %s && %s digest --drop-state b.h5", tmpdir, sb_test_bin()), 0);
    CHECK_EQ_INT(sb_sh(after, sizeof after, NULL, 0, "cd %s && %s report --format csv b.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strcmp(before, after) == 0);
    CHECK(size_of(tmpdir, "b.h5") < once);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s render b.h5 --out b.png --quiet", tmpdir, sb_test_bin()), 2);
    CHECK(strstr(err, "digest") && strstr(err, "/final/x"));
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s render b.h5 --step 1 --out b.png --quiet", tmpdir,
                       sb_test_bin()), 2);
    CHECK(strstr(err, "digest") != NULL);
}

SB_TEST(a_study_picture_of_a_digest_without_state_stands)
{
    char rec[512], png[512], err[2048];
    CHECK_EQ_INT(make_record("c.h5", ""), 0);
    snprintf(rec, sizeof rec, "%s/c.h5", tmpdir);
    snprintf(png, sizeof png, "%s/thumb-c.png", tmpdir);
    CHECK_EQ_INT(sb_study_thumbnail(rec, png, err, sizeof err), 0);
    struct stat s0, s1;
    CHECK(stat(png, &s0) == 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "%s digest --drop-state %s", sb_test_bin(), rec), 0);
    CHECK_EQ_INT(sb_record_keeps_state(rec, err, sizeof err), 0);
    sleep(1);
    CHECK_EQ_INT(sb_study_thumbnail(rec, png, err, sizeof err), 0);   /* kept, not drawn again */
    CHECK(stat(png, &s1) == 0 && s1.st_mtime == s0.st_mtime);
    /* a picture of another record is not taken for it */
    char other[512];
    snprintf(other, sizeof other, "%s/thumb-other.png", tmpdir);
    CHECK_EQ_INT(make_record("d.h5", ""), 0);
    char rec_d[512];
    snprintf(rec_d, sizeof rec_d, "%s/d.h5", tmpdir);
    CHECK_EQ_INT(sb_study_thumbnail(rec_d, other, err, sizeof err), 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "cp %s %s", other, png), 0);
    CHECK(sb_study_thumbnail(rec, png, err, sizeof err) != 0);
    CHECK(strstr(err, "digest") != NULL);
}

SB_TEST(checkpoints_non_records_and_bad_options_are_refused)
{
    char err[2048];
    CHECK_EQ_INT(make_record("p.h5", "--stop-after-steps 1"), 4);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s digest p.h5.partial", tmpdir, sb_test_bin()), 2);
    /* issue 37 item 13: it said "checkpoint ... (file truncated, corrupt or not a shellbench record)" */
    CHECK_MSG(strstr(err, "checkpoint") && strstr(err, "--resume") && !strstr(err, "corrupt"), "%s", err);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "cd %s && echo hello > not.h5", tmpdir), 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s digest not.h5", tmpdir, sb_test_bin()), 2);
    CHECK(strstr(err, "not.h5") != NULL);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "cd %s && %s digest missing.h5", tmpdir, sb_test_bin()), 2);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "%s digest --keep", sb_test_bin()), 2);
    CHECK(strstr(err, "--keep") != NULL);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "%s digest", sb_test_bin()), 2);
    /* the checkpoint and the non-record are untouched */
    CHECK(size_of(tmpdir, "not.h5") == 6);
}

/* issue 37 item 13: a record in a directory the user cannot write said
 * "HDF5 failed copying it" after the copy; the directory is named first.
 * As root (who may write anywhere) the digest runs as nobody (setpriv). */
SB_TEST(an_unwritable_directory_is_named_before_any_work)
{
    char err[2048], dir[512];
    snprintf(dir, sizeof dir, "%s/ro", tmpdir);
    CHECK_EQ_INT(make_record("ro.h5", ""), 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "mkdir -p %s && mv %s/ro.h5 %s/ && chmod 644 %s/ro.h5 && chmod 555 %s && "
                       "chmod 755 %s", dir, tmpdir, dir, dir, dir, tmpdir), 0);
    const char *as = "";
    if (geteuid() == 0) {
        if (sb_sh(NULL, 0, NULL, 0, "command -v setpriv >/dev/null") != 0) {
            printf("# skipped: running as root without setpriv\n");
            return;
        }
        as = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
    }
    const long before = size_of(dir, "ro.h5");
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "%s%s digest %s/ro.h5", as, sb_test_bin(), dir), 2);
    CHECK_MSG(strstr(err, "directory") && strstr(err, "not writable") && strstr(err, "/ro") && !strstr(err, "HDF5"),
              "%s", err);
    CHECK_EQ_INT(size_of(dir, "ro.h5"), before);
    CHECK(sb_sh(NULL, 0, NULL, 0, "chmod 755 %s", dir) == 0);
}

/* dataset NAME of FILE: its values (n doubles into buf) and its filter count */
static int read_dset(const char *file, const char *name, double *buf, size_t cap, size_t *n, int *nfilters)
{
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, name, H5P_DEFAULT);
    hid_t sp = d < 0 ? -1 : H5Dget_space(d), pl = d < 0 ? -1 : H5Dget_create_plist(d);
    hssize_t np = sp < 0 ? -1 : H5Sget_simple_extent_npoints(sp);
    int rc = np < 0 || (size_t)np > cap || pl < 0 ||
             H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0;
    *n = np < 0 ? 0 : (size_t)np;
    *nfilters = pl < 0 ? -1 : H5Pget_nfilters(pl);
    if (pl >= 0) H5Pclose(pl);
    if (sp >= 0) H5Sclose(sp);
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    return rc ? -1 : 0;
}

SB_TEST(a_digest_stores_large_datasets_compressed_and_equal)
{
    static double full[65536], dig[65536];
    static char out[4096], err[1024], path[1200];
    size_t nf = 0, nd = 0;
    int ff = -1, fd = -1;
    CHECK_EQ_INT(make_record("z.h5", ""), 0);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "cd %s && cp z.h5 z_full.h5 && %s digest z.h5", tmpdir, sb_test_bin()), 0);
    snprintf(path, sizeof path, "%s/z_full.h5", tmpdir);
    CHECK_EQ_INT(read_dset(path, "/final/sample_pos", full, 65536, &nf, &ff), 0);
    snprintf(path, sizeof path, "%s/z.h5", tmpdir);
    CHECK_EQ_INT(read_dset(path, "/final/sample_pos", dig, 65536, &nd, &fd), 0);
    CHECK(nf * sizeof *full >= 4096);                 /* large enough to be compressed */
    CHECK_EQ_INT((long)nd, (long)nf);
    CHECK_EQ_INT(ff, 0);                              /* the run's record: contiguous */
    CHECK_EQ_INT(fd, 2);                              /* the digest: shuffle + deflate */
    CHECK(memcmp(full, dig, nf * sizeof *full) == 0);  /* bit for bit */
    /* a digest from before compression (no "digest_storage") is rewritten
     * once, keeps its note of what it dropped, and is then left alone */
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    CHECK(f >= 0 && H5Adelete(f, "digest_storage") >= 0);
    if (f >= 0) H5Fclose(f);
    CHECK_EQ_INT(sb_record_seal(path, err, sizeof err), 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, NULL, 0, "cd %s && %s digest z.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strstr(out, "already a digest") == NULL);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK(f >= 0 && H5Aexists(f, "digest_storage") > 0 && H5Aexists(f, "digest") > 0);
    if (f >= 0) H5Fclose(f);
    CHECK_EQ_INT(sb_sh(out, sizeof out, NULL, 0, "cd %s && %s digest z.h5", tmpdir, sb_test_bin()), 0);
    CHECK(strstr(out, "already a digest") != NULL);
    CHECK_EQ_INT(read_dset(path, "/final/sample_pos", dig, 65536, &nd, &fd), 0);
    CHECK(nd == nf && memcmp(full, dig, nf * sizeof *full) == 0);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_test_digest_%d", (int)getpid());
    mkdir(tmpdir, 0755);
    static const sb_test_case cases[] = {
        SB_CASE(a_digest_reports_as_the_same_run), SB_CASE(a_digest_stores_large_datasets_compressed_and_equal),
        SB_CASE(a_study_picture_of_a_digest_without_state_stands),
        SB_CASE(checkpoints_non_records_and_bad_options_are_refused),
        SB_CASE(an_unwritable_directory_is_named_before_any_work), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
