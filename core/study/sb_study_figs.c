/* sb_study_figs.c — the study report's figures (sb_study_fig.h):
 * work-precision diagrams, performance profiles and convergence plots.
 * Legends sit outside the plotting area (right), so they never cover data
 * or an axis label; axes carry their quantity and unit. */
#include "sb_study_fig.h"
#include "sb_record.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *sb_cost_name(int cost) { return cost == SB_COST_SECONDS ? "seconds" : "work units"; }

const char *sb_cost_axis(int cost)
{
    return cost == SB_COST_SECONDS ? "run time (s, wall clock, one core per run)"
                                   : "assembly work units (fine-level assemblies, RMTR paper Eq. 7.3)";
}

static const char *error_axis(sb_error_kind e)
{
    switch (e) {
    case SB_ERRKIND_PROBE: return "max probe error (relative to the analytic displacement)";
    case SB_ERRKIND_FIELD_RMS: return "RMS field error |x - x_ref| / domain diameter";
    case SB_ERRKIND_FIELD_MAX: return "max field error |x - x_ref| / domain diameter";
    default: return "error";
    }
}

/* Curve styles: gnuplot's default cycle has 8 colours, so a ninth
 * configuration would repeat the first one's.  12 distinct colours (the
 * Okabe-Ito set and six more, none grey: grey is the Pareto front), point
 * types on a cycle of 7 and, beyond 12 configurations, a dash pattern per
 * round of the palette: no two of the first 84 curves look alike. */
static const char *const palette[] = { "#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9",
                                       "#000000", "#8c564b", "#7b3294", "#a6a600", "#d62728", "#1b7837" };
#define N_PALETTE ((int)(sizeof palette / sizeof palette[0]))
static const int point_types[] = { 5, 7, 9, 11, 13, 15, 3 };

const char *sb_fig_colour(int c) { return palette[((c % N_PALETTE) + N_PALETTE) % N_PALETTE]; }

/* "lc rgb '#rrggbb' dt D" (and " pt P" when with_points) of curve c */
static const char *curve_style(int c, int with_points, char *buf, size_t len)
{
    int u = c < 0 ? 0 : c;
    int n = snprintf(buf, len, "lc rgb '%s' dt %d", sb_fig_colour(u), 1 + (u / N_PALETTE) % 5);
    if (with_points && n > 0 && (size_t)n < len) snprintf(buf + n, len - n, " pt %d", point_types[u % 7]);
    return buf;
}

static void png_svg(const char *stem, char *png, char *svg, size_t len)
{
    snprintf(png, len, "%s.png", stem);
    snprintf(svg, len, "%s.svg", stem);
}

