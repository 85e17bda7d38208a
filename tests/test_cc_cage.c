/* test_cc_cage.c — control cages and the level hierarchy of the rmtr method:
 * the paper's dof counts (147 ... 51,483), the ghost ring, the L-shape with
 * an exact notch, cages with extraordinary vertices. */
#include "sb_test.h"
#include "../methods/rmtr/cc.h"
#include "sb_scene.h"

#include <stdlib.h>
#include <string.h>

static double row_sum(const cc_csr *S, int i)
{
    double s = 0;
    for (int p = S->rp[i]; p < S->rp[i + 1]; p++) s += S->v[p];
    return s;
}

/* The paper's sizes: levels 1..6 = 4..128 elements per side + ghost ring. */
SB_TEST(square_sizes_match_paper)
{
    static const int paper[6] = { 147, 363, 1083, 3675, 13467, 51483 };
    double lines[5];
    cc_mesh m;
    cc_err e = { "" };
    CHECK(cc_cage_lines(4, 0, 0, lines, NULL) == SB_OK);
    CHECK(cc_cage_grid(lines, 4, lines, 4, -1, 0, 0, &m, &e) == SB_OK);
    cc_hier h;
    int st = cc_hier_build(&h, &m, 6, 0, &e);
    CHECK_MSG(st == SB_OK, "%s", e.msg);
    if (st) return;
    CHECK_EQ_INT(h.nlev, 6);
    for (int l = 0; l < 6; l++) {
        const cc_mesh *c = &h.mesh[l];
        int n = 4 << l;
        CHECK_EQ_INT(3 * c->nv, paper[l]);
        /* exactly one ghost ring: grid coordinates -1..n+1, (n+2)^2 faces, n^2 domain faces */
        int gmin = 1 << 30, gmax = -(1 << 30), ndom = 0;
        for (int v = 0; v < c->nv; v++)
            for (int s = 0; s < 2; s++) {
                if (c->grid[2 * v + s] < gmin) gmin = c->grid[2 * v + s];
                if (c->grid[2 * v + s] > gmax) gmax = c->grid[2 * v + s];
            }
        for (int f = 0; f < c->nf; f++) ndom += c->dom[f];
        CHECK_EQ_INT(gmin, -1);
        CHECK_EQ_INT(gmax, n + 1);
        CHECK_EQ_INT(c->nf, (n + 2) * (n + 2));
        CHECK_EQ_INT(ndom, n * n);
        /* uniform square: control parameters are the grid itself (ghost = mirror) */
        double err = 0;
        for (int v = 0; v < c->nv; v++)
            for (int s = 0; s < 2; s++) {
                double d = fabs(c->st[2 * v + s] - (double)c->grid[2 * v + s] / n);
                if (d > err) err = d;
            }
        CHECK(err < 1e-13);
        if (l + 1 < 6) {
            CHECK_EQ_INT(h.S[l].nr, h.mesh[l + 1].nv);
            CHECK_EQ_INT(h.S[l].nc, c->nv);
            double rs = 0;
            for (int i = 0; i < h.S[l].nr; i++) rs = fmax(rs, fabs(row_sum(&h.S[l], i) - 1.0));
            CHECK(rs < 1e-14);
        }
    }
    cc_hier_free(&h);
}

/* L-shape, notch 0.3 x 0.3 at corner 11: non-uniform coarse lines with a line
 * at 0.7; every level's notch lines are exact in the limit. */
SB_TEST(lshape_exact_notch)
{
    double lines[5];
    int m_notch = 0;
    CHECK(cc_cage_lines(4, 0.7, 1, lines, &m_notch) == SB_OK);
    CHECK_EQ_INT(m_notch, 1);
    CHECK_NEAR(lines[3], 0.7, 1e-15);
    CHECK_NEAR(lines[4], 1.0, 1e-15);
    cc_mesh m;
    cc_err e = { "" };
    int st = cc_cage_grid(lines, 4, lines, 4, SB_CORNER_11, 1, 1, &m, &e);
    CHECK_MSG(st == SB_OK, "%s", e.msg);
    if (st) return;
    cc_hier h;
    st = cc_hier_build(&h, &m, 4, 0, &e);
    CHECK_MSG(st == SB_OK, "%s", e.msg);
    if (st) return;
    /* level 0 by hand: the 7 x 7 grid minus the outer notch corner vertex (the
     * notch cell itself is the diagonal ghost face at the re-entrant corner) */
    for (int l = 0; l < 4; l++) {
        const cc_mesh *c = &h.mesh[l];
        int n = 4 << l, k = n / 4;              /* notch = k x k cells */
        if (l == 0) CHECK_EQ_INT(3 * c->nv, 3 * 48);
        printf("    L-shape level %d: %d dofs (paper, square: %d)\n", l + 1, 3 * c->nv,
               3 * (n + 3) * (n + 3));
        int ndom = 0;
        for (int f = 0; f < c->nf; f++) ndom += c->dom[f];
        CHECK_EQ_INT(ndom, n * n - k * k);
        /* every domain vertex is interior with valence 4 (re-entrant corner included) */
        int bad = 0;
        for (int f = 0; f < c->nf; f++)
            if (c->dom[f])
                for (int a = 0; a < 4; a++) {
                    int v = c->fv[4 * f + a];
                    bad += c->bnd[v] || c->val[v] != 4;
                }
        CHECK_EQ_INT(bad, 0);
        /* limit of the notch line i = n - k: (x_{i-1} + 4 x_i + x_{i+1})/6 = 0.7 on every row */
        int i0 = n - k, found = 0;
        double xm = 0, x0 = 0, xp = 0;
        for (int v = 0; v < c->nv; v++) {
            int gi = c->grid[2 * v];
            if (c->grid[2 * v + 1] != 0) continue;
            if (gi == i0 - 1) { xm = c->st[2 * v]; found++; }
            if (gi == i0) { x0 = c->st[2 * v]; found++; }
            if (gi == i0 + 1) { xp = c->st[2 * v]; found++; }
        }
        CHECK_EQ_INT(found, 3);
        CHECK_NEAR((xm + 4 * x0 + xp) / 6, 0.7, 1e-14);
    }
    cc_hier_free(&h);
}

