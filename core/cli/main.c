/* main.c — the shellbench command line: dispatch, and the thin commands
 * run, check, report and inspect.  list, sweep, help and argument parsing
 * are in core/cli/sb_cli_*.c; the reference is docs/cli.md (how to run:
 * docs/running.md).
 *   shellbench list [scenes|methods|solvers|params [NAME]]
 *   shellbench check SCENE...
 *   shellbench run --scene NAME|PATH --method NAME --solver NAME [options]
 *   shellbench sweep --scenes A,B --methods M,N --solvers S,T [options]
 *   shellbench report [--format md|csv] [--plot FILE] FILE.h5...
 *   shellbench inspect [--format md|csv] FILE.h5...
 *   shellbench help [COMMAND] | --version
 *   shellbench render FILE.h5 [options]   (core/render/sb_render_cli.c, docs/render.md)
 *   shellbench regress [options]          (core/cli/sb_cli_regress.c, docs/regression.md)
 * Exit codes: 0 converged / ok, 1 ran but did not converge, 2 usage or input
 * error, 3 internal error, 4 stopped by --stop-after-steps, 5 converged but
 * validation failed (--strict). */
#include "sb_cli.h"
#include "sb_inspect.h"
#include "sb_output.h"
#include "sb_record.h"
#include "sb_regress.h"
#include "sb_render.h"
#include "sb_run.h"
#include "sb_scene.h"
#include "sb_study.h"

#include <stdlib.h>
#include <string.h>

static int wants_help(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return 1;
    return 0;
}

/* Results on stdout, errors on stderr. */
static int cmd_check(int argc, char **argv)
{
    int bad = 0, allow_unsealed = 0, n_scenes = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--allow-unsealed-reference")) allow_unsealed = 1;
        else n_scenes++;
    }
    if (n_scenes < 1) {
        fprintf(stderr, "shellbench check: no scene given (see `shellbench help check`)\n");
        return 2;
    }
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--allow-unsealed-reference")) continue;
        sb_scene sc;
        char err[2048], path[1024];
        const char *file = sb_scene_resolve(argv[i], path, sizeof path) == SB_OK ? path : argv[i];
        if (sb_scene_load(file, &sc, err, sizeof err)) {
            sb_escape_print(stderr, "%s", err);
            bad = 1;
        } else if (sb_run_scene_methods_check(&sc, err, sizeof err) ||
                   sb_reference_check(&sc, NULL, 0, allow_unsealed, err, sizeof err)) {   /* a reference file must be usable */
            char e[1100];
            fprintf(stderr, "%s: %s\n", sb_escape_copy(file, e, sizeof e), err);
            sb_scene_free(&sc);
            bad = 1;
        } else {
            char e[1100];
            printf("%s: ok (%s)\n", sb_escape_copy(file, e, sizeof e), sc.name);
            sb_scene_free(&sc);
        }
    }
    return bad ? 2 : 0;
}

static int cmd_run(int argc, char **argv)
{
    sb_cli_run c;
    memset(&c, 0, sizeof c);
    int rc = sb_cli_parse_run(argc, argv, &c, 0);
    if (rc) return rc;
    if (!c.req.scene || !c.req.method || !c.req.solver) {
        fprintf(stderr, "shellbench run: --scene, --method and --solver are required (see `shellbench help run`)\n");
        return 2;
    }
    return sb_run_execute(&c.req, stdout, stderr, NULL);
}

