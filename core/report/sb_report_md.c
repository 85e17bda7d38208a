/* sb_report_md.c — the Markdown report of run records (sb_record_io.h):
 * a header (title, when and by which build it was made, when the runs
 * started, machine, builds, BLAS kernel sets, the parameters the runs were
 * given), the table (one row per record; runs that did not finish all their
 * steps marked), the columns' definitions and the time of each run per
 * event.  Everything comes from the records, never from re-running. */
#include "sb_record_io.h"
#include "sb_sysinfo.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* Markdown cell text: control characters escaped, '|' would end the cell. */
static void md_text(FILE *out, const char *s)
{
    char buf[1100];
    sb_escape_copy(s, buf, sizeof buf);
    for (const char *p = buf; *p; p++) {
        if (*p == '|') fputs("\\|", out);
        else fputc(*p, out);
    }
}

static void md_cell(FILE *out, const char *s)
{
    fputs("| ", out);
    md_text(out, s);
    fputc(' ', out);
}

/* The distinct values of a string field over the runs, "a; b" (at most 6). */
static void distinct(int n, const sb_record_summary *s, size_t off, char *buf, size_t len)
{
    size_t used = 0;
    int shown = 0;
    buf[0] = 0;
    for (int i = 0; i < n; i++) {
        const char *v = (const char *)&s[i] + off;
        int seen = 0;
        for (int j = 0; j < i && !seen; j++) seen = strcmp(v, (const char *)&s[j] + off) == 0;
        if (seen) continue;
        if (shown++ == 6) {
            snprintf(buf + used, len - used, "; ...");
            return;
        }
        int w = snprintf(buf + used, len - used, "%s%s", used ? "; " : "", v[0] ? v : "unknown");
        if (w < 0 || used + (size_t)w >= len) return;
        used += (size_t)w;
    }
}

static void run_label(const sb_record_summary *s, char *buf, size_t len)
{
    snprintf(buf, len, "%s/%s/%s r%d l%d", s->scene, s->method, s->solver, s->res, s->levels);
}

static void header(FILE *out, int n, const sb_record_summary *s)
{
    char buf[2048], now[32], id[64], first[32] = "", last[32] = "";
    sb_sysinfo_now_iso(now, sizeof now);
    sb_sysinfo_build_id(id, sizeof id);
    for (int i = 0; i < n; i++) {
        if (!first[0] || strcmp(s[i].started, first) < 0) snprintf(first, sizeof first, "%s", s[i].started);
        if (strcmp(s[i].started, last) > 0) snprintf(last, sizeof last, "%s", s[i].started);
    }
    fprintf(out, "# shellbench report: %d run%s\n\n| | |\n|---|---|\n", n, n == 1 ? "" : "s");
    fprintf(out, "| generated | %s by shellbench %s, from the records alone |\n", now, id);
    fprintf(out, "| runs started | %s%s%s |\n", first, strcmp(first, last) ? " to " : "", strcmp(first, last) ? last : "");
    size_t used = 0;
    buf[0] = 0;
    for (int i = 0; i < n && used + 160 < sizeof buf; i++) {   /* machines: CPU model and cores */
        char m[200];
        snprintf(m, sizeof m, "%s (%d cores)", s[i].cpu_model, s[i].n_cores);
        if (!strstr(buf, m)) used += (size_t)snprintf(buf + used, sizeof buf - used, "%s%s", used ? "; " : "", m);
    }
    fputs("| machine | ", out), md_text(out, buf), fputs(" |\n", out);
    distinct(n, s, offsetof(sb_record_summary, build_id), buf, sizeof buf);
    fputs("| build | ", out), md_text(out, buf), fputs(" |\n", out);
    distinct(n, s, offsetof(sb_record_summary, blas_core), buf, sizeof buf);
    fputs("| BLAS kernels | ", out), md_text(out, buf), fputs(" |\n", out);
    /* the parameters the runs were given, grouped by identical sets */
    int any = 0;
    for (int i = 0; i < n; i++) any |= s[i].overrides[0] != 0;
    if (!any) {
        fputs("| parameters | every run at the defaults of its build |\n", out);
    } else {
        for (int i = 0; i < n; i++) {
            int seen = 0, same = 0;
            for (int j = 0; j < i && !seen; j++) seen = strcmp(s[i].overrides, s[j].overrides) == 0;
            if (seen || !s[i].overrides[0]) continue;
            for (int j = 0; j < n; j++) same += strcmp(s[i].overrides, s[j].overrides) == 0;
            fputs("| parameters set | ", out);
            md_text(out, s[i].overrides);
            if (same == n) fputs(" (every run)", out);
            else {
                fputs(" (", out);
                for (int j = 0, k = 0; j < n; j++)
                    if (!strcmp(s[i].overrides, s[j].overrides)) {
                        run_label(&s[j], buf, sizeof buf);
                        fputs(k++ ? ", " : "", out), md_text(out, buf);
                    }
                fputs(")", out);
            }
            fputs(" |\n", out);
        }
    }
    fputc('\n', out);
}

