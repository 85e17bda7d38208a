/* fuzz_record.c — libFuzzer harness of the run-record readers (`make fuzz`,
 * docs/cli.md "Fuzzing").  The input is written to a file and read back
 * with every reader (summary, set-up for inspect, sample grid); each must
 * return SB_OK or an error naming the file, and leave no HDF5 object open
 * (a handle left open aborts).  HDF5's own leak on malformed files
 * (HDFGroup/hdf5#6677; bounded) is suppressed (tests/lsan.supp).  Seeds:
 * small records, checkpoints and non-records made by `make fuzz`. */
#include "sb_record.h"

#include <hdf5.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char path[64];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    sb_record_library_init();
    /* a file in memory where there is a tmpfs for it */
    snprintf(path, sizeof path, "%s/sb_fuzz_record_%ld.h5", access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp",
             (long)getpid());
    return 0;
}

static void check_closed(const char *who)
{
    ssize_t n = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
    if (n != 0) {
        fprintf(stderr, "fuzz_record: %s left %ld HDF5 objects open\n", who, (long)n);
        abort();
    }
}

static void check_message(int rc, const char *err)
{
    if (rc != SB_OK && !strstr(err, path) && !strstr(err, "out of memory")) {
        fprintf(stderr, "fuzz_record: error message without the file name: %s\n", err);
        abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    fwrite(data, 1, size, f);
    fclose(f);
    char err[2048] = "";
    sb_record_summary s;
    int rc = sb_record_read_summary(path, &s, err, sizeof err);
    check_message(rc, err);
    if (rc == SB_OK) {
        /* what the report does with it: every history entry is read */
        double sum = 0;
        for (int i = 0; i < s.n_hist; i++) sum += s.hist_gnorm[i] + s.hist_step[i] + s.hist_level[i] + s.hist_iter[i];
        if (sum == 42.4242) fputc(' ', stderr);
        sb_record_summary_free(&s);
    }
    check_closed("sb_record_read_summary");
    sb_record_setup su;
    rc = sb_record_read_setup(path, &su, err, sizeof err);
    check_message(rc, err);
    if (rc == SB_OK) sb_record_setup_free(&su);
    check_closed("sb_record_read_setup");
    int n = 0;
    double *st = NULL, *pos = NULL;
    rc = sb_record_read_samples(path, &n, &st, &pos, err, sizeof err);
    check_message(rc, err);
    if (rc == SB_OK) {
        double sum = 0;
        for (int i = 0; i < n; i++) sum += st[2 * i] + pos[3 * i + 2];
        if (sum == 42.4242) fputc(' ', stderr);
    }
    free(st);
    free(pos);
    check_closed("sb_record_read_samples");
    return 0;
}
