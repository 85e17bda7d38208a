/* test_site.c — issue 41: `shellbench site`.  The Markdown converter and the
 * escaping of every string that reaches a page (a study description, a
 * history's case and host, a report's raw markup and javascript: link show
 * as text); the output directory refused when it is a symbolic link, FIFO or
 * device; the site of a small study (part of the committed accuracy study,
 * read from its records), a small nightly history and a report; and, when
 * /usr/bin/chromium and node are installed, the browser check of
 * scripts/check_site.js on that site (make check-site runs it too, with
 * screenshots and the accuracy study's load time). */
#define _XOPEN_SOURCE 700
#include "cli_sh.h"
#include "sb_site.h"
#include "sb_test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char out[1 << 16], err[1 << 14];

static char *md(const char *src)
{
    char *buf = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&buf, &n);
    sb_md_to_html(f, src, strlen(src), NULL, NULL);
    fclose(f);
    return buf;
}

SB_TEST(markdown_subset)
{
    char *h = md("# Title *x*\n\nA **bold** and *em* with `a<b>` and [a link](docs/x.md) and [bad](javascript:alert(1)).\n\n"
                 "| a | b |\n|---|--:|\n| 1 | `x|y` |\n\n* one\n* two\n\n1. first\n\n```\n<script>alert(1)</script>\n```\n\n"
                 "![pic](img.png)\n\n<script>alert(1)</script>\n");
    CHECK_MSG(strstr(h, "<h1 id=\"title-x\">Title <em>x</em></h1>"), "%s", h);
    CHECK(strstr(h, "<strong>bold</strong>") && strstr(h, "<em>em</em>"));
    CHECK(strstr(h, "<code>a&lt;b&gt;</code>"));
    CHECK(strstr(h, "<a href=\"docs/x.md\">a link</a>"));
    CHECK_MSG(!strstr(h, "href=\"javascript"), "%s", h);
    CHECK(strstr(h, "<th class=\"r\">b</th>") && strstr(h, "<code>x|y</code>"));
    CHECK(strstr(h, "<ul>\n<li>one</li>\n<li>two</li>\n</ul>") && strstr(h, "<ol>\n<li>first</li>"));
    CHECK(strstr(h, "<pre><code>&lt;script&gt;alert(1)&lt;/script&gt;\n</code></pre>"));
    CHECK(strstr(h, "<img src=\"img.png\" alt=\"pic\""));
    CHECK_MSG(!strstr(h, "<script>"), "raw markup passed through: %s", h);
    free(h);
    h = md("plate_clamped and snake_case_names stay as they are; 2 * 3 * 4 too\n");
    CHECK_MSG(strstr(h, "plate_clamped and snake_case_names") && strstr(h, "2 * 3 * 4") && !strstr(h, "<em>"), "%s", h);
    free(h);
}

/* random inputs from the constructs' pieces, each in a buffer of exactly
 * its length (no terminator): under `make check-asan` a read past a span is
 * an error; here, that it ends and never emits a raw '<' */
SB_TEST(markdown_random_inputs)
{
    static const char *const atoms[] = { "#", "# ", "|", "---", "|--:|", "`", "``", "```\n", "*", "**", "_", "__", "[",
                                         "]", "(", ")", "![", "\n", "\n\n", "  \n", "    ", "* ", "1. ", "> ", "\\", "<",
                                         ">", "&", "\"", "a", "b c", "http://x", "javascript:", "~~~", "\r\n", "\t" };
    const int na = (int)(sizeof atoms / sizeof *atoms);
    unsigned long seed = 12345;
    int raw = 0;
    for (int it = 0; it < 20000; it++) {
        char buf[1024];
        size_t len = 0;
        seed = seed * 6364136223846793005UL + 1442695040888963407UL;
        int k = (int)((seed >> 33) % 80);
        for (int j = 0; j < k; j++) {
            seed = seed * 6364136223846793005UL + 1442695040888963407UL;
            const char *a = atoms[(seed >> 33) % (unsigned long)na];
            size_t l = strlen(a);
            if (len + l >= sizeof buf) break;
            memcpy(buf + len, a, l), len += l;
        }
        char *exact = malloc(len ? len : 1);
        memcpy(exact, buf, len);
        char *html = NULL;
        size_t n = 0;
        FILE *f = open_memstream(&html, &n);
        sb_md_to_html(f, exact, len, NULL, NULL);
        fclose(f);
        /* every '<' written is one of the converter's own tags */
        for (const char *p = html; (p = strchr(p, '<')) != NULL; p++)
            if (!strchr("/abcdehilmoprstu", p[1])) raw++;
        free(html);
        free(exact);
    }
    CHECK_EQ_INT(raw, 0);
}

SB_TEST(escaping)
{
    char *buf = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&buf, &n);
    sb_html_text(f, "<script>alert('1')</script> & \"q\"");
    fputc('|', f);
    sb_json_str(f, "</script><!-- \"\\ \n\xe2\x80\xa8");
    fclose(f);
    CHECK_MSG(strcmp(buf, "&lt;script&gt;alert(&#39;1&#39;)&lt;/script&gt; &amp; &quot;q&quot;|"
                          "\"\\u003c/script\\u003e\\u003c!-- \\\"\\\\ \\u000a\\u2028\"") == 0, "%s", buf);
    free(buf);
    CHECK(sb_url_ok("a/b.html") && sb_url_ok("https://x.org/") && sb_url_ok("#top"));
    CHECK(!sb_url_ok("javascript:alert(1)") && !sb_url_ok("data:text/html,x") && !sb_url_ok("//evil.org/x") && !sb_url_ok(""));
    char s[64];
    sb_site_slug("../<b>x", s, sizeof s);
    CHECK_MSG(strcmp(s, "_.__b_x") == 0, "%s", s);
    sb_site_slug("..", s, sizeof s);
    CHECK(strcmp(s, "..") != 0 && !strchr(s, '/'));
}

