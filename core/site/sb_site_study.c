/* sb_site_study.c — a study's pages: the overview (description, provenance,
 * the method-selection table, performance profiles, one card per scene with
 * its picture), one page per scene (interactive work-precision diagrams,
 * every run in a table) and one page per recorded run (sb_site_run.c).
 * Everything is computed from the records by core/study (sb_study_data_load:
 * the same numbers as report.md); nothing is run. */
#include "sb_site.h"
#include "sb_site_int.h"
#include "sb_study_data.h"
#include "sb_study_fig.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The rule for run pages: every record of a study gets its page while the
 * study has at most SB_SITE_MAX_RUN_PAGES records; a larger study gets them
 * for the points of its work-precision diagrams only (recorded runs of the
 * unperturbed start with an error), the others are rows of the scene's
 * table with a link to their record. */
#define SB_SITE_MAX_RUN_PAGES 1000

static int has_page(const sb_study_data *d, int k, int all)
{
    const sb_study_point *q = &d->pt[k];
    if (q->state != SB_POINT_RECORDED) return 0;
    return all || (d->plan.runs[k].start == 0 && isfinite(q->error) && q->error > 0);
}

static int unique_ranked(const sb_study *st, int i)
{
    return st->scenes[i].solution == SB_SOLUTION_UNIQUE && st->scenes[i].error != SB_ERRKIND_NONE;
}

static const char *point_status(const sb_study_point *q)
{
    switch (q->state) {
    case SB_POINT_RECORDED: return q->status == 0 ? "converged" : "not converged";
    case SB_POINT_REFUSED: return "refused";
    case SB_POINT_MISSING: return "not run";
    case SB_POINT_SKIPPED: return "skipped";
    default: return "not applicable";
    }
}

/* the run page of plan run k, relative to the site root */
static void run_rel(const sb_study *st, const sb_study_data *d, int k, char *buf, size_t len)
{
    char sn[128], stem[1100], nm[128];
    sb_site_slug(st->name, nm, sizeof nm);
    sb_site_slug(st->scenes[d->plan.runs[k].scene].name, sn, sizeof sn);
    const char *base = strrchr(d->plan.runs[k].out, '/');
    base = base ? base + 1 : d->plan.runs[k].out;
    snprintf(stem, sizeof stem, "%s", base);
    char *dot = strstr(stem, ".h5");
    if (dot) *dot = 0;
    char slug[1100];
    sb_site_slug(stem, slug, sizeof slug);
    snprintf(buf, len, "studies/%.100s/runs/%.100s/%.400s.html", nm, sn, slug);
}

static void num_cell(FILE *f, double v, const char *fmt)
{
    if (!isfinite(v)) { fputs("<td class=\"r\" data-v=\"\">—</td>", f); return; }
    fprintf(f, "<td class=\"r\" data-v=\"%.17g\">", v);
    fprintf(f, fmt, v);
    fputs("</td>", f);
}

/* a cost and how it was reached (the bracketing dofs) */
static void cost_cell(FILE *f, double v, const char *how)
{
    if (!isfinite(v)) { fputs("<td class=\"r\" data-v=\"\">—</td>", f); return; }
    fprintf(f, "<td class=\"r\" data-v=\"%.17g\">%.3g<br><span class=\"how\">", v, v);
    sb_html_text(f, how);
    fputs("</span></td>", f);
}

static void label_of(const sb_study_data *d, int c, char *buf, size_t len) { sb_study_config_label(d, c, buf, len); }

/* ---- the overview ------------------------------------------------------------ */

