/* sb_study_rep.h — internal to the study report: the report under way and
 * the sections written by sb_study_report_runs.c. */
#ifndef SB_STUDY_REP_H
#define SB_STUDY_REP_H

#include "sb_study_fig.h"

typedef struct sb_rep {
    const sb_study *st;
    const sb_study_data *d;
    const sb_study_report_options *o;
    FILE *md, *err;
    char dir[1024];
    int n_costs, costs[2];     /* the cost measures shown (seconds first) */
    int refused;               /* output paths refused (sb_study_output_ok): the report exits 2 */
    /* per scene: its picture thumb-SCENE.png (1 drawn) and its caption, or
     * why there is none */
    int thumb[SB_STUDY_MAX_SCENES];
    char thumb_caption[SB_STUDY_MAX_SCENES][400];
} sb_rep;

/* the picture of scene i (and its caption) into the report, or the line
 * saying why there is none */
void sb_rep_thumb(sb_rep *R, int i);

/* "%.3g", or an em dash for a non-finite value */
void sb_rep_g3(char *buf, size_t len, double v);
/* scenes with several solutions (and perturbed starts): energy, spread, cost */
void sb_rep_multiple_scenes(sb_rep *R);
/* every record per scene */
void sb_rep_run_tables(sb_rep *R);
/* refused, missing, skipped, not applicable */
void sb_rep_without_records(sb_rep *R);

#endif
