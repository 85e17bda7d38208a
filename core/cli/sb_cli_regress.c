/* sb_cli_regress.c — `shellbench regress` (and `make nightly`): run the
 * nightly suite, compare it with the baseline, write the report, append the
 * history, and exit 0 (no regression), 1 (regression: a case slower, with
 * changed deterministic figures, or failed) or 2 (input error: the suite,
 * the baseline or an option).  docs/regression.md. */
#include "sb_cli.h"
#include "sb_regress_int.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

const char sb_cli_regress_help[] =
    "usage: shellbench regress [--suite FILE] [--baseline FILE] [--history FILE] [--out DIR]\n"
    "                          [--repeat K] [--jobs N] [--set KEY=VALUE]... [--update-baseline]\n"
    "                          [--no-history] [--no-confirm] [--alpha A] [--min-effect E] [--min-seconds S]\n"
    "                          [--rtol R] [--quiet]\n"
    "Nightly performance regression (docs/regression.md): runs the suite (a study file) K times with a\n"
    "calibration pass per round, compares every case with the baseline and gives a verdict per case:\n"
    "same, faster, slower (CPU time / calibration, Mann-Whitney U test p < A and a change of at least\n"
    "E), changed (iterations, work units, nnz, flops, status, reason; energy and probes to R), failed,\n"
    "new.  Writes DIR/report.md and DIR/history-CASE.png, appends the history.  Every file it writes is\n"
    "checked before the first run (symbolic links, FIFOs, directories refused: exit 2); the suite and the\n"
    "baseline are read only from regular files; RECORDS.lock keeps a second invocation off the records.\n"
    "  --suite FILE          the suite (default bench/nightly/nightly.json)\n"
    "  --baseline FILE       the baseline (default bench/nightly/baseline.json)\n"
    "  --history FILE        the history (default results/nightly/history.csv)\n"
    "  --out DIR             report and plots (default results/nightly)\n"
    "  --repeat K            runs per case, 2..64 (default 5)\n"
    "  --jobs N              runs at once (default 1: the times are the least disturbed)\n"
    "  --set KEY=VALUE       an extra parameter of every run (an experiment), repeatable\n"
    "  --update-baseline     write the baseline from this run (with its provenance); refused when a\n"
    "                        case failed\n"
    "  --no-history          do not append to the history\n"
    "  --no-confirm          do not measure a case judged slower or faster a second time (by default\n"
    "                        the verdict stands only when a second measurement agrees)\n"
    "  --alpha A             significance of the U test (default 0.05)\n"
    "  --min-effect E        smallest relative change of the median time called a change (default 0.10)\n"
    "  --min-seconds S       smallest change of a run's CPU seconds called a change (default 0.01)\n"
    "  --rtol R              relative tolerance of energies and probe positions (default 1e-9)\n"
    "exit code: 0 no regression, 1 regression, 2 input error, 3 internal error.\n";

static int real_opt(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    double x = v ? strtod(v, &end) : 0;
    if (!v || end == v || *end || !(x >= lo && x <= hi)) {
        char e[64];
        fprintf(stderr, "shellbench regress: %s: \"%s\" is not a number in [%g, %g]\n", opt,
                sb_escape_copy(v ? v : "", e, sizeof e), lo, hi);
        return -1;
    }
    *out = x;
    return 0;
}

static int int_opt(const char *opt, const char *v, int lo, int hi, int *out)
{
    if (!v || sb_cli_parse_int(v, lo, hi, out)) {
        char e[64];
        fprintf(stderr, "shellbench regress: %s: \"%s\" is not an integer in [%d, %d]\n", opt,
                sb_escape_copy(v ? v : "", e, sizeof e), lo, hi);
        return -1;
    }
    return 0;
}

static int dir_of(const char *file, char *buf, size_t len)
{
    snprintf(buf, len, "%s", file);
    char *s = strrchr(buf, '/');
    if (!s) return 0;
    *s = 0;
    return buf[0] ? sb_mkdir_p(buf) : 0;
}

/* The files the command writes, checked before any run: DIR a directory
 * (or makeable), DIR/report.md, the history (NULL: not written) and the
 * baseline (NULL: not written) new or regular files in writable
 * directories.  0, or -1 with *opt the option they come from and a
 * sentence. */
