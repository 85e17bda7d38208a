/* sb_site_run.c — one record's page: what `shellbench report` prints for
 * one record, as a page: its summary, the convergence history as a plot
 * (log ||g|| per outer iteration, one series per level), the counts and
 * seconds of every event per level, the probes against their expected
 * values, and links to the record and its XDMF sidecar. */
#include "sb_site_int.h"
#include "sb_record.h"
#include "sb_record_io.h"
#include "sb_stats.h"

#include <hdf5.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int sb_site_link(const sb_site *S, const char *rel, const char *target, char *buf, size_t len)
{
    char dir[1400];
    snprintf(dir, sizeof dir, "%s/%s", S->dir, rel);
    char *sl = strrchr(dir, '/');
    if (sl) *sl = 0;
    return sb_path_relative(dir, target, buf, len);
}

static void kv(FILE *f, const char *k, const char *v)
{
    fputs("<tr><th>", f);
    sb_html_text(f, k);
    fputs("</th><td>", f);
    sb_html_text(f, v);
    fputs("</td></tr>\n", f);
}

static void kvg(FILE *f, const char *k, double v, const char *fmt)
{
    char b[64];
    if (isfinite(v)) snprintf(b, sizeof b, fmt, v);
    else snprintf(b, sizeof b, "—");
    kv(f, k, b);
}

/* per-level events and probes straight from the record */
typedef struct extra {
    int levels, nev;
    double *count, *secs;        /* levels x nev */
    char names[SB_EV_COUNT + 8][16];
    int np, nsteps;
    char (*pnames)[64];
    double *expected, *relerr, *traj;
} extra;

static void extra_read(const char *path, extra *x)
{
    memset(x, 0, sizeof *x);
    char err[512];
    sb_h5r r = { path, err, sizeof err, NULL, NULL };
    hid_t f;
    if (sb_h5r_open(&r, &f)) { sb_h5r_close(&r, f); return; }
    hsize_t dims[3];
    void *c = NULL, *s = NULL;
    if (sb_h5r_dset(&r, f, "/stats/events_count", 2, H5T_NATIVE_DOUBLE, sizeof(double), dims, &c) == 0 &&
        sb_h5r_dset(&r, f, "/stats/events_seconds", 2, H5T_NATIVE_DOUBLE, sizeof(double), dims, &s) == 0 &&
        dims[1] <= SB_EV_COUNT + 8) {
        x->levels = (int)dims[0], x->nev = (int)dims[1], x->count = c, x->secs = s;
        c = s = NULL;
        hid_t g = H5Gopen2(f, "/stats", H5P_DEFAULT);
        if (g >= 0 && H5Aexists(g, "event_names") > 0) {
            hid_t a = H5Aopen(g, "event_names", H5P_DEFAULT), t = H5Tcopy(H5T_C_S1);
            H5Tset_size(t, 16);
            H5Tset_strpad(t, H5T_STR_NULLTERM);
            hid_t sp = H5Aget_space(a);
            if (a >= 0 && sp >= 0 && H5Sget_simple_extent_npoints(sp) == x->nev) H5Aread(a, t, x->names);
            if (sp >= 0) H5Sclose(sp);
            H5Tclose(t);
            if (a >= 0) H5Aclose(a);
        }
        if (g >= 0) H5Gclose(g);
        for (int k = 0; k < x->nev; k++) {
            x->names[k][15] = 0;
            if (!x->names[k][0]) snprintf(x->names[k], 16, "event %d", k % 1000);   /* k < SB_EV_COUNT */
        }
    }
    free(c), free(s);
    void *e = NULL, *re = NULL, *tr = NULL;
    if (H5Lexists(f, "/probes", H5P_DEFAULT) > 0 && H5Lexists(f, "/probes/names", H5P_DEFAULT) > 0 &&
        sb_h5r_dset(&r, f, "/probes/expected", 2, H5T_NATIVE_DOUBLE, sizeof(double), dims, &e) == 0 && dims[1] == 3) {
        int np = (int)dims[0];
        if (sb_h5r_dset(&r, f, "/probes/rel_error", 1, H5T_NATIVE_DOUBLE, sizeof(double), dims, &re) == 0 && (int)dims[0] == np &&
            sb_h5r_dset(&r, f, "/probes/trajectory", 3, H5T_NATIVE_DOUBLE, sizeof(double), dims, &tr) == 0 &&
            (int)dims[1] == np && dims[2] == 3 && dims[0] >= 1) {
            x->pnames = calloc((size_t)np + 1, sizeof *x->pnames);
            hid_t d = H5Dopen2(f, "/probes/names", H5P_DEFAULT), t = H5Tcopy(H5T_C_S1);
            H5Tset_size(t, 64);
            H5Tset_strpad(t, H5T_STR_NULLTERM);
            hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
            if (x->pnames && sp >= 0 && H5Sget_simple_extent_npoints(sp) == np && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, x->pnames) >= 0) {
                for (int k = 0; k < np; k++) x->pnames[k][63] = 0;
                x->np = np, x->nsteps = (int)dims[0], x->expected = e, x->relerr = re, x->traj = tr;
                e = re = tr = NULL;
            }
            if (sp >= 0) H5Sclose(sp);
            H5Tclose(t);
            if (d >= 0) H5Dclose(d);
        }
    }
    free(e), free(re), free(tr);
    if (!x->np) free(x->pnames), x->pnames = NULL;
    sb_h5r_close(&r, f);
}

