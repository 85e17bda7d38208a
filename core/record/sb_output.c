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

/* the pid a lock file holds, or 0 */
static long read_pid(int fd)
{
    char buf[64];
    ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
    if (n <= 0) return 0;
    buf[n] = 0;
    return strtol(buf, NULL, 10);
}

int sb_output_check_dir(const char *dir, const char *what, char *err, size_t errlen)
{
    char p[4096];
    struct stat st;
    if (!dir || !dir[0]) {
        snprintf(err, errlen, "empty directory path for %s", what);
        return SB_ERR_INPUT;
    }
    if (snprintf(p, sizeof p, "%s", dir) >= (int)sizeof p) {
        snprintf(err, errlen, "cannot write %s into %s: the path is too long", what, dir);
        return SB_ERR_INPUT;
    }
    for (;;) {
        if (stat(p, &st) == 0) {
            if (!S_ISDIR(st.st_mode)) {
                if (!strcmp(p, dir))
                    snprintf(err, errlen, "cannot write %s into %s: it is %s, not a directory", what, dir,
                             S_ISREG(st.st_mode) ? "a regular file" : type_name(st.st_mode));
                else
                    snprintf(err, errlen, "cannot write %s into %s: %s is not a directory", what, dir, p);
                return SB_ERR_INPUT;
            }
            if (access(p, W_OK | X_OK) != 0) {
                snprintf(err, errlen, "cannot write %s into %s: %s is not writable (%s)", what, dir, p, strerror(errno));
                return SB_ERR_INPUT;
            }
            return SB_OK;
        }
        if (errno != ENOENT && errno != ENOTDIR) {   /* ENOTDIR: the ancestor that is a file is named below */
            snprintf(err, errlen, "cannot write %s into %s: %s: %s", what, dir, p, strerror(errno));
            return SB_ERR_INPUT;
        }
        if (!strcmp(p, ".") || !strcmp(p, "/")) {
            snprintf(err, errlen, "cannot write %s into %s: %s", what, dir, strerror(errno));
            return SB_ERR_INPUT;
        }
        char *slash = strrchr(p, '/');
        while (slash && slash > p && slash[1] == 0) {   /* "dir/": the trailing slash names dir */
            *slash = 0;
            slash = strrchr(p, '/');
        }
        if (!slash) snprintf(p, sizeof p, ".");          /* relative: the current directory decides */
        else if (slash == p) p[1] = 0;                   /* the root */
        else *slash = 0;
    }
}

int sb_output_check_file_dir(const char *path, const char *what, int must_exist, char *err, size_t errlen)
{
    char dir[4096];
    if (snprintf(dir, sizeof dir, "%s", path ? path : "") >= (int)sizeof dir) {
        snprintf(err, errlen, "cannot write %s %s: the path is too long", what, path);
        return SB_ERR_INPUT;
    }
    char *slash = strrchr(dir, '/');
    if (!slash) snprintf(dir, sizeof dir, ".");
    else if (slash == dir) dir[1] = 0;
    else *slash = 0;
    struct stat st;
    if (must_exist && stat(dir, &st) != 0 && errno == ENOENT) {
        snprintf(err, errlen, "cannot write %s %s: its directory %s does not exist", what, path, dir);
        return SB_ERR_INPUT;
    }
    char w[300];
    snprintf(w, sizeof w, "the %s %s", what, path);
    return sb_output_check_dir(dir, w, err, errlen);
}

int sb_output_check_lockfile(const char *out_path, char *err, size_t errlen)
{
    char lp[4200];
    struct stat st;
    if (snprintf(lp, sizeof lp, "%s.lock", out_path) >= (int)sizeof lp) {
        snprintf(err, errlen, "output path %s is too long", out_path);
        return SB_ERR_INPUT;
    }
    if (lstat(lp, &st) != 0 || S_ISREG(st.st_mode)) return SB_OK;
    snprintf(err, errlen, "cannot lock %s: its lock file %s is %s (a lock file is made by shellbench as a regular "
             "file; remove it)", out_path, lp, type_name(st.st_mode));
    return SB_ERR_INPUT;
}

int sb_output_lock_clear_stale(const char *out_path, char *err, size_t errlen)
{
    char lp[4200];
    struct stat st;
    if (snprintf(lp, sizeof lp, "%s.lock", out_path) >= (int)sizeof lp) {
        snprintf(err, errlen, "output path %s is too long", out_path);
        return SB_ERR_INPUT;
    }
    if (lstat(lp, &st) != 0) return SB_OK;
    if (!S_ISREG(st.st_mode)) return sb_output_check_lockfile(out_path, err, errlen);
    int fd = open(lp, O_RDWR | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return SB_OK;   /* gone meanwhile */
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        long pid = read_pid(fd);
        close(fd);
        if (pid > 0)
            snprintf(err, errlen, "%s is being written by another process, %ld (lock %s)", out_path, pid, lp);
        else
            snprintf(err, errlen, "%s is being written by another process (lock %s)", out_path, lp);
        return SB_ERR_INPUT;
    }
    /* nobody holds it: its writer is gone (the kernel drops a lock with its process) */
    struct stat b;
    if (fstat(fd, &st) == 0 && lstat(lp, &b) == 0 && st.st_ino == b.st_ino && st.st_dev == b.st_dev) unlink(lp);
    close(fd);
    return SB_OK;
}

FILE *sb_input_open(const char *path, const char *what, char *err, size_t errlen)
{
    struct stat st;
    memset(&st, 0, sizeof st);
    if (!path || !path[0]) {
        snprintf(err, errlen, "empty %s path", what);
        return NULL;
    }
    /* O_NONBLOCK: opening a FIFO without a writer would block here */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, errlen, "cannot open the %s %s: %s", what, path, strerror(errno));
        return NULL;
    }
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "will not read the %s %s: it is %s; %ss are read only from regular files (a FIFO or "
                 "device could block forever or never end)", what, path, type_name(st.st_mode), what);
        close(fd);
        return NULL;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        snprintf(err, errlen, "cannot open the %s %s: %s", what, path, strerror(errno));
        close(fd);
    }
    return f;
}

void sb_output_lock_init(sb_output_lock *lk)
{
    lk->fd = -1;
    lk->path[0] = 0;
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