static void count_valences(const cc_mesh *m, int hist[16])
{
    memset(hist, 0, 16 * sizeof *hist);
    for (int v = 0; v < m->nv; v++)
        if (!m->bnd[v] && m->val[v] < 16) hist[m->val[v]]++;
}

SB_TEST(star_and_multi_cages)
{
    static const int vals[4] = { 3, 5, 6, 8 };
    cc_err e = { "" };
    for (int a = 0; a < 4; a++) {
        cc_mesh m;
        int st = cc_cage_star(vals[a], 4, &m, &e);
        CHECK_MSG(st == SB_OK, "%s", e.msg);
        if (st) continue;
        int hist[16];
        count_valences(&m, hist);
        CHECK_EQ_INT(hist[vals[a]], 1);
        cc_hier h;
        st = cc_hier_build(&h, &m, 3, 0, &e);
        CHECK_MSG(st == SB_OK, "%s", e.msg);
        if (st) continue;
        for (int l = 0; l < 3; l++) {
            count_valences(&h.mesh[l], hist);
            CHECK_EQ_INT(hist[vals[a]], 1);     /* the extraordinary vertex persists */
        }
        cc_hier_free(&h);
    }
    cc_mesh m;
    int st = cc_cage_multi(&m, &e);
    CHECK_MSG(st == SB_OK, "%s", e.msg);
    if (!st) {
        int hist[16];
        count_valences(&m, hist);
        CHECK_EQ_INT(hist[3], 1);
        CHECK_EQ_INT(hist[5], 1);
        CHECK_EQ_INT(hist[6], 1);
        cc_mesh_free(&m);
    }
    st = cc_cage_cube(&m, &e);
    CHECK(st == SB_OK);
    if (!st) {
        CHECK_EQ_INT(m.ne, 12);
        int hist[16];
        count_valences(&m, hist);
        CHECK_EQ_INT(hist[3], 8);
        cc_mesh_free(&m);
    }
}

SB_TEST(bad_cages_are_rejected)
{
    cc_err e = { "" };
    cc_mesh m;
    double lines[3] = { 0, 0.5, 0.4 };
    CHECK(cc_cage_grid(lines, 2, lines, 2, -1, 0, 0, &m, &e) == SB_ERR_INPUT);
    CHECK(strlen(e.msg) > 0);
    double ok[3] = { 0, 0.5, 1 };
    CHECK(cc_cage_grid(ok, 2, ok, 2, SB_CORNER_11, 2, 1, &m, &e) == SB_ERR_INPUT);
    CHECK(cc_cage_star(2, 4, &m, &e) == SB_ERR_INPUT);
    /* non-manifold edge: three faces on one edge */
    CHECK(cc_mesh_alloc(&m, 8, 3, 0) == SB_OK);
    int fv[12] = { 0, 1, 2, 3, 1, 0, 4, 5, 0, 1, 6, 7 };
    memcpy(m.fv, fv, sizeof fv);
    CHECK(cc_mesh_topology(&m, &e) == SB_ERR_INPUT);
    cc_mesh_free(&m);
    /* inconsistent orientation */
    CHECK(cc_mesh_alloc(&m, 6, 2, 0) == SB_OK);
    int fw[8] = { 0, 1, 2, 3, 0, 1, 4, 5 };
    memcpy(m.fv, fw, sizeof fw);
    CHECK(cc_mesh_topology(&m, &e) == SB_ERR_INPUT);
    cc_mesh_free(&m);
    CHECK(cc_cage_lines(1, 0.7, 1, lines, NULL) == SB_ERR_INPUT);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(square_sizes_match_paper),
        SB_CASE(lshape_exact_notch),
        SB_CASE(star_and_multi_cages),
        SB_CASE(bad_cages_are_rejected),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