static int check_outputs(const char *outdir, const char *history, const char *baseline, const char **opt, char *err,
                         size_t len)
{
    char report[1100];
    sb_output_kind kind;
    *opt = "--out";
    if (sb_output_check_dir(outdir, "the report and plots", err, len)) return -1;
    snprintf(report, sizeof report, "%s/report.md", outdir);
    if (sb_output_check(report, "report", &kind, err, len)) return -1;
    *opt = "--history";
    if (history && (sb_output_check(history, "history file", &kind, err, len) ||
                    sb_output_check_file_dir(history, "history file", 0, err, len)))
        return -1;
    *opt = "--baseline";
    if (baseline && (sb_output_check(baseline, "baseline", &kind, err, len) ||
                     sb_output_check_file_dir(baseline, "baseline", 0, err, len)))
        return -1;
    if (baseline && kind == SB_OUTPUT_DISCARD) {
        snprintf(err, len, "will not write the baseline to the null device %s (--update-baseline writes it)", baseline);
        return -1;
    }
    return 0;
}

int sb_cli_regress(int argc, char **argv)
{
    const char *suite = "bench/nightly/nightly.json", *baseline = "bench/nightly/baseline.json",
               *history = "results/nightly/history.csv", *outdir = "results/nightly";
    sb_regress_run_options o;
    memset(&o, 0, sizeof o);
    o.repeat = 5, o.jobs = 1;
    sb_regress_rules ru;
    sb_regress_rules_default(&ru);
    int update = 0, no_history = 0, confirm = 1;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (!strcmp(a, "--suite") && v) suite = v;
        else if (!strcmp(a, "--baseline") && v) baseline = v;
        else if (!strcmp(a, "--history") && v) history = v;
        else if (!strcmp(a, "--out") && v) outdir = v;
        else if (!strcmp(a, "--repeat")) { if (int_opt(a, v, 2, SB_REGRESS_MAX_REPEAT, &o.repeat)) return 2; }
        else if (!strcmp(a, "--jobs")) { if (int_opt(a, v, 1, 64, &o.jobs)) return 2; }
        else if (!strcmp(a, "--alpha")) { if (real_opt(a, v, 1e-6, 0.5, &ru.alpha)) return 2; }
        else if (!strcmp(a, "--min-effect")) { if (real_opt(a, v, 0, 10, &ru.min_effect)) return 2; }
        else if (!strcmp(a, "--min-seconds")) { if (real_opt(a, v, 0, 1e6, &ru.min_seconds)) return 2; }
        else if (!strcmp(a, "--rtol")) { if (real_opt(a, v, 0, 1, &ru.rtol)) return 2; }
        else if (!strcmp(a, "--set") && v && strchr(v, '=')) {
            if (o.n_sets == SB_REGRESS_MAX_SETS) { fprintf(stderr, "shellbench regress: more than %d --set\n", SB_REGRESS_MAX_SETS); return 2; }
            o.sets[o.n_sets++] = v;
        } else {
            takes = 0;
            if (!strcmp(a, "--update-baseline")) update = 1;
            else if (!strcmp(a, "--no-history")) no_history = 1;
            else if (!strcmp(a, "--no-confirm")) confirm = 0;
            else if (!strcmp(a, "--quiet")) o.quiet = 1;
            else {
                char e[80];
                fprintf(stderr, "shellbench regress: unknown option, missing or malformed value \"%s\" (see `shellbench help regress`)\n",
                        sb_escape_copy(a, e, sizeof e));
                return 2;
            }
        }
        i += takes;
    }
    char err[2048];
    /* every output before any run (docs/cli.md "Output safety"): the report
     * and plots, the history, the baseline to write; the records below */
    const char *opt = NULL;
    if (check_outputs(outdir, no_history ? NULL : history, update ? baseline : NULL, &opt, err, sizeof err)) {
        sb_escape_controls(err, sizeof err);
        fprintf(stderr, "shellbench regress: %s: %s\n", opt, err);
        return 2;
    }
    /* the baseline first: a broken one is an input error before minutes of runs */
    sb_regress_set base, now;
    memset(&base, 0, sizeof base);
    memset(&now, 0, sizeof now);
    int have_base = 0;
    struct stat stt;
    if (stat(baseline, &stt) == 0) {
        if (sb_regress_baseline_read(baseline, &base, err, sizeof err)) {
                sb_escape_print(stderr, "shellbench regress: --baseline: %s", err);
            return 2;
        }
        have_base = 1;
    } else if (!update) {
        sb_escape_print(stderr, "shellbench regress: no baseline %s: make one with --update-baseline", baseline);
        return 2;
    }
    sb_study *st = malloc(sizeof *st);
    if (!st) return 3;
    if (sb_study_load(suite, NULL, st, err, sizeof err)) {
        sb_escape_print(stderr, "shellbench regress: --suite: %s", err);
        free(st);
        sb_regress_set_free(&base);
        return 2;
    }
    /* the records, history plots and pictures; one invocation at a time */
    sb_output_lock lock;
    if (sb_regress_prepare_outputs(st, o.repeat, outdir, &lock, err, sizeof err)) {
        sb_escape_print(stderr, "shellbench regress: %s", err);
        sb_study_free(st);
        free(st);
        sb_regress_set_free(&base);
        return 2;
    }
    int rc = sb_regress_measure(st, &o, &now, stdout, stderr);
    if (rc) {
        sb_output_lock_release(&lock);
        sb_study_free(st);
        free(st);
        sb_regress_set_free(&base);
        sb_regress_set_free(&now);
        return rc;
    }
    char records[1024];   /* where the runs' records are (the pictures are drawn from them) */
    snprintf(records, sizeof records, "%s", st->records);
    int regressions = sb_regress_judge(&now, have_base ? &base : NULL, &ru);
    /* a new baseline is being made: the verdicts against the old one are for information */
    if (!rc && confirm && have_base && !update) rc = sb_regress_confirm(st, &o, &now, &base, &ru, &regressions, stdout, stderr);
    sb_study_free(st);
    free(st);
    if (rc) {
        sb_output_lock_release(&lock);
        sb_regress_set_free(&base);
        sb_regress_set_free(&now);
        return rc;
    }
    char dir[1024], report[1100];
    if (sb_mkdir_p(outdir)) {
        sb_escape_print(stderr, "shellbench regress: cannot create %s: %s", outdir, strerror(errno));
        rc = 3;
    } else {
        /* written to a new temporary file and renamed onto the report: never
         * through a link that appeared since the check */
        char tmp[1200];
        snprintf(report, sizeof report, "%s/report.md", outdir);
        snprintf(tmp, sizeof tmp, "%s.tmp.%ld", report, (long)getpid());
        err[0] = 0;
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
        if (!f && fd >= 0) close(fd);
        if (f) {
            sb_regress_markdown(f, &now, have_base ? &base : NULL, &ru, baseline);
            sb_regress_pictures(f, &now, records, outdir, stderr);
            if (fclose(f)) f = NULL;
        }
        sb_output_kind kind;
        if (f && (sb_output_check(report, "report", &kind, err, sizeof err) || rename(tmp, report))) f = NULL;
        if (!f) {
            sb_escape_print(stderr, "shellbench regress: cannot write %s: %s", report, err[0] ? err : strerror(errno));
            unlink(tmp);
            rc = 3;
        }
    }
    sb_regress_markdown(stdout, &now, have_base ? &base : NULL, &ru, baseline);
    if (!no_history) {
        if (dir_of(history, dir, sizeof dir) || sb_regress_history_append(&now, history, err, sizeof err)) {
            sb_escape_print(stderr, "shellbench regress: %s", err);
            rc = 3;
        } else if (!rc) {
            sb_regress_history_plots(history, &now, outdir, NULL, stderr);
        }
    }
    if (update) {
        int failed = 0;
        for (int k = 0; k < now.n; k++) failed += now.c[k].verdict == SB_VERDICT_FAILED;
        if (failed) {
            sb_escape_print(stderr, "shellbench regress: %d case%s failed: the baseline %s is left as it was", failed,
                    failed > 1 ? "s" : "", baseline);
            regressions = regressions ? regressions : 1;
        } else if (dir_of(baseline, dir, sizeof dir) || sb_regress_baseline_write(&now, baseline, err, sizeof err)) {
            sb_escape_print(stderr, "shellbench regress: %s", err);
            rc = 3;
        } else {
            sb_escape_print(stdout, "baseline written: %s (%d cases, build %s)", baseline, now.n, now.prov.build);
            regressions = 0;   /* the new baseline is this run: nothing regressed against it */
        }
    }
    sb_output_lock_release(&lock);
    sb_regress_set_free(&base);
    sb_regress_set_free(&now);
    if (rc) return rc;
    return regressions ? 1 : 0;
}
