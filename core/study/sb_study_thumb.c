/* sb_study_thumb.c — the study reports' pictures and their output checks
 * (sb_study_fig.h): a small ray-traced image of a record's final state
 * (core/render, `shellbench render` with fewer pixels and samples), and the
 * check every file a report writes passes before it is renamed onto its
 * path (core/record/sb_output.h: new or regular files only). */
#include "sb_study_fig.h"
#include "sb_output.h"
#include "sb_render.h"
#include "sb_record.h"
#include "sb_run.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

int sb_study_output_ok(const char *path, const char *what, char *err, size_t errlen)
{
    sb_output_kind kind;
    char msg[1200];
    if (sb_output_check(path, what, &kind, msg, sizeof msg)) {
        snprintf(err, errlen, "%s", msg);
        return SB_FIG_REFUSED;
    }
    if (kind == SB_OUTPUT_DISCARD) {
        snprintf(err, errlen, "will not write %s %s: a report's files are written by renaming onto their paths, "
                 "which would replace the null device", what, path);
        return SB_FIG_REFUSED;
    }
    return 0;
}

FILE *sb_study_open_tmp(const char *tmp)
{
    unlink(tmp);   /* a stale one, or a link planted there: removed, never followed */
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0666);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "w");
    if (!f) close(fd);
    return f;
}

int sb_study_commit_report(FILE *md, const char *tmp, const char *path, int refused, FILE *err)
{
    char msg[1400];
    int bad = ferror(md);
    if (fclose(md) || bad) {
        sb_escape_print(err, "shellbench report: cannot write %s", path);
        unlink(tmp);
        return SB_EXIT_INTERNAL;
    }
    if (sb_study_output_ok(path, "report", msg, sizeof msg)) {
        sb_escape_print(err, "shellbench report: %s", msg);
        unlink(tmp);
        return SB_EXIT_INPUT;
    }
    if (rename(tmp, path)) {
        sb_escape_print(err, "shellbench report: cannot write %s: %s", path, strerror(errno));
        unlink(tmp);
        return SB_EXIT_INTERNAL;
    }
    sb_escape_print(err, "shellbench report: %s", path);
    if (refused) {
        fprintf(err, "shellbench report: %d output path%s refused (above): exit 2\n", refused, refused > 1 ? "s" : "");
        return SB_EXIT_INPUT;
    }
    return 0;
}

int sb_study_thumbnail(const char *record, const char *png, char *err, size_t errlen)
{
    int rc = sb_study_output_ok(png, "picture", err, errlen);
    if (rc) return rc;
    /* A digest without its final state (`shellbench digest --drop-state`,
     * docs/reproducibility.md) cannot be drawn again: the picture drawn from
     * it before it was digested stands, recognised by the record it names
     * (its Source text) and its size. */
    char msg[1024], source[4096];
    const int state = sb_record_keeps_state(record, msg, sizeof msg);
    if (state < 0) {
        snprintf(err, errlen, "picture %s not drawn: %s", png, msg);
        return -1;
    }
    if (state == 0) {
        int w = 0, h = 0;
        if (sb_image_png_text(png, "Source", source, sizeof source, &w, &h) == 0 && !strcmp(source, record) &&
            w == SB_THUMB_W && h == SB_THUMB_H)
            return 0;
        snprintf(err, errlen, "picture %s not drawn: %s is a digest without its final state and %s is not a picture of "
                 "it (run the scene again to draw it)", png, record, png);
        return -1;
    }
    sb_render_request rq;
    memset(&rq, 0, sizeof rq);
    sb_render_options_default(&rq.opt);
    rq.record = record;
    rq.out = png;
    rq.step = -1;
    rq.quiet = 1;
    rq.opt.width = SB_THUMB_W;
    rq.opt.height = SB_THUMB_H;
    rq.opt.spp = SB_THUMB_SPP;
    if (sb_render_record(&rq, NULL, NULL, 0, msg, sizeof msg)) {
        snprintf(err, errlen, "picture %s not drawn: %s", png, msg);
        return -1;
    }
    return 0;
}
