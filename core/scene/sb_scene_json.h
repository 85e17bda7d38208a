/* sb_scene_json.h — internal helpers of the scene parser: a parse context that
 * tracks the JSON pointer of the value being read, typed getters that validate
 * and report "FILE:LINE:COLUMN: at /json/path: what is wrong", and the section
 * parsers (one file each).  Not part of the public API. */
#ifndef SB_SCENE_JSON_H
#define SB_SCENE_JSON_H

#include <jansson.h>
#include <stddef.h>

#include "sb_scene.h"

#define SBJ_PTR_MAX 512

typedef struct sbj_ctx {
    const char *text;        /* raw file text (for positions) */
    size_t len;
    const char *file;        /* name used in messages */
    char *err;
    size_t errlen;
    char ptr[SBJ_PTR_MAX];   /* JSON pointer of the current object */
} sbj_ctx;

/* Report an error at the current pointer, extended by `key` (NULL: the
 * current value itself).  at_key = 1 points at the member's key instead of its
 * value (unknown keys).  Always returns SB_ERR_INPUT. */
int sbj_fail(sbj_ctx *c, const char *key, int at_key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* Descend into member `key` / element `idx`; returns the previous pointer
 * length for sbj_pop(). */
size_t sbj_push(sbj_ctx *c, const char *key);
size_t sbj_push_index(sbj_ctx *c, size_t idx);
void sbj_pop(sbj_ctx *c, size_t mark);

/* Human name of a JSON value's type ("number", "string", ...). */
const char *sbj_type_name(const json_t *v);

/* Reject members of obj not in the NULL-terminated list `allowed`. */
int sbj_check_keys(sbj_ctx *c, const json_t *obj, const char *const *allowed);

/* Member getters on object `obj` (the value at the current pointer).  When
 * the key is absent: required -> error "missing required key", otherwise the
 * output is left untouched and *present (if not NULL) is set to 0.
 * Numbers must be finite. */
int sbj_get_object(sbj_ctx *c, const json_t *obj, const char *key, int required,
                   json_t **out);
int sbj_get_array(sbj_ctx *c, const json_t *obj, const char *key, int required,
                  int nonempty, json_t **out);
int sbj_get_number(sbj_ctx *c, const json_t *obj, const char *key, int required,
                   double *out, int *present);
/* Integer in [lo, hi] (a real with an integral value is accepted). */
int sbj_get_int(sbj_ctx *c, const json_t *obj, const char *key, int required,
                long lo, long hi, long *out);
int sbj_get_bool(sbj_ctx *c, const json_t *obj, const char *key, int *out);
/* String of at most size-1 bytes. */
int sbj_get_string(sbj_ctx *c, const json_t *obj, const char *key, int required,
                   char *buf, size_t size, int *present);
/* String that must be one of `choices` (NULL-terminated); *index set. */
int sbj_get_choice(sbj_ctx *c, const json_t *obj, const char *key, int required,
                   const char *const *choices, int *index);
/* Array of exactly n finite numbers. */
int sbj_get_vec(sbj_ctx *c, const json_t *obj, const char *key, int required,
                int n, double *out, int *present);
/* Array value (already fetched) of exactly n numbers; pointer is the current
 * one (used for arrays of points). */
int sbj_vec_value(sbj_ctx *c, const json_t *v, int n, double *out);

/* Value checks on a member already read: report at /ptr/key. */
int sbj_require_positive(sbj_ctx *c, const char *key, double v);
int sbj_require_nonneg(sbj_ctx *c, const char *key, double v);

/* A name made of [A-Za-z0-9_.-], 1..SB_NAME_LEN-1 chars. */
int sbj_valid_name(const char *s);

/* ---- section parsers (sb_scene_*.c) ---------------------------------- */
int sbj_parse_domain(sbj_ctx *c, const json_t *root, sb_domain *d);
int sbj_parse_geometry(sbj_ctx *c, const json_t *root, const sb_domain *d, sb_chart *ch);
int sbj_parse_material(sbj_ctx *c, const json_t *root, sb_material_spec *m);
/* Optional array `key` of at most `max` objects: item(c, object, sc, index)
 * parses each (errors located at /key/index/...); *count counts the parsed
 * items.  `what` names the items in the "too many" message. */
typedef int (*sbj_item_fn)(sbj_ctx *c, const json_t *o, sb_scene *sc, size_t i);
int sbj_parse_list(sbj_ctx *c, const json_t *root, const char *key, const char *what, int max,
                   sbj_item_fn item, sb_scene *sc, int *count);

int sbj_parse_loads(sbj_ctx *c, const json_t *root, sb_scene *sc);
int sbj_parse_boundary(sbj_ctx *c, const json_t *root, sb_scene *sc);
int sbj_parse_time(sbj_ctx *c, const json_t *root, sb_time_spec *t);
int sbj_parse_probes(sbj_ctx *c, const json_t *root, sb_scene *sc);
int sbj_parse_reference(sbj_ctx *c, const json_t *root, sb_scene *sc);
/* "resolution" (N or [N, M]) of obj; untouched when absent */
int sbj_parse_resolution(sbj_ctx *c, const json_t *obj, const char *key, int *res, int *res_t);
int sbj_parse_methods(sbj_ctx *c, const json_t *root, sb_scene *sc);
/* "obstacles" and "contact" (sb_scene_contact.c); OBJ files resolved
 * relative to the directory of c->file */
int sbj_parse_obstacles(sbj_ctx *c, const json_t *root, sb_scene *sc);
/* Optional "schedule" of object o (sb_scene_schedule.c): keyframes validated
 * against the time spec tm (parsed before); *present set. */
int sbj_parse_schedule(sbj_ctx *c, const json_t *o, const sb_time_spec *tm, sb_schedule *sch, int *present);
void sbj_free_obstacles(sb_scene *sc);
/* Wavefront OBJ (v and f lines; polygons fanned into triangles): SB_OK or
 * SB_ERR_INPUT with "FILE:LINE: problem" in msg (sb_obj.c) */
int sb_obj_read(const char *path, double **verts, int *nv, int **tris, int *nt, char *msg, size_t msglen);

/* Parts: member "on" (edge names) and/or "at" (material points) of object
 * obj; edges_ok/points_ok say which are allowed; at least one part needed. */
int sbj_parse_parts(sbj_ctx *c, const json_t *obj, const sb_domain *d, int edges_ok,
                    int points_ok, sb_part *parts, int *n_parts);
/* A material point xi that must lie in the (closed) domain; fills st. */
int sbj_parse_point(sbj_ctx *c, const json_t *v, const sb_domain *d, double xi[2],
                    double st[2]);

/* Degrees in JSON, radians in memory. */
#define SBJ_DEG (3.14159265358979323846 / 180.0)

#endif
