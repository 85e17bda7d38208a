/* sb_blob.h — a method's own state as flat integers and doubles, for
 * checkpoints (sb_method.h save_mesh / restore_mesh; written as
 * /resume/mesh_ints and /resume/mesh_doubles, docs/recorded_figures.md). */
#ifndef SB_BLOB_H
#define SB_BLOB_H

#include <stdlib.h>
#include <string.h>

typedef struct sb_blob {
    int n_int, n_dbl;
    int *ints;
    double *dbls;
} sb_blob;

static inline void sb_blob_free(sb_blob *b)
{
    if (!b) return;
    free(b->ints);
    free(b->dbls);
    memset(b, 0, sizeof *b);
}

#endif
