/* sb_regress_pictures.c — the nightly report's pictures: for each scene of
 * the suite one representative case (its first converged case, else its
 * first case with a record), whose record of the first repeat is drawn at
 * its final state (sb_study_thumbnail: `shellbench render` at 240x180, 4
 * samples per pixel) into DIR/final-SCENE.png, shown in a table under the
 * report's case table with a caption naming the case. */
#include "sb_regress.h"
#include "sb_study_fig.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define MAX_SCENES 32

/* the scene of a case id "SCENE/METHOD-SOLVER-rN.h5" (len bytes) */
static size_t scene_len(const char *id)
{
    const char *s = strchr(id, '/');
    return s ? (size_t)(s - id) : strlen(id);
}

void sb_regress_picture_path(const char *dir, const char *id, char *buf, size_t len)
{
    snprintf(buf, len, "%s/final-%.*s.png", dir, (int)scene_len(id), id);
}

int sb_regress_pictures(FILE *md, const sb_regress_set *now, const char *records, const char *dir, FILE *err)
{
    int pick[MAX_SCENES], n = 0;
    for (int k = 0; k < now->n; k++) {
        const sb_regress_case *c = &now->c[k];
        if (!c->ok) continue;
        const size_t L = scene_len(c->id);
        int j = 0;
        while (j < n && !(scene_len(now->c[pick[j]].id) == L && !strncmp(now->c[pick[j]].id, c->id, L))) j++;
        if (j == n) {
            if (n == MAX_SCENES) continue;
            pick[n++] = k;
        } else if (now->c[pick[j]].fig.status != 0 && c->fig.status == 0) {
            pick[j] = k;   /* a converged case before one that stopped */
        }
    }
    char png[MAX_SCENES][1100], cap[MAX_SCENES][600];
    int drawn = 0, bad = 0;
    for (int j = 0; j < n; j++) {
        const sb_regress_case *c = &now->c[pick[j]];
        char rec[1200], msg[1400], scene[SB_REGRESS_ID_LEN];
        const size_t L = scene_len(c->id);
        snprintf(scene, sizeof scene, "%.*s", (int)L, c->id);
        snprintf(rec, sizeof rec, "%s/rep1/%s", records, c->id);
        sb_regress_picture_path(dir, c->id, png[drawn], sizeof png[drawn]);
        if (access(rec, R_OK)) {
            fprintf(err, "shellbench regress: warning: no picture of %s: its record %s is gone\n", c->id, rec);
            bad++;
            continue;
        }
        if (sb_study_thumbnail(rec, png[drawn], msg, sizeof msg)) {
            fprintf(err, "shellbench regress: warning: %s\n", msg);
            bad++;
            continue;
        }
        snprintf(cap[drawn], sizeof cap[drawn], "`%s`, final state (%s), repeat 1 of this run", c->id,
                 c->fig.status == 0 ? "converged" : "not converged");
        snprintf(png[drawn], sizeof png[drawn], "final-%s.png", scene);   /* relative to the report */
        drawn++;
    }
    if (!drawn) return bad ? -1 : 0;
    fprintf(md, "\n## Final states\n\nOne case per scene (its first converged case), drawn from its record by "
                "`shellbench render` (%dx%d, %d samples per pixel; docs/render.md).\n\n", SB_THUMB_W, SB_THUMB_H,
            SB_THUMB_SPP);
    for (int i = 0; i < drawn; i += 3) {
        const int m = drawn - i < 3 ? drawn - i : 3;
        fprintf(md, "|");
        for (int j = 0; j < m; j++) fprintf(md, " ![%s](%s) |", cap[i + j], png[i + j]);
        fprintf(md, "\n|");
        for (int j = 0; j < m; j++) fprintf(md, "---|");
        fprintf(md, "\n|");
        for (int j = 0; j < m; j++) fprintf(md, " %s |", cap[i + j]);
        fprintf(md, "\n\n");
    }
    return bad ? -1 : 0;
}
