/* sb_report.c — tables of run records: Markdown (sb_report_md.c: a header,
 * one row per file: scene, method, solver, dofs, levels, steps, iterations,
 * assembly and QP work units (RMTR paper Eq. 7.3), seconds, error, status,
 * the columns' definitions and the time per event) or CSV with the same
 * columns plus more (per-event seconds, machine, file).  Generated from the
 * HDF5 files only, never by re-running.  The plot is in sb_report_plot.c. */
#include "sb_record_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* RFC 4180 field: quoted when it holds a comma, quote or line break. */
static void csv_field(FILE *out, const char *s, int first)
{
    if (!first) fputc(',', out);
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, out);
        return;
    }
    fputc('"', out);
    for (; *s; s++) {
        if (*s == '"') fputc('"', out);
        fputc(*s, out);
    }
    fputc('"', out);
}

void sb_report_status_text(const sb_record_summary *s, char *buf, size_t len)
{
    if (s->status == SB_STATUS_UNFINISHED) {   /* a checkpoint of a run still going (or killed) */
        snprintf(buf, len, "unfinished (%s)", s->reason_name);
        return;
    }
    const char *word = s->status == 0 ? "converged" : s->status == 1 ? "not converged"
                     : s->status < 0 ? "failed" : "outcome";
    if (s->status > 1) snprintf(buf, len, "%s %d (%s)", word, s->status, s->reason_name);
    else snprintf(buf, len, "%s (%s)", word, s->reason_name);
}

/* The run's error figure: RMS field error, or max probe relative error,
 * whichever the run has (error kind "field" / "probes"); NaN when none. */
double sb_report_error_value(const sb_record_summary *s, const char **label)
{
    *label = "";
    if (!s->has_error) return NAN;
    if (strcmp(s->error_kind, "probes") == 0 || !isfinite(s->error_rms)) {
        *label = "probe";
        return s->error_probe;
    }
    *label = "rms";
    return s->error_rms;
}

static void csv_header(FILE *out)
{
    static const char *const cols[] = {
        "scene", "method", "solver", "dofs", "levels", "steps", "iterations", "work_assembly",
        "work_qp", "seconds", "error", "status", "status_code", "reason", "error_kind",
        "error_rms", "error_max", "error_probe", "steps_planned",
    };
    for (size_t i = 0; i < sizeof cols / sizeof *cols; i++) csv_field(out, cols[i], i == 0);
    for (int e = 0; e < SB_EV_COUNT; e++) fprintf(out, ",seconds_%s", sb_event_name((sb_event)e));
    fputs(",build_id,cpu_model,n_cores,blas_core,started,file,resumes,resume_steps,resume_point,res,parameters\n", out);
}

/* Numbers in CSV: %.9g; non-finite values as an empty field. */
static void csv_num(FILE *out, double v)
{
    if (isfinite(v)) fprintf(out, ",%.9g", v);
    else fputc(',', out);
}

static void csv_row(FILE *out, const sb_record_summary *s, const char *file)
{
    char buf[128];
    const char *label;
    csv_field(out, s->scene, 1);
    csv_field(out, s->method, 0);
    csv_field(out, s->solver, 0);
    fprintf(out, ",%ld,%d,%d,%d", s->dofs, s->levels, s->steps, s->iterations);
    csv_num(out, s->work_assembly);
    csv_num(out, s->work_qp);
    csv_num(out, s->seconds);
    csv_num(out, sb_report_error_value(s, &label));
    sb_report_status_text(s, buf, sizeof buf);
    csv_field(out, buf, 0);
    fprintf(out, ",%d", s->status);
    csv_field(out, s->reason_name, 0);
    csv_field(out, s->has_error ? s->error_kind : "none", 0);
    csv_num(out, s->error_rms);
    csv_num(out, s->error_max);
    csv_num(out, s->error_probe);
    fprintf(out, ",%d", s->steps_planned);
    for (int e = 0; e < SB_EV_COUNT; e++) csv_num(out, s->seconds_event[e]);
    csv_field(out, s->build_id, 0);
    csv_field(out, s->cpu_model, 0);
    fprintf(out, ",%d", s->n_cores);
    csv_field(out, s->blas_core, 0);
    csv_field(out, s->started, 0);
    csv_field(out, file, 0);
    fprintf(out, ",%d", s->resumes);
    csv_field(out, s->resume_steps, 0);
    if (s->resume_point >= 0) fprintf(out, ",%d", s->resume_point);
    else fputs(",", out);
    fprintf(out, ",%d", s->res);
    csv_field(out, s->overrides, 0);
    fputc('\n', out);
}

