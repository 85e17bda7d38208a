/* sb_json_pos.c — JSON pointer (RFC 6901) -> byte offset -> line:column in
 * raw JSON text.  Used only for error messages; works on any bytes (never
 * reads past len, never recurses), and gives a best-effort position when the
 * text is not valid JSON. */
#include "sb_json_pos.h"

#include <string.h>

#define TOKEN_MAX 512

static size_t skip_ws(const char *s, size_t len, size_t i)
{
    while (i < len && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) i++;
    return i;
}

/* s[i] == '"'; returns the index just after the closing quote (or len). */
static size_t skip_string(const char *s, size_t len, size_t i)
{
    for (i++; i < len; i++) {
        if (s[i] == '\\') { i++; continue; }
        if (s[i] == '"') return i + 1;
    }
    return len;
}

/* Skip one JSON value starting at i (after whitespace); iterative over
 * nesting: brackets are counted, strings skipped whole. */
static size_t skip_value(const char *s, size_t len, size_t i)
{
    if (i >= len) return len;
    if (s[i] == '"') return skip_string(s, len, i);
    if (s[i] == '{' || s[i] == '[') {
        size_t depth = 0;
        while (i < len) {
            char c = s[i];
            if (c == '"') { i = skip_string(s, len, i); continue; }
            if (c == '{' || c == '[') depth++;
            else if (c == '}' || c == ']') {
                if (--depth == 0) return i + 1;
            }
            i++;
        }
        return len;
    }
    /* scalar: up to the next delimiter */
    while (i < len && s[i] != ',' && s[i] != '}' && s[i] != ']' && s[i] != ' ' &&
           s[i] != '\t' && s[i] != '\n' && s[i] != '\r')
        i++;
    return i;
}

