/* sb_site_html.c — escaping for HTML and for JSON inside a page, the pages'
 * head and foot, and files written into the site by rename after the output
 * checks every other output of the suite has (core/record/sb_output.c). */
#include "sb_site.h"
#include "sb_output.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void esc(FILE *f, const char *s, size_t n)
{
    for (size_t i = 0; i < n && s[i]; i++) {
        unsigned char c = (unsigned char)s[i];
        switch (c) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&#39;", f); break;
        default:
            if (c < 0x20 && c != '\t' && c != '\n') break;
            if (c == 0x7f) break;
            fputc(c, f);
        }
    }
}

void sb_html_text(FILE *f, const char *s) { if (s) esc(f, s, (size_t)-1); }
void sb_html_attr(FILE *f, const char *s) { if (s) esc(f, s, (size_t)-1); }
void sb_html_textn(FILE *f, const char *s, size_t n) { if (s) esc(f, s, n); }

void sb_json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        unsigned c = *p;
        if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
        else if (c < 0x20 || c == '<' || c == '>' || c == '&' || c == 0x7f) fprintf(f, "\\u%04x", c);
        else if (c == 0xe2 && p[1] == 0x80 && (p[2] == 0xa8 || p[2] == 0xa9)) fprintf(f, "\\u%04x", p[2] == 0xa8 ? 0x2028 : 0x2029), p += 2;
        else fputc((int)c, f);
    }
    fputc('"', f);
}

void sb_json_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, "%.6g", v);
    else fputs("null", f);
}

void sb_site_slug(const char *s, char *buf, size_t len)
{
    size_t n = 0;
    for (; s && *s && n + 1 < len; s++) {
        char c = *s;
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
        buf[n++] = ok ? c : '_';
    }
    buf[n] = 0;
    if (n == 0 || strcmp(buf, ".") == 0 || strcmp(buf, "..") == 0) snprintf(buf, len, "_%s", n ? buf : "");
    if (buf[0] == '.') buf[0] = '_';
}

int sb_url_ok(const char *u)
{
    if (!u || !*u) return 0;
    if (!strncmp(u, "http://", 7) || !strncmp(u, "https://", 8) || !strncmp(u, "mailto:", 7) || u[0] == '#') return 1;
    /* relative: no scheme (a ':' before the first '/', '?' or '#'), no "//host" */
    if (u[0] == '/' && u[1] == '/') return 0;
    for (const char *p = u; *p && *p != '/' && *p != '?' && *p != '#'; p++)
        if (*p == ':') return 0;
    for (const char *p = u; *p; p++)
        if ((unsigned char)*p < 0x20 || *p == '\\') return 0;
    return 1;
}

int sb_site_mkdirs(sb_site *S, const char *rel)
{
    char tmp[1400];
    snprintf(tmp, sizeof tmp, "%s/%s", S->dir, rel);
    char *last = strrchr(tmp, '/');
    if (!last) return 0;
    *last = 0;
    size_t base = strlen(S->dir);
    for (char *p = tmp + base + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0777) && errno != EEXIST) return -1;
            *p = '/';
        }
    if (mkdir(tmp, 0777) && errno != EEXIST) return -1;
    struct stat st;
    if (lstat(tmp, &st) || !S_ISDIR(st.st_mode)) return -1;   /* a link or file where a directory goes */
    return 0;
}

/* open PATH.tmp anew after checking PATH; NULL with a sentence on S->err */
static FILE *open_tmp(sb_site *S, const char *path, char *tmp, size_t tlen)
{
    char why[1600];
    sb_output_kind kind;
    if (sb_output_check(path, "site page", &kind, why, sizeof why)) {
        fprintf(S->err, "shellbench site: %s\n", why);
        return NULL;
    }
    snprintf(tmp, tlen, "%s.tmp", path);
    unlink(tmp);
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
    if (fd < 0) {
        fprintf(S->err, "shellbench site: cannot write %s: %s\n", tmp, strerror(errno));
        return NULL;
    }
    FILE *f = fdopen(fd, "w");
    if (!f) close(fd), unlink(tmp);
    return f;
}

static int commit(sb_site *S, FILE *f, const char *tmp, const char *path)
{
    char why[1600];
    sb_output_kind kind;
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    if (bad) {
        fprintf(S->err, "shellbench site: cannot write %s\n", path);
        unlink(tmp);
        return -1;
    }
    if (sb_output_check(path, "site page", &kind, why, sizeof why)) {
        fprintf(S->err, "shellbench site: %s\n", why);
        unlink(tmp);
        return -1;
    }
    if (rename(tmp, path)) {
        fprintf(S->err, "shellbench site: cannot rename %s onto %s: %s\n", tmp, path, strerror(errno));
        unlink(tmp);
        return -1;
    }
    return 0;
}

