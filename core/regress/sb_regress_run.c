/* sb_regress_run.c — running the nightly suite (docs/regression.md "How a
 * case is measured").  The suite is a study file; its cases are the planned
 * runs (sb_study_plan), identified by their record path under the study's
 * records directory.  The suite is run `repeat` times in rounds: each round
 * starts with one pass of the calibration kernel, then runs every case once
 * (interleaving the repeats spreads a passing load over all cases rather
 * than onto one).  Every run is a child process of its own, with a fresh
 * record RECORDS/repK/ID (never resumed from an earlier invocation's); its
 * CPU time (user + system, wait4's rusage) is the time judged, its record's
 * seconds_total is kept beside it.  The first repeat's deterministic figures
 * are the case's; a later repeat that differs makes the case "changed"
 * (not reproducible). */
#include "sb_regress_int.h"
#include "sb_study_int.h"
#include "sb_run.h"
#include "sb_sysinfo.h"
#include "sb_gsl.h"
#include "sb_record.h"
#include "sb_output.h"

#include <dirent.h>

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* the case id: the record path under the records directory */
static const char *case_id(const sb_study *st, const sb_plan_run *r)
{
    size_t n = strlen(st->records);
    return !strncmp(r->out, st->records, n) && r->out[n] == '/' ? r->out + n + 1 : r->out;
}

/* the 1-minute load average (NaN when /proc/loadavg cannot be read) */
static double load_average(void)
{
    FILE *f = fopen("/proc/loadavg", "r");
    double l = NAN;
    if (f && fscanf(f, "%lf", &l) != 1) l = NAN;
    if (f) fclose(f);
    return l;
}

static int selected(const sb_regress_run_options *o, const char *id)
{
    if (o->n_only <= 0) return 1;
    for (int k = 0; k < o->n_only; k++)
        if (!strcmp(o->only[k], id)) return 1;
    return 0;
}

/* the outputs of an earlier invocation; its lock only when nobody holds it
 * (a live writer's lock is left to refuse the run) */
static void remove_outputs(const char *out)
{
    static const char *const suffix[] = { "", ".partial", ".log" };
    char p[1200];
    for (size_t k = 0; k < sizeof suffix / sizeof *suffix; k++) {
        snprintf(p, sizeof p, "%s%s", out, suffix[k]);
        unlink(p);
    }
    if (sb_record_xdmf_path(out, p, sizeof p) == SB_OK) unlink(p);
    sb_output_lock_clear_stale(out, p, sizeof p);
}

/* Every lock file under dir (RECORDS/repK/SCENE/...: depth <= 4) whose
 * writer is gone is removed (an invocation killed with its runs leaves
 * them); one a live process holds is an error. */
static int clear_stale_locks(const char *dir, int depth, char *err, size_t errlen)
{
    DIR *d = opendir(dir);
    if (!d) return SB_OK;
    struct dirent *e;
    int rc = SB_OK;
    while (rc == SB_OK && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char p[2048];
        if (snprintf(p, sizeof p, "%s/%s", dir, e->d_name) >= (int)sizeof p) continue;
        struct stat st;
        if (lstat(p, &st) != 0) continue;
        size_t n = strlen(p);
        if (n > 5 && !strcmp(p + n - 5, ".lock")) {
            p[n - 5] = 0;
            rc = sb_output_lock_clear_stale(p, err, errlen);
        } else if (S_ISDIR(st.st_mode) && depth > 0) {
            rc = clear_stale_locks(p, depth - 1, err, errlen);
        }
    }
    closedir(d);
    return rc;
}

