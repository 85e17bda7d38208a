/* test_resume.c — step-boundary resume (run --resume, --stop-after-steps):
 * a run stopped after a step and resumed, twice, computes bit for bit what
 * an uninterrupted run computes (history, final state, probes, counts and
 * work units; only the symbolic analysis is redone once per resume); a
 * checkpoint of another run, an unreadable one, or a resume without a
 * record path is refused with the file and field named and nothing
 * touched; an existing record is not run again. */
#include "sb_test.h"
#include "sb_record.h"
#include "sb_run.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

typedef struct outcome {
    int exit_code;
    json_t *summary;     /* NULL when the run wrote none */
    char msg[4096];      /* what it said on its error stream */
} outcome;

/* drooping (dynamic: v matters; RMTR's first-step nested start), 363 dofs, 3 levels */
static outcome run(const char *out, int resume, int stop_after, const char *set, int res)
{
    outcome o = { 0 };
    const char *sets[1] = { set };
    sb_run_request req;
    memset(&req, 0, sizeof req);
    req.scene = "drooping";
    req.method = "rmtr";
    req.solver = "rmtr";
    req.res = res;
    req.levels = 3;
    req.out = out;
    req.quiet = 1;
    req.resume = resume;
    req.stop_after_steps = stop_after;
    req.n_sets = set ? 1 : 0;
    req.sets = sets;
    char *buf = NULL, *js = NULL;
    size_t len = 0;
    FILE *err = open_memstream(&buf, &len), *devnull = fopen("/dev/null", "w");
    o.exit_code = sb_run_execute(&req, devnull ? devnull : stdout, err ? err : stderr, &js);
    if (err) fclose(err);
    if (devnull) fclose(devnull);
    snprintf(o.msg, sizeof o.msg, "%s", buf ? buf : "");
    free(buf);
    json_error_t e;
    o.summary = js ? json_loads(js, 0, &e) : NULL;
    free(js);
    return o;
}

static long count_of(json_t *summary, const char *event)
{
    return (long)json_integer_value(json_object_get(json_object_get(summary, "counts"), event));
}

static double num(json_t *o, const char *a, const char *b)
{
    json_t *v = json_object_get(o, a);
    return json_number_value(b ? json_object_get(v, b) : v);
}

static int same_file_state(const char *path, const struct stat *before)
{
    struct stat now;
    return stat(path, &now) == 0 && now.st_size == before->st_size && now.st_mtim.tv_sec == before->st_mtim.tv_sec &&
           now.st_mtim.tv_nsec == before->st_mtim.tv_nsec;
}

