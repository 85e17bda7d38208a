/* sb_regress_files.c — the nightly regression's committed text files
 * (docs/regression.md "Files"):
 *
 *   baseline (JSON, bench/nightly/baseline.json): the provenance of the
 *   measurement (build, date, host, CPU, BLAS kernel set, suite, repeats,
 *   calibration passes) and per case its deterministic figures and its k
 *   CPU, wall and normalized times.  Written by --update-baseline.
 *
 *   history (CSV, results/nightly/history.csv): one line per case per
 *   invocation, appended; what the history plots are drawn from.
 *
 * Both are written to a temporary file and renamed into place. */
#include "sb_regress.h"
#include "sb_gsl.h"
#include "sb_output.h"

#include <errno.h>
#include <fcntl.h>
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define BASELINE_FORMAT "shellbench-nightly-baseline"
#define BASELINE_VERSION 1

static json_t *reals(const double *x, int n)
{
    json_t *a = json_array();
    for (int i = 0; i < n; i++) json_array_append_new(a, json_real(x[i]));
    return a;
}

static json_t *case_json(const sb_regress_case *c)
{
    json_t *o = json_object();
    json_object_set_new(o, "id", json_string(c->id));
    json_object_set_new(o, "status", json_integer(c->fig.status));
    json_object_set_new(o, "reason", json_string(c->fig.reason));
    for (int k = 0; k < SB_RF_COUNT_INT; k++) json_object_set_new(o, sb_regress_int_name(k), json_integer(c->fig.n[k]));
    for (int k = 0; k < SB_RF_COUNT_EXACT; k++) json_object_set_new(o, sb_regress_exact_name(k), json_real(c->fig.x[k]));
    json_object_set_new(o, "energy_final", c->fig.has_energy ? json_real(c->fig.energy) : json_null());
    json_t *p = json_array();
    for (int i = 0; i < c->fig.n_probes; i++) json_array_append_new(p, reals(c->fig.probe[i], 3));
    json_object_set_new(o, "probes", p);
    json_object_set_new(o, "cpu_seconds", reals(c->cpu, c->n_rep));
    json_object_set_new(o, "wall_seconds", reals(c->wall, c->n_rep));
    json_object_set_new(o, "normalized", reals(c->norm, c->n_rep));
    return o;
}

static int replace_file(const char *path, const char *text, char *err, size_t errlen)
{
    char tmp[1200];
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    int bad = !f || fputs(text, f) < 0;
    if (f && fclose(f)) bad = 1;
    if (bad || rename(tmp, path)) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        unlink(tmp);
        return SB_ERR_IO;
    }
    return SB_OK;
}

int sb_regress_baseline_write(const sb_regress_set *s, const char *path, char *err, size_t errlen)
{
    const sb_regress_prov *p = &s->prov;
    json_t *root = json_object(), *pv = json_object(), *cases = json_array();
    json_object_set_new(root, "format", json_string(BASELINE_FORMAT));
    json_object_set_new(root, "version", json_integer(BASELINE_VERSION));
    json_object_set_new(pv, "build", json_string(p->build));
    json_object_set_new(pv, "date", json_string(p->date));
    json_object_set_new(pv, "host", json_string(p->host));
    json_object_set_new(pv, "cpu", json_string(p->cpu));
    json_object_set_new(pv, "blas_core", json_string(p->blas_core));
    json_object_set_new(pv, "suite", json_string(p->suite));
    json_object_set_new(pv, "repeat", json_integer(p->repeat));
    json_object_set_new(pv, "calibration_seconds", reals(p->calib, p->n_calib));
    json_object_set_new(pv, "calibration_median", json_real(p->calib_median));
    json_object_set_new(pv, "load_average_max", isfinite(p->load_max) ? json_real(p->load_max) : json_null());
    json_object_set_new(pv, "cores", json_integer(p->cores));
    json_object_set_new(pv, "calibration_version", json_integer(p->calib_version));
    json_object_set_new(root, "provenance", pv);
    for (int k = 0; k < s->n; k++)
        if (s->c[k].ok) json_array_append_new(cases, case_json(&s->c[k]));
    json_object_set_new(root, "cases", cases);
    char *text = json_dumps(root, JSON_INDENT(1) | JSON_PRESERVE_ORDER);
    json_decref(root);
    if (!text) {
        snprintf(err, errlen, "cannot write %s: out of memory", path);
        return SB_ERR_NOMEM;
    }
    size_t n = strlen(text);
    char *t2 = realloc(text, n + 2);
    if (t2) text = t2, text[n] = '\n', text[n + 1] = 0;
    int rc = replace_file(path, text, err, errlen);
    free(text);
    return rc;
}

/* ---- reading: every problem names the file and the JSON member ---------- */

typedef struct rd {
    const char *path;
    char *err;
    size_t errlen;
    int bad;
} rd;

static void fail(rd *r, const char *where, const char *what)
{
    if (!r->bad) snprintf(r->err, r->errlen, "%s: at %s: %s", r->path, where, what);
    r->bad = 1;
}