static int unfinished(const sb_record_summary *s) { return s->steps < s->steps_planned; }

static void table(FILE *out, int n, const sb_record_summary *s)
{
    char buf[128];
    fputs("| scene | method | solver | dofs | levels | res | steps | iterations | assembly WU | QP WU | seconds | error "
          "| status | validation |\n|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|---|---|---|\n", out);
    for (int i = 0; i < n; i++) {
        const sb_record_summary *r = &s[i];
        md_cell(out, r->scene);
        md_cell(out, r->method);
        md_cell(out, r->solver);
        snprintf(buf, sizeof buf, "%ld", r->dofs), md_cell(out, buf);
        snprintf(buf, sizeof buf, "%d", r->levels), md_cell(out, buf);
        if (r->res_t > 0) snprintf(buf, sizeof buf, "%dx%d", r->res, r->res_t);   /* --res NxM */
        else snprintf(buf, sizeof buf, "%d", r->res);
        md_cell(out, r->res > 0 ? buf : "\xE2\x80\x94");
        if (unfinished(r)) snprintf(buf, sizeof buf, "%d of %d *", r->steps, r->steps_planned);
        else snprintf(buf, sizeof buf, "%d", r->steps);
        md_cell(out, buf);
        snprintf(buf, sizeof buf, "%d", r->iterations), md_cell(out, buf);
        snprintf(buf, sizeof buf, "%.4g", r->work_assembly), md_cell(out, buf);
        snprintf(buf, sizeof buf, "%.4g", r->work_qp), md_cell(out, buf);
        snprintf(buf, sizeof buf, "%.3f", r->seconds), md_cell(out, buf);
        const char *label;
        double e = sb_report_error_value(r, &label);
        if (isfinite(e)) snprintf(buf, sizeof buf, "%s %.2e", label, e);
        else snprintf(buf, sizeof buf, "\xE2\x80\x94");   /* em dash: no error figure */
        md_cell(out, buf);
        sb_report_status_text(r, buf, sizeof buf);
        md_cell(out, buf);
        /* expected probe values judged, apart from convergence (docs/trust.md) */
        md_cell(out, r->validation[0] ? r->validation : "\xE2\x80\x94");
        fputs("|\n", out);
    }
    int marked = 0;
    for (int i = 0; i < n; i++) marked += unfinished(&s[i]);
    if (marked)
        fprintf(out, "\n\\* %d run%s did not finish all planned steps: stopped at a step that did not converge, by "
                     "--stop-after-steps, or a checkpoint of a run still going or killed (status unfinished).\n",
                marked, marked == 1 ? "" : "s");
}

