/* sb_path.c — paths of outputs: directories made with their parents,
 * relative links between files of a report or site. */
#include "sb_common.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* mkdir -p: DIR and its missing parents (0777 before the umask); 0, or -1
 * with errno when one cannot be made or the path is too long */
int sb_mkdir_p(const char *dir)
{
    char tmp[4200];
    if (snprintf(tmp, sizeof tmp, "%s/", dir) >= (int)sizeof tmp) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = tmp + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0777) && errno != EEXIST) return -1;
            *p = '/';
        }
    return 0;
}

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