static int hexval(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

static long read_hex4(const char *s, size_t len, size_t i)
{
    long v = 0;
    if (i + 4 > len) return -1;
    for (int k = 0; k < 4; k++) {
        int h = hexval(s[i + (size_t)k]);
        if (h < 0) return -1;
        v = v * 16 + h;
    }
    return v;
}

static int utf8_encode(unsigned long cp, unsigned char out[4])
{
    if (cp < 0x80) { out[0] = (unsigned char)cp; return 1; }
    if (cp < 0x800) {
        out[0] = (unsigned char)(0xC0 | (cp >> 6));
        out[1] = (unsigned char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (unsigned char)(0xE0 | (cp >> 12));
        out[1] = (unsigned char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (unsigned char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (unsigned char)(0xF0 | (cp >> 18));
    out[1] = (unsigned char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (unsigned char)(0x80 | ((cp >> 6) & 0x3F));
    out[3] = (unsigned char)(0x80 | (cp & 0x3F));
    return 4;
}

/* Does the JSON string starting at s[i] == '"' decode to tok[0..tlen)? */
static int string_equals(const char *s, size_t len, size_t i, const char *tok, size_t tlen)
{
    size_t k = 0;
    for (i++; i < len; i++) {
        unsigned char buf[4];
        int n = 1;
        char c = s[i];
        if (c == '"') return k == tlen;
        if (c != '\\') {
            buf[0] = (unsigned char)c;
        } else {
            if (++i >= len) return 0;
            switch (s[i]) {
            case 'b': buf[0] = '\b'; break;
            case 'f': buf[0] = '\f'; break;
            case 'n': buf[0] = '\n'; break;
            case 'r': buf[0] = '\r'; break;
            case 't': buf[0] = '\t'; break;
            case 'u': {
                long cp = read_hex4(s, len, i + 1);
                if (cp < 0) return 0;
                i += 4;
                if (cp >= 0xD800 && cp < 0xDC00 && i + 2 < len && s[i + 1] == '\\' && s[i + 2] == 'u') {
                    long lo = read_hex4(s, len, i + 3);
                    if (lo >= 0xDC00 && lo < 0xE000) {
                        cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                        i += 6;
                    }
                }
                n = utf8_encode((unsigned long)cp, buf);
                break;
            }
            default: buf[0] = (unsigned char)s[i]; break; /* \" \\ \/ */
            }
        }
        if (k + (size_t)n > tlen || memcmp(tok + k, buf, (size_t)n) != 0) return 0;
        k += (size_t)n;
    }
    return 0;
}

/* Decode the next pointer token starting after '/' at p; returns its end. */
static const char *next_token(const char *p, char *tok, size_t *tlen)
{
    size_t k = 0;
    while (*p && *p != '/') {
        char c = *p++;
        if (c == '~' && (*p == '0' || *p == '1')) c = (*p++ == '0') ? '~' : '/';
        if (k < TOKEN_MAX) tok[k] = c;
        k++;
    }
    *tlen = k;
    return p;
}

int sb_json_pointer_offset(const char *text, size_t len, const char *pointer, int at_key,
                           size_t *offset)
{
    char tok[TOKEN_MAX];
    size_t i = skip_ws(text, len, 0);
    const char *p = pointer ? pointer : "";
    *offset = i;
    while (*p == '/') {
        size_t tlen;
        p = next_token(p + 1, tok, &tlen);
        int last = (*p == '\0');
        if (tlen > TOKEN_MAX || i >= len) return 1;
        if (text[i] == '{') {
            size_t found = (size_t)-1, key_at = 0;
            i++;
            for (;;) {
                i = skip_ws(text, len, i);
                if (i >= len || text[i] != '"') return 1;
                size_t k0 = i;
                int match = string_equals(text, len, i, tok, tlen);
                i = skip_ws(text, len, skip_string(text, len, i));
                if (i >= len || text[i] != ':') return 1;
                i = skip_ws(text, len, i + 1);
                if (match) { found = i; key_at = k0; break; }
                i = skip_ws(text, len, skip_value(text, len, i));
                if (i >= len || text[i] != ',') return 1;
                i++;
            }
            if (last && at_key) { *offset = key_at; return 0; }
            i = found;
        } else if (text[i] == '[') {
            size_t idx = 0, want = 0;
            if (tlen == 0 || tlen > 18) return 1;
            for (size_t k = 0; k < tlen; k++) {
                if (tok[k] < '0' || tok[k] > '9') return 1;
                want = want * 10 + (size_t)(tok[k] - '0');
            }
            i = skip_ws(text, len, i + 1);
            while (idx < want) {
                if (i >= len || text[i] == ']') return 1;
                i = skip_ws(text, len, skip_value(text, len, i));
                if (i >= len || text[i] != ',') return 1;
                i = skip_ws(text, len, i + 1);
                idx++;
            }
            if (i >= len || text[i] == ']') return 1;
        } else {
            return 1;
        }
        *offset = i;
    }
    return 0;
}

void sb_json_offset_linecol(const char *text, size_t len, size_t offset, int *line, int *col)
{
    int l = 1, c = 1;
    if (offset > len) offset = len;
    for (size_t i = 0; i < offset; i++) {
        unsigned char b = (unsigned char)text[i];
        if (b == '\n') { l++; c = 1; }
        else if ((b & 0xC0) != 0x80) c++;  /* not a UTF-8 continuation byte */
    }
    *line = l;
    *col = c;
}

int sb_json_pointer_append(char *buf, size_t size, const char *token)
{
    size_t n = strlen(buf), need = 1;
    for (const char *t = token; *t; t++) need += (*t == '~' || *t == '/') ? 2 : 1;
    if (n + need + 1 > size) return -1;
    buf[n++] = '/';
    for (const char *t = token; *t; t++) {
        if (*t == '~') { buf[n++] = '~'; buf[n++] = '0'; }
        else if (*t == '/') { buf[n++] = '~'; buf[n++] = '1'; }
        else buf[n++] = *t;
    }
    buf[n] = '\0';
    return 0;
}
