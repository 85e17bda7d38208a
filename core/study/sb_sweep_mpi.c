/* sb_sweep_mpi.c — `mpirun -n N shellbench sweep --study FILE`: a study's
 * runs distributed over MPI ranks (docs/regression.md "Distributed
 * sweeps").  Compiled twice: without MPI into libshellbench.a (the
 * ordinary build/shellbench, which under an MPI launcher execs the MPI
 * build beside it), and, when the Makefile finds mpicc, with SB_HAVE_MPI
 * into build/shellbench-mpi, the only binary that links libmpi.
 *
 * Rank 0 plans (as every rank does: the plan is deterministic), queues the
 * runs without a record or refusal marker, longest expected first
 * (sb_sweep_order.c), and hands them out one at a time to whichever rank
 * asks; it runs runs itself between messages.  Every run is a child process
 * of its rank (sb_study_start_child), exactly as `--jobs` runs it: it writes
 * its record atomically, leaves a refusal marker or keeps its log, so the
 * records are those of a serial sweep whatever rank ran them.  The child
 * dies with its rank (PR_SET_PDEATHSIG), so a rank that dies loses its
 * current run only (its checkpoint stays); the launcher then ends the job,
 * and `sweep --study FILE` again (serially or under mpirun) runs what is
 * not recorded.
 *
 * Messages: a worker sends TAG_READY {finished run or -1, its exit code};
 * rank 0 answers TAG_RUN {run index, or -1: no more work}. */
#include "sb_study_int.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef SB_HAVE_MPI

/* This object is the one in libshellbench.a: the ordinary binary and the
 * test programs, which do not load libmpi and its libraries (and so never
 * meet MPI under the sanitizers or in a forked run).  Under an MPI launcher
 * it hands over to the MPI build beside it, BUILD/shellbench-mpi, with the
 * same arguments. */
int sb_study_sweep_mpi(const sb_study *st, const sb_sweep_options *o, int argc, char **argv, FILE *out, FILE *err)
{
    (void)st, (void)o, (void)out;
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 16);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        snprintf(slash ? slash + 1 : exe, sizeof exe - (size_t)(slash ? slash + 1 - exe : 0), "shellbench-mpi");
        char **args = calloc((size_t)argc + 3, sizeof *args);
        if (args && access(exe, X_OK) == 0) {
            args[0] = exe;
            args[1] = (char *)"sweep";
            for (int i = 0; i < argc; i++) args[i + 2] = argv[i];
            fflush(NULL);
            execv(exe, args);
        }
        free(args);
    }
    const char *rank = getenv("OMPI_COMM_WORLD_RANK");
    if (!rank || !strcmp(rank, "0"))
        fprintf(err, "shellbench sweep: started by an MPI launcher, but this build has no MPI (no shellbench-mpi beside "
                     "it: mpicc was not found at build time; install openmpi with scripts/ensure_deps.sh and run make); "
                     "without MPI run `sweep --study FILE --jobs N` or a job array (`--emit slurm`)\n");
    return SB_EXIT_INPUT;
}

#else

#include <errno.h>
#include <mpi.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

enum { TAG_READY = 101, TAG_RUN = 102 };

/* a run of this rank in a child process (which dies with the rank) */
static pid_t start_run(const sb_study *st, const sb_plan_run *r, FILE *err) { return sb_study_start_child(st, r, err); }

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int wait_child(pid_t pid)
{
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return SB_EXIT_INTERNAL;
    return WIFEXITED(status) ? WEXITSTATUS(status) : SB_EXIT_INTERNAL;
}

/* Wait for a request without spinning: OpenMPI's blocking calls poll at
 * full speed, which on a machine with as many ranks as cores would take
 * the cores from the runs. */
static void wait_request(MPI_Request *q)
{
    int done = 0;
    for (;;) {
        MPI_Test(q, &done, MPI_STATUS_IGNORE);
        if (done) return;
        struct timespec nap = { 0, 2000000 };   /* 2 ms */
        nanosleep(&nap, NULL);
    }
}