static void selection_rows(FILE *f, const sb_study_data *d, int cost)
{
    const sb_study *st = d->st;
    int nc = d->n_configs;
    double *cst = malloc((size_t)nc * sizeof *cst);
    int *ord = malloc((size_t)nc * sizeof *ord);
    char (*how)[96] = malloc((size_t)nc * sizeof *how);
    if (!cst || !ord || !how) goto out;
    for (int i = 0; i < st->n_scenes; i++) {
        if (!unique_ranked(st, i)) continue;
        for (int t = 0; t < st->n_targets; t++) {
            for (int c = 0; c < nc; c++) {
                long lo, hi;
                double best;
                cst[c] = sb_study_reach(d, i, c, cost, st->targets[t], &lo, &hi, &best);
                if (isfinite(cst[c]) && lo == 0) snprintf(how[c], sizeof how[c], "≤, already at %ld dofs", hi);
                else if (isfinite(cst[c])) snprintf(how[c], sizeof how[c], "%ld–%ld dofs", lo, hi);
                else if (isfinite(best)) snprintf(how[c], sizeof how[c], "best %.2g", best);
                else snprintf(how[c], sizeof how[c], "no converged run with an error");
                if (!sb_study_has_record(d, i, c) || isnan(cst[c])) cst[c] = INFINITY;
            }
            int nfin = sb_select_order(nc, cst, ord);
            char a[160] = "—", b[160] = "—";
            if (nfin >= 1) label_of(d, ord[0], a, sizeof a);
            if (nfin >= 2) label_of(d, ord[1], b, sizeof b);
            fputs("<tr><td>", f);
            sb_html_text(f, st->scenes[i].name);
            fprintf(f, "</td><td>%s</td>", sb_cost_name(cost));
            num_cell(f, st->targets[t], "%g");
            fputs("<td>", f);
            sb_html_text(f, a);
            fputs("</td>", f);
            cost_cell(f, nfin >= 1 ? cst[ord[0]] : NAN, nfin >= 1 ? how[ord[0]] : "");
            fputs("<td>", f);
            sb_html_text(f, b);
            fputs("</td>", f);
            cost_cell(f, nfin >= 2 ? cst[ord[1]] : NAN, nfin >= 2 ? how[ord[1]] : "");
            num_cell(f, nfin >= 2 ? cst[ord[1]] / cst[ord[0]] : NAN, "%.2f");
            fputs("<td>", f);
            int listed = 0;
            for (int k = nfin; k < nc; k++) {
                if (!sb_study_has_record(d, i, ord[k])) continue;
                char l[160];
                label_of(d, ord[k], l, sizeof l);
                if (listed++) fputs("; ", f);
                sb_html_text(f, l);
                fputs(" <span class=\"how\">(", f);
                sb_html_text(f, how[ord[k]]);
                fputs(")</span>", f);
            }
            fputs(listed ? "" : "none", f);
            fputs("</td></tr>\n", f);
        }
    }
out:
    free(cst);
    free(ord);
    free(how);
}

