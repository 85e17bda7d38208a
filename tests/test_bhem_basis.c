/* test_bhem_basis.c — BHEM shape functions, quadrature, patch grid, DOF
 * layout and the exact initial state from the chart. */
#include "test_bhem_common.h"

#include <float.h>
#include <gsl/gsl_integration.h>
#include <math.h>

/* partition of unity: the value-kind functions sum to 1, their derivatives to 0 */
SB_TEST(test_partition_of_unity)
{
    unsigned long long st = 7;
    double N[16], N1[16], N2[16], N11[16], N12[16], N22[16];
    for (int k = 0; k < 50; k++) {
        double a = 0.5 + 0.5 * tb_rand(&st), b = 0.5 + 0.5 * tb_rand(&st);
        bhem_basis_eval(a, b, 0.25, 0.1, N, N1, N2, N11, N12, N22);
        double s[6] = { 0 };
        for (int c = 0; c < 4; c++) {
            int I = 4 * c;   /* kind 0 of corner c */
            s[0] += N[I]; s[1] += N1[I]; s[2] += N2[I]; s[3] += N11[I]; s[4] += N12[I]; s[5] += N22[I];
        }
        CHECK_NEAR(s[0], 1.0, 1e-14);
        for (int d = 1; d < 6; d++) CHECK_NEAR(s[d], 0.0, 1e-10);
    }
}

/* Hermite interpolation property at the corners (BHEM App. A) */
SB_TEST(test_nodal_interpolation)
{
    double hs = 0.5, ht = 0.2, N[16], N1[16], N2[16], N12[16];
    for (int corner = 0; corner < 4; corner++) {
        double a = corner & 1, b = corner >> 1;
        bhem_basis_eval(a, b, hs, ht, N, N1, N2, NULL, N12, NULL);
        for (int I = 0; I < 16; I++) {
            int me = I / 4 == corner;
            CHECK_NEAR(N[I], me && I % 4 == 0 ? 1.0 : 0.0, 1e-15);
            CHECK_NEAR(N1[I] * hs, me && I % 4 == 1 ? 1.0 : 0.0, 1e-14);
            CHECK_NEAR(N2[I] * ht, me && I % 4 == 2 ? 1.0 : 0.0, 1e-14);
            CHECK_NEAR(N12[I] * hs * ht, me && I % 4 == 3 ? 1.0 : 0.0, 1e-14);
        }
    }
}

/* first and second derivatives against central differences */
SB_TEST(test_basis_fd)
{
    const double hs = 0.3, ht = 0.7, e = 1e-5;
    double N[16], N1[16], N2[16], N11[16], N12[16], N22[16];
    double P[16], M[16], P1[16], M1[16], P2[16], M2[16];
    unsigned long long st = 11;
    double worst = 0.0;
    for (int k = 0; k < 20; k++) {
        double a = 0.5 + 0.45 * tb_rand(&st), b = 0.5 + 0.45 * tb_rand(&st);
        bhem_basis_eval(a, b, hs, ht, N, N1, N2, N11, N12, N22);
        /* d/ds = (1/hs) d/dth1 */
        bhem_basis_eval(a + e, b, hs, ht, P, P1, P2, NULL, NULL, NULL);
        bhem_basis_eval(a - e, b, hs, ht, M, M1, M2, NULL, NULL, NULL);
        for (int I = 0; I < 16; I++) {
            worst = fmax(worst, fabs((P[I] - M[I]) / (2 * e * hs) - N1[I]));
            worst = fmax(worst, fabs((P1[I] - M1[I]) / (2 * e * hs) - N11[I]) * hs);
            worst = fmax(worst, fabs((P2[I] - M2[I]) / (2 * e * hs) - N12[I]) * hs);
        }
        bhem_basis_eval(a, b + e, hs, ht, P, P1, P2, NULL, NULL, NULL);
        bhem_basis_eval(a, b - e, hs, ht, M, M1, M2, NULL, NULL, NULL);
        for (int I = 0; I < 16; I++) {
            worst = fmax(worst, fabs((P[I] - M[I]) / (2 * e * ht) - N2[I]));
            worst = fmax(worst, fabs((P2[I] - M2[I]) / (2 * e * ht) - N22[I]) * ht);
            worst = fmax(worst, fabs((P1[I] - M1[I]) / (2 * e * ht) - N12[I]) * ht);
        }
    }
    CHECK(worst < 1e-8);
}

