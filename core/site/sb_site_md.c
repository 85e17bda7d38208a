/* sb_site_md.c — the Markdown the suite's reports are written in, to HTML:
 * ATX headings, pipe tables (with alignment), bullet and numbered lists,
 * fenced and indented code, block quotes, rules, paragraphs with hard
 * breaks; inline code, **strong**, *emphasis*, links and images.  Raw HTML
 * in the source is not passed through: every character is escaped, so a
 * report cannot put markup or scripts into the site. */
#include "sb_site.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

typedef struct md_ctx {
    FILE *o;
    sb_md_rewrite rw;
    void *ctx;
} md_ctx;

static void inline_md(md_ctx *m, const char *s, size_t n, int in_link);

/* the closing delimiter of length dl starting the search at i; n when none */
static size_t find(const char *s, size_t n, size_t i, const char *d, size_t dl)
{
    for (; i + dl <= n; i++) {
        if (s[i] == '\\' && i + 1 < n && s[i + 1] != '`') { i++; continue; }
        if (!memcmp(s + i, d, dl)) return i;
    }
    return n;
}

/* [text](target) at s[i] == '[': end of the whole link, or 0 */
static size_t link_end(const char *s, size_t n, size_t i, size_t *text_end, size_t *t0, size_t *t1)
{
    int depth = 0;
    size_t j = i;
    for (; j < n; j++) {
        if (s[j] == '\\') { j++; continue; }
        if (s[j] == '`') { size_t k = find(s, n, j + 1, "`", 1); if (k < n) j = k; continue; }
        if (s[j] == '[') depth++;
        else if (s[j] == ']' && --depth == 0) break;
    }
    if (j >= n || j + 1 >= n || s[j + 1] != '(') return 0;
    *text_end = j;
    size_t k = j + 2, par = 1;
    for (; k < n; k++) {
        if (s[k] == '(') par++;
        else if (s[k] == ')' && --par == 0) break;
    }
    if (k >= n) return 0;
    *t0 = j + 2, *t1 = k;
    /* a title after the target ("...") is dropped */
    for (size_t q = *t0; q < *t1; q++)
        if (s[q] == ' ') { *t1 = q; break; }
    return k + 1;
}

static void emit_link(md_ctx *m, const char *s, size_t n, size_t i, size_t te, size_t t0, size_t t1, int image)
{
    char target[1024], href[1400];
    size_t tl = t1 - t0 < sizeof target - 1 ? t1 - t0 : sizeof target - 1;
    memcpy(target, s + t0, tl);
    target[tl] = 0;
    if (tl >= 2 && target[0] == '<' && target[tl - 1] == '>') memmove(target, target + 1, tl - 2), target[tl - 2] = 0;
    int ok;
    if (m->rw) ok = m->rw(m->ctx, target, image, href, sizeof href);
    else ok = sb_url_ok(target), snprintf(href, sizeof href, "%s", target);
    if (ok && !sb_url_ok(href)) ok = 0;
    size_t a = i + (image ? 2 : 1);
    (void)n;
    if (image) {
        if (ok) {
            fputs("<img src=\"", m->o);
            sb_html_attr(m->o, href);
            fputs("\" alt=\"", m->o);
            sb_html_textn(m->o, s + a, te - a);
            fputs("\" loading=\"lazy\">", m->o);
        } else {
            fputs("<span class=\"missing\">[picture: ", m->o);
            sb_html_textn(m->o, s + a, te - a);
            fputs("]</span>", m->o);
        }
        return;
    }
    if (ok) {
        fputs("<a href=\"", m->o);
        sb_html_attr(m->o, href);
        fputs(strncmp(href, "http", 4) == 0 ? "\" rel=\"noopener noreferrer\">" : "\">", m->o);
    }
    inline_md(m, s + a, te - a, 1);
    if (ok) fputs("</a>", m->o);
    else if (strcmp(target, "") != 0) {
        fputs(" <span class=\"target\">(", m->o);
        sb_html_text(m->o, target);
        fputs(")</span>", m->o);
    }
}