/* profiles as JSON: [{title, series: [{label, colour, pts: [[tau, rho]...]}]}] */
static int profiles_json(FILE *f, const sb_study_data *d, int n_costs, const int *costs)
{
    const sb_study *st = d->st;
    int np = 0, nc = d->n_configs, scenes[SB_STUDY_MAX_SCENES], nplots = 0;
    for (int i = 0; i < st->n_scenes; i++) if (unique_ranked(st, i)) scenes[np++] = i;
    int *cfg = malloc((size_t)nc * sizeof *cfg), ns = 0;
    double *t = NULL, *ratio = NULL, *taus = NULL;
    fputs("[", f);
    if (!cfg || np == 0) goto out;
    for (int c = 0; c < nc; c++) {
        int any = 0;
        for (int p = 0; p < np; p++) any |= sb_study_has_record(d, scenes[p], c);
        if (any) cfg[ns++] = c;
    }
    t = malloc((size_t)np * ns * sizeof *t), ratio = malloc((size_t)np * ns * sizeof *ratio);
    taus = malloc((size_t)(np + 2) * sizeof *taus);
    if (!t || !ratio || !taus || ns == 0) goto out;
    for (int k = 0; k < n_costs; k++)
        for (int tg = 0; tg < st->n_targets; tg++) {
            int cost = costs[k];
            for (int p = 0; p < np; p++)
                for (int s = 0; s < ns; s++) t[p * ns + s] = sb_study_reach(d, scenes[p], cfg[s], cost, st->targets[tg], NULL, NULL, NULL);
            sb_profile_ratios(np, ns, t, ratio);
            double tmax = 1;
            for (int q = 0; q < np * ns; q++) if (isfinite(ratio[q]) && ratio[q] > tmax) tmax = ratio[q];
            tmax *= 2;
            fprintf(f, "%s{\"id\":\"profile-%d-%d\",\"title\":", nplots++ ? "," : "", cost, tg);
            char title[200];
            snprintf(title, sizeof title, "%s to reach error %g (%d scenes)", sb_cost_name(cost), st->targets[tg], np);
            sb_json_str(f, title);
            fputs(",\"series\":[", f);
            for (int s = 0; s < ns; s++) {
                char l[160];
                label_of(d, cfg[s], l, sizeof l);
                fprintf(f, "%s{\"label\":", s ? "," : "");
                sb_json_str(f, l);
                fprintf(f, ",\"colour\":\"%s\",\"pts\":[", sb_fig_colour(cfg[s]));
                /* breakpoints: 1, every finite ratio of s, the right end */
                int nt = 0;
                taus[nt++] = 1;
                for (int p = 0; p < np; p++) if (isfinite(ratio[p * ns + s])) taus[nt++] = ratio[p * ns + s];
                taus[nt++] = tmax;
                for (int a = 1; a < nt; a++)   /* insertion sort */
                    for (int b = a; b > 0 && taus[b] < taus[b - 1]; b--) { double x = taus[b]; taus[b] = taus[b - 1]; taus[b - 1] = x; }
                for (int a = 0; a < nt; a++) {
                    fputs(a ? ",[" : "[", f);
                    sb_json_num(f, taus[a]);
                    fputc(',', f);
                    sb_json_num(f, sb_profile_rho(np, ns, ratio, s, taus[a]));
                    fputc(']', f);
                }
                fputs("]}", f);
            }
            fputs("]}", f);
        }
out:
    fputs("]", f);
    free(cfg);
    free(t);
    free(ratio);
    free(taus);
    return nplots;
}

/* ---- a scene page ------------------------------------------------------------------ */

