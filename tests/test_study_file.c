/* test_study_file.c — study files (core/study/sb_study_json.c,
 * sb_study_check.c): every error names FILE:LINE:COL and the JSON pointer,
 * and is found before anything runs; a good file plans every registered
 * method. */
#include "sb_test.h"
#include "sb_study_int.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

/* parse `text` as study "s.json"; 0 when it parses, else the message in err */
static int parse(const char *text, char *err, size_t len)
{
    sb_study *st = calloc(1, sizeof *st);
    if (!st) return -99;
    int rc = sb_study_parse_string(text, "s.json", "/tmp/never", st, err, len);
    sb_study_free(st);
    free(st);
    return rc;
}

typedef struct bad { const char *text, *expect; } bad;

#define HEAD "{\n  \"study\": \"t\",\n"
#define UNIQUE "  \"scenes\": [\"plate_clamped\"],\n"
#define MS "  \"methods\": [\"rmtr\"],\n  \"solvers\": [\"tr\"],\n"

static const bad bads[] = {
    { HEAD "  \"bogus\": 1,\n" UNIQUE MS "  \"res\": [4]\n}",
      "s.json:3:3: at /bogus: unknown key \"bogus\"" },
    { HEAD UNIQUE "  \"methods\": [\"rmtr\", \"no_such_method\"],\n  \"solvers\": [\"tr\"],\n  \"res\": [4]\n}",
      "s.json:4:23: at /methods/1: unknown method \"no_such_method\"" },
    { HEAD UNIQUE "  \"methods\": [\"rmtr\"],\n  \"solvers\": [{\"solver\": \"rmtr\", \"levels\": 1}],\n  \"res\": [4]\n}",
      "s.json:5:44: at /solvers/0/levels: solver rmtr needs at least 2 levels" },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"rules\": [{\"scene\": \"drape\", \"set\": {\"run.max_iter\": 5}}]\n}",
      "s.json:7:23: at /rules/0/scene: scene \"drape\" is not in this study" },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"set\": {\"solver.bogus\": 1}\n}",
      "s.json:7:27: at /set/solver.bogus: " },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"set\": {\"run.max_iter\": 0}\n}",
      "s.json:7:27: at /set/run.max_iter: " },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"dofs\": [300]\n}",
      "s.json:7:3: at /dofs: give \"res\" or \"dofs\", not both" },
    { HEAD "  \"scenes\": [\"tests/scenes/drooping_1step.json\"],\n" MS "  \"res\": [4]\n}",
      "s.json:3:14: at /scenes/0: scene drooping_1step has no analytic reference: say \"solution\"" },
    { HEAD "  \"scenes\": [{\"scene\": \"tests/scenes/drooping_1step.json\", \"solution\": \"unique\"}],\n" MS "  \"res\": [4]\n}",
      "s.json:3:14: at /scenes/0: scene drooping_1step is \"unique\" but has nothing to measure the error against" },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"targets\": [1e-3, 1e-2]\n}",
      "s.json:7:21: at /targets/1: targets must decrease" },
    { HEAD UNIQUE MS "  \"res\": [8, 4]\n}",
      "s.json:6:14: at /res/1: must be larger than the entry before" },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"vary\": {\"solver.eta9\": [0.1, 0.2]}\n}",
      "s.json:7:27: at /vary/solver.eta9: --set solver.eta9=0.1: unknown parameter" },
    { HEAD UNIQUE "  \"methods\": [{\"method\": \"rmtr\", \"set\": {\"solver.eta1\": 0.2}}],\n  \"solvers\": [\"tr\"],\n  \"res\": [4]\n}",
      "s.json:4:42: at /methods/0/set/solver.eta1: parameter \"solver.eta1\" cannot be set here" },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"dt\": {\"max\": 1}\n}",
      "s.json:7:3: at /dt: \"dt\" belongs to a study of kind \"dt_stability\"" },
    { HEAD "  \"kind\": \"dt_stability\",\n" UNIQUE MS "  \"res\": [4],\n  \"dt\": {\"max\": 1}\n}",
      "s.json:4:14: at /scenes/0: a dt study needs dynamic scenes" },
    { HEAD "  \"kind\": \"dt_stability\",\n  \"scenes\": [{\"scene\": \"trampoline\", \"solution\": \"unique\"}],\n" MS
      "  \"res\": [4],\n  \"dt\": {\"max\": 1, \"min\": 1e-5, \"descent\": 1}\n}",
      "s.json:8:44: at /dt/descent: must be a factor above 1.5" },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"rules\": [{\"method\": \"rmtr\"}]\n}",
      "s.json:7:13: at /rules/0: the rule does nothing" },
    { HEAD UNIQUE MS "  \"res\": [4]\n  \"samples\": 5\n}",
      "s.json:7:11: at /: invalid JSON: " },
    { HEAD UNIQUE "  \"methods\": \"all\",\n  \"solvers\": [\"tr\"],\n  \"res\": [4],\n  \"rules\": [{\"method\": \"rmtr\", \"solver\": \"tr\", \"skip\": \"\"}]\n}",
      "s.json:7:56: at /rules/0/skip: say why the runs are skipped" },
    { HEAD UNIQUE MS "  \"res\": [4],\n  \"rules\": [{\"solver\": \"tr\", \"levels\": 3, \"res\": [4]}]\n}",
      "s.json:7:40: at /rules/0/levels: no solver of this study runs on 3 levels" },
    /* a solver entry's "linear" (issue 38: Krylov paths as configurations of their own) */
    { HEAD UNIQUE "  \"methods\": [\"bhem\"],\n  \"solvers\": [{\"solver\": \"lsnewton\", \"linear\": \"pcg-gmres\"}],\n  \"res\": [4]\n}",
      "s.json:5:48: at /solvers/0/linear: unknown linear solver \"pcg-gmres\"" },
    { HEAD UNIQUE "  \"methods\": [\"bhem\"],\n  \"solvers\": [{\"solver\": \"lsnewton\", \"levels\": 2, \"linear\": \"pcg-mg\"}, "
      "{\"solver\": \"lsnewton\", \"levels\": 2, \"linear\": \"pcg-mg\"}],\n  \"res\": [4]\n}",
      "s.json:5:83: at /solvers/1/solver: solver \"lsnewton\" with 2 levels and linear solver pcg-mg is listed twice" },
    { HEAD UNIQUE "  \"methods\": [\"bhem\"],\n  \"solvers\": [{\"solver\": \"lsnewton\", \"linear\": \"pcg-mg\", "
      "\"set\": {\"solver.linear\": \"cholmod\"}}],\n  \"res\": [4]\n}",
      "s.json:5:48: at /solvers/0/linear: given twice" },
};

