/* sb_record_reference.c — reference records: whether a record may serve as
 * the reference of a scene and a sample grid, and the field error against
 * it (sb_reference.h). */
#include "sb_reference.h"
#include "sb_record_io.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Members of a scene that do not change its solution.  The name is one of
 * them: a copy of a scene under another name keeps its reference, and the
 * check made by `check` and at the start of a run (sb_reference_check,
 * which compares the parsed problem) and the one made when the error is
 * computed here must give the same verdict. */
static const char *const not_the_problem[] = { "name", "description", "resolution", "methods", "reference", "probes",
                                               NULL };

static json_t *problem_of(const char *text)
{
    json_error_t e;
    json_t *o = text ? json_loads(text, JSON_DECODE_ANY, &e) : NULL;
    if (!o) return NULL;
    if (!json_is_object(o)) {
        json_decref(o);
        return NULL;
    }
    for (const char *const *k = not_the_problem; *k; k++) json_object_del(o, *k);
    return o;
}

int sb_scene_same_problem(const char *json_a, const char *json_b, char *why, size_t whylen)
{
    if (why && whylen) why[0] = 0;
    json_t *a = problem_of(json_a), *b = problem_of(json_b);
    int same = -1;
    if (a && b) {
        same = json_equal(a, b) ? 1 : 0;
        if (!same && why && whylen) {
            const char *key;
            json_t *va;
            json_object_foreach(a, key, va) {
                if (!json_equal(va, json_object_get(b, key))) {
                    snprintf(why, whylen, "/%s", key);
                    break;
                }
            }
            if (!why[0]) json_object_foreach(b, key, va) {
                if (!json_object_get(a, key)) {
                    snprintf(why, whylen, "/%s", key);
                    break;
                }
            }
        }
    }
    json_decref(a);
    json_decref(b);
    return same;
}

void sb_refrec_free(sb_refrec *ref)
{
    if (!ref) return;
    free(ref->st);
    free(ref->pos);
    ref->st = ref->pos = NULL;
    ref->n = 0;
}

/* Grid parameters written with %.17g and read back are bit-identical; the
 * tolerance only absorbs a grid computed by another expression. */
#define ST_TOL 1e-12

int sb_reference_sealed(const char *path, int allow_unsealed, char *err, size_t errlen)
{
    int sealed = 0;
    int rc = sb_record_verify(path, &sealed, err, errlen);   /* a sealed file's checksum must match */
    if (rc || sealed || allow_unsealed) return rc;
    snprintf(err, errlen, "reference %s carries no checksum (a record written before checksums, format version 1), so "
             "a damaged copy could not be told from a good one: regenerate it with `shellbench reference SCENE "
             "--force`, or pass --allow-unsealed-reference to use it unverified", path);
    return SB_ERR_INPUT;
}

int sb_refrec_load(const char *path, const char *scene_name, const char *scene_json, int n,
                   const double *st, sb_refrec *ref, char *err, size_t errlen)
{
    return sb_refrec_load_opt(path, scene_name, scene_json, n, st, 0, ref, err, errlen);
}

