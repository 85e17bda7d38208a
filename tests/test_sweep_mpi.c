/* test_sweep_mpi.c — distributed sweeps (core/study/sb_sweep_mpi.c,
 * sb_sweep_slurm.c, docs/regression.md): a study swept by `mpirun
 * --oversubscribe -n 3` gives the records of the serial sweep, record by
 * record (status, reason, counts, work units, energy and the sampled final
 * surface bit for bit) and the same deterministic report byte for byte; a
 * rank killed mid-run loses only its run, and `sweep --resume` completes
 * the study with the serial sweep's records; the Slurm job array's tasks,
 * run one by one as Slurm would, do the same.  The MPI cases need mpirun
 * and build/shellbench-mpi (the Makefile builds it when mpicc is found;
 * build/shellbench hands an MPI launch over to it): without them they say
 * so and check instead that a launch under mpirun is refused with a
 * sentence. */
#include "sb_test.h"
#include "cli_sh.h"
#include "sb_record.h"
#include "sb_study_int.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char tmpdir[256], study[400];
static char out[100000], err[100000];

static int have_mpi(void)
{
    static int known = -1;
    if (known < 0) {
        /* the MPI build beside the binary (Makefile: built when mpicc is found) */
        known = sb_sh(out, sizeof out, NULL, 0, "command -v mpirun") == 0 &&
                sb_sh(out, sizeof out, NULL, 0, "test -x \"$(dirname %s)/shellbench-mpi\"", sb_test_bin()) == 0;
        if (!known) printf("# mpirun or build/shellbench-mpi missing: the MPI cases check the refusal instead\n");
    }
    return known;
}

/* Without MPI in the build: a launch under an MPI launcher is refused with
 * a sentence, and nothing is run (the check the MPI cases make instead). */
static void refused_without_mpi(sb_test_state *T)
{
    int rc = sb_sh(out, sizeof out, err, sizeof err, "cd %s && OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0 %s sweep --study %s --dir %s/nompi",
                   sb_test_root(), sb_test_bin(), study, tmpdir);
    CHECK_MSG(rc == 2 && strstr(err, "shellbench-mpi"), "rc %d: %s", rc, err);
    char d[400];
    snprintf(d, sizeof d, "%s/nompi", tmpdir);
    CHECK(access(d, F_OK) != 0);
}

static const char *mpirun(void)
{
    /* as root OpenMPI wants --allow-run-as-root; leaks inside libmpi are not ours */
    return "ASAN_OPTIONS=detect_leaks=0 OMPI_MCA_rmaps_base_oversubscribe=1 mpirun --allow-run-as-root --oversubscribe";
}