static void inline_md(md_ctx *m, const char *s, size_t n, int in_link)
{
    FILE *o = m->o;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (c == '\\' && i + 1 < n && ispunct((unsigned char)s[i + 1])) {
            sb_html_textn(o, s + i + 1, 1);
            i++;
            continue;
        }
        if (c == '`') {
            size_t k = i;
            while (k < n && s[k] == '`') k++;
            size_t tl = k - i;
            char delim[8];
            if (tl >= sizeof delim) tl = sizeof delim - 1;
            memset(delim, '`', tl), delim[tl] = 0;
            size_t e = k;
            for (; e + tl <= n; e++) if (!memcmp(s + e, delim, tl)) break;
            if (e + tl <= n) {
                fputs("<code>", o);
                size_t a = k, b = e;
                if (b > a + 1 && s[a] == ' ' && s[b - 1] == ' ') a++, b--;
                sb_html_textn(o, s + a, b - a);
                fputs("</code>", o);
                i = e + tl - 1;
                continue;
            }
        }
        if ((c == '*' && i + 1 < n && s[i + 1] == '*') || (c == '_' && i + 1 < n && s[i + 1] == '_' && (i == 0 || !isalnum((unsigned char)s[i - 1])))) {
            char d[3] = { c, c, 0 };
            size_t e = find(s, n, i + 2, d, 2);
            if (e < n && e > i + 2) {
                fputs("<strong>", o);
                inline_md(m, s + i + 2, e - i - 2, in_link);
                fputs("</strong>", o);
                i = e + 1;
                continue;
            }
        }
        if ((c == '*' || c == '_') && i + 1 < n && s[i + 1] != ' ' && (i == 0 || !isalnum((unsigned char)s[i - 1]))) {
            char d[2] = { c, 0 };
            size_t e = i + 1;
            for (; e < n; e++) {
                if (s[e] == '\\') { e++; continue; }
                if (s[e] == '`') { size_t k = find(s, n, e + 1, "`", 1); if (k < n) { e = k; continue; } }
                if (s[e] == c && s[e - 1] != ' ' && (e + 1 >= n || !isalnum((unsigned char)s[e + 1])) &&
                    !(c == '*' && e + 1 < n && s[e + 1] == '*')) break;
            }
            if (e < n && e > i + 1) {
                (void)d;
                fputs("<em>", o);
                inline_md(m, s + i + 1, e - i - 1, in_link);
                fputs("</em>", o);
                i = e;
                continue;
            }
        }
        if (c == '!' && i + 1 < n && s[i + 1] == '[') {
            size_t te, t0, t1, end = link_end(s, n, i + 1, &te, &t0, &t1);
            if (end) {
                emit_link(m, s, n, i, te, t0, t1, 1);
                i = end - 1;
                continue;
            }
        }
        if (c == '[' && !in_link) {
            size_t te, t0, t1, end = link_end(s, n, i, &te, &t0, &t1);
            if (end) {
                emit_link(m, s, n, i, te, t0, t1, 0);
                i = end - 1;
                continue;
            }
        }
        sb_html_textn(o, s + i, 1);
    }
}

/* ---- blocks ------------------------------------------------------------- */

typedef struct line { const char *s; size_t n; } line;

static int blank(line l)
{
    for (size_t i = 0; i < l.n; i++) if (!isspace((unsigned char)l.s[i])) return 0;
    return 1;
}
static size_t indent(line l)
{
    size_t i = 0;
    while (i < l.n && l.s[i] == ' ') i++;
    return i;
}
static int is_fence(line l)
{
    size_t i = indent(l);
    return i < 4 && l.n >= i + 3 && (!memcmp(l.s + i, "```", 3) || !memcmp(l.s + i, "~~~", 3));
}
static int heading_level(line l)
{
    size_t i = 0;
    while (i < l.n && l.s[i] == '#') i++;
    return i >= 1 && i <= 6 && (i == l.n || l.s[i] == ' ') ? (int)i : 0;
}
/* bullet or number: the offset of the item text, or 0 */
static size_t list_item(line l, int *ordered)
{
    size_t i = indent(l);
    if (i + 1 < l.n && (l.s[i] == '*' || l.s[i] == '-' || l.s[i] == '+') && l.s[i + 1] == ' ') return *ordered = 0, i + 2;
    size_t j = i;
    while (j < l.n && isdigit((unsigned char)l.s[j])) j++;
    if (j > i && j - i < 10 && j + 1 < l.n && (l.s[j] == '.' || l.s[j] == ')') && l.s[j + 1] == ' ') return *ordered = 1, j + 2;
    return 0;
}
static int is_rule(line l)
{
    size_t k = 0;
    char c = 0;
    for (size_t i = 0; i < l.n; i++) {
        if (l.s[i] == ' ') continue;
        if (l.s[i] != '-' && l.s[i] != '*' && l.s[i] != '_') return 0;
        if (c && l.s[i] != c) return 0;
        c = l.s[i], k++;
    }
    return k >= 3;
}
static int is_table_sep(line l)
{
    int dash = 0, bar = 0;
    for (size_t i = 0; i < l.n; i++) {
        char c = l.s[i];
        if (c == '-') dash++;
        else if (c == '|') bar++;
        else if (c != ':' && c != ' ') return 0;
    }
    return dash >= 1 && bar >= 1;
}
static int is_table_row(line l) { size_t i = indent(l); return i < l.n && l.s[i] == '|'; }

