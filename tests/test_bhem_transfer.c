/* test_bhem_transfer.c — BHEM level hierarchy: prolongation is exact (nested
 * Hermite spaces), restriction is its transpose, projection is injection
 * with P I = id; on rectangles, L-shapes and periodic cylinders. */
#include "test_bhem_common.h"

#include <math.h>

static const char *scene_json(int k, char *buf, size_t len)
{
    static const char *dom[3] = {
        "{\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1.0, 0.6]}",
        "{\"type\": \"l_shape\", \"origin\": [0, 0], \"size\": [1, 1], \"notch\": [0.5, 0.5], \"notch_corner\": \"10\"}",
        "{\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1.0, 0.6]}",
    };
    static const char *geo[3] = {
        TB_PLANE, TB_PLANE, "{\"type\": \"cylinder\", \"radius\": 0.3, \"angle\": [0, 360], \"length\": 0.6}"
    };
    snprintf(buf, len, TB_SCENE("%s", "%s", TB_STVK, "[{\"type\": \"clamped\", \"on\": [\"bottom\"]}]", "[]"), dom[k], geo[k]);
    return buf;
}

static void check_hierarchy(sb_test_state *T, int k, int res, int levels)
{
    char json[2048];
    tb_method m;
    int rc = tb_create(&m, scene_json(k, json, sizeof json), res, levels, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    CHECK(sb_method_bhem.flags & SB_METHOD_HIERARCHY);
    unsigned long long st = 99 + k;
    for (int lc = 0; lc + 1 < levels; lc++) {
        int nc = sb_method_bhem.n_dofs(m.S, lc), nf = sb_method_bhem.n_dofs(m.S, lc + 1);
        double *xc = malloc(sizeof(double) * nc), *xc2 = malloc(sizeof(double) * nc), *rc_ = malloc(sizeof(double) * nc);
        double *xf = malloc(sizeof(double) * nf), *yf = malloc(sizeof(double) * nf);
        for (int i = 0; i < nc; i++) xc[i] = tb_rand(&st);
        for (int i = 0; i < nf; i++) yf[i] = tb_rand(&st);
        /* P I = id */
        CHECK_EQ_INT(sb_method_bhem.prolong(m.S, lc, xc, xf), SB_OK);
        CHECK_EQ_INT(sb_method_bhem.project(m.S, lc, xf, xc2), SB_OK);
        double worst = 0;
        for (int i = 0; i < nc; i++) worst = fmax(worst, fabs(xc2[i] - xc[i]));
        CHECK_MSG(worst < 1e-14, "level %d: |P I x - x| = %g", lc, worst);
        /* <I xc, yf> = <xc, R yf> */
        CHECK_EQ_INT(sb_method_bhem.restrict_adj(m.S, lc, yf, rc_), SB_OK);
        double a = sb_dot(nf, xf, yf), b = sb_dot(nc, xc, rc_);
        CHECK_MSG(fabs(a - b) <= 1e-12 * (fabs(a) + 1), "level %d: <I x, y> = %.15g, <x, R y> = %.15g", lc, a, b);
        /* exactness: the fine surface equals the coarse one everywhere */
        enum { NP = 40 };
        double pts[2 * NP], pc[3 * NP], pf[3 * NP];
        int np = 0;
        while (np < NP) {
            double s = 0.5 + 0.5 * tb_rand(&st), t = 0.5 + 0.5 * tb_rand(&st);
            if (!sb_domain_contains_st(&m.scene.domain, s, t)) continue;
            pts[2 * np] = s;
            pts[2 * np + 1] = t;
            np++;
        }
        CHECK_EQ_INT(sb_method_bhem.eval_points(m.S, lc, xc, NP, pts, pc), SB_OK);
        CHECK_EQ_INT(sb_method_bhem.eval_points(m.S, lc + 1, xf, NP, pts, pf), SB_OK);
        worst = 0;
        for (int i = 0; i < 3 * NP; i++) worst = fmax(worst, fabs(pc[i] - pf[i]));
        CHECK_MSG(worst < 1e-13, "level %d: surfaces differ by %g", lc, worst);
        /* the restriction is not the injection (the test can tell them apart) */
        sb_method_bhem.project(m.S, lc, yf, xc2);
        worst = 0;
        for (int i = 0; i < nc; i++) worst = fmax(worst, fabs(xc2[i] - rc_[i]));
        CHECK(worst > 1e-3);
        /* plane chart: the coarse reference prolongs to the fine reference */
        if (k < 2) {
            sb_method_bhem.initial(m.S, lc, xc);
            sb_method_bhem.prolong(m.S, lc, xc, xf);
            sb_method_bhem.initial(m.S, lc + 1, yf);
            worst = 0;
            for (int i = 0; i < nf; i++) worst = fmax(worst, fabs(xf[i] - yf[i]));
            CHECK(worst < 1e-15);
        }
        free(xc); free(xc2); free(rc_); free(xf); free(yf);
    }
    tb_free(&m);
}

SB_TEST(test_rectangle) { check_hierarchy(T, 0, 8, 3); }
SB_TEST(test_l_shape) { check_hierarchy(T, 1, 8, 3); }
SB_TEST(test_periodic_cylinder) { check_hierarchy(T, 2, 8, 2); }

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_rectangle), SB_CASE(test_l_shape), SB_CASE(test_periodic_cylinder), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