SB_TEST(study_file_errors_name_file_line_and_column)
{
    char err[2048];
    for (size_t k = 0; k < sizeof bads / sizeof *bads; k++) {
        int rc = parse(bads[k].text, err, sizeof err);
        CHECK_MSG(rc == SB_ERR_INPUT, "case %zu parsed (rc %d)", k, rc);
        CHECK_MSG(strncmp(err, bads[k].expect, strlen(bads[k].expect)) == 0, "case %zu:\n      got    %s\n      expect %s", k, err,
                  bads[k].expect);
    }
}

SB_TEST(a_good_study_plans_every_registered_method)
{
    char err[2048];
    sb_study *st = calloc(1, sizeof *st);
    const char *text = HEAD "  \"scenes\": [\"plate_clamped\", {\"scene\": \"drooping\", \"solution\": \"multiple\", "
                       "\"starts\": {\"perturb\": 1e-4, \"seeds\": [1, 2]}}, \"strip_end_moment\"],\n"
                       "  \"methods\": \"all\",\n  \"solvers\": [\"tr\", {\"solver\": \"rmtr\", \"levels\": 2}, \"linearized\"],\n"
                       "  \"dofs\": [300],\n  \"vary\": {\"run.gtol\": [1e-7, 1e-8]},\n"
                       "  \"rules\": [{\"scene\": \"plate_clamped\", \"solver\": \"rmtr\", \"skip\": \"not needed\"}]\n}";
    int rc = sb_study_parse_string(text, "s.json", tmpdir, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return; }
    int methods = 0;
    for (int k = 0; k < sb_method_count(); k++) methods += !(sb_method_at(k)->flags & SB_METHOD_TEST_FIXTURE);
    CHECK_EQ_INT(st->n_methods, methods);
    sb_plan p;
    CHECK(sb_study_plan(st, &p, err, sizeof err) == 0);
    int runs = 0, skipped = 0, refused = 0, starts = 0, per_method[SB_STUDY_MAX_METHODS] = { 0 };
    for (int k = 0; k < p.n; k++) {
        const sb_plan_run *r = &p.runs[k];
        runs += r->state == SB_PLAN_RUN;
        skipped += r->state == SB_PLAN_SKIP;
        refused += r->state == SB_PLAN_REFUSED;
        starts += r->state == SB_PLAN_RUN && r->start > 0;
        if (r->state == SB_PLAN_RUN) {
            per_method[r->method]++;
            /* within a factor 1.6 of the target: the nearest resolution in ratio */
            CHECK_MSG(r->dofs > 300 / 1.6 && r->dofs < 300 * 1.6, "%s at res %d: %ld dofs for a 300-dof target",
                      st->methods[r->method].name, r->res, r->dofs);
        }
        if (r->state == SB_PLAN_RUN && r->start > 0) CHECK(strstr(r->out, "-s1.h5") || strstr(r->out, "-s2.h5"));
    }
    for (int m = 0; m < st->n_methods; m++) CHECK_MSG(per_method[m] > 0, "method %s has no run", st->methods[m].name);
    CHECK_EQ_INT(skipped, st->n_methods * 2);     /* plate_clamped x rmtr solver x 2 variants */
    CHECK(starts > 0);
    CHECK(refused >= 1);                          /* rmtr refuses the end moment */
    sb_plan_free(&p);
    sb_study_free(st);
    free(st);
}