int sb_fig_work_precision(const sb_study_data *d, int i, int cost, const char *stem, const char *gnuplot,
                          char *err, size_t errlen)
{
    const sb_study *st = d->st;
    sb_gp g;
    char path[700], png[1100], svg[1100];
    if (sb_gp_open(&g, gnuplot)) {
        snprintf(err, errlen, "figure %s not written: no temporary directory", stem);
        return -1;
    }
    int *idx = malloc((size_t)(d->plan.n ? d->plan.n : 1) * sizeof *idx);
    double *fc = malloc((size_t)(d->plan.n ? d->plan.n : 1) * 2 * sizeof *fc);
    int *front = malloc((size_t)(d->plan.n ? d->plan.n : 1) * sizeof *front);
    int *fidx = malloc((size_t)(d->plan.n ? d->plan.n : 1) * sizeof *fidx);
    if (!idx || !fc || !front || !fidx) {
        free(idx), free(fc), free(front), free(fidx);
        sb_gp_abandon(&g);
        snprintf(err, errlen, "figure %s not written: out of memory", stem);
        return -1;
    }
    FILE *body = g.body;
    fprintf(body, "set title ");
    char title[512];
    snprintf(title, sizeof title, "%s: error against %s (one curve per method/solver, points labelled by dofs)",
             st->scenes[i].name, sb_cost_name(cost));
    sb_gp_quoted(body, title);
    fprintf(body, "\nset logscale xy\nset format x '%%g'\nset format y '%%g'\n"
                  "set xlabel '%s'\nset ylabel '%s'\nset grid\nset key outside right top vertical Left reverse "
                  "spacing 1.1\nset mxtics 10\nset mytics 10\n",
            sb_cost_axis(cost), error_axis(st->scenes[i].error));
    for (int t = 0; t < st->n_targets; t++)
        fprintf(body, "set arrow from graph 0, first %g to graph 1, first %g nohead dt 2 lc rgb '#888888'\n"
                      "set label 'target %g' at graph 0.01, first %g offset 0,0.6 tc rgb '#666666' font ',8'\n",
                st->targets[t], st->targets[t], st->targets[t], st->targets[t]);
    /* all curve points for the front */
    int nf = 0, curves = 0;
    fprintf(body, "plot ");
    for (int c = 0; c < d->n_configs; c++) {
        int n = sb_study_curve(d, i, c, cost, idx);
        if (n == 0) continue;
        FILE *f = sb_gp_data(&g, path, sizeof path);
        if (!f) break;
        for (int k = 0; k < n; k++) {
            const sb_study_point *q = &d->pt[idx[k]];
            fprintf(f, "%.10g %.10g %ld\n", sb_point_cost(q, cost), q->error, q->dofs);
            fc[2 * nf] = sb_point_cost(q, cost), fc[2 * nf + 1] = q->error, fidx[nf] = idx[k];
            nf++;
        }
        fclose(f);
        char label[128];
        sb_study_config_label(d, c, label, sizeof label);
        fprintf(body, "%s", curves ? ", \\\n     " : "");
        sb_gp_quoted(body, path);
        char sty[96];
        fprintf(body, " using 1:2 with linespoints lw 2 ps 1.2 %s title ", curve_style(c, 1, sty, sizeof sty));
        sb_gp_quoted(body, label);
        fprintf(body, ", \\\n     ");
        sb_gp_quoted(body, path);
        fprintf(body, " using 1:2:(sprintf('%%d', $3)) with labels offset char 0.9,0.7 font ',7' tc rgb '%s' notitle", sb_fig_colour(c));
        curves++;
    }
    if (curves == 0) {
        free(idx), free(fc), free(front), free(fidx);
        sb_gp_abandon(&g);
        snprintf(err, errlen, "no converged run of scene %s has an error: no work-precision diagram", st->scenes[i].name);
        return -1;
    }
    /* the Pareto front: cheaper and more accurate than every other point */
    double *cst = malloc((size_t)nf * sizeof *cst), *er = malloc((size_t)nf * sizeof *er);
    if (cst && er) {
        for (int k = 0; k < nf; k++) cst[k] = fc[2 * k], er[k] = fc[2 * k + 1];
        sb_wp_pareto(nf, cst, er, front);
        FILE *f = sb_gp_data(&g, path, sizeof path);
        if (f) {
            /* in increasing cost (a staircase down to the right) */
            int *ord = malloc((size_t)nf * sizeof *ord);
            double *key = malloc((size_t)nf * sizeof *key);
            if (ord && key) {
                for (int k = 0; k < nf; k++) key[k] = front[k] ? cst[k] : HUGE_VAL;
                sb_select_order(nf, key, ord);
                for (int k = 0; k < nf; k++)
                    if (front[ord[k]]) fprintf(f, "%.10g %.10g\n", cst[ord[k]], er[ord[k]]);
            }
            free(key);
            free(ord);
            fclose(f);
            fprintf(body, ", \\\n     ");
            sb_gp_quoted(body, path);
            fprintf(body, " using 1:2 with steps lw 7 lc rgb '#60a0a0a0' title 'Pareto front', \\\n     ");
            sb_gp_quoted(body, path);
            fprintf(body, " using 1:2 with points pt 6 ps 2.2 lc rgb '#404040' notitle");
        }
    }
    free(cst), free(er);
    fprintf(body, "\n");
    png_svg(stem, png, svg, sizeof png);
    int rc = sb_gp_finish(&g, png, svg, 1100, 620, err, errlen);
    free(idx), free(fc), free(front), free(fidx);
    return rc;
}

int sb_fig_profile(int np, int ns, const double *ratio, char (*labels)[128], const int *style, const char *title,
                   const char *stem, const char *gnuplot, char *err, size_t errlen)
{
    sb_gp g;
    char path[700], png[1100], svg[1100];
    if (np <= 0 || ns <= 0) {
        snprintf(err, errlen, "figure %s not written: no problems", stem);
        return -1;
    }
    if (sb_gp_open(&g, gnuplot)) {
        snprintf(err, errlen, "figure %s not written: no temporary directory", stem);
        return -1;
    }
    double tmax = 2;
    for (int k = 0; k < np * ns; k++) if (isfinite(ratio[k]) && ratio[k] * 1.5 > tmax) tmax = ratio[k] * 1.5;
    FILE *body = g.body;
    fprintf(body, "set title ");
    sb_gp_quoted(body, title);
    fprintf(body, "\nset logscale x 2\nset xrange [1:%g]\nset yrange [0:1.05]\nset xlabel 'tau: within this factor of the "
                  "cheapest configuration'\nset ylabel 'share of scenes (rho(tau))'\nset grid\n"
                  "set key outside right top vertical Left reverse\nplot ", tmax);
    double *r = malloc((size_t)np * sizeof *r);
    for (int s = 0; s < ns && r; s++) {
        FILE *f = sb_gp_data(&g, path, sizeof path);
        if (!f) break;
        int m = 0;
        for (int p = 0; p < np; p++) if (isfinite(ratio[p * ns + s])) r[m++] = ratio[p * ns + s];
        /* rho is right-continuous: value at tau = 1, then a step at each ratio */
        fprintf(f, "1 %.10g\n", sb_profile_rho(np, ns, ratio, s, 1.0));
        for (int a = 0; a < m; a++)
            for (int b = a + 1; b < m; b++) if (r[b] < r[a]) { double t = r[a]; r[a] = r[b]; r[b] = t; }
        for (int a = 0; a < m; a++) if (r[a] > 1) fprintf(f, "%.10g %.10g\n", r[a], sb_profile_rho(np, ns, ratio, s, r[a]));
        fprintf(f, "%.10g %.10g\n", tmax, sb_profile_rho(np, ns, ratio, s, tmax));
        fclose(f);
        fprintf(body, "%s", s ? ", \\\n     " : "");
        sb_gp_quoted(body, path);
        char sty[96];
        fprintf(body, " using 1:2 with steps lw 2 %s title ", curve_style(style ? style[s] : s, 0, sty, sizeof sty));
        sb_gp_quoted(body, labels[s]);
    }
    free(r);
    fprintf(body, "\n");
    png_svg(stem, png, svg, sizeof png);
    return sb_gp_finish(&g, png, svg, 1000, 560, err, errlen);
}