/* the cells of a table row: bounds into a[], b[]; returns their number */
static int cells(line l, size_t *a, size_t *b, int max)
{
    size_t i = indent(l), n = l.n;
    while (n > i && (l.s[n - 1] == ' ' || l.s[n - 1] == '\r')) n--;
    if (i < n && l.s[i] == '|') i++;
    if (n > i && l.s[n - 1] == '|' && !(n >= 2 && l.s[n - 2] == '\\')) n--;
    int k = 0;
    size_t start = i;
    int code = 0;
    for (size_t j = i; j <= n && k < max; j++) {
        if (j < n && l.s[j] == '\\') { j++; continue; }
        if (j < n && l.s[j] == '`') code = !code;
        if (j == n || (l.s[j] == '|' && !code)) {
            size_t x = start, y = j;
            while (x < y && l.s[x] == ' ') x++;
            while (y > x && l.s[y - 1] == ' ') y--;
            a[k] = x, b[k] = y, k++;
            start = j + 1;
        }
    }
    return k;
}

static void para(md_ctx *m, line *L, int from, int to)
{
    /* joined with newlines; "  " at a line's end is a hard break */
    for (int k = from; k < to; k++) {
        line l = L[k];
        size_t n = l.n;
        while (n && l.s[n - 1] == '\r') n--;
        int br = n >= 2 && l.s[n - 1] == ' ' && l.s[n - 2] == ' ';
        size_t st = indent(l);
        while (n > st && l.s[n - 1] == ' ') n--;
        inline_md(m, l.s + st, n - st, 0);
        if (k + 1 < to) fputs(br ? "<br>\n" : "\n", m->o);
    }
}

static void heading_id(FILE *o, const char *s, size_t n)
{
    int dash = 0, any = 0;   /* a dash between words, never at either end */
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (isalnum(c) || c == '_' || c == '-') {
            if (dash && any) fputc('-', o);
            fputc(isalnum(c) ? tolower(c) : c, o), dash = 0, any = 1;
        } else dash = 1;
    }
}