SB_TEST(stopped_and_resumed_run_equals_uninterrupted_run)
{
    char a[300], b[300], pb[320];
    snprintf(a, sizeof a, "%s/a.h5", tmpdir);
    snprintf(b, sizeof b, "%s/b.h5", tmpdir);
    snprintf(pb, sizeof pb, "%s.partial", b);
    outcome A = run(a, 0, 0, NULL, 8);
    CHECK_EQ_INT(A.exit_code, SB_EXIT_CONVERGED);
    outcome S1 = run(b, 0, 2, NULL, 8);
    CHECK_EQ_INT(S1.exit_code, SB_EXIT_STOPPED);
    CHECK_MSG(access(pb, R_OK) == 0 && access(b, F_OK) != 0, "stopped run: want %s and no record", pb);
    sb_record_summary rs;
    char msg[1024];
    CHECK_EQ_INT(sb_record_read_summary(pb, &rs, msg, sizeof msg), SB_OK);
    CHECK_MSG(rs.status == SB_STATUS_UNFINISHED && rs.resume_point == 2 && rs.steps == 2 && rs.resumes == 0,
              "checkpoint: status %d, resume point %d, steps %d", rs.status, rs.resume_point, rs.steps);
    sb_record_summary_free(&rs);
    outcome S2 = run(b, 1, 3, NULL, 8);                /* resume after step 2, stop after step 3 */
    CHECK_EQ_INT(S2.exit_code, SB_EXIT_STOPPED);
    outcome B = run(b, 1, 0, NULL, 8);                 /* resume after step 3 to the end */
    CHECK_EQ_INT(B.exit_code, SB_EXIT_CONVERGED);
    CHECK_MSG(access(pb, F_OK) != 0, "the finished run left its checkpoint %s", pb);
    CHECK(A.summary && B.summary);
    if (!A.summary || !B.summary) return;
    /* the counts: equal (a resumed process's repeat of a symbolic analysis is
     * set-up, in the resume log), but for checkpoint, which follows the clock */
    const char *events[] = { "energy", "gradient", "hessian", "analyze", "factorize", "solve", "cg_iter", "qp",
                             "transfer", "galerkin", "record" };
    for (int e = 0; e < 11; e++)
        CHECK_MSG(count_of(A.summary, events[e]) == count_of(B.summary, events[e]), "%s: %ld uninterrupted, %ld resumed",
                  events[e], count_of(A.summary, events[e]), count_of(B.summary, events[e]));
    CHECK(num(A.summary, "work_units", "assembly") == num(B.summary, "work_units", "assembly"));
    CHECK(num(A.summary, "work_units", "qp") == num(B.summary, "work_units", "qp"));
    CHECK(num(A.summary, "iterations", NULL) == num(B.summary, "iterations", NULL) && num(A.summary, "iterations", NULL) > 5);
    CHECK_EQ_INT((int)num(B.summary, "resumed", "count"), 2);
    CHECK(strcmp(json_string_value(json_object_get(json_object_get(B.summary, "resumed"), "after_steps")), "2,3") == 0);
    CHECK_EQ_INT((int)num(A.summary, "resumed", "count"), 0);
    /* the records: history and final state bit for bit */
    sb_record_summary ra, rb;
    CHECK_EQ_INT(sb_record_read_summary(a, &ra, msg, sizeof msg), SB_OK);
    CHECK_EQ_INT(sb_record_read_summary(b, &rb, msg, sizeof msg), SB_OK);
    CHECK_EQ_INT(ra.n_hist, rb.n_hist);
    if (ra.n_hist == rb.n_hist) {
        CHECK(memcmp(ra.hist_gnorm, rb.hist_gnorm, (size_t)ra.n_hist * sizeof *ra.hist_gnorm) == 0);
        CHECK(memcmp(ra.hist_step, rb.hist_step, (size_t)ra.n_hist * sizeof *ra.hist_step) == 0);
        CHECK(memcmp(ra.hist_level, rb.hist_level, (size_t)ra.n_hist * sizeof *ra.hist_level) == 0);
    }
    CHECK(ra.seconds > 0 && rb.seconds > 0);
    sb_record_summary_free(&ra);
    sb_record_summary_free(&rb);
    sb_record_setup xa, xb;
    CHECK_EQ_INT(sb_record_read_setup(a, &xa, msg, sizeof msg), SB_OK);
    CHECK_EQ_INT(sb_record_read_setup(b, &xb, msg, sizeof msg), SB_OK);
    CHECK(xa.n_x == xb.n_x && xa.n_x > 0 && memcmp(xa.x, xb.x, (size_t)xa.n_x * sizeof *xa.x) == 0);
    sb_record_setup_free(&xa);
    sb_record_setup_free(&xb);
    json_t *pa = json_object_get(json_object_get(A.summary, "probes"), "free_corner");
    json_t *pbj = json_object_get(json_object_get(B.summary, "probes"), "free_corner");
    CHECK(pa && json_equal(pa, pbj));
    /* the report's CSV says so */
    char *csv = NULL;
    size_t csv_len = 0;
    FILE *mem = open_memstream(&csv, &csv_len);
    char *files[1] = { b };
    CHECK(mem && sb_report(1, files, "csv", mem, NULL, msg, sizeof msg) == SB_OK);
    if (mem) fclose(mem);
    CHECK_MSG(csv && strstr(csv, ",resumes,resume_steps,resume_point,res,parameters\n") && strstr(csv, ",2,\"2,3\",,"), "CSV: %s", csv ? csv : "");
    free(csv);
    /* a resume of a recorded run does not run it again */
    struct stat before;
    CHECK(stat(b, &before) == 0);
    outcome R = run(b, 1, 0, NULL, 8);
    CHECK_EQ_INT(R.exit_code, SB_EXIT_CONVERGED);
    CHECK_MSG(R.summary == NULL && same_file_state(b, &before), "the recorded run %s was run again", b);
    json_decref(A.summary);
    json_decref(B.summary);
    json_decref(R.summary);
}

