/* sb_scene_json.c — parse context and validating getters of the scene parser.
 * Every error names FILE:LINE:COLUMN (found by sb_json_pos.c from the JSON
 * pointer of the offending value), the pointer, and what is wrong. */
#include "sb_scene_json.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "sb_json_pos.h"

int sbj_fail(sbj_ctx *c, const char *key, int at_key, const char *fmt, ...)
{
    char ptr[SBJ_PTR_MAX], msg[512];
    size_t off = 0;
    int line, col;
    va_list ap;

    snprintf(ptr, sizeof ptr, "%s", c->ptr);
    if (key && sb_json_pointer_append(ptr, sizeof ptr, key) != 0) at_key = 0;
    if (!c->text || sb_json_pointer_offset(c->text, c->len, ptr, at_key, &off) != 0) {
        /* not found (should not happen for parsed JSON): point at the parent */
        if (c->text) sb_json_pointer_offset(c->text, c->len, c->ptr, 0, &off);
    }
    sb_json_offset_linecol(c->text ? c->text : "", c->text ? c->len : 0, off, &line, &col);
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (c->err && c->errlen)
        snprintf(c->err, c->errlen, "%s:%d:%d: at %s: %s", c->file, line, col,
                 ptr[0] ? ptr : "/", msg);
    return SB_ERR_INPUT;
}

size_t sbj_push(sbj_ctx *c, const char *key)
{
    size_t mark = strlen(c->ptr);
    /* on overflow the pointer stays at the parent: messages remain valid */
    (void)sb_json_pointer_append(c->ptr, sizeof c->ptr, key);
    return mark;
}

size_t sbj_push_index(sbj_ctx *c, size_t idx)
{
    char tok[32];
    snprintf(tok, sizeof tok, "%zu", idx);
    return sbj_push(c, tok);
}

void sbj_pop(sbj_ctx *c, size_t mark)
{
    if (mark < sizeof c->ptr) c->ptr[mark] = '\0';
}

const char *sbj_type_name(const json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return "an object";
    case JSON_ARRAY: return "an array";
    case JSON_STRING: return "a string";
    case JSON_INTEGER:
    case JSON_REAL: return "a number";
    case JSON_TRUE:
    case JSON_FALSE: return "a boolean";
    case JSON_NULL: return "null";
    }
    return "an unknown value";
}

int sbj_check_keys(sbj_ctx *c, const json_t *obj, const char *const *allowed)
{
    const char *key;
    json_t *val;
    json_object_foreach((json_t *)obj, key, val) {
        int ok = 0;
        for (const char *const *a = allowed; *a; a++)
            if (strcmp(*a, key) == 0) { ok = 1; break; }
        if (!ok) {
            char list[400];
            size_t n = 0;
            list[0] = '\0';
            for (const char *const *a = allowed; *a && n < sizeof list; a++)
                n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", a == allowed ? "" : ", ", *a);
            return sbj_fail(c, key, 1, "unknown key \"%.80s\" (expected one of: %s)", key, list);
        }
    }
    return SB_OK;
}

/* Fetch member; 1 = present, 0 = absent (ok), <0 = error (missing required). */
static int member(sbj_ctx *c, const json_t *obj, const char *key, int required, json_t **v)
{
    *v = json_object_get(obj, key);
    if (*v) return 1;
    if (required) return sbj_fail(c, NULL, 0, "missing required key \"%s\"", key);
    return 0;
}

int sbj_get_object(sbj_ctx *c, const json_t *obj, const char *key, int required, json_t **out)
{
    json_t *v;
    int r = member(c, obj, key, required, &v);
    *out = NULL;
    if (r <= 0) return r;
    if (!json_is_object(v)) return sbj_fail(c, key, 0, "must be an object, got %s", sbj_type_name(v));
    *out = v;
    return SB_OK;
}

int sbj_get_array(sbj_ctx *c, const json_t *obj, const char *key, int required, int nonempty,
                  json_t **out)
{
    json_t *v;
    int r = member(c, obj, key, required, &v);
    *out = NULL;
    if (r <= 0) return r;
    if (!json_is_array(v)) return sbj_fail(c, key, 0, "must be an array, got %s", sbj_type_name(v));
    if (nonempty && json_array_size(v) == 0) return sbj_fail(c, key, 0, "must not be empty");
    *out = v;
    return SB_OK;
}

static int number_value(sbj_ctx *c, const char *key, const json_t *v, double *out)
{
    if (!json_is_number(v)) return sbj_fail(c, key, 0, "must be a number, got %s", sbj_type_name(v));
    double x = json_number_value(v);
    if (!isfinite(x)) return sbj_fail(c, key, 0, "must be a finite number");
    *out = x;
    return SB_OK;
}

int sbj_get_number(sbj_ctx *c, const json_t *obj, const char *key, int required, double *out,
                   int *present)
{
    json_t *v;
    int r = member(c, obj, key, required, &v);
    if (present) *present = r > 0;
    if (r <= 0) return r;
    return number_value(c, key, v, out);
}

