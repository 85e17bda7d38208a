/* sb_study_fig.h — the study report's figures (gnuplot PNG + SVG): one
 * gnuplot run per figure (sb_study_gnuplot.c), the figures themselves in
 * sb_study_figs.c.  Every function returns 0, or -1 with a warning sentence
 * in err (the report goes on without that figure), or SB_FIG_REFUSED (an
 * output path that must not be written: below). */
#ifndef SB_STUDY_FIG_H
#define SB_STUDY_FIG_H

#include "sb_study_data.h"

#include <stdio.h>

typedef struct sb_gp {
    char dir[512];            /* private temporary directory */
    const char *prog;         /* gnuplot */
    FILE *body;               /* the plot commands (written twice: PNG, SVG) */
    char *body_text;
    size_t body_len;
    int ndata;
} sb_gp;

int   sb_gp_open(sb_gp *g, const char *prog);
/* a new data file in the figure's directory (its path into path) */
FILE *sb_gp_data(sb_gp *g, char *path, size_t len);
void  sb_gp_quoted(FILE *f, const char *s);
/* run gnuplot: the body into png and svg (replaced atomically), clean up */
int   sb_gp_finish(sb_gp *g, const char *png, const char *svg, int width, int height, char *err, size_t errlen);
void  sb_gp_abandon(sb_gp *g);

/* Output safety (sb_study_thumb.c): every file a report writes is checked
 * with sb_output_check (new or regular files only; a symbolic link, FIFO,
 * device or directory is refused with a sentence, since the file is renamed
 * onto its path).  Functions below return SB_FIG_REFUSED for such a path:
 * the report then exits 2. */
#define SB_FIG_REFUSED (-2)
int sb_study_output_ok(const char *path, const char *what, char *err, size_t errlen);
/* the temporary file a report is written to before its rename: created
 * anew (O_EXCL | O_NOFOLLOW, after removing whatever was at the path) */
FILE *sb_study_open_tmp(const char *tmp);
/* Close a report written to tmp (opened by sb_study_open_tmp) and rename it
 * onto path after checking path again (it may have changed meanwhile);
 * `refused` counts the report's refused figure and picture paths.  Says what
 * happened on err and returns the exit code: 0, SB_EXIT_INPUT (a refused
 * path) or SB_EXIT_INTERNAL (a failed write; tmp removed). */
int sb_study_commit_report(FILE *md, const char *tmp, const char *path, int refused, FILE *err);

/* A picture of a record's final state (`shellbench render` at
 * SB_THUMB_W x SB_THUMB_H, SB_THUMB_SPP samples per pixel): 0, -1 (the
 * record cannot be drawn: the sentence in err) or SB_FIG_REFUSED. */
#define SB_THUMB_W 240
#define SB_THUMB_H 180
#define SB_THUMB_SPP 4
int sb_study_thumbnail(const char *record, const char *png, char *err, size_t errlen);

/* cost measures of the diagrams and profiles */
enum { SB_COST_SECONDS = 0, SB_COST_WORK = 1 };
const char *sb_cost_name(int cost);       /* "seconds", "work units" */
const char *sb_cost_axis(int cost);       /* axis label with its unit */

/* Work-precision diagram of scene i: error against cost, one curve per
 * configuration (start 0, converged runs, increasing dofs), points labelled
 * by dofs, the Pareto front, the error targets.  STEM.png / STEM.svg. */
int sb_fig_work_precision(const sb_study_data *d, int i, int cost, const char *stem, const char *gnuplot,
                          char *err, size_t errlen);
/* Performance profile: rho_s(tau) for the ns configurations (labels) over
 * np problems (ratio[p * ns + s]); style[s] is configuration s's config id,
 * so that it has the same colour as in the other figures (NULL: s). */
int sb_fig_profile(int np, int ns, const double *ratio, char (*labels)[128], const int *style, const char *title,
                   const char *stem, const char *gnuplot, char *err, size_t errlen);
/* the colour ("#rrggbb") of configuration c in every figure: 12 distinct
 * colours, then dash patterns (sb_study_figs.c) */
const char *sb_fig_colour(int c);
/* log10 ||g|| against cumulative iteration, one line per configuration at
 * the resolution nearest the scene's middle dofs (start 0). */
int sb_fig_convergence(const sb_study_data *d, int i, const char *stem, const char *gnuplot, char *err, size_t errlen);

#endif
