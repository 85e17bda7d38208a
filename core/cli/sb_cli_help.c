/* sb_cli_help.c — `shellbench help [CMD]`, `CMD --help` and `--version`
 * (sb_cli.h).  The full reference is docs/cli.md. */
#include "sb_cli.h"
#include "sb_record.h"
#include "sb_render.h"
#include "sb_sysinfo.h"

#include <string.h>

static const char overview[] =
    "usage: shellbench COMMAND [options]   (shellbench help COMMAND for its options)\n"
    "  list [scenes|methods|solvers|params [NAME]]   what this build has\n"
    "  check SCENE...                                validate scene files\n"
    "  run --scene S --method M --solver V [...]     one run, one record\n"
    "  sweep --scenes A,B --methods M,N --solvers V,W [...]   many runs, validated up front\n"
    "  report [--format md|csv] [--plot FILE] FILE.h5...     tables (and a plot) from records\n"
    "  inspect [--format md|csv] FILE.h5...          material state of recorded states\n"
    "  sweep --study FILE / report --study FILE      a study: work-precision, profiles, selection (docs/study.md)\n"
    "  reference SCENE [...]                         compute and store a scene's reference record\n"
    "  render FILE.h5 [--out FILE.png] [...]         a ray-traced picture of a record (docs/render.md)\n"
    "  regress [--update-baseline] [...]             nightly regression against a baseline (docs/regression.md)\n"
    "  digest [--drop-state] RECORD.h5...            rewrite records as what reports read (docs/reproducibility.md)\n"
    "  help [COMMAND], --version\n"
    "exit codes: 0 converged / ok, 1 ran but did not converge, 2 usage or input error,\n"
    "            3 internal error, 4 stopped by --stop-after-steps (resumable),\n"
    "            5 converged but validation failed (--strict)\n"
    "reference: docs/cli.md\n";

static const char run_help[] =
    "usage: shellbench run --scene NAME|PATH --method NAME --solver NAME [options]\n"
    "One scene through one discretization and one outer solver; writes one HDF5 record.\n"
    "  --scene NAME|PATH     a bundled scene (shellbench list scenes) or a scene file; /dev/stdin reads a pipe\n"
    "  --method NAME         discretization (shellbench list methods)\n"
    "  --solver NAME         outer nonlinear solver (shellbench list solvers)\n"
    "  --res N|NxM           elements per side, 1..4096, or N along s and M along t (default: the scene's\n"
    "                        \"resolution\")\n"
    "  --levels L            levels of the hierarchy, 1..8 (default 1; solver rmtr needs 2 or more)\n"
    "  --set KEY=VALUE       a parameter, repeatable (shellbench list params [METHOD|SOLVER])\n"
    "  --out FILE.h5|none    the record (default results/runs/SCENE-METHOD-SOLVER-rRES-lLEVELS.h5);\n"
    "                        none or /dev/null: no record.  Only new paths or regular files are written;\n"
    "                        FILE.h5.lock keeps a second run off the same record\n"
    "  --summary json        the run's summary as JSON on stdout\n"
    "  --samples N           sample grid per side for errors and the surface, 2..2001 (default 21)\n"
    "  --resume              continue from the checkpoint FILE.h5.partial (same scene, method, solver,\n"
    "                        sizes, parameters and obstacle meshes); a finished record: nothing to do,\n"
    "                        exit by its recorded verdict (with --strict: 5 when its validation failed)\n"
    "  --stop-after-steps K  stop after step K with a checkpoint (exit 4; continue with --resume)\n"
    "  --strict              a converged run whose expected probe values are out of tolerance exits 5\n"
    "                        (validation failed, docs/trust.md)\n"
    "  --allow-unsealed-reference  use the scene's reference record even without a checksum (a record\n"
    "                        of format version 1); refused otherwise (exit 2, docs/trust.md)\n"
    "  --quiet               no step lines, no progress line\n"
    "  --progress            the progress line also off a terminal (one line a second)\n"
    "  --no-progress         no progress line on a terminal\n"
    "Sizes are checked before any work: a run whose memory estimate exceeds run.max_memory (default:\n"
    "the machine's physical memory) is refused (exit 2).\n";

static const char sweep_help[] =
    "usage: shellbench sweep --scenes A,B --methods M,N --solvers S,T [options]\n"
    "Every combination of the lists, one record each in --dir; the whole sweep is validated before\n"
    "the first run (names, scene files, resolutions and memory, --set keys, output paths).\n"
    "Combinations that cannot work (rmtr without a hierarchy or with one level) are left out and named.\n"
    "  --scenes A,B          bundled names or scene files (records are named by the scene's \"name\")\n"
    "  --methods M,N         discretizations\n"
    "  --solvers S,T         outer solvers\n"
    "  --res N,M             resolutions (default: each scene's own)\n"
    "  --levels L,M          level counts (default 1)\n"
    "  --set KEY=VALUE       a parameter for every run, repeatable\n"
    "  --dir DIR             where the records go (default results/sweep): DIR/SCENE-METHOD-SOLVER-rRES-lL.h5\n"
    "  --samples N           sample grid per side, 2..2001\n"
    "  --resume              skip runs whose record exists (reported as skipped, with its recorded\n"
    "                        verdict, which counts for the exit code), continue checkpoints\n"
    "  --strict              as for run: a converged run whose validation failed counts as exit 5,\n"
    "                        also when it is skipped\n"
    "  --allow-unsealed-reference   as for run\n"
    "  --progress, --no-progress, --quiet   as for run; the progress line shows runs done and time left\n"
    "exit code: the worst of its runs.\n"
    "usage: shellbench sweep --study FILE [--jobs N] [--max-runs N] [--dir DIR] [--plan] [--quiet] [--resume]\n"
    "A study file (docs/study.md), checked whole before any run (FILE:LINE:COL); runs what is not\n"
    "recorded (--resume is implied), N at a time in child processes; refusals leave RECORD.refused;\n"
    "--max-runs stops resumably (exit 4); --plan prints the runs and runs nothing;\n"
    "--allow-unsealed-reference as for run.  A record in a run's place that is not that run's\n"
    "(scene, method, solver, resolution, levels) is refused: nothing is run (exit 2).\n"
    "  mpirun -n N shellbench sweep --study FILE   the runs over N MPI ranks, longest expected first\n"
    "  --emit slurm [--out FILE]   write an sbatch job array of the runs not recorded (default\n"
    "                        RECORDS/STUDY.sbatch); --task K runs its task K (docs/regression.md)\n";

