/* sb_context.h — one context per run (CHOLMOD-common style): resolved
 * parameters, the cholmod_common, statistics and the error message.  No
 * global mutable state anywhere: everything a run changes hangs off this. */
#ifndef SB_CONTEXT_H
#define SB_CONTEXT_H

#include "sb_params.h"
#include "sb_stats.h"

#include <stdarg.h>

typedef struct sb_context {
    sb_paramset params;
    sb_stats stats;
    void *cholmod;            /* cholmod_common*, owned (opaque here) */
    int verbose;
    /* Called by the shared outer loop (sb_solve_step) after every recorded
     * iteration, PETSc SNESMonitor-style; the run uses it for checkpoints.
     * NULL: nothing is called. */
    void (*monitor)(void *data, const sb_iter_record *r);
    void *monitor_data;
    int status;               /* last error status */
    char err[1024];           /* last error, a full sentence */
} sb_context;

int  sb_context_init(sb_context *ctx);
void sb_context_free(sb_context *ctx);
/* printf-style error: stores the message, returns `status` for chaining. */
int  sb_error(sb_context *ctx, int status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* The same with a component prefix ("bhem: ...") and a va_list, for the
 * error helpers of methods; with ctx == NULL the message goes to stderr. */
int  sb_verror(sb_context *ctx, int status, const char *prefix, const char *fmt, va_list ap);

#endif