static double get_real(rd *r, json_t *o, const char *key, const char *where)
{
    json_t *v = json_object_get(o, key);
    char w[400];
    snprintf(w, sizeof w, "%s/%s", where, key);
    if (!json_is_number(v)) { fail(r, w, "missing or not a number"); return NAN; }
    return json_number_value(v);
}

static long get_int(rd *r, json_t *o, const char *key, const char *where)
{
    json_t *v = json_object_get(o, key);
    char w[400];
    snprintf(w, sizeof w, "%s/%s", where, key);
    if (!json_is_integer(v)) { fail(r, w, "missing or not an integer"); return 0; }
    return (long)json_integer_value(v);
}

static void get_str(rd *r, json_t *o, const char *key, const char *where, char *buf, size_t len)
{
    json_t *v = json_object_get(o, key);
    char w[400];
    snprintf(w, sizeof w, "%s/%s", where, key);
    if (!json_is_string(v)) { fail(r, w, "missing or not a string"); buf[0] = 0; return; }
    snprintf(buf, len, "%s", json_string_value(v));
}

static int get_reals(rd *r, json_t *o, const char *key, const char *where, double *x, int max, int positive)
{
    json_t *a = json_object_get(o, key);
    char w[400];
    snprintf(w, sizeof w, "%s/%s", where, key);
    if (!json_is_array(a)) { fail(r, w, "missing or not an array"); return 0; }
    if ((int)json_array_size(a) > max) { fail(r, w, "too many values"); return 0; }
    for (size_t i = 0; i < json_array_size(a); i++) {
        json_t *v = json_array_get(a, i);
        if (!json_is_number(v) || (positive && !(json_number_value(v) > 0))) {
            fail(r, w, positive ? "an entry that is not a positive number" : "an entry that is not a number");
            return 0;
        }
        x[i] = json_number_value(v);
    }
    return (int)json_array_size(a);
}

static void read_case(rd *r, json_t *o, int k, sb_regress_set *s)
{
    char where[64], id[SB_REGRESS_ID_LEN];
    snprintf(where, sizeof where, "/cases/%d", k);
    if (!json_is_object(o)) { fail(r, where, "not an object"); return; }
    get_str(r, o, "id", where, id, sizeof id);
    if (r->bad) return;
    if (sb_regress_set_find(s, id)) { fail(r, where, "a second case with this id"); return; }
    sb_regress_case *c = sb_regress_set_add(s, id);
    if (!c) { fail(r, where, "out of memory"); return; }
    c->ok = 1;
    c->fig.status = (int)get_int(r, o, "status", where);
    get_str(r, o, "reason", where, c->fig.reason, sizeof c->fig.reason);
    for (int i = 0; i < SB_RF_COUNT_INT; i++) c->fig.n[i] = get_int(r, o, sb_regress_int_name(i), where);
    for (int i = 0; i < SB_RF_COUNT_EXACT; i++) c->fig.x[i] = get_real(r, o, sb_regress_exact_name(i), where);
    json_t *e = json_object_get(o, "energy_final");
    if (json_is_number(e)) c->fig.has_energy = 1, c->fig.energy = json_number_value(e);
    else if (!json_is_null(e)) fail(r, where, "energy_final: missing, or neither a number nor null");
    json_t *pr = json_object_get(o, "probes");
    if (!json_is_array(pr) || json_array_size(pr) > SB_REGRESS_MAX_PROBES) fail(r, where, "probes: missing, not an array or too long");
    for (size_t i = 0; !r->bad && i < json_array_size(pr); i++) {
        json_t *v = json_array_get(pr, i);
        for (int d = 0; d < 3; d++) {
            json_t *x = json_is_array(v) && json_array_size(v) == 3 ? json_array_get(v, (size_t)d) : NULL;
            if (!json_is_number(x)) { fail(r, where, "probes: an entry that is not three numbers"); break; }
            c->fig.probe[i][d] = json_number_value(x);
        }
        c->fig.n_probes = (int)i + 1;
    }
    c->n_rep = get_reals(r, o, "cpu_seconds", where, c->cpu, SB_REGRESS_MAX_REPEAT, 1);
    int nw = get_reals(r, o, "wall_seconds", where, c->wall, SB_REGRESS_MAX_REPEAT, 0);
    int nn = get_reals(r, o, "normalized", where, c->norm, SB_REGRESS_MAX_REPEAT, 1);
    if (!r->bad && (nw != c->n_rep || nn != c->n_rep || c->n_rep < 1))
        fail(r, where, "cpu_seconds, wall_seconds and normalized must have the same (non-zero) length");
}