/* a rule with "levels" applies to the solver entries with that level count
 * only: rmtr on 2 levels at res 8, on 3 levels at res 16 (the scaling
 * study's levels growing with size), tr at both */
SB_TEST(a_rule_matches_solver_entries_by_levels)
{
    char err[2048];
    sb_study *st = calloc(1, sizeof *st);
    const char *text = HEAD UNIQUE "  \"methods\": [\"rmtr\"],\n"
                       "  \"solvers\": [\"tr\", {\"solver\": \"rmtr\", \"levels\": 2}, {\"solver\": \"rmtr\", \"levels\": 3}],\n"
                       "  \"res\": [8, 16],\n  \"rules\": [{\"solver\": \"rmtr\", \"levels\": 2, \"res\": [8]},\n"
                       "            {\"solver\": \"rmtr\", \"levels\": 3, \"res\": [16]}]\n}";
    int rc = sb_study_parse_string(text, "s.json", tmpdir, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return; }
    sb_plan p;
    rc = sb_study_plan(st, &p, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc == 0) {
        int tr = 0, l2 = 0, l3 = 0;
        for (int k = 0; k < p.n; k++) {
            const sb_plan_run *r = &p.runs[k];
            if (r->state != SB_PLAN_RUN) continue;
            const sb_study_solver *so = &st->solvers[r->solver];
            if (so->levels == 1) tr++;
            else if (so->levels == 2) { l2++; CHECK_EQ_INT(r->res, 8); }
            else if (so->levels == 3) { l3++; CHECK_EQ_INT(r->res, 16); }
        }
        CHECK_EQ_INT(tr, 2);
        CHECK_EQ_INT(l2, 1);
        CHECK_EQ_INT(l3, 1);
        sb_plan_free(&p);
    }
    sb_study_free(st);
    free(st);
}

SB_TEST(a_bad_study_runs_nothing)
{
    char path[400], cmd[1200], dir[400];
    snprintf(path, sizeof path, "%s/bad.json", tmpdir);
    snprintf(dir, sizeof dir, "%s/records", tmpdir);
    FILE *f = fopen(path, "w");
    fprintf(f, HEAD UNIQUE MS "  \"res\": [4],\n  \"records\": \"%s\",\n  \"set\": {\"run.max_iter\": -1}\n}\n", dir);
    fclose(f);
    snprintf(cmd, sizeof cmd, "%s sweep --study %s > %s/out.txt 2>&1", sb_test_bin(), path, tmpdir);
    CHECK_EQ_INT(WEXITSTATUS(system(cmd)), 2);
    struct stat s;
    CHECK_MSG(stat(dir, &s) != 0, "the records directory was created");
    snprintf(cmd, sizeof cmd, "grep -q 'bad.json:8:27: at /set/run.max_iter' %s/out.txt", tmpdir);
    CHECK_EQ_INT(system(cmd), 0);
}

