/* sb_reference.h — reference records and the field error against them
 * (DESIGN.md "Accuracy", docs/study.md "References").
 *
 * A reference is a finished, converged run record of the same scene whose
 * final state, sampled on the same grid of material points, stands in for
 * the exact solution.  Records sample the final surface on an n x n grid in
 * the grid parameter (s,t); every method maps (s,t) to the material point
 * xi = sb_domain_map(s,t) of the scene (tests/test_study_error.c checks it
 * for every registered method), so equal (s,t) grids are equal material
 * points whatever the two discretizations are.
 *
 * Error = RMS and max over the sample points of |x(xi) - x_ref(xi)|, divided
 * by the domain's diameter. */
#ifndef SB_REFERENCE_H
#define SB_REFERENCE_H

#include "sb_common.h"

#include <stddef.h>

/* A reference record, read and checked. */
typedef struct sb_refrec {
    char path[1024];
    char scene[SB_NAME_LEN], method[SB_NAME_LEN], solver[SB_NAME_LEN];
    int res, levels;
    long dofs;
    int n;                  /* sample points */
    double *st, *pos;       /* 2n grid parameters, 3n final positions (owned) */
    double energy;          /* energy_final (NaN when the record has none) */
} sb_refrec;

/* 1 when the two scene texts describe the same problem: equal JSON after
 * the members that do not change the solution are set aside ("description",
 * "resolution", "reference", "probes"); 0 when they differ (why: the first
 * differing member, "/material"), -1 when one of them is no JSON object. */
int sb_scene_same_problem(const char *json_a, const char *json_b, char *why, size_t whylen);

/* Read the reference record `path` for the scene (name, verbatim JSON text)
 * and the sample grid (n points st[2n]).  Refused with one sentence naming
 * the file (SB_ERR_INPUT / SB_ERR_IO): an unreadable or unfinished record
 * (a checkpoint), a run that did not converge, a record of another problem
 * (the scene's name does not count: a renamed copy keeps its reference, as
 * sb_reference_check says at `check`), another sample grid, and a record
 * without a checksum (sb_reference_sealed).
 * On success ref owns its arrays (sb_refrec_free). */
int sb_refrec_load(const char *path, const char *scene_name, const char *scene_json, int n,
                   const double *st, sb_refrec *ref, char *err, size_t errlen);
/* The same, with a record without a checksum accepted when allow_unsealed
 * (--allow-unsealed-reference). */
int sb_refrec_load_opt(const char *path, const char *scene_name, const char *scene_json, int n,
                       const double *st, int allow_unsealed, sb_refrec *ref, char *err, size_t errlen);

/* A reference must carry a checksum (a sealed record, docs/trust.md
 * "Reference files"): a record without one (format version 1) could be
 * damaged without anyone knowing.  SB_OK when PATH is sealed and its
 * checksum matches, or when it carries none and allow_unsealed
 * (--allow-unsealed-reference); else SB_ERR_INPUT (or SB_ERR_IO) with one
 * sentence naming the file. */
int sb_reference_sealed(const char *path, int allow_unsealed, char *err, size_t errlen);
void sb_refrec_free(sb_refrec *ref);

/* The final probe positions of a record: *n probes, names[n][SB_NAME_LEN]
 * and pos[3n] (both owned by the caller, free()). */
int sb_record_read_probes(const char *path, int *n, char (**names)[SB_NAME_LEN], double **pos, char *err,
                          size_t errlen);

/* RMS and max of |pos_i - ref_i| over the n points, divided by diam. */
void sb_field_error(int n, const double *pos, const double *ref, double diam, double *rms, double *max);

#endif
