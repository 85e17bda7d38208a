/* main.c — the shellbench command line (docs/running.md).
 *   shellbench list [scenes|methods|solvers]
 *   shellbench check SCENE...
 *   shellbench run --scene NAME|PATH --method NAME --solver NAME [--res N] [--levels L]
 *                  [--set key=value]... [--out FILE.h5|none] [--summary json] [--samples N] [--quiet]
 *   shellbench sweep --scenes A,B --methods M,N --solvers S,T [--res 4,8] [--levels 1,2]
 *                  [--set key=value]... [--dir DIR]
 *   shellbench report [--format md|csv] [--plot FILE.png|FILE.svg] FILE.h5...
 *   shellbench inspect [--format md|csv] FILE.h5...
 * Exit codes: 0 converged / ok, 1 ran but did not converge, 2 usage or input error, 3 internal error. */
#include "sb_context.h"
#include "sb_inspect.h"
#include "sb_method.h"
#include "sb_record.h"
#include "sb_run.h"
#include "sb_scene.h"
#include "sb_solver.h"
#include "sb_study.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage:\n"
            "  shellbench list [scenes|methods|solvers]\n"
            "  shellbench check SCENE.json...\n"
            "  shellbench run --scene NAME|PATH --method NAME --solver NAME [--res N] [--levels L]\n"
            "                 [--set key=value]... [--out FILE.h5|none] [--summary json] [--samples N] [--quiet]\n"
            "                 [--resume] [--stop-after-steps K]\n"
            "  shellbench sweep --scenes A,B --methods M,.. --solvers S,.. [--res N,..] [--levels L,..]\n"
            "                 [--set key=value]... [--dir DIR] [--resume]\n"
            "  --resume: skip a run whose record exists, continue one from the last completed step of\n"
            "            its checkpoint OUT.partial (same scene, method, solver, sizes and parameters)\n"
            "  shellbench report [--format md|csv] [--plot FILE.png|FILE.svg] FILE.h5...\n"
            "  shellbench inspect [--format md|csv] FILE.h5...   (material state of the recorded final state)\n"
            "  shellbench sweep --study FILE [--jobs N] [--max-runs N] [--dir DIR] [--plan]   (docs/study.md)\n"
            "  shellbench report --study FILE [--out DIR] [--deterministic]\n"
            "  shellbench reference SCENE [--method M] [--solver S] [--res N | --dofs N] [--levels L] [--set k=v]...\n"
            "exit codes: 0 converged, 1 did not converge, 2 usage or input error, 3 internal error,\n"
            "            4 stopped by --stop-after-steps (resumable)\n");
}

static int parse_int(const char *s, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < 0 || v > 1000000) return -1;
    *out = (int)v;
    return 0;
}

static int cmd_list(int argc, char **argv)
{
    const char *what = argc > 0 ? argv[0] : "all";
    int all = strcmp(what, "all") == 0;
    if (!all && strcmp(what, "scenes") && strcmp(what, "methods") && strcmp(what, "solvers")) {
        fprintf(stderr, "shellbench list: unknown category \"%s\" (scenes, methods, solvers)\n", what);
        return 2;
    }
    if (all || !strcmp(what, "scenes")) {
        if (all) printf("scenes:\n");
        char path[1024];
        if (sb_scene_resolve("trampoline", path, sizeof path) == 0) {
            char *slash = strrchr(path, '/');
            if (slash) *slash = 0;
            struct dirent **names;
            int n = scandir(path, &names, NULL, alphasort);
            for (int i = 0; i < n; i++) {
                size_t l = strlen(names[i]->d_name);
                if (l > 5 && strcmp(names[i]->d_name + l - 5, ".json") == 0)
                    printf("%s%.*s\n", all ? "  " : "", (int)(l - 5), names[i]->d_name);
                free(names[i]);
            }
            if (n >= 0) free(names);
        }
    }
    if (all || !strcmp(what, "methods")) {
        if (all) printf("methods:\n");
        for (int i = 0; i < sb_method_count(); i++) {
            const sb_method_type *m = sb_method_at(i);
            printf("%s%-20s %s%s\n", all ? "  " : "", m->name, m->description,
                   (m->flags & SB_METHOD_HIERARCHY) ? " [hierarchy]" : "");
        }
    }
    if (all || !strcmp(what, "solvers")) {
        if (all) printf("solvers:\n");
        for (int i = 0; i < sb_solver_count(); i++) {
            const sb_solver_type *s = sb_solver_at(i);
            printf("%s%-20s %s\n", all ? "  " : "", s->name, s->description);
        }
    }
    return 0;
}

static int cmd_check(int argc, char **argv)
{
    if (argc < 1) { usage(stderr); return 2; }
    int bad = 0;
    for (int i = 0; i < argc; i++) {
        sb_scene sc;
        char err[2048];
        if (sb_scene_load(argv[i], &sc, err, sizeof err)) {
            printf("%s\n", err);
            bad = 1;
        } else {
            printf("%s: ok (%s)\n", argv[i], sc.name);
            sb_scene_free(&sc);
        }
    }
    return bad ? 2 : 0;
}

