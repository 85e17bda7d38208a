/* sb_reference_check.c — is a scene's `reference: {type: file}` a record an
 * error can be measured against?  (docs/trust.md "References")
 *
 * Checked by `shellbench check` and at the start of every run, before any
 * work: the file is a readable shellbench record (a regular HDF5 file whose
 * checksum matches: not missing, not a directory, not /dev/zero, not a JSON
 * file), of a finished, converged run (not an unfinished checkpoint), of
 * the same scene — the same domain, geometry, material, loads, boundary
 * conditions and time mode (for dynamic scenes also dt, steps and damping),
 * named section by section, and then the same problem by the test the end
 * of the run and the study reports make (sb_scene_same_problem: obstacles,
 * contact, load steps; issue 37: one verdict everywhere), with obstacle
 * meshes of the same contents — sealed with a checksum unless the caller
 * allows otherwise, and, at run start, recorded on this run's sample grid
 * (the error is taken point by point on it). */
#include "sb_record_io.h"
#include "sb_reference.h"
#include "sb_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int parts_differ(int n, const sb_part *a, const sb_part *b)
{
    for (int i = 0; i < n; i++)
        if (a[i].kind != b[i].kind || strcmp(a[i].name, b[i].name) || memcmp(a[i].st0, b[i].st0, sizeof a[i].st0) ||
            memcmp(a[i].st1, b[i].st1, sizeof a[i].st1) || memcmp(a[i].xi, b[i].xi, sizeof a[i].xi))
            return 1;
    return 0;
}

#define DIFF(field) (memcmp(&a->field, &b->field, sizeof a->field) != 0)

/* The first section in which scene b (the reference's) differs from a, or NULL. */
static const char *physics_differs(const sb_scene *a, const sb_scene *b)
{
    if (DIFF(domain.kind) || DIFF(domain.origin) || DIFF(domain.size) || DIFF(domain.notch) ||
        DIFF(domain.notch_corner) || DIFF(domain.center) || DIFF(domain.r_in) || DIFF(domain.r_out) ||
        DIFF(domain.theta))
        return "domain";
    if (DIFF(chart.kind) || DIFF(chart.radius) || DIFF(chart.angle) || DIFF(chart.length) || DIFF(chart.polar) ||
        DIFF(chart.azimuth))
        return "geometry";
    if (DIFF(material.kind) || DIFF(material.young) || DIFF(material.poisson) || DIFF(material.thickness) ||
        DIFF(material.density) || DIFF(material.warp_angle) ||
        (a->material.kind == SB_MAT_DENIM &&
         (DIFF(material.denim.k) || DIFF(material.denim.d) || DIFF(material.denim.mu) || DIFF(material.denim.alpha) ||
          DIFF(material.denim.beyond_fit))))
        return "material";
    if (a->n_loads != b->n_loads) return "loads";
    for (int i = 0; i < a->n_loads; i++)
        if (DIFF(loads[i].kind) || DIFF(loads[i].vec) || DIFF(loads[i].value) || DIFF(loads[i].follower) ||
            DIFF(loads[i].n_parts) || DIFF(loads[i].ramp_steps) ||
            parts_differ(a->loads[i].n_parts, a->loads[i].parts, b->loads[i].parts))
            return "loads";
    if (a->n_bcs != b->n_bcs) return "boundary";
    for (int i = 0; i < a->n_bcs; i++)
        if (DIFF(bcs[i].kind) || DIFF(bcs[i].n_parts) || DIFF(bcs[i].components) || DIFF(bcs[i].axis) ||
            DIFF(bcs[i].translation) || DIFF(bcs[i].rot_axis) || DIFF(bcs[i].rot_center) || DIFF(bcs[i].rot_angle) ||
            DIFF(bcs[i].ramp_steps) || DIFF(bcs[i].clamp_tangent) || DIFF(bcs[i].derivative) || DIFF(bcs[i].schedule.n) ||
            DIFF(bcs[i].schedule.t) || DIFF(bcs[i].schedule.f) ||
            parts_differ(a->bcs[i].n_parts, a->bcs[i].parts, b->bcs[i].parts))
            return "boundary";
    if (DIFF(time.mode)) return "time mode";
    if (a->time.mode == SB_TIME_DYNAMIC && (DIFF(time.dt) || DIFF(time.steps) || DIFF(time.rayleigh_alpha) ||
                                            DIFF(time.rayleigh_beta)))
        return "time stepping";
    return NULL;
}
#undef DIFF

/* The sample grid of `domain` with n points per side (the run's, see
 * sb_run_build_samples: (i/(n-1), j/(n-1)) inside the domain, s fastest)
 * equals the m points in st. */
static int grid_matches(const sb_domain *d, int n, int m, const double *st)
{
    int k = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double s = (double)i / (n - 1), t = (double)j / (n - 1);
            if (!sb_domain_contains_st(d, s, t)) continue;
            if (k >= m || st[2 * k] != s || st[2 * k + 1] != t) return 0;
            k++;
        }
    return k == m;
}

