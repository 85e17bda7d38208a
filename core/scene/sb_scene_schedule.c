/* sb_scene_schedule.c — motion schedules of moving boundaries and obstacles
 * (docs/scene_format.md "Schedules"): the parser of
 *
 *   "schedule": [[t_0, f_0], [t_1, f_1], ...]
 *
 * and the piecewise-linear factor f(t) (sb_scene.h, sb_schedule).  A ramp
 * (ramp_steps) can only rise; a schedule lets a boundary go and come back
 * (the sqrt3 paper's curtain, Bender & Deul §7, is opened and closed). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sb_scene_json.h"

#define MAX_FACTOR 1000.0

int sbj_parse_schedule(sbj_ctx *c, const json_t *o, const sb_time_spec *tm, sb_schedule *sch, int *present)
{
    json_t *a;
    int r = sbj_get_array(c, o, "schedule", 0, 1, &a);
    memset(sch, 0, sizeof *sch);
    if (present) *present = a != NULL;
    if (r || !a) return r;
    const char *unit = tm->mode == SB_TIME_DYNAMIC ? "s" : "load steps";
    const double t_end = tm->mode == SB_TIME_DYNAMIC ? tm->steps * tm->dt : (double)tm->steps;
    size_t n = json_array_size(a);
    size_t mark = sbj_push(c, "schedule");
    if (n < 2 || n > SB_SCHEDULE_MAX) {
        r = sbj_fail(c, NULL, 0, "must have 2 to %d keyframes [time, factor], got %zu", SB_SCHEDULE_MAX, n);
        goto out;
    }
    for (size_t k = 0; k < n; k++) {
        double kv[2];
        size_t m2 = sbj_push_index(c, k);
        r = sbj_vec_value(c, json_array_get(a, k), 2, kv);
        if (!r && !(kv[0] >= 0))
            r = sbj_fail(c, "0", 0, "keyframe time must be >= 0 %s, got %g", unit, kv[0]);
        if (!r && k > 0 && !(kv[0] > sch->t[k - 1]))
            r = sbj_fail(c, "0", 0, "keyframe times must increase strictly: %g %s after %g %s", kv[0], unit,
                         sch->t[k - 1], unit);
        if (!r && tm->mode == SB_TIME_QUASI_STATIC && kv[0] != floor(kv[0]))
            r = sbj_fail(c, "0", 0, "keyframe time of a quasi-static scene is a load step (an integer), got %g",
                         kv[0]);
        if (!r && !(fabs(kv[1]) <= MAX_FACTOR))
            r = sbj_fail(c, "1", 0, "factor must be in [-%g, %g], got %g", MAX_FACTOR, MAX_FACTOR, kv[1]);
        /* the reference configuration is the state at t = 0: factor 0 there */
        if (!r && kv[0] == 0 && kv[1] != 0)
            r = sbj_fail(c, "1", 0, "factor at time 0 must be 0 (the reference configuration), got %g", kv[1]);
        sbj_pop(c, m2);
        if (r) goto out;
        sch->t[k] = kv[0];
        sch->f[k] = kv[1];
    }
    if (!(sch->t[0] < t_end)) {
        size_t m2 = sbj_push_index(c, 0);
        r = sbj_fail(c, "0", 0, "first keyframe at %g %s is not before the end of the run (%g %s)", sch->t[0], unit,
                     t_end, unit);
        sbj_pop(c, m2);
        goto out;
    }
    sch->n = (int)n;
out:
    sbj_pop(c, mark);
    if (r) memset(sch, 0, sizeof *sch);
    return r;
}

double sb_schedule_factor(const sb_schedule *sch, double t)
{
    /* piecewise-linear interpolation through (0, 0), (t_0, f_0), ..., held at f_(n-1) */
    if (sch->n <= 0 || !(t > 0)) return 0;
    double t0 = 0, f0 = 0;
    for (int k = 0; k < sch->n; k++) {
        if (t <= sch->t[k]) {
            double w = sch->t[k] > t0 ? (t - t0) / (sch->t[k] - t0) : 1;
            return f0 + w * (sch->f[k] - f0);
        }
        t0 = sch->t[k];
        f0 = sch->f[k];
    }
    return f0;
}
