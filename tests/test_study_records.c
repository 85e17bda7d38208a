/* test_study_records.c — issue 37, item 7: a record in another run's place
 * is not that run (core/study/sb_study_records.c).  On the code before the
 * fix a plate_simply_supported record copied to plate_clamped's path was
 * skipped by `sweep` as recorded (exit 0) and ranked by `report` as the
 * clamped plate's; now the sweep refuses (exit 2, nothing run, the file
 * kept) and the report counts the run as not run, each with a sentence
 * naming the file and what differs. */
#include "sb_test.h"
#include "sb_study_int.h"
#include "sb_record.h"

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

/* the sweep's exit code; what it said on stderr in *said (caller frees) */
static int sweep(sb_study *st, char **said)
{
    sb_sweep_options o = { 1, 0, 1 };
    char p[400];
    snprintf(p, sizeof p, "%s/sweep.err", tmpdir);
    FILE *err = fopen(p, "w"), *devnull = fopen("/dev/null", "w");
    int rc = sb_study_sweep(st, &o, devnull, err);
    fclose(err);
    fclose(devnull);
    *said = slurp(p);
    return rc;
}

/* the deterministic report's exit code; its stderr in *said */
static int report(sb_study *st, char **said)
{
    sb_study_report_options o = { NULL, "/nonexistent/gnuplot", 1 };
    char p[400];
    snprintf(p, sizeof p, "%s/report.err", tmpdir);
    FILE *err = fopen(p, "w");
    int rc = sb_study_report(st, &o, err);
    fclose(err);
    *said = slurp(p);
    return rc;
}

static int copy_file(const char *from, const char *to)
{
    FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
    if (!a || !b) {
        if (a) fclose(a);
        if (b) fclose(b);
        return -1;
    }
    char buf[1 << 15];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, a)) > 0) fwrite(buf, 1, n, b);
    fclose(a);
    return fclose(b);
}

/* the planned run of scene i at resolution res */
static const sb_plan_run *find(const sb_study *st, const sb_plan *p, const char *scene, int res)
{
    for (int k = 0; k < p->n; k++)
        if (p->runs[k].state == SB_PLAN_RUN && p->runs[k].res == res && !strcmp(st->scenes[p->runs[k].scene].name, scene))
            return &p->runs[k];
    return NULL;
}

/* the study of FILE under tmpdir from fmt (its one %s: tmpdir), loaded;
 * NULL (a failed check) when it does not load */
static sb_study *study_from(sb_test_state *T, const char *file, const char *fmt)
{
    char path[400], err[2048];
    snprintf(path, sizeof path, "%s/%s", tmpdir, file);
    FILE *f = fopen(path, "w");
    if (!f) return NULL;
    fprintf(f, fmt, tmpdir);
    fclose(f);
    sb_study *st = calloc(1, sizeof *st);
    int rc = sb_study_load(path, NULL, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return NULL; }
    return st;
}

SB_TEST(misplaced_records_refused_by_sweep_and_flagged_by_report)
{
    char err[2048];
    int rc;
    sb_study *st = study_from(T, "study.json", "{\"study\": \"misplaced\", \"records\": \"%s/rec\",\n"
                              " \"scenes\": [\"plate_clamped\", \"plate_simply_supported\"],\n"
                              " \"methods\": [\"bhem\"], \"solvers\": [\"lsnewton\"], \"res\": [2, 4]}\n");
    if (!st) return;
    char *said = NULL;
    CHECK_EQ_INT(sweep(st, &said), 0);
    free(said);
    CHECK_EQ_INT(report(st, &said), 0);
    CHECK_MSG(said && !strstr(said, "not the record of the planned run"), "%s", said ? said : "");
    free(said);
    sb_plan p;
    CHECK(sb_study_plan(st, &p, err, sizeof err) == 0);
    const sb_plan_run *c4 = find(st, &p, "plate_clamped", 4), *c2 = find(st, &p, "plate_clamped", 2),
                      *s4 = find(st, &p, "plate_simply_supported", 4);
    CHECK(c4 && c2 && s4);
    if (!c4 || !c2 || !s4) { sb_plan_free(&p); sb_study_free(st); free(st); return; }

    /* digests (committed studies keep only these: no /final/x) are still the
       planned runs' records: the check reads the identity, not the state */
    int already = 0;
    CHECK_MSG(sb_record_digest(c2->out, 1, &already, err, sizeof err) == 0, "%s", err);
    CHECK_MSG(sb_record_digest(s4->out, 1, &already, err, sizeof err) == 0, "%s", err);
    CHECK_EQ_INT(report(st, &said), 0);
    CHECK_MSG(said && !strstr(said, "not the record of the planned run") && !strstr(said, "counted as not run"),
              "report over digests: %s", said ? said : "");
    free(said);

    /* another scene's record in the clamped plate's place */
    CHECK(copy_file(s4->out, c4->out) == 0);
    struct stat before, after;
    stat(c4->out, &before);
    rc = sweep(st, &said);
    CHECK_MSG(rc == 2 && said && strstr(said, c4->out) && strstr(said, "is not the record of the planned run") &&
              strstr(said, "its scene is plate_simply_supported, the plan's plate_clamped"),
              "sweep with a misplaced record: exit %d, %s", rc, said ? said : "");
    free(said);
    CHECK(stat(c4->out, &after) == 0 && after.st_ino == before.st_ino && after.st_mtime == before.st_mtime);
    rc = report(st, &said);
    CHECK_MSG(said && strstr(said, c4->out) && strstr(said, "is not the record of the planned run") &&
              strstr(said, "counted as not run"), "report with a misplaced record: exit %d, %s", rc, said ? said : "");
    free(said);
    /* the report's table lists the run as missing, not as the simply supported plate's */
    char rp[700];
    snprintf(rp, sizeof rp, "%s/report.md", st->records);
    char *md = slurp(rp);
    CHECK_MSG(md && strstr(md, "not the planned run's record (misplaced)"), "report.md does not flag the run");
    free(md);

    /* the same scene at another resolution */
    CHECK(copy_file(c2->out, c4->out) == 0);
    rc = sweep(st, &said);
    CHECK_MSG(rc == 2 && said && strstr(said, "its resolution is 2, the plan's 4"), "sweep: exit %d, %s", rc,
              said ? said : "");
    free(said);
    sb_plan_free(&p);
    sb_study_free(st);
    free(st);
}

