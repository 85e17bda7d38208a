/* sb_site.c — `shellbench site [--out DIR] ...`: the index, the rendered
 * reports, the copied scripts; the study and nightly pages come from
 * sb_site_study.c and sb_site_nightly.c (docs/site.md). */
#include "sb_site_int.h"
#include "sb_common.h"
#include "sb_run.h"
#include "sb_study.h"
#include "sb_sysinfo.h"

#include <errno.h>
#include <fcntl.h>
#include <glob.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define SB_SITE_VEGA_DIR "/usr/share/javascript/vega"
#define MAX_ITEMS 128

const char sb_cli_site_help[] =
    "usage: shellbench site [--out DIR] [--study FILE [--dir RECORDS]]... [--history CSV] [--baseline JSON]\n"
    "                       [--report FILE.md]... [--commit-url PREFIX]\n"
    "A static, self-contained HTML site from records and digests only (docs/site.md): an index; per study\n"
    "the method-selection table (sortable, filterable), performance profiles and per-scene interactive\n"
    "work-precision diagrams; one page per recorded run; the nightly history; the reports rendered from\n"
    "their Markdown.  Open DIR/index.html in a browser (file:// works; nothing is fetched from the network).\n"
    "  --out DIR          the site (default results/site); a symbolic link, FIFO, device or file there is refused\n"
    "  --study FILE       a study file (repeatable); its records are read, nothing is run\n"
    "  --dir RECORDS      the records directory of every --study (as `report --study --dir`)\n"
    "  --history CSV      the nightly history (shellbench regress; results/nightly/history.csv)\n"
    "  --baseline JSON    the baseline drawn in the history (bench/nightly/baseline.json)\n"
    "  --report FILE.md   a Markdown report to render with its pictures (repeatable)\n"
    "  --commit-url URL   link build ids to URL + commit (e.g. https://forge/repo/commit/); default: the run's row\n"
    "Without --study, --history and --report: every study of bench/studies/ whose records exist, the nightly\n"
    "history with its baseline and every results/*.md and results/*/*.md.\n"
    "exit codes: 0 written, 2 an option or path is wrong or a page could not be written (named on stderr)\n";

/* ---- reports --------------------------------------------------------------------- */

typedef struct rep_ctx {
    sb_site *S;
    const char *md_dir;        /* the report's directory (relative to cwd) */
    const char *rel;           /* the page (site-relative) */
    const char *id;            /* its slug: pictures go to reports/ID/ */
    char (*reports)[512];      /* every rendered report (md path), for links between them */
    int n_reports;
} rep_ctx;

static void report_id(const char *md, char *buf, size_t len)
{
    char t[512];
    snprintf(t, sizeof t, "%s", md);
    if (!strncmp(t, "results/", 8)) memmove(t, t + 8, strlen(t + 8) + 1);
    size_t n = strlen(t);
    if (n > 3 && !strcmp(t + n - 3, ".md")) t[n - 3] = 0;
    for (char *p = t; *p; p++) if (*p == '/') *p = '-';
    sb_site_slug(t, buf, len);
}

/* "a/b/../c" -> "a/c"; 0, or -1 when it climbs above its start */
static int normalize(char *p)
{
    char out[1024] = "";
    size_t n = 0;
    const char *s = p;
    while (*s) {
        const char *e = strchr(s, '/');
        size_t l = e ? (size_t)(e - s) : strlen(s);
        if (l == 0 || (l == 1 && s[0] == '.')) {
        } else if (l == 2 && s[0] == '.' && s[1] == '.') {
            if (n == 0) return -1;
            while (n > 0 && out[n - 1] != '/') n--;
            if (n > 0) n--;
            out[n] = 0;
        } else {
            if (n + l + 2 >= sizeof out) return -1;
            if (n) out[n++] = '/';
            memcpy(out + n, s, l), n += l, out[n] = 0;
        }
        s = e ? e + 1 : s + l;
    }
    strcpy(p, out);
    return 0;
}

