/* sb_cli_sweep.c — `shellbench sweep`: the lists of the command line into
 * sb_sweep_axes, the whole plan validated (sb_sweep.h), then one run per
 * record, one line each on stdout and a closing count.  With --resume a
 * run whose record exists is skipped and reported as skipped (with the
 * recorded outcome); a checkpoint is continued.  On a terminal (or with
 * --progress) the live line says runs done/total and the time left,
 * estimated from the runs done so far. */
#include "sb_cli.h"
#include "sb_study.h"
#include "sb_record.h"
#include "sb_stats.h"
#include "sb_sweep.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { MAX_ITEMS = 64 };

static int parse_ints(const char *opt, char **items, int n, long lo, long hi, int *out)
{
    char e[64];
    for (int i = 0; i < n; i++)
        if (sb_cli_parse_int(items[i], lo, hi, &out[i])) {
            fprintf(stderr, "shellbench sweep: %s: \"%s\" is not an integer in [%ld, %ld]\n", opt,
                    sb_escape_copy(items[i], e, sizeof e), lo, hi);
            return 2;
        }
    return 0;
}

static int split_opt(const char *opt, const char *value, char *buf, size_t len, char **items, int *n)
{
    if (snprintf(buf, len, "%s", value) >= (int)len) {
        fprintf(stderr, "shellbench sweep: %s: list too long\n", opt);
        return 2;
    }
    int rc = sb_cli_split(buf, items, MAX_ITEMS, n);
    if (rc == -2) fprintf(stderr, "shellbench sweep: %s: more than %d items\n", opt, MAX_ITEMS);
    else if (rc) fprintf(stderr, "shellbench sweep: %s: an empty list or an empty item in \"%s\"\n", opt, value);
    return rc ? 2 : 0;
}

static void format_left(double s, char *buf, size_t len)
{
    if (s < 90) snprintf(buf, len, "%.0f s", s);
    else if (s < 5400) snprintf(buf, len, "%.0f min", s / 60);
    else snprintf(buf, len, "%.1f h", s / 3600);
}