/* every committed study (bench/studies, bench/nightly) loads and plans with
 * the methods this build registers: a method that joins the registry must
 * not break `make run` (adaptive_sqrt3 has only linearized, which the
 * default study did not list) */
SB_TEST(every_committed_study_plans)
{
    const char *files[] = { "bench/studies/default.json", "bench/studies/accuracy.json",
                            "bench/studies/dt_stability.json", "bench/studies/dt_stability_large.json",
                            "bench/studies/dt_stability_large_rmtr.json",
                            "bench/studies/scaling_small.json", "bench/nightly/nightly.json",
                            "bench/studies/accuracy_sqrt3.json" };
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        char err[2048];
        sb_study *st = calloc(1, sizeof *st);
        if (!st) return;
        int rc = sb_study_load(files[i], tmpdir, st, err, sizeof err);
        CHECK_MSG(rc == 0, "%s: %s", files[i], err);
        if (rc == 0) {
            sb_plan p;
            rc = sb_study_plan(st, &p, err, sizeof err);
            CHECK_MSG(rc == 0, "%s: %s", files[i], err);
            int runs = 0;
            for (int k = 0; rc == 0 && k < p.n; k++) runs += p.runs[k].state == SB_PLAN_RUN;
            CHECK_MSG(rc != 0 || runs > 0, "%s plans no run", files[i]);
            if (rc == 0) sb_plan_free(&p);
            sb_study_free(st);
        }
        free(st);
    }
}

/* a study sizes a run with the parameters the run applies: the scene's
 * bundled method.* sets first ("methods": {"adaptive_sqrt3": {"set":
 * {"method.adaptive": 0, "method.max_generation": 2}}}), so the dofs of
 * sheet_swing are those of the full-resolution mesh, 3 ((n+1)^2 + 2 n^2) on
 * an n x n base (a split vertex per base triangle), not the base mesh's
 * 3 (n+1)^2 (issue 40: the study planned them on the base mesh) */
SB_TEST(a_scenes_bundled_sets_size_its_runs)
{
    char err[2048];
    sb_study *st = calloc(1, sizeof *st);
    if (!st) return;
    int rc = sb_study_load("bench/studies/accuracy_sqrt3.json", tmpdir, st, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) { free(st); return; }
    sb_plan p;
    rc = sb_study_plan(st, &p, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    int full = 0, adaptive = 0;
    for (int k = 0; rc == 0 && k < p.n; k++) {
        const sb_plan_run *r = &p.runs[k];
        if (r->state != SB_PLAN_RUN) continue;
        const long n = r->res;
        if (!strcmp(st->scenes[r->scene].name, "sheet_swing")) {
            full++;
            CHECK_MSG(r->dofs == 3 * ((n + 1) * (n + 1) + 2 * n * n), "sheet_swing at res %ld planned with %ld dofs", n,
                      r->dofs);
        } else {
            adaptive++;   /* method.adaptive=1: the base mesh the run starts from */
            CHECK_MSG(r->dofs == 3 * (n + 1) * (n + 1), "sheet_swing_adaptive at res %ld planned with %ld dofs", n,
                      r->dofs);
        }
    }
    CHECK(full == 4 && adaptive == 3);
    if (rc == 0) sb_plan_free(&p);
    sb_study_free(st);
    free(st);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_study_file_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    if (chdir(sb_test_root()) != 0) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(study_file_errors_name_file_line_and_column), SB_CASE(a_scenes_bundled_sets_size_its_runs),
        SB_CASE(a_good_study_plans_every_registered_method),
        SB_CASE(a_rule_matches_solver_entries_by_levels), SB_CASE(a_bad_study_runs_nothing),
        SB_CASE(every_committed_study_plans), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
