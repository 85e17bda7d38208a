/* sb_output.h — output paths a run or a report may write, and the lock that
 * keeps two writers off one record.
 *
 * Records, XDMF sidecars, checkpoints and plots are written to a temporary
 * file and renamed onto their path, which replaces whatever is there.  So
 * an output path must be new or a regular file; /dev/null means "discard"
 * (like --out none); a character or block device, FIFO, socket, directory or
 * symbolic link is refused with one sentence (a symbolic link even to a
 * regular file: the rename would replace the link, not its target).
 * docs/cli.md "Output safety". */
#ifndef SB_OUTPUT_H
#define SB_OUTPUT_H

#include <stddef.h>

typedef enum {
    SB_OUTPUT_NEW = 0,        /* nothing there yet */
    SB_OUTPUT_REGULAR = 1,    /* a regular file, replaced when the output is written */
    SB_OUTPUT_DISCARD = 2     /* /dev/null: write nothing */
} sb_output_kind;

/* Classify `path` for writing by rename.  SB_OK with *kind, or SB_ERR_INPUT
 * with a sentence naming `what` ("record", "plot") and the path. */
int sb_output_check(const char *path, const char *what, sb_output_kind *kind, char *err, size_t errlen);

/* 1 when path names the null device (/dev/null, or any path to the same
 * character device). */
int sb_output_is_null(const char *path);

/* An exclusive lock on an output: the file OUT.lock beside it, holding the
 * writer's pid, locked with flock(LOCK_EX).  A second writer is refused with
 * a sentence naming the first one's pid.  The kernel drops the lock when its
 * process ends however it ends, so the lock file a killed run leaves behind
 * is taken over by the next writer (a stale lock never blocks).  Creating
 * the lock file also proves, before any work, that the output's directory
 * is writable. */
typedef struct sb_output_lock {
    int fd;                   /* -1: not held */
    char path[4200];
} sb_output_lock;

void sb_output_lock_init(sb_output_lock *lk);
/* Take the lock of out_path; SB_OK, or SB_ERR_INPUT (held by another
 * process, not creatable) with a sentence. */
int  sb_output_lock_take(sb_output_lock *lk, const char *out_path, char *err, size_t errlen);
/* Remove the lock file and release the lock (no-op when not held). */
void sb_output_lock_release(sb_output_lock *lk);

#endif
