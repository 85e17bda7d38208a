/* test_lf_imperfection.c — method.imperfection of linear_fem: its vertices on
 * the imperfect surface chart + delta n of core/scene/sb_imperfection.c, the
 * field bhem puts at its nodes (the two methods buckle from the same
 * surface, bench/bhem/fem_compare.sh), a stress-free reference, and no
 * change at all without it. */
#include "test_lf_common.h"
#include "sb_imperfection.h"
#include "sb_sparse.h"

#include <math.h>
#include <stdio.h>

#define SHEET TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "[{\"type\": \"clamped\", \"on\": [\"left\", \"right\"]}]", "[]")

SB_TEST(vertices_sit_on_the_shared_imperfect_surface)
{
    const double A = 1e-3;
    const char *with[] = { "method.mesh=jitter", "method.imperfection=0.001", NULL };
    const char *without[] = { "method.mesh=jitter", NULL };
    tl_method m, m0;
    CHECK_EQ_INT(tl_create(&m, SHEET, 8, 1, with), SB_OK);
    CHECK_EQ_INT(tl_create(&m0, SHEET, 8, 1, without), SB_OK);
    if (!m.S || !m0.S) return;
    const int n = sb_method_linear_fem.n_dofs(m.S, 0), nv = m.S->lv[0].nv;
    CHECK_EQ_INT(n, sb_method_linear_fem.n_dofs(m0.S, 0));
    double *x = malloc(sizeof(double) * n), *x0 = malloc(sizeof(double) * n), *g = calloc(n, sizeof(double)), f;
    sb_method_linear_fem.initial(m.S, 0, x);
    sb_method_linear_fem.initial(m0.S, 0, x0);
    double zmax = 0;
    for (int v = 0; v < nv; v++) {
        const double *st = m.S->lv[0].mesh.st + 2 * v;
        double imp[4];
        sb_imperfection_eval(A, st[0], st[1], imp);
        /* flat sheet: the unit normal is +z; in-plane positions (the jitter mesh) unchanged */
        CHECK_NEAR(x[3 * v + 2], imp[0], 1e-15);
        CHECK_NEAR(x[3 * v], x0[3 * v], 0.0);
        CHECK_NEAR(x[3 * v + 1], x0[3 * v + 1], 0.0);
        CHECK_NEAR(x0[3 * v + 2], 0.0, 0.0);
        CHECK(fabs(imp[0]) <= A);
        zmax = fmax(zmax, fabs(imp[0]));
    }
    CHECK_MSG(zmax > 0.2 * A, "the field is nearly zero at the vertices (max %g)", zmax);
    /* the imperfect surface is the stress-free reference */
    tl_step(&m, 1.0, 1.0);
    CHECK_EQ_INT(sb_method_linear_fem.energy(m.S, 0, x, &f, g, NULL), SB_OK);
    CHECK_NEAR(f, 0.0, 1e-14);
    CHECK_MSG(sb_norm2(n, g) < 1e-9, "rest gradient %g", sb_norm2(n, g));
    /* and differs from the flat one: flattening it costs bending energy */
    CHECK_EQ_INT(sb_method_linear_fem.energy(m.S, 0, x0, &f, NULL, NULL), SB_OK);
    CHECK(f > 0.0);
    free(x); free(x0); free(g);
    tl_free(&m);
    tl_free(&m0);
}

SB_TEST(bhem_nodes_carry_the_same_field)
{
    /* bhem interpolates its node values: at a grid node its reference
     * surface is chart + delta n with the same delta */
    const double A = 1e-3;
    char err[1024];
    sb_scene sc;
    CHECK_EQ_INT(sb_scene_parse_string(SHEET, "inline.json", &sc, err, sizeof err), SB_OK);
    const sb_method_type *M = sb_method_find("bhem");
    sb_paramset ps;
    sb_paramset_init(&ps);
    sb_paramset_add(&ps, "method", M->params);
    CHECK_EQ_INT(sb_paramset_set(&ps, "method.imperfection=0.001", err, sizeof err), SB_OK);
    void *S = calloc(1, M->state_size);
    sb_method_config cfg = { 5, 1, &ps, NULL, 0 };
    CHECK_EQ_INT(M->create(S, &sc, &cfg), SB_OK);
    const int n = M->n_dofs(S, 0);
    double *x = malloc(sizeof(double) * n);
    M->initial(S, 0, x);
    for (int j = 0; j <= 5; j++)
        for (int i = 0; i <= 5; i++) {
            double st[2] = { i / 5.0, j / 5.0 }, p[3], imp[4];
            CHECK_EQ_INT(M->eval_points(S, 0, x, 1, st, p), 0);
            sb_imperfection_eval(A, st[0], st[1], imp);
            CHECK_NEAR(p[2], imp[0], 1e-15);
        }
    free(x);
    M->destroy(S);
    free(S);
    sb_scene_free(&sc);
}

SB_TEST(negative_imperfection_is_refused)
{
    const char *sets[] = { "method.imperfection=-1e-6", NULL };
    tl_method m;
    CHECK(tl_create(&m, SHEET, 4, 1, sets) != SB_OK);
    tl_free(&m);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(vertices_sit_on_the_shared_imperfect_surface), SB_CASE(bhem_nodes_carry_the_same_field),
        SB_CASE(negative_imperfection_is_refused), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
