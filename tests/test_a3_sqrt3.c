/* test_a3_sqrt3.c — sqrt3 refinement and coarsening (a3_sqrt3.h, sqrt3 paper
 * §5): uniform refinement to the maximum generation (triangle counts of the
 * tri-adic split, area kept, a valid manifold mesh with consistent
 * orientation and the generation rule) and back to the base mesh exactly;
 * long random refine / coarsen sequences keep every invariant and end on
 * the base mesh. */
#include "sb_test.h"
#include "../methods/adaptive_sqrt3/a3_sqrt3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *SCENE =
    "{\"name\": \"t\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1.5]},"
    " \"geometry\": {\"type\": \"plane\"}, \"material\": {\"model\": \"stvk\", \"young\": 1e6, \"poisson\": 0.3,"
    " \"thickness\": 0.001, \"density\": 0.1}, \"boundary\": [{\"type\": \"fixed\", \"on\": [\"top\"]}],"
    " \"time\": {\"mode\": \"dynamic\", \"dt\": 0.01, \"steps\": 1}}";

static unsigned long long rng = 12345;
static int rnd(int n)
{
    rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
    return (int)((rng >> 33) % (unsigned long long)n);
}

static double st_area(const sb_mesh *m)
{
    double a = 0;
    for (int t = 0; t < m->nt; t++) a += sb_mesh_tri_area_st(m, t);
    return a;
}

static int same_mesh(const sb_mesh *a, const sb_mesh *b)
{
    if (a->nv != b->nv || a->nt != b->nt || a->ne != b->ne) return 0;
    return !memcmp(a->tri, b->tri, sizeof(int) * 3 * (size_t)a->nt) &&
           !memcmp(a->st, b->st, sizeof(double) * 2 * (size_t)a->nv) &&
           !memcmp(a->edge_v, b->edge_v, sizeof(int) * 2 * (size_t)a->ne);
}

/* forest invariants and the exported mesh's (manifold, orientation, boundary, positive areas) */
static void check_all(sb_test_state *T, const a3_forest *F, const sb_scene *sc, const char *when)
{
    char msg[512];
    CHECK_MSG(a3_forest_check(F, msg, sizeof msg) == 0, "%s: %s", when, msg);
    sb_mesh m;
    sb_mesh_init(&m);
    int *vmap = NULL;
    CHECK_MSG(a3_forest_mesh(F, sc, &m, &vmap) == SB_OK, "%s: export failed", when);
    CHECK_MSG(sb_mesh_check(&m, msg, sizeof msg) == SB_OK, "%s: %s", when, msg);
    CHECK_MSG(fabs(st_area(&m) - 1.0) < 1e-12, "%s: (s,t) area %.15g", when, st_area(&m));
    /* the domain boundary is kept: boundary vertices lie on the unit square's sides */
    for (int v = 0; v < m.nv; v++)
        if (m.vflag[v] & SB_MESH_V_BOUNDARY) {
            const double s = m.st[2 * v], t = m.st[2 * v + 1];
            CHECK(fabs(s) < 1e-14 || fabs(s - 1) < 1e-14 || fabs(t) < 1e-14 || fabs(t - 1) < 1e-14);
        }
    free(vmap);
    sb_mesh_free(&m);
}

static int base_mesh(sb_scene *sc, sb_mesh *m, int n)
{
    char err[512];
    if (sb_scene_parse_string(SCENE, "inline.json", sc, err, sizeof err)) return -1;
    sb_mesh_spec spec = { n, n, SB_MESH_ALTERNATE, 0, 1 };
    const char *rn = NULL;
    sb_mesh_init(m);
    return sb_mesh_from_domain(sc, &spec, m, &rn, err, sizeof err);
}

SB_TEST(test_refine_all_coarsen_all)
{
    sb_scene sc;
    sb_mesh base;
    CHECK(base_mesh(&sc, &base, 2) == SB_OK);
    for (int gmax = 2; gmax <= 6; gmax += 2) {
        a3_forest F;
        CHECK(a3_forest_init(&F, &base, gmax) == SB_OK);
        CHECK(a3_forest_refine_all(&F) == SB_OK);
        check_all(T, &F, &sc, "refined");
        int n = 0, at_max = 0, waiting = 0;
        for (int t = 0; t < F.nt; t++)
            if (F.t[t].alive) {
                n++;
                at_max += F.t[t].gen == gmax;
                /* a boundary triangle one below: its boundary step (g + 3) would pass the maximum */
                waiting += F.t[t].gen == gmax - 1 && F.t[t].mate >= 0 &&
                           a3_forest_across(&F, F.t[t].v[(F.t[t].mate + 1) % 3], F.t[t].v[(F.t[t].mate + 2) % 3], t) < 0;
            }
        printf("    max generation %d: %d triangles (base %d, x %.1f), %d at generation %d\n", gmax, n, base.nt,
               (double)n / base.nt, at_max, gmax);
        /* every sqrt3 step (split + flip, two generations) triples the triangles; two are a tri-adic split */
        CHECK_EQ_INT(n, base.nt * (int)lround(pow(3.0, gmax / 2)));
        CHECK_EQ_INT(at_max + waiting, n);
        if (gmax % 4 == 0) CHECK_EQ_INT(waiting, 0);
        CHECK(a3_forest_coarsen_all(&F) == SB_OK);
        sb_mesh m;
        sb_mesh_init(&m);
        int *vmap = NULL;
        CHECK(a3_forest_mesh(&F, &sc, &m, &vmap) == SB_OK);
        CHECK_MSG(same_mesh(&m, &base), "coarsening everything did not return the base mesh (%d vs %d triangles)", m.nt,
                  base.nt);
        free(vmap);
        sb_mesh_free(&m);
        a3_forest_free(&F);
    }
    sb_mesh_free(&base);
    sb_scene_free(&sc);
}

SB_TEST(test_random_sequences)
{
    sb_scene sc;
    sb_mesh base;
    CHECK(base_mesh(&sc, &base, 3) == SB_OK);
    a3_forest F;
    CHECK(a3_forest_init(&F, &base, 6) == SB_OK);
    int refined = 0, coarsened = 0, maxn = 0;
    for (int it = 0; it < 3000; it++) {
        if (rnd(100) < 55) {
            const int t = rnd(F.nt);
            if (F.t[t].alive) refined += a3_forest_refine(&F, t) > 0;
        } else if (F.nop) {
            coarsened += a3_forest_coarsen(&F, rnd(F.nop)) > 0;
        }
        int n = 0;
        for (int t = 0; t < F.nt; t++) n += F.t[t].alive;
        if (n > maxn) maxn = n;
        if (it % 250 == 0) check_all(T, &F, &sc, "random sequence");
    }
    check_all(T, &F, &sc, "random sequence end");
    printf("    %d refinements, %d coarsenings, up to %d triangles, %d records\n", refined, coarsened, maxn, F.nt);
    CHECK(refined > 100 && coarsened > 50);
    CHECK(a3_forest_coarsen_all(&F) == SB_OK);
    sb_mesh m;
    sb_mesh_init(&m);
    int *vmap = NULL;
    CHECK(a3_forest_mesh(&F, &sc, &m, &vmap) == SB_OK);
    CHECK_MSG(same_mesh(&m, &base), "coarsening everything did not return the base mesh (%d vs %d triangles)", m.nt, base.nt);
    free(vmap);
    sb_mesh_free(&m);
    a3_forest_free(&F);
    sb_mesh_free(&base);
    sb_scene_free(&sc);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_refine_all_coarsen_all),
        SB_CASE(test_random_sequences),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
