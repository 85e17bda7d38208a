/* bhem_profile.c — evaluate a BHEM run's final surface on a fine grid of
 * grid parameters (for wrinkle counts, wavelengths and amplitudes).  Reports
 * read the HDF5 record written by `shellbench run --out FILE.h5`; they never
 * re-run the simulation.
 *
 * usage: bhem_profile SCENE.json RECORD.h5 RES CELLS_T NS NT [S0 S1 T0 T1]
 *   prints "s,t,x,y,z" for an NS x NT grid over [S0,S1] x [T0,T1] (default
 *   the whole domain), evaluated from /final/x with the method at --res RES
 *   and method.cells_t = CELLS_T (0 = RES), single level. */
#include "../../methods/bhem/bhem.h"
#include "sb_context.h"

#include "record_x.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>


int main(int argc, char **argv)
{
    if (argc != 7 && argc != 11) {
        fprintf(stderr, "usage: %s SCENE.json RECORD.h5 RES CELLS_T NS NT [S0 S1 T0 T1]\n", argv[0]);
        return 2;
    }
    int res = atoi(argv[3]), cells_t = atoi(argv[4]), ns = atoi(argv[5]), nt = atoi(argv[6]);
    double box[4] = { 0, 1, 0, 1 };
    for (int k = 0; argc == 11 && k < 4; k++) box[k] = atof(argv[7 + k]);
    if (res < 1 || cells_t < 0 || ns < 2 || nt < 1) { fprintf(stderr, "bhem_profile: bad sizes\n"); return 2; }
    sb_scene scene;
    char err[1024];
    if (sb_scene_load(argv[1], &scene, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 2; }
    sb_context ctx;
    if (sb_context_init(&ctx)) return 3;
    sb_paramset *ps = &ctx.params;
    sb_paramset_add(ps, "method", sb_method_bhem.params);
    char set[64];
    snprintf(set, sizeof set, "method.cells_t=%d", cells_t);
    sb_paramset_set(ps, set, err, sizeof err);
    bhem_state *S = calloc(1, sb_method_bhem.state_size);
    sb_method_config cfg = { res, 1, ps, &ctx, 0 };
    int rc = S ? sb_method_bhem.create(S, &scene, &cfg) : SB_ERR_NOMEM;
    if (rc) { fprintf(stderr, "bhem_profile: %s\n", ctx.err); return 2; }
    long n = 0;
    double *x = read_x(argv[2], &n);
    if (!x || n != sb_method_bhem.n_dofs(S, 0)) {
        fprintf(stderr, "bhem_profile: %s: /final/x has %ld values, the %d-patch grid needs %d\n", argv[2], n, res,
                sb_method_bhem.n_dofs(S, 0));
        return 2;
    }
    printf("s,t,x,y,z\n");
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) {
            double st[2] = { box[0] + (box[1] - box[0]) * i / (ns - 1),
                             nt > 1 ? box[2] + (box[3] - box[2]) * j / (nt - 1) : box[2] };
            double p[3];
            if (sb_method_bhem.eval_points(S, 0, x, 1, st, p)) continue;
            printf("%.9g,%.9g,%.12g,%.12g,%.12g\n", st[0], st[1], p[0], p[1], p[2]);
        }
    free(x);
    sb_method_bhem.destroy(S);
    free(S);
    sb_scene_free(&scene);
    sb_context_free(&ctx);
    return 0;
}