SB_TEST(resume_refuses_another_runs_checkpoint_and_touches_nothing)
{
    char c[300], pc[320], d[300], pd[320];
    snprintf(c, sizeof c, "%s/c.h5", tmpdir);
    snprintf(pc, sizeof pc, "%s.partial", c);
    outcome S = run(c, 0, 1, NULL, 8);
    CHECK_EQ_INT(S.exit_code, SB_EXIT_STOPPED);
    struct stat before;
    CHECK(stat(pc, &before) == 0);
    outcome P = run(c, 1, 0, "solver.eta1=0.2", 8);      /* another parameter value */
    CHECK_EQ_INT(P.exit_code, SB_EXIT_INPUT);
    CHECK_MSG(strstr(P.msg, pc) && strstr(P.msg, "parameter solver.eta1"), "message: %s", P.msg);
    outcome Q = run(c, 1, 0, NULL, 4);                   /* another resolution */
    CHECK_EQ_INT(Q.exit_code, SB_EXIT_INPUT);
    CHECK_MSG(strstr(Q.msg, "its res is 8, this run's is 4"), "message: %s", Q.msg);
    CHECK_MSG(same_file_state(pc, &before), "a refused resume changed %s", pc);
    CHECK(access(c, F_OK) != 0);
    /* the checkpoint interval may differ */
    outcome K = run(c, 1, 0, "run.checkpoint=1e6", 8);
    CHECK_EQ_INT(K.exit_code, SB_EXIT_CONVERGED);
    /* not a record */
    snprintf(d, sizeof d, "%s/d.h5", tmpdir);
    snprintf(pd, sizeof pd, "%s.partial", d);
    FILE *f = fopen(pd, "w");
    CHECK(f != NULL);
    if (f) { fputs("not HDF5\n", f); fclose(f); }
    CHECK(stat(pd, &before) == 0);
    outcome G = run(d, 1, 0, NULL, 8);
    CHECK_EQ_INT(G.exit_code, SB_EXIT_INPUT);
    CHECK_MSG(strstr(G.msg, pd) != NULL, "message: %s", G.msg);
    CHECK(same_file_state(pd, &before));
    /* no record path */
    outcome N = run("none", 1, 0, NULL, 8);
    CHECK_EQ_INT(N.exit_code, SB_EXIT_INPUT);
    CHECK(strstr(N.msg, "--out") != NULL);
    json_decref(K.summary);
}

/* sweep --resume: runs already recorded are not run again */
SB_TEST(sweep_resume_skips_recorded_runs)
{
    char cmd[2048], rec[400];
    snprintf(cmd, sizeof cmd, "%s sweep --scenes trampoline --methods fixture_membrane --solvers tr,lsnewton --res 6 "
             "--dir %s/sw --resume >/dev/null 2>&1", sb_test_bin(), tmpdir);
    CHECK_EQ_INT(system(cmd), 0);
    snprintf(rec, sizeof rec, "%s/sw/trampoline-fixture_membrane-tr-r6-l1.h5", tmpdir);
    struct stat before;
    CHECK_MSG(stat(rec, &before) == 0, "the sweep wrote no %s", rec);
    CHECK_EQ_INT(system(cmd), 0);
    CHECK_MSG(same_file_state(rec, &before), "sweep --resume ran %s again", rec);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_resume_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    if (chdir(sb_test_root()) != 0) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(stopped_and_resumed_run_equals_uninterrupted_run),
        SB_CASE(resume_refuses_another_runs_checkpoint_and_touches_nothing),
        SB_CASE(sweep_resume_skips_recorded_runs), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
