/* test_study_wp.c — the analysis behind work-precision diagrams, performance
 * profiles and the selection table (core/study/sb_study_wp.c and the data
 * layer): hand-made numbers and hand-made records with known answers. */
#include "sb_test.h"
#include "sb_record.h"
#include "sb_study_data.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

SB_TEST(pareto_front_of_hand_made_points)
{
    /* (cost, error): 0 and 2 and 4 are on the front; 1 is dominated by 0,
     * 3 by 2 (equal cost, larger error), 5 has no finite error */
    double c[] = { 1, 2, 3, 3, 10, 0.5 }, e[] = { 1e-2, 2e-2, 1e-3, 2e-3, 1e-5, NAN };
    int f[6];
    sb_wp_pareto(6, c, e, f);
    CHECK(f[0] && !f[1] && f[2] && !f[3] && f[4] && !f[5]);
}

SB_TEST(cost_to_reach_interpolates_log_log_and_never_extrapolates)
{
    int from, first;
    /* halfway in log error between 1e-1 and 1e-3: halfway in log cost, sqrt(1 * 4) = 2 */
    double c1[] = { 1, 4, 16 }, e1[] = { 1e-1, 1e-3, 1e-5 };
    CHECK_REL(sb_wp_cost_to_reach(3, c1, e1, 1e-2, &from, &first), 2.0, 1e-14);
    CHECK(from == 1 && !first);
    /* exactly on a point */
    CHECK_REL(sb_wp_cost_to_reach(3, c1, e1, 1e-3, &from, &first), 4.0, 1e-14);
    /* below the target at the coarsest point already: its cost, flagged */
    CHECK_REL(sb_wp_cost_to_reach(3, c1, e1, 0.5, &from, &first), 1.0, 0);
    CHECK(first && from == 0);
    /* the finest point misses: never (no extrapolation) */
    CHECK(isinf(sb_wp_cost_to_reach(3, c1, e1, 1e-6, &from, &first)) && from == -1);
    /* reached, lost, reached again: from the point it stays below */
    double c2[] = { 1, 2, 4 }, e2[] = { 5e-3, 2e-2, 1e-3 };
    double w = log(0.5) / log(0.05);
    CHECK_REL(sb_wp_cost_to_reach(3, c2, e2, 1e-2, &from, &first), pow(2.0, 1.0 + w), 1e-14);
    CHECK(from == 2 && !first);
}

SB_TEST(performance_profile_of_a_hand_made_table)
{
    /* 3 problems x 3 solvers (Dolan & More 2002): ratios to the best per problem */
    double t[] = { 1, 2, INFINITY,
                   4, 2, 8,
                   INFINITY, INFINITY, INFINITY };
    double r[9];
    sb_profile_ratios(3, 3, t, r);
    CHECK(r[0] == 1 && r[1] == 2 && isinf(r[2]) && r[3] == 2 && r[4] == 1 && r[5] == 4 && isinf(r[6]) && isinf(r[8]));
    CHECK_NEAR(sb_profile_rho(3, 3, r, 0, 1), 1.0 / 3, 1e-15);
    CHECK_NEAR(sb_profile_rho(3, 3, r, 0, 2), 2.0 / 3, 1e-15);
    CHECK_NEAR(sb_profile_rho(3, 3, r, 1, 1.999), 1.0 / 3, 1e-15);
    CHECK_NEAR(sb_profile_rho(3, 3, r, 2, 4), 1.0 / 3, 1e-15);
    CHECK_NEAR(sb_profile_rho(3, 3, r, 2, INFINITY), 1.0 / 3, 1e-15);   /* nobody solves problem 3 */
    int o[4];
    double c[] = { 3, INFINITY, 1, 3 };
    CHECK_EQ_INT(sb_select_order(4, c, o), 3);
    CHECK(o[0] == 2 && o[1] == 0 && o[2] == 3 && o[3] == 1);   /* ties by index, infinite last */
}

