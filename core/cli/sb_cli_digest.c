/* sb_cli_digest.c — `shellbench digest [--drop-state] RECORD.h5...`: rewrite
 * finished records as digests, the part reports read (sb_record_digest.c,
 * docs/reproducibility.md "Committed records"). */
#include "sb_cli.h"
#include "sb_common.h"
#include "sb_record.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

const char sb_cli_digest_help[] =
    "usage: shellbench digest [--drop-state] RECORD.h5...\n"
    "Rewrites each finished record in place as a digest: everything reports read (attributes,\n"
    "parameters, statistics, histories, probes, errors, the final sample grid), without the per-step\n"
    "surfaces and the final displacement, reference grid and triangles.  --drop-state also drops the\n"
    "final dof vector, which `render` and `inspect` need.  A digest is sealed like any record; a\n"
    "digest is left as it is, but for --drop-state on one that still holds its final dof vector.\n"
    "Exit 2 if any file is not a finished record.\n";

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : 0;
}

int sb_cli_digest(int argc, char **argv)
{
    int drop_state = 0, rc = 0, nf = 0;
    long before = 0, after = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--drop-state")) {
            drop_state = 1;
            continue;
        }
        if (argv[i][0] == '-' && argv[i][1]) {
            char e[64];
            fprintf(stderr, "shellbench digest: unknown option \"%s\" (see `shellbench help digest`)\n",
                    sb_escape_copy(argv[i], e, sizeof e));
            return 2;
        }
    }
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--drop-state")) continue;
        nf++;
        char err[1200] = "";
        int already = 0;
        const long b = file_size(argv[i]);
        int st = sb_record_digest(argv[i], drop_state, &already, err, sizeof err);
        if (st) {
            sb_escape_controls(err, sizeof err);
            fprintf(stderr, "shellbench digest: %s\n", err);
            rc = st == SB_ERR_NOMEM ? 3 : rc ? rc : 2;
            continue;
        }
        const long a = file_size(argv[i]);
        before += b;
        after += a;
        sb_escape_print(stdout, "%s: %s%ld -> %ld bytes", argv[i], already ? "already a digest, " : "", b, a);
    }
    if (nf == 0) {
        fprintf(stderr, "shellbench digest: no record given (see `shellbench help digest`)\n");
        return 2;
    }
    if (nf > 1) printf("%d records: %ld -> %ld bytes\n", nf, before, after);
    return rc;
}
