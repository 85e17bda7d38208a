/* test_lf_common.h — helpers shared by the tests/test_lf*.c binaries: build a
 * linear_fem method state from an inline JSON scene, sparse Hessians, steps. */
#ifndef TEST_LF_COMMON_H
#define TEST_LF_COMMON_H

#include "sb_test.h"
#include "../methods/linear_fem/lf.h"

#include <stdlib.h>
#include <string.h>

typedef struct tl_method {
    sb_scene scene;
    sb_paramset ps;
    lf_state *S;
} tl_method;

/* Parse json, register the method parameters, apply "key=value" overrides
 * (NULL-terminated) and create the method.  Returns the create status. */
static inline int tl_create(tl_method *m, const char *json, int res, int levels, const char *const *sets)
{
    char err[1024];
    memset(m, 0, sizeof *m);
    if (sb_scene_parse_string(json, "inline.json", &m->scene, err, sizeof err)) {
        printf("    scene: %s\n", err);
        return SB_ERR_INPUT;
    }
    sb_paramset_init(&m->ps);
    sb_paramset_add(&m->ps, "method", sb_method_linear_fem.params);
    for (int i = 0; sets && sets[i]; i++)
        if (sb_paramset_set(&m->ps, sets[i], err, sizeof err)) {
            printf("    param: %s\n", err);
            return SB_ERR_INPUT;
        }
    m->S = calloc(1, sb_method_linear_fem.state_size);
    if (!m->S) return SB_ERR_NOMEM;
    sb_method_config cfg = { res, levels, &m->ps, NULL };
    int rc = sb_method_linear_fem.create(m->S, &m->scene, &cfg);
    if (rc) { free(m->S); m->S = NULL; }
    return rc;
}

static inline void tl_free(tl_method *m)
{
    if (m->S) {
        sb_method_linear_fem.destroy(m->S);
        free(m->S);
    }
    sb_scene_free(&m->scene);
    memset(m, 0, sizeof *m);
}

/* deterministic uniform numbers in [-1, 1) */
static inline double tl_rand(unsigned long long *st)
{
    *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*st >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

static inline void tl_step(tl_method *m, double load, double motion)
{
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1;
    si.n_steps = 1;
    for (int k = 0; k < SB_SCENE_MAX_LOADS; k++) si.load_factor[k] = load;
    for (int k = 0; k < SB_SCENE_MAX_BCS; k++) si.motion_factor[k] = motion;
    sb_method_linear_fem.set_step(m->S, &si);
}

typedef struct tl_sys { sb_pattern *pat; sb_matrix H; } tl_sys;

static inline int tl_sys_init(tl_sys *s, lf_state *S, int level)
{
    int n = sb_method_linear_fem.n_dofs(S, level), bs = sb_method_linear_fem.block_size(S, level);
    sb_pattern_builder *pb = sb_pattern_builder_new(n / bs, bs);
    if (!pb) return SB_ERR_NOMEM;
    int rc = sb_method_linear_fem.pattern(S, level, pb);
    int rc2 = sb_pattern_builder_finish(pb, &s->pat);
    if (rc || rc2) return rc ? rc : rc2;
    return sb_matrix_init(&s->H, s->pat);
}
static inline void tl_sys_free(tl_sys *s)
{
    sb_matrix_free(&s->H);
    sb_pattern_free(s->pat);
}

#define TL_SCENE(domain, geometry, material, boundary, loads)                                   \
    "{\"name\": \"t\", \"domain\": " domain ", \"geometry\": " geometry ", \"material\": " material \
    ", \"boundary\": " boundary ", \"loads\": " loads                                          \
    ", \"time\": {\"mode\": \"quasi_static\", \"steps\": 1}}"

#define TL_STVK "{\"model\": \"stvk\", \"young\": 1e5, \"poisson\": 0.3, \"thickness\": 0.01, \"density\": 0.5}"
#define TL_DENIM "{\"model\": \"denim\", \"warp_angle\": 30}"
#define TL_RECT "{\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1.0, 0.6]}"
#define TL_PLANE "{\"type\": \"plane\"}"
#define TL_CYL "{\"type\": \"cylinder\", \"radius\": 0.3, \"angle\": [-40, 40], \"length\": 0.6}"

#endif
