/* sb_study_gnuplot.c — one figure through gnuplot as PNG and SVG: data
 * files and the script in a private temporary directory, gnuplot writing to
 * OUT.tmp.<pid>, renamed onto OUT only when it succeeded and OUT is new or a
 * regular file (sb_study_output_ok: never over a symbolic link, FIFO or
 * device).  A missing or failing gnuplot is a warning for the caller (the
 * report's tables stand without figures). */
#include "sb_study_fig.h"

#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

void sb_gp_quoted(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'') fputc('\'', f);
        fputc(*s, f);
    }
    fputc('\'', f);
}

int sb_gp_open(sb_gp *g, const char *prog)
{
    memset(g, 0, sizeof *g);
    const char *env = getenv("SB_GNUPLOT");
    g->prog = prog ? prog : env && *env ? env : "gnuplot";
    const char *tmp = getenv("TMPDIR");
    snprintf(g->dir, sizeof g->dir, "%s/sb_study_XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(g->dir)) return -1;
    g->body = open_memstream(&g->body_text, &g->body_len);
    return g->body ? 0 : -1;
}

FILE *sb_gp_data(sb_gp *g, char *path, size_t len)
{
    snprintf(path, len, "%s/d%d.dat", g->dir, g->ndata++);
    return fopen(path, "w");
}

static int run_prog(const char *prog, const char *script, const char *log)
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
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

static void first_line(const char *path, char *buf, size_t len)
{
    FILE *f = fopen(path, "r");
    char line[512];
    buf[0] = 0;
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = 0;
        if (strspn(line, " \t^") < strlen(line)) {
            snprintf(buf, len, "%s", line + strspn(line, " \t"));
            break;
        }
    }
    if (f) fclose(f);
}

int sb_gp_finish(sb_gp *g, const char *png, const char *svg, int width, int height, char *err, size_t errlen)
{
    char script[600], log[600], tpng[1200], tsvg[1200], why[512];
    int status = -1;
    fclose(g->body);
    g->body = NULL;
    snprintf(script, sizeof script, "%s/plot.gp", g->dir);
    snprintf(log, sizeof log, "%s/gnuplot.log", g->dir);
    snprintf(tpng, sizeof tpng, "%s.tmp.%ld", png, (long)getpid());
    snprintf(tsvg, sizeof tsvg, "%s.tmp.%ld", svg, (long)getpid());
    FILE *f = fopen(script, "w");
    if (f) {
        /* the same figure twice: PNG (cairo when available) and SVG */
        fprintf(f, "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n  set terminal pngcairo size %d,%d font ',10'\n"
                   "} else {\n  set terminal png size %d,%d\n}\nset termoption noenhanced\nset output ", width, height, width, height);
        sb_gp_quoted(f, tpng);
        fprintf(f, "\n%s\nset output\n", g->body_text ? g->body_text : "");
        fprintf(f, "set terminal svg size %d,%d dynamic font ',10'\nset termoption noenhanced\nset output ", width, height);
        sb_gp_quoted(f, tsvg);
        fprintf(f, "\n%s\nset output\n", g->body_text ? g->body_text : "");
        status = ferror(f) ? -1 : 0;
        if (fclose(f)) status = -1;
    }
    if (status) {
        snprintf(err, errlen, "figure %s not written: cannot write the gnuplot script in %s", png, g->dir);
    } else if (sb_study_output_ok(png, "figure", err, errlen) || sb_study_output_ok(svg, "figure", err, errlen)) {
        status = SB_FIG_REFUSED;   /* before gnuplot runs, and again before the renames */
    } else {
        int rc = run_prog(g->prog, script, log);
        first_line(log, why, sizeof why);
        if (rc == 127) snprintf(err, errlen, "figure %s not written: gnuplot (\"%s\") is not installed or not on PATH", png, g->prog), status = -1;
        else if (rc != 0) snprintf(err, errlen, "figure %s not written: gnuplot exited with status %d%s%s", png, rc, why[0] ? ": " : "", why), status = -1;
        else if (sb_study_output_ok(png, "figure", err, errlen) || sb_study_output_ok(svg, "figure", err, errlen)) status = SB_FIG_REFUSED;
        else if (rename(tpng, png) || rename(tsvg, svg)) snprintf(err, errlen, "figure %s not written: %s", png, strerror(errno)), status = -1;
    }
    unlink(tpng);
    unlink(tsvg);
    for (int k = 0; k < g->ndata; k++) {
        char p[600];
        snprintf(p, sizeof p, "%s/d%d.dat", g->dir, k);
        unlink(p);
    }
    unlink(script);
    unlink(log);
    rmdir(g->dir);
    free(g->body_text);
    g->body_text = NULL;
    return status;
}

void sb_gp_abandon(sb_gp *g)
{
    /* nothing to draw: remove the temporary files without running gnuplot */
    if (g->body) fclose(g->body);
    g->body = NULL;
    for (int k = 0; k < g->ndata; k++) {
        char p[600];
        snprintf(p, sizeof p, "%s/d%d.dat", g->dir, k);
        unlink(p);
    }
    rmdir(g->dir);
    free(g->body_text);
    g->body_text = NULL;
}
