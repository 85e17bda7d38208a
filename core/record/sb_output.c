/* sb_output.c — output path checks and output locks (sb_output.h). */
#include "sb_output.h"
#include "sb_common.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

int sb_output_is_null(const char *path)
{
    struct stat a, b;
    if (!path || stat(path, &a) != 0 || !S_ISCHR(a.st_mode)) return 0;
    return stat("/dev/null", &b) == 0 && S_ISCHR(b.st_mode) && a.st_rdev == b.st_rdev;
}

static const char *type_name(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISCHR(m) ? "a character device" : S_ISBLK(m) ? "a block device"
         : S_ISFIFO(m) ? "a FIFO (named pipe)" : S_ISSOCK(m) ? "a socket" : S_ISLNK(m) ? "a symbolic link"
         : "not a regular file";
}

int sb_output_check(const char *path, const char *what, sb_output_kind *kind, char *err, size_t errlen)
{
    struct stat st;
    *kind = SB_OUTPUT_NEW;
    if (!path || !path[0]) {
        snprintf(err, errlen, "empty %s path", what);
        return SB_ERR_INPUT;
    }
    if (lstat(path, &st) != 0) {
        if (errno == ENOENT) return SB_OK;
        if (errno == ENOTDIR) {
            snprintf(err, errlen, "cannot write %s %s: a component of the path is not a directory", what, path);
            return SB_ERR_INPUT;
        }
        snprintf(err, errlen, "cannot write %s %s: %s", what, path, strerror(errno));
        return SB_ERR_INPUT;
    }
    if (S_ISREG(st.st_mode)) {
        *kind = SB_OUTPUT_REGULAR;
        return SB_OK;
    }
    if (sb_output_is_null(path)) {   /* /dev/null itself (not a link to it: links are refused below) */
        if (!S_ISLNK(st.st_mode)) {
            *kind = SB_OUTPUT_DISCARD;
            return SB_OK;
        }
    }
    if (S_ISLNK(st.st_mode)) {
        snprintf(err, errlen, "will not write %s %s: it is a symbolic link, and writing replaces the file at a path by "
                 "renaming onto it, which would replace the link rather than write its target; give the target's path",
                 what, path);
        return SB_ERR_INPUT;
    }
    snprintf(err, errlen, "will not write %s %s: it is %s; %ss are written only to regular files or new paths "
             "(/dev/null or none discards)", what, path, type_name(st.st_mode), what);
    return SB_ERR_INPUT;
}

void sb_output_lock_init(sb_output_lock *lk)
{
    lk->fd = -1;
    lk->path[0] = 0;
}

/* the pid a lock file holds, or 0 */
static long read_pid(int fd)
{
    char buf[64];
    ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
    if (n <= 0) return 0;
    buf[n] = 0;
    return strtol(buf, NULL, 10);
}

int sb_output_lock_take(sb_output_lock *lk, const char *out_path, char *err, size_t errlen)
{
    sb_output_lock_init(lk);
    if (snprintf(lk->path, sizeof lk->path, "%s.lock", out_path) >= (int)sizeof lk->path) {
        snprintf(err, errlen, "output path %s is too long", out_path);
        return SB_ERR_INPUT;
    }
    for (int attempt = 0; attempt < 8; attempt++) {
        int fd = open(lk->path, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0644);
        if (fd < 0) {
            if (errno == ELOOP)
                snprintf(err, errlen, "cannot lock %s: its lock file %s is a symbolic link", out_path, lk->path);
            else
                snprintf(err, errlen, "cannot write %s: cannot create its lock file %s: %s", out_path, lk->path,
                         strerror(errno));
            return SB_ERR_INPUT;
        }
        struct stat a, b;
        if (fstat(fd, &a) != 0 || !S_ISREG(a.st_mode)) {
            close(fd);
            snprintf(err, errlen, "cannot lock %s: its lock file %s is not a regular file", out_path, lk->path);
            return SB_ERR_INPUT;
        }
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            int e = errno;
            long pid = read_pid(fd);
            close(fd);
            if (e == EWOULDBLOCK) {
                if (pid > 0)
                    snprintf(err, errlen, "%s is being written by another run, process %ld (lock %s): wait for it to "
                             "finish or choose another output", out_path, pid, lk->path);
                else
                    snprintf(err, errlen, "%s is being written by another run (lock %s): wait for it to finish or "
                             "choose another output", out_path, lk->path);
            } else {
                snprintf(err, errlen, "cannot lock %s (%s): %s", out_path, lk->path, strerror(e));
            }
            return SB_ERR_INPUT;
        }
        /* the file we hold must still be the one at the path: the previous
         * holder unlinks it before it lets go */
        if (stat(lk->path, &b) != 0 || a.st_ino != b.st_ino || a.st_dev != b.st_dev) {
            close(fd);
            continue;
        }
        char line[32];
        int len = snprintf(line, sizeof line, "%ld\n", (long)getpid());
        if (ftruncate(fd, 0) != 0 || pwrite(fd, line, (size_t)len, 0) != len) {
            int e = errno;
            unlink(lk->path);
            close(fd);
            snprintf(err, errlen, "cannot write %s: cannot write its lock file %s: %s", out_path, lk->path, strerror(e));
            return SB_ERR_INPUT;
        }
        lk->fd = fd;
        return SB_OK;
    }
    snprintf(err, errlen, "cannot lock %s: its lock file %s keeps changing", out_path, lk->path);
    return SB_ERR_INPUT;
}

void sb_output_lock_release(sb_output_lock *lk)
{
    if (lk->fd < 0) return;
    unlink(lk->path);
    close(lk->fd);
    lk->fd = -1;
}