static void compare_dirs(sb_test_state *T, const char *a, const char *b)
{
    sb_study *st = malloc(sizeof *st), *sb = malloc(sizeof *sb);
    char e[2048];
    sb_plan pa, pb;
    CHECK(st && sb);
    if (!st || !sb) { free(st), free(sb); return; }
    CHECK_EQ_INT(sb_study_load(study, a, st, e, sizeof e), SB_OK);
    CHECK_EQ_INT(sb_study_load(study, b, sb, e, sizeof e), SB_OK);
    CHECK_EQ_INT(sb_study_plan(st, &pa, e, sizeof e), SB_OK);
    CHECK_EQ_INT(sb_study_plan(sb, &pb, e, sizeof e), SB_OK);
    CHECK_EQ_INT(pa.n, pb.n);
    int compared = 0;
    for (int k = 0; k < pa.n && k < pb.n; k++) {
        if (pa.runs[k].state != SB_PLAN_RUN) continue;
        sb_record_summary x, y;
        int rx = sb_record_read_summary(pa.runs[k].out, &x, e, sizeof e);
        int ry = sb_record_read_summary(pb.runs[k].out, &y, e, sizeof e);
        CHECK_MSG(rx == SB_OK && ry == SB_OK, "%s / %s: %s", pa.runs[k].out, pb.runs[k].out, e);
        if (rx == SB_OK && ry == SB_OK) {
            CHECK_MSG(x.status == y.status && x.reason == y.reason && x.iterations == y.iterations && x.steps == y.steps &&
                      x.work_assembly == y.work_assembly && x.work_qp == y.work_qp && x.dofs == y.dofs &&
                      !memcmp(&x.energy_final, &y.energy_final, sizeof(double)),
                      "%s: status %d/%d iterations %d/%d WU %.17g/%.17g E %.17g/%.17g", pb.runs[k].out, x.status, y.status,
                      x.iterations, y.iterations, x.work_assembly, y.work_assembly, x.energy_final, y.energy_final);
            int na, nb;
            double *sa = NULL, *pa_ = NULL, *sb_ = NULL, *pb_ = NULL;
            if (sb_record_read_samples(pa.runs[k].out, &na, &sa, &pa_, e, sizeof e) == SB_OK &&
                sb_record_read_samples(pb.runs[k].out, &nb, &sb_, &pb_, e, sizeof e) == SB_OK) {
                CHECK_MSG(na == nb && !memcmp(pa_, pb_, (size_t)na * 3 * sizeof(double)), "%s: final surfaces differ", pb.runs[k].out);
            } else {
                CHECK_MSG(0, "samples: %s", e);
            }
            free(sa), free(pa_), free(sb_), free(pb_);
            compared++;
        }
        if (rx == SB_OK) sb_record_summary_free(&x);
        if (ry == SB_OK) sb_record_summary_free(&y);
    }
    CHECK(compared >= 8);
    /* the deterministic reports, byte for byte but for the directories they name */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && SB_GNUPLOT=/nonexistent %s report --study %s --dir %s --out %s/ra --deterministic "
                       "&& SB_GNUPLOT=/nonexistent %s report --study %s --dir %s --out %s/rb --deterministic "
                       "&& sed -e 's#%s/ra#OUT#g' -e 's#%s#DIR#g' %s/ra/report.md > %s/ra.md "
                       "&& sed -e 's#%s/rb#OUT#g' -e 's#%s#DIR#g' %s/rb/report.md > %s/rb.md && cmp %s/ra.md %s/rb.md",
                       sb_test_root(), sb_test_bin(), study, a, b, sb_test_bin(), study, b, b,
                       b, a, b, b, b, b, b, b, b, b), 0);
    sb_plan_free(&pa), sb_plan_free(&pb);
    sb_study_free(st), sb_study_free(sb);
    free(st), free(sb);
}

static int serial_done;

static void serial(sb_test_state *T)
{
    if (serial_done) return;
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --study %s --dir %s/serial --quiet", sb_test_root(),
                       sb_test_bin(), study, tmpdir), 0);
    serial_done = 1;
}

SB_TEST(mpi_sweep_equals_the_serial_sweep)
{
    if (!have_mpi()) { refused_without_mpi(T); return; }
    serial(T);
    int rc = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s -n 3 %s sweep --study %s --dir %s/mpi", sb_test_root(), mpirun(),
                   sb_test_bin(), study, tmpdir);
    CHECK_MSG(rc == 0 && strstr(out, "on 3 MPI ranks") && strstr(out, "rank 1") && strstr(out, "rank 2"), "rc %d\n%s\n%s", rc, out, err);
    char a[400], b[400];
    snprintf(a, sizeof a, "%s/serial", tmpdir);
    snprintf(b, sizeof b, "%s/mpi", tmpdir);
    compare_dirs(T, a, b);
    /* a second sweep has nothing left to do */
    rc = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s -n 2 %s sweep --study %s --dir %s/mpi", sb_test_root(), mpirun(),
               sb_test_bin(), study, tmpdir);
    CHECK_MSG(rc == 0 && strstr(out, "0 to run"), "rc %d\n%s\n%s", rc, out, err);
}

