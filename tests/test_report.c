/* test_report.c — report tables (Markdown, CSV) and the gnuplot plot, made
 * from run records written by sb_record_write. */
#include "sb_record.h"
#include "sb_test.h"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A small run: `iters` iterations with ||g|| = 10^-i on the finest level,
 * 2 levels, one step. */
typedef struct mini {
    sb_run run;
    sb_stats stats;
    double st[8], ref[12], pos[12];
    int tris[6];
} mini;

static void mini_make(mini *m, const char *scene, const char *method, const char *solver,
                      int iters, const char *error_kind, int status, int reason)
{
    memset(m, 0, sizeof *m);
    sb_run *r = &m->run;
    sb_run_init(r);
    snprintf(r->scene_name, sizeof r->scene_name, "%s", scene);
    snprintf(r->method, sizeof r->method, "%s", method);
    snprintf(r->solver, sizeof r->solver, "%s", solver);
    r->scene_json = "{}";
    r->levels = 2;
    r->n_dofs = 300 + iters;
    r->status = status;
    r->reason = reason;
    r->steps_planned = r->steps_done = 1;
    sb_stats_init(&m->stats);
    m->stats.n_levels = 2;
    m->stats.work_assembly = 12.5;
    m->stats.work_qp = 4.25;
    m->stats.seconds_total = 0.5 + iters;
    m->stats.ev[1][SB_EV_FACTORIZE].count = iters;
    m->stats.ev[1][SB_EV_FACTORIZE].seconds = 0.125;
    for (int i = 0; i < iters; i++) {
        sb_iter_record it = { .step = 1, .iter = i, .level = 1, .gnorm = pow(10.0, -i) };
        sb_stats_push_iter(&m->stats, &it);
        sb_iter_record coarse = { .step = 1, .iter = i, .level = 0, .gnorm = 1e3 };
        sb_stats_push_iter(&m->stats, &coarse);   /* coarse records are not outer iterations */
    }
    r->stats = &m->stats;
    /* two triangles over four samples */
    for (int k = 0; k < 4; k++) {
        m->st[2 * k] = k & 1, m->st[2 * k + 1] = k >> 1;
        m->ref[3 * k] = m->pos[3 * k] = k & 1;
        m->ref[3 * k + 1] = m->pos[3 * k + 1] = k >> 1;
        m->pos[3 * k + 2] = 0.01 * k;
    }
    int t[6] = { 0, 1, 3, 0, 3, 2 };
    memcpy(m->tris, t, sizeof t);
    r->n_samples = 4;
    r->sample_st = m->st;
    r->sample_ref = m->ref;
    r->sample_pos = m->pos;
    r->n_tris = 2;
    r->tris = m->tris;
    snprintf(r->error_kind, sizeof r->error_kind, "%s", error_kind);
    r->has_error = strcmp(error_kind, "none") != 0;
    r->error_rms = strcmp(error_kind, "field") == 0 ? 2.5e-3 : NAN;
    r->error_max = strcmp(error_kind, "field") == 0 ? 7.5e-3 : NAN;
    r->error_probe = strcmp(error_kind, "probes") == 0 ? 0.0425 : NAN;
}

typedef struct setup {
    char dir[64];
    char paths[3][128];
    char *files[4];
} setup;