static void columns(FILE *out)
{
    fputs("\n### Columns\n\n"
          "- **dofs**: degrees of freedom of the finest level; **levels**: levels of the hierarchy; **res**: elements "
          "per side of the finest level.\n"
          "- **steps**: time or load steps completed (of those the scene plans, when fewer).\n"
          "- **iterations**: outer iterations over all steps (trust-region iterations, Newton iterations, or V-cycles "
          "of rmtr).\n"
          "- **assembly WU**: work units of assemblies (RMTR paper Eq. 7.3): one energy + gradient + Hessian "
          "assembly on the finest level is 1 WU, on level l it is n_l / n_L WU (n = dof count).\n"
          "- **QP WU**: work units of trust-region subproblem solves, counted the same way (the paper's Tables 6-7).\n"
          "- **seconds**: wall-clock time of the run (set-up, steps, recording; resumed runs: all processes but the "
          "time lost past the last step boundary).\n"
          "- **error**: rms = RMS distance to the reference run over the sample grid divided by the domain's "
          "diameter; probe = the largest relative error of a probe against its expected value; \xE2\x80\x94 = none.\n"
          "- **status**: converged or not, with the reason of the last step (grad_tol, f_tol, x_tol, roundoff_limit, "
          "single_step: converged; max_iter, stalled, diverged, penalty_violated, strain_bound, ...: not); "
          "unfinished = a checkpoint.\n"
          "- **validation**: the scene's expected probe values against their tolerances (passed, failed; none: "
          "nothing expected or the run stopped early), apart from convergence (docs/trust.md).\n", out);
}

/* seconds per event and run: exclusive ones where the record has them
 * (format 3: they and `other` add up to the total), else inclusive ones
 * (nested events, e.g. qp containing the subproblem's factorizations,
 * overlap) */
static const double *event_seconds(const sb_record_summary *s)
{
    return s->has_self ? s->seconds_self : s->seconds_event;
}

static void times(FILE *out, int n, const sb_record_summary *s)
{
    int show[SB_EV_COUNT], k = 0, any_self = 0, any_old = 0;
    for (int i = 0; i < n; i++) {
        any_self |= s[i].has_self;
        any_old |= !s[i].has_self;
    }
    for (int e = 0; e < SB_EV_COUNT; e++) {
        show[e] = 0;
        for (int i = 0; i < n; i++) show[e] |= event_seconds(&s[i])[e] > 0;
        k += show[e];
    }
    fputs("\n### Time per run (seconds)\n\nWall-clock seconds per event (docs/recorded_figures.md, /stats): ", out);
    if (any_self)
        fputs("exclusive seconds, each event without the events timed inside it (hessian = assemblies, solver = the "
              "step's own work outside every event, setup, samples, error, record = the harness), which with other "
              "(the time no event covers) add up to the total", out);
    if (any_self && any_old) fputs("; for records written before exclusive seconds were kept (marked *) ", out);
    if (any_old)
        fputs("inclusive seconds: hessian = assemblies, qp = subproblem solves including their factorizations and "
              "solves, so the columns overlap and do not add up to the total", out);
    fputs(".\n\n| run | total", out);
    for (int e = 0; e < SB_EV_COUNT; e++) if (show[e]) fprintf(out, " | %s", sb_event_name((sb_event)e));
    if (any_self) fputs(" | other", out);
    fputs(" |\n|---|--:", out);
    for (int e = 0; e < k + any_self; e++) fputs("|--:", out);
    fputs("|\n", out);
    for (int i = 0; i < n; i++) {
        char label[256];
        run_label(&s[i], label, sizeof label);
        md_cell(out, label);
        fprintf(out, "| %.3f%s ", s[i].seconds, any_self && !s[i].has_self ? "*" : "");
        const double *v = event_seconds(&s[i]);
        for (int e = 0; e < SB_EV_COUNT; e++) if (show[e]) fprintf(out, "| %.3f ", v[e]);
        if (any_self) {
            if (s[i].has_self) fprintf(out, "| %.3f ", s[i].seconds_unattributed);
            else fputs("| — ", out);
        }
        fputs("|\n", out);
    }
}

void sb_report_markdown(FILE *out, int n, const sb_record_summary *s)
{
    header(out, n, s);
    table(out, n, s);
    columns(out);
    times(out, n, s);
}
