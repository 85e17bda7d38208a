/* sb_escape.c — messages safe for a terminal (sb_common.h). */
#include "sb_common.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Length of the valid UTF-8 sequence at s (1..4), 0 when invalid. */
static int utf8_len(const unsigned char *s, size_t left)
{
    unsigned c = s[0];
    int n = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
    if (n == 0 || (size_t)n > left) return 0;
    for (int i = 1; i < n; i++)
        if ((s[i] & 0xC0) != 0x80) return 0;
    if (n == 2 && c < 0xC2) return 0;                                  /* overlong */
    if (n == 3 && c == 0xE0 && s[1] < 0xA0) return 0;
    if (n == 4 && ((c == 0xF0 && s[1] < 0x90) || c > 0xF4 || (c == 0xF4 && s[1] > 0x8F))) return 0;
    return n;
}

/* U+202A..U+202E (LRE, RLE, PDF, LRO, RLO) and U+2066..U+2069 (LRI, RLI,
 * FSI, PDI): UTF-8 E2 80 AA..AE and E2 81 A6..A9 */
static int is_bidi(const unsigned char *s)
{
    return s[0] == 0xE2 && ((s[1] == 0x80 && s[2] >= 0xAA && s[2] <= 0xAE) || (s[1] == 0x81 && s[2] >= 0xA6 && s[2] <= 0xA9));
}

size_t sb_escape_controls(char *s, size_t cap)
{
    if (!s || cap == 0) return 0;
    size_t len = strnlen(s, cap - 1);
    char out[4096];
    size_t o = 0, changed = 0;
    const unsigned char *p = (const unsigned char *)s;
    for (size_t i = 0; i < len && o + 7 < sizeof out;) {
        int n = utf8_len(p + i, len - i);
        const char *named = p[i] == '\n' ? "\\n" : p[i] == '\r' ? "\\r" : p[i] == '\t' ? "\\t" : NULL;
        if (named) {
            memcpy(out + o, named, 2), o += 2, i++, changed++;
        } else if (n == 0 || p[i] < 0x20 || p[i] == 0x7F) {
            o += (size_t)snprintf(out + o, sizeof out - o, "\\x%02x", p[i]), i++, changed++;
        } else if (n == 2 && p[i] == 0xC2 && p[i + 1] < 0xA0) {   /* C1 controls U+0080..U+009F (CSI is U+009B) */
            o += (size_t)snprintf(out + o, sizeof out - o, "\\u%04x", p[i + 1]), i += 2, changed++;
        } else if (n == 3 && p[i] == 0xEF && p[i + 1] == 0xBB && p[i + 2] == 0xBF) {   /* the BOM, invisible */
            memcpy(out + o, "\\ufeff", 6), o += 6, i += 3, changed++;
        } else if (n == 3 && is_bidi(p + i)) {   /* bidi embeddings, overrides and isolates reorder the line */
            const unsigned cp = ((p[i] & 0x0Fu) << 12) | ((p[i + 1] & 0x3Fu) << 6) | (p[i + 2] & 0x3Fu);
            o += (size_t)snprintf(out + o, sizeof out - o, "\\u%04x", cp), i += 3, changed++;
        } else {
            memcpy(out + o, p + i, (size_t)n), o += (size_t)n, i += (size_t)n;
        }
    }
    if (!changed) return 0;
    if (o >= cap) {   /* keep whole characters only */
        o = cap - 1;
        while (o > 0 && ((unsigned char)out[o] & 0xC0) == 0x80) o--;
    }
    memcpy(s, out, o);
    s[o] = 0;
    return changed;
}

const char *sb_escape_copy(const char *s, char *buf, size_t len)
{
    if (!buf || len == 0) return "";
    snprintf(buf, len, "%s", s ? s : "(null)");
    sb_escape_controls(buf, len);
    return buf;
}

void sb_escape_print(FILE *f, const char *fmt, ...)
{
    char msg[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    sb_escape_controls(msg, sizeof msg);
    fprintf(f, "%s\n", msg);
}