int sb_regress_baseline_read(const char *path, sb_regress_set *s, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    json_error_t je;
    FILE *f = sb_input_open(path, "baseline", err, errlen);
    if (!f) return SB_ERR_INPUT;
    json_t *root = json_loadf(f, 0, &je);
    fclose(f);
    if (!root) {
        snprintf(err, errlen, "%s:%d:%d: %s", path, je.line, je.column, je.text);
        return SB_ERR_INPUT;
    }
    rd r = { path, err, errlen, 0 };
    json_t *fmt = json_object_get(root, "format"), *ver = json_object_get(root, "version");
    if (!json_is_string(fmt) || strcmp(json_string_value(fmt), BASELINE_FORMAT))
        fail(&r, "/format", "not \"" BASELINE_FORMAT "\" (not a nightly baseline)");
    else if (!json_is_integer(ver) || json_integer_value(ver) != BASELINE_VERSION)
        fail(&r, "/version", "not 1 (a baseline of another version of shellbench)");
    json_t *pv = json_object_get(root, "provenance");
    if (!r.bad && !json_is_object(pv)) fail(&r, "/provenance", "missing or not an object");
    if (!r.bad) {
        sb_regress_prov *p = &s->prov;
        get_str(&r, pv, "build", "/provenance", p->build, sizeof p->build);
        get_str(&r, pv, "date", "/provenance", p->date, sizeof p->date);
        get_str(&r, pv, "host", "/provenance", p->host, sizeof p->host);
        get_str(&r, pv, "cpu", "/provenance", p->cpu, sizeof p->cpu);
        get_str(&r, pv, "blas_core", "/provenance", p->blas_core, sizeof p->blas_core);
        get_str(&r, pv, "suite", "/provenance", p->suite, sizeof p->suite);
        p->repeat = (int)get_int(&r, pv, "repeat", "/provenance");
        p->n_calib = get_reals(&r, pv, "calibration_seconds", "/provenance", p->calib, SB_REGRESS_MAX_REPEAT, 1);
        p->calib_median = get_real(&r, pv, "calibration_median", "/provenance");
        /* optional (baselines written before they were kept) */
        json_t *l = json_object_get(pv, "load_average_max"), *c = json_object_get(pv, "cores");
        p->load_max = json_is_number(l) ? json_number_value(l) : NAN;
        p->cores = json_is_integer(c) ? (int)json_integer_value(c) : 0;
        json_t *cv = json_object_get(pv, "calibration_version");
        p->calib_version = json_is_integer(cv) ? (int)json_integer_value(cv) : 1;
    }
    json_t *cases = json_object_get(root, "cases");
    if (!r.bad && !json_is_array(cases)) fail(&r, "/cases", "missing or not an array");
    for (size_t k = 0; !r.bad && k < json_array_size(cases); k++) read_case(&r, json_array_get(cases, k), (int)k, s);
    json_decref(root);
    if (r.bad) {
        sb_regress_set_free(s);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

/* ---- history ------------------------------------------------------------- */

/* a CSV field: quoted, inner quotes doubled */
static void csv_field(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s == '\n' || *s == '\r' ? ' ' : *s, f);
    }
    fputc('"', f);
}

#define HISTORY_HEADER "date,build,host,cpu,blas_core,case,verdict,repeat,cpu_median,cpu_min,normalized_median," \
                       "normalized_min,normalized_max,calibration_median,iterations,work_assembly\n"

int sb_regress_history_append(const sb_regress_set *s, const char *path, char *err, size_t errlen)
{
    struct stat stt;
    int fresh = stat(path, &stt) != 0 || stt.st_size == 0;
    /* appended, never through a symbolic link (O_NOFOLLOW) */
    int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
    FILE *f = fd >= 0 ? fdopen(fd, "a") : NULL;
    if (!f && fd >= 0) close(fd);
    if (!f) {
        snprintf(err, errlen, "cannot append to %s: %s", path, strerror(errno));
        return SB_ERR_IO;
    }
    if (fresh) fputs(HISTORY_HEADER, f);
    const sb_regress_prov *p = &s->prov;
    for (int k = 0; k < s->n; k++) {
        const sb_regress_case *c = &s->c[k];
        double q[3] = { NAN, NAN, NAN }, cm = NAN, cmin = NAN;
        static const double pr[3] = { 0.5, 0.0, 1.0 };
        if (c->n_rep > 0) {
            if (sb_quantiles(c->norm, (size_t)c->n_rep, pr, 3, q)) q[0] = q[1] = q[2] = NAN;
            double cq[2];
            if (!sb_quantiles(c->cpu, (size_t)c->n_rep, pr, 2, cq)) cm = cq[0], cmin = cq[1];
        }
        csv_field(f, p->date), fputc(',', f);
        csv_field(f, p->build), fputc(',', f);
        csv_field(f, p->host), fputc(',', f);
        csv_field(f, p->cpu), fputc(',', f);
        csv_field(f, p->blas_core), fputc(',', f);
        csv_field(f, c->id), fputc(',', f);
        fprintf(f, "%s,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,%.10g\n", sb_verdict_name(c->verdict), c->n_rep, cm, cmin,
                q[0], q[1], q[2], p->calib_median, c->ok ? c->fig.n[SB_RF_ITERATIONS] : -1L,
                c->ok ? c->fig.x[SB_RF_WORK_ASSEMBLY] : NAN);
    }
    int bad = ferror(f);
    if (fclose(f)) bad = 1;
    if (bad) {
        snprintf(err, errlen, "cannot append to %s: %s", path, strerror(errno));
        return SB_ERR_IO;
    }
    return SB_OK;
}