/* the pid in the first lock file under dir (a run under way), or 0 */
static pid_t running_run(const char *dir)
{
    char o[4096];
    if (sb_sh(o, sizeof o, NULL, 0, "cat $(find %s -name '*.h5.lock' 2>/dev/null | head -n 1) 2>/dev/null", dir) != 0) return 0;
    return (pid_t)atol(o);
}

static pid_t parent_of(pid_t pid)
{
    char p[64];
    snprintf(p, sizeof p, "/proc/%ld/stat", (long)pid);
    FILE *f = fopen(p, "r");
    if (!f) return 0;
    long pp = 0;
    char comm[256], state;
    if (fscanf(f, "%*d (%255[^)]) %c %ld", comm, &state, &pp) != 3) pp = 0;
    fclose(f);
    return (pid_t)pp;
}

SB_TEST(a_rank_killed_mid_run_then_resume)
{
    if (!have_mpi()) { refused_without_mpi(T); return; }
    serial(T);
    char dir[400];
    snprintf(dir, sizeof dir, "%s/killed", tmpdir);
    mkdir(dir, 0777);
    pid_t job = fork();
    if (job == 0) {
        char cmd[2000];
        snprintf(cmd, sizeof cmd, "cd %s && %s -n 3 %s sweep --study %s --dir %s > %s/mpirun.log 2>&1", sb_test_root(), mpirun(),
                 sb_test_bin(), study, dir, tmpdir);
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
        _exit(127);
    }
    /* the first run under way: its parent is a rank (a run is a child of its rank) */
    pid_t victim = 0;
    int status = 0, ended = 0;
    for (int i = 0; i < 60000 && !victim && !ended; i++) {   /* until mpirun ends, at most 10 minutes */
        if (waitpid(job, &status, WNOHANG) == job) { ended = 1; break; }
        struct timespec nap = { 0, 10000000 };
        nanosleep(&nap, NULL);
        pid_t run = running_run(dir);
        if (run > 0) victim = parent_of(run);
    }
    CHECK_MSG(victim > 1, "no run under way found");
    if (victim > 1) kill(victim, SIGKILL);
    if (!ended) waitpid(job, &status, 0);
    CHECK_MSG(!(WIFEXITED(status) && WEXITSTATUS(status) == 0), "mpirun exited 0 after a rank was killed");
    char o[64];
    CHECK_EQ_INT(sb_sh(o, sizeof o, NULL, 0, "find %s -name '*.h5' | wc -l", dir), 0);
    int recorded = atoi(o);
    CHECK_MSG(recorded < 16, "%d records after the kill", recorded);
    /* the rest, serially (any rank count would do) */
    int rc = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --study %s --dir %s --resume", sb_test_root(), sb_test_bin(),
                   study, dir);
    CHECK_MSG(rc == 0, "rc %d\n%s\n%s", rc, out, err);
    char a[400];
    snprintf(a, sizeof a, "%s/serial", tmpdir);
    compare_dirs(T, a, dir);
}