/* Three records in a fresh temp dir: field error, probe error, none. */
static int setup_make(setup *S)
{
    char dir[sizeof S->dir] = "/tmp/sb_test_report_XXXXXX";   /* mkdtemp(3) template: it replaces the X characters */
    if (!mkdtemp(dir)) return 0;
    memcpy(S->dir, dir, sizeof dir);   /* paths below are built from the local copy (no overlap with S) */
    const char *scenes[3] = { "trampoline", "plate, clamped", "roll|up" };
    const char *kinds[3] = { "field", "probes", "none" };
    int ok = 1;
    for (int i = 0; i < 3; i++) {
        mini m;
        mini_make(&m, scenes[i], i ? "bhem" : "rmtr", i == 2 ? "lsnewton" : "rmtr", 4 + i, kinds[i],
                  i == 2 ? 1 : 0, i == 2 ? SB_REASON_MAX_ITER : SB_REASON_GRAD_TOL);
        snprintf(S->paths[i], sizeof S->paths[i], "%s/run%d.h5", dir, i);
        char err[512];
        ok &= sb_record_write(&m.run, S->paths[i], err, sizeof err) == SB_OK;
        sb_stats_free(&m.stats);
        S->files[i] = S->paths[i];
    }
    S->files[3] = NULL;
    return ok;
}

static void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char p[512];
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        unlink(p);
    }
    closedir(d);
    rmdir(dir);
}

/* Runs the report into a memory buffer. */
static int report_to_string(int n, char **files, const sb_report_options *o, char **text, char *err, size_t errlen)
{
    size_t len = 0;
    *text = NULL;
    FILE *out = open_memstream(text, &len);
    if (!out) return -100;
    int rc = sb_report_opts(n, files, o, out, err, errlen);
    fclose(out);
    return rc;
}

SB_TEST(test_markdown_table)
{
    setup S;
    CHECK(setup_make(&S));
    char *text = NULL, err[1024] = "";
    sb_report_options o = { "md", NULL, NULL };
    CHECK_EQ_INT(report_to_string(3, S.files, &o, &text, err, sizeof err), SB_OK);
    CHECK(text != NULL);
    if (text) {
        /* the report opens with its title and header (test_cli_report.c checks them) */
        CHECK(strncmp(text, "# shellbench report: 3 runs\n", 28) == 0);
        const char *table = strstr(text, "| scene | method | solver | dofs | levels | res | steps | iterations | "
                                         "assembly WU | QP WU | seconds | error | status |\n");
        CHECK(table != NULL);
        /* res: these synthetic records have none (0), shown as a dash */
        CHECK_MSG(strstr(text, "| trampoline | rmtr | rmtr | 304 | 2 | \xE2\x80\x94 | 1 | 4 | 12.5 | 4.25 | 4.500 | "
                               "rms 2.50e-03 | converged (grad_tol) |\n") != NULL, "table:\n%s", text);
        CHECK_MSG(strstr(text, "| plate, clamped | bhem | rmtr | 305 | 2 | \xE2\x80\x94 | 1 | 5 | 12.5 | 4.25 | 5.500 | "
                               "probe 4.25e-02 |") != NULL, "table:\n%s", text);
        CHECK_MSG(strstr(text, "| roll\\|up | bhem | lsnewton | 306 | 2 | \xE2\x80\x94 | 1 | 6 |") != NULL, "table:\n%s", text);
        CHECK(strstr(text, "| \xE2\x80\x94 | not converged (max_iter) |") != NULL);
        int rows = 0;   /* the table: header, rule, one row per record, then a blank line */
        for (const char *p = table; p && *p == '|'; p = strchr(p, '\n'), p = p ? p + 1 : NULL) rows++;
        CHECK_EQ_INT(rows, 5);
    }
    free(text);
    /* the short form writes the same table */
    FILE *out = tmpfile();
    CHECK_EQ_INT(sb_report(1, S.files, "md", out, NULL, err, sizeof err), SB_OK);
    CHECK(ftell(out) > 100);
    fclose(out);
    remove_dir(S.dir);
}

/* Splits one CSV record (RFC 4180); returns the number of fields. */
static int csv_count(const char *line, char fields[][128], int max)
{
    int n = 0;
    const char *p = line;
    for (;;) {
        char buf[128];
        size_t k = 0;
        if (*p == '"') {
            for (p++; *p && !(*p == '"' && p[1] != '"'); p++) {
                if (*p == '"') p++;
                if (k + 1 < sizeof buf) buf[k++] = *p;
            }
            if (*p == '"') p++;
        } else {
            for (; *p && *p != ',' && *p != '\n'; p++) if (k + 1 < sizeof buf) buf[k++] = *p;
        }
        buf[k] = 0;
        if (n < max) memcpy(fields[n], buf, k + 1);
        n++;
        if (*p != ',') break;
        p++;
    }
    return n;
}