/* --format and --plot of report / inspect; the rest are record files. */
static int parse_files(const char *cmd, int argc, char **argv, const char **format, const char **plot, char **files,
                       int *nf)
{
    char e[64];
    *nf = 0;
    for (int i = 0; i < argc; i++) {
        const int is_format = !strcmp(argv[i], "--format"), is_plot = plot && !strcmp(argv[i], "--plot");
        if (is_format || is_plot) {
            if (i + 1 >= argc) {
                fprintf(stderr, "shellbench %s: %s needs a value (see `shellbench help %s`)\n", cmd, argv[i], cmd);
                return 2;
            }
            if (is_format) *format = argv[++i];
            else *plot = argv[++i];
        } else if (argv[i][0] == '-' && argv[i][1] == '-') {
            fprintf(stderr, "shellbench %s: unknown option \"%s\" (see `shellbench help %s`)\n", cmd,
                    sb_escape_copy(argv[i], e, sizeof e), cmd);
            return 2;
        } else {
            files[(*nf)++] = argv[i];
        }
    }
    if (strcmp(*format, "md") && strcmp(*format, "csv")) {
        fprintf(stderr, "shellbench %s: --format must be md or csv, got \"%s\"\n", cmd, sb_escape_copy(*format, e, sizeof e));
        return 2;
    }
    if (*nf == 0) {
        fprintf(stderr, "shellbench %s: no record files given\n", cmd);
        return 2;
    }
    return 0;
}

static int cmd_report(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--study")) return sb_study_cmd_report(argc, argv);   /* docs/study.md */
    const char *format = "md", *plot = NULL;
    char **files = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *files);
    int nf = 0;
    if (!files) return 3;
    int rc = parse_files("report", argc, argv, &format, &plot, files, &nf);
    char err[2048] = "";
    if (!rc && plot) {   /* the plot's path and format, before any work */
        sb_output_kind kind;
        if (sb_output_check(plot, "plot", &kind, err, sizeof err) ||
            (kind != SB_OUTPUT_DISCARD && (sb_report_plot_format(plot, NULL, err, sizeof err) ||
                                           sb_output_check_file_dir(plot, "plot", 1, err, sizeof err)))) {
            sb_escape_controls(err, sizeof err);
            fprintf(stderr, "shellbench report: %s\n", err);
            rc = 2;
        } else if (kind == SB_OUTPUT_DISCARD) {
            plot = NULL;
        }
    }
    if (!rc) {
        int st = sb_report(nf, files, format, stdout, plot, err, sizeof err);
        sb_escape_controls(err, sizeof err);
        if (st != 0) fprintf(stderr, "shellbench %s%s\n", strncmp(err, "report: ", 8) ? "report: " : "", err);
        /* unreadable inputs: input errors (2); a plot that failed: 3 */
        rc = st < 0 || (st & SB_REPORT_WARN_FILES) ? 2 : st & SB_REPORT_WARN_PLOT ? 3 : 0;
    }
    free(files);
    return rc;
}

static int cmd_inspect(int argc, char **argv)
{
    const char *format = "md";
    char **files = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *files);
    int nf = 0;
    if (!files) return 3;
    int rc = parse_files("inspect", argc, argv, &format, NULL, files, &nf);
    if (!rc && sb_inspect_report(nf, files, format, stdout, stderr) > 0) rc = 2;
    free(files);
    return rc;
}

int main(int argc, char **argv)
{
    sb_record_library_init();   /* before any HDF5 call */
    if (argc < 2) {
        sb_cli_usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    int n = argc - 2;
    char **rest = argv + 2;
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        sb_cli_version(stdout);
        return 0;
    }
    if (!strcmp(cmd, "help") || !strcmp(cmd, "--help") || !strcmp(cmd, "-h")) return sb_cli_help(n > 0 ? rest[0] : NULL, stdout);
    static const struct { const char *name; int (*fn)(int, char **); } cmds[] = {
        { "list", sb_cli_list }, { "check", cmd_check }, { "run", cmd_run }, { "sweep", sb_cli_sweep },
        { "report", cmd_report }, { "inspect", cmd_inspect }, { "render", sb_render_main },
        { "reference", sb_study_cmd_reference }, { "regress", sb_cli_regress },
        { "digest", sb_cli_digest },
    };
    for (size_t i = 0; i < sizeof cmds / sizeof *cmds; i++)
        if (!strcmp(cmd, cmds[i].name)) {
            if (wants_help(n, rest)) return sb_cli_help(cmd, stdout);
            return cmds[i].fn(n, rest);
        }
    char e[64];
    fprintf(stderr, "shellbench: unknown command \"%s\"\n", sb_escape_copy(cmd, e, sizeof e));
    sb_cli_usage(stderr);
    return 2;
}