static void report(FILE *out, const sb_sweep_options *o, int done, int nq, const sb_plan_run *r, const char *what,
                   int rank, double t)
{
    if (o->quiet) return;
    fprintf(out, "[%d/%d] %-64s %s (rank %d, %.1f s)\n", done, nq, r->out, what, rank, t);
    fflush(out);
}

static int worker(const sb_study *st, const sb_plan *plan, FILE *err)
{
    int msg[2] = { -1, 0 };
    for (;;) {
        MPI_Request q;
        MPI_Isend(msg, 2, MPI_INT, 0, TAG_READY, MPI_COMM_WORLD, &q);
        wait_request(&q);
        int run;
        MPI_Irecv(&run, 1, MPI_INT, 0, TAG_RUN, MPI_COMM_WORLD, &q);
        wait_request(&q);
        if (run < 0) return 0;
        const sb_plan_run *r = &plan->runs[run];
        pid_t pid = start_run(st, r, err);
        int code = pid < 0 ? SB_EXIT_INTERNAL : wait_child(pid);
        sb_study_finish_child(r, code, err);
        msg[0] = run, msg[1] = code;
    }
}

static int scheduler(const sb_study *st, const sb_plan *plan, const sb_sweep_options *o, int size, FILE *out, FILE *err)
{
    int *queue = malloc((size_t)(plan->n ? plan->n : 1) * sizeof *queue), nq = 0, recorded = 0;
    double *t0 = calloc((size_t)(plan->n ? plan->n : 1), sizeof *t0);
    if (!queue || !t0) {
        free(queue), free(t0);
        MPI_Abort(MPI_COMM_WORLD, SB_EXIT_INTERNAL);
        return SB_EXIT_INTERNAL;
    }
    int misplaced = 0;
    char why[3072];
    for (int k = 0; k < plan->n; k++) {
        const sb_plan_run *r = &plan->runs[k];
        if (r->state != SB_PLAN_RUN) continue;
        if (access(r->out, F_OK) == 0 && sb_study_record_check(st, r, why, sizeof why) == SB_ERR_INPUT) {
            /* another run's record in this run's place (sb_study_records.c) */
            fprintf(err, "shellbench sweep: %s\n", why);
            misplaced++;
            continue;
        }
        if (sb_study_run_done(r)) { recorded++; continue; }
        queue[nq++] = k;
    }
    if (misplaced) {   /* nothing is run: the ranks are released at once */
        fprintf(err, "shellbench sweep: %d record%s of study %s %s not the planned run%s: nothing run\n", misplaced,
                misplaced > 1 ? "s" : "", st->name, misplaced > 1 ? "are" : "is", misplaced > 1 ? "s" : "");
        nq = 0;
    }
    /* every output before the first run: refused, no rank runs anything */
    const int refused = misplaced || sb_study_check_outputs(plan, queue, nq, err) != 0;
    if (refused) nq = 0;
    int total_new = nq;
    sb_study_order_longest_first(st, plan, queue, nq, NULL);
    if (o->max_runs > 0 && nq > o->max_runs) nq = o->max_runs;
    if (!refused)
        fprintf(out, "study %s: %d runs planned, %d already recorded, %d to run%s on %d MPI ranks, longest expected first\n",
            st->name, recorded + total_new, recorded, nq, nq < total_new ? " now" : "", size);
    fflush(out);
    int next = 0, done = 0, failed = 0, stopped = 0, local = -1;
    pid_t local_pid = -1;
    while (stopped < size - 1 || local >= 0 || (size == 1 && next < nq)) {
        /* answer every rank that asks */
        int flag = 1;
        while (flag) {
            MPI_Status s;
            MPI_Iprobe(MPI_ANY_SOURCE, TAG_READY, MPI_COMM_WORLD, &flag, &s);
            if (!flag) break;
            int msg[2];
            MPI_Recv(msg, 2, MPI_INT, s.MPI_SOURCE, TAG_READY, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            if (msg[0] >= 0) {
                const sb_plan_run *r = &plan->runs[msg[0]];
                done++;
                failed += msg[1] == SB_EXIT_INTERNAL;
                const char *what = msg[1] == SB_EXIT_CONVERGED ? "converged" : msg[1] == SB_EXIT_NOT_CONVERGED ? "NOT converged"
                                 : msg[1] == SB_EXIT_INPUT ? "refused" : "internal error (log kept)";
                report(out, o, done, nq, r, what, s.MPI_SOURCE, now_s() - t0[msg[0]]);
            }
            int run = next < nq ? queue[next++] : -1;
            if (run >= 0) t0[run] = now_s();
            else stopped++;
            MPI_Send(&run, 1, MPI_INT, s.MPI_SOURCE, TAG_RUN, MPI_COMM_WORLD);
        }
        /* rank 0's own run */
        if (local >= 0) {
            int status;
            pid_t w = waitpid(local_pid, &status, WNOHANG);
            if (w == local_pid || (w < 0 && errno != EINTR)) {
                int code = w == local_pid && WIFEXITED(status) ? WEXITSTATUS(status) : SB_EXIT_INTERNAL;
                const char *what = sb_study_finish_child(&plan->runs[local], code, err);
                done++;
                failed += code == SB_EXIT_INTERNAL;
                report(out, o, done, nq, &plan->runs[local], what, 0, now_s() - t0[local]);
                local = -1;
            }
        }
        if (local < 0 && next < nq) {
            local = queue[next++];
            t0[local] = now_s();
            local_pid = start_run(st, &plan->runs[local], err);
            if (local_pid < 0) {
                sb_study_finish_child(&plan->runs[local], SB_EXIT_INTERNAL, err);
                failed++, done++;
                local = -1;
            }
        }
        struct timespec nap = { 0, 5000000 };   /* 5 ms between polls */
        nanosleep(&nap, NULL);
    }
    free(queue), free(t0);
    if (refused) return SB_EXIT_INPUT;
    if (failed) {
        fprintf(err, "shellbench sweep: %d run%s failed (internal error; logs kept beside the records)\n", failed, failed > 1 ? "s" : "");
        return SB_EXIT_INTERNAL;
    }
    if (nq < total_new) {
        fprintf(out, "stopped after %d new runs as asked; %d left (run the same command again to continue)\n", nq, total_new - nq);
        return SB_EXIT_STOPPED;
    }
    fprintf(out, "study %s: every run recorded under %s\n", st->name, st->records);
    return SB_EXIT_CONVERGED;
}

int sb_study_sweep_mpi(const sb_study *st, const sb_sweep_options *o, int argc, char **argv, FILE *out, FILE *err)
{
    (void)argc, (void)argv;
    int rank = 0, size = 1;
    if (MPI_Init(NULL, NULL) != MPI_SUCCESS) {
        fprintf(err, "shellbench sweep: MPI_Init failed\n");
        return SB_EXIT_INTERNAL;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    sb_plan plan;
    char msg[1024];
    int rc;
    if (sb_study_plan(st, &plan, msg, sizeof msg)) {
        if (rank == 0) fprintf(err, "shellbench sweep: %s: %s\n", st->path, msg);
        rc = SB_EXIT_INPUT;   /* every rank plans alike, so every rank stops here */
    } else {
        rc = rank == 0 ? scheduler(st, &plan, o, size, out, err) : worker(st, &plan, err);
        sb_plan_free(&plan);
    }
    /* every rank returns rank 0's verdict (waiting without spinning) */
    MPI_Request q;
    MPI_Ibcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD, &q);
    wait_request(&q);
    MPI_Finalize();
    return rc;
}

#endif
