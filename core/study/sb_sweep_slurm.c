/* sb_sweep_slurm.c — a study as a batch-scheduler job array, for clusters
 * without MPI (docs/regression.md "Slurm job arrays"):
 *
 *   shellbench sweep --study FILE --emit slurm [--out FILE.sbatch]
 *       writes an sbatch script whose array has one task per run that is
 *       not recorded yet (--array=0,3,5-9: the task numbers of
 *       sb_study_tasks, the runnable runs in plan order);
 *   shellbench sweep --study FILE --task K
 *       what each array task runs: task K, unless it is recorded, in a
 *       child process exactly as a sweep runs it (record written
 *       atomically, refusal marker, log kept on an internal error).
 *
 * Task numbers index the plan, which depends only on the study file and
 * the method set-ups, so a script stays valid while records accumulate; a
 * task whose run was recorded meanwhile exits at once.  After the array
 * (or a part of it) has run, `sweep --study FILE` runs what is left. */
#include "sb_study_int.h"
#include "sb_sysinfo.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* a shell word in single quotes */
static void sh_quote(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'') fputs("'\\''", f);
        else fputc(*s, f);
    }
    fputc('\'', f);
}

static void absolute(const char *path, char *buf, size_t len)
{
    char cwd[PATH_MAX];
    int n = path[0] == '/' || !getcwd(cwd, sizeof cwd) ? snprintf(buf, len, "%s", path)
                                                        : snprintf(buf, len, "%s/%s", cwd, path);
    if (n < 0 || (size_t)n >= len) snprintf(buf, len, "%s", path);   /* too long: as given */
}

/* a path in a comment line: control characters (a newline would end the
 * comment and start a command) become '?' */
static const char *comment_safe(const char *s, char *buf, size_t len)
{
    size_t i = 0;
    for (; *s && i + 1 < len; s++) buf[i++] = (unsigned char)*s < 0x20 || *s == 0x7f ? '?' : *s;
    buf[i] = 0;
    return buf;
}

/* "0,3,5-9" from increasing task numbers */
static void ranges(FILE *f, const int *t, int n)
{
    for (int i = 0; i < n;) {
        int j = i;
        while (j + 1 < n && t[j + 1] == t[j] + 1) j++;
        fprintf(f, "%s%d", i ? "," : "", t[i]);
        if (j > i) fprintf(f, "-%d", t[j]);
        i = j + 1;
    }
}

