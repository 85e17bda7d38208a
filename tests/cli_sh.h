/* cli_sh.h — run a shell command from a test and capture what it says:
 * stdout and stderr apart, so tests can check which stream a message took. */
#ifndef CLI_SH_H
#define CLI_SH_H

#include <stddef.h>

/* Runs the printf-formatted command with /bin/sh; stdout into out and
 * stderr into err (each NUL-terminated, truncated to its size; NULL
 * discards).  Returns the exit status, 128 + signal, or -1. */
int sb_sh(char *out, size_t outlen, char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

#endif
