/* sb_study_sweep.c — `shellbench sweep --study FILE`: run every planned run
 * that has neither a record nor a refusal marker, `jobs` at a time, each in
 * a child process of its own (a crash in one run is that run's outcome, not
 * the sweep's).  Records are written atomically by the run, so a sweep that
 * is interrupted keeps every finished record and a second sweep continues
 * where the first stopped; runs interrupted mid-way continue from their
 * checkpoint (sb_run_request.resume).  A run the method or solver refuses
 * (exit 2) leaves OUT.refused with its sentence: the report lists it, and
 * no later sweep tries it again (delete the marker to retry). */
#include "sb_output.h"
#include "sb_study_int.h"
#include "sb_run.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

int sb_study_run_one(const sb_study *st, const sb_plan_run *r, FILE *err)
{
    const char *sets[sizeof r->sets / sizeof r->sets[0]];
    for (int k = 0; k < r->n_sets; k++) sets[k] = r->sets[k];
    char scene[1100];
    if (r->dt > 0) {
        if (sb_study_dt_scene(st, r, scene, sizeof scene, err)) return SB_EXIT_INTERNAL;
    } else {
        snprintf(scene, sizeof scene, "%s", st->scenes[r->scene].path);
    }
    sb_run_request q;
    memset(&q, 0, sizeof q);
    q.scene = scene;
    q.method = st->methods[r->method].name;
    q.solver = st->solvers[r->solver].name;
    q.res = r->res;
    q.levels = r->levels;
    q.out = r->out;
    q.n_sets = r->n_sets;
    q.sets = sets;
    q.quiet = 1;
    q.sample_n = st->samples;
    q.resume = 1;
    q.allow_unsealed_reference = st->allow_unsealed_reference;
    return sb_run_execute(&q, stdout, err, NULL);
}

static int exists(const char *p)
{
    struct stat s;
    return stat(p, &s) == 0;
}

/* 1 when the run has a record or a refusal marker already */
int sb_study_run_done(const sb_plan_run *r)
{
    char ref[1100];
    sb_plan_refused_path(r->out, ref, sizeof ref);
    return exists(r->out) || exists(ref);
}

typedef struct child {
    pid_t pid;
    int run;
    double t0;
} child;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void log_path(const sb_plan_run *r, char *buf, size_t len) { snprintf(buf, len, "%s.log", r->out); }

static int mkdirs_for(const char *file)
{
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s", file);
    for (char *p = tmp + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0777) && errno != EEXIST) return -1;
            *p = '/';
        }
    return 0;
}

pid_t sb_study_start_child(const sb_study *st, const sb_plan_run *r, FILE *err)
{
    char lp[1100];
    log_path(r, lp, sizeof lp);
    if (mkdirs_for(lp)) {
        sb_escape_print(err, "shellbench sweep: cannot create the directory of %s: %s", lp, strerror(errno));
        return -1;
    }
    fflush(NULL);
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid != 0) return pid;
    /* the child dies with the sweep (or MPI rank) that started it: a killed
     * sweep leaves no orphan run behind, only the run's checkpoint */
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(SB_EXIT_INTERNAL);
    /* the run's peak_rss is its own, not the sweep's (issue 42) */
    sb_peak_rss_reset();
    /* the child: its messages into OUT.log, its stdout discarded */
    FILE *log = fopen(lp, "w");
    int devnull = open("/dev/null", O_WRONLY);
    if (devnull >= 0) dup2(devnull, STDOUT_FILENO);
    int code = sb_study_run_one(st, r, log ? log : stderr);
    if (log) fclose(log);
    _exit(code);
}

/* what a finished child leaves: OUT.refused for a refusal (exit 2), the log
 * shown and removed otherwise (kept for internal errors) */