int sb_report_opts(int n_files, char **files, const sb_report_options *o, FILE *out,
                   char *err, size_t errlen)
{
    const char *format = o && o->format ? o->format : "md";
    int csv = strcmp(format, "csv") == 0;
    if (!csv && strcmp(format, "md") != 0 && strcmp(format, "markdown") != 0) {
        snprintf(err, errlen, "report: unknown format \"%s\" (use md or csv)", format);
        return SB_ERR_INPUT;
    }
    if (n_files <= 0 || !files || !out) {
        snprintf(err, errlen, "report: no record files given");
        return SB_ERR_INPUT;
    }
    sb_record_summary *sum = calloc((size_t)n_files, sizeof *sum);
    if (!sum) {
        snprintf(err, errlen, "report: out of memory");
        return SB_ERR_NOMEM;
    }
    /* Read every file first: unreadable ones are left out of the table and
     * named in the warning (the first one's reason is kept). */
    int n_ok = 0, n_bad = 0, first_bad_rc = SB_OK;
    char first_bad[1024] = "";
    sb_record_summary *ok = sum;
    char **ok_files = malloc((size_t)n_files * sizeof *ok_files);
    if (!ok_files) {
        free(sum);
        snprintf(err, errlen, "report: out of memory");
        return SB_ERR_NOMEM;
    }
    for (int i = 0; i < n_files; i++) {
        char e[1024];
        int rc = sb_record_read_summary(files[i], &ok[n_ok], e, sizeof e);
        if (rc == SB_OK) {
            ok_files[n_ok++] = files[i];
        } else {
            if (!n_bad++) {
                first_bad_rc = rc;
                snprintf(first_bad, sizeof first_bad, "%s", e);
            }
        }
    }
    int status = SB_OK;
    if (n_ok == 0) {
        snprintf(err, errlen, "report: no readable record (%s)", first_bad);
        status = first_bad_rc;
    } else {
        if (csv) {
            csv_header(out);
            for (int i = 0; i < n_ok; i++) csv_row(out, &ok[i], ok_files[i]);
        } else {
            sb_report_markdown(out, n_ok, ok);
        }
        fflush(out);
        if (n_bad) {
            status |= SB_REPORT_WARN_FILES;
            snprintf(err, errlen, "report: %d of %d files left out; first: %s", n_bad, n_files, first_bad);
        }
        if (o && o->plot_path) {
            const char *prog = o->gnuplot ? o->gnuplot : getenv("SB_GNUPLOT");
            char perr[1024];
            int prc = sb_report_plot(n_ok, ok, o->plot_path, prog && *prog ? prog : "gnuplot", perr, sizeof perr);
            if (prc < 0) {
                status = prc;
                snprintf(err, errlen, "%s", perr);
            } else if (prc > 0) {
                if (status) {
                    size_t used = strlen(err);
                    snprintf(err + used, errlen > used ? errlen - used : 0, "; %s", perr);
                } else {
                    snprintf(err, errlen, "%s", perr);
                }
                status |= prc;
            }
        }
    }
    for (int i = 0; i < n_ok; i++) sb_record_summary_free(&ok[i]);
    free(ok_files);
    free(sum);
    return status;
}

int sb_report(int n_files, char **files, const char *format, FILE *out,
              const char *png_path, char *err, size_t errlen)
{
    sb_report_options o = { format, png_path, NULL };
    return sb_report_opts(n_files, files, &o, out, err, errlen);
}
