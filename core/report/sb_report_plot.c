/* sb_report_plot.c — the report's convergence plot: log10 ||g|| against the
 * cumulative outer iteration of each run, one line per record, drawn by
 * gnuplot (pngcairo, or libgd png when cairo is missing; svg; jpeg), in the
 * format of the path's extension.
 *
 * Data and script go to a private temporary directory; gnuplot writes to
 * PLOT.tmp.<pid>, renamed onto PLOT only when gnuplot succeeded.  A missing
 * or failing gnuplot is a warning (SB_REPORT_WARN_PLOT), not an error: the
 * table has been written already. */
#include "sb_output.h"
#include "sb_record_io.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* gnuplot single-quoted string: only the quote itself needs doubling. */
static void gp_quoted(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'') fputc('\'', f);
        fputc(*s, f);
    }
    fputc('\'', f);
}

/* The finest level present in a history (outer iterations; coarse-level
 * records of a multilevel solver are not plotted). */
static int finest_level(const sb_record_summary *s)
{
    int L = 0;
    for (int i = 0; i < s->n_hist; i++) if (s->hist_level[i] > L) L = s->hist_level[i];
    return L;
}

static int plottable(const sb_record_summary *s, int i, int L)
{
    return s->hist_level[i] == L && isfinite(s->hist_gnorm[i]) && s->hist_gnorm[i] > 0.0;
}

/* Writes one data block per run with points ("index" k in gnuplot); marks
 * in has[] which runs have any.  Returns the number of blocks, -1 on I/O error. */
static int write_data(const char *path, int n, const sb_record_summary *s, int *has)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    int blocks = 0;
    for (int k = 0; k < n; k++) {
        int L = finest_level(&s[k]);
        has[k] = 0;
        for (int i = 0; i < s[k].n_hist; i++) if (plottable(&s[k], i, L)) has[k] = 1;
        if (!has[k]) continue;
        fprintf(f, "# %s/%s/%s\n", s[k].scene, s[k].method, s[k].solver);
        /* x = iterations of the earlier steps + iteration within this step;
         * a step's iteration-0 record (its starting point) lands on the
         * previous step's last iteration. */
        int base = 0, last = 0, step = s[k].n_hist ? s[k].hist_step[0] : 0;
        for (int i = 0; i < s[k].n_hist; i++) {
            if (s[k].hist_level[i] != L) continue;
            if (s[k].hist_step[i] != step) {
                base += last;
                last = 0;
                step = s[k].hist_step[i];
            }
            if (s[k].hist_iter[i] > last) last = s[k].hist_iter[i];
            if (plottable(&s[k], i, L))
                fprintf(f, "%d %.17g\n", base + s[k].hist_iter[i], log10(s[k].hist_gnorm[i]));
        }
        fputs("\n\n", f);   /* two blank lines end a gnuplot data block */
        blocks++;
    }
    int bad = ferror(f);
    if (fclose(f) != 0) bad = 1;
    return bad ? -1 : blocks;
}

int sb_report_plot_format(const char *path, const char **format, char *err, size_t errlen)
{
    static const struct { const char *ext, *fmt; } known[] = {
        { ".png", "png" }, { ".svg", "svg" }, { ".jpg", "jpeg" }, { ".jpeg", "jpeg" },
    };
    size_t pl = path ? strlen(path) : 0;
    for (size_t i = 0; i < sizeof known / sizeof *known; i++) {
        size_t el = strlen(known[i].ext);
        if (pl > el && strcasecmp(path + pl - el, known[i].ext) == 0) {
            if (format) *format = known[i].fmt;
            return SB_OK;
        }
    }
    snprintf(err, errlen, "--plot %s: the plot's format follows its extension: .png, .svg or .jpg", path ? path : "");
    return SB_ERR_INPUT;
}

static int write_script(const char *path, const char *data, const char *out, const char *format,
                        int n, const sb_record_summary *s, const int *has)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    if (!strcmp(format, "svg")) fputs("set terminal svg size 1100,600 dynamic\n", f);
    else if (!strcmp(format, "jpeg")) fputs("set terminal jpeg size 1100,600\n", f);
    else fputs("if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
               "    set terminal pngcairo size 1100,600\n"
               "} else {\n"
               "    set terminal png size 1100,600\n"
               "}\n", f);
    fputs("set termoption noenhanced\nset output ", f);
    gp_quoted(f, out);
    fputs("\nset title 'convergence: log10 ||g|| against cumulative iteration'\n"
          "set xlabel 'cumulative iteration'\nset ylabel 'log10 ||g||  (N)'\n"
          "set grid\nset key outside right top vertical Left reverse\nplot ", f);   /* never over the data or the axis label */
    int block = 0;
    for (int k = 0; k < n; k++) {
        if (!has[k]) continue;
        char title[3 * SB_NAME_LEN + 32];
        snprintf(title, sizeof title, "%s/%s/%s %ld dofs", s[k].scene, s[k].method, s[k].solver, s[k].dofs);
        if (block) fputs(", \\\n     ", f);
        gp_quoted(f, data);
        fprintf(f, " index %d using 1:2 with linespoints title ", block++);
        gp_quoted(f, title);
    }
    fputs("\nset output\n", f);
    int bad = ferror(f);
    if (fclose(f) != 0) bad = 1;
    return bad ? -1 : 0;
}