static int rewrite(void *vctx, const char *target, int is_image, char *buf, size_t len)
{
    rep_ctx *c = vctx;
    if (!sb_url_ok(target)) return 0;
    if (!strncmp(target, "http", 4) || !strncmp(target, "mailto:", 7) || target[0] == '#') {
        snprintf(buf, len, "%s", target);
        return 1;
    }
    if (target[0] == '/') return 0;
    char path[1024], frag[256] = "";
    snprintf(path, sizeof path, "%s/%s", c->md_dir, target);
    char *h = strchr(path, '#');
    if (h) snprintf(frag, sizeof frag, "%s", h), *h = 0;
    if (normalize(path)) return 0;
    struct stat st;
    if (stat(path, &st) || !S_ISREG(st.st_mode)) return 0;
    if (is_image) {
        char slug[512], rel[800];
        sb_site_slug(target, slug, sizeof slug);
        snprintf(rel, sizeof rel, "reports/%s/%s", c->id, slug);
        if (sb_site_copy_file(c->S, path, rel)) return 0;
        snprintf(buf, len, "%s/%s", c->id, slug);
        return 1;
    }
    for (int k = 0; k < c->n_reports; k++) {
        char a[1024];
        snprintf(a, sizeof a, "%s", c->reports[k]);
        if (normalize(a) == 0 && !strcmp(a, path)) {
            char id[512];
            report_id(c->reports[k], id, sizeof id);
            snprintf(buf, len, "%s.html%s", id, frag);
            return 1;
        }
    }
    /* another file of the repository: linked where it is */
    char link[4200];
    if (sb_site_link(c->S, c->rel, path, link, sizeof link)) return 0;
    snprintf(buf, len, "%s%s", link, frag);
    return 1;
}

/* the commit date of a file (git log), else its modification time */
static void file_date(const char *path, char *buf, size_t len)
{
    buf[0] = 0;
    int fd[2];
    if (pipe(fd) == 0) {
        pid_t pid = fork();
        if (pid == 0) {
            dup2(fd[1], 1);
            int nul = open("/dev/null", 0);
            if (nul >= 0) dup2(nul, 2);
            close(fd[0]);
            execlp("git", "git", "log", "-1", "--format=%cI", "--", path, (char *)NULL);
            _exit(127);
        }
        close(fd[1]);
        if (pid > 0) {
            ssize_t n = read(fd[0], buf, len - 1);
            buf[n > 0 ? n : 0] = 0;
            buf[strcspn(buf, "\r\n")] = 0;
            int stt;
            waitpid(pid, &stt, 0);
        }
        close(fd[0]);
    }
    if (buf[0]) return;
    struct stat st;
    if (stat(path, &st) == 0) {
        struct tm tm;
        gmtime_r(&st.st_mtime, &tm);
        strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ (file time)", &tm);
    } else snprintf(buf, len, "—");
}

static int report_page(sb_site *S, const char *md, char (*reports)[512], int n_reports, sb_site_entry *e)
{
    FILE *in = fopen(md, "rb");
    if (!in) {
        fprintf(S->err, "shellbench site: cannot read the report %s: %s\n", md, strerror(errno));
        S->errors++;
        return -1;
    }
    char *text = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n + 65536 > cap) {
            char *t = realloc(text, cap = n + 65536 * 2);
            if (!t) break;
            text = t;
        }
        size_t k = fread(text + n, 1, cap - n, in);
        if (!k) break;
        n += k;
    }
    fclose(in);
    if (!text) return -1;
    text[n] = 0;   /* cap > n: the converter may look one byte past a line */
    char id[512], rel[700], dir[1024], title[300] = "";
    report_id(md, id, sizeof id);
    snprintf(rel, sizeof rel, "reports/%s.html", id);
    snprintf(dir, sizeof dir, "%s", md);
    char *sl = strrchr(dir, '/');
    if (sl) *sl = 0;
    else snprintf(dir, sizeof dir, ".");
    /* the title: the first heading */
    for (size_t i = 0; i < n; i++)
        if (text[i] == '#' && (i == 0 || text[i - 1] == '\n')) {
            size_t a = i;
            while (a < n && text[a] == '#') a++;
            while (a < n && text[a] == ' ') a++;
            size_t b = a;
            while (b < n && text[b] != '\n') b++;
            size_t t = 0;   /* the heading's text without its inline-code and emphasis marks */
            for (size_t q = a; q < b && t + 1 < sizeof title && t < 250; q++)
                if (text[q] != '`' && text[q] != '*') title[t++] = text[q];
            title[t] = 0;
            break;
        }
    if (!title[0]) snprintf(title, sizeof title, "%s", md);
    sb_page p;
    if (sb_page_open(S, &p, rel, title, 0)) {
        free(text);
        return -1;
    }
    char date[80];
    file_date(md, date, sizeof date);
    fputs("<p class=\"crumbs\">Rendered from <code>", p.f);
    sb_html_text(p.f, md);
    fputs("</code> (", p.f);
    sb_html_text(p.f, date);
    fputs(").</p>\n<article class=\"md\">\n", p.f);
    rep_ctx c = { S, dir, rel, id, reports, n_reports };
    sb_md_to_html(p.f, text, n, rewrite, &c);
    fputs("</article>\n", p.f);
    free(text);
    int rc = sb_page_close(S, &p);
    snprintf(e->href, sizeof e->href, "%s", rel);
    snprintf(e->title, sizeof e->title, "%s", title);
    snprintf(e->date, sizeof e->date, "%s", date);
    snprintf(e->provenance, sizeof e->provenance, "%s", md);
    return rc;
}

