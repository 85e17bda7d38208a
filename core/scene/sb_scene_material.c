/* sb_scene_material.c — the "material" section of a scene file.
 *
 *   {"model": "stvk", "young": Pa, "poisson": -, "thickness": m,
 *    "density": kg/m^2, "warp_angle": deg}
 *   {"model": "denim", "thickness": m, "density": kg/m^2, "warp_angle": deg,
 *    "k": {"1": Pa, ...} or [k1, k2, k3, k4], "d": {"1": n, ...} or [d1..d4],
 *    "mu": {"12": -, ...}, "alpha": {"11": -, ...}}
 *
 * denim defaults are the RMTR paper's Table 1 (sb_material_spec_denim): every
 * entry may be overridden.  mu_j1 is not in Table 1; unless a scene gives it
 * explicitly it is recomputed as mu_j1 = 1 - sum_{i=2..d_j} mu_ji so that
 * phi_j'(0) = 1 (RMTR Eq. 3.4; assumption documented in sb_material.c). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sb_scene_json.h"
#include "sb_material.h"

/* "k"/"d": an array of 4 numbers or an object with keys "1".."4". */
static int parse_per_direction(sbj_ctx *c, const json_t *mat, const char *key, int integer,
                               double out[4], int given[4])
{
    json_t *v = json_object_get(mat, key);
    size_t mark;
    int r = SB_OK;
    memset(given, 0, 4 * sizeof(int));
    if (!v) return SB_OK;
    mark = sbj_push(c, key);
    if (json_is_array(v)) {
        if (json_array_size(v) != 4) {
            r = sbj_fail(c, NULL, 0, "must be an array of 4 numbers (directions 1..4) or an object "
                                     "with keys \"1\"..\"4\"");
            goto out;
        }
        for (int j = 0; j < 4 && !r; j++) {
            json_t *e = json_array_get(v, (size_t)j);
            char tok[16];
            snprintf(tok, sizeof tok, "%d", j);
            if (!json_is_number(e)) r = sbj_fail(c, tok, 0, "must be a number, got %s", sbj_type_name(e));
            else { out[j] = json_number_value(e); given[j] = 1; }
        }
    } else if (json_is_object(v)) {
        const char *k;
        json_t *e;
        json_object_foreach(v, k, e) {
            if (!(k[0] >= '1' && k[0] <= '4' && k[1] == '\0')) {
                r = sbj_fail(c, k, 1, "unknown key \"%.40s\" (expected one of: 1, 2, 3, 4)", k);
                goto out;
            }
            if (!json_is_number(e)) {
                r = sbj_fail(c, k, 0, "must be a number, got %s", sbj_type_name(e));
                goto out;
            }
            out[k[0] - '1'] = json_number_value(e);
            given[k[0] - '1'] = 1;
        }
    } else {
        r = sbj_fail(c, NULL, 0, "must be an array of 4 numbers or an object, got %s", sbj_type_name(v));
        goto out;
    }
    for (int j = 0; j < 4 && !r; j++) {
        if (!given[j]) continue;
        char tok[16];
        snprintf(tok, sizeof tok, "%d", json_is_array(v) ? j : j + 1);
        if (!isfinite(out[j])) r = sbj_fail(c, tok, 0, "must be a finite number");
        else if (!integer && !(out[j] > 0)) r = sbj_fail(c, tok, 0, "k_%d must be > 0 Pa, got %g", j + 1, out[j]);
        else if (integer && (out[j] != floor(out[j]) || out[j] < 1 || out[j] > SB_DENIM_MAX_TERMS))
            r = sbj_fail(c, tok, 0, "d_%d must be an integer in [1, %d], got %g", j + 1,
                         SB_DENIM_MAX_TERMS, out[j]);
    }
out:
    sbj_pop(c, mark);
    return r;
}

/* "mu"/"alpha": object with keys "ji" (j = 1..4, i = 1..5). */
static int parse_terms(sbj_ctx *c, const json_t *mat, const char *key, const int d[4],
                       double tab[4][SB_DENIM_MAX_TERMS], int given[4][SB_DENIM_MAX_TERMS])
{
    json_t *v = json_object_get(mat, key), *e;
    const char *k;
    size_t mark;
    int r = SB_OK;
    if (!v) return SB_OK;
    if (!json_is_object(v))
        return sbj_fail(c, key, 0, "must be an object with keys \"ji\" (e.g. \"12\" for %s_12), got %s",
                        key, sbj_type_name(v));
    mark = sbj_push(c, key);
    json_object_foreach(v, k, e) {
        if (!(k[0] >= '1' && k[0] <= '4' && k[1] >= '1' && k[1] <= '0' + SB_DENIM_MAX_TERMS &&
              k[2] == '\0')) {
            r = sbj_fail(c, k, 1, "unknown key \"%.40s\" (expected \"ji\" with direction j in 1..4 and "
                                  "term i in 1..%d)", k, SB_DENIM_MAX_TERMS);
            break;
        }
        int j = k[0] - '1', i = k[1] - '1';
        if (!json_is_number(e) || !isfinite(json_number_value(e))) {
            r = sbj_fail(c, k, 0, "must be a finite number, got %s", sbj_type_name(e));
            break;
        }
        if (i >= d[j]) {
            r = sbj_fail(c, k, 1, "%s_%s is not used: d_%d = %d", key, k, j + 1, d[j]);
            break;
        }
        tab[j][i] = json_number_value(e);
        given[j][i] = 1;
    }
    sbj_pop(c, mark);
    return r;
}