int sb_study_emit_slurm(const sb_study *st, const char *study_file, const char *path, FILE *out, FILE *err)
{
    sb_plan plan;
    char msg[1024];
    if (sb_study_plan(st, &plan, msg, sizeof msg)) {
        fprintf(err, "shellbench sweep: %s: %s\n", st->path, msg);
        return SB_EXIT_INPUT;
    }
    int *task = malloc((size_t)(plan.n ? plan.n : 1) * sizeof *task), *pending = malloc((size_t)(plan.n ? plan.n : 1) * sizeof *pending);
    if (!task || !pending) {
        free(task), free(pending);
        sb_plan_free(&plan);
        return SB_EXIT_INTERNAL;
    }
    int nt = sb_study_tasks(&plan, task), nd = 0;
    for (int k = 0; k < nt; k++)
        if (!sb_study_run_done(&plan.runs[task[k]])) pending[nd++] = k;
    char def[1100], bin[PATH_MAX], cwd[PATH_MAX], sfile[PATH_MAX], rec[PATH_MAX], id[64], date[32];
    if (!path) {
        snprintf(def, sizeof def, "%s/%s.sbatch", st->records, st->name);
        path = def;
    }
    ssize_t nb = readlink("/proc/self/exe", bin, sizeof bin - 1);
    if (nb <= 0) snprintf(bin, sizeof bin, "shellbench");
    else bin[nb] = 0;
    if (!getcwd(cwd, sizeof cwd)) snprintf(cwd, sizeof cwd, ".");
    absolute(study_file, sfile, sizeof sfile);
    absolute(st->records, rec, sizeof rec);
    sb_sysinfo_build_id(id, sizeof id);
    sb_sysinfo_now_iso(date, sizeof date);
    int rc = SB_EXIT_CONVERGED;
    if (nd == 0) {
        fprintf(out, "study %s: all %d runs are recorded under %s: nothing to submit (no script written)\n", st->name, nt, st->records);
    } else {
        /* the directory of the script and of the array's output files */
        char tmp[PATH_MAX + 64];
        if (snprintf(tmp, sizeof tmp, "%s/", rec) < (int)sizeof tmp)
            for (char *p = tmp + 1; *p; p++)
                if (*p == '/') { *p = 0; mkdir(tmp, 0777); *p = '/'; }
        snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
        FILE *f = fopen(tmp, "w");
        char c1[PATH_MAX], c2[PATH_MAX];
        if (f) {
            fprintf(f, "#!/bin/bash\n# shellbench study %s as a Slurm job array: one task per run not yet recorded\n"
                       "# (%d of %d), written by `shellbench sweep --study %s --emit slurm` (build %s, %s).\n"
                       "# Submit with `sbatch %s`; add the --time, --partition and --account your site asks for.\n"
                       "# Afterwards `shellbench sweep --study FILE` runs whatever is left (docs/regression.md).\n",
                    st->name, nd, nt, comment_safe(study_file, c1, sizeof c1), id, date, comment_safe(path, c2, sizeof c2));
            fprintf(f, "#SBATCH --job-name=sb-%s\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n#SBATCH --array=", st->name);
            int *tn = malloc((size_t)nd * sizeof *tn);
            for (int k = 0; tn && k < nd; k++) tn[k] = pending[k];
            if (tn) ranges(f, tn, nd);
            free(tn);
            fprintf(f, "\n#SBATCH --output=%s/slurm-%%A_%%a.out\n", comment_safe(rec, c1, sizeof c1));
            fprintf(f, "set -eu\ncd ");
            sh_quote(f, cwd);
            fprintf(f, "\n# the BLAS kernels the benches pin (docs/reproducibility.md)\n"
                       "export OPENBLAS_NUM_THREADS=1 OPENBLAS_CORETYPE=\"${SB_BLAS_CORE:-Prescott}\"\nexec ");
            sh_quote(f, bin);
            fprintf(f, " sweep --study ");
            sh_quote(f, sfile);
            fprintf(f, " --dir ");
            sh_quote(f, rec);
            fprintf(f, "%s --task \"$SLURM_ARRAY_TASK_ID\"\n",
                    st->allow_unsealed_reference ? " --allow-unsealed-reference" : "");
        }
        int bad = !f || ferror(f);
        if (f && fclose(f)) bad = 1;
        if (bad || chmod(tmp, 0755) || rename(tmp, path)) {
            fprintf(err, "shellbench sweep: cannot write %s: %s\n", path, strerror(errno));
            unlink(tmp);
            rc = SB_EXIT_INPUT;
        } else {
            fprintf(out, "wrote %s: a job array of %d tasks (%d runs planned, %d recorded); submit with: sbatch %s\n", path,
                    nd, nt, nt - nd, path);
        }
    }
    free(task), free(pending);
    sb_plan_free(&plan);
    return rc;
}

int sb_study_run_task(const sb_study *st, int k, FILE *out, FILE *err)
{
    sb_plan plan;
    char msg[1024];
    if (sb_study_plan(st, &plan, msg, sizeof msg)) {
        fprintf(err, "shellbench sweep: %s: %s\n", st->path, msg);
        return SB_EXIT_INPUT;
    }
    int *task = malloc((size_t)(plan.n ? plan.n : 1) * sizeof *task);
    if (!task) { sb_plan_free(&plan); return SB_EXIT_INTERNAL; }
    int nt = sb_study_tasks(&plan, task), rc = SB_EXIT_CONVERGED;
    char why[3072];
    if (k >= nt) {
        fprintf(err, "shellbench sweep: --task %d: the study %s has %d tasks (0..%d)\n", k, st->name, nt, nt - 1);
        rc = SB_EXIT_INPUT;
    } else if (access(plan.runs[task[k]].out, F_OK) == 0 &&
               sb_study_record_check(st, &plan.runs[task[k]], why, sizeof why) == SB_ERR_INPUT) {
        /* another run's record in this task's place (sb_study_records.c): neither counted nor overwritten */
        fprintf(err, "shellbench sweep: --task %d: %s\n", k, why);
        rc = SB_EXIT_INPUT;
    } else if (sb_study_run_done(&plan.runs[task[k]])) {
        fprintf(out, "task %d: %s is recorded already\n", k, plan.runs[task[k]].out);
    } else {
        sb_sweep_options o = { 1, 0, 0 };
        int failed = 0;
        rc = sb_study_run_queue(st, &plan, &task[k], 1, &o, out, err, &failed);
        if (!rc && failed) rc = SB_EXIT_INTERNAL;
    }
    free(task);
    sb_plan_free(&plan);
    return rc;
}
