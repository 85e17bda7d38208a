/* method_fixture.c — see method_fixture.h. */
#include "method_fixture.h"

#include <stdlib.h>
#include <string.h>

void sb_method_fixture_init(sb_method_fixture *S)
{
    memset(S, 0, sizeof *S);
    sb_context_init(&S->ctx);
}

int sb_method_fixture_create(sb_test_state *T, sb_method_fixture *S, const sb_method_type *mt, int res)
{
    if (mt->params) sb_paramset_add(&S->ctx.params, "method", mt->params);
    S->mt = mt;
    S->ms = calloc(1, mt->state_size);
    sb_method_config cfg = { res, 1, &S->ctx.params, &S->ctx, 0 };
    int rc = S->ms ? mt->create(S->ms, &S->sc, &cfg) : SB_ERR_NOMEM;
    CHECK_MSG(rc == 0, "%s: %s", mt->name, S->ctx.err);
    return rc ? -1 : 0;
}

void sb_method_fixture_free(sb_method_fixture *S)
{
    if (S->ms && S->mt) S->mt->destroy(S->ms);
    free(S->ms);
    S->ms = NULL;
    sb_scene_free(&S->sc);
    sb_context_free(&S->ctx);
}