SB_TEST(test_csv_table)
{
    setup S;
    CHECK(setup_make(&S));
    char *text = NULL, err[1024] = "";
    sb_report_options o = { "csv", NULL, NULL };
    CHECK_EQ_INT(report_to_string(3, S.files, &o, &text, err, sizeof err), SB_OK);
    int expected_cols = 19 + SB_EV_COUNT + 11;   /* ... build_id, cpu_model, n_cores, blas_core, started, file,
                                                  resumes, resume_steps, resume_point, res, parameters */
    char f[64][128];
    int row = 0;
    for (char *line = text, *nl; line && *line; line = nl + 1, row++) {
        nl = strchr(line, '\n');
        CHECK(nl != NULL);
        if (!nl) break;
        *nl = 0;
        int n = csv_count(line, f, 64);
        CHECK_MSG(n == expected_cols, "row %d has %d columns, expected %d: %s", row, n, expected_cols, line);
        if (row == 0) {
            CHECK(strcmp(f[0], "scene") == 0 && strcmp(f[10], "error") == 0 && strcmp(f[11], "status") == 0);
            CHECK(strcmp(f[19 + SB_EV_FACTORIZE], "seconds_factorize") == 0);
        }
        if (row == 2) {
            CHECK(strcmp(f[0], "plate, clamped") == 0);
            CHECK(strcmp(f[6], "5") == 0);
            CHECK_NEAR(atof(f[10]), 0.0425, 1e-12);
            CHECK(strcmp(f[14], "probes") == 0);
            CHECK_NEAR(atof(f[19 + SB_EV_FACTORIZE]), 0.125, 1e-12);
            CHECK(strcmp(f[expected_cols - 6], S.paths[1]) == 0);
            CHECK(strcmp(f[expected_cols - 5], "0") == 0);   /* resumes: a run never resumed */
            CHECK(f[expected_cols - 3][0] == 0);              /* resume_point: only checkpoints */
            CHECK(strcmp(f[expected_cols - 2], "0") == 0);   /* res: none in these synthetic records */
            CHECK(f[expected_cols - 1][0] == 0);              /* parameters: none set */
        }
        if (row == 3) {
            CHECK(f[10][0] == 0);                 /* no error figure: empty field */
            CHECK(strcmp(f[11], "not converged (max_iter)") == 0);
            CHECK(strcmp(f[12], "1") == 0);
        }
    }
    CHECK_EQ_INT(row, 4);
    free(text);
    o.format = "xml";
    FILE *out = tmpfile();
    CHECK_EQ_INT(sb_report_opts(3, S.files, &o, out, err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "xml") != NULL);
    fclose(out);
    remove_dir(S.dir);
}

/* Unreadable files are left out with a warning; none readable is an error. */
SB_TEST(test_unreadable_in_report)
{
    setup S;
    CHECK(setup_make(&S));
    char missing[160], *text = NULL, err[1024] = "";
    snprintf(missing, sizeof missing, "%s/missing.h5", S.dir);
    char *files[3] = { S.files[0], missing, S.files[2] };
    sb_report_options o = { "md", NULL, NULL };
    CHECK_EQ_INT(report_to_string(3, files, &o, &text, err, sizeof err), SB_REPORT_WARN_FILES);
    CHECK_MSG(strstr(err, missing) != NULL && strstr(err, "1 of 3") != NULL, "message: %s", err);
    CHECK(text && strstr(text, "| trampoline |") && strstr(text, "| roll\\|up |"));
    free(text);
    char *only[1] = { missing };
    CHECK_EQ_INT(report_to_string(1, only, &o, &text, err, sizeof err), SB_ERR_IO);
    CHECK(text == NULL || text[0] == 0);
    free(text);
    remove_dir(S.dir);
}

