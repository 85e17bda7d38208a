/* isect_classes.c — the BHEM paper's Table 1 per ray class: the cost of one
 * ray–patch test of each intersection algorithm (core/render/sb_bezier_ray.h:
 * subdivision, newton, clipping, clipping-dfs) on the patches of a bhem
 * record, separately for
 *
 *   hit       rays aimed at a random point x(u,v) of a patch from far away,
 *             at more than 17° to its tangent plane (|cos(d, n)| >= 0.3);
 *   graze     rays aimed at a random point within 1.7° of its tangent plane
 *             (|cos(d, n)| <= 0.03), half of them lifted off the surface by
 *             1e-3 of the patch size along n, so that some touch or cross
 *             twice and some just miss (reported as graze_hit / graze_miss
 *             by the outcome);
 *   miss      rays through a random point of the patch's bounding box in a
 *             random direction that do not hit the patch (the tests a BVH
 *             lets through but that find nothing: most of a render's tests
 *             on 10x10 patches).
 *
 * The outcome (hit or not, t) is the subdivision algorithm's, which the
 * others must reproduce (counted as disagreements).  Each class is timed per
 * algorithm by process CPU time over REPEATS passes, tmax = infinity (the
 * first patch a ray meets), eps = 1e-6 x the surface's bounding-box diagonal
 * as in `shellbench render`.  Prints one JSON line per (class, algorithm);
 * bench/bhem/table1.sh runs it and bench/bhem/table1.py reports it.
 *
 * usage: isect_classes SCENE.json RECORD.h5 RES N REPEATS */
#include "sb_bezier_ray.h"
#include "sb_context.h"
#include "sb_method.h"
#include "sb_surface.h"

#include "record_x.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { CL_HIT, CL_GRAZE_HIT, CL_GRAZE_MISS, CL_MISS, CL_COUNT };
static const char *const CL_NAMES[CL_COUNT] = { "hit", "graze_hit", "graze_miss", "miss" };

typedef struct test { int patch; sb_ray r; double t_ref; } test;
typedef struct tset { test *v; int n, cap; } tset;

static double rnd(unsigned long long *st)
{
    *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*st >> 11) / 9007199254740992.0;
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}


static int add(tset *s, int patch, const sb_ray *r, double t_ref)
{
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 256;
        test *v = realloc(s->v, (size_t)cap * sizeof *v);
        if (!v) return -1;
        s->v = v;
        s->cap = cap;
    }
    s->v[s->n++] = (test){ patch, *r, t_ref };
    return 0;
}