const char *sb_study_finish_child(const sb_plan_run *r, int code, FILE *err)
{
    char lp[1100], rp[1100], line[1024];
    log_path(r, lp, sizeof lp);
    if (code == SB_EXIT_INPUT) {
        sb_plan_refused_path(r->out, rp, sizeof rp);
        sb_output_kind kind;
        char msg[1400];
        if (sb_output_check(rp, "refusal note", &kind, msg, sizeof msg) || kind == SB_OUTPUT_DISCARD)
            sb_escape_print(err, "shellbench sweep: %s", kind == SB_OUTPUT_DISCARD ? "a refusal note path is the null device" : msg);
        else if (rename(lp, rp))
            sb_escape_print(err, "shellbench sweep: cannot write %s: %s", rp, strerror(errno));
        return "refused";
    }
    FILE *f = fopen(lp, "r");
    while (f && fgets(line, sizeof line, f)) fprintf(err, "  %s", line);
    if (f) fclose(f);
    if (code == SB_EXIT_CONVERGED || code == SB_EXIT_NOT_CONVERGED) unlink(lp);
    return code == SB_EXIT_CONVERGED ? "converged" : code == SB_EXIT_NOT_CONVERGED ? "NOT converged"
         : code == SB_EXIT_STOPPED ? "stopped" : "internal error (log kept)";
}

int sb_study_check_outputs(const sb_plan *plan, const int *queue, int nq, FILE *err)
{
    char msg[2400], p[1100];
    for (int k = 0; k < nq; k++) {
        const sb_plan_run *r = &plan->runs[queue[k]];
        sb_output_kind kind;
        int bad = sb_output_check(r->out, "record", &kind, msg, sizeof msg);
        if (!bad && kind == SB_OUTPUT_DISCARD)
            bad = 1, snprintf(msg, sizeof msg, "will not write record %s: it is the null device", r->out);
        if (!bad) bad = sb_output_check_file_dir(r->out, "record", 0, msg, sizeof msg);
        if (!bad) bad = sb_output_check_lockfile(r->out, msg, sizeof msg);
        if (!bad) {
            log_path(r, p, sizeof p);
            bad = sb_output_check(p, "run log", &kind, msg, sizeof msg);
        }
        if (!bad) {
            sb_plan_refused_path(r->out, p, sizeof p);
            bad = sb_output_check(p, "refusal note", &kind, msg, sizeof msg);
        }
        if (bad) {
            sb_escape_controls(msg, sizeof msg);
            fprintf(err, "shellbench sweep: %s (nothing was run)\n", msg);
            return -1;
        }
    }
    return 0;
}

int sb_study_run_queue(const sb_study *st, const sb_plan *plan, const int *queue, int nq, const sb_sweep_options *o,
                       FILE *out, FILE *err, int *failed)
{
    *failed = 0;
    if (sb_study_check_outputs(plan, queue, nq, err)) return SB_EXIT_INPUT;
    int jobs = o->jobs > 0 ? o->jobs : 1, next = 0, running = 0, done = 0, n_conv = 0, n_not = 0, n_refused = 0;
    child *ch = calloc((size_t)jobs, sizeof *ch);
    if (!ch) return SB_EXIT_INTERNAL;
    *failed = 0;
    while (next < nq || running > 0) {
        while (running < jobs && next < nq) {
            int k = 0;
            while (ch[k].pid > 0) k++;
            const sb_plan_run *r = &plan->runs[queue[next]];
            pid_t pid = sb_study_start_child(st, r, err);
            if (pid < 0) {
                sb_escape_print(err, "shellbench sweep: cannot start %s: %s", r->out, strerror(errno));
                *failed += 1;
                next++;
                continue;
            }
            ch[k].pid = pid, ch[k].run = queue[next], ch[k].t0 = now_s();
            next++, running++;
        }
        if (running == 0) break;
        int status;
        pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (int k = 0; k < jobs; k++)
            if (ch[k].pid == pid) {
                const sb_plan_run *r = &plan->runs[ch[k].run];
                int code = WIFEXITED(status) ? WEXITSTATUS(status) : SB_EXIT_INTERNAL;
                const char *what = sb_study_finish_child(r, code, err);
                if (code == SB_EXIT_INTERNAL) *failed += 1;
                n_conv += code == SB_EXIT_CONVERGED;
                n_not += code == SB_EXIT_NOT_CONVERGED;
                n_refused += code == SB_EXIT_INPUT;
                done++;
                if (!o->quiet)
                    sb_escape_print(out, "[%d/%d] %-64s %s%s (%.1f s)", done, nq, r->out, what,
                            WIFSIGNALED(status) ? " by a signal" : "", now_s() - ch[k].t0);
                fflush(out);
                ch[k].pid = 0;
                running--;
            }
    }
    free(ch);
    /* what this invocation ran, so that the main job ends by saying how many failed */
    if (nq > 0)
        fprintf(out, "runs made now: %d of %d: %d converged, %d NOT converged (reason recorded), %d refused (the "
                     "method cannot honour the scene: OUT.refused says why), %d stopped, %d failed (could not be "
                     "carried out: log kept)\n", done, nq, n_conv, n_not, n_refused,
                done - n_conv - n_not - n_refused - *failed, *failed);
    return SB_EXIT_CONVERGED;
}

