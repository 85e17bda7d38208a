/* sb_site_nightly.c — the nightly history page (asv / LNT style) from the
 * history CSV that `shellbench regress` appends to and the baseline it
 * judges against (docs/regression.md): the last invocation's summary first,
 * every invocation with its build and provenance, a table of the cases,
 * and per case its normalized CPU time over the invocations (median, min to
 * max), each point coloured by its verdict, the baseline's median drawn as
 * a line; hover names the build, date, verdict, counts. */
#include "sb_site_int.h"
#include "sb_regress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NCOL 16
static const char *const cols[NCOL] = { "date", "build", "host", "cpu", "blas_core", "case", "verdict", "repeat",
                                        "cpu_median", "cpu_min", "normalized_median", "normalized_min", "normalized_max",
                                        "calibration_median", "iterations", "work_assembly" };
enum { C_DATE, C_BUILD, C_HOST, C_CPU, C_BLAS, C_CASE, C_VERDICT, C_REPEAT, C_CPUMED, C_CPUMIN, C_NMED, C_NMIN, C_NMAX,
       C_CALIB, C_ITER, C_WU };

typedef struct hrow {
    char f[NCOL][256];
    int inv;                   /* invocation index */
    int cs;                    /* case index */
} hrow;

/* one CSV record (RFC 4180 quoting, one line): fields into r; count */
static int csv_split(const char *line, char out[][256], int max)
{
    int k = 0;
    const char *p = line;
    while (k < max) {
        size_t n = 0;
        if (*p == '"') {
            p++;
            while (*p) {
                if (*p == '"' && p[1] == '"') { if (n < 255) out[k][n++] = '"'; p += 2; continue; }
                if (*p == '"') { p++; break; }
                if (n < 255) out[k][n++] = *p;
                p++;
            }
        } else {
            while (*p && *p != ',' && *p != '\n' && *p != '\r') { if (n < 255) out[k][n++] = *p; p++; }
        }
        out[k][n] = 0;
        k++;
        while (*p && *p != ',' && *p != '\n') p++;
        if (*p != ',') break;
        p++;
    }
    return k;
}

static double num(const char *s)
{
    char *e;
    double v = strtod(s, &e);
    return e == s ? NAN : v;
}

