/* run_json.c — see run_json.h */
#include "run_json.h"

#include <stdio.h>
#include <stdlib.h>

json_t *sb_test_run_json(const sb_run_request *req, int *exit_code)
{
    char *js = NULL;
    FILE *devnull = fopen("/dev/null", "w");
    *exit_code = sb_run_execute(req, devnull ? devnull : stdout, stderr, &js);
    if (devnull) fclose(devnull);
    json_error_t e;
    json_t *root = js ? json_loads(js, 0, &e) : NULL;
    free(js);
    return root;
}