/* issue 38: a solver entry's "linear" is a configuration of its own (own
 * label, own record), and a record made with another linear solver in its
 * place is not its run */
SB_TEST(a_linear_solver_entry_is_its_own_configuration)
{
    char err[2048];
    int rc;
    sb_study *st = study_from(T, "linear.json", "{\"study\": \"linear\", \"records\": \"%s/lin\",\n"
                              " \"scenes\": [\"plate_clamped\"], \"methods\": [\"bhem\"],\n"
                              " \"solvers\": [{\"solver\": \"lsnewton\", \"levels\": 2},\n"
                              "             {\"solver\": \"lsnewton\", \"levels\": 2, \"linear\": \"pcg-mg\"}], "
                              "\"res\": [4]}\n");
    if (!st) return;
    sb_plan p;
    CHECK(sb_study_plan(st, &p, err, sizeof err) == 0);
    const sb_plan_run *a = NULL, *b = NULL;
    for (int k = 0; k < p.n; k++)
        if (p.runs[k].state == SB_PLAN_RUN) *(st->solvers[p.runs[k].solver].linear[0] ? &b : &a) = &p.runs[k];
    CHECK(a && b);
    if (!a || !b) { sb_plan_free(&p); sb_study_free(st); free(st); return; }
    char la[256], lb[256];
    sb_plan_config_label(st, a, la, sizeof la);
    sb_plan_config_label(st, b, lb, sizeof lb);
    CHECK_MSG(!strcmp(la, "bhem/lsnewton L2") && !strcmp(lb, "bhem/lsnewton+pcg-mg L2"), "labels %s, %s", la, lb);
    CHECK_MSG(strstr(b->out, "bhem-lsnewton+pcg-mg-l2-r4.h5") && strcmp(a->out, b->out), "paths %s, %s", a->out, b->out);
    char *said = NULL;
    CHECK_EQ_INT(sweep(st, &said), 0);
    free(said);
    sb_record_setup su;
    CHECK_MSG(sb_record_read_identity(b->out, &su, err, sizeof err) == 0, "%s", err);
    CHECK_MSG(!strcmp(su.linear, "pcg-mg"), "the pcg-mg entry's record has solver.linear \"%s\"", su.linear);
    sb_record_setup_free(&su);
    /* the direct solve's record in the Krylov entry's place */
    CHECK(copy_file(a->out, b->out) == 0);
    rc = sweep(st, &said);
    CHECK_MSG(rc == 2 && said && strstr(said, "its linear solver is cholmod, the plan's pcg-mg"), "sweep: exit %d, %s", rc,
              said ? said : "");
    free(said);
    sb_plan_free(&p);
    sb_study_free(st);
    free(st);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_study_records_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    if (chdir(sb_test_root()) != 0) return 3;
    static const sb_test_case cases[] = { SB_CASE(misplaced_records_refused_by_sweep_and_flagged_by_report),
                                          SB_CASE(a_linear_solver_entry_is_its_own_configuration), SB_END };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
