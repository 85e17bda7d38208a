/* sb_path.c — relative links between files of a report or site. */
#include "sb_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The path of `target` (relative to the current directory, normally the
 * project root) as seen from directory `dir`: a relative link that works in
 * a report or page wherever it is written (study reports, the site).  0, or
 * -1 when either does not exist. */
int sb_path_relative(const char *dir, const char *target, char *buf, size_t len)
{
    char a[4100], b[4100];
    if (!realpath(dir, a) || !realpath(target, b)) return -1;
    size_t la = strlen(a);
    if (la == 0 || a[la - 1] != '/') a[la] = '/', a[la + 1] = 0;   /* the directory as "DIR/" */
    /* the common leading directories end at the last '/' both share */
    size_t cut = 0;
    for (size_t i = 0; a[i] && b[i] && a[i] == b[i]; i++)
        if (a[i] == '/') cut = i + 1;
    /* one "../" per directory of dir below them, then the rest of target */
    size_t n = 0;
    buf[0] = 0;
    for (const char *p = a + cut; *p; p++)
        if (*p == '/' && n + 3 < len) memcpy(buf + n, "../", 4), n += 3;
    snprintf(buf + n, len - n, "%s", b + cut);
    return 0;
}
