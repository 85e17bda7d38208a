/* test_bhem_common.h — helpers shared by the tests/test_bhem*.c binaries:
 * build a BHEM method state from an inline JSON scene. */
#ifndef TEST_BHEM_COMMON_H
#define TEST_BHEM_COMMON_H

#include "sb_test.h"
#include "../methods/bhem/bhem.h"

#include <stdlib.h>
#include <string.h>

typedef struct tb_method {
    sb_scene scene;
    sb_paramset ps;
    bhem_state *S;
} tb_method;

/* Parse `json`, register the method parameters, apply "key=value" overrides
 * (NULL-terminated, may be NULL) and create the method.  Returns the create
 * status (or SB_ERR_INPUT when the scene does not parse). */
static inline int tb_create(tb_method *m, const char *json, int res, int levels, const char *const *sets)
{
    char err[1024];
    memset(m, 0, sizeof *m);
    if (sb_scene_parse_string(json, "inline.json", &m->scene, err, sizeof err)) {
        printf("    scene: %s\n", err);
        return SB_ERR_INPUT;
    }
    sb_paramset_init(&m->ps);
    sb_paramset_add(&m->ps, "method", sb_method_bhem.params);
    for (int i = 0; sets && sets[i]; i++)
        if (sb_paramset_set(&m->ps, sets[i], err, sizeof err)) {
            printf("    param: %s\n", err);
            return SB_ERR_INPUT;
        }
    m->S = calloc(1, sb_method_bhem.state_size);
    if (!m->S) return SB_ERR_NOMEM;
    sb_method_config cfg = { res, levels, &m->ps, NULL, 0 };
    int rc = sb_method_bhem.create(m->S, &m->scene, &cfg);
    if (rc) { free(m->S); m->S = NULL; }
    return rc;
}

static inline void tb_free(tb_method *m)
{
    if (m->S) {
        sb_method_bhem.destroy(m->S);
        free(m->S);
    }
    sb_scene_free(&m->scene);
    memset(m, 0, sizeof *m);
}

/* deterministic uniform numbers in [-1, 1) */
static inline double tb_rand(unsigned long long *st)
{
    *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*st >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/* a scene with a chosen domain/geometry/material/boundary/loads body */
#define TB_SCENE(domain, geometry, material, boundary, loads)                                   \
    "{\"name\": \"t\", \"domain\": " domain ", \"geometry\": " geometry ", \"material\": " material \
    ", \"boundary\": " boundary ", \"loads\": " loads                                          \
    ", \"time\": {\"mode\": \"quasi_static\", \"steps\": 1}}"

#define TB_STVK "{\"model\": \"stvk\", \"young\": 1e5, \"poisson\": 0.3, \"thickness\": 0.01, \"density\": 0.5}"
#define TB_RECT "{\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1.0, 0.6]}"
#define TB_PLANE "{\"type\": \"plane\"}"

#endif
