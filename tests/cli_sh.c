/* cli_sh.c — see cli_sh.h. */
#include "cli_sh.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static void slurp(FILE *f, char *buf, size_t len)
{
    size_t n = 0;
    if (buf && len) {
        n = fread(buf, 1, len - 1, f);
        buf[n] = 0;
    }
    char tmp[4096];
    while (fread(tmp, 1, sizeof tmp, f) > 0) {}
}

int sb_sh(char *out, size_t outlen, char *err, size_t errlen, const char *fmt, ...)
{
    char cmd[8192], full[8400], errfile[64] = "/tmp/sb_sh_err_XXXXXX";
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    int fd = mkstemp(errfile);
    if (fd < 0) return -1;
    close(fd);
    snprintf(full, sizeof full, "( %s ) 2>%s", cmd, errfile);
    FILE *p = popen(full, "r");
    if (!p) {
        unlink(errfile);
        return -1;
    }
    slurp(p, out, outlen);
    int st = pclose(p);
    FILE *e = fopen(errfile, "r");
    if (e) {
        slurp(e, err, errlen);
        fclose(e);
    } else if (err && errlen) {
        err[0] = 0;
    }
    unlink(errfile);
    return WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
}
