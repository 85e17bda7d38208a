/* sb_regress_report.c — the nightly regression's report: a Markdown table
 * (one row per case: verdict, counts, times against the baseline, the test)
 * and one PNG per case of its history over the stored runs (the history CSV:
 * normalized CPU time, median with min..max, each point labelled by build,
 * date, host and BLAS kernel set).  Figures through gnuplot
 * (core/study/sb_study_gnuplot.c); a missing gnuplot is a warning. */
#include "sb_regress.h"
#include "sb_gsl.h"
#include "sb_study_fig.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double med(const double *x, int n)
{
    double m = NAN;
    if (n < 1 || sb_median(x, (size_t)n, &m)) return NAN;
    return m;
}

static double minimum(const double *x, int n)
{
    double m = INFINITY;
    for (int i = 0; i < n; i++) m = fmin(m, x[i]);
    return n ? m : NAN;
}

static void prov_line(FILE *out, const char *what, const sb_regress_prov *p)
{
    fprintf(out, "* %s: build `%s`, %s, host `%s`, %s, BLAS kernels `%s`, %d repeats, calibration %.3f s CPU (median of %d)",
            what, p->build, p->date, p->host, p->cpu, p->blas_core, p->repeat, p->calib_median, p->n_calib);
    if (isfinite(p->load_max) && p->cores > 0) fprintf(out, ", load average up to %.1f on %d cores", p->load_max, p->cores);
    fprintf(out, "\n");
}

/* a measurement made on a machine busier than its cores */
static int busy(const sb_regress_prov *p) { return p && isfinite(p->load_max) && p->cores > 0 && p->load_max > p->cores; }

void sb_regress_markdown(FILE *out, const sb_regress_set *now, const sb_regress_set *base, const sb_regress_rules *ru,
                         const char *baseline_path)
{
    int count[SB_VERDICT_COUNT] = { 0 };
    for (int k = 0; k < now->n; k++) count[now->c[k].verdict]++;
    char esc[1100];   /* the suite's and the baseline's names as given, terminal-safe (sb_escape_copy) */
    fprintf(out, "# Nightly regression: `%s`\n\n", sb_escape_copy(now->prov.suite, esc, sizeof esc));
    prov_line(out, "this run", &now->prov);
    if (base) prov_line(out, "baseline", &base->prov);
    else fprintf(out, "* baseline: none (`%s`)\n", sb_escape_copy(baseline_path, esc, sizeof esc));
    fprintf(out, "* times: CPU seconds of each run's process divided by the calibration kernel's (same invocation); "
                 "slower/faster when a two-sided Mann-Whitney U test gives p < %g **and** the medians differ by at least "
                 "%.0f %% **and** by at least %.0f ms of the run's CPU time; deterministic figures exactly (energy and "
                 "probes to %.0e relative)\n\n",
            ru->alpha, 100 * ru->min_effect, 1e3 * ru->min_seconds, ru->rtol);
    if (busy(&now->prov) || (base && busy(&base->prov)))
        fprintf(out, "**Warning**: the machine was busier than its cores during %s (load average above the core "
                     "count): CPU times then inflate unevenly (shared caches and memory bandwidth), which the calibration "
                     "does not fully absorb; treat slower/faster verdicts with care and re-run on a quiet machine "
                     "(docs/regression.md \"Shared machines\").\n\n",
                busy(&now->prov) && base && busy(&base->prov) ? "this run and the baseline's" : busy(&now->prov) ? "this run" : "the baseline's");
    fprintf(out, "**%d cases:", now->n);
    for (int v = 0; v < SB_VERDICT_COUNT; v++)
        if (count[v]) fprintf(out, " %d %s", count[v], sb_verdict_name((sb_verdict)v));
    int reg = count[SB_VERDICT_SLOWER] + count[SB_VERDICT_CHANGED] + count[SB_VERDICT_FAILED];
    fprintf(out, "; %s**\n\n", reg ? "REGRESSION" : "no regression");
    fprintf(out, "| case | verdict | iterations | assembly WU | CPU s (median, min) | normalized: baseline → now | ratio | p | detail |\n");
    fprintf(out, "|---|---|--:|--:|--:|--:|--:|--:|---|\n");
    for (int k = 0; k < now->n; k++) {
        const sb_regress_case *c = &now->c[k];
        const sb_regress_case *b = sb_regress_set_find(base, c->id);
        fprintf(out, "| `%s` | %s%s%s | ", c->id, sb_verdict_is_regression(c->verdict) ? "**" : "",
                sb_verdict_name(c->verdict), sb_verdict_is_regression(c->verdict) ? "**" : "");
        if (c->ok && b && b->ok && b->fig.n[SB_RF_ITERATIONS] != c->fig.n[SB_RF_ITERATIONS])
            fprintf(out, "%ld → %ld | ", b->fig.n[SB_RF_ITERATIONS], c->fig.n[SB_RF_ITERATIONS]);
        else if (c->ok) fprintf(out, "%ld | ", c->fig.n[SB_RF_ITERATIONS]);
        else fprintf(out, "– | ");
        if (c->ok) fprintf(out, "%.4g | ", c->fig.x[SB_RF_WORK_ASSEMBLY]);
        else fprintf(out, "– | ");
        if (c->n_rep) fprintf(out, "%.3f, %.3f | ", med(c->cpu, c->n_rep), minimum(c->cpu, c->n_rep));
        else fprintf(out, "– | ");
        if (b && b->n_rep && c->n_rep) fprintf(out, "%.3f → %.3f | ", med(b->norm, b->n_rep), med(c->norm, c->n_rep));
        else if (c->n_rep) fprintf(out, "– → %.3f | ", med(c->norm, c->n_rep));
        else fprintf(out, "– | ");
        if (isfinite(c->ratio)) fprintf(out, "%.3f | ", c->ratio);
        else fprintf(out, "– | ");
        if (isfinite(c->p)) fprintf(out, "%.3g | ", c->p);
        else fprintf(out, "– | ");
        for (const char *s = c->detail; *s; s++) fputc(*s == '|' ? '/' : *s, out);
        fprintf(out, " |\n");
    }
    for (int k = 0; base && k < base->n; k++)
        if (!sb_regress_set_find(now, base->c[k].id))
            fprintf(out, "| `%s` | removed | | | | | | | in the baseline, no longer in the suite |\n", base->c[k].id);
}