void sb_md_to_html(FILE *out, const char *md, size_t n, sb_md_rewrite rewrite, void *ctx)
{
    md_ctx m = { out, rewrite, ctx };
    /* split into lines */
    int nl = 1;
    for (size_t i = 0; i < n; i++) nl += md[i] == '\n';
    line *L = malloc((size_t)nl * sizeof *L);
    if (!L) return;
    int k = 0;
    size_t st = 0;
    for (size_t i = 0; i <= n; i++)
        if (i == n || md[i] == '\n') {
            size_t e = i;
            if (e > st && md[e - 1] == '\r') e--;
            L[k].s = md + st, L[k].n = e - st, k++;
            st = i + 1;
        }
    nl = k;
    int i = 0;
    while (i < nl) {
        line l = L[i];
        int ordered;
        if (blank(l)) { i++; continue; }
        if (is_fence(l)) {
            size_t fi = indent(l);
            char fch = l.s[fi];
            fputs("<pre><code>", out);
            int j = i + 1;
            for (; j < nl; j++) {
                size_t ji = indent(L[j]);
                if (ji < 4 && L[j].n >= ji + 3 && L[j].s[ji] == fch && L[j].s[ji + 1] == fch && L[j].s[ji + 2] == fch) break;
                sb_html_textn(out, L[j].s, L[j].n);
                fputc('\n', out);
            }
            fputs("</code></pre>\n", out);
            i = j + 1;
            continue;
        }
        if (indent(l) >= 4) {
            fputs("<pre><code>", out);
            int j = i;
            for (; j < nl && (indent(L[j]) >= 4 || blank(L[j])); j++) {
                if (blank(L[j])) {
                    int q = j;
                    while (q < nl && blank(L[q])) q++;
                    if (q >= nl || indent(L[q]) < 4) break;
                    fputc('\n', out);
                    continue;
                }
                sb_html_textn(out, L[j].s + 4, L[j].n - 4);
                fputc('\n', out);
            }
            fputs("</code></pre>\n", out);
            i = j;
            continue;
        }
        int h = heading_level(l);
        if (h) {
            size_t a = (size_t)h, b = l.n;
            while (a < b && l.s[a] == ' ') a++;
            while (b > a && (l.s[b - 1] == ' ' || l.s[b - 1] == '#')) b--;
            fprintf(out, "<h%d id=\"", h);
            heading_id(out, l.s + a, b - a);
            fputs("\">", out);
            inline_md(&m, l.s + a, b - a, 0);
            fprintf(out, "</h%d>\n", h);
            i++;
            continue;
        }
        if (is_rule(l)) { fputs("<hr>\n", out); i++; continue; }
        if (is_table_row(l) && i + 1 < nl && is_table_sep(L[i + 1])) {
            size_t a[64], b[64], sa[64], sb[64];
            int nh = cells(l, a, b, 64), ns = cells(L[i + 1], sa, sb, 64);
            char align[64];
            for (int c = 0; c < 64; c++) {
                align[c] = 0;
                if (c < ns && sb[c] > sa[c]) {
                    int left = L[i + 1].s[sa[c]] == ':', right = L[i + 1].s[sb[c] - 1] == ':';
                    align[c] = right && !left ? 'r' : (left && right ? 'c' : 0);
                }
            }
            fputs("<div class=\"tablewrap\"><table class=\"md\">\n<thead><tr>", out);
            for (int c = 0; c < nh; c++) {
                fputs(align[c] == 'r' ? "<th class=\"r\">" : align[c] == 'c' ? "<th class=\"c\">" : "<th>", out);
                inline_md(&m, l.s + a[c], b[c] - a[c], 0);
                fputs("</th>", out);
            }
            fputs("</tr></thead>\n<tbody>\n", out);
            int j = i + 2;
            for (; j < nl && is_table_row(L[j]); j++) {
                int nc = cells(L[j], a, b, 64);
                fputs("<tr>", out);
                for (int c = 0; c < nc; c++) {
                    fputs(align[c] == 'r' ? "<td class=\"r\">" : align[c] == 'c' ? "<td class=\"c\">" : "<td>", out);
                    inline_md(&m, L[j].s + a[c], b[c] - a[c], 0);
                    fputs("</td>", out);
                }
                fputs("</tr>\n", out);
            }
            fputs("</tbody></table></div>\n", out);
            i = j;
            continue;
        }
        size_t off = list_item(l, &ordered);
        if (off) {
            int ord0 = ordered;
            fputs(ord0 ? "<ol>\n" : "<ul>\n", out);
            int j = i;
            while (j < nl) {
                int o2;
                size_t of = list_item(L[j], &o2);
                if (!of || o2 != ord0) break;
                /* the item: its first line and the continuation lines */
                int e = j + 1;
                while (e < nl && !blank(L[e]) && !list_item(L[e], &o2) && !heading_level(L[e]) && !is_fence(L[e])) e++;
                fputs("<li>", out);
                line first = { L[j].s + of, L[j].n - of };
                line save = L[j];
                L[j] = first;
                para(&m, L, j, e);
                L[j] = save;
                fputs("</li>\n", out);
                j = e;
                /* a blank line between items keeps the list going */
                int q = j;
                while (q < nl && blank(L[q])) q++;
                if (q < nl && list_item(L[q], &o2) && o2 == ord0) j = q;
            }
            fputs(ord0 ? "</ol>\n" : "</ul>\n", out);
            i = j;
            continue;
        }
        if (indent(l) < l.n && l.s[indent(l)] == '>') {
            fputs("<blockquote>", out);
            int j = i;
            for (; j < nl && !blank(L[j]) && L[j].s[indent(L[j])] == '>'; j++) {
                size_t a = indent(L[j]) + 1;
                if (a < L[j].n && L[j].s[a] == ' ') a++;
                inline_md(&m, L[j].s + a, L[j].n - a, 0);
                fputc('\n', out);
            }
            fputs("</blockquote>\n", out);
            i = j;
            continue;
        }
        /* a paragraph: up to a blank line or another block's start */
        int j = i + 1;
        while (j < nl && !blank(L[j]) && !heading_level(L[j]) && !is_fence(L[j]) && !list_item(L[j], &ordered) &&
               !(is_table_row(L[j]) && j + 1 < nl && is_table_sep(L[j + 1])))
            j++;
        fputs("<p>", out);
        para(&m, L, i, j);
        fputs("</p>\n", out);
        i = j;
    }
    free(L);
}
