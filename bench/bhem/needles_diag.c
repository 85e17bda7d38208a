/* needles_diag.c — where a BHEM needle run strains its cloth most (issue 39:
 * needles at 16^2 stops with strain_bound).  Reads /final/x of a record,
 * evaluates the midsurface Green strain at every Gauss point with the same
 * kernel the run's material_state used (bhem_material_state), and prints the
 * K largest |E_ij| with their patch (i, j), grid parameter, position and the
 * horizontal distance of that point to the nearest capsule (needle) axis and
 * the height above that needle's apex.  Reports read records; this never
 * re-runs the simulation.
 *
 * usage: needles_diag SCENE.json RECORD.h5 RES [K] */
#include "../../methods/bhem/bhem.h"
#include "sb_context.h"
#include "sb_shell.h"

#include "record_x.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


typedef struct hit { double e, E[3], st[2], p[3]; int elem, comp; } hit;

static int cmp(const void *a, const void *b)
{
    double x = ((const hit *)a)->e, y = ((const hit *)b)->e;
    return x < y ? 1 : x > y ? -1 : 0;
}

int main(int argc, char **argv)
{
    if (argc != 4 && argc != 5) {
        fprintf(stderr, "usage: %s SCENE.json RECORD.h5 RES [K]\n", argv[0]);
        return 2;
    }
    const int res = atoi(argv[3]), K = argc == 5 ? atoi(argv[4]) : 10;
    sb_scene scene;
    char err[1024];
    if (sb_scene_load(argv[1], &scene, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 2; }
    sb_context ctx;
    if (sb_context_init(&ctx)) return 3;
    sb_paramset_add(&ctx.params, "method", sb_method_bhem.params);
    bhem_state *S = calloc(1, sb_method_bhem.state_size);
    sb_method_config cfg = { res, 1, &ctx.params, &ctx, 0 };
    if (!S || sb_method_bhem.create(S, &scene, &cfg)) { fprintf(stderr, "needles_diag: %s\n", ctx.err); return 2; }
    long n = 0;
    double *x = read_x(argv[2], &n);
    bhem_level *L = &S->lv[0];
    if (!x || n != L->n_dofs) { fprintf(stderr, "needles_diag: /final/x does not fit --res %d\n", res); return 2; }
    double gx[BHEM_NQ1], gw[BHEM_NQ1];
    bhem_gauss_rule(gx, gw);                 /* q = a + NQ1 b (bhem_grid.c) */
    hit *h = calloc((size_t)L->n_elems * BHEM_NQP, sizeof *h);
    int nh = 0;
    for (int e = 0; e < L->n_elems; e++) {
        bhem_gather(L, e, x, S->qe);
        const sb_shell_ref *ref = L->ref + (size_t)e * BHEM_NQP;
        for (int q = 0; q < BHEM_NQP; q++) {
            const bhem_qp_basis *B = &L->qb[q];
            sb_shell_basis b = { BHEM_NB, B->N, B->N1, B->N2, B->N11, B->N12, B->N22 };
            sb_material_state ms;
            sb_material_state_init(&ms);
            sb_material_state_add(&ms, &S->mat, &ref[q], &b, S->qe, S->work);
            hit *t = &h[nh++];
            t->elem = e;
            for (int c = 0; c < 3; c++) {
                t->E[c] = ms.max_strain[c];
                if (ms.max_strain[c] > t->e) { t->e = ms.max_strain[c]; t->comp = c; }
            }
            double p[3] = { 0, 0, 0 };
            for (int I = 0; I < BHEM_NB; I++)
                for (int c = 0; c < 3; c++) p[c] += B->N[I] * S->qe[3 * I + c];
            memcpy(t->p, p, sizeof p);
            /* grid parameter of the Gauss point: patch corner + local coordinate */
            const int cell = L->elem_cell[e], ci = cell % L->n1, cj = cell / L->n1;
            t->st[0] = (ci + gx[q % BHEM_NQ1]) / L->n1;
            t->st[1] = (cj + gx[q / BHEM_NQ1]) / L->n2;
            t->elem = cell;
        }
    }
    qsort(h, (size_t)nh, sizeof *h, cmp);
    static const char *const name[] = { "E11", "E22", "E12" };
    printf("rank,patch_i,patch_j,s,t,x,y,z,E11,E22,E12,largest,needle,dist_axis_m,height_above_apex_m\n");
    for (int k = 0; k < K && k < nh; k++) {
        const hit *t = &h[k];
        int best = -1;
        double bd = INFINITY, up = 0;
        for (int o = 0; o < scene.n_obstacles; o++) {
            const sb_obstacle_spec *ob = &scene.obstacles[o];
            if (ob->kind != SB_OBST_CAPSULE) continue;
            const double dx = t->p[0] - ob->b[0], dy = t->p[1] - ob->b[1], d = sqrt(dx * dx + dy * dy);
            if (d < bd) { bd = d; best = o; up = t->p[2] - ob->b[2] - ob->radius; }
        }
        printf("%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%s,%s,%.4f,%.4f\n", k + 1, t->elem % L->n1,
               t->elem / L->n1, t->st[0], t->st[1], t->p[0], t->p[1], t->p[2], t->E[0], t->E[1], t->E[2],
               name[t->comp], best >= 0 ? scene.obstacles[best].name : "-", bd, up);
    }
    free(h);
    free(x);
    sb_method_bhem.destroy(S);
    free(S);
    sb_scene_free(&scene);
    sb_context_free(&ctx);
    return 0;
}