static void build_href(const sb_site *S, const char *build, int inv, char *buf, size_t len)
{
    if (S->commit_url[0]) {
        char id[64];
        snprintf(id, sizeof id, "%s", build);
        id[strcspn(id, "-+ ")] = 0;
        snprintf(buf, len, "%s%s", S->commit_url, id);
    } else {
        snprintf(buf, len, "#run-%d", inv);
    }
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int sb_site_nightly(sb_site *S, const char *history, const char *baseline, sb_site_entry *e)
{
    FILE *in = fopen(history, "r");
    if (!in) {
        fprintf(S->err, "shellbench site: cannot read the nightly history %s\n", history);
        S->errors++;
        return -1;
    }
    char line[8192], hdr[NCOL + 8][256];
    int map[NCOL];
    for (int c = 0; c < NCOL; c++) map[c] = -1;
    if (!fgets(line, sizeof line, in)) { fclose(in); fprintf(S->err, "shellbench site: %s is empty\n", history); S->errors++; return -1; }
    int nh = csv_split(line, hdr, NCOL + 8);
    for (int k = 0; k < nh; k++)
        for (int c = 0; c < NCOL; c++) if (!strcmp(hdr[k], cols[c])) map[c] = k;
    if (map[C_DATE] < 0 || map[C_BUILD] < 0 || map[C_CASE] < 0 || map[C_VERDICT] < 0 || map[C_NMED] < 0) {
        fclose(in);
        fprintf(S->err, "shellbench site: %s has no date, build, case, verdict and normalized_median columns: not a history of shellbench regress\n", history);
        S->errors++;
        return -1;
    }
    hrow *rows = NULL;
    int n = 0, cap = 0;
    char (*inv_date)[256] = NULL;
    int ninv = 0, invcap = 0;
    char (*cases)[256] = NULL;
    int ncase = 0, casecap = 0;
    char f[NCOL + 8][256];
    while (fgets(line, sizeof line, in)) {
        int nf = csv_split(line, f, NCOL + 8);
        if (nf < nh) continue;
        if (n == cap) {
            hrow *r2 = realloc(rows, (size_t)(cap = cap ? 2 * cap : 256) * sizeof *rows);
            if (!r2) break;
            rows = r2;
        }
        hrow *r = &rows[n];
        for (int c = 0; c < NCOL; c++) snprintf(r->f[c], sizeof r->f[c], "%s", map[c] >= 0 ? f[map[c]] : "");
        /* invocation: by date and build (appended in order) */
        int iv = ninv - 1;
        if (iv < 0 || strcmp(inv_date[iv], r->f[C_DATE]) != 0) {
            if (ninv == invcap) {
                void *p2 = realloc(inv_date, (size_t)(invcap = invcap ? 2 * invcap : 16) * sizeof *inv_date);
                if (!p2) break;
                inv_date = p2;
            }
            snprintf(inv_date[ninv], 256, "%s", r->f[C_DATE]);
            iv = ninv++;
        }
        r->inv = iv;
        int cs = -1;
        for (int k = 0; k < ncase; k++) if (!strcmp(cases[k], r->f[C_CASE])) { cs = k; break; }
        if (cs < 0) {
            if (ncase == casecap) {
                void *p2 = realloc(cases, (size_t)(casecap = casecap ? 2 * casecap : 64) * sizeof *cases);
                if (!p2) break;
                cases = p2;
            }
            snprintf(cases[ncase], 256, "%s", r->f[C_CASE]);
            cs = ncase++;
        }
        r->cs = cs;
        n++;
    }
    fclose(in);
    /* the baseline's normalized median per case */
    sb_regress_set base;
    memset(&base, 0, sizeof base);
    int have_base = 0;
    char berr[1024];
    if (baseline && sb_regress_baseline_read(baseline, &base, berr, sizeof berr) == 0) have_base = 1;
    else if (baseline) fprintf(S->err, "shellbench site: warning: %s\n", berr);
    double *bmed = malloc((size_t)(ncase + 1) * sizeof *bmed);
    for (int k = 0; k < ncase && bmed; k++) {
        bmed[k] = NAN;
        const sb_regress_case *c = have_base ? sb_regress_set_find(&base, cases[k]) : NULL;
        if (c && c->n_rep > 0) {
            double v[SB_REGRESS_MAX_REPEAT];
            memcpy(v, c->norm, (size_t)c->n_rep * sizeof *v);
            qsort(v, (size_t)c->n_rep, sizeof *v, cmp_dbl);
            bmed[k] = c->n_rep % 2 ? v[c->n_rep / 2] : 0.5 * (v[c->n_rep / 2 - 1] + v[c->n_rep / 2]);
        }
    }
    sb_page p;
    const char *rel = "nightly/index.html";
    if (!bmed || sb_page_open(S, &p, rel, "nightly history", 1)) {
        free(rows), free(inv_date), free(cases), free(bmed);
        sb_regress_set_free(&base);
        return -1;
    }
    FILE *o = p.f;
    const int last = ninv - 1;
    /* the last run first */
    int counts[8] = { 0 };
    static const char *const vnames[] = { "same", "faster", "slower", "changed", "failed", "new", "removed" };
    const hrow *lr = NULL;
    for (int k = 0; k < n; k++)
        if (rows[k].inv == last) {
            lr = &rows[k];
            int v = 7;
            for (int q = 0; q < 7; q++) if (!strcmp(rows[k].f[C_VERDICT], vnames[q])) v = q;
            counts[v]++;
        }
    fputs("<h1>Nightly history</h1>\n<p>Source: <code>", o);
    sb_html_text(o, history);
    fputs("</code>", o);
    if (have_base) fputs(" and the baseline <code>", o), sb_html_text(o, baseline), fputs("</code>", o);
    fprintf(o, ": %d invocations of <code>shellbench regress</code>, %d cases.  Times are CPU seconds divided by the "
               "calibration kernel's of the same invocation (docs/regression.md).</p>\n", ninv, ncase);
    if (lr) {
        char bh[700];
        build_href(S, lr->f[C_BUILD], last, bh, sizeof bh);
        fputs("<section class=\"last\"><h2>Last run</h2>\n<p>Build <a href=\"", o);
        sb_html_attr(o, bh);
        fputs("\"><code>", o);
        sb_html_text(o, lr->f[C_BUILD]);
        fputs("</code></a>, ", o);
        sb_html_text(o, lr->f[C_DATE]);
        fputs(", host <code>", o);
        sb_html_text(o, lr->f[C_HOST]);
        fputs("</code>, ", o);
        sb_html_text(o, lr->f[C_CPU]);
        fputs(", BLAS kernels <code>", o);
        sb_html_text(o, lr->f[C_BLAS]);
        fputs("</code>.</p>\n<p class=\"verdicts\">", o);
        int regress = counts[2] + counts[3] + counts[4];
        for (int q = 0; q < 8; q++)
            if (counts[q]) fprintf(o, "<span class=\"v v-%s\">%d %s</span> ", q < 7 ? vnames[q] : "other", counts[q], q < 7 ? vnames[q] : "other");
        fprintf(o, "<strong>%s</strong></p>\n", regress ? "regression" : "no regression");
        if (regress) {
            fputs("<ul>", o);
            for (int k = 0; k < n; k++)
                if (rows[k].inv == last && (!strcmp(rows[k].f[C_VERDICT], "slower") || !strcmp(rows[k].f[C_VERDICT], "changed") ||
                                            !strcmp(rows[k].f[C_VERDICT], "failed"))) {
                    fprintf(o, "<li><a href=\"#case-%d\"><code>", rows[k].cs);
                    sb_html_text(o, rows[k].f[C_CASE]);
                    fputs("</code></a>: ", o);
                    sb_html_text(o, rows[k].f[C_VERDICT]);
                    fputs("</li>", o);
                }
            fputs("</ul>\n", o);
        }
        if (have_base) {
            char bb[700];
            build_href(S, base.prov.build, -1, bb, sizeof bb);
            fputs("<p>Baseline: build <code>", o);
            sb_html_text(o, base.prov.build);
            fputs("</code>, ", o);
            sb_html_text(o, base.prov.date);
            fputs(", host <code>", o);
            sb_html_text(o, base.prov.host);
            fprintf(o, "</code>, %d repeats; drawn as the dashed line in each case's plot.</p>\n", base.prov.repeat);
            (void)bb;
        }
        fputs("</section>\n", o);
    }
    /* the invocations */
    fputs("<h2>Runs</h2>\n<div class=\"tablewrap\"><table class=\"sb-table\" id=\"invocations\"><thead><tr><th class=\"r\">#</th>"
          "<th>date (UTC)</th><th>build</th><th>host</th><th>CPU</th><th>BLAS</th><th class=\"r\">cases</th><th>verdicts</th>"
          "</tr></thead><tbody>\n", o);
    for (int iv = ninv - 1; iv >= 0; iv--) {
        const hrow *r0 = NULL;
        int nc = 0, vc[8] = { 0 };
        for (int k = 0; k < n; k++)
            if (rows[k].inv == iv) {
                if (!r0) r0 = &rows[k];
                nc++;
                int v = 7;
                for (int q = 0; q < 7; q++) if (!strcmp(rows[k].f[C_VERDICT], vnames[q])) v = q;
                vc[v]++;
            }
        if (!r0) continue;
        char bh[700];
        build_href(S, r0->f[C_BUILD], iv, bh, sizeof bh);
        fprintf(o, "<tr id=\"run-%d\"><td class=\"r\" data-v=\"%d\">%d</td><td>", iv, iv, iv + 1);
        sb_html_text(o, r0->f[C_DATE]);
        fputs("</td><td><a href=\"", o);
        sb_html_attr(o, bh);
        fputs("\"><code>", o);
        sb_html_text(o, r0->f[C_BUILD]);
        fputs("</code></a></td><td>", o);
        sb_html_text(o, r0->f[C_HOST]);
        fputs("</td><td>", o);
        sb_html_text(o, r0->f[C_CPU]);
        fputs("</td><td>", o);
        sb_html_text(o, r0->f[C_BLAS]);
        fprintf(o, "</td><td class=\"r\" data-v=\"%d\">%d</td><td>", nc, nc);
        for (int q = 0; q < 8; q++) if (vc[q]) fprintf(o, "<span class=\"v v-%s\">%d %s</span> ", q < 7 ? vnames[q] : "other", vc[q], q < 7 ? vnames[q] : "other");
        fputs("</td></tr>\n", o);
    }
    fputs("</tbody></table></div>\n", o);
    /* the cases */
    fputs("<h2>Cases</h2>\n<p><input class=\"sb-filter\" data-table=\"cases\" placeholder=\"filter: scene, method, solver, verdict…\"> "
          "<span class=\"count\" data-count-for=\"cases\"></span></p>\n<div class=\"tablewrap\"><table class=\"sb-table\" "
          "id=\"cases\"><thead><tr><th>case</th><th>last verdict</th><th class=\"r\">normalized now</th>"
          "<th class=\"r\">baseline</th><th class=\"r\">ratio</th><th class=\"r\">iterations</th><th class=\"r\">assembly WU</th>"
          "</tr></thead><tbody>\n", o);
    for (int c = 0; c < ncase; c++) {
        const hrow *r = NULL;
        for (int k = 0; k < n; k++) if (rows[k].cs == c) r = &rows[k];
        if (!r) continue;
        double now = num(r->f[C_NMED]);
        fprintf(o, "<tr><td><a href=\"#case-%d\"><code>", c);
        sb_html_text(o, cases[c]);
        fputs("</code></a></td><td><span class=\"v v-", o);
        sb_html_attr(o, r->f[C_VERDICT]);
        fputs("\">", o);
        sb_html_text(o, r->f[C_VERDICT]);
        fputs("</span>", o);
        if (r->inv != last) fputs(" (not in the last run)", o);
        fputs("</td>", o);
        double vals[5] = { now, bmed[c], now / bmed[c], num(r->f[C_ITER]), num(r->f[C_WU]) };
        const char *fm[5] = { "%.3f", "%.3f", "%.3f", "%.0f", "%.6g" };
        for (int q = 0; q < 5; q++) {
            if (isfinite(vals[q])) { fprintf(o, "<td class=\"r\" data-v=\"%.17g\">", vals[q]); fprintf(o, fm[q], vals[q]); fputs("</td>", o); }
            else fputs("<td class=\"r\" data-v=\"\">—</td>", o);
        }
        fputs("</tr>\n", o);
    }
    fputs("</tbody></table></div>\n", o);
    fputs("<h2>History per case</h2>\n<p>Normalized CPU time (median of the repeats; the bar spans min to max) per "
          "invocation, coloured by verdict (grey same, green faster, red slower, purple changed, black failed, blue new); "
          "the dashed line is the baseline's median.  Hover a point for its build, date, verdict and counts; click it for the "
          "build.  Wheel: zoom.</p>\n", o);
    for (int c = 0; c < ncase; c++) {
        fprintf(o, "<h3 id=\"case-%d\"><code>", c);
        sb_html_text(o, cases[c]);
        fprintf(o, "</code></h3>\n<div class=\"sb-plot\" data-plot=\"hist\" data-case=\"%d\" data-expect-series=\"1\"></div>\n", c);
    }
    sb_page_data_open(&p);
    fputs("{\"runs\":[", o);
    for (int iv = 0; iv < ninv; iv++) {
        const hrow *r0 = NULL;
        for (int k = 0; k < n && !r0; k++) if (rows[k].inv == iv) r0 = &rows[k];
        char bh[700];
        build_href(S, r0 ? r0->f[C_BUILD] : "", iv, bh, sizeof bh);
        fprintf(o, "%s{\"date\":", iv ? "," : "");
        sb_json_str(o, inv_date[iv]);
        fputs(",\"build\":", o);
        sb_json_str(o, r0 ? r0->f[C_BUILD] : "");
        fputs(",\"href\":", o);
        sb_json_str(o, sb_url_ok(bh) ? bh : "#");
        fputc('}', o);
    }
    fputs("],\"cases\":[", o);
    for (int c = 0; c < ncase; c++) {
        fprintf(o, "%s{\"id\":", c ? ",\n" : "");
        sb_json_str(o, cases[c]);
        fputs(",\"base\":", o);
        sb_json_num(o, bmed[c]);
        fputs(",\"pts\":[", o);
        int m = 0;
        for (int k = 0; k < n; k++) {
            if (rows[k].cs != c) continue;
            const hrow *r = &rows[k];
            fprintf(o, "%s{\"run\":%d,\"verdict\":", m++ ? "," : "", r->inv);
            sb_json_str(o, r->f[C_VERDICT]);
            fputs(",\"med\":", o), sb_json_num(o, num(r->f[C_NMED]));
            fputs(",\"min\":", o), sb_json_num(o, map[C_NMIN] >= 0 ? num(r->f[C_NMIN]) : NAN);
            fputs(",\"max\":", o), sb_json_num(o, map[C_NMAX] >= 0 ? num(r->f[C_NMAX]) : NAN);
            fputs(",\"cpu\":", o), sb_json_num(o, map[C_CPUMED] >= 0 ? num(r->f[C_CPUMED]) : NAN);
            fputs(",\"iterations\":", o), sb_json_num(o, map[C_ITER] >= 0 ? num(r->f[C_ITER]) : NAN);
            fputs(",\"wu\":", o), sb_json_num(o, map[C_WU] >= 0 ? num(r->f[C_WU]) : NAN);
            fputc('}', o);
        }
        fputs("]}", o);
    }
    fputs("]}", o);
    sb_page_data_close(&p);
    sb_page_close(S, &p);
    snprintf(e->href, sizeof e->href, "%s", rel);
    snprintf(e->title, sizeof e->title, "nightly history: %d runs, %d cases", ninv, ncase);
    snprintf(e->date, sizeof e->date, "%s", ninv ? inv_date[last] : "—");
    snprintf(e->provenance, sizeof e->provenance, "%s%s%s; last build %s", history, have_base ? ", baseline " : "",
             have_base ? baseline : "", lr ? lr->f[C_BUILD] : "—");
    free(rows), free(inv_date), free(cases), free(bmed);
    sb_regress_set_free(&base);
    return 0;
}