/* ---- assets -------------------------------------------------------------------------- */

static int copy_assets(sb_site *S)
{
    int rc = 0;
    rc |= sb_site_write_file(S, "static/site.js", sb_site_js, strlen(sb_site_js));
    rc |= sb_site_write_file(S, "static/site.css", sb_site_css, strlen(sb_site_css));
    rc |= sb_site_write_file(S, "static/amd.js", sb_site_amd_js, strlen(sb_site_amd_js));
    for (int k = 0; sb_site_vega_modules[k]; k++) {
        char src[512], rel[256];
        snprintf(src, sizeof src, "%s/vega-%s.min.js", SB_SITE_VEGA_DIR, sb_site_vega_modules[k]);
        snprintf(rel, sizeof rel, "static/vega/vega-%s.min.js", sb_site_vega_modules[k]);
        if (sb_site_copy_file(S, src, rel)) {
            fprintf(S->err, "shellbench site: Vega is missing (%s): install Debian's libjs-vega (bash scripts/ensure_deps.sh)\n", src);
            return -1;
        }
    }
    struct stat st;
    if (stat("/usr/share/doc/libjs-vega/copyright", &st) == 0)
        sb_site_copy_file(S, "/usr/share/doc/libjs-vega/copyright", "static/vega/COPYRIGHT");
    return rc ? -1 : 0;
}

/* ---- the index ---------------------------------------------------------------------- */

static void entries(FILE *f, const char *heading, const sb_site_entry *e, int n, const char *none)
{
    fprintf(f, "<h2>%s</h2>\n", heading);
    if (!n) { fprintf(f, "<p>%s</p>\n", none); return; }
    fputs("<div class=\"tablewrap\"><table class=\"sb-table\"><thead><tr><th>page</th><th>date</th><th>provenance</th></tr></thead><tbody>\n", f);
    for (int k = 0; k < n; k++) {
        fputs("<tr><td><a href=\"", f);
        sb_html_attr(f, e[k].href);
        fputs("\">", f);
        sb_html_text(f, e[k].title);
        fputs("</a></td><td>", f);
        sb_html_text(f, e[k].date);
        fputs("</td><td><code>", f);
        sb_html_text(f, e[k].provenance);
        fputs("</code></td></tr>\n", f);
    }
    fputs("</tbody></table></div>\n", f);
}

static int is_dir_or_absent(const char *path, char *why, size_t len)
{
    struct stat st;
    if (lstat(path, &st) != 0) return errno == ENOENT ? 0 : (snprintf(why, len, "cannot use %s: %s", path, strerror(errno)), -1);
    if (S_ISDIR(st.st_mode)) return 0;
    const char *what = S_ISLNK(st.st_mode) ? "a symbolic link" : S_ISFIFO(st.st_mode) ? "a FIFO" :
                       (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) ? "a device" : S_ISSOCK(st.st_mode) ? "a socket" : "a file";
    snprintf(why, len, "the site directory %s is %s, not a directory: refused (only a new or an existing real directory "
                       "is written; docs/cli.md \"Output safety\")", path, what);
    return -1;
}