static int parse_denim(sbj_ctx *c, const json_t *mat, sb_material_spec *m)
{
    static const char *const keys[] = { "model", "thickness", "density", "warp_angle", "k", "d",
                                        "mu", "alpha", "beyond_fit", NULL };
    static const char *const beyond[] = { "extend", "inadmissible", NULL };
    sb_denim_params *p = &m->denim;
    double k[4], dd[4];
    int kg[4], dg[4], mug[4][SB_DENIM_MAX_TERMS] = { { 0 } }, alg[4][SB_DENIM_MAX_TERMS] = { { 0 } };
    int r;

    if ((r = sbj_check_keys(c, mat, keys))) return r;
    sb_material_spec_denim(m);               /* RMTR paper Table 1 */
    if ((r = parse_per_direction(c, mat, "k", 0, k, kg))) return r;
    if ((r = parse_per_direction(c, mat, "d", 1, dd, dg))) return r;
    for (int j = 0; j < 4; j++) {
        if (kg[j]) p->k[j] = k[j];
        if (dg[j]) {
            /* terms beyond a lowered d_j are dropped */
            p->d[j] = (int)dd[j];
            for (int i = p->d[j]; i < SB_DENIM_MAX_TERMS; i++) p->mu[j][i] = p->alpha[j][i] = 0;
        }
    }
    if ((r = parse_terms(c, mat, "mu", p->d, p->mu, mug))) return r;
    if ((r = parse_terms(c, mat, "alpha", p->d, p->alpha, alg))) return r;
    if (json_object_get(mat, "beyond_fit") && (r = sbj_get_choice(c, mat, "beyond_fit", 0, beyond, &p->beyond_fit)))
        return r;
    for (int j = 0; j < 4; j++) {
        /* ASSUMPTION (Table 1 omits mu_j1): mu_j1 = 1 - sum_{i>=2} mu_ji
         * (phi_j'(0) = 1, RMTR Eq. 3.4) unless the scene gives mu_j1. */
        if (!mug[j][0]) {
            double s = 0;
            for (int i = 1; i < p->d[j]; i++) s += p->mu[j][i];
            p->mu[j][0] = 1 - s;
        }
        for (int i = 0; i < p->d[j]; i++) {
            /* Eq. (3.4) divides by alpha_ji */
            if (p->alpha[j][i] == 0)
                return sbj_fail(c, alg[j][i] ? "alpha" : (dg[j] ? "d" : "alpha"), 0,
                                "alpha_%d%d must be given and nonzero (d_%d = %d)", j + 1, i + 1,
                                j + 1, p->d[j]);
        }
    }
    return SB_OK;
}

static int parse_stvk(sbj_ctx *c, const json_t *mat, sb_material_spec *m)
{
    static const char *const keys[] = { "model", "young", "poisson", "thickness", "density",
                                        "warp_angle", NULL };
    int r;
    if ((r = sbj_check_keys(c, mat, keys))) return r;
    if ((r = sbj_get_number(c, mat, "young", 1, &m->young, NULL))) return r;
    if ((r = sbj_require_positive(c, "young", m->young))) return r;
    if ((r = sbj_get_number(c, mat, "poisson", 1, &m->poisson, NULL))) return r;
    /* BHEM paper Eq. (8): plane-stress Lame constants need nu in (-1, 0.5] */
    if (!(m->poisson > -1 && m->poisson <= 0.5))
        return sbj_fail(c, "poisson", 0, "must be in (-1, 0.5], got %g", m->poisson);
    if ((r = sbj_get_number(c, mat, "thickness", 1, &m->thickness, NULL))) return r;
    return sbj_get_number(c, mat, "density", 1, &m->density, NULL);
}

int sbj_parse_material(sbj_ctx *c, const json_t *root, sb_material_spec *m)
{
    static const char *const models[] = { "stvk", "denim", NULL };
    json_t *mat;
    int model = 0, r;
    double warp = 0;
    size_t mark;

    if ((r = sbj_get_object(c, root, "material", 1, &mat))) return r;
    mark = sbj_push(c, "material");
    memset(m, 0, sizeof *m);
    if ((r = sbj_get_choice(c, mat, "model", 1, models, &model))) goto out;
    m->kind = model == 0 ? SB_MAT_STVK : SB_MAT_DENIM;
    r = m->kind == SB_MAT_STVK ? parse_stvk(c, mat, m) : parse_denim(c, mat, m);
    if (r) goto out;
    /* denim: thickness and density default to Table 1; present keys override */
    if ((r = sbj_get_number(c, mat, "thickness", 0, &m->thickness, NULL))) goto out;
    if ((r = sbj_require_positive(c, "thickness", m->thickness))) goto out;
    if ((r = sbj_get_number(c, mat, "density", 0, &m->density, NULL))) goto out;
    if ((r = sbj_require_nonneg(c, "density", m->density))) goto out;
    if ((r = sbj_get_number(c, mat, "warp_angle", 0, &warp, NULL))) goto out;
    if (!(fabs(warp) <= 360)) {
        r = sbj_fail(c, "warp_angle", 0, "must be in [-360, 360] degrees, got %g", warp);
        goto out;
    }
    m->warp_angle = warp * SBJ_DEG;
out:
    sbj_pop(c, mark);
    return r;
}