typedef struct cli_run {
    sb_run_request req;
    const char *sets[256];
    const char *scenes, *methods, *solvers, *res_list, *level_list, *dir, *format, *plot;
} cli_run;

static int parse_run_args(int argc, char **argv, cli_run *c, int sweep)
{
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED_VALUE() do { if (!v) { fprintf(stderr, "shellbench: %s needs a value\n", a); return 2; } i++; } while (0)
        if (!strcmp(a, "--quiet")) { c->req.quiet = 1; continue; }
        if (!strcmp(a, "--resume")) { c->req.resume = 1; continue; }
        if (!sweep && !strcmp(a, "--scene")) { NEED_VALUE(); c->req.scene = v; }
        else if (!sweep && !strcmp(a, "--method")) { NEED_VALUE(); c->req.method = v; }
        else if (!sweep && !strcmp(a, "--solver")) { NEED_VALUE(); c->req.solver = v; }
        else if (!sweep && !strcmp(a, "--res")) {
            NEED_VALUE();
            if (parse_int(v, &c->req.res)) { fprintf(stderr, "shellbench: --res: \"%s\" is not a non-negative integer\n", v); return 2; }
        } else if (!sweep && !strcmp(a, "--levels")) {
            NEED_VALUE();
            if (parse_int(v, &c->req.levels) || c->req.levels < 1) { fprintf(stderr, "shellbench: --levels: \"%s\" is not a positive integer\n", v); return 2; }
        } else if (!strcmp(a, "--samples")) {
            NEED_VALUE();
            if (parse_int(v, &c->req.sample_n) || c->req.sample_n < 2 || c->req.sample_n > 2001) {
                fprintf(stderr, "shellbench: --samples: \"%s\" is not an integer in [2, 2001]\n", v);
                return 2;
            }
        } else if (!sweep && !strcmp(a, "--stop-after-steps")) {
            NEED_VALUE();
            if (parse_int(v, &c->req.stop_after_steps) || c->req.stop_after_steps < 1) {
                fprintf(stderr, "shellbench: --stop-after-steps: \"%s\" is not a positive integer\n", v);
                return 2;
            }
        } else if (!sweep && !strcmp(a, "--out")) { NEED_VALUE(); c->req.out = v; }
        else if (!sweep && !strcmp(a, "--summary")) {
            NEED_VALUE();
            if (strcmp(v, "json")) { fprintf(stderr, "shellbench: --summary: only \"json\" is supported, got \"%s\"\n", v); return 2; }
            c->req.summary_json = 1;
        } else if (!strcmp(a, "--set")) {
            NEED_VALUE();
            if (c->req.n_sets >= 256) { fprintf(stderr, "shellbench: too many --set options\n"); return 2; }
            c->sets[c->req.n_sets++] = v;
        } else if (sweep && !strcmp(a, "--scenes")) { NEED_VALUE(); c->scenes = v; }
        else if (sweep && !strcmp(a, "--methods")) { NEED_VALUE(); c->methods = v; }
        else if (sweep && !strcmp(a, "--solvers")) { NEED_VALUE(); c->solvers = v; }
        else if (sweep && !strcmp(a, "--res")) { NEED_VALUE(); c->res_list = v; }
        else if (sweep && !strcmp(a, "--levels")) { NEED_VALUE(); c->level_list = v; }
        else if (sweep && !strcmp(a, "--dir")) { NEED_VALUE(); c->dir = v; }
        else {
            fprintf(stderr, "shellbench %s: unknown option \"%s\"\n", sweep ? "sweep" : "run", a);
            usage(stderr);
            return 2;
        }
#undef NEED_VALUE
    }
    c->req.sets = c->sets;
    return 0;
}

static int cmd_run(int argc, char **argv)
{
    cli_run c;
    memset(&c, 0, sizeof c);
    int rc = parse_run_args(argc, argv, &c, 0);
    if (rc) return rc;
    if (!c.req.scene || !c.req.method || !c.req.solver) {
        fprintf(stderr, "shellbench run: --scene, --method and --solver are required\n");
        usage(stderr);
        return 2;
    }
    return sb_run_execute(&c.req, stdout, stderr, NULL);
}

/* split "a,b,c" into at most max tokens (modifies a copy) */
static int split(char *s, char **tok, int max)
{
    int n = 0;
    for (char *p = strtok(s, ","); p && n < max; p = strtok(NULL, ",")) tok[n++] = p;
    return n;
}