SB_TEST(output_directory_refused)
{
    const char *bin = sb_test_bin();
    char dir[] = "/tmp/sb-site-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    /* a symbolic link to a directory, a FIFO, a device, a regular file */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "mkdir %s/real && ln -s real %s/link && mkfifo %s/fifo && touch %s/file",
                       dir, dir, dir, dir), 0);
    const char *cases[][2] = { { "link", "symbolic link" }, { "fifo", "FIFO" }, { "file", "a file" } };
    for (int k = 0; k < 3; k++) {
        int rc = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s site --report tests/site/report.md --out %s/%s",
                       sb_test_root(), bin, dir, cases[k][0]);
        CHECK_EQ_INT(rc, 2);
        CHECK_MSG(strstr(err, cases[k][1]) && strstr(err, "refused"), "%s: %s", cases[k][0], err);
    }
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s site --report tests/site/report.md --out /dev/null",
                       sb_test_root(), bin), 2);
    CHECK_MSG(strstr(err, "a device") && strstr(err, "refused"), "%s", err);
    /* nothing was written through the link */
    struct stat st;
    char p[256];
    snprintf(p, sizeof p, "%s/real/index.html", dir);
    CHECK(stat(p, &st) != 0);
    /* a page inside the site that is a link is refused too, not followed */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "mkdir -p %s/site && ln -s %s/file %s/site/index.html && cd %s && "
                       "%s site --report tests/site/report.md --out %s/site", dir, dir, dir, sb_test_root(), bin, dir), 2);
    CHECK_MSG(strstr(err, "symbolic link"), "%s", err);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s site --frobnicate", bin), 2);
    sb_sh(NULL, 0, NULL, 0, "rm -rf %s", dir);
}

static int file_has(const char *path, const char *needle)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    static char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    return strstr(buf, needle) != NULL;
}

SB_TEST(small_site_and_browser)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char dir[] = "/tmp/sb-site-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    int rc = sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s site --out %s/site --study tests/site/study.json "
                   "--history tests/site/history.csv --baseline bench/nightly/baseline.json --report tests/site/report.md",
                   root, bin, dir);
    CHECK_MSG(rc == 0, "exit %d: %s", rc, err);
    char p[512];
    const char *pages[] = { "index.html", "studies/site_check/index.html", "studies/site_check/scene-plate_clamped.html",
                            "studies/site_check/runs/plate_clamped/bhem-tr-r8.html", "nightly/index.html",
                            "reports/tests-site-report.html", "static/site.js", "static/vega/vega-view.min.js" };
    for (int k = 0; k < 8; k++) {
        snprintf(p, sizeof p, "%s/site/%s", dir, pages[k]);
        CHECK_MSG(access(p, R_OK) == 0, "missing %s", p);
    }
    /* the study's description, the history's case and host, the report's markup: text, never markup */
    snprintf(p, sizeof p, "%s/site/studies/site_check/index.html", dir);
    CHECK_EQ_INT(file_has(p, "&lt;script&gt;window.__sbXss=1&lt;/script&gt;&lt;img src=x"), 1);
    CHECK_EQ_INT(file_has(p, "<script>window"), 0);
    CHECK_EQ_INT(file_has(p, "<img src=x"), 0);
    snprintf(p, sizeof p, "%s/site/nightly/index.html", dir);
    CHECK_EQ_INT(file_has(p, "<script>window"), 0);
    CHECK_EQ_INT(file_has(p, "\\u003cscript\\u003ewindow.__sbXss=1\\u003c/script\\u003e/a.h5"), 1);
    CHECK_EQ_INT(file_has(p, "&lt;img src=x onerror=&quot;window.__sbXss=1&quot;&gt;"), 1);
    snprintf(p, sizeof p, "%s/site/reports/tests-site-report.html", dir);
    CHECK_EQ_INT(file_has(p, "<script>window"), 0);
    CHECK_EQ_INT(file_has(p, "href=\"javascript"), 0);
    /* the browser check, when there is a browser */
    if (access("/usr/bin/chromium", X_OK) != 0 || sb_sh(NULL, 0, NULL, 0, "command -v node") != 0) {
        printf("test_site: browser check skipped: /usr/bin/chromium or node is not installed "
               "(scripts/ensure_deps.sh installs chromium; make check-site)\n");
    } else {
        rc = sb_sh(out, sizeof out, err, sizeof err, "cd %s && node scripts/check_site.js %s/site "
                   "%s/shots tests/site/spec.json", root, dir, dir);
        CHECK_MSG(rc == 0, "browser check failed (exit %d):\n%s%s", rc, out, err);
        if (rc == 0) printf("test_site: browser check passed\n");
    }
    sb_sh(NULL, 0, NULL, 0, "rm -rf %s", dir);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(markdown_subset), SB_CASE(markdown_random_inputs), SB_CASE(escaping), SB_CASE(output_directory_refused), SB_CASE(small_site_and_browser),
        SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