/* A record with the given cost and probe error (nothing else in it). */
static int fake_record(const char *path, const sb_scene *sc, const char *method, const char *solver, long dofs,
                       double seconds, double work, double err)
{
    sb_run run;
    sb_stats stats;
    sb_run_init(&run);
    sb_stats_init(&stats);
    stats.seconds_total = seconds;
    stats.work_assembly = work;
    snprintf(run.scene_name, sizeof run.scene_name, "%s", sc->name);
    snprintf(run.scene_path, sizeof run.scene_path, "%s", sc->path);
    run.scene_json = sc->json_text;
    snprintf(run.method, sizeof run.method, "%s", method);
    snprintf(run.solver, sizeof run.solver, "%s", solver);
    run.levels = 1;
    run.n_dofs = dofs;
    run.stats = &stats;
    run.steps_planned = run.steps_done = 1;
    run.has_error = 1;
    run.error_probe = err;
    snprintf(run.error_kind, sizeof run.error_kind, "probes");
    char msg[1024];
    char dir[1100];
    snprintf(dir, sizeof dir, "%s", path);
    *strrchr(dir, '/') = 0;
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
    if (system(cmd)) return -1;
    int rc = sb_record_write(&run, path, msg, sizeof msg);
    if (rc) fprintf(stderr, "%s\n", msg);
    sb_stats_free(&stats);
    return rc;
}

/* configurations A = rmtr/lsnewton, B = rmtr/tr, C = bhem/lsnewton, D = bhem/tr;
 * per scene and configuration (seconds at res 4, 8, 16; errors), NAN: no record */
typedef struct fake { const char *scene, *method, *solver; double s[3], e[3]; } fake;
static const fake fakes[] = {
    { "plate_clamped", "rmtr", "lsnewton", { 1, 4, 16 }, { 1e-1, 1e-3, 1e-5 } },            /* reaches 1e-2 at 2 */
    { "plate_clamped", "rmtr", "tr", { 3, 8, 32 }, { 5e-3, 1e-3, 1e-4 } },                   /* at the coarsest: 3 */
    { "plate_clamped", "bhem", "lsnewton", { 1, 2, 3 }, { 2e-2, 2e-2, 2e-2 } },              /* never */
    { "plate_clamped", "bhem", "tr", { 1, 2, 4 }, { 5e-3, 2e-2, 1e-3 } },                    /* 2^(1 + w) */
    { "plate_simply_supported", "rmtr", "lsnewton", { 1, 2, 4 }, { 1e-3, 1e-3, 1e-3 } },     /* 1 */
    { "plate_simply_supported", "rmtr", "tr", { 0.5, 1, 2 }, { 1e-3, 1e-4, 1e-5 } },         /* 0.5 */
    { "plate_simply_supported", "bhem", "tr", { 1, 2, 4 }, { 5e-2, 4e-2, 3e-2 } },           /* never */
};

