/* test_cc_subdiv.c — subdivision matrix S by the rules in C (RMTR paper
 * (5.12)–(5.15), (A.1)–(A.2)) against OpenSubdiv, on cages with
 * extraordinary vertices, boundaries, corners and the L-shape notch. */
#include "sb_test.h"
#include "../methods/rmtr/cc.h"
#include "sb_scene.h"

#include <stdlib.h>
#include <string.h>

/* max |S_rules - S_osd| over the union of both patterns; -1 on failure */
static double compare_with_osd(const cc_mesh *c)
{
    cc_mesh f;
    cc_csr S, So;
    cc_err e = { "" };
    if (cc_subdivide(c, &f, &S, &e)) return -1;
    if (cc_osd_subdiv_matrix(c, &So, &e)) {
        printf("    %s\n", e.msg);
        cc_mesh_free(&f);
        cc_csr_free(&S);
        return -1;
    }
    double d = 0;
    if (S.nr != So.nr || S.nc != So.nc) d = 1e300;
    for (int i = 0; i < S.nr && d < 1e300; i++) {
        for (int p = S.rp[i]; p < S.rp[i + 1]; p++) d = fmax(d, fabs(S.v[p] - cc_csr_get(&So, i, S.ci[p])));
        for (int p = So.rp[i]; p < So.rp[i + 1]; p++) d = fmax(d, fabs(So.v[p] - cc_csr_get(&S, i, So.ci[p])));
    }
    cc_mesh_free(&f);
    cc_csr_free(&S);
    cc_csr_free(&So);
    return d;
}

SB_TEST(rules_equal_opensubdiv)
{
    cc_err e = { "" };
    cc_mesh m;
    static const int vals[4] = { 3, 5, 6, 8 };
    for (int a = 0; a < 4; a++) {
        CHECK(cc_cage_star(vals[a], 3, &m, &e) == SB_OK);
        double d = compare_with_osd(&m);
        CHECK_MSG(d >= 0 && d < 1e-14, "star %d: max diff %g", vals[a], d);
        cc_mesh_free(&m);
    }
    CHECK(cc_cage_multi(&m, &e) == SB_OK);
    double d = compare_with_osd(&m);
    CHECK_MSG(d >= 0 && d < 1e-14, "multi: max diff %g", d);
    cc_mesh_free(&m);
    CHECK(cc_cage_cube(&m, &e) == SB_OK);
    d = compare_with_osd(&m);
    CHECK_MSG(d >= 0 && d < 1e-14, "cube: max diff %g", d);
    cc_mesh_free(&m);
    double lines[5];
    CHECK(cc_cage_lines(4, 0.7, 1, lines, NULL) == SB_OK);
    CHECK(cc_cage_grid(lines, 4, lines, 4, SB_CORNER_11, 1, 1, &m, &e) == SB_OK);
    d = compare_with_osd(&m);   /* boundary corners (valence 2) and the concave ghost corner */
    CHECK_MSG(d >= 0 && d < 1e-14, "L-shape: max diff %g", d);
    cc_mesh_free(&m);
}

/* The regular weights written out: vertex 9/16, 3/32, 1/64; edge 3/8, 1/16;
 * boundary vertex 3/4, 1/8; boundary edge 1/2. */
SB_TEST(regular_weights)
{
    double lines[4] = { 0, 1.0 / 3, 2.0 / 3, 1 };
    cc_mesh c, f;
    cc_csr S;
    cc_err e = { "" };
    CHECK(cc_cage_grid(lines, 3, lines, 3, -1, 0, 0, &c, &e) == SB_OK);
    CHECK(cc_subdivide(&c, &f, &S, &e) == SB_OK);
    int vid[6][6];
    for (int v = 0; v < c.nv; v++) vid[c.grid[2 * v] + 1][c.grid[2 * v + 1] + 1] = v;
    int v = vid[2][2];                              /* grid (1,1): interior */
    CHECK_NEAR(cc_csr_get(&S, v, v), 9.0 / 16, 1e-15);
    CHECK_NEAR(cc_csr_get(&S, v, vid[3][2]), 3.0 / 32, 1e-15);
    CHECK_NEAR(cc_csr_get(&S, v, vid[3][3]), 1.0 / 64, 1e-15);
    CHECK_EQ_INT(S.rp[v + 1] - S.rp[v], 9);
    int b = vid[0][2];                              /* grid (-1,1): cage boundary */
    CHECK_NEAR(cc_csr_get(&S, b, b), 0.75, 1e-15);
    CHECK_NEAR(cc_csr_get(&S, b, vid[0][1]), 0.125, 1e-15);
    CHECK_NEAR(cc_csr_get(&S, b, vid[1][2]), 0.0, 1e-15);
    int corner = vid[0][0];
    CHECK_NEAR(cc_csr_get(&S, corner, corner), 0.75, 1e-15);
    /* edge points: find the fine vertex at grid (3,2) = edge (1,1)-(2,1) in coarse grid units */
    for (int i = 0; i < f.nv; i++) {
        if (f.grid[2 * i] == 3 && f.grid[2 * i + 1] == 2) {
            CHECK_NEAR(cc_csr_get(&S, i, vid[2][2]), 3.0 / 8, 1e-15);
            CHECK_NEAR(cc_csr_get(&S, i, vid[2][3]), 1.0 / 16, 1e-15);
        }
        if (f.grid[2 * i] == -1 && f.grid[2 * i + 1] == -2) {   /* boundary edge midpoint */
            CHECK_NEAR(cc_csr_get(&S, i, vid[0][0]), 0.5, 1e-15);
            CHECK_NEAR(cc_csr_get(&S, i, vid[1][0]), 0.5, 1e-15);
        }
    }
    cc_csr_free(&S);
    cc_mesh_free(&f);
    cc_mesh_free(&c);
}

/* A hierarchy built with OpenSubdiv's S equals the one built by the rules. */
SB_TEST(hierarchy_osd_equals_rules)
{
    cc_err e = { "" };
    cc_mesh a, b;
    CHECK(cc_cage_star(5, 4, &a, &e) == SB_OK);
    CHECK(cc_cage_star(5, 4, &b, &e) == SB_OK);
    cc_hier ha, hb;
    CHECK(cc_hier_build(&ha, &a, 3, 0, &e) == SB_OK);
    int st = cc_hier_build(&hb, &b, 3, 1, &e);
    CHECK_MSG(st == SB_OK, "%s", e.msg);
    if (st) {
        cc_hier_free(&ha);
        return;
    }
    for (int l = 0; l < 2; l++) {
        CHECK_EQ_INT(ha.S[l].nr, hb.S[l].nr);
        double d = 0;
        for (int i = 0; i < ha.S[l].nr; i++)
            for (int p = ha.S[l].rp[i]; p < ha.S[l].rp[i + 1]; p++)
                d = fmax(d, fabs(ha.S[l].v[p] - cc_csr_get(&hb.S[l], i, ha.S[l].ci[p])));
        CHECK(d < 1e-14);
        CHECK_EQ_INT(ha.S[l].rp[ha.S[l].nr], hb.S[l].rp[hb.S[l].nr]);
    }
    cc_hier_free(&ha);
    cc_hier_free(&hb);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(rules_equal_opensubdiv),
        SB_CASE(regular_weights),
        SB_CASE(hierarchy_osd_equals_rules),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
