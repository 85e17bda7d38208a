/* test_study_resume.c — a study interrupted and resumed gives the same
 * report as one run straight through (core/study/sb_study_sweep.c): the
 * sweep skips what is recorded, --max-runs stops it resumably (exit 4), and
 * the deterministic report (work units, no wall clock) of the resumed study
 * is byte for byte the uninterrupted one's. */
#include "sb_test.h"
#include "sb_study_int.h"
#include "sb_stats.h"

#include <hdf5.h>
#include <math.h>

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) n = 0;
    if (b) b[n] = 0;
    fclose(f);
    return b;
}

static int sweep(sb_study *st, int jobs, int max_runs)
{
    sb_sweep_options o = { jobs, max_runs, 1 };
    FILE *devnull = fopen("/dev/null", "w");
    int rc = sb_study_sweep(st, &o, devnull, devnull);
    fclose(devnull);
    return rc;
}

/* the same, with the sweep's stdout kept in *text */
static int sweep_text(sb_study *st, int jobs, int max_runs, char **text)
{
    sb_sweep_options o = { jobs, max_runs, 1 };
    char p[400];
    snprintf(p, sizeof p, "%s/sweep.out", tmpdir);
    FILE *out = fopen(p, "w"), *devnull = fopen("/dev/null", "w");
    int rc = sb_study_sweep(st, &o, out, devnull);
    fclose(out);
    fclose(devnull);
    *text = slurp(p);
    return rc;
}

static char *report(sb_study *st)
{
    sb_study_report_options o = { NULL, "/nonexistent/gnuplot", 1 };
    FILE *devnull = fopen("/dev/null", "w");
    int rc = sb_study_report(st, &o, devnull);
    fclose(devnull);
    char p[700];
    snprintf(p, sizeof p, "%s/report.md", st->records);
    return rc ? NULL : slurp(p);
}

SB_TEST(an_interrupted_study_resumed_gives_the_same_report)
{
    char path[400], err[2048];
    snprintf(path, sizeof path, "%s/study.json", tmpdir);
    FILE *f = fopen(path, "w");
    fprintf(f, "{\"study\": \"resume\", \"records\": \"%s/rec\",\n"
               " \"scenes\": [\"plate_clamped\", \"plate_simply_supported\", \"strip_end_moment\"],\n"
               " \"methods\": [\"rmtr\", \"bhem\"], \"solvers\": [\"tr\", \"lsnewton\"], \"res\": [4, 8],\n"
               " \"rules\": [{\"scene\": \"strip_end_moment\", \"method\": \"bhem\", \"skip\": \"20 load steps: too slow for a test\"}]}\n",
            tmpdir);
    fclose(f);
    sb_study *st = calloc(1, sizeof *st);
    int rc = sb_study_load(path, NULL, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return; }
    /* straight through */
    CHECK_EQ_INT(sweep(st, 2, 0), 0);
    char *first = report(st);
    CHECK(first != NULL);
    /* interrupted: half of the records gone, a run's temporary file left behind */
    sb_plan p;
    CHECK(sb_study_plan(st, &p, err, sizeof err) == 0);
    int runs = 0, removed = 0;
    struct stat kept_before = { 0 };
    const char *kept = NULL;
    for (int k = 0; k < p.n; k++) {
        if (p.runs[k].state != SB_PLAN_RUN) continue;
        if (runs++ % 2) {
            char x[1100];
            unlink(p.runs[k].out);
            snprintf(x, sizeof x, "%.*s.xdmf", (int)strlen(p.runs[k].out) - 3, p.runs[k].out);
            unlink(x);
            if (!removed++) {
                snprintf(x, sizeof x, "%s.tmp.999999", p.runs[k].out);
                FILE *t = fopen(x, "w");
                if (t) fputs("half-written", t), fclose(t);
            }
        } else if (!kept) {
            kept = p.runs[k].out;
            stat(kept, &kept_before);
        }
    }
    CHECK(runs == 16 && removed == 8);
    /* resumed in two pieces: stops after 3 new runs, then finishes */
    char *said = NULL;
    CHECK_EQ_INT(sweep_text(st, 1, 3, &said), 4);
    /* the sweep ends by saying what became of the runs it made */
    CHECK_MSG(said && strstr(said, "runs made now: 3 of 3: 3 converged, 0 NOT converged (reason recorded), 0 refused"),
              "%s", said ? said : "(no output)");
    free(said);
    int done = 0;
    for (int k = 0; k < p.n; k++) done += p.runs[k].state == SB_PLAN_RUN && sb_study_run_done(&p.runs[k]);
    CHECK_EQ_INT(done, 8 + 3);
    CHECK_EQ_INT(sweep(st, 2, 0), 0);
    struct stat kept_after;
    CHECK(kept && stat(kept, &kept_after) == 0 && kept_after.st_ino == kept_before.st_ino &&
          kept_after.st_mtime == kept_before.st_mtime);
    char *second = report(st);
    CHECK(second != NULL);
    CHECK_MSG(first && second && strcmp(first, second) == 0, "the resumed study's report differs from the uninterrupted one's");
    CHECK(first && strstr(first, "| strip_end_moment | rmtr/tr | 4 | 0 | refused | method rmtr on scene strip_end_moment"));
    CHECK(first && strstr(first, "| strip_end_moment | bhem/tr | — | 0 | skipped | 20 load steps"));
    /* every scene's picture: the finest converged run's final state, a PNG beside the report */
    CHECK(first && strstr(first, "![plate_clamped: final state](thumb-plate_clamped.png)  \n*plate_clamped: final state of "
                                 "the finest converged run, "));
    /* the related reports are linked (the paths relative to the report's directory) */
    CHECK(first && strstr(first, "## Related studies and reports") && strstr(first, "* [results/rmtr/cond.md](") &&
          strstr(first, "* [results/dt_stability/report.md]("));
    const char *lk = first ? strstr(first, "* [results/rmtr/cond.md](") : NULL;
    if (lk) {
        lk += strlen("* [results/rmtr/cond.md](");
        char rel[600], joined[1400], r1[4096], r2[4096];
        snprintf(rel, sizeof rel, "%.*s", (int)strcspn(lk, ")"), lk);
        snprintf(joined, sizeof joined, "%s/%s", st->records, rel);
        CHECK_MSG(rel[0] != '/' && realpath(joined, r1) && realpath("results/rmtr/cond.md", r2) && strcmp(r1, r2) == 0,
                  "the link %s from %s leads to results/rmtr/cond.md", rel, st->records);
    }
    char png[700];
    snprintf(png, sizeof png, "%s/thumb-plate_clamped.png", st->records);
    char *pic = slurp(png);
    CHECK_MSG(pic && memcmp(pic, "\x89PNG", 4) == 0, "%s is a PNG", png);
    free(pic);
    /* a third sweep has nothing to do */
    CHECK_EQ_INT(sweep(st, 2, 0), 0);
    sb_plan_free(&p);
    free(first);
    free(second);
    sb_study_free(st);
    free(st);
}