int sb_site_write_file(sb_site *S, const char *rel, const void *data, size_t n)
{
    char path[1300], tmp[1400];
    if (sb_site_mkdirs(S, rel)) {
        fprintf(S->err, "shellbench site: cannot make the directory of %s/%s\n", S->dir, rel);
        S->errors++;
        return -1;
    }
    snprintf(path, sizeof path, "%s/%s", S->dir, rel);
    FILE *f = open_tmp(S, path, tmp, sizeof tmp);
    if (!f) return S->errors++, -1;
    if (n) fwrite(data, 1, n, f);
    if (commit(S, f, tmp, path)) return S->errors++, -1;
    return 0;
}

int sb_site_copy_file(sb_site *S, const char *src, const char *rel)
{
    FILE *in = fopen(src, "rb");
    if (!in) {
        fprintf(S->err, "shellbench site: warning: cannot read %s: %s\n", src, strerror(errno));
        return -1;
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n + 65536 > cap) {
            char *b = realloc(buf, cap = n + 65536 * 4);
            if (!b) { free(buf); fclose(in); return -1; }
            buf = b;
        }
        size_t k = fread(buf + n, 1, cap - n, in);
        n += k;
        if (k == 0) break;
    }
    fclose(in);
    int rc = sb_site_write_file(S, rel, buf, n);
    free(buf);
    return rc;
}

void sb_page_href(const sb_page *p, const char *rel, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = 0;
    for (int i = 0; i < p->depth && n + 4 < len; i++) memcpy(buf + n, "../", 4), n += 3;
    snprintf(buf + n, len - n, "%s", rel);
}

/* the Vega modules the pages load, in dependency order (sb_site.c copies them) */
const char *const sb_site_vega_modules[] = {
    "util", "canvas", "time", "format", "loader", "dataflow", "scale", "statistics", "expression", "event-selector",
    "scenegraph", "selection", "functions", "runtime", "view", "parser", "transforms", "encode", "view-transforms", NULL,
};

int sb_page_open(sb_site *S, sb_page *p, const char *rel, const char *title, int plots)
{
    memset(p, 0, sizeof *p);
    for (const char *c = rel; *c; c++) p->depth += *c == '/';
    if (sb_site_mkdirs(S, rel)) {
        fprintf(S->err, "shellbench site: cannot make the directory of %s/%s\n", S->dir, rel);
        S->errors++;
        return -1;
    }
    snprintf(p->path, sizeof p->path, "%s/%s", S->dir, rel);
    p->f = open_tmp(S, p->path, p->tmp, sizeof p->tmp);
    if (!p->f) return S->errors++, -1;
    FILE *f = p->f;
    char h[1200];
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>", f);
    sb_html_text(f, title);
    fputs(" — shellbench</title>\n", f);
    sb_page_href(p, "static/site.css", h, sizeof h);
    fprintf(f, "<link rel=\"stylesheet\" href=\"%s\">\n", h);
    if (plots) {
        sb_page_href(p, "static/amd.js", h, sizeof h);
        fprintf(f, "<script src=\"%s\"></script>\n", h);
        for (int k = 0; sb_site_vega_modules[k]; k++) {
            char rel2[128];
            snprintf(rel2, sizeof rel2, "static/vega/vega-%s.min.js", sb_site_vega_modules[k]);
            sb_page_href(p, rel2, h, sizeof h);
            fprintf(f, "<script src=\"%s\" data-amd=\"vega-%s\"></script>\n", h, sb_site_vega_modules[k]);
        }
    }
    sb_page_href(p, "static/site.js", h, sizeof h);
    fprintf(f, "<script src=\"%s\" defer></script>\n</head>\n<body>\n<nav class=\"top\">", h);
    sb_page_href(p, "index.html", h, sizeof h);
    fprintf(f, "<a href=\"%s\">shellbench</a> <span class=\"build\">build ", h);
    sb_html_text(f, S->build);
    fputs("</span></nav>\n<main>\n", f);
    return 0;
}

int sb_page_close(sb_site *S, sb_page *p)
{
    if (!p->f) return -1;
    fputs("</main>\n<footer>Generated by <code>shellbench site</code> (build ", p->f);
    sb_html_text(p->f, S->build);
    fputs(", ", p->f);
    sb_html_text(p->f, S->generated);
    fputs(") from records and digests only.</footer>\n</body></html>\n", p->f);
    int rc = commit(S, p->f, p->tmp, p->path);
    p->f = NULL;
    if (rc) S->errors++;
    return rc;
}

void sb_page_data_open(sb_page *p) { fputs("<script type=\"application/json\" id=\"sb-data\">", p->f); }
void sb_page_data_close(sb_page *p) { fputs("</script>\n", p->f); }