static int cmd_sweep(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--study")) return sb_study_cmd_sweep(argc, argv);   /* docs/study.md */
    cli_run c;
    memset(&c, 0, sizeof c);
    int rc = parse_run_args(argc, argv, &c, 1);
    if (rc) return rc;
    if (!c.scenes || !c.methods || !c.solvers) {
        fprintf(stderr, "shellbench sweep: --scenes, --methods and --solvers are required\n");
        return 2;
    }
    char sb[1024], mb[1024], vb[1024], rb[256], lb[256];
    snprintf(sb, sizeof sb, "%s", c.scenes);
    snprintf(mb, sizeof mb, "%s", c.methods);
    snprintf(vb, sizeof vb, "%s", c.solvers);
    snprintf(rb, sizeof rb, "%s", c.res_list ? c.res_list : "0");
    snprintf(lb, sizeof lb, "%s", c.level_list ? c.level_list : "1");
    char *sc[64], *me[64], *so[64], *re[64], *le[64];
    int nsc = split(sb, sc, 64), nme = split(mb, me, 64), nso = split(vb, so, 64), nre = split(rb, re, 64), nle = split(lb, le, 64);
    const char *dir = c.dir ? c.dir : "results/sweep";
    int worst = 0, runs = 0;
    for (int a = 0; a < nsc; a++)
        for (int b = 0; b < nme; b++)
            for (int d = 0; d < nso; d++)
                for (int e = 0; e < nre; e++)
                    for (int f = 0; f < nle; f++) {
                        sb_run_request r = c.req;
                        r.scene = sc[a];
                        r.method = me[b];
                        r.solver = so[d];
                        if (parse_int(re[e], &r.res) || parse_int(le[f], &r.levels) || r.levels < 1) {
                            fprintf(stderr, "shellbench sweep: bad --res/--levels entry \"%s\"/\"%s\"\n", re[e], le[f]);
                            return 2;
                        }
                        char out[1024];
                        /* one file per run: an interrupted sweep keeps every finished run */
                        snprintf(out, sizeof out, "%s/%s-%s-%s-r%d-l%d.h5", dir, sc[a], me[b], so[d], r.res, r.levels);
                        r.out = out;
                        r.quiet = 1;
                        int x = sb_run_execute(&r, stdout, stderr, NULL);
                        runs++;
                        printf("%-40s %s\n", out, x == 0 ? "converged" : x == 1 ? "NOT converged" : x == 2 ? "input error" : x == 4 ? "stopped" : "internal error");
                        fflush(stdout);
                        if (x > worst) worst = x;
                    }
    printf("%d runs in %s\n", runs, dir);
    return worst;
}

static int cmd_report(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--study")) return sb_study_cmd_report(argc, argv);  /* docs/study.md */
    const char *format = "md", *plot = NULL;
    char **files = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *files);
    int nf = 0;
    if (!files) return 3;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--format") && i + 1 < argc) format = argv[++i];
        else if (!strcmp(argv[i], "--plot") && i + 1 < argc) plot = argv[++i];
        else if (argv[i][0] == '-' && argv[i][1] == '-') {
            fprintf(stderr, "shellbench report: unknown option \"%s\"\n", argv[i]);
            free(files);
            return 2;
        } else files[nf++] = argv[i];
    }
    if (strcmp(format, "md") && strcmp(format, "csv")) {
        fprintf(stderr, "shellbench report: --format must be md or csv, got \"%s\"\n", format);
        free(files);
        return 2;
    }
    if (nf == 0) {
        fprintf(stderr, "shellbench report: no record files given\n");
        free(files);
        return 2;
    }
    char err[2048] = "";
    int rc = sb_report(nf, files, format, stdout, plot, err, sizeof err);
    free(files);
    if (rc < 0) {
        fprintf(stderr, "shellbench report: %s\n", err);
        return 2;
    }
    if (rc > 0 && err[0]) fprintf(stderr, "shellbench report: warning: %s\n", err);
    return 0;
}

static int cmd_inspect(int argc, char **argv)
{
    const char *format = "md";
    char **files = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *files);
    int nf = 0;
    if (!files) return 3;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--format") && i + 1 < argc) format = argv[++i];
        else if (argv[i][0] == '-' && argv[i][1] == '-') {
            fprintf(stderr, "shellbench inspect: unknown option \"%s\"\n", argv[i]);
            free(files);
            return 2;
        } else files[nf++] = argv[i];
    }
    int rc = 0;
    if (strcmp(format, "md") && strcmp(format, "csv")) {
        fprintf(stderr, "shellbench inspect: --format must be md or csv, got \"%s\"\n", format);
        rc = 2;
    } else if (nf == 0) {
        fprintf(stderr, "shellbench inspect: no record files given\n");
        rc = 2;
    } else if (sb_inspect_report(nf, files, format, stdout, stderr) > 0) {
        rc = 2;
    }
    free(files);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) { usage(stderr); return 2; }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "list")) return cmd_list(argc - 2, argv + 2);
    if (!strcmp(cmd, "check")) return cmd_check(argc - 2, argv + 2);
    if (!strcmp(cmd, "run")) return cmd_run(argc - 2, argv + 2);
    if (!strcmp(cmd, "sweep")) return cmd_sweep(argc - 2, argv + 2);
    if (!strcmp(cmd, "report")) return cmd_report(argc - 2, argv + 2);
    if (!strcmp(cmd, "inspect")) return cmd_inspect(argc - 2, argv + 2);
    if (!strcmp(cmd, "reference")) return sb_study_cmd_reference(argc - 2, argv + 2);
    if (!strcmp(cmd, "help") || !strcmp(cmd, "--help") || !strcmp(cmd, "-h")) { usage(stdout); return 0; }
    fprintf(stderr, "shellbench: unknown command \"%s\"\n", cmd);
    usage(stderr);
    return 2;
}