/* the run of configuration c on scene i (start 0, recorded) nearest to
 * `mid` dofs in ratio */
static int run_near(const sb_study_data *d, int i, int c, double mid)
{
    int best = -1;
    double bq = INFINITY;
    for (int k = 0; k < d->plan.n; k++) {
        const sb_study_point *q = &d->pt[k];
        if (d->plan.runs[k].scene != i || q->config != c || d->plan.runs[k].start != 0 || q->state != SB_POINT_RECORDED) continue;
        double qq = fabs(log((double)q->dofs / mid));
        if (qq < bq) bq = qq, best = k;
    }
    return best;
}

int sb_fig_convergence(const sb_study_data *d, int i, const char *stem, const char *gnuplot, char *err, size_t errlen)
{
    const sb_study *st = d->st;
    double lo = INFINITY, hi = 0;
    for (int k = 0; k < d->plan.n; k++)
        if (d->plan.runs[k].scene == i && d->pt[k].state == SB_POINT_RECORDED)
            lo = fmin(lo, (double)d->pt[k].dofs), hi = fmax(hi, (double)d->pt[k].dofs);
    if (!(hi > 0)) {
        snprintf(err, errlen, "scene %s has no record: no convergence plot", st->scenes[i].name);
        return -1;
    }
    double mid = sqrt(lo * hi);
    sb_gp g;
    char path[700], png[1100], svg[1100], msg[1024];
    if (sb_gp_open(&g, gnuplot)) {
        snprintf(err, errlen, "figure %s not written: no temporary directory", stem);
        return -1;
    }
    FILE *body = g.body;
    char title[256];
    snprintf(title, sizeof title, "%s: log10 ||g|| against cumulative iteration (finest level)", st->scenes[i].name);
    fprintf(body, "set title ");
    sb_gp_quoted(body, title);
    fprintf(body, "\nset xlabel 'cumulative iteration over all steps'\nset ylabel 'log10 ||g||'\nset grid\n"
                  "set key outside right top vertical Left reverse\nplot ");
    int lines = 0;
    for (int c = 0; c < d->n_configs; c++) {
        int k = run_near(d, i, c, mid);
        if (k < 0) continue;
        sb_record_summary s;
        if (sb_record_read_summary(d->plan.runs[k].out, &s, msg, sizeof msg)) continue;
        int L = 0;
        for (int h = 0; h < s.n_hist; h++) if (s.hist_level[h] > L) L = s.hist_level[h];
        FILE *f = sb_gp_data(&g, path, sizeof path);
        int any = 0;
        if (f) {
            int base = 0, last = 0, step = s.n_hist ? s.hist_step[0] : 0;
            for (int h = 0; h < s.n_hist; h++) {
                if (s.hist_level[h] != L) continue;
                if (s.hist_step[h] != step) base += last, last = 0, step = s.hist_step[h];
                if (s.hist_iter[h] > last) last = s.hist_iter[h];
                if (isfinite(s.hist_gnorm[h]) && s.hist_gnorm[h] > 0)
                    fprintf(f, "%d %.10g\n", base + s.hist_iter[h], log10(s.hist_gnorm[h])), any = 1;
            }
            fclose(f);
        }
        sb_record_summary_free(&s);
        if (!any) continue;
        char label[200], cl[128];
        sb_study_config_label(d, c, cl, sizeof cl);
        snprintf(label, sizeof label, "%s (%ld dofs)%s", cl, d->pt[k].dofs, d->pt[k].status ? " NOT converged" : "");
        fprintf(body, "%s", lines ? ", \\\n     " : "");
        sb_gp_quoted(body, path);
        char sty[96];
        fprintf(body, " using 1:2 with lines lw 1.5 %s title ", curve_style(c, 0, sty, sizeof sty));
        sb_gp_quoted(body, label);
        lines++;
    }
    if (!lines) {
        sb_gp_abandon(&g);
        snprintf(err, errlen, "scene %s: no history to plot", st->scenes[i].name);
        return -1;
    }
    fprintf(body, "\n");
    png_svg(stem, png, svg, sizeof png);
    return sb_gp_finish(&g, png, svg, 1100, 560, err, errlen);
}