/* ---- history plots --------------------------------------------------------- */

/* split one CSV line into at most max fields (quoted fields, "" inside) */
static int csv_split(char *line, char **f, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        if (*p == '"') {
            char *w = ++p;
            f[n++] = w;
            while (*p) {
                if (*p == '"' && p[1] == '"') *w++ = '"', p += 2;
                else if (*p == '"') { p++; break; }
                else *w++ = *p++;
            }
            *w = 0;
            while (*p && *p != ',') p++;
        } else {
            f[n++] = p;
            while (*p && *p != ',' && *p != '\n') p++;
        }
        if (*p != ',') { *p = 0; break; }
        *p++ = 0;
    }
    return n;
}

enum { H_DATE, H_BUILD, H_HOST, H_CPU, H_BLAS, H_CASE, H_VERDICT, H_REPEAT, H_CPU_MED, H_CPU_MIN, H_N_MED, H_N_MIN,
       H_N_MAX, H_FIELDS = 16 };

static void file_name(const char *id, char *buf, size_t len)
{
    size_t j = 0;
    for (const char *s = id; *s && j + 1 < len; s++)
        buf[j++] = (*s == '/' || *s == ' ') ? '_' : *s;
    buf[j] = 0;
    char *dot = strstr(buf, ".h5");
    if (dot && dot[3] == 0) *dot = 0;
}

void sb_regress_plot_path(const char *dir, const char *id, const char *ext, char *buf, size_t len)
{
    char stem[300];
    file_name(id, stem, sizeof stem);
    snprintf(buf, len, "%s/history-%s.%s", dir, stem, ext);
}

static int plot_case(const char *history, const char *id, const char *dir, const char *gnuplot, char *why, size_t len)
{
    FILE *h = fopen(history, "r");
    if (!h) { snprintf(why, len, "cannot read %s", history); return -1; }
    sb_gp g;
    if (sb_gp_open(&g, gnuplot)) { fclose(h); snprintf(why, len, "cannot make a temporary directory"); return -1; }
    char dat[600], line[2048];
    FILE *d = sb_gp_data(&g, dat, sizeof dat);
    int n = 0;
    while (d && fgets(line, sizeof line, h)) {
        char *f[H_FIELDS];
        if (csv_split(line, f, H_FIELDS) < H_N_MAX + 1 || strcmp(f[H_CASE], id)) continue;
        double m = atof(f[H_N_MED]), lo = atof(f[H_N_MIN]), hi = atof(f[H_N_MAX]);
        if (!isfinite(m)) continue;
        char date[16];
        snprintf(date, sizeof date, "%.10s", f[H_DATE]);
        /* x, median, min, max, tic label, point label */
        fprintf(d, "%d %.6g %.6g %.6g \"%s\\n%s\" \"%s %s\"\n", n, m, lo, hi, f[H_BUILD], date, f[H_HOST], f[H_BLAS]);
        n++;
    }
    fclose(h);
    if (d) fclose(d);
    if (n == 0) { sb_gp_abandon(&g); snprintf(why, len, "no history of %s", id); return -1; }
    fprintf(g.body, "set title ");
    sb_gp_quoted(g.body, id);
    fprintf(g.body, "\nset ylabel 'CPU time / calibration (median, min..max)'\nset grid ytics\nset key off\n"
                    "set xrange [-0.5:%d.5]\nset yrange [0:*]\nset xtics rotate by -30 font ',8'\n"
                    "plot ", n - 1);
    sb_gp_quoted(g.body, dat);
    fprintf(g.body, " using 1:2:3:4:xtic(5) with yerrorlines lw 2 pt 7, ");
    sb_gp_quoted(g.body, dat);
    fprintf(g.body, " using 1:2:6 with labels offset 0,1 font ',7'\n");
    char png[900], svg[900];
    sb_regress_plot_path(dir, id, "png", png, sizeof png);
    sb_regress_plot_path(dir, id, "svg", svg, sizeof svg);
    return sb_gp_finish(&g, png, svg, 720, 400, why, len);
}

int sb_regress_history_plots(const char *history, const sb_regress_set *now, const char *dir, const char *gnuplot, FILE *err)
{
    int bad = 0;
    for (int k = 0; k < now->n; k++) {
        char why[1024];
        if (plot_case(history, now->c[k].id, dir, gnuplot, why, sizeof why)) {
            fprintf(err, "shellbench regress: warning: %s\n", why);
            bad++;
            if (strstr(why, "not installed")) break;   /* once is enough */
        }
    }
    return bad ? -1 : 0;
}