SB_TEST(slurm_job_array)
{
    serial(T);
    char dir[400], script[450];
    snprintf(dir, sizeof dir, "%s/slurm", tmpdir);
    snprintf(script, sizeof script, "%s/job.sbatch", tmpdir);
    /* two runs recorded beforehand: the array has the others only */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --study %s --dir %s --max-runs 2 --quiet", sb_test_root(),
                       sb_test_bin(), study, dir), 4);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --study %s --dir %s --emit slurm --out %s", sb_test_root(),
                       sb_test_bin(), study, dir, script), 0);
    CHECK_MSG(strstr(out, "job array of 14 tasks"), "%s%s", out, err);
    FILE *f = fopen(script, "r");
    CHECK(f != NULL);
    if (!f) return;
    size_t n = fread(out, 1, sizeof out - 1, f);
    out[n] = 0;
    fclose(f);
    char *arr = strstr(out, "#SBATCH --array=");
    CHECK_MSG(arr && strstr(out, "--task \"$SLURM_ARRAY_TASK_ID\"") && strstr(out, "#!/bin/bash"), "%s", out);
    /* run every task of the array as Slurm would (sequentially here) */
    int tasks[64], nt = 0;
    if (arr) {
        char *p = arr + strlen("#SBATCH --array=");
        while (*p && *p != '\n' && nt < 64) {
            int lo = (int)strtol(p, &p, 10), hi = lo;
            if (*p == '-') hi = (int)strtol(p + 1, &p, 10);
            for (int t = lo; t <= hi && nt < 64; t++) tasks[nt++] = t;
            if (*p == ',') p++;
        }
    }
    CHECK_EQ_INT(nt, 14);
    for (int k = 0; k < nt; k++)
        CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "SLURM_ARRAY_TASK_ID=%d bash %s", tasks[k], script), 0);
    /* every task once more: recorded, nothing to do; a task out of range: input error */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "SLURM_ARRAY_TASK_ID=%d bash %s", tasks[0], script), 0);
    CHECK(strstr(out, "recorded already") != NULL);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "SLURM_ARRAY_TASK_ID=99 bash %s", script), 2);
    CHECK_MSG(strstr(err, "has 16 tasks"), "%s", err);
    char a[400];
    snprintf(a, sizeof a, "%s/serial", tmpdir);
    compare_dirs(T, a, dir);
    /* nothing left: no script */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --study %s --dir %s --emit slurm --out %s.2", sb_test_root(),
                       sb_test_bin(), study, dir, script), 0);
    CHECK(strstr(out, "nothing to submit") != NULL);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --study %s --emit pbs", sb_test_root(), sb_test_bin(), study), 2);
}

SB_TEST(longest_expected_first)
{
    serial(T);
    sb_study *st = malloc(sizeof *st);
    char e[2048], dir[400];
    snprintf(dir, sizeof dir, "%s/serial", tmpdir);
    CHECK(st != NULL);
    if (!st) return;
    CHECK_EQ_INT(sb_study_load(study, dir, st, e, sizeof e), SB_OK);
    sb_plan p;
    CHECK_EQ_INT(sb_study_plan(st, &p, e, sizeof e), SB_OK);
    int q[64], nq = sb_study_tasks(&p, q);
    double t[64];
    sb_study_order_longest_first(st, &p, q, nq, t);
    for (int k = 1; k < nq; k++) CHECK(t[k - 1] >= t[k]);
    /* the estimate of a recorded run is its own time (same config, same dofs) */
    sb_record_summary s;
    CHECK_EQ_INT(sb_record_read_summary(p.runs[q[0]].out, &s, e, sizeof e), SB_OK);
    CHECK_REL(t[0], s.seconds, 1e-12);
    sb_record_summary_free(&s);
    sb_plan_free(&p);
    sb_study_free(st);
    free(st);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_test_mpi_XXXXXX");
    if (!mkdtemp(tmpdir)) return 1;
    snprintf(study, sizeof study, "%s/study.json", tmpdir);
    FILE *f = fopen(study, "w");
    fprintf(f, "{\"study\": \"mpi\", \"records\": \"%s/unused\",\n"
               " \"scenes\": [\"plate_clamped\", {\"scene\": \"trampoline\", \"solution\": \"unique\"}],\n"
               " \"methods\": [\"bhem\", \"linear_fem\"], \"solvers\": [\"lsnewton\", \"tr\"], \"res\": [4, 6]}\n", tmpdir);
    fclose(f);
    static const sb_test_case cases[] = {
        SB_CASE(mpi_sweep_equals_the_serial_sweep), SB_CASE(a_rank_killed_mid_run_then_resume), SB_CASE(slurm_job_array),
        SB_CASE(longest_expected_first), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) { /* best effort */ }
    return rc;
}
