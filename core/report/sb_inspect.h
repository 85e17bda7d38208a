/* sb_inspect.h — `shellbench inspect`: examine the final (or checkpointed)
 * state of records without re-running them.  The discretization is rebuilt
 * from what the record keeps (scene text, method, --res, --levels,
 * method.* parameters) and the state is evaluated on its finest level. */
#ifndef SB_INSPECT_H
#define SB_INSPECT_H

#include "sb_method.h"
#include <stdio.h>

/* The material state (sb_material_state) of the record's state.  Returns
 * SB_OK; SB_ERR_INPUT / SB_ERR_IO with a sentence naming the file in err;
 * SB_ERR_UNSUPPORTED when the method has no material_state. */
int sb_inspect_material(const char *path, sb_material_state *ms, char *err, size_t errlen);

/* One row per file (format "md" or "csv") on out; unreadable files are
 * named on err and left out.  Returns the number of files left out. */
int sb_inspect_report(int n_files, char **files, const char *format, FILE *out, FILE *err);

#endif