int sb_study_sweep(const sb_study *st, const sb_sweep_options *o, FILE *out, FILE *err)
{
    if (st->kind == SB_STUDY_DT_STABILITY) return sb_study_dt_sweep(st, o, out, err);
    sb_plan plan;
    char msg[1024];
    if (sb_study_plan(st, &plan, msg, sizeof msg)) {
        sb_escape_print(err, "shellbench sweep: %s: %s", st->path, msg);
        return SB_EXIT_INPUT;
    }
    int *queue = malloc((size_t)(plan.n ? plan.n : 1) * sizeof *queue), nq = 0, recorded = 0, refused = 0, other = 0;
    if (!queue) { sb_plan_free(&plan); return SB_EXIT_INTERNAL; }
    int misplaced = 0;
    char why[3072];
    for (int k = 0; k < plan.n; k++) {
        const sb_plan_run *r = &plan.runs[k];
        if (r->state != SB_PLAN_RUN) { other++; continue; }
        if (exists(r->out) && sb_study_record_check(st, r, why, sizeof why) == SB_ERR_INPUT) {
            /* another run's record in this run's place: neither counted nor overwritten */
            fprintf(err, "shellbench sweep: %s\n", why);
            misplaced++;
            continue;
        }
        if (sb_study_run_done(r)) { recorded++; continue; }
        queue[nq++] = k;
    }
    if (misplaced) {
        fprintf(err, "shellbench sweep: %d record%s of study %s %s not the planned run%s: nothing run\n", misplaced,
                misplaced > 1 ? "s" : "", st->name, misplaced > 1 ? "are" : "is", misplaced > 1 ? "s" : "");
        free(queue);
        sb_plan_free(&plan);
        return SB_EXIT_INPUT;
    }
    int total_new = nq;
    if (o->max_runs > 0 && nq > o->max_runs) nq = o->max_runs;
    for (int k = 0; k < plan.n; k++) refused += plan.runs[k].state == SB_PLAN_REFUSED;
    sb_escape_print(out, "study %s: %d runs planned, %d already recorded, %d to run%s (%d jobs); %d configurations without runs "
            "(%d refused by the method at set-up)", st->name, recorded + total_new, recorded, nq,
            nq < total_new ? " now" : "", o->jobs > 0 ? o->jobs : 1, other, refused);
    fflush(out);
    int failed = 0;
    int rc = sb_study_run_queue(st, &plan, queue, nq, o, out, err, &failed);
    free(queue);
    sb_plan_free(&plan);
    if (rc) return rc;
    if (failed) {
        fprintf(err, "shellbench sweep: %d run%s failed (internal error; logs kept beside the records)\n", failed, failed > 1 ? "s" : "");
        return SB_EXIT_INTERNAL;
    }
    if (nq < total_new) {
        fprintf(out, "stopped after %d new runs as asked; %d left (run the same command again to continue)\n", nq, total_new - nq);
        return SB_EXIT_STOPPED;
    }
    sb_escape_print(out, "study %s: every run recorded under %s", st->name, st->records);
    return SB_EXIT_CONVERGED;
}
