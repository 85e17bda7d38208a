/* surface_profile.c — evaluate the final surface of a run of any method on a
 * fine grid of grid parameters (wrinkle counts, wavelengths and amplitudes of
 * bhem and linear_fem runs side by side; bench/bhem/fem_compare.sh).  The
 * method is made again from the scene with the run's options (the same
 * --res and --set assignments; a linear_fem jitter mesh is fixed by
 * method.jitter and run.seed) and /final/x of the record is evaluated with
 * its eval_points.  Reports never re-run the simulation.
 *
 * usage: surface_profile METHOD SCENE.json RECORD.h5 RES NS NT [KEY=VALUE ...]
 *   prints "s,t,x,y,z" for an NS x NT grid over the whole (s,t) square,
 *   single level. */
#include "sb_context.h"
#include "sb_method.h"
#include "sb_solver.h"

#include "record_x.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>


int main(int argc, char **argv)
{
    if (argc < 7) {
        fprintf(stderr, "usage: %s METHOD SCENE.json RECORD.h5 RES NS NT [KEY=VALUE ...]\n", argv[0]);
        return 2;
    }
    const sb_method_type *M = sb_method_find(argv[1]);
    if (!M) { fprintf(stderr, "surface_profile: unknown method %s\n", argv[1]); return 2; }
    int res = atoi(argv[4]), ns = atoi(argv[5]), nt = atoi(argv[6]);
    if (res < 1 || ns < 2 || nt < 1) { fprintf(stderr, "surface_profile: bad sizes\n"); return 2; }
    sb_scene scene;
    char err[1024];
    if (sb_scene_load(argv[2], &scene, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 2; }
    sb_context ctx;
    if (sb_context_init(&ctx)) return 3;
    sb_paramset *ps = &ctx.params;
    sb_paramset_add(ps, "method", M->params);
    sb_paramset_add(ps, "run", sb_solve_params);
    for (int k = 7; k < argc; k++)
        if (sb_paramset_set(ps, argv[k], err, sizeof err)) { fprintf(stderr, "surface_profile: %s\n", err); return 2; }
    void *S = calloc(1, M->state_size);
    sb_method_config cfg = { res, 1, ps, &ctx, 0 };
    int rc = S ? M->create(S, &scene, &cfg) : SB_ERR_NOMEM;
    if (rc) { fprintf(stderr, "surface_profile: %s\n", ctx.err); return 2; }
    long n = 0;
    double *x = read_x(argv[3], &n);
    if (!x || n != M->n_dofs(S, 0)) {
        fprintf(stderr, "surface_profile: %s: /final/x has %ld values, the method at --res %d has %d dofs\n", argv[3], n,
                res, M->n_dofs(S, 0));
        return 2;
    }
    printf("s,t,x,y,z\n");
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) {
            double st[2] = { (double)i / (ns - 1), nt > 1 ? (double)j / (nt - 1) : 0.5 };
            double p[3];
            if (M->eval_points(S, 0, x, 1, st, p)) continue;
            printf("%.9g,%.9g,%.12g,%.12g,%.12g\n", st[0], st[1], p[0], p[1], p[2]);
        }
    free(x);
    M->destroy(S);
    free(S);
    sb_scene_free(&scene);
    sb_context_free(&ctx);
    return 0;
}
