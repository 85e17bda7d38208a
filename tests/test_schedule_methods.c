/* test_schedule_methods.c — a moving boundary with a schedule
 * (docs/scene_format.md "Schedules") is followed by every method: a corner
 * goes out (factor 1 at 0.2 s), stops, and comes back past its start
 * (factor -0.5 at 0.6 s, the end), which no ramp can do; at the end its
 * probe's displacement is -0.5 times the translation, exactly for the
 * methods that impose the motion as a Dirichlet condition and within the
 * reported penalty violation for rmtr (penalty boundary conditions). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "run_json.h"
#include "sb_test.h"

static const char scene[] =
    "{\"name\": \"sched_go_back\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1]},\n"
    " \"material\": {\"model\": \"stvk\", \"young\": 1e5, \"poisson\": 0.3, \"thickness\": 0.001, \"density\": 0.1},\n"
    " \"loads\": [{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]}],\n"
    " \"boundary\": [{\"type\": \"fixed\", \"at\": [0, 1]},\n"
    "   {\"type\": \"moving\", \"at\": [1, 1], \"translation\": [0.1, 0, 0.05],\n"
    "    \"schedule\": [[0, 0], [0.2, 1], [0.4, 1], [0.6, -0.5]]}],\n"
    " \"time\": {\"mode\": \"dynamic\", \"dt\": 0.1, \"steps\": 6},\n"
    " \"probes\": [{\"name\": \"corner\", \"at\": [1, 1]}]}\n";

SB_TEST(every_method_follows_a_schedule)
{
    static const char *const methods[] = { "linear_fem", "bhem", "rmtr", "adaptive_sqrt3" };
    static const char *const solvers[] = { "lsnewton", "lsnewton", "lsnewton", "linearized" };
    static const char *const sets[] = { "run.single_step_rtol=1e300" };
    const double want[3] = { -0.05, 0, -0.025 };
    char path[256];
    snprintf(path, sizeof path, "/tmp/sb_test_schedule_%d.json", (int)getpid());
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fputs(scene, f);
    fclose(f);
    for (int m = 0; m < 4; m++) {
        sb_run_request rq;
        memset(&rq, 0, sizeof rq);
        rq.scene = path;
        rq.method = methods[m];
        rq.solver = solvers[m];
        rq.res = 4;
        rq.out = "none";
        rq.quiet = 1;
        rq.n_sets = m == 3;
        rq.sets = sets;
        int code = -1;
        json_t *o = sb_test_run_json(&rq, &code);
        CHECK_MSG(code == 0 && o, "%s: exit %d", methods[m], code);
        if (!o) continue;
        json_t *u = json_object_get(json_object_get(json_object_get(o, "probes"), "corner"), "displacement");
        json_t *pen = json_object_get(o, "penalty");
        const double tol = json_is_object(pen) ? json_number_value(json_object_get(pen, "position_max")) + 1e-9 : 1e-9;
        double err = 0;
        for (int k = 0; k < 3; k++) err = fmax(err, fabs(json_number_value(json_array_get(u, (size_t)k)) - want[k]));
        printf("    %-14s corner displacement off by %.3g m (allowed %.3g)\n", methods[m], err, tol);
        CHECK_MSG(err <= tol, "%s: the corner is %g m from where the schedule puts it", methods[m], err);
        /* back past its start (a ramp would leave it at +0.1 m or on the way there) */
        const double ux = json_number_value(json_array_get(u, 0));
        CHECK_MSG(ux < -0.045, "%s: u_x = %g, not back past the start", methods[m], ux);
        json_decref(o);
    }
    remove(path);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = { SB_CASE(every_method_follows_a_schedule), SB_END };
    return sb_test_main(argc, argv, cases);
}