int sb_regress_prepare_outputs(const sb_study *st, int repeat, const char *dir, sb_output_lock *lock, char *err,
                               size_t errlen)
{
    sb_output_lock_init(lock);
    sb_plan plan;
    char msg[1200];
    if (sb_study_plan(st, &plan, msg, sizeof msg)) {
        snprintf(err, errlen, "%s: %s", st->path, msg);
        return SB_ERR_INPUT;
    }
    int rc = sb_output_check_dir(st->records, "the suite's records", err, errlen);
    for (int k = 0; k < plan.n && rc == SB_OK; k++) {
        const sb_plan_run *r = &plan.runs[k];
        if (r->state != SB_PLAN_RUN) continue;
        const char *id = case_id(st, r);
        char path[2048];
        sb_output_kind kind;
        sb_regress_plot_path(dir, id, "png", path, sizeof path);
        rc = sb_output_check(path, "history plot", &kind, err, errlen);
        if (rc == SB_OK) {
            sb_regress_plot_path(dir, id, "svg", path, sizeof path);
            rc = sb_output_check(path, "history plot", &kind, err, errlen);
        }
        if (rc == SB_OK) {
            sb_regress_picture_path(dir, id, path, sizeof path);
            rc = sb_output_check(path, "picture", &kind, err, errlen);
        }
        for (int rep = 1; rep <= repeat && rc == SB_OK; rep++) {
            snprintf(path, sizeof path, "%s/rep%d/%s", st->records, rep, id);
            rc = sb_output_check(path, "record", &kind, err, errlen);
            if (rc == SB_OK && kind == SB_OUTPUT_DISCARD) {
                snprintf(err, errlen, "will not write record %s: it is the null device", path);
                rc = SB_ERR_INPUT;
            }
            if (rc == SB_OK) rc = sb_output_check_lockfile(path, err, errlen);
        }
    }
    sb_plan_free(&plan);
    if (rc) return SB_ERR_INPUT;
    /* one invocation at a time on these records: RECORDS.lock beside them */
    char parent[1100];
    snprintf(parent, sizeof parent, "%s/", st->records);
    for (char *q = parent + 1; *q; q++)
        if (*q == '/') {
            *q = 0;
            if (mkdir(parent, 0777) && errno != EEXIST) {
                snprintf(err, errlen, "cannot create the records directory %s: %s", parent, strerror(errno));
                return SB_ERR_INPUT;
            }
            *q = '/';
        }
    if (sb_output_lock_take(lock, st->records, err, errlen)) return SB_ERR_INPUT;
    if (clear_stale_locks(st->records, 4, err, errlen)) {
        sb_output_lock_release(lock);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

typedef struct slot {
    pid_t pid;
    int run, rep;
    sb_plan_run r;
} slot;

/* one timed run in its own process: the sweep's child (its log in OUT.log,
 * stdout discarded, killed with its parent), after the case's earlier
 * outputs are removed so that the run is made, not skipped */
static pid_t start(const sb_study *st, slot *s, FILE *err)
{
    remove_outputs(s->r.out);
    return sb_study_start_child(st, &s->r, err);
}

static void first_log_line(const char *out, char *buf, size_t len)
{
    char lp[1200], line[600];
    snprintf(lp, sizeof lp, "%s.log", out);
    FILE *f = fopen(lp, "r");
    buf[0] = 0;
    if (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        snprintf(buf, len, "%s", line);
    }
    if (f) fclose(f);
}

static double real_calibrate(void *ctx, int round)
{
    (void)ctx, (void)round;
    return sb_regress_calibrate();
}

/* user + system CPU seconds of the run's process */
static double real_run_seconds(void *ctx, const char *id, int rep, const struct rusage *ru)
{
    (void)ctx, (void)id, (void)rep;
    return (double)ru->ru_utime.tv_sec + 1e-6 * (double)ru->ru_utime.tv_usec +
           (double)ru->ru_stime.tv_sec + 1e-6 * (double)ru->ru_stime.tv_usec;
}

const sb_regress_clock *sb_regress_clock_real(void)
{
    static const sb_regress_clock real = { real_calibrate, real_run_seconds, NULL };
    return &real;
}

/* a finished child: its time and figures into the case; 1 when the run was
 * refused as input (exit 2: a bad --set), else 0 */
static int finish(sb_regress_case *c, const slot *s, int status, const struct rusage *ru, const sb_regress_clock *clk,
                  FILE *err)
{
    int code = WIFEXITED(status) ? WEXITSTATUS(status) : SB_EXIT_INTERNAL;
    char why[600], msg[1200];
    if (code == SB_EXIT_INPUT) {
        first_log_line(s->r.out, why, sizeof why);
        fprintf(err, "shellbench regress: %s refused: %s\n", c->id, why[0] ? why : "(no message)");
        return 1;
    }
    if (code != SB_EXIT_CONVERGED && code != SB_EXIT_NOT_CONVERGED) {
        first_log_line(s->r.out, why, sizeof why);
        if (!c->crashed)
            snprintf(c->failure, sizeof c->failure, "repeat %d: %s%s%.400s", s->rep + 1,
                     WIFSIGNALED(status) ? "killed by a signal" : "internal error", why[0] ? ": " : "", why);
        c->crashed = 1;
        return 0;
    }
    sb_regress_figures g;
    if (sb_regress_figures_read(s->r.out, &g, msg, sizeof msg)) {
        if (!c->crashed) snprintf(c->failure, sizeof c->failure, "repeat %d: %.400s", s->rep + 1, msg);
        c->crashed = 1;
        return 0;
    }
    sb_record_summary sum;
    double wall = NAN;
    if (sb_record_read_summary(s->r.out, &sum, msg, sizeof msg) == SB_OK) {
        wall = sum.seconds;
        sb_record_summary_free(&sum);
    }
    if (!c->ok) {
        c->fig = g;
        c->ok = 1;
    } else if (!c->crashed && !c->failure[0] && sb_regress_figures_differ(&c->fig, &g, 0.0, msg, sizeof msg)) {
        snprintf(c->failure, sizeof c->failure, "not reproducible: repeat %d differs from the first: %.400s", s->rep + 1, msg);
    }
    if (c->n_rep < SB_REGRESS_MAX_REPEAT) {
        c->cpu[c->n_rep] = clk->run_seconds(clk->ctx, c->id, s->rep, ru);
        c->wall[c->n_rep] = wall;
        c->n_rep++;
    }
    return 0;
}

int sb_regress_measure(const sb_study *st, const sb_regress_run_options *o, sb_regress_set *now, FILE *out, FILE *err)
{
    sb_plan plan;
    char msg[1200];
    if (sb_study_plan(st, &plan, msg, sizeof msg)) {
        fprintf(err, "shellbench regress: %s: %s\n", st->path, msg);
        return SB_EXIT_INPUT;
    }
    int *runs = malloc((size_t)(plan.n ? plan.n : 1) * sizeof *runs), n = 0;
    if (!runs) { sb_plan_free(&plan); return SB_EXIT_INTERNAL; }
    for (int k = 0; k < plan.n; k++)
        if (plan.runs[k].state == SB_PLAN_RUN && selected(o, case_id(st, &plan.runs[k]))) {
            runs[n++] = k;
            if (!sb_regress_set_add(now, case_id(st, &plan.runs[k]))) { free(runs); sb_plan_free(&plan); return SB_EXIT_INTERNAL; }
        }
    sb_regress_prov *p = &now->prov;
    sb_sysinfo_build_id(p->build, sizeof p->build);
    sb_sysinfo_now_iso(p->date, sizeof p->date);
    sb_sysinfo_hostname(p->host, sizeof p->host);
    sb_sysinfo_cpu_model(p->cpu, sizeof p->cpu);
    sb_sysinfo_blas_core(p->blas_core, sizeof p->blas_core);
    snprintf(p->suite, sizeof p->suite, "%s", st->path);
    p->repeat = o->repeat;
    p->cores = sb_sysinfo_cores();
    p->calib_version = SB_REGRESS_CALIB_VERSION;
    p->load_max = NAN;
    const sb_regress_clock *clk = o->clock ? o->clock : sb_regress_clock_real();
    int jobs = o->jobs > 0 ? o->jobs : 1, refused = 0;
    slot *sl = calloc((size_t)jobs, sizeof *sl);
    if (!sl) { free(runs); sb_plan_free(&plan); return SB_EXIT_INTERNAL; }
    if (!o->quiet)
        fprintf(out, "regress %s: %d cases x %d repeats, %d at a time, calibration before each round\n", st->name, n,
                o->repeat, jobs);
    for (int rep = 0; rep < o->repeat && !refused; rep++) {
        double l = load_average();
        if (isfinite(l) && !(l <= p->load_max)) p->load_max = l;
        p->calib[p->n_calib++] = clk->calibrate(clk->ctx, rep);
        int next = 0, running = 0;
        while ((next < n || running > 0) && !refused) {
            while (running < jobs && next < n) {
                int k = 0;
                while (sl[k].pid > 0) k++;
                sl[k].r = plan.runs[runs[next]];
                sl[k].run = next, sl[k].rep = rep;
                /* RECORDS/repK/ID, and the extra parameters of --set */
                snprintf(sl[k].r.out, sizeof sl[k].r.out, "%s/rep%d/%s", st->records, rep + 1, now->c[next].id);
                for (int j = 0; j < o->n_sets && sl[k].r.n_sets < (int)(sizeof sl[k].r.sets / sizeof sl[k].r.sets[0]); j++)
                    snprintf(sl[k].r.sets[sl[k].r.n_sets++], sizeof sl[k].r.sets[0], "%s", o->sets[j]);
                pid_t pid = start(st, &sl[k], err);
                next++;
                if (pid < 0) {
                    sb_regress_case *c = &now->c[sl[k].run];
                    if (!c->crashed) snprintf(c->failure, sizeof c->failure, "cannot start: %s", strerror(errno));
                    c->crashed = 1;
                    continue;
                }
                sl[k].pid = pid;
                running++;
            }
            if (running == 0) break;
            int status;
            struct rusage ru;
            pid_t pid = wait4(-1, &status, 0, &ru);
            if (pid < 0) {
                if (errno == EINTR) continue;
                break;
            }
            for (int k = 0; k < jobs; k++)
                if (sl[k].pid == pid) {
                    sb_regress_case *c = &now->c[sl[k].run];
                    int had = c->n_rep;
                    refused |= finish(c, &sl[k], status, &ru, clk, err);
                    if (!o->quiet && c->n_rep > had)
                        fprintf(out, "  round %d/%d  %-60s %7.2f s CPU\n", rep + 1, o->repeat, c->id, c->cpu[had]);
                    else if (!o->quiet)
                        fprintf(out, "  round %d/%d  %-60s failed: %s\n", rep + 1, o->repeat, c->id, c->failure);
                    fflush(out);
                    sl[k].pid = 0;
                    running--;
                }
        }
        /* a refusal stops the suite: let the runs under way finish */
        while (running > 0) {
            int status;
            if (wait(&status) > 0 || errno != EINTR) running--;
        }
    }
    free(sl);
    free(runs);
    sb_plan_free(&plan);
    if (refused) return SB_EXIT_INPUT;
    if (sb_median(p->calib, (size_t)p->n_calib, &p->calib_median) || !(p->calib_median > 0)) {
        fprintf(err, "shellbench regress: the calibration took no measurable CPU time\n");
        return SB_EXIT_INTERNAL;
    }
    for (int k = 0; k < now->n; k++)
        for (int i = 0; i < now->c[k].n_rep; i++) now->c[k].norm[i] = now->c[k].cpu[i] / p->calib_median;
    return SB_EXIT_CONVERGED;
}

/* A timing verdict (slower, faster) is confirmed by measuring the case again
 * (k fresh repeats with their own calibration) and judging the new samples:
 * it stands only when both measurements agree, so a passing disturbance of
 * the machine (a false positive at level alpha) must strike twice (alpha^2).
 * The case keeps the confirming samples. */
int sb_regress_confirm(const sb_study *st, const sb_regress_run_options *o, sb_regress_set *now,
                       const sb_regress_set *base, const sb_regress_rules *ru, int *regressions, FILE *out, FILE *err)
{
    const char **ids = malloc((size_t)(now->n ? now->n : 1) * sizeof *ids);
    int n = 0;
    if (!ids) return SB_EXIT_INTERNAL;
    for (int k = 0; k < now->n; k++)
        if (now->c[k].verdict == SB_VERDICT_SLOWER || now->c[k].verdict == SB_VERDICT_FASTER) ids[n++] = now->c[k].id;
    if (n == 0) { free(ids); return 0; }
    if (!o->quiet) fprintf(out, "confirming %d timing verdict%s with %d more repeats\n", n, n > 1 ? "s" : "", o->repeat);
    sb_regress_run_options o2 = *o;
    o2.n_only = n, o2.only = ids;
    sb_regress_set again;
    memset(&again, 0, sizeof again);
    int rc = sb_regress_measure(st, &o2, &again, out, err);
    if (!rc) {
        sb_regress_judge(&again, base, ru);
        for (int j = 0; j < again.n; j++) {
            sb_regress_case *c = (sb_regress_case *)sb_regress_set_find(now, again.c[j].id), *a = &again.c[j];
            if (!c) continue;
            char first[200];
            snprintf(first, sizeof first, "first measurement %s x%.3f p = %.3g", sb_verdict_name(c->verdict), c->ratio, c->p);
            if (a->verdict == c->verdict) {
                snprintf(a->detail + strlen(a->detail), sizeof a->detail - strlen(a->detail), "; confirmed (%s)", first);
            } else {
                char d[512];
                snprintf(d, sizeof d, "%.300s; not confirmed (%.150s)", a->detail, first);
                snprintf(a->detail, sizeof a->detail, "%s", d);
                if (a->verdict == SB_VERDICT_SLOWER || a->verdict == SB_VERDICT_FASTER) a->verdict = SB_VERDICT_SAME;
            }
            *regressions += sb_verdict_is_regression(a->verdict) - sb_verdict_is_regression(c->verdict);
            *c = *a;
        }
    }
    sb_regress_set_free(&again);
    free(ids);
    return rc;
}