SB_TEST(selection_and_profiles_from_hand_made_records)
{
    char path[600], err[2048], text[2048];
    snprintf(path, sizeof path, "%s/hand.json", tmpdir);
    snprintf(text, sizeof text, "{\"study\": \"hand\", \"records\": \"%s/hand\", \"scenes\": [\"plate_clamped\", "
             "\"plate_simply_supported\"], \"methods\": [\"rmtr\", \"bhem\"], \"solvers\": [\"lsnewton\", \"tr\"], "
             "\"res\": [4, 8, 16], \"targets\": [1e-2]}", tmpdir);
    sb_study *st = calloc(1, sizeof *st);
    CHECK(st != NULL);
    if (!st) return;
    int rc = sb_study_parse_string(text, path, NULL, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return; }
    sb_plan plan;
    CHECK(sb_study_plan(st, &plan, err, sizeof err) == 0);
    for (size_t f = 0; f < sizeof fakes / sizeof *fakes; f++)
        for (int k = 0; k < plan.n; k++) {
            const sb_plan_run *r = &plan.runs[k];
            if (strcmp(st->scenes[r->scene].name, fakes[f].scene) || strcmp(st->methods[r->method].name, fakes[f].method) ||
                strcmp(st->solvers[r->solver].name, fakes[f].solver))
                continue;
            int j = r->res == 4 ? 0 : r->res == 8 ? 1 : 2;
            CHECK(fake_record(r->out, st->scenes[r->scene].scene, fakes[f].method, fakes[f].solver, r->dofs,
                              fakes[f].s[j], 10 * fakes[f].s[j], fakes[f].e[j]) == 0);
        }
    sb_plan_free(&plan);
    sb_study_data d;
    CHECK(sb_study_data_load(st, &d, stderr) == 0);
    int A = sb_study_config(st, 1, 0, 0, 0), B = sb_study_config(st, 1, 0, 1, 0), C = sb_study_config(st, 1, 1, 0, 0),
        D = sb_study_config(st, 1, 1, 1, 0);
    double w = log(0.5) / log(0.05);
    long lo, hi;
    CHECK_REL(sb_study_reach(&d, 0, A, 0, 1e-2, &lo, &hi, NULL), 2.0, 1e-12);
    CHECK(lo > 0 && hi > lo);
    CHECK_REL(sb_study_reach(&d, 0, B, 0, 1e-2, &lo, &hi, NULL), 3.0, 1e-12);
    CHECK(lo == 0);                                          /* at the coarsest run */
    CHECK(isinf(sb_study_reach(&d, 0, C, 0, 1e-2, NULL, NULL, NULL)));
    CHECK_REL(sb_study_reach(&d, 0, D, 0, 1e-2, NULL, NULL, NULL), pow(2.0, 1 + w), 1e-12);
    CHECK_REL(sb_study_reach(&d, 0, D, 1, 1e-2, NULL, NULL, NULL), 10 * pow(2.0, 1 + w), 1e-12);   /* work units */
    CHECK(!sb_study_has_record(&d, 1, C));
    /* selection on plate_clamped at 1e-2: A (2), runner-up D (2.35), ratio 1.17 */
    double cost[4];
    int order[4], cfg[4] = { A, B, C, D };
    for (int c = 0; c < 4; c++) cost[c] = sb_study_reach(&d, 0, cfg[c], 0, 1e-2, NULL, NULL, NULL);
    CHECK_EQ_INT(sb_select_order(4, cost, order), 3);
    CHECK(cfg[order[0]] == A && cfg[order[1]] == D && cfg[order[2]] == B && cfg[order[3]] == C);
    /* the profile over both scenes */
    double t[8], ratio[8];
    for (int p = 0; p < 2; p++)
        for (int c = 0; c < 4; c++) t[p * 4 + c] = sb_study_reach(&d, p, cfg[c], 0, 1e-2, NULL, NULL, NULL);
    sb_profile_ratios(2, 4, t, ratio);
    CHECK_NEAR(sb_profile_rho(2, 4, ratio, 0, 1), 0.5, 0);     /* A cheapest on plate_clamped */
    CHECK_NEAR(sb_profile_rho(2, 4, ratio, 0, 2), 1.0, 0);     /* 1 / 0.5 on the other */
    CHECK_NEAR(sb_profile_rho(2, 4, ratio, 1, 1), 0.5, 0);     /* B cheapest on plate_simply_supported */
    CHECK_NEAR(sb_profile_rho(2, 4, ratio, 1, 1.49), 0.5, 0);
    CHECK_NEAR(sb_profile_rho(2, 4, ratio, 1, 1.5 + 1e-12), 1.0, 0);   /* 3 / 2 */
    CHECK_NEAR(sb_profile_rho(2, 4, ratio, 2, INFINITY), 0.0, 0);
    CHECK_NEAR(sb_profile_rho(2, 4, ratio, 3, INFINITY), 0.5, 0);
    /* the report's selection table says the same */
    sb_study_report_options o = { NULL, "/nonexistent/gnuplot", 0 };
    FILE *devnull = fopen("/dev/null", "w");
    CHECK(sb_study_report(st, &o, devnull) == 0);
    fclose(devnull);
    char rp[700];
    snprintf(rp, sizeof rp, "%s/hand/report.md", tmpdir);
    FILE *f = fopen(rp, "r");
    CHECK(f != NULL);
    if (f) {
        static char md[1 << 17];
        size_t n = fread(md, 1, sizeof md - 1, f);
        md[n] = 0;
        fclose(f);
        CHECK_MSG(strstr(md, "| plate_clamped | 0.01 | rmtr/lsnewton | 2 (") != NULL, "selection row of plate_clamped");
        CHECK_MSG(strstr(md, "| bhem/tr | 2.35 (") != NULL && strstr(md, "| 1.17 | bhem/lsnewton (best 0.02") != NULL,
                  "runner-up, ratio and the configuration that never reaches the target");
        CHECK_MSG(strstr(md, "| plate_simply_supported | 0.01 | rmtr/tr | 0.5 (≤, already at") != NULL, "second scene");
        char *sel = strstr(md, "## Method selection"), *wp = strstr(md, "## Work-precision");
        CHECK_MSG(sel && wp && sel < wp, "the selection table comes first");
    }
    sb_study_data_free(&d);
    sb_study_free(st);
    free(st);
}