int sb_refrec_load_opt(const char *path, const char *scene_name, const char *scene_json, int n,
                       const double *st, int allow_unsealed, sb_refrec *ref, char *err, size_t errlen)
{
    (void)scene_name;   /* the problem decides, not the name (not_the_problem) */
    memset(ref, 0, sizeof *ref);
    ref->energy = NAN;
    snprintf(ref->path, sizeof ref->path, "%s", path);
    sb_record_setup su;
    sb_record_summary sm;
    char msg[1536], why[256];
    int rc = sb_reference_sealed(path, allow_unsealed, msg, sizeof msg);
    if (rc) {
        snprintf(err, errlen, "reference %s refused: %s", path, msg);
        return rc;
    }
    rc = sb_record_read_setup(path, &su, msg, sizeof msg);
    if (rc) {
        snprintf(err, errlen, "reference %s refused: %s", path, msg);
        return rc;
    }
    rc = sb_record_read_summary(path, &sm, msg, sizeof msg);
    if (rc) {
        snprintf(err, errlen, "reference %s refused: %s", path, msg);
        sb_record_setup_free(&su);
        return rc;
    }
    snprintf(ref->scene, sizeof ref->scene, "%s", su.scene);
    snprintf(ref->method, sizeof ref->method, "%s", su.method);
    snprintf(ref->solver, sizeof ref->solver, "%s", su.solver);
    ref->res = su.res;
    ref->levels = su.levels;
    ref->dofs = sm.dofs;
    ref->energy = sm.energy_final;
    rc = SB_ERR_INPUT;
    int same;
    if (sm.status == SB_STATUS_UNFINISHED) {
        snprintf(err, errlen, "reference %s refused: it is the checkpoint of an unfinished run (%d of %d steps done), "
                 "not a finished record", path, sm.steps, sm.steps_planned);
    } else if (sm.status != 0) {
        snprintf(err, errlen, "reference %s refused: its run did not converge (%s after %d of %d steps)", path,
                 sm.reason_name, sm.steps, sm.steps_planned);
    } else if ((same = sb_scene_same_problem(su.scene_json, scene_json, why, sizeof why)) != 1) {
        if (same < 0)
            snprintf(err, errlen, "reference %s refused: its scene text or the scene's is not a JSON object", path);
        else
            snprintf(err, errlen, "reference %s refused: it was computed for scene \"%s\" with another problem "
                     "(%s differs from the scene's)", path, su.scene, why);
    } else if ((rc = sb_record_read_samples(path, &ref->n, &ref->st, &ref->pos, msg, sizeof msg)) != SB_OK) {
        snprintf(err, errlen, "reference %s refused: %s", path, msg);
    } else if (ref->n != n) {
        rc = SB_ERR_INPUT;
        snprintf(err, errlen, "reference %s refused: it samples %d material points, the run %d "
                 "(another sample grid: make both with the same --samples)", path, ref->n, n);
    } else {
        for (int i = 0; i < 2 * n && rc == SB_OK; i++)
            if (!(fabs(ref->st[i] - st[i]) <= ST_TOL)) {
                rc = SB_ERR_INPUT;
                snprintf(err, errlen, "reference %s refused: its sample point %d is (s,t) = (%.17g, %.17g), "
                         "the run's (%.17g, %.17g) (another sample grid)", path, i / 2, ref->st[i & ~1],
                         ref->st[i | 1], st[i & ~1], st[i | 1]);
            }
    }
    sb_record_setup_free(&su);
    sb_record_summary_free(&sm);
    if (rc) sb_refrec_free(ref);
    return rc;
}

void sb_field_error(int n, const double *pos, const double *ref, double diam, double *rms, double *max)
{
    double s2 = 0, mx = 0;
    for (int i = 0; i < n; i++) {
        double d2 = 0;
        for (int k = 0; k < 3; k++) d2 += (pos[3 * i + k] - ref[3 * i + k]) * (pos[3 * i + k] - ref[3 * i + k]);
        s2 += d2;
        mx = fmax(mx, sqrt(d2));
    }
    *rms = n > 0 ? sqrt(s2 / n) / diam : NAN;
    *max = n > 0 ? mx / diam : NAN;
}

int sb_record_read_probes(const char *path, int *n, char (**names)[SB_NAME_LEN], double **pos, char *err,
                          size_t errlen)
{
    *n = 0;
    *names = NULL;
    *pos = NULL;
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    hsize_t dt[3];
    double *traj = NULL;
    int rc = sb_h5r_open(&r, &f);
    if (!rc) rc = sb_h5r_dset(&r, f, "/probes/trajectory", 3, H5T_NATIVE_DOUBLE, sizeof(double), dt, (void **)&traj);
    if (!rc && (dt[2] != 3 || dt[0] < 1 || dt[1] > 100000)) rc = sb_h5r_fail(&r, SB_ERR_INPUT, "bad shape of", "/probes/trajectory");
    int np = rc ? 0 : (int)dt[1];
    if (!rc) {
        *names = calloc((size_t)(np ? np : 1), sizeof **names);
        *pos = malloc((size_t)(np ? np : 1) * 3 * sizeof **pos);
        if (!*names || !*pos) {
            rc = SB_ERR_NOMEM;
            snprintf(err, errlen, "out of memory reading %s", path);
        }
    }
    if (!rc && np > 0) {
        hid_t ds = H5Dopen2(f, "/probes/names", H5P_DEFAULT);
        hid_t t = sb_h5w_str_type(SB_NAME_LEN);
        if (ds < 0 || t < 0 || H5Dread(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, *names) < 0)
            rc = sb_h5r_fail(&r, SB_ERR_INPUT, "cannot read", "/probes/names");
        if (t >= 0) H5Tclose(t);
        if (ds >= 0) H5Dclose(ds);
        for (int p = 0; p < np; p++) (*names)[p][SB_NAME_LEN - 1] = 0;
    }
    if (!rc) memcpy(*pos, traj + (size_t)(dt[0] - 1) * (size_t)np * 3, (size_t)np * 3 * sizeof(double));
    free(traj);
    sb_h5r_close(&r, f);
    if (rc) {
        free(*names);
        free(*pos);
        *names = NULL;
        *pos = NULL;
        return rc;
    }
    *n = np;
    return SB_OK;
}
