/* sb_json_pos.h — where in the raw JSON text a value lives.
 *
 * jansson reports line/column only for syntax errors.  For semantic errors in
 * a scene file we locate the value named by a JSON pointer (RFC 6901, e.g.
 * "/boundary/2/on/0") by scanning the raw text, and convert the byte offset to
 * a 1-based line and column.  Columns count characters (UTF-8 continuation
 * bytes do not advance the column), the same convention as jansson's syntax
 * errors.  The scanner is iterative (no recursion), so any nesting depth and
 * any malformed text are safe. */
#ifndef SB_JSON_POS_H
#define SB_JSON_POS_H

#include <stddef.h>

/* Byte offset of the value at `pointer` ("" = the whole document).  With
 * at_key = 1 and a last token that names an object member, the offset of the
 * member's key string is returned instead of its value.  Returns 0 when the
 * pointer was found; 1 when it was not, with *offset set to the deepest
 * enclosing value that was found (best effort for messages). */
int sb_json_pointer_offset(const char *text, size_t len, const char *pointer, int at_key,
                           size_t *offset);

/* 1-based line and column of byte `offset` (clamped to len). */
void sb_json_offset_linecol(const char *text, size_t len, size_t offset, int *line, int *col);

/* Append `token` to the pointer in buf (escaping '~' as "~0" and '/' as "~1").
 * Returns 0, or -1 (buf unchanged) when it would not fit. */
int sb_json_pointer_append(char *buf, size_t size, const char *token);

#endif