static void scene_page(sb_site *S, const sb_study_data *d, int i, const char *nm, int n_costs, const int *costs, int all)
{
    const sb_study *st = d->st;
    char rel[700], sn[128], title[300], h[1400];
    sb_site_slug(st->scenes[i].name, sn, sizeof sn);
    snprintf(rel, sizeof rel, "studies/%s/scene-%s.html", nm, sn);
    snprintf(title, sizeof title, "%s — study %s", st->scenes[i].name, st->name);
    sb_page p;
    int ranked = unique_ranked(st, i);
    if (sb_page_open(S, &p, rel, title, ranked)) return;
    FILE *f = p.f;
    fputs("<p class=\"crumbs\"><a href=\"index.html\">study ", f);
    sb_html_text(f, st->name);
    fputs("</a></p>\n<h1>Scene ", f);
    sb_html_text(f, st->scenes[i].name);
    fputs("</h1>\n", f);
    if (st->scenes[i].scene && st->scenes[i].scene->description[0]) {
        fputs("<p class=\"desc\">", f);
        sb_html_text(f, st->scenes[i].scene->description);
        fputs("</p>\n", f);
    }
    char thumb[1300];
    snprintf(thumb, sizeof thumb, "%s/thumb-%s.png", st->records, st->scenes[i].name);
    struct stat sst;
    if (stat(thumb, &sst) == 0 && S_ISREG(sst.st_mode)) fprintf(f, "<figure><img src=\"thumb-%s.png\" alt=\"final state\"><figcaption>final state (the report's picture)</figcaption></figure>\n", sn);
    /* curves: configurations with converged points of the unperturbed start */
    int *idx = malloc((size_t)(d->plan.n + 1) * sizeof *idx);
    if (ranked && idx) {
        fputs("<h2>Work-precision diagrams</h2>\n<p>Error against cost, log-log; one line per configuration through its "
              "converged runs in increasing dofs (the unperturbed start; perturbed starts are in the table below); hollow points did not converge; circled "
              "points are on the Pareto front; dashed lines are the error targets.  Wheel: zoom, drag: pan, double "
              "click: reset; hover a point for its run, click it for the run's page.</p>\n", f);
        for (int k = 0; k < n_costs; k++) {
            int nser = 0;
            for (int c = 0; c < d->n_configs; c++) nser += sb_study_curve(d, i, c, costs[k], idx) > 0;
            fprintf(f, "<div class=\"sb-plot\" data-plot=\"wp\" data-cost=\"%d\" data-expect-series=\"%d\"></div>\n", costs[k], nser);
        }
        /* the points: every recorded run with a finite error and positive cost */
        sb_page_data_open(&p);
        fputs("{\"targets\":[", f);
        for (int t = 0; t < st->n_targets; t++) fprintf(f, "%s%g", t ? "," : "", st->targets[t]);
        fputs("],\"error\":", f);
        sb_json_str(f, st->scenes[i].error == SB_ERRKIND_PROBE ? "max probe error (relative)" :
                       st->scenes[i].error == SB_ERRKIND_FIELD_MAX ? "max field error / diameter" : "RMS field error / diameter");
        fputs(",\"points\":[", f);
        int n = 0;
        /* Pareto fronts per cost over the plotted points */
        int np = 0;
        int *pk = malloc((size_t)(d->plan.n + 1) * sizeof *pk);
        double *cs = malloc((size_t)(d->plan.n + 1) * sizeof *cs), *cw = malloc((size_t)(d->plan.n + 1) * sizeof *cw);
        double *er = malloc((size_t)(d->plan.n + 1) * sizeof *er);
        int *fs = calloc((size_t)(d->plan.n + 1), sizeof *fs), *fw = calloc((size_t)(d->plan.n + 1), sizeof *fw);
        if (pk && cs && cw && er && fs && fw) {
            for (int k = 0; k < d->plan.n; k++) {
                const sb_study_point *q = &d->pt[k];
                if (d->plan.runs[k].scene != i || d->plan.runs[k].start != 0 || q->state != SB_POINT_RECORDED || !isfinite(q->error) ||
                    q->error <= 0)
                    continue;
                pk[np] = k, cs[np] = q->seconds > 0 ? q->seconds : NAN, cw[np] = q->work > 0 ? q->work : NAN, er[np] = q->error;
                if (q->status != 0 || d->plan.runs[k].start != 0) cs[np] = cw[np] = NAN;   /* not on a front */
                np++;
            }
            sb_wp_pareto(np, cs, er, fs);
            sb_wp_pareto(np, cw, er, fw);
            for (int a = 0; a < np; a++) {
                int k = pk[a];
                const sb_study_point *q = &d->pt[k];
                char l[160], rr[700];
                label_of(d, q->config, l, sizeof l);
                run_rel(st, d, k, rr, sizeof rr);
                const char *base = strrchr(d->plan.runs[k].out, '/');
                fprintf(f, "%s{\"c\":", n++ ? ",\n" : "");
                sb_json_str(f, l);
                fprintf(f, ",\"colour\":\"%s\",\"dofs\":%ld,\"start\":%d,\"seconds\":", sb_fig_colour(q->config), q->dofs, d->plan.runs[k].start);
                sb_json_num(f, q->seconds);
                fputs(",\"work\":", f);
                sb_json_num(f, q->work);
                fputs(",\"error\":", f);
                sb_json_num(f, q->error);
                fprintf(f, ",\"iterations\":%d,\"converged\":%d,\"front0\":%d,\"front1\":%d,\"status\":", q->iterations,
                        q->status == 0, fs[a], fw[a]);
                sb_json_str(f, point_status(q));
                fputs(",\"record\":", f);
                sb_json_str(f, base ? base + 1 : d->plan.runs[k].out);
                fputs(",\"href\":", f);
                /* relative to the scene page (studies/NAME/) */
                sb_json_str(f, rr + strlen("studies/") + strlen(nm) + 1);
                fputc('}', f);
            }
        }
        free(pk), free(cs), free(cw), free(er), free(fs), free(fw);
        fputs("]}", f);
        sb_page_data_close(&p);
    } else if (!ranked) {
        fputs("<p>This scene has several solutions (or nothing to measure its error against): it is not ranked by "
              "distance to a reference (docs/study.md); its runs are listed below.</p>\n", f);
    }
    free(idx);
    /* every run of the scene */
    fputs("<h2>Runs</h2>\n<p><input class=\"sb-filter\" data-table=\"runs\" placeholder=\"filter: method, solver, status…\"> "
          "<span class=\"count\" data-count-for=\"runs\"></span></p>\n", f);
    fputs("<div class=\"tablewrap\"><table class=\"sb-table\" id=\"runs\"><thead><tr><th>configuration</th><th>start</th>"
          "<th class=\"r\">res</th><th class=\"r\">dofs</th><th>status</th><th class=\"r\">iterations</th>"
          "<th class=\"r\">seconds</th><th class=\"r\">work units</th><th class=\"r\">error</th><th class=\"r\">energy (J)</th>"
          "<th>run</th></tr></thead><tbody>\n", f);
    for (int k = 0; k < d->plan.n; k++) {
        const sb_plan_run *r = &d->plan.runs[k];
        const sb_study_point *q = &d->pt[k];
        if (r->scene != i) continue;
        char l[160];
        label_of(d, q->config, l, sizeof l);
        fputs("<tr><td>", f);
        sb_html_text(f, l);
        fprintf(f, "</td><td>%s</td>", r->start ? "perturbed" : "unperturbed");
        num_cell(f, r->res, "%.0f");
        num_cell(f, q->dofs > 0 ? (double)q->dofs : NAN, "%.0f");
        fputs("<td>", f);
        sb_html_text(f, point_status(q));
        if (q->state == SB_POINT_RECORDED && q->status) fputs(" (", f), sb_html_text(f, q->reason), fputc(')', f);
        if (q->state != SB_POINT_RECORDED && q->why[0]) fputs(": ", f), sb_html_text(f, q->why);
        fputs("</td>", f);
        int rec = q->state == SB_POINT_RECORDED;
        num_cell(f, rec ? q->iterations : NAN, "%.0f");
        num_cell(f, rec ? q->seconds : NAN, "%.3g");
        num_cell(f, rec ? q->work : NAN, "%.4g");
        num_cell(f, rec ? q->error : NAN, "%.3g");
        num_cell(f, rec ? q->energy : NAN, "%.6g");
        if (has_page(d, k, all)) {
            char rr[700];
            run_rel(st, d, k, rr, sizeof rr);
            fputs("<td><a href=\"", f);
            sb_html_attr(f, rr + strlen("studies/") + strlen(nm) + 1);
            fputs("\">page</a></td>", f);
        } else if (rec) {
            char link[4200];
            if (sb_site_link(S, rel, r->out, link, sizeof link) == 0) {
                fputs("<td><a href=\"", f);
                sb_html_attr(f, link);
                fputs("\">record</a></td>", f);
            } else fputs("<td></td>", f);
        } else fputs("<td></td>", f);
        fputs("</tr>\n", f);
    }
    fputs("</tbody></table></div>\n", f);
    (void)h;
    sb_page_close(S, &p);
    if (stat(thumb, &sst) == 0 && S_ISREG(sst.st_mode)) {
        char trel[700];
        snprintf(trel, sizeof trel, "studies/%s/thumb-%s.png", nm, sn);
        sb_site_copy_file(S, thumb, trel);
    }
}