int sb_reference_check(const sb_scene *sc, const double *sample_st, int n_samples, int allow_unsealed, char *err,
                       size_t errlen)
{
    if (sc->reference.kind != SB_REF_FILE) return SB_OK;
    const char *path = sc->reference.file;
    char msg[1024];
    sb_record_summary sum;
    /* sb_record_read_summary opens through sb_h5r_open: existence, regular
     * file, checksum, HDF5, shellbench format, version */
    int rc = sb_record_read_summary(path, &sum, msg, sizeof msg);
    if (rc) {
        snprintf(err, errlen, "scene %s: reference file %s cannot serve as a reference: %s", sc->name, path, msg);
        return SB_ERR_INPUT;
    }
    /* a readable record whose checksum matches; one without a checksum only when asked (sb_reference_sealed) */
    if (sb_reference_sealed(path, allow_unsealed, msg, sizeof msg)) {
        sb_record_summary_free(&sum);
        snprintf(err, errlen, "scene %s: %s", sc->name, msg);
        return SB_ERR_INPUT;
    }
    int status = sum.status;
    char reason[32];
    snprintf(reason, sizeof reason, "%s", sum.reason_name);
    sb_record_summary_free(&sum);
    if (status == SB_STATUS_UNFINISHED) {
        snprintf(err, errlen, "scene %s: reference file %s is the checkpoint of an unfinished run, not a finished record",
                 sc->name, path);
        return SB_ERR_INPUT;
    }
    if (status != 0) {
        snprintf(err, errlen, "scene %s: reference file %s records a run that did not converge (%s)", sc->name, path, reason);
        return SB_ERR_INPUT;
    }
    sb_record_setup setup;
    if ((rc = sb_record_read_setup(path, &setup, msg, sizeof msg))) {
        snprintf(err, errlen, "scene %s: reference file %s cannot serve as a reference: %s", sc->name, path, msg);
        return SB_ERR_INPUT;
    }
    /* the test the end of the run and the study reports make (sb_refrec_load):
       the scene texts as JSON, what does not change the solution set aside;
       it sees what the section-by-section comparison below does not name
       (obstacles, contact, the load steps) */
    char why[256];
    const int same = sb_scene_same_problem(sc->json_text, setup.scene_json, why, sizeof why);
    sb_scene ref;
    /* parsed as from the reference's own scene file: its OBJ meshes are found beside it */
    rc = sb_scene_parse_string(setup.scene_json, setup.scene_path[0] ? setup.scene_path : path, &ref, msg, sizeof msg);
    sb_record_setup_free(&setup);
    const char *what = NULL;
    char ref_name[SB_NAME_LEN] = "";
    if (!rc) {
        what = physics_differs(sc, &ref);
        snprintf(ref_name, sizeof ref_name, "%s", ref.name);
        sb_scene_free(&ref);
    }
    if (what) {
        snprintf(err, errlen, "scene %s: reference file %s is a record of another scene (%s: its %s differs from this "
                 "scene's)", sc->name, path, ref_name, what);
        return SB_ERR_INPUT;
    }
    if (same < 0) {
        snprintf(err, errlen, "scene %s: reference file %s cannot serve as a reference: its scene text or this scene's "
                 "is not a JSON object", sc->name, path);
        return SB_ERR_INPUT;
    }
    if (!same) {
        snprintf(err, errlen, "scene %s: reference file %s is a record of another scene (%s: its %s differs from this "
                 "scene's)", sc->name, path, ref_name[0] ? ref_name : "its scene text", why);
        return SB_ERR_INPUT;
    }
    if (rc) {
        snprintf(err, errlen, "scene %s: the scene recorded in reference file %s does not parse with this build: %s",
                 sc->name, path, msg);
        return SB_ERR_INPUT;
    }
    /* the obstacle meshes: the same file names (above), and the same contents */
    char ours[SB_RECORD_MESH_SUMS_LEN], theirs[SB_RECORD_MESH_SUMS_LEN];
    sb_record_mesh_sums(sc, ours, sizeof ours);
    if (ours[0]) {
        if (sb_record_read_mesh_sums(path, theirs, sizeof theirs, msg, sizeof msg)) {
            snprintf(err, errlen, "scene %s: reference file %s cannot serve as a reference: %s", sc->name, path, msg);
            return SB_ERR_INPUT;
        }
        if (strcmp(ours, theirs)) {
            snprintf(err, errlen, "scene %s: reference file %s was computed with other obstacle meshes (its [%s], this "
                     "scene's [%s]: an OBJ file differs)", sc->name, path, theirs[0] ? theirs : "no mesh checksums",
                     ours);
            return SB_ERR_INPUT;
        }
    }
    int n = 0;
    double *st = NULL, *pos = NULL;
    if ((rc = sb_record_read_samples(path, &n, &st, &pos, msg, sizeof msg))) {
        snprintf(err, errlen, "scene %s: reference file %s cannot serve as a reference: %s", sc->name, path, msg);
        return SB_ERR_INPUT;
    }
    int ok = 1, finite = 1;
    if (sample_st) {
        ok = n == n_samples;
        for (int i = 0; ok && i < 2 * n; i++) ok = st[i] == sample_st[i];
    } else {
        /* check time: a sample grid of this domain with some number of points per side */
        ok = 0;
        for (int g = 2; g <= 2001 && !ok && (long)g * g <= 64L * n + 64; g++) ok = grid_matches(&sc->domain, g, n, st);
    }
    for (int i = 0; i < 3 * n; i++) finite &= isfinite(pos[i]) != 0;
    free(st);
    free(pos);
    if (!ok && sample_st) {
        snprintf(err, errlen, "scene %s: reference file %s was recorded on another sample grid (%d points, this run %d): "
                 "the error is taken point by point, so run with the reference's --samples", sc->name, path, n, n_samples);
        return SB_ERR_INPUT;
    }
    if (!ok) {
        snprintf(err, errlen, "scene %s: reference file %s holds %d sample points that are no sample grid of this "
                 "scene's domain", sc->name, path, n);
        return SB_ERR_INPUT;
    }
    if (!finite) {
        snprintf(err, errlen, "scene %s: reference file %s holds non-finite sample positions", sc->name, path);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}
