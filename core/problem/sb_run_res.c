/* sb_run_res.c — the --res value (sb_run.h): "N" or "NxM". */
#include "sb_run.h"

#include <stdlib.h>
#include <string.h>

/* a positive integer (or 0 when zero_ok) of at most 1000000 at *s; advances *s */
static int number(const char **s, int zero_ok, int *out)
{
    if (**s < '0' || **s > '9') return -1;
    char *end;
    long v = strtol(*s, &end, 10);
    if (v > 1000000 || (v == 0 && !zero_ok)) return -1;
    *out = (int)v;
    *s = end;
    return 0;
}

int sb_run_parse_res(const char *text, int *res, int *res_t)
{
    const char *s = text;
    *res = *res_t = 0;
    if (!s || number(&s, 1, res)) return -1;
    if (!*s) return 0;
    if (*res == 0) return -1;               /* "0x4": no default along s with a count along t */
    if (*s == 'x' || *s == 'X') s++;
    else if (strncmp(s, "\xC3\x97", 2) == 0) s += 2;   /* U+00D7 MULTIPLICATION SIGN */
    else return -1;
    if (number(&s, 0, res_t) || *s) return -1;
    if (*res_t == *res) *res_t = 0;          /* N x N is --res N */
    return 0;
}