static int has_gnuplot(void) { return system("command -v gnuplot >/dev/null 2>&1") == 0; }

SB_TEST(test_plot_png_svg)
{
    if (!has_gnuplot()) {
        printf("    (gnuplot not found: plot test skipped)\n");
        CHECK(1);
        return;
    }
    setup S;
    CHECK(setup_make(&S));
    char png[160], svg[160], err[1024] = "", *text = NULL;
    snprintf(png, sizeof png, "%s/conv.png", S.dir);
    snprintf(svg, sizeof svg, "%s/conv.svg", S.dir);
    sb_report_options o = { "md", png, NULL };
    int rc = report_to_string(3, S.files, &o, &text, err, sizeof err);
    CHECK_MSG(rc == SB_OK, "rc %d: %s", rc, err);
    free(text);
    unsigned char magic[8] = { 0 };
    FILE *f = fopen(png, "rb");
    CHECK(f != NULL);
    if (f) {
        CHECK(fread(magic, 1, 8, f) == 8);
        fseek(f, 0, SEEK_END);
        CHECK(ftell(f) > 1000);
        fclose(f);
    }
    static const unsigned char png_magic[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
    CHECK(memcmp(magic, png_magic, 8) == 0);

    o.plot_path = svg;
    rc = report_to_string(3, S.files, &o, &text, err, sizeof err);
    CHECK_MSG(rc == SB_OK, "rc %d: %s", rc, err);
    free(text);
    f = fopen(svg, "r");
    CHECK(f != NULL);
    if (f) {
        char buf[4096] = "";
        size_t n = fread(buf, 1, sizeof buf - 1, f);
        buf[n] = 0;
        fclose(f);
        CHECK(strstr(buf, "<svg") != NULL);
    }
    /* every temp file is gone */
    DIR *d = opendir(S.dir);
    struct dirent *e;
    int tmp = 0;
    while (d && (e = readdir(d))) tmp += strstr(e->d_name, ".tmp.") != NULL;
    if (d) closedir(d);
    CHECK_EQ_INT(tmp, 0);
    remove_dir(S.dir);
}

/* A missing gnuplot is a warning: the table is still written. */
SB_TEST(test_plot_without_gnuplot)
{
    setup S;
    CHECK(setup_make(&S));
    char png[160], err[1024] = "", *text = NULL;
    snprintf(png, sizeof png, "%s/conv.png", S.dir);
    sb_report_options o = { "md", png, "/nonexistent/gnuplot" };
    CHECK_EQ_INT(report_to_string(3, S.files, &o, &text, err, sizeof err), SB_REPORT_WARN_PLOT);
    CHECK_MSG(strstr(err, "not installed") != NULL, "message: %s", err);
    CHECK(text && strstr(text, "| trampoline |") != NULL);
    free(text);
    CHECK(access(png, F_OK) != 0);
    /* a failing gnuplot ("false" exits 1) is reported with its status */
    o.gnuplot = "false";
    CHECK_EQ_INT(report_to_string(3, S.files, &o, &text, err, sizeof err), SB_REPORT_WARN_PLOT);
    CHECK_MSG(strstr(err, "status 1") != NULL, "message: %s", err);
    free(text);
    CHECK(access(png, F_OK) != 0);
    remove_dir(S.dir);
}

static const sb_test_case cases[] = {
    SB_CASE(test_markdown_table),
    SB_CASE(test_csv_table),
    SB_CASE(test_unreadable_in_report),
    SB_CASE(test_plot_png_svg),
    SB_CASE(test_plot_without_gnuplot),
    SB_END,
};

int main(int argc, char **argv) { return sb_test_main(argc, argv, cases); }