static const char check_help[] =
    "usage: shellbench check [--allow-unsealed-reference] SCENE...\n"
    "Validates scene files (or bundled names): \"FILE: ok (NAME)\" on stdout for each good one,\n"
    "\"FILE:LINE:COL: at /POINTER: what is wrong\" on stderr for each bad one; exit 2 if any is bad.\n"
    "A scene's reference record must fit it and carry a checksum (--allow-unsealed-reference: or not).\n"
    "Regular files and the standard input (/dev/stdin) are read; FIFOs and devices are refused.\n";

static const char report_help[] =
    "usage: shellbench report [--format md|csv] [--plot FILE.png|FILE.svg|FILE.jpg] FILE.h5...\n"
    "Tables of run records (never re-running): Markdown with a header (title, date, machine, build,\n"
    "BLAS kernels, non-default parameters, column definitions, time per event), or CSV.\n"
    "  --format md|csv       table format (default md)\n"
    "  --plot FILE           log10 ||g|| against iteration through gnuplot; the format follows the\n"
    "                        extension; /dev/null: no plot\n"
    "A file that is not a readable record, or a plot that cannot be made, is an error: the table of the\n"
    "others is still written, and the exit code is 2 (input) or 3 (plot failed).\n"
    "usage: shellbench report --study FILE [--out DIR] [--dir DIR] [--deterministic]\n"
    "The study's report.md: method selection, work-precision diagrams, performance profiles, the\n"
    "nonconvex scenes by energy, convergence plots (docs/study.md); --deterministic leaves out\n"
    "wall-clock figures (the same records give the same bytes); --allow-unsealed-reference: a scene's\n"
    "reference record without a checksum is used.\n";

static const char reference_help[] =
    "usage: shellbench reference SCENE [--method M] [--solver S] [--res N | --dofs N] [--levels L]\n"
    "                            [--set KEY=VALUE]... [--samples N] [--out FILE.h5] [--no-check] [--force]\n"
    "Computes a scene's reference record (default: bhem near 12,000 dofs, rmtr on 3 levels,\n"
    "run.gtol=1e-8) into results/references/SCENE.h5 with its provenance SCENE.json and a self-check\n"
    "at half the resolution; prints the line that points the scene at it (docs/study.md).\n";

static const char inspect_help[] =
    "usage: shellbench inspect [--format md|csv] FILE.h5...\n"
    "Rebuilds each record's discretization and reports the material state of its final (or\n"
    "checkpointed) state: softening points, area fraction, largest strains.  Exit 2 if any file fails.\n";

static const char list_help[] =
    "usage: shellbench list [scenes|methods|solvers|params [run|METHOD|SOLVER]]\n"
    "  scenes                the bundled scenes with their description\n"
    "  methods, solvers      the registered discretizations and outer solvers\n"
    "  params                every --set key: run.*, then solver.* per solver and method.* per method,\n"
    "                        with default, range (or choices) and meaning; params NAME only those of\n"
    "                        run, one method or one solver\n";

int sb_cli_help(const char *cmd, FILE *f)
{
    static const struct { const char *name, *text; } topics[] = {
        { "run", run_help }, { "sweep", sweep_help }, { "check", check_help }, { "report", report_help },
        { "inspect", inspect_help }, { "list", list_help }, { "reference", reference_help },
    };
    if (!cmd) {
        fputs(overview, f);
        return 0;
    }
    for (size_t i = 0; i < sizeof topics / sizeof *topics; i++)
        if (strcmp(cmd, topics[i].name) == 0) {
            fputs(topics[i].text, f);
            return 0;
        }
    if (!strcmp(cmd, "digest")) {   /* beside the command (core/cli/sb_cli_digest.c) */
        fputs(sb_cli_digest_help, f);
        return 0;
    }
    if (!strcmp(cmd, "regress")) {   /* beside the command (core/cli/sb_cli_regress.c) */
        fputs(sb_cli_regress_help, f);
        return 0;
    }
    if (!strcmp(cmd, "render")) {   /* render's options live beside it (core/render/sb_render_cli.c) */
        char opt[] = "--help";
        char *argv[] = { opt, NULL };
        return sb_render_main(1, argv);
    }
    if (!strcmp(cmd, "help") || !strcmp(cmd, "version")) {
        fputs(overview, f);
        return 0;
    }
    char e[64];
    fprintf(stderr, "shellbench help: no command \"%s\"\n", sb_escape_copy(cmd, e, sizeof e));
    fputs(overview, stderr);
    return 2;
}

void sb_cli_usage(FILE *f) { fputs(overview, f); }

void sb_cli_version(FILE *f)
{
    char id[64], blas[64];
    sb_sysinfo_build_id(id, sizeof id);
    sb_sysinfo_blas_core(blas, sizeof blas);
    fprintf(f, "shellbench %s (record format %s %d; BLAS kernels %s)\n", id, SB_RECORD_FORMAT_NAME,
            SB_RECORD_FORMAT_VERSION, blas);
}