/* 4-point Gauss–Legendre on [0,1] integrates degree 7 exactly (App. A) */
SB_TEST(test_gauss_rule)
{
    double x[4], w[4];
    bhem_gauss_rule(x, w);
    for (int p = 0; p <= 7; p++) {
        double s = 0.0;
        for (int i = 0; i < 4; i++) s += w[i] * pow(x[i], p);
        CHECK_NEAR(s, 1.0 / (p + 1), 1e-15);
    }
    double s8 = 0.0;
    for (int i = 0; i < 4; i++) s8 += w[i] * pow(x[i], 8);
    CHECK(fabs(s8 - 1.0 / 9) > 1e-6);   /* and not degree 8: the test can fail */
    /* the paper's closed form is GSL's 4-point rule on [0, 1] up to round-off
     * (kept for its bits, bhem_basis.c): within eps |GSL's| (about 2 ulp) */
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(4);
    CHECK(t != NULL);
    if (!t) return;
    for (int i = 0; i < 4; i++) {
        double xg, wg;
        gsl_integration_glfixed_point(0.0, 1.0, (size_t)i, &xg, &wg, t);
        CHECK_NEAR(x[i], xg, DBL_EPSILON * xg);
        CHECK_NEAR(w[i], wg, DBL_EPSILON * wg);
    }
    gsl_integration_glfixed_table_free(t);
}

/* A bicubic polynomial surface is reproduced exactly from nodal data */
SB_TEST(test_bicubic_reproduction)
{
    tb_method m;
    int rc = tb_create(&m, TB_SCENE(TB_RECT, TB_PLANE, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]", "[]"),
                       5, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    bhem_level *L = &m.S->lv[0];
    double c[3][4][4];
    unsigned long long st = 3;
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) c[k][i][j] = tb_rand(&st);
    double *x = malloc(sizeof(double) * L->n_dofs);
    for (int n = 0; n < L->n_nodes; n++) {
        double s = L->node_i[n] * L->hs, t = L->node_j[n] * L->ht;
        for (int k = 0; k < 3; k++) {
            double v = 0, vs = 0, vt = 0, vst = 0;
            for (int i = 0; i < 4; i++)
                for (int j = 0; j < 4; j++) {
                    double a = c[k][i][j];
                    v += a * pow(s, i) * pow(t, j);
                    if (i) vs += a * i * pow(s, i - 1) * pow(t, j);
                    if (j) vt += a * j * pow(s, i) * pow(t, j - 1);
                    if (i && j) vst += a * i * j * pow(s, i - 1) * pow(t, j - 1);
                }
            x[12 * n + k] = v;
            x[12 * n + 3 + k] = L->hs * vs;
            x[12 * n + 6 + k] = L->ht * vt;
            x[12 * n + 9 + k] = L->hs * L->ht * vst;
        }
    }
    double pts[2 * 30], pos[3 * 30], worst = 0;
    for (int p = 0; p < 30; p++) {
        pts[2 * p] = 0.5 + 0.5 * tb_rand(&st);
        pts[2 * p + 1] = 0.5 + 0.5 * tb_rand(&st);
    }
    CHECK_EQ_INT(bhem_eval(m.S, L, x, 30, pts, pos), SB_OK);
    for (int p = 0; p < 30; p++)
        for (int k = 0; k < 3; k++) {
            double v = 0, s = pts[2 * p], t = pts[2 * p + 1];
            for (int i = 0; i < 4; i++)
                for (int j = 0; j < 4; j++) v += c[k][i][j] * pow(s, i) * pow(t, j);
            worst = fmax(worst, fabs(v - pos[3 * p + k]));
        }
    CHECK(worst < 1e-13);
    free(x);
    tb_free(&m);
}

