/* sb_cli_args.c — parsing the command line's values and the options of
 * `run` and `sweep` (sb_cli.h).  Every value is checked where it is read:
 * a mistake costs a sentence naming the option, exit 2. */
#include "sb_cli.h"
#include "sb_scene.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

int sb_cli_parse_int(const char *s, long lo, long hi, int *out)
{
    char *end;
    if (!s || !*s) return -1;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno == ERANGE || v < lo || v > hi || v < INT_MIN || v > INT_MAX) return -1;
    *out = (int)v;
    return 0;
}

int sb_cli_parse_res(const char *s, int *res, char *err, size_t errlen)
{
    if (sb_cli_parse_int(s, 0, SB_SCENE_MAX_RESOLUTION, res)) {
        char e[64];
        snprintf(err, errlen, "--res: \"%s\" is not a resolution: give elements per side, 1 to %d (0: the scene's "
                 "own)", sb_escape_copy(s, e, sizeof e), SB_SCENE_MAX_RESOLUTION);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

int sb_cli_split(char *s, char **items, int max, int *n)
{
    *n = 0;
    if (!s || !*s) return -1;
    for (char *p = s;;) {
        char *comma = strchr(p, ',');
        if (comma) *comma = 0;
        if (!*p) return -1;
        if (*n >= max) return -2;
        items[(*n)++] = p;
        if (!comma) return 0;
        p = comma + 1;
    }
}

static int bad_value(const char *opt, const char *v, const char *what)
{
    char e[64];
    fprintf(stderr, "shellbench: %s: \"%s\" is not %s\n", opt, sb_escape_copy(v, e, sizeof e), what);
    return 2;
}

int sb_cli_parse_run(int argc, char **argv, sb_cli_run *c, int sweep)
{
    const char *cmd = sweep ? "sweep" : "run";
    char msg[256];
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED_VALUE() do { if (!v) { fprintf(stderr, "shellbench %s: %s needs a value (see `shellbench help %s`)\n", \
                                            cmd, a, cmd); return 2; } i++; } while (0)
        if (!strcmp(a, "--quiet")) { c->req.quiet = 1; continue; }
        if (!strcmp(a, "--resume")) { c->req.resume = 1; continue; }
        if (!strcmp(a, "--strict")) { c->req.strict = 1; continue; }   /* docs/trust.md: exit 5 */
        if (!strcmp(a, "--allow-unsealed-reference")) { c->req.allow_unsealed_reference = 1; continue; }
        if (!strcmp(a, "--progress")) { c->req.progress = 1; continue; }
        if (!strcmp(a, "--no-progress")) { c->req.progress = -1; continue; }
        if (!sweep && !strcmp(a, "--scene")) { NEED_VALUE(); c->req.scene = v; }
        else if (!sweep && !strcmp(a, "--method")) { NEED_VALUE(); c->req.method = v; }
        else if (!sweep && !strcmp(a, "--solver")) { NEED_VALUE(); c->req.solver = v; }
        else if (!sweep && !strcmp(a, "--res")) {
            NEED_VALUE();
            /* N, or NxM: N along s, M along t (sb_run_parse_res) */
            if (strpbrk(v, "xX\xC3") ? sb_run_parse_res(v, &c->req.res, &c->req.res_t) != 0
                                      : sb_cli_parse_res(v, &c->req.res, msg, sizeof msg) != SB_OK) {
                if (strpbrk(v, "xX\xC3")) {
                    char e[64];
                    snprintf(msg, sizeof msg, "--res: \"%s\" is not a resolution NxM: N elements along s and M along "
                             "t, each 1 to %d", sb_escape_copy(v, e, sizeof e), SB_SCENE_MAX_RESOLUTION);
                }
                fprintf(stderr, "shellbench: %s\n", msg);
                return 2;
            }
        } else if (!sweep && !strcmp(a, "--levels")) {
            NEED_VALUE();
            if (sb_cli_parse_int(v, 1, SB_MAX_LEVELS, &c->req.levels)) return bad_value(a, v, "a level count from 1 to 8");
        } else if (!strcmp(a, "--samples")) {
            NEED_VALUE();
            if (sb_cli_parse_int(v, 2, SB_RUN_MAX_SAMPLES, &c->req.sample_n))
                return bad_value(a, v, "an integer in [2, 2001]");
        } else if (!sweep && !strcmp(a, "--stop-after-steps")) {
            NEED_VALUE();
            if (sb_cli_parse_int(v, 1, INT_MAX, &c->req.stop_after_steps)) return bad_value(a, v, "a positive integer");
        } else if (!sweep && !strcmp(a, "--out")) { NEED_VALUE(); c->req.out = v; }
        else if (!sweep && !strcmp(a, "--summary")) {
            NEED_VALUE();
            if (strcmp(v, "json")) return bad_value(a, v, "a summary format (only \"json\" is supported)");
            c->req.summary_json = 1;
        } else if (!strcmp(a, "--set")) {
            NEED_VALUE();
            if (c->req.n_sets >= SB_CLI_MAX_SETS) { fprintf(stderr, "shellbench: too many --set options\n"); return 2; }
            c->sets[c->req.n_sets++] = v;
        } else if (sweep && !strcmp(a, "--scenes")) { NEED_VALUE(); c->scenes = v; }
        else if (sweep && !strcmp(a, "--methods")) { NEED_VALUE(); c->methods = v; }
        else if (sweep && !strcmp(a, "--solvers")) { NEED_VALUE(); c->solvers = v; }
        else if (sweep && !strcmp(a, "--res")) { NEED_VALUE(); c->res_list = v; }
        else if (sweep && !strcmp(a, "--levels")) { NEED_VALUE(); c->level_list = v; }
        else if (sweep && !strcmp(a, "--dir")) { NEED_VALUE(); c->dir = v; }
        else {
            char e[64];
            fprintf(stderr, "shellbench %s: unknown option \"%s\" (see `shellbench help %s`)\n", cmd,
                    sb_escape_copy(a, e, sizeof e), cmd);
            return 2;
        }
#undef NEED_VALUE
    }
    c->req.sets = c->sets;
    return 0;
}