int sb_cli_site(int argc, char **argv)
{
    const char *out = "results/site", *history = NULL, *baseline = NULL, *records = NULL;
    const char *studies[MAX_ITEMS];
    char (*reports)[512] = calloc(MAX_ITEMS, sizeof *reports);
    int ns = 0, nr = 0, explicit = 0;
    sb_site *S = calloc(1, sizeof *S);
    sb_site_entry *es = calloc(3 * MAX_ITEMS + 2, sizeof *es);
    if (!reports || !S || !es) {
        free(reports), free(S), free(es);
        fprintf(stderr, "shellbench site: out of memory\n");
        return SB_EXIT_INTERNAL;
    }
    int code = 0;
    S->err = stderr;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--out") && v) out = v, i++;
        else if (!strcmp(a, "--study") && v && ns < MAX_ITEMS) studies[ns++] = v, i++, explicit = 1;
        else if (!strcmp(a, "--history") && v) history = v, i++, explicit = 1;
        else if (!strcmp(a, "--dir") && v) records = v, i++;
        else if (!strcmp(a, "--baseline") && v) baseline = v, i++;
        else if (!strcmp(a, "--report") && v && nr < MAX_ITEMS) snprintf(reports[nr++], 512, "%s", v), i++, explicit = 1;
        else if (!strcmp(a, "--commit-url") && v) {
            if (strncmp(v, "https://", 8) && strncmp(v, "http://", 7)) {
                fprintf(stderr, "shellbench site: --commit-url must start with http:// or https://\n");
                code = SB_EXIT_INPUT;
                goto done;
            }
            snprintf(S->commit_url, sizeof S->commit_url, "%s", v), i++;
        } else {
            char e[96];
            fprintf(stderr, "shellbench site: unknown option or missing value: \"%s\" (shellbench help site)\n",
                    sb_escape_copy(a, e, sizeof e));
            code = SB_EXIT_INPUT;
            goto done;
        }
    }
    glob_t g;
    if (!explicit) {
        /* the studies whose records exist, the nightly history, the reports */
        static const char *const pats[] = { "results/*.md", "results/*/*.md" };
        if (glob("bench/studies/*.json", 0, NULL, &g) == 0) {
            for (size_t k = 0; k < g.gl_pathc && ns < MAX_ITEMS; k++) studies[ns++] = strdup(g.gl_pathv[k]);
            globfree(&g);
        }
        struct stat st;
        if (stat("results/nightly/history.csv", &st) == 0) history = "results/nightly/history.csv";
        if (!baseline && stat("bench/nightly/baseline.json", &st) == 0) baseline = "bench/nightly/baseline.json";
        for (int q = 0; q < 2; q++)
            if (glob(pats[q], 0, NULL, &g) == 0) {
                for (size_t k = 0; k < g.gl_pathc && nr < MAX_ITEMS; k++) snprintf(reports[nr++], 512, "%s", g.gl_pathv[k]);
                globfree(&g);
            }
    }
    char why[1400];
    if (is_dir_or_absent(out, why, sizeof why)) {
        fprintf(stderr, "shellbench site: %s\n", why);
        code = SB_EXIT_INPUT;
        goto done;
    }
    if (sb_mkdir_p(out) || is_dir_or_absent(out, why, sizeof why)) {
        fprintf(stderr, "shellbench site: cannot make the directory %s: %s\n", out, strerror(errno));
        code = SB_EXIT_INPUT;
        goto done;
    }
    snprintf(S->dir, sizeof S->dir, "%s", out);
    sb_sysinfo_build_id(S->build, sizeof S->build);
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(S->generated, sizeof S->generated, "%Y-%m-%dT%H:%M:%SZ", &tm);
    if (copy_assets(S)) {
        code = SB_EXIT_INPUT;
        goto done;
    }
    sb_site_entry *est = es, *erp = es + MAX_ITEMS, *eng = es + 2 * MAX_ITEMS;
    int nst = 0, nrp = 0, nng = 0;
    for (int k = 0; k < ns; k++) {
        if (!explicit) {   /* default: only studies whose records directory exists */
            sb_study *st = calloc(1, sizeof *st);
            char err[1024];
            struct stat sst;
            int ok = st && sb_study_load(studies[k], NULL, st, err, sizeof err) == 0 && stat(st->records, &sst) == 0 &&
                     S_ISDIR(sst.st_mode) && st->kind == SB_STUDY_ACCURACY;
            if (st) sb_study_free(st);
            free(st);
            if (!ok) continue;
        }
        int rc = sb_site_study(S, studies[k], records, &est[nst]);
        if (rc == 0) nst++;
    }
    for (int k = 0; k < nr; k++)
        if (report_page(S, reports[k], reports, nr, &erp[nrp]) == 0) nrp++;
    if (history && sb_site_nightly(S, history, baseline, &eng[0]) == 0) nng++;
    sb_page p;
    if (sb_page_open(S, &p, "index.html", "shellbench results", 0) == 0) {
        FILE *f = p.f;
        char cpu[128];
        sb_sysinfo_cpu_model(cpu, sizeof cpu);
        fputs("<h1>shellbench results</h1>\n<p>Build <code>", f);
        sb_html_text(f, S->build);
        fputs("</code>; site generated ", f);
        sb_html_text(f, S->generated);
        fputs(" on ", f);
        sb_html_text(f, cpu);
        fputs(" from records and digests only (nothing was run).  Every plot is drawn in the page by Vega 5 from the "
              "data in the page; the site needs no network.</p>\n", f);
        entries(f, "Studies", est, nst, "No study with records.");
        entries(f, "Nightly history", eng, nng, "No nightly history.");
        entries(f, "Reports", erp, nrp, "No reports.");
        sb_page_close(S, &p);
    }
    if (S->errors) code = SB_EXIT_INPUT;
    fprintf(stderr, "shellbench site: %s/index.html: %d stud%s, %d report%s, %s%s\n", out, nst, nst == 1 ? "y" : "ies", nrp,
            nrp == 1 ? "" : "s", nng ? "the nightly history" : "no nightly history",
            S->errors ? " (some pages were not written: above)" : "");
    if (!explicit)
        for (int k = 0; k < ns; k++) free((char *)studies[k]);
done:
    free(reports), free(S), free(es);
    return code;
}
