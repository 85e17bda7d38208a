/* sb_study_cli.c — the study commands of the command line (core/cli/main.c
 * dispatches to them):
 *
 *   shellbench sweep --study FILE [--jobs N] [--max-runs N] [--dir DIR] [--plan] [--quiet] [--resume]
 *                    [--emit slurm [--out FILE]] [--task K]
 *   mpirun -n N shellbench sweep --study FILE ...   (sb_sweep_mpi.c)
 *   shellbench report --study FILE [--out DIR] [--dir DIR] [--deterministic]
 *
 * Exit codes as for runs: 0 done, 2 the study file or an option is wrong
 * (FILE:LINE:COL, nothing run), 3 internal error, 4 stopped by --max-runs
 * (run the same command again to continue). */
#include "sb_study_int.h"
#include "sb_run.h"

#include <stdlib.h>
#include <string.h>

static int parse_count(const char *opt, const char *v, int lo, int *out)
{
    char *end;
    long x = v ? strtol(v, &end, 10) : 0;
    if (!v || end == v || *end || x < lo || x > 100000) {
        sb_escape_print(stderr, "shellbench: %s: \"%s\" is not an integer >= %d", opt, v ? v : "", lo);
        return -1;
    }
    *out = (int)x;
    return 0;
}

static void print_plan(const sb_study *st, const sb_plan *p, FILE *out)
{
    static const char *const state[] = { "run", "skip", "not applicable", "refused" };
    for (int k = 0; k < p->n; k++) {
        const sb_plan_run *r = &p->runs[k];
        char label[128];
        sb_plan_config_label(st, r, label, sizeof label);
        if (r->state == SB_PLAN_RUN)
            sb_escape_print(out, "%-16s %-28s res %4d %7ld dofs start %d  %s%s", st->scenes[r->scene].name, label, r->res, r->dofs,
                    r->start, r->out, sb_study_run_done(r) ? "  (recorded)" : "");
        else
            sb_escape_print(out, "%-16s %-28s %s: %s", st->scenes[r->scene].name, label, state[r->state], r->why);
    }
}

int sb_study_cmd_sweep(int argc, char **argv)
{
    const char *file = NULL, *dir = NULL;
    sb_sweep_options o = { 1, 0, 0 };
    int plan_only = 0, task = -1, allow_unsealed = 0;
    const char *emit = NULL, *emit_out = NULL;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--study") && v) file = v, i++;
        else if (!strcmp(a, "--emit") && v) emit = v, i++;
        else if (!strcmp(a, "--out") && v) emit_out = v, i++;
        else if (!strcmp(a, "--task")) { if (parse_count(a, v, 0, &task)) return 2; i++; }
        else if (!strcmp(a, "--resume")) { /* a study sweep always resumes: accepted for `sweep --resume` */ }
        else if (!strcmp(a, "--dir") && v) dir = v, i++;
        else if (!strcmp(a, "--jobs")) { if (parse_count(a, v, 1, &o.jobs)) return 2; i++; }
        else if (!strcmp(a, "--max-runs")) { if (parse_count(a, v, 1, &o.max_runs)) return 2; i++; }
        else if (!strcmp(a, "--plan")) plan_only = 1;
        else if (!strcmp(a, "--quiet")) o.quiet = 1;
        else if (!strcmp(a, "--allow-unsealed-reference")) allow_unsealed = 1;
        else {
            sb_escape_print(stderr, "shellbench sweep --study: unknown option or missing value \"%s\" "
                            "(--study FILE [--jobs N] [--max-runs N] [--dir DIR] [--plan] [--quiet] [--resume] "
                            "[--allow-unsealed-reference] [--emit slurm [--out FILE]] [--task K])", a);
            return 2;
        }
    }
    if (!file) {
        fprintf(stderr, "shellbench sweep: --study needs a file\n");
        return 2;
    }
    if (emit && strcmp(emit, "slurm")) {
        char e[64];
        fprintf(stderr, "shellbench sweep: --emit: \"%s\" is not a known batch system (slurm)\n", sb_escape_copy(emit, e, sizeof e));
        return 2;
    }
    if (emit_out && !emit) {
        fprintf(stderr, "shellbench sweep --study: --out goes with --emit slurm (the records go to --dir)\n");
        return 2;
    }
    sb_study *st = malloc(sizeof *st);
    char err[2048];
    if (!st) return 3;
    if (sb_study_load(file, dir, st, err, sizeof err)) {
        sb_escape_print(stderr, "shellbench sweep: --study: %s", err);
        free(st);
        return 2;
    }
    st->allow_unsealed_reference = allow_unsealed;
    int rc;
    if (emit) {
        rc = sb_study_emit_slurm(st, file, emit_out, stdout, stderr);
    } else if (task >= 0) {
        rc = sb_study_run_task(st, task, stdout, stderr);
    } else if (sb_mpi_launched() && !plan_only) {
        rc = sb_study_sweep_mpi(st, &o, argc, argv, stdout, stderr);
    } else if (plan_only) {
        sb_plan p;
        rc = 0;
        if (sb_study_plan(st, &p, err, sizeof err)) {
            sb_escape_print(stderr, "shellbench sweep: %s: %s", file, err);
            rc = 2;
        } else {
            print_plan(st, &p, stdout);
            sb_plan_free(&p);
        }
    } else {
        rc = sb_study_sweep(st, &o, stdout, stderr);
    }
    sb_study_free(st);
    free(st);
    return rc;
}

int sb_study_cmd_report(int argc, char **argv)
{
    const char *file = NULL, *dir = NULL;
    sb_study_report_options o = { NULL, NULL, 0 };
    int allow_unsealed = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--study") && v) file = v, i++;
        else if (!strcmp(a, "--dir") && v) dir = v, i++;
        else if (!strcmp(a, "--out") && v) o.out_dir = v, i++;
        else if (!strcmp(a, "--deterministic")) o.deterministic = 1;
        else if (!strcmp(a, "--allow-unsealed-reference")) allow_unsealed = 1;
        else {
            sb_escape_print(stderr, "shellbench report --study: unknown option or missing value \"%s\" "
                            "(--study FILE [--out DIR] [--dir DIR] [--deterministic] [--allow-unsealed-reference])", a);
            return 2;
        }
    }
    if (!file) {
        fprintf(stderr, "shellbench report: --study needs a file\n");
        return 2;
    }
    sb_study *st = malloc(sizeof *st);
    char err[2048];
    if (!st) return 3;
    if (sb_study_load(file, dir, st, err, sizeof err)) {
        sb_escape_print(stderr, "shellbench report: --study: %s", err);
        free(st);
        return 2;
    }
    st->allow_unsealed_reference = allow_unsealed;
    int rc = sb_study_report(st, &o, stderr);
    sb_study_free(st);
    free(st);
    return rc;
}