/* Runs `prog script` with stdout and stderr into log; returns the exit
 * status, 127 when the program cannot be started, -1 on spawn failure. */
static int run_gnuplot(const char *prog, const char *script, const char *log)
{
    posix_spawn_file_actions_t fa;
    if (posix_spawn_file_actions_init(&fa) != 0) return -1;
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    char *argv[] = { (char *)prog, (char *)script, NULL };
    pid_t pid;
    int rc = posix_spawnp(&pid, prog, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc == ENOENT || rc == EACCES) return 127;
    if (rc != 0) return -1;
    int st;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

/* First non-empty line of gnuplot's output, for the warning. */
static void first_line(const char *path, char *buf, size_t len)
{
    buf[0] = 0;
    FILE *f = fopen(path, "r");
    if (!f) return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = 0;
        if (strspn(line, " \t^") < strlen(line)) {
            snprintf(buf, len, "%s", line + strspn(line, " \t"));
            break;
        }
    }
    fclose(f);
}

int sb_report_plot(int n, const sb_record_summary *s, const char *plot_path,
                   const char *gnuplot, char *err, size_t errlen)
{
    const char *format;
    if (sb_report_plot_format(plot_path, &format, err, errlen)) return SB_ERR_INPUT;
    const char *tmpdir = getenv("TMPDIR");
    char dir[512], data[600], script[600], log[600], out[4096];
    snprintf(dir, sizeof dir, "%s/sb_report_XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
    if (snprintf(out, sizeof out, "%s.tmp.%ld", plot_path, (long)getpid()) >= (int)sizeof out) {
        snprintf(err, errlen, "plot path too long: %s", plot_path);
        return SB_ERR_INPUT;
    }
    int *has = calloc((size_t)(n > 0 ? n : 1), sizeof *has);
    if (!has) {
        snprintf(err, errlen, "plot: out of memory");
        return SB_ERR_NOMEM;
    }
    if (!mkdtemp(dir)) {
        snprintf(err, errlen, "plot not written: cannot create a temporary directory %s: %s", dir, strerror(errno));
        free(has);
        return SB_REPORT_WARN_PLOT;
    }
    snprintf(data, sizeof data, "%s/gnorm.dat", dir);
    snprintf(script, sizeof script, "%s/plot.gp", dir);
    snprintf(log, sizeof log, "%s/gnuplot.log", dir);
    int status = SB_REPORT_WARN_PLOT;
    int blocks = write_data(data, n, s, has);
    if (blocks < 0 || write_script(script, data, out, format, n, s, has) != 0) {
        snprintf(err, errlen, "plot not written: cannot write temporary files in %s", dir);
    } else if (blocks == 0) {
        snprintf(err, errlen, "plot %s not written: no run has a positive ||g|| history", plot_path);
    } else {
        int rc = run_gnuplot(gnuplot, script, log);
        char why[1024];
        sb_output_kind kind = SB_OUTPUT_NEW;
        first_line(log, why, sizeof why);
        if (rc == 127) {
            snprintf(err, errlen, "plot %s not written: gnuplot (\"%s\") is not installed or not on PATH",
                     plot_path, gnuplot);
        } else if (rc != 0) {
            snprintf(err, errlen, "plot %s not written: gnuplot exited with status %d%s%s", plot_path, rc,
                     why[0] ? ": " : "", why);
        } else if (sb_output_check(plot_path, "plot", &kind, why, sizeof why) || kind == SB_OUTPUT_DISCARD) {
            snprintf(err, errlen, "plot not written: %s", kind == SB_OUTPUT_DISCARD ? "the path is the null device" : why);
        } else if (rename(out, plot_path) != 0) {
            snprintf(err, errlen, "plot %s not written: rename from %s failed: %s", plot_path, out, strerror(errno));
        } else {
            status = SB_OK;
        }
    }
    if (status != SB_OK) unlink(out);
    unlink(data);
    unlink(script);
    unlink(log);
    rmdir(dir);
    free(has);
    return status;
}
