/* sb_study_parse.h — internal to the study parser (sb_study_json.c,
 * sb_study_check.c): section helpers on the scene parser's context. */
#ifndef SB_STUDY_PARSE_H
#define SB_STUDY_PARSE_H

#include "sb_scene_json.h"
#include "sb_study_int.h"

/* "set" member of obj as "key=value" assignments (keys with the prefixes). */
int sbs_parse_sets(sbj_ctx *c, const json_t *obj, const char *key, const char *const *prefixes,
                   sb_study_sets *out);
/* Increasing integers in [lo, hi], at most max, into out (*n of them). */
int sbs_parse_longs(sbj_ctx *c, const json_t *obj, const char *key, long lo, long hi, int max, long *out, int *n);
/* "rules": scope, parameters, resolutions, skips. */
int sbs_parse_rules(sbj_ctx *c, const json_t *root, sb_study *st);
/* Every parameter against every method and solver it reaches; combinations
 * that cannot run. */
int sbs_check(sbj_ctx *c, const json_t *root, sb_study *st);

#endif