static char *slurp(const char *path)
{
    static char md[1 << 17];
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    size_t n = fread(md, 1, sizeof md - 1, f);
    md[n] = 0;
    fclose(f);
    return md;
}

/* a symbolic link at PATH to TARGET (which holds "mine"); 1 when both are
 * still as made */
static int make_link(const char *path, const char *target)
{
    FILE *f = fopen(target, "w");
    if (!f) return 0;
    fputs("mine", f);
    fclose(f);
    return symlink(target, path) == 0;
}

static int link_intact(const char *path, const char *target)
{
    struct stat st;
    char buf[16] = "";
    FILE *f = fopen(target, "r");
    if (f) {
        if (!fgets(buf, sizeof buf, f)) buf[0] = 0;
        fclose(f);
    }
    return lstat(path, &st) == 0 && S_ISLNK(st.st_mode) && strcmp(buf, "mine") == 0;
}

/* Per-run tables say "distance to the reference's minimum" on a scene with
 * several solutions and "error" on a unique one; a record that cannot be
 * drawn leaves a sentence instead of a picture; a report.md or a figure that
 * is a symbolic link is refused (exit 2) and the link and its target are
 * left alone, for the accuracy report and the dt report. */
SB_TEST(report_tables_pictures_and_refused_outputs)
{
    char path[600], err[2048], text[2048], rp[700], tgt[700];
    snprintf(path, sizeof path, "%s/several.json", tmpdir);
    snprintf(text, sizeof text, "{\"study\": \"several\", \"records\": \"%s/several\", \"scenes\": [\"plate_clamped\", "
             "{\"scene\": \"tests/scenes/drooping_1step.json\", \"solution\": \"multiple\"}], \"methods\": [\"rmtr\"], "
             "\"solvers\": [\"tr\"], \"res\": [4]}", tmpdir);
    sb_study *st = calloc(1, sizeof *st);
    CHECK(st != NULL);
    if (!st) return;
    int rc = sb_study_parse_string(text, path, NULL, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return; }
    sb_plan plan;
    CHECK(sb_study_plan(st, &plan, err, sizeof err) == 0);
    for (int k = 0; k < plan.n; k++)
        CHECK(fake_record(plan.runs[k].out, st->scenes[plan.runs[k].scene].scene, "rmtr", "tr", plan.runs[k].dofs, 1, 10,
                          1e-3) == 0);
    sb_plan_free(&plan);
    sb_study_report_options o = { NULL, "/nonexistent/gnuplot", 1 };
    FILE *devnull = fopen("/dev/null", "w");
    CHECK(sb_study_report(st, &o, devnull) == 0);
    snprintf(rp, sizeof rp, "%s/several/report.md", tmpdir);
    char *md = slurp(rp);
    CHECK(md != NULL);
    if (md) {
        char *runs = strstr(md, "## Runs"), *uniq = runs ? strstr(runs, "### plate_clamped") : NULL,
             *sev = runs ? strstr(runs, "### drooping_1step") : NULL;
        CHECK(uniq && sev && uniq < sev);
        if (uniq && sev) {
            char *a = strstr(uniq, "| probe error | RMS field error | max field error |");
            char *b = strstr(sev, "| probe distance to the reference's minimum | RMS distance to it | max distance to it |");
            CHECK_MSG(a && a < sev, "the unique scene's table has error columns");
            CHECK_MSG(b != NULL, "the table of the scene with several solutions has distance columns");
            CHECK_MSG(!strstr(sev, "| probe error |"), "no error columns after the scene with several solutions");
        }
        /* the scenes with several solutions: where the minimum lies in the
         * material law (docs/denim.md); hand-made records hold no
         * /final/material, so the cell is a dash */
        char *ms = strstr(md, "## Scenes with several solutions");
        char *hd = ms ? strstr(ms, "| E (J) | ΔE | below rest | starts converged |") : NULL;
        CHECK_MSG(hd != NULL, "the several-solutions table has a below-rest column");
        char *row = hd ? strstr(hd, "\n| rmtr/tr |") : NULL;
        CHECK_MSG(row && strstr(row, " | — | 1 of 1 |") && strstr(row, " | — | 1 of 1 |") < strchr(row + 1, '\n'),
                  "a record without a material state shows a dash");
        /* hand-made records hold no final state: a sentence, not a picture */
        CHECK(strstr(md, "*plate_clamped: no picture: the record cannot be drawn") != NULL);
        CHECK(!strstr(md, "](thumb-"));
    }
    /* report.md a symbolic link: refused before anything is written */
    snprintf(tgt, sizeof tgt, "%s/target.md", tmpdir);
    CHECK(unlink(rp) == 0 && make_link(rp, tgt));
    CHECK_EQ_INT(sb_study_report(st, &o, devnull), SB_EXIT_INPUT);
    CHECK_MSG(link_intact(rp, tgt), "the symbolic link report.md and its target are left alone");
    /* a figure a symbolic link: the report is written, the figure refused, exit 2 */
    CHECK(unlink(rp) == 0);
    char fig[700], ftgt[700];
    snprintf(fig, sizeof fig, "%s/several/wp-plate_clamped-work.png", tmpdir);
    snprintf(ftgt, sizeof ftgt, "%s/target.png", tmpdir);
    CHECK(make_link(fig, ftgt));
    CHECK_EQ_INT(sb_study_report(st, &o, devnull), SB_EXIT_INPUT);
    CHECK(link_intact(fig, ftgt));
    CHECK(access(rp, F_OK) == 0);
    /* a link planted at the temporary report.md.tmp is removed, never written through */
    CHECK(unlink(fig) == 0);
    char tmpl[760], ttgt[700];
    snprintf(tmpl, sizeof tmpl, "%s.tmp", rp);
    snprintf(ttgt, sizeof ttgt, "%s/target-tmp.md", tmpdir);
    CHECK(make_link(tmpl, ttgt));
    CHECK_EQ_INT(sb_study_report(st, &o, devnull), 0);
    char *t = slurp(ttgt);
    CHECK_MSG(t && strcmp(t, "mine") == 0, "the target of a link at report.md.tmp is left alone");
    struct stat rs;
    CHECK(lstat(rp, &rs) == 0 && S_ISREG(rs.st_mode) && access(tmpl, F_OK) != 0);
    sb_study_free(st);
    /* the dt report (no probes recorded: its tables still stand) */
    snprintf(path, sizeof path, "%s/dt.json", tmpdir);
    snprintf(text, sizeof text, "{\"study\": \"dt\", \"kind\": \"dt_stability\", \"records\": \"%s/dt\", \"scenes\": "
             "[{\"scene\": \"trampoline\", \"solution\": \"unique\"}], \"methods\": [\"rmtr\"], \"solvers\": [\"tr\"], "
             "\"res\": [4], \"dt\": {\"max\": 1, \"min\": 0.01}}", tmpdir);
    rc = sb_study_parse_string(text, path, NULL, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (!rc) {
        CHECK(sb_study_report(st, &o, devnull) == 0);
        snprintf(rp, sizeof rp, "%s/dt/report.md", tmpdir);
        md = slurp(rp);
        CHECK(md && strstr(md, "| rmtr | tr | ") && strstr(md, "*trampoline: no picture (no probe converged).*"));
        snprintf(tgt, sizeof tgt, "%s/target-dt.md", tmpdir);
        CHECK(unlink(rp) == 0 && make_link(rp, tgt));
        CHECK_EQ_INT(sb_study_report(st, &o, devnull), SB_EXIT_INPUT);
        CHECK(link_intact(rp, tgt));
        sb_study_free(st);
    }
    fclose(devnull);
    free(st);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_study_wp_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    if (chdir(sb_test_root()) != 0) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(pareto_front_of_hand_made_points),
        SB_CASE(cost_to_reach_interpolates_log_log_and_never_extrapolates),
        SB_CASE(performance_profile_of_a_hand_made_table),
        SB_CASE(selection_and_profiles_from_hand_made_records), SB_CASE(report_tables_pictures_and_refused_outputs), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