#define TB_CYL_OPEN "{\"type\": \"cylinder\", \"radius\": 0.3, \"angle\": [-40, 40], \"length\": 0.6}"
#define TB_CYL_FULL "{\"type\": \"cylinder\", \"radius\": 0.3, \"angle\": [0, 360], \"length\": 0.6}"

/* Initial state: nodal values and patch-scaled derivatives are the chart's
 * exactly (incl. the mixed derivative); the interpolant converges O(h^4). */
SB_TEST(test_initial_from_chart)
{
    double err[2];
    for (int r = 0; r < 2; r++) {
        tb_method m;
        int rc = tb_create(&m, TB_SCENE(TB_RECT, TB_CYL_OPEN, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]", "[]"),
                           r ? 8 : 4, 1, NULL);
        CHECK_EQ_INT(rc, SB_OK);
        if (rc) return;
        bhem_level *L = &m.S->lv[0];
        CHECK_EQ_INT(L->n_dofs, 12 * (L->n1 + 1) * (L->n2 + 1));
        double *x = malloc(sizeof(double) * L->n_dofs), worst = 0;
        sb_method_bhem.initial(m.S, 0, x);
        for (int n = 0; n < L->n_nodes; n++) {
            sb_jet3 J;
            double s = L->node_i[n] * L->hs, t = L->node_j[n] * L->ht;
            sb_geometry_eval_st(&m.scene, s, t, &J);
            for (int k = 0; k < 3; k++) {
                worst = fmax(worst, fabs(x[12 * n + k] - J.x[k]));
                worst = fmax(worst, fabs(x[12 * n + 3 + k] - L->hs * J.d1[k]));
                worst = fmax(worst, fabs(x[12 * n + 6 + k] - L->ht * J.d2[k]));
                worst = fmax(worst, fabs(x[12 * n + 9 + k] - L->hs * L->ht * J.d12[k]));
            }
        }
        CHECK(worst < 1e-15);
        /* interpolation error at interior points */
        double pts[2 * 64], pos[3 * 64];
        for (int p = 0; p < 64; p++) {
            pts[2 * p] = (p % 8 + 0.37) / 8.0;
            pts[2 * p + 1] = (p / 8 + 0.61) / 8.0;
        }
        sb_method_bhem.eval_points(m.S, 0, x, 64, pts, pos);
        err[r] = 0;
        for (int p = 0; p < 64; p++) {
            sb_jet3 J;
            sb_geometry_eval_st(&m.scene, pts[2 * p], pts[2 * p + 1], &J);
            for (int k = 0; k < 3; k++) err[r] = fmax(err[r], fabs(pos[3 * p + k] - J.x[k]));
        }
        free(x);
        tb_free(&m);
    }
    CHECK(err[0] < 1e-4);
    CHECK_MSG(err[0] / err[1] > 12.0, "interpolation error ratio %g for h -> h/2 (expected ~16)", err[0] / err[1]);
}

