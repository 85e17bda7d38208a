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
#include <stdio.h>

typedef enum {
    SB_OUTPUT_NEW = 0,        /* nothing there yet */
    SB_OUTPUT_REGULAR = 1,    /* a regular file, replaced when the output is written */
    SB_OUTPUT_DISCARD = 2     /* /dev/null: write nothing */
} sb_output_kind;

/* Classify `path` for writing by rename.  SB_OK with *kind, or SB_ERR_INPUT
 * with a sentence naming `what` ("record", "plot") and the path. */
int sb_output_check(const char *path, const char *what, sb_output_kind *kind, char *err, size_t errlen);

/* A directory outputs will be written into (made if missing): it is a
 * writable directory, or its nearest existing ancestor is one.  SB_OK, or
 * SB_ERR_INPUT with a sentence naming `what` ("records", "report"), the
 * directory and what is wrong (a file where a directory is wanted, not
 * writable).  Checked before any work, so that nothing is computed for an
 * output that cannot be written. */
int sb_output_check_dir(const char *dir, const char *what, char *err, size_t errlen);
/* sb_output_check_dir on the directory of the file `path` ("." without a
 * slash); the sentence names `what` and the file.  must_exist: the
 * directory is not made by the writer, so it must exist now. */
int sb_output_check_file_dir(const char *path, const char *what, int must_exist, char *err, size_t errlen);

/* The lock file OUT.lock of out_path is absent or a regular file (a
 * symbolic link, FIFO or directory there is refused with a sentence):
 * the check a planner makes before any run, sb_output_lock_take's own
 * refusal made early. */
int sb_output_check_lockfile(const char *out_path, char *err, size_t errlen);

/* An input file (a study, suite or baseline): opened without blocking,
 * then accepted only when it is a regular file (a FIFO without a writer
 * would block the open or the read forever, a device never end).  The
 * stream, or NULL with a sentence naming `what` ("study file") and the
 * path. */
FILE *sb_input_open(const char *path, const char *what, char *err, size_t errlen);

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
/* Remove the lock file OUT.lock a writer that is gone left behind (nobody
 * holds its lock).  SB_OK (none, or removed), or SB_ERR_INPUT when a live
 * process holds it (its pid in the sentence) or it is not a regular file. */
int  sb_output_lock_clear_stale(const char *out_path, char *err, size_t errlen);
/* Remove the lock file and release the lock (no-op when not held). */
void sb_output_lock_release(sb_output_lock *lk);

#endif