static double stats_attr(const char *path, const char *name)
{
    double v = NAN;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) return v;
    hid_t a = H5Aopen_by_name(f, "/stats", name, H5P_DEFAULT, H5P_DEFAULT);
    if (a >= 0) {
        H5Aread(a, H5T_NATIVE_DOUBLE, &v);
        H5Aclose(a);
    }
    H5Fclose(f);
    return v;
}

/* A sweep's runs are forked from the sweep, whose plan sets every method up
 * at every size (here bhem at about 4e5 dofs): the run's peak_rss must be
 * its own, not the plan's (issue 42: before the fix a 51,483-dof run
 * recorded the 1.2 GB of a 1e6-dof plan, and the memory estimate looked 2x
 * off).  The sweep stops after the small run (--max-runs 1). */
SB_TEST(a_sweep_run_s_peak_memory_is_its_own)
{
    char path[400], err[2048], rec[1100];
    snprintf(path, sizeof path, "%s/peak.json", tmpdir);
    FILE *f = fopen(path, "w");
    fprintf(f, "{\"study\": \"peak\", \"records\": \"%s/peak\", \"scenes\": [\"plate_simply_supported\"],\n"
               " \"methods\": [\"bhem\"], \"solvers\": [\"lsnewton\"], \"dofs\": [500, 400000]}\n", tmpdir);
    fclose(f);
    sb_study *st = calloc(1, sizeof *st);
    int rc = sb_study_load(path, NULL, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return; }
    CHECK_EQ_INT(sweep(st, 1, 1), 4);
    sb_plan p;
    CHECK(sb_study_plan(st, &p, err, sizeof err) == 0);
    CHECK_EQ_INT(p.n, 2);
    rec[0] = 0;
    for (int k = 0; k < p.n; k++) {
        if (p.runs[k].dofs < 10000) snprintf(rec, sizeof rec, "%s", p.runs[k].out);
        else CHECK_MSG(!sb_study_run_done(&p.runs[k]), "the 4e5-dof run was not to be run (--max-runs 1)");
    }
    /* the plan did grow this process: the test can fail */
    const double parent_peak = sb_peak_rss();
    const double start = stats_attr(rec, "peak_rss_start"), setup = stats_attr(rec, "peak_rss_setup"),
                 peak = stats_attr(rec, "peak_rss"), est = stats_attr(rec, "memory_estimate");
    CHECK_MSG(parent_peak > 150e6, "the plan's set-up at 4e5 dofs reached only %.0f MB", parent_peak / 1e6);
    CHECK_MSG(start > 0 && start <= setup && setup <= peak, "%s: peak_rss_start %g, setup %g, peak %g", rec, start, setup, peak);
#if defined(__SANITIZE_ADDRESS__)
    /* AddressSanitizer's allocator keeps the plan's freed pages (no
     * malloc_trim), so the child starts with them resident: only the reset
     * of its high-water mark is checked, which without it would be the
     * parent's whole peak */
    CHECK_MSG(peak < parent_peak,
#else
    CHECK_MSG(peak < 0.5 * parent_peak && peak < 120e6,
#endif
              "%s: peak_rss %.0f MB (estimate %.0f MB) carries the sweep's %.0f MB", rec, peak / 1e6, est / 1e6,
              parent_peak / 1e6);
    sb_plan_free(&p);
    sb_study_free(st);
    free(st);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_study_resume_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    if (chdir(sb_test_root()) != 0) return 3;
    static const sb_test_case cases[] = { SB_CASE(an_interrupted_study_resumed_gives_the_same_report),
                                          SB_CASE(a_sweep_run_s_peak_memory_is_its_own), SB_END };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