/* Periodic seam of a closed cylinder: s = 0 and s = 1 nodes are shared */
SB_TEST(test_periodic_cylinder)
{
    tb_method m;
    int rc = tb_create(&m, TB_SCENE(TB_RECT, TB_CYL_FULL, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"bottom\"]}]", "[]"),
                       6, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    CHECK_EQ_INT(m.S->periodic_s, 1);
    CHECK_EQ_INT(m.S->periodic_t, 0);
    bhem_level *L = &m.S->lv[0];
    CHECK_EQ_INT(L->n_nodes, 6 * 7);
    CHECK_EQ_INT(bhem_node_at(m.S, L, 6, 3), bhem_node_at(m.S, L, 0, 3));
    /* the rest state is stress free across the seam */
    double *x = malloc(sizeof(double) * L->n_dofs), *g = calloc(L->n_dofs, sizeof(double)), f;
    sb_method_bhem.initial(m.S, 0, x);
    CHECK_EQ_INT(sb_method_bhem.energy(m.S, 0, x, &f, g, NULL), SB_OK);
    CHECK_NEAR(f, 0.0, 1e-14);
    CHECK(sb_norm2(L->n_dofs, g) < 1e-10);
    free(x); free(g);
    tb_free(&m);
    /* the open cylinder is not periodic */
    rc = tb_create(&m, TB_SCENE(TB_RECT, TB_CYL_OPEN, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"bottom\"]}]", "[]"),
                   6, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (!rc) CHECK_EQ_INT(m.S->periodic_s, 0);
    tb_free(&m);
}

/* L-shape: cells in the notch are masked; misaligned notches are refused */
SB_TEST(test_l_shape_mask)
{
    const char *dom = "{\"type\": \"l_shape\", \"origin\": [0, 0], \"size\": [1, 1], \"notch\": [0.5, 0.5], "
                      "\"notch_corner\": \"11\"}";
    char json[2048];
    snprintf(json, sizeof json, TB_SCENE("%s", TB_PLANE, TB_STVK, "[{\"type\": \"clamped\", \"on\": [\"left\"]}]", "[]"), dom);
    tb_method m;
    int rc = tb_create(&m, json, 8, 2, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    bhem_level *L = &m.S->lv[1];
    CHECK_EQ_INT(L->n_elems, 48);
    CHECK_EQ_INT(L->n_nodes, 81 - 16);   /* nodes strictly inside the notch are inactive */
    CHECK_EQ_INT(m.S->lv[0].n_elems, 12);
    double st[2] = { 0.75, 0.75 }, pos[3];
    double *x = malloc(sizeof(double) * L->n_dofs);
    sb_method_bhem.initial(m.S, 1, x);
    CHECK(bhem_eval(m.S, L, x, 1, st, pos) != SB_OK);   /* inside the notch */
    st[0] = 0.5; st[1] = 0.75;                          /* on the notch edge */
    CHECK_EQ_INT(bhem_eval(m.S, L, x, 1, st, pos), SB_OK);
    CHECK_NEAR(pos[0], 0.5, 1e-15);
    free(x);
    tb_free(&m);
    /* 3 patches per side do not align with a notch at 1/2 */
    rc = tb_create(&m, json, 6, 2, NULL);
    CHECK_EQ_INT(rc, SB_ERR_INPUT);
    tb_free(&m);
}

/* bad resolutions are input errors, not crashes */
SB_TEST(test_bad_resolution)
{
    tb_method m;
    const char *json = TB_SCENE(TB_RECT, TB_PLANE, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]", "[]");
    CHECK_EQ_INT(tb_create(&m, json, 6, 3, NULL), SB_ERR_INPUT);   /* 6 not divisible by 4 */
    tb_free(&m);
    CHECK_EQ_INT(tb_create(&m, json, 8, 3, NULL), SB_OK);
    if (m.S) {
        CHECK_EQ_INT(sb_method_bhem.n_levels(m.S), 3);
        CHECK_EQ_INT(sb_method_bhem.n_dofs(m.S, 0), 12 * 9);
        CHECK_EQ_INT(sb_method_bhem.n_dofs(m.S, 2), 12 * 81);
    }
    tb_free(&m);
    const char *sets[] = { "method.cells_t=2", NULL };
    CHECK_EQ_INT(tb_create(&m, json, 8, 1, sets), SB_OK);
    if (m.S) CHECK_EQ_INT(m.S->lv[0].n_elems, 16);
    tb_free(&m);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_partition_of_unity), SB_CASE(test_nodal_interpolation), SB_CASE(test_basis_fd),
        SB_CASE(test_gauss_rule), SB_CASE(test_bicubic_reproduction), SB_CASE(test_initial_from_chart),
        SB_CASE(test_periodic_cylinder), SB_CASE(test_l_shape_mask), SB_CASE(test_bad_resolution), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