static void extra_free(extra *x)
{
    free(x->count), free(x->secs), free(x->pnames), free(x->expected), free(x->relerr), free(x->traj);
}

int sb_site_run(sb_site *S, const char *record, const char *rel, const char *back, const char *label, char *started,
                size_t slen)
{
    sb_record_summary s;
    char err[1024];
    memset(&s, 0, sizeof s);
    if (sb_record_read_summary(record, &s, err, sizeof err)) {
        fprintf(S->err, "shellbench site: warning: %s (no page for it)\n", err);
        sb_record_summary_free(&s);
        return -1;
    }
    if (started) snprintf(started, slen, "%s", s.started);
    extra x;
    extra_read(record, &x);
    sb_page p;
    char title[600], h[1400], b[64];
    snprintf(title, sizeof title, "run %s", label);
    if (sb_page_open(S, &p, rel, title, 1)) {
        sb_record_summary_free(&s);
        extra_free(&x);
        return -1;
    }
    FILE *f = p.f;
    sb_page_href(&p, back, h, sizeof h);
    fputs("<p class=\"crumbs\"><a href=\"", f);
    sb_html_attr(f, h);
    fputs("\">back to the scene</a></p>\n<h1>Run: ", f);
    sb_html_text(f, label);
    fputs("</h1>\n", f);
    /* links to the files */
    char link[PATH_MAX + 64], xd[1300];
    fputs("<p>Record: ", f);
    if (sb_site_link(S, rel, record, link, sizeof link) == 0) {
        fputs("<a href=\"", f);
        sb_html_attr(f, link);
        fputs("\"><code>", f);
        sb_html_text(f, record);
        fputs("</code></a>", f);
    } else {
        fputs("<code>", f);
        sb_html_text(f, record);
        fputs("</code>", f);
    }
    struct stat st;
    if (sb_record_xdmf_path(record, xd, sizeof xd) == 0 && stat(xd, &st) == 0 && sb_site_link(S, rel, xd, link, sizeof link) == 0) {
        fputs(", XDMF sidecar for ParaView: <a href=\"", f);
        sb_html_attr(f, link);
        fputs("\"><code>", f);
        sb_html_text(f, xd);
        fputs("</code></a>", f);
    }
    fputs(" (links relative to the repository the site was made in).</p>\n", f);
    /* summary */
    fputs("<h2>Summary</h2>\n<table class=\"kv\">\n", f);
    kv(f, "scene", s.scene);
    kv(f, "method", s.method);
    kv(f, "solver", s.solver);
    snprintf(b, sizeof b, "%d%s", s.res, s.res ? "" : " (not recorded)");
    kv(f, "resolution", b);
    snprintf(b, sizeof b, "%d", s.levels), kv(f, "levels", b);
    snprintf(b, sizeof b, "%ld", s.dofs), kv(f, "dofs (finest level)", b);
    snprintf(b, sizeof b, "%d of %d", s.steps, s.steps_planned), kv(f, "steps", b);
    snprintf(b, sizeof b, "%d", s.iterations), kv(f, "outer iterations", b);
    kv(f, "status", sb_record_status_name(s.status));
    kv(f, "stop reason (last step)", s.reason_name);
    kvg(f, "seconds (wall, total)", s.seconds, "%.4g");
    kvg(f, "work units (assembly)", s.work_assembly, "%.6g");
    kvg(f, "work units (quadrature points)", s.work_qp, "%.6g");
    if (s.has_error) {
        kv(f, "error measured against", s.error_kind);
        kvg(f, "probe error", s.error_probe, "%.4g");
        kvg(f, "field error, RMS / diameter", s.error_rms, "%.4g");
        kvg(f, "field error, max / diameter", s.error_max, "%.4g");
    }
    kvg(f, "energy of the final state (J)", s.energy_final, "%.8g");
    kv(f, "validation of expected probe values", s.validation[0] ? s.validation : "not recorded");
    kv(f, "parameters given (--set)", s.overrides[0] ? s.overrides : "none");
    kv(f, "build", s.build_id);
    kv(f, "CPU", s.cpu_model);
    snprintf(b, sizeof b, "%d", s.n_cores), kv(f, "cores", b);
    kv(f, "BLAS kernels", s.blas_core);
    kv(f, "started (UTC)", s.started);
    if (s.resumes) {
        snprintf(b, sizeof b, "%d", s.resumes);
        kv(f, "resumed", b);
    }
    fputs("</table>\n", f);
    /* convergence */
    int nlev = 0, lev_seen[64] = { 0 };
    for (int k = 0; k < s.n_hist; k++)
        if (s.hist_level[k] >= 0 && s.hist_level[k] < 64 && isfinite(s.hist_gnorm[k]) && s.hist_gnorm[k] > 0 && !lev_seen[s.hist_level[k]]++) nlev++;
    fputs("<h2>Convergence history</h2>\n<p>‖g‖ of every recorded iteration against its index over all steps, log "
          "scale, one series per level (level 0 the coarsest).  Wheel: zoom; hover: step, iteration, level.</p>\n", f);
    fprintf(f, "<div class=\"sb-plot\" data-plot=\"conv\" data-expect-series=\"%d\"></div>\n", nlev);
    /* per-level events */
    if (x.levels > 0) {
        fputs("<h2>Events per level: counts and seconds</h2>\n<div class=\"tablewrap\"><table class=\"sb-table\" id=\"events\">"
              "<thead><tr><th>event</th>", f);
        for (int l = 0; l < x.levels; l++) fprintf(f, "<th class=\"r\">level %d count</th><th class=\"r\">level %d s</th>", l, l);
        fputs("</tr></thead><tbody>\n", f);
        for (int e = 0; e < x.nev; e++) {
            int any = 0;
            for (int l = 0; l < x.levels; l++) any |= x.count[l * x.nev + e] != 0;
            if (!any) continue;
            fputs("<tr><td>", f);
            sb_html_text(f, x.names[e]);
            fputs("</td>", f);
            for (int l = 0; l < x.levels; l++)
                fprintf(f, "<td class=\"r\" data-v=\"%.17g\">%.0f</td><td class=\"r\" data-v=\"%.17g\">%.3g</td>", x.count[l * x.nev + e],
                        x.count[l * x.nev + e], x.secs[l * x.nev + e], x.secs[l * x.nev + e]);
            fputs("</tr>\n", f);
        }
        fputs("</tbody></table></div>\n", f);
    }
    /* probes */
    if (x.np > 0) {
        fputs("<h2>Probes</h2>\n<div class=\"tablewrap\"><table class=\"sb-table\" id=\"probes\"><thead><tr><th>probe</th>"
              "<th class=\"r\">displacement x</th><th class=\"r\">y</th><th class=\"r\">z</th><th class=\"r\">expected x</th>"
              "<th class=\"r\">y</th><th class=\"r\">z</th><th class=\"r\">relative error</th></tr></thead><tbody>\n", f);
        int last = x.nsteps - 1;
        for (int k = 0; k < x.np; k++) {
            fputs("<tr><td>", f);
            sb_html_text(f, x.pnames[k]);
            fputs("</td>", f);
            for (int c = 0; c < 3; c++) {
                double u = x.traj[(last * x.np + k) * 3 + c] - x.traj[k * 3 + c];
                fprintf(f, "<td class=\"r\">%.6g</td>", u);
            }
            for (int c = 0; c < 3; c++) {
                double v = x.expected[k * 3 + c];
                if (isfinite(v)) fprintf(f, "<td class=\"r\">%.6g</td>", v);
                else fputs("<td class=\"r\">—</td>", f);
            }
            if (isfinite(x.relerr[k])) fprintf(f, "<td class=\"r\">%.3g</td>", x.relerr[k]);
            else fputs("<td class=\"r\">—</td>", f);
            fputs("</tr>\n", f);
        }
        fputs("</tbody></table></div>\n<p>Displacement of the final step from the reference configuration (m); "
              "expected values from the scene (— : none).</p>\n", f);
    }
    /* data: the history */
    sb_page_data_open(&p);
    fputs("{\"hist\":[", f);
    int n = 0;
    for (int k = 0; k < s.n_hist; k++) {
        if (!isfinite(s.hist_gnorm[k]) || s.hist_gnorm[k] <= 0) continue;
        fprintf(f, "%s[%d,%.4g,%d,%d,%d]", n++ ? "," : "", k, s.hist_gnorm[k], s.hist_level[k], s.hist_step[k],
                s.hist_iter ? s.hist_iter[k] : 0);
    }
    fputs("]}", f);
    sb_page_data_close(&p);
    int rc = sb_page_close(S, &p);
    sb_record_summary_free(&s);
    extra_free(&x);
    return rc;
}
