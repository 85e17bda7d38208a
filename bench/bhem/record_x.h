/* record_x.h — the final dof vector /final/x of a record, for the bhem bench
 * tools (bhem_profile, isect_classes, needles_diag, surface_profile): read
 * through the library's record reader (sb_record_read_setup: checksum,
 * format and digest checks, a sentence on failure), returned as a malloc'd
 * copy the caller frees; NULL after printing why. */
#ifndef BENCH_BHEM_RECORD_X_H
#define BENCH_BHEM_RECORD_X_H

#include "sb_record.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static inline double *read_x(const char *path, long *n)
{
    sb_record_setup s;
    char err[1024];
    if (sb_record_read_setup(path, &s, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return NULL;
    }
    double *x = s.n_x > 0 ? malloc(sizeof(double) * (size_t)s.n_x) : NULL;
    if (x) memcpy(x, s.x, sizeof(double) * (size_t)s.n_x);
    *n = x ? s.n_x : 0;
    sb_record_setup_free(&s);
    return x;
}

#endif
