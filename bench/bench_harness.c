/* bench_harness.c — harness overhead: recording and statistics as a
 * percentage of a run's time (issue: aim below 2 %).
 *
 * Recording = the exclusive seconds of the harness events (issue 42): record
 * (history, the HDF5 write), samples (probes, sample grid, material state),
 * error, progress and checkpoint.  Statistics = the clock reads around every counted event: their
 * number (from the run's own counts) times the measured cost of one
 * sb_now() pair.  Runs the membrane fixture through sb_run_execute, the code
 * path of `shellbench run`. */
#include "sb_run.h"
#include "sb_stats.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double clock_pair_cost(void)
{
    const int n = 2000000;
    double t0 = sb_now(), acc = 0;
    for (int i = 0; i < n; i++) acc += sb_now();
    double t1 = sb_now();
    if (acc == 0) printf(" ");
    return 2.0 * (t1 - t0) / n;
}

int main(int argc, char **argv)
{
    const char *scene = argc > 1 ? argv[1] : "tests/scenes/membrane_dynamic.json";
    int res = argc > 2 ? atoi(argv[2]) : 32;
    const char *solvers[] = { "lsnewton", "tr", "rmtr" };
    double pair = clock_pair_cost();
    printf("harness overhead, membrane fixture %dx%d on %s (clock pair %.1f ns)\n", res, res, scene, 1e9 * pair);
    printf("| solver | total s | harness s | harness %% | clock reads | statistics %% | overhead %% |\n|---|--:|--:|--:|--:|--:|--:|\n");
    for (int k = 0; k < 3; k++) {
        sb_run_request req;
        memset(&req, 0, sizeof req);
        req.scene = scene;
        req.method = "fixture_membrane";
        req.solver = solvers[k];
        req.res = res;
        req.levels = k == 2 ? 3 : 1;
        req.out = "/tmp/sb_bench_harness.h5";
        req.quiet = 1;
        char *js = NULL;
        FILE *devnull = fopen("/dev/null", "w");
        int ec = sb_run_execute(&req, devnull, stderr, &js);
        fclose(devnull);
        json_error_t e;
        json_t *o = js ? json_loads(js, 0, &e) : NULL;
        free(js);
        if (!o || ec > 1) { printf("| %s | run failed (exit %d) |\n", solvers[k], ec); json_decref(o); continue; }
        json_t *sec = json_object_get(o, "seconds"), *cnt = json_object_get(o, "counts");
        json_t *self = json_object_get(o, "seconds_self");
        double total = json_number_value(json_object_get(sec, "total"));
        static const char *const harness[] = { "record", "samples", "error", "progress", "checkpoint" };
        double rec = 0;
        for (int h = 0; h < 5; h++) rec += json_number_value(json_object_get(self, harness[h]));
        long reads = 0;
        const char *key;
        json_t *val;
        json_object_foreach(cnt, key, val) reads += json_integer_value(val);
        double stats = reads * pair;
        printf("| %s | %.3f | %.4f | %.2f | %ld | %.3f | %.2f |\n", solvers[k], total, rec, 100 * rec / total, reads,
               100 * stats / total, 100 * (rec + stats) / total);
        json_decref(o);
    }
    remove("/tmp/sb_bench_harness.h5");
    return 0;
}
