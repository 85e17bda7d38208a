/* run_json.h — one run through sb_run_execute (exactly the `shellbench run`
 * path), its progress output discarded and its JSON summary parsed. */
#ifndef RUN_JSON_H
#define RUN_JSON_H

#include "sb_run.h"
#include <jansson.h>

/* The summary as a JSON object (caller decrefs), NULL when the run wrote none;
 * *exit_code receives the run's exit code. */
json_t *sb_test_run_json(const sb_run_request *req, int *exit_code);

/* *req zeroed, then scene, method, solver and res set, no record written
 * (out "none"), quiet, no progress: the request most tests start from */
void sb_test_request(sb_run_request *req, const char *scene, const char *method, const char *solver, int res);

#endif
