/* sb_site.h — `shellbench site [--out DIR]`: a static, self-contained HTML
 * site from records and digests only (docs/site.md): an index, one page per
 * study (selection table, performance profiles, per-scene pages with
 * interactive work-precision diagrams), one page per recorded run, the
 * nightly history over builds, and the paper reports rendered from their
 * Markdown.  Plots are drawn in the page by Vega 5 (Debian's libjs-vega,
 * copied into DIR); tables sort and filter with the site's own few lines of
 * JavaScript (core/site/assets/site.js).
 *
 * Every string that comes from a record, a scene, a study or a report is
 * escaped for HTML (sb_html_text, sb_html_attr) or, inside the pages' JSON
 * data blocks, for JSON with '<', '>' and '&' written as \u escapes
 * (sb_json_str), so that no such string can open a tag or end a script.
 *
 *   sb_site_html.c     escaping, JSON, page head and foot, files written by rename
 *   sb_site_md.c       the Markdown subset of the reports to HTML
 *   sb_site_study.c    study and scene pages; sb_site_run.c: one record's page
 *   sb_site_nightly.c  the nightly history
 *   sb_site.c          the command, the index, the copied scripts */
#ifndef SB_SITE_H
#define SB_SITE_H

#include <stddef.h>
#include <stdio.h>

/* ---- escaping (sb_site_html.c) ------------------------------------------- */
/* text content and attribute values: & < > " ' escaped; bytes below 0x20
 * other than tab and newline dropped */
void sb_html_text(FILE *f, const char *s);
void sb_html_attr(FILE *f, const char *s);
/* the first n bytes of s as text */
void sb_html_textn(FILE *f, const char *s, size_t n);
/* a JSON string literal, safe inside <script type="application/json">:
 * quotes, backslashes, controls, '<', '>', '&' and U+2028/9 as \u escapes */
void sb_json_str(FILE *f, const char *s);
/* a JSON number; null when not finite */
void sb_json_num(FILE *f, double v);
/* a file or path component made safe for a file name in the site:
 * [A-Za-z0-9._-] kept, everything else '_' (never empty, never "." or "..") */
void sb_site_slug(const char *s, char *buf, size_t len);
/* 1 when the URL may be written into an href: a relative path without a
 * scheme, or http:, https:, mailto:, or a #fragment */
int sb_url_ok(const char *url);

/* ---- the site under way ----------------------------------------------------- */
typedef struct sb_site {
    char dir[1024];            /* output directory (made; checked) */
    char build[64];            /* this binary's build id */
    char generated[32];        /* ISO 8601 UTC */
    char commit_url[512];      /* "" or a prefix a build id is appended to */
    int errors;                /* pages that could not be written */
    FILE *err;
} sb_site;

/* A page written to DIR/rel: PATH.tmp created anew (O_EXCL | O_NOFOLLOW),
 * renamed onto its path by sb_page_close after sb_output_check (a link,
 * FIFO, device or directory at the path is refused with a sentence). */
typedef struct sb_page {
    FILE *f;
    char path[1300], tmp[1400];
    int depth;                 /* directories below the site root: links to ../ */
} sb_page;

/* Open DIR/rel (its directories made) and write the head: title, the
 * stylesheet and scripts (vega only when `plots`), the navigation bar. */
int  sb_page_open(sb_site *S, sb_page *p, const char *rel, const char *title, int plots);
/* the foot; renamed onto its path; 0 or -1 (a sentence on S->err) */
int  sb_page_close(sb_site *S, sb_page *p);
/* "../" repeated depth times, then rel */
void sb_page_href(const sb_page *p, const char *rel, char *buf, size_t len);
/* a whole file written by rename (copies of scripts and pictures) */
int  sb_site_write_file(sb_site *S, const char *rel, const void *data, size_t n);
int  sb_site_copy_file(sb_site *S, const char *src, const char *rel);
/* mkdir -p DIR/rel's directory */
int  sb_site_mkdirs(sb_site *S, const char *rel);
/* the data block <script type="application/json" id="sb-data">: opened and closed */
void sb_page_data_open(sb_page *p);
void sb_page_data_close(sb_page *p);

/* ---- Markdown (sb_site_md.c) ------------------------------------------------ */
/* Convert the Markdown subset of the reports (ATX headings, pipe tables,
 * lists, fenced and indented code, paragraphs, inline code, emphasis,
 * links, images) to HTML, every character of the source escaped.  Links
 * and images go through rewrite(ctx, target, is_image, buf, len), which
 * writes the href/src to use into buf and returns 1, or 0 to leave the
 * link as text; NULL keeps targets that pass sb_url_ok. */
typedef int (*sb_md_rewrite)(void *ctx, const char *target, int is_image, char *buf, size_t len);
void sb_md_to_html(FILE *out, const char *md, size_t n, sb_md_rewrite rewrite, void *ctx);

/* ---- pages ------------------------------------------------------------------- */
typedef struct sb_site_entry {   /* a line of the index */
    char href[800], title[512], date[80], provenance[1024];
} sb_site_entry;

/* a study's pages (overview, scenes, runs) from its file (records: its
 * records directory instead of the file's, or NULL); the index line in e;
 * 1 for a study that is not an accuracy study (its report is rendered) */
int sb_site_study(sb_site *S, const char *study_file, const char *records, sb_site_entry *e);
/* the nightly history page from the history CSV and the baseline (may be NULL) */
int sb_site_nightly(sb_site *S, const char *history, const char *baseline, sb_site_entry *e);

/* the assets embedded in the binary (core/site/assets/, sb_site_assets.c) */
extern const char sb_site_js[], sb_site_css[], sb_site_amd_js[];

int sb_cli_site(int argc, char **argv);
extern const char sb_cli_site_help[];

#endif