static void unit_random(unsigned long long *st, double d[3])
{
    double n2;
    do {
        for (int c = 0; c < 3; c++) d[c] = 2 * rnd(st) - 1;
        n2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (n2 > 1.0 || n2 < 1e-6);
    for (int c = 0; c < 3; c++) d[c] /= sqrt(n2);
}

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: %s SCENE.json RECORD.h5 RES N REPEATS\n", argv[0]);
        return 2;
    }
    const int res = atoi(argv[3]), N = atoi(argv[4]), reps = atoi(argv[5]);
    if (res < 1 || N < 1 || reps < 1) { fprintf(stderr, "isect_classes: bad sizes\n"); return 2; }
    const sb_method_type *M = sb_method_find("bhem");
    sb_scene scene;
    char err[1024];
    if (sb_scene_load(argv[1], &scene, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 2; }
    sb_context ctx;
    if (sb_context_init(&ctx)) return 3;
    sb_paramset_add(&ctx.params, "method", M->params);
    void *S = calloc(1, M->state_size);
    sb_method_config cfg = { res, 1, &ctx.params, &ctx, 0 };
    if (!S || M->create(S, &scene, &cfg)) { fprintf(stderr, "isect_classes: %s\n", ctx.err); return 2; }
    long nx = 0;
    double *x = read_x(argv[2], &nx);
    if (!x || nx != M->n_dofs(S, 0)) { fprintf(stderr, "isect_classes: %s: /final/x does not fit --res %d\n", argv[2], res); return 2; }
    sb_surface surf;
    memset(&surf, 0, sizeof surf);
    if (M->surface(S, 0, x, &surf) || surf.n_patches < 1) { fprintf(stderr, "isect_classes: no patches\n"); return 2; }
    double lo[3], hi[3];
    sb_surface_bounds(&surf, lo, hi);
    const double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
    const double eps = 1e-6 * diag;
    double *plo = malloc(sizeof(double) * 3 * (size_t)surf.n_patches), *phi = malloc(sizeof(double) * 3 * (size_t)surf.n_patches);
    sb_bezier_ws *ws = sb_bezier_ws_new();
    if (!plo || !phi || !ws) return 3;
    for (int p = 0; p < surf.n_patches; p++) sb_bezier_bounds(surf.patch + (size_t)p * SB_BEZ_N, plo + 3 * p, phi + 3 * p);

    /* ---- the test sets (labelled by subdivision) ---- */
    tset set[CL_COUNT];
    memset(set, 0, sizeof set);
    unsigned long long st = 12345;
    long tries = 0;
    while ((set[CL_HIT].n < N || set[CL_GRAZE_HIT].n < N / 2 || set[CL_GRAZE_MISS].n < N / 2 || set[CL_MISS].n < N) &&
           tries++ < 200L * N) {
        const int p = (int)(rnd(&st) * surf.n_patches) % surf.n_patches;
        const double *P = surf.patch + (size_t)p * SB_BEZ_N, *bl = plo + 3 * p, *bh = phi + 3 * p;
        const double size = fmax(bh[0] - bl[0], fmax(bh[1] - bl[1], bh[2] - bl[2]));
        const int kind = (int)(rnd(&st) * 3);   /* 0 aimed steep, 1 aimed grazing, 2 through the box */
        double o[3], d[3], xs[3], xu[3], xv[3], n[3];
        sb_bezier_eval(P, 0.02 + 0.96 * rnd(&st), 0.02 + 0.96 * rnd(&st), xs, xu, xv);
        n[0] = xu[1] * xv[2] - xu[2] * xv[1];
        n[1] = xu[2] * xv[0] - xu[0] * xv[2];
        n[2] = xu[0] * xv[1] - xu[1] * xv[0];
        const double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(nn > 0)) continue;
        for (int c = 0; c < 3; c++) n[c] /= nn;
        unit_random(&st, d);
        double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        if (kind == 0) {
            if (fabs(dn) < 0.3) continue;
        } else if (kind == 1) {
            /* into the tangent plane, then tilted by at most 0.03 rad */
            for (int c = 0; c < 3; c++) d[c] -= dn * n[c];
            const double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (!(dl > 1e-3)) continue;
            const double g = 0.03 * (2 * rnd(&st) - 1);
            for (int c = 0; c < 3; c++) d[c] = cos(g) * d[c] / dl + sin(g) * n[c];
            if (rnd(&st) < 0.5)
                for (int c = 0; c < 3; c++) xs[c] += (rnd(&st) < 0.5 ? 1e-3 : -1e-3) * size * n[c];
        } else {
            for (int c = 0; c < 3; c++) xs[c] = bl[c] + rnd(&st) * (bh[c] - bl[c]);
        }
        for (int c = 0; c < 3; c++) o[c] = xs[c] - 2.0 * diag * d[c];
        sb_ray r;
        if (sb_ray_init(&r, o, d, 0.0, INFINITY)) continue;
        sb_patch_hit h;
        const int rc = sb_bezier_intersect(SB_ISECT_SUBDIVISION, P, bl, bh, &r, INFINITY, eps, ws, &h);
        if (rc < 0) return 3;
        double dn_hit = 1.0;
        if (rc > 0) {   /* the angle where the reference hit is */
            double y[3], yu[3], yv[3], m[3];
            sb_bezier_eval(P, h.u, h.v, y, yu, yv);
            m[0] = yu[1] * yv[2] - yu[2] * yv[1];
            m[1] = yu[2] * yv[0] - yu[0] * yv[2];
            m[2] = yu[0] * yv[1] - yu[1] * yv[0];
            const double mn = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
            dn_hit = mn > 0 ? fabs(m[0] * r.d[0] + m[1] * r.d[1] + m[2] * r.d[2]) / mn : 0.0;
        }
        int cl = -1;
        if (kind == 0 && rc > 0 && dn_hit >= 0.3) cl = CL_HIT;
        else if (kind == 1) cl = rc > 0 ? CL_GRAZE_HIT : CL_GRAZE_MISS;
        else if (kind == 2 && rc == 0) cl = CL_MISS;
        const int want = cl == CL_HIT || cl == CL_MISS ? N : N / 2;
        if (cl >= 0 && set[cl].n < want && add(&set[cl], p, &r, rc > 0 ? h.t : NAN)) return 3;
    }

    /* ---- timing ---- */
    char machine[300] = "?";
    FILE *ci = fopen("/proc/cpuinfo", "r");
    if (ci) {
        char line[256];
        while (fgets(line, sizeof line, ci))
            if (!strncmp(line, "model name", 10)) {
                const char *c = strchr(line, ':');
                snprintf(machine, sizeof machine, "%s", c ? c + 2 : line);
                machine[strcspn(machine, "\n\"")] = 0;
                break;
            }
        fclose(ci);
    }
    for (int cl = 0; cl < CL_COUNT; cl++) {
        if (set[cl].n == 0) continue;
        for (int k = 0; k < SB_ISECT_COUNT; k++) {
            sb_isect_counts *cnt = sb_bezier_ws_counts(ws);
            memset(cnt, 0, sizeof *cnt);
            long disagree = 0;
            const double t0 = cpu_now();
            for (int rep = 0; rep < reps; rep++)
                for (int i = 0; i < set[cl].n; i++) {
                    const test *T = &set[cl].v[i];
                    sb_patch_hit h;
                    const int rc = sb_bezier_intersect((sb_isect_kind)k, surf.patch + (size_t)T->patch * SB_BEZ_N,
                                                       plo + 3 * T->patch, phi + 3 * T->patch, &T->r, INFINITY, eps, ws, &h);
                    if (rep == 0 && ((rc > 0) != isfinite(T->t_ref) ||
                                     (rc > 0 && fabs(h.t - T->t_ref) > 1e-3 * diag)))
                        disagree++;
                }
            const double sec = cpu_now() - t0;
            const double calls = (double)cnt->calls;
            printf("{\"class\": \"%s\", \"algorithm\": \"%s\", \"tests\": %d, \"repeats\": %d, \"us_per_test\": %.4f, "
                   "\"regions_per_test\": %.3f, \"subpatches_per_test\": %.3f, \"newton_per_test\": %.3f, "
                   "\"clips_per_test\": %.3f, \"hits\": %ld, \"budget_stops\": %ld, \"disagree\": %ld, "
                   "\"patches\": %d, \"eps\": %.3e, \"machine\": \"%s\"}\n",
                   CL_NAMES[cl], sb_isect_names[k], set[cl].n, reps, 1e6 * sec / fmax(1.0, calls), cnt->regions / calls,
                   cnt->splits / calls, cnt->newton / calls, cnt->clips / calls, cnt->hits / reps, cnt->budget, disagree,
                   surf.n_patches, eps, machine);
        }
    }
    for (int cl = 0; cl < CL_COUNT; cl++) free(set[cl].v);
    sb_bezier_ws_free(ws);
    free(plo);
    free(phi);
    sb_surface_free(&surf);
    free(x);
    M->destroy(S);
    free(S);
    sb_scene_free(&scene);
    sb_context_free(&ctx);
    return 0;
}