int sb_site_study(sb_site *S, const char *study_file, const char *records, sb_site_entry *e)
{
    sb_study *st = calloc(1, sizeof *st);
    char err[2048];
    if (!st) return -1;
    if (sb_study_load(study_file, records, st, err, sizeof err)) {
        fprintf(S->err, "shellbench site: %s\n", err);
        free(st);
        S->errors++;
        return -1;
    }
    if (st->kind != SB_STUDY_ACCURACY) {
        sb_study_free(st);
        free(st);
        return 1;   /* a dt study: its report is rendered instead */
    }
    sb_study_data d;
    if (sb_study_data_load(st, &d, S->err)) {
        sb_study_free(st);
        free(st);
        S->errors++;
        return -1;
    }
    char nm[128], rel[400];
    sb_site_slug(st->name, nm, sizeof nm);
    snprintf(rel, sizeof rel, "studies/%s/index.html", nm);
    int costs[2] = { SB_COST_SECONDS, SB_COST_WORK }, n_costs = 2;
    /* provenance: builds and dates of the records */
    int rec = 0, conv = 0, planned = 0, pages = 0;
    char builds[512] = "", first[32] = "", last[32] = "";
    for (int k = 0; k < d.plan.n; k++) {
        const sb_study_point *q = &d.pt[k];
        planned += d.plan.runs[k].state == SB_PLAN_RUN || q->state == SB_POINT_REFUSED;
        if (q->state != SB_POINT_RECORDED) continue;
        rec++, conv += q->status == 0;
        if (q->build[0] && !strstr(builds, q->build) && strlen(builds) + strlen(q->build) + 3 < sizeof builds)
            snprintf(builds + strlen(builds), sizeof builds - strlen(builds), "%s%s", builds[0] ? ", " : "", q->build);
    }
    /* one page per recorded run (the rule above) */
    const int all = rec <= SB_SITE_MAX_RUN_PAGES;
    for (int k = 0; k < d.plan.n; k++) {
        if (!has_page(&d, k, all)) continue;
        char rr[700], back[300], sn[128], label[400], l[160];
        run_rel(st, &d, k, rr, sizeof rr);
        sb_site_slug(st->scenes[d.plan.runs[k].scene].name, sn, sizeof sn);
        snprintf(back, sizeof back, "studies/%s/scene-%s.html", nm, sn);
        label_of(&d, d.pt[k].config, l, sizeof l);
        snprintf(label, sizeof label, "%s, %s, %ld dofs%s", st->scenes[d.plan.runs[k].scene].name, l, d.pt[k].dofs,
                 d.plan.runs[k].start ? ", perturbed start" : "");
        char started[32] = "";
        pages += sb_site_run(S, d.plan.runs[k].out, rr, back, label, started, sizeof started) == 0;
        if (started[0] && (!first[0] || strcmp(started, first) < 0)) snprintf(first, sizeof first, "%s", started);
        if (started[0] && strcmp(started, last) > 0) snprintf(last, sizeof last, "%s", started);
    }
    sb_page p;
    char title[200];
    snprintf(title, sizeof title, "study %s", st->name);
    if (sb_page_open(S, &p, rel, title, 1) == 0) {
        FILE *f = p.f;
        fputs("<h1>Study <code>", f);
        sb_html_text(f, st->name);
        fputs("</code></h1>\n", f);
        if (st->description[0]) { fputs("<p class=\"desc\">", f); sb_html_text(f, st->description); fputs("</p>\n", f); }
        fprintf(f, "<p>Study file <code>");
        sb_html_text(f, st->path);
        fputs("</code>, records under <code>", f);
        sb_html_text(f, st->records);
        fprintf(f, "</code>: %d planned runs, %d recorded (%d converged).  Builds of the records: ", planned, rec, conv);
        sb_html_text(f, builds[0] ? builds : "—");
        fputs("; recorded ", f);
        sb_html_text(f, first[0] ? first : "—");
        fputs(" to ", f);
        sb_html_text(f, last[0] ? last : "—");
        fputs(".  The same numbers as the study's <code>report.md</code> (<code>shellbench report --study</code>): "
              "both are computed by core/study from the records.</p>\n", f);
        /* scenes */
        fputs("<h2>Scenes</h2>\n<div class=\"cards\">\n", f);
        for (int i = 0; i < st->n_scenes; i++) {
            char sn[128], thumb[1300];
            sb_site_slug(st->scenes[i].name, sn, sizeof sn);
            snprintf(thumb, sizeof thumb, "%s/thumb-%s.png", st->records, st->scenes[i].name);
            struct stat sst;
            fprintf(f, "<a class=\"card\" href=\"scene-%s.html\">", sn);
            if (stat(thumb, &sst) == 0 && S_ISREG(sst.st_mode)) fprintf(f, "<img src=\"thumb-%s.png\" alt=\"\">", sn);
            fputs("<span>", f);
            sb_html_text(f, st->scenes[i].name);
            fputs(unique_ranked(st, i) ? "" : " (several solutions)", f);
            fputs("</span></a>\n", f);
        }
        fputs("</div>\n", f);
        /* the selection table */
        fputs("<h2>Method selection</h2>\n<p>Per scene with a unique solution and error target: the configuration that "
              "reaches the target cheapest, the runner-up and the ratio of their costs (interpolated log-log between the "
              "bracketing resolutions, never extrapolated; docs/study.md).  Click a column to sort; type to filter "
              "(scene, method, solver, cost).</p>\n<p><input class=\"sb-filter\" data-table=\"selection\" "
              "placeholder=\"filter: scene, method, solver…\"> <span class=\"count\" data-count-for=\"selection\"></span></p>\n", f);
        fputs("<div class=\"tablewrap\"><table class=\"sb-table\" id=\"selection\"><thead><tr><th data-key=\"scene\">scene</th>"
              "<th data-key=\"by\">by</th><th class=\"r\" data-key=\"target\">error target</th><th data-key=\"cheapest\">cheapest</th>"
              "<th class=\"r\" data-key=\"cost\">cost</th><th data-key=\"runnerup\">runner-up</th><th class=\"r\" data-key=\"cost2\">cost</th>"
              "<th class=\"r\" data-key=\"ratio\">ratio</th><th data-key=\"never\">never reach the target</th></tr></thead><tbody>\n", f);
        for (int k = 0; k < n_costs; k++) selection_rows(f, &d, costs[k]);
        fputs("</tbody></table></div>\n", f);
        /* profiles */
        fputs("<h2>Performance profiles</h2>\n<p>Dolan &amp; Moré (2002): ρ(τ) is the share of the scenes with a unique "
              "solution on which a configuration reaches the error target within a factor τ of the cheapest.  "
              "ρ(1): how often it is the cheapest; the right end: how often it reaches the target at all.</p>\n", f);
        long pos = ftell(f);
        (void)pos;
        /* the data first into a memory buffer, to know the plots' count */
        char *buf = NULL;
        size_t blen = 0;
        FILE *mf = open_memstream(&buf, &blen);
        int nplots = mf ? profiles_json(mf, &d, n_costs, costs) : 0;
        if (mf) fclose(mf);
        for (int k = 0; k < nplots; k++) fprintf(f, "<div class=\"sb-plot\" data-plot=\"profile\" data-index=\"%d\"></div>\n", k);
        sb_page_data_open(&p);
        fputs("{\"profiles\":", f);
        if (buf) fwrite(buf, 1, blen, f);
        fputs("}", f);
        sb_page_data_close(&p);
        free(buf);
        sb_page_close(S, &p);
    }
    for (int i = 0; i < st->n_scenes; i++) scene_page(S, &d, i, nm, n_costs, costs, all);
    snprintf(e->href, sizeof e->href, "%s", rel);
    snprintf(e->title, sizeof e->title, "study %s: %d scenes, %d records, %d run pages", st->name, st->n_scenes, rec, pages);
    snprintf(e->date, sizeof e->date, "%s", last[0] ? last : "—");
    snprintf(e->provenance, sizeof e->provenance, "%.500s; builds %.500s", st->path, builds[0] ? builds : "—");
    sb_study_data_free(&d);
    sb_study_free(st);
    free(st);
    return 0;
}
