/* sb_context.c — one context per run: parameters, cholmod_common, statistics, errors. */
#include "sb_context.h"
#include "sb_gsl.h"
#include "sb_cholmod_alloc.h"

#include <cholmod.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int sb_context_init(sb_context *ctx)
{
    memset(ctx, 0, sizeof *ctx);
    sb_paramset_init(&ctx->params);
    sb_stats_init(&ctx->stats);
    /* GSL errors return codes that the caller maps, never abort (sb_gsl.h) */
    sb_gsl_errors_off();
    cholmod_common *cm = malloc(sizeof *cm);
    if (!cm) return SB_ERR_NOMEM;
    sb_cholmod_alloc_install();   /* large factors on huge pages (idempotent) */
    cholmod_start(cm);
    /* Always supernodal LL': an indefinite matrix is then reported as
     * CHOLMOD_NOT_POSDEF instead of being factored as LDL' (DESIGN.md). */
    cm->supernodal = CHOLMOD_SUPERNODAL;
    cm->final_ll = 1;
    cm->print = 0;
    cm->error_handler = NULL;
    ctx->cholmod = cm;
    return SB_OK;
}

void sb_context_free(sb_context *ctx)
{
    if (ctx->cholmod) {
        cholmod_finish(ctx->cholmod);
        free(ctx->cholmod);
    }
    sb_stats_free(&ctx->stats);
    ctx->cholmod = NULL;
}

int sb_error(sb_context *ctx, int status, const char *fmt, ...)
{
    va_list ap;
    if (!ctx) return status;   /* callers without a context (tests, estimates) get the status alone */
    va_start(ap, fmt);
    vsnprintf(ctx->err, sizeof ctx->err, fmt, ap);
    va_end(ap);
    sb_escape_controls(ctx->err, sizeof ctx->err);   /* names from scene files reach a terminal */
    ctx->status = status;
    return status;
}

int sb_verror(sb_context *ctx, int status, const char *prefix, const char *fmt, va_list ap)
{
    char msg[900];
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (ctx) return sb_error(ctx, status, "%s: %s", prefix, msg);
    fprintf(stderr, "%s: %s\n", prefix, msg);
    return status;
}
