/* method_fixture.h — a method set up on a loaded scene for tests that call
 * a method's ops directly (tests/test_pin.c, tests/test_contact.c): the
 * context, the scene, the method type and its state, created and freed in
 * one place. */
#ifndef SB_METHOD_FIXTURE_H
#define SB_METHOD_FIXTURE_H

#include "sb_context.h"
#include "sb_method.h"
#include "sb_scene.h"
#include "sb_test.h"

typedef struct sb_method_fixture {
    sb_context ctx;
    sb_scene sc;
    const sb_method_type *mt;
    void *ms;
} sb_method_fixture;

/* Zero S and start its context; the caller then fills S->sc (load or parse). */
void sb_method_fixture_init(sb_method_fixture *S);
/* Create method mt on S->sc at resolution res, one level (its method.*
 * defaults registered); a failure is a failed check and -1. */
int  sb_method_fixture_create(sb_test_state *T, sb_method_fixture *S, const sb_method_type *mt, int res);
/* Destroy the method, the scene and the context (after any init). */
void sb_method_fixture_free(sb_method_fixture *S);

#endif
