/* run_json.c — see run_json.h */
#include "run_json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sb_test_request(sb_run_request *req, const char *scene, const char *method, const char *solver, int res)
{
    memset(req, 0, sizeof *req);
    req->scene = scene;
    req->method = method;
    req->solver = solver;
    req->res = res;
    req->out = "none";
    req->quiet = 1;
    req->progress = -1;
}

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
