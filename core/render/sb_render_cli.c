/* sb_render_cli.c — `shellbench render RECORD.h5 [options]` (docs/render.md). */
#include "sb_render.h"
#include "sb_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: shellbench render RECORD.h5 [--out FILE.png] [--size WxH] [--spp N] [--thumb]\n"
            "         [--camera AZ,EL[,ZOOM] | --camera EX,EY,EZ,TX,TY,TZ] [--fov DEG]\n"
            "         [--color none|curvature|strain|softening] [--intersect subdivision|newton|clipping|clipping-dfs]\n"
            "         [--step K] [--no-shadows] [--no-ground] [--title TEXT] [--stats] [--quiet]\n"
            "  draws the record's final state (or the recorded surface of step K) as a ray-traced PNG;\n"
            "  --thumb = --size 320x240 --spp 8; --stats prints the work counts as one JSON line\n");
}

/* comma-separated finite numbers; returns how many (<= max), -1 on a bad one */
static int parse_list(const char *s, double *v, int max)
{
    int n = 0;
    const char *p = s;
    while (*p) {
        char *end;
        double x = strtod(p, &end);
        if (end == p || !isfinite(x) || n >= max) return -1;
        v[n++] = x;
        if (*end == ',') p = end + 1;
        else if (*end == 0) p = end;
        else return -1;
    }
    return n;
}

static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