int sb_cli_sweep(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--study")) return sb_study_cmd_sweep(argc, argv);   /* docs/study.md */
    if (sb_mpi_launched()) {   /* N copies of one list would each run every combination */
        const char *rank = getenv("OMPI_COMM_WORLD_RANK");
        if (!rank || !strcmp(rank, "0"))
            fprintf(stderr, "shellbench sweep: under an MPI launcher only a study is distributed: write the lists as a "
                            "study file and run `sweep --study FILE` (docs/study.md, docs/regression.md)\n");
        return 2;
    }
    sb_cli_run c;
    char err[2048];
    memset(&c, 0, sizeof c);
    int rc = sb_cli_parse_run(argc, argv, &c, 1);
    if (rc) return rc;
    if (!c.scenes || !c.methods || !c.solvers) {
        fprintf(stderr, "shellbench sweep: --scenes, --methods and --solvers are required (see `shellbench help sweep`)\n");
        return 2;
    }
    char sb[4096], mb[1024], vb[1024], rb[1024], lb[256];
    char *sc[MAX_ITEMS], *me[MAX_ITEMS], *so[MAX_ITEMS], *re[MAX_ITEMS], *le[MAX_ITEMS];
    int nsc, nme, nso, nre = 1, nle = 1, res[MAX_ITEMS] = { 0 }, lev[MAX_ITEMS] = { 1 };
    if (split_opt("--scenes", c.scenes, sb, sizeof sb, sc, &nsc) || split_opt("--methods", c.methods, mb, sizeof mb, me, &nme) ||
        split_opt("--solvers", c.solvers, vb, sizeof vb, so, &nso))
        return 2;
    if (c.res_list && split_opt("--res", c.res_list, rb, sizeof rb, re, &nre)) return 2;
    for (int i = 0; c.res_list && i < nre; i++)   /* each item as `run --res` takes it */
        if (sb_cli_parse_res(re[i], &res[i], err, sizeof err)) {
            sb_escape_print(stderr, "shellbench sweep: %s", err);
            return 2;
        }
    if (c.level_list && (split_opt("--levels", c.level_list, lb, sizeof lb, le, &nle) ||
                         parse_ints("--levels", le, nle, 1, SB_MAX_LEVELS, lev)))
        return 2;
    sb_sweep_axes ax = { nsc, (const char *const *)sc, nme, (const char *const *)me, nso, (const char *const *)so,
                         nre, res, nle, lev, c.req.n_sets, c.sets, c.dir ? c.dir : "results/sweep", c.req.sample_n };
    sb_sweep_plan plan;
    if (sb_sweep_validate(&ax, &plan, err, sizeof err)) {
        sb_escape_print(stderr, "shellbench %s", err);
        return 2;
    }
    if (plan.n_left_out)
        fprintf(stderr, "shellbench sweep: %d combination%s left out: %s\n", plan.n_left_out,
                plan.n_left_out > 1 ? "s" : "", plan.left_out);
    const int show = c.req.progress > 0 || (c.req.progress == 0 && isatty(STDERR_FILENO));
    int worst = 0, n_conv = 0, n_not = 0, n_val = 0, n_skip = 0, n_fail = 0, n_ran = 0;
    double t0 = sb_now(), ran_seconds = 0;
    for (int k = 0; k < plan.n; k++) {
        const sb_sweep_item *it = &plan.items[k];
        if (c.req.resume && access(it->out, F_OK) == 0) {
            sb_record_summary s;
            if (sb_record_read_summary(it->out, &s, err, sizeof err) == SB_OK) {
                /* the recorded verdict counts as the run's: status and, with --strict, validation */
                int code = sb_run_recorded_exit(s.status, s.validation, c.req.strict);
                sb_escape_print(stdout, "%-60s skipped (recorded: %s%s)", it->out, sb_record_status_name(s.status),
                                code == SB_EXIT_VALIDATION ? ", validation failed" : "");
                sb_record_summary_free(&s);
                n_skip++;
                if (code > worst) worst = code;
                continue;
            }
        }
        char prefix[96] = "", left[32];
        if (n_ran > 0) {
            format_left(ran_seconds / n_ran * (plan.n - k), left, sizeof left);
            snprintf(prefix, sizeof prefix, "[%d/%d, about %s left] ", k + 1, plan.n, left);
        } else {
            snprintf(prefix, sizeof prefix, "[%d/%d] ", k + 1, plan.n);
        }
        sb_run_request r = c.req;
        r.scene = it->scene;
        r.method = it->method;
        r.solver = it->solver;
        r.res = it->res;
        r.levels = it->levels;
        r.out = it->out;
        r.quiet = 1;
        r.progress = show ? 1 : -1;
        r.progress_prefix = prefix;
        double t1 = sb_now();
        int x = sb_run_execute(&r, stdout, stderr, NULL);
        ran_seconds += sb_now() - t1;
        n_ran++;
        const char *what = x == 0 ? "converged" : x == 1 ? "NOT converged" : x == 2 ? "input error"
                         : x == 4 ? "stopped" : x == 5 ? "validation failed" : "internal error";
        sb_escape_print(stdout, "%-60s %s", it->out, what);
        fflush(stdout);
        if (x == 0) n_conv++;
        else if (x == 1) n_not++;
        else if (x == 5) n_val++;   /* --strict: converged, but a probe missed its expected value */
        else n_fail++;
        if (x > worst) worst = x;
    }
    sb_escape_print(stdout, "%d run%s in %s: %d converged, %d not converged, %d skipped (already recorded), %d failed, "
                    "%d validation failed; %.1f s", plan.n, plan.n == 1 ? "" : "s", ax.dir, n_conv, n_not, n_skip, n_fail,
                    n_val, sb_now() - t0);
    sb_sweep_plan_free(&plan);
    return worst;
}