int sbj_get_int(sbj_ctx *c, const json_t *obj, const char *key, int required, long lo, long hi,
                long *out)
{
    json_t *v;
    int r = member(c, obj, key, required, &v);
    if (r <= 0) return r;
    if (json_is_integer(v)) {
        json_int_t x = json_integer_value(v);
        if (x < lo || x > hi)
            return sbj_fail(c, key, 0, "must be an integer in [%ld, %ld], got %lld", lo, hi, (long long)x);
        *out = (long)x;
        return SB_OK;
    }
    if (json_is_real(v)) {
        double x = json_real_value(v);
        if (!isfinite(x) || x != floor(x))
            return sbj_fail(c, key, 0, "must be an integer, got %g", x);
        if (x < (double)lo || x > (double)hi)
            return sbj_fail(c, key, 0, "must be an integer in [%ld, %ld], got %g", lo, hi, x);
        *out = (long)x;
        return SB_OK;
    }
    return sbj_fail(c, key, 0, "must be an integer, got %s", sbj_type_name(v));
}

int sbj_get_bool(sbj_ctx *c, const json_t *obj, const char *key, int *out)
{
    json_t *v;
    int r = member(c, obj, key, 0, &v);
    if (r <= 0) return r;
    if (!json_is_boolean(v)) return sbj_fail(c, key, 0, "must be true or false, got %s", sbj_type_name(v));
    *out = json_is_true(v);
    return SB_OK;
}

int sbj_get_string(sbj_ctx *c, const json_t *obj, const char *key, int required, char *buf,
                   size_t size, int *present)
{
    json_t *v;
    int r = member(c, obj, key, required, &v);
    if (present) *present = r > 0;
    if (r <= 0) return r;
    if (!json_is_string(v)) return sbj_fail(c, key, 0, "must be a string, got %s", sbj_type_name(v));
    size_t n = json_string_length(v);
    if (n >= size) return sbj_fail(c, key, 0, "too long (%zu bytes, at most %zu)", n, size - 1);
    if (strlen(json_string_value(v)) != n) return sbj_fail(c, key, 0, "must not contain a NUL character");
    memcpy(buf, json_string_value(v), n + 1);
    return SB_OK;
}

int sbj_get_choice(sbj_ctx *c, const json_t *obj, const char *key, int required,
                   const char *const *choices, int *index)
{
    char s[SB_NAME_LEN];
    json_t *v;
    int r = member(c, obj, key, required, &v);
    if (r <= 0) return r;
    if (!json_is_string(v)) return sbj_fail(c, key, 0, "must be a string, got %s", sbj_type_name(v));
    snprintf(s, sizeof s, "%s", json_string_value(v));
    for (int i = 0; choices[i]; i++)
        if (strcmp(choices[i], json_string_value(v)) == 0) { *index = i; return SB_OK; }
    char list[300];
    size_t n = 0;
    list[0] = '\0';
    for (int i = 0; choices[i] && n < sizeof list; i++)
        n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", i ? ", " : "", choices[i]);
    return sbj_fail(c, key, 0, "unknown value \"%s\" (expected one of: %s)", s, list);
}

int sbj_vec_value(sbj_ctx *c, const json_t *v, int n, double *out)
{
    if (!json_is_array(v) || json_array_size(v) != (size_t)n)
        return sbj_fail(c, NULL, 0, "must be an array of %d numbers, got %s%s", n, sbj_type_name(v),
                        json_is_array(v) ? (json_array_size(v) < (size_t)n ? " that is too short"
                                                                             : " that is too long")
                                         : "");
    for (int i = 0; i < n; i++) {
        char tok[16];
        snprintf(tok, sizeof tok, "%d", i);
        int r = number_value(c, tok, json_array_get(v, (size_t)i), &out[i]);
        if (r) return r;
    }
    return SB_OK;
}

int sbj_get_vec(sbj_ctx *c, const json_t *obj, const char *key, int required, int n, double *out,
                int *present)
{
    json_t *v;
    int r = member(c, obj, key, required, &v);
    if (present) *present = r > 0;
    if (r <= 0) return r;
    size_t mark = sbj_push(c, key);
    r = sbj_vec_value(c, v, n, out);
    sbj_pop(c, mark);
    return r;
}

int sbj_require_positive(sbj_ctx *c, const char *key, double v)
{
    if (v > 0) return SB_OK;
    return sbj_fail(c, key, 0, "must be > 0, got %g", v);
}

int sbj_require_nonneg(sbj_ctx *c, const char *key, double v)
{
    if (v >= 0) return SB_OK;
    return sbj_fail(c, key, 0, "must be >= 0, got %g", v);
}

int sbj_valid_name(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n >= SB_NAME_LEN) return 0;
    for (; *s; s++) {
        char ch = *s;
        if (!((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
              ch == '_' || ch == '-' || ch == '.'))
            return 0;
    }
    return 1;
}

int sbj_parse_list(sbj_ctx *c, const json_t *root, const char *key, const char *what, int max,
                   sbj_item_fn item, sb_scene *sc, int *count)
{
    json_t *arr, *o;
    size_t i;
    int r = sbj_get_array(c, root, key, 0, 0, &arr);
    if (r || !arr) return r;
    if (json_array_size(arr) > (size_t)max)
        return sbj_fail(c, key, 0, "too many %s: %zu (at most %d)", what, json_array_size(arr), max);
    size_t mark = sbj_push(c, key);
    json_array_foreach(arr, i, o) {
        size_t m2 = sbj_push_index(c, i);
        r = item(c, o, sc, i);
        sbj_pop(c, m2);
        if (r) break;
        (*count)++;
    }
    sbj_pop(c, mark);
    return r;
}