int sb_render_main(int argc, char **argv)
{
    sb_render_request rq;
    memset(&rq, 0, sizeof rq);
    sb_render_options_default(&rq.opt);
    rq.step = -1;
    int stats = 0;
    char out_default[4096];
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED() do { if (!v) { sb_escape_print(stderr, "shellbench render: %s needs a value", a); return 2; } i++; } while (0)
#define BAD(...) do { sb_escape_print(stderr, "shellbench render: " __VA_ARGS__); return 2; } while (0)
        if (!strcmp(a, "--out")) { NEED(); rq.out = v; }
        else if (!strcmp(a, "--size")) {
            NEED();
            int w, h;
            char tail;
            if (sscanf(v, "%dx%d%c", &w, &h, &tail) != 2 || w < 8 || h < 8 || w > 8192 || h > 8192)
                BAD("--size: \"%s\" is not WxH with 8 <= W, H <= 8192", v);
            rq.opt.width = w;
            rq.opt.height = h;
        } else if (!strcmp(a, "--spp")) {
            NEED();
            if (parse_int(v, 1, 4096, &rq.opt.spp)) BAD("--spp: \"%s\" is not an integer in [1, 4096]", v);
        } else if (!strcmp(a, "--thumb")) {
            rq.opt.width = 320;
            rq.opt.height = 240;
            rq.opt.spp = 8;
        } else if (!strcmp(a, "--camera")) {
            NEED();
            double c[6];
            int n = parse_list(v, c, 6);
            if (n == 2 || n == 3) {
                rq.opt.azimuth = c[0];
                rq.opt.elevation = c[1];
                if (n == 3) {
                    if (!(c[2] > 0)) BAD("--camera: the zoom must be > 0, got %g", c[2]);
                    rq.opt.zoom = c[2];
                }
                if (fabs(rq.opt.elevation) > 90) BAD("--camera: elevation %g is outside [-90, 90]", rq.opt.elevation);
            } else if (n == 6) {
                rq.opt.use_eye = 1;
                memcpy(rq.opt.eye, c, 3 * sizeof *c);
                memcpy(rq.opt.at, c + 3, 3 * sizeof *c);
                if (c[0] == c[3] && c[1] == c[4] && c[2] == c[5]) BAD("--camera: the eye and the target coincide");
            } else {
                BAD("--camera: \"%s\" is neither AZ,EL[,ZOOM] nor EX,EY,EZ,TX,TY,TZ", v);
            }
        } else if (!strcmp(a, "--fov")) {
            NEED();
            double f;
            if (parse_list(v, &f, 1) != 1 || !(f >= 1 && f <= 170)) BAD("--fov: \"%s\" is not a number in [1, 170]", v);
            rq.opt.fov = f;
        } else if (!strcmp(a, "--color") || !strcmp(a, "--colour")) {
            NEED();
            int k = -1;
            for (int j = 0; sb_color_names[j]; j++)
                if (!strcmp(v, sb_color_names[j])) k = j;
            if (k < 0) BAD("--color: \"%s\" is not one of none, curvature, strain, softening", v);
            rq.opt.color = (sb_color_kind)k;
        } else if (!strcmp(a, "--intersect")) {
            NEED();
            int k = sb_isect_find(v);
            if (k < 0) BAD("--intersect: \"%s\" is not one of subdivision, newton, clipping, clipping-dfs", v);
            rq.opt.isect = (sb_isect_kind)k;
        } else if (!strcmp(a, "--step")) {
            NEED();
            if (parse_int(v, 0, 100000000, &rq.step)) BAD("--step: \"%s\" is not a non-negative integer", v);
        } else if (!strcmp(a, "--title")) {
            NEED();
            snprintf(rq.opt.title, sizeof rq.opt.title, "%s", v);
            snprintf(rq.opt.subtitle, sizeof rq.opt.subtitle, " ");
        } else if (!strcmp(a, "--no-shadows")) rq.opt.shadows = 0;
        else if (!strcmp(a, "--no-ground")) rq.opt.ground = 0;
        else if (!strcmp(a, "--stats")) stats = 1;
        else if (!strcmp(a, "--quiet")) rq.quiet = 1;
        else if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        else if (a[0] == '-' && a[1] == '-') { sb_escape_print(stderr, "shellbench render: unknown option \"%s\"", a); usage(stderr); return 2; }
        else if (!rq.record) rq.record = a;
        else BAD("one record at a time (got \"%s\" and \"%s\")", rq.record, a);
#undef NEED
#undef BAD
    }
    if (!rq.record) {
        fprintf(stderr, "shellbench render: no record given\n");
        usage(stderr);
        return 2;
    }
    if (!rq.out) {
        size_t n = strlen(rq.record);
        if (n > 3 && !strcmp(rq.record + n - 3, ".h5")) n -= 3;
        if (rq.step >= 0) snprintf(out_default, sizeof out_default, "%.*s.step%d.png", (int)n, rq.record, rq.step);
        else snprintf(out_default, sizeof out_default, "%.*s.png", (int)n, rq.record);
        rq.out = out_default;
    }
    sb_render_stats st;
    char info[1024] = "", err[2048] = "";
    int rc = sb_render_record(&rq, &st, info, sizeof info, err, sizeof err);
    if (rc) {
        sb_escape_print(stderr, "shellbench render: %s", err);
        return rc == SB_ERR_NOMEM || rc == SB_ERR_INTERNAL ? 3 : 2;
    }
    if (!rq.quiet) sb_escape_print(stdout, "%s", info);   /* names the picture as given */
    if (stats) {
        const sb_isect_counts *c = &st.isect;
        printf("{\"seconds\": %.6f, \"cpu_seconds\": %.6f, \"build_seconds\": %.6f, \"width\": %d, \"height\": %d, \"spp\": %d, "
               "\"intersect\": \"%s\", \"primary_rays\": %ld, \"shadow_rays\": %ld, \"patch_tests\": %ld, "
               "\"patch_hits\": %ld, \"regions\": %ld, \"subpatches\": %ld, \"newton\": %ld, \"newton_roots\": %ld, "
               "\"excluded\": %ld, \"clips\": %ld, \"budget_stops\": %ld, \"triangle_tests\": %ld}\n",
               st.seconds, st.cpu_seconds, st.build_seconds, rq.opt.width, rq.opt.height, rq.opt.spp, sb_isect_names[rq.opt.isect],
               st.primary_rays, st.shadow_rays, c->calls, c->hits, c->regions, c->splits, c->newton, c->newton_roots,
               c->excluded, c->clips, c->budget, st.tri_tests);
    }
    return 0;
}
