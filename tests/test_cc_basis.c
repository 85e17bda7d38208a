/* test_cc_basis.c — subdivision basis functions of the rmtr method:
 * partition of unity, linear reproduction, derivatives by finite differences,
 * B-spline fast path and local subdivision against OpenSubdiv limit stencils,
 * C^1 (tangent-plane) continuity across an edge at an extraordinary vertex. */
#include "sb_test.h"
#include "../methods/rmtr/cc_method.h"
#include "sb_scene.h"

#include <stdlib.h>
#include <string.h>

static const double G3[3] = { 0.1127016653792583, 0.5, 0.8872983346207417 };

static double rnd(unsigned long *s)
{
    *s = *s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(*s >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

/* a face of the star cage touching the centre (sector j, cell (0,0)) */
static int star_center_face(int j, int k) { return j * k * k; }

SB_TEST(partition_of_unity)
{
    cc_err e = { "" };
    static const int vals[5] = { 3, 4, 5, 6, 8 };
    int idx[CC_MAX_BASIS];
    double W[6 * CC_MAX_BASIS];
    for (int a = 0; a < 5; a++) {
        cc_mesh m;
        CHECK(cc_cage_star(vals[a], 3, &m, &e) == SB_OK);
        for (int f = 0; f < m.nf; f++) {
            if (!m.dom[f]) continue;
            for (int p = 0; p < 9; p++) {
                int k;
                int st = cc_face_basis(&m, f, G3[p % 3], G3[p / 3], &k, idx, W, CC_MAX_BASIS, &e);
                CHECK_MSG(st == SB_OK, "%s", e.msg);
                if (st) break;
                if (f == star_center_face(0, 3) && p == 0) CHECK_EQ_INT(k, 2 * vals[a] + 8);
                for (int r = 0; r < 6; r++) {
                    double s = 0;
                    for (int i = 0; i < k; i++) s += W[r * k + i];
                    CHECK_NEAR(s, r == 0 ? 1.0 : 0.0, 1e-12);
                }
                double mn = 1;
                for (int i = 0; i < k; i++) mn = fmin(mn, W[i]);
                CHECK(mn > -1e-14);               /* subdivision basis functions are >= 0 */
            }
        }
        cc_mesh_free(&m);
    }
}

/* Uniform square: sum N_I st_I = ((i+u)/n, (j+v)/n) exactly; L-shape: the
 * limit at the notch line (u = 0 of the first notch column) is 0.7. */
SB_TEST(linear_reproduction)
{
    cc_err e = { "" };
    double lines[9];
    cc_mesh m;
    CHECK(cc_cage_lines(8, 0, 0, lines, NULL) == SB_OK);
    CHECK(cc_cage_grid(lines, 8, lines, 8, -1, 0, 0, &m, &e) == SB_OK);
    int idx[CC_MAX_BASIS];
    double W[6 * CC_MAX_BASIS], err = 0;
    for (int f = 0; f < m.nf; f++) {
        if (!m.dom[f]) continue;
        for (int p = 0; p < 9; p++) {
            double u = G3[p % 3], v = G3[p / 3], x[6][2] = { { 0 } };
            int k;
            CHECK(cc_face_basis(&m, f, u, v, &k, idx, W, CC_MAX_BASIS, &e) == SB_OK);
            for (int r = 0; r < 6; r++)
                for (int i = 0; i < k; i++)
                    for (int c = 0; c < 2; c++) x[r][c] += W[r * k + i] * m.st[2 * idx[i] + c];
            double ex[6][2] = { { (m.cell[2 * f] + u) / 8, (m.cell[2 * f + 1] + v) / 8 },
                                { 1.0 / 8, 0 }, { 0, 1.0 / 8 }, { 0, 0 }, { 0, 0 }, { 0, 0 } };
            for (int r = 0; r < 6; r++)
                for (int c = 0; c < 2; c++) err = fmax(err, fabs(x[r][c] - ex[r][c]));
        }
    }
    CHECK(err < 1e-14);
    cc_mesh_free(&m);
    CHECK(cc_cage_lines(4, 0.7, 1, lines, NULL) == SB_OK);
    CHECK(cc_cage_grid(lines, 4, lines, 4, SB_CORNER_11, 1, 1, &m, &e) == SB_OK);
    int checked = 0;
    for (int f = 0; f < m.nf; f++) {
        if (!m.dom[f] || m.cell[2 * f] != 2) continue;    /* cells left of the notch line s = 0.7 */
        for (int p = 0; p < 3; p++) {
            int k;
            double s = 0;
            CHECK(cc_face_basis(&m, f, 1.0, G3[p], &k, idx, W, CC_MAX_BASIS, &e) == SB_OK);
            for (int i = 0; i < k; i++) s += W[i] * m.st[2 * idx[i]];
            CHECK_NEAR(s, 0.7, 1e-14);
            checked++;
        }
    }
    CHECK_EQ_INT(checked, 12);
    cc_mesh_free(&m);
}

/* first and second derivatives against central differences of the values
 * and first derivatives, on a face at a valence-5 vertex */
SB_TEST(derivatives_by_finite_differences)
{
    cc_err e = { "" };
    cc_mesh m;
    CHECK(cc_cage_star(5, 3, &m, &e) == SB_OK);
    int f = star_center_face(1, 3), k, idx[CC_MAX_BASIS];
    double W0[6 * CC_MAX_BASIS], Wp[6 * CC_MAX_BASIS], Wm[6 * CC_MAX_BASIS];
    const double h = 1e-5, u = 0.37, v = 0.61;
    CHECK(cc_face_basis(&m, f, u, v, &k, idx, W0, CC_MAX_BASIS, &e) == SB_OK);
    double err = 0;
    for (int dir = 0; dir < 2; dir++) {
        CHECK(cc_face_basis(&m, f, u + (dir == 0) * h, v + (dir == 1) * h, &k, idx, Wp, CC_MAX_BASIS, &e) == SB_OK);
        CHECK(cc_face_basis(&m, f, u - (dir == 0) * h, v - (dir == 1) * h, &k, idx, Wm, CC_MAX_BASIS, &e) == SB_OK);
        for (int i = 0; i < k; i++) {
            err = fmax(err, fabs((Wp[i] - Wm[i]) / (2 * h) - W0[(1 + dir) * k + i]));
            /* d/du of N_u is N_uu (dir 0) or N_uv (dir 1); d/dv of N_v is N_vv */
            err = fmax(err, fabs((Wp[k + i] - Wm[k + i]) / (2 * h) - W0[(3 + dir) * k + i]));
            if (dir == 1) err = fmax(err, fabs((Wp[2 * k + i] - Wm[2 * k + i]) / (2 * h) - W0[5 * k + i]));
        }
    }
    CHECK_MSG(err < 1e-6, "max FD error %g", err);
    cc_mesh_free(&m);
}

/* max |W_cc - W_osd| over all control points and the 6 rows, at points (u,v) of faces */
static double compare_osd(const cc_mesh *m, int np, const int *face, const double *uv)
{
    cc_err e = { "" };
    double *Wo = calloc((size_t)6 * np * m->nv, sizeof *Wo);
    if (cc_osd_limit_dense(m, np, face, uv, Wo, &e)) {
        printf("    %s\n", e.msg);
        free(Wo);
        return 1e300;
    }
    double d = 0, W[6 * CC_MAX_BASIS];
    int idx[CC_MAX_BASIS], k;
    for (int p = 0; p < np; p++) {
        if (cc_face_basis(m, face[p], uv[2 * p], uv[2 * p + 1], &k, idx, W, CC_MAX_BASIS, &e)) {
            d = 1e300;
            break;
        }
        for (int r = 0; r < 6; r++) {
            double *row = Wo + (size_t)(6 * p + r) * m->nv;
            for (int i = 0; i < k; i++) row[idx[i]] -= W[r * k + i];
            for (int i = 0; i < m->nv; i++) d = fmax(d, fabs(row[i]));
        }
    }
    free(Wo);
    return d;
}

SB_TEST(fast_path_and_local_subdivision_equal_opensubdiv)
{
    cc_err e = { "" };
    cc_mesh m;
    double lines[5];
    int face[128];
    double uv[256];
    CHECK(cc_cage_lines(4, 0, 0, lines, NULL) == SB_OK);
    CHECK(cc_cage_grid(lines, 4, lines, 4, -1, 0, 0, &m, &e) == SB_OK);
    int np = 0;
    for (int f = 0; f < m.nf && np < 60; f++)
        if (m.dom[f]) {
            face[np] = f;
            uv[2 * np] = G3[np % 3];
            uv[2 * np + 1] = G3[(np / 3) % 3];
            np++;
        }
    double d = compare_osd(&m, np, face, uv);
    CHECK_MSG(d < 1e-12, "regular: max diff %g", d);
    cc_mesh_free(&m);
    static const int vals[4] = { 3, 5, 6, 8 };
    for (int a = 0; a < 4; a++) {
        CHECK(cc_cage_star(vals[a], 3, &m, &e) == SB_OK);
        np = 0;
        for (int j = 0; j < vals[a]; j++)
            for (int p = 0; p < 4; p++, np++) {
                face[np] = star_center_face(j, 3);
                uv[2 * np] = p < 3 ? G3[p] : 0.04;
                uv[2 * np + 1] = p < 3 ? G3[2 - p] : 0.06;
            }
        for (int f = 0; f < m.nf; f++)          /* every domain face, regular ones next to the EV included */
            if (m.dom[f]) {
                face[np] = f;
                uv[2 * np] = G3[1];
                uv[2 * np + 1] = G3[0];
                np++;
            }
        d = compare_osd(&m, np, face, uv);
        CHECK_MSG(d < 1e-9, "valence %d: max diff %g", vals[a], d);
        printf("    valence %d: max |N - N_osd| over values and derivatives %.2e\n", vals[a], d);
        cc_mesh_free(&m);
    }
}

/* Across the edge centre -> ray_{j+1} shared by sector j (v-axis of its
 * centre face) and sector j+1 (u-axis): same position, same tangent along
 * the edge, same unit normal (tangent-plane continuity) for random 3D data. */
SB_TEST(c1_across_extraordinary_edge)
{
    cc_err e = { "" };
    static const int vals[3] = { 3, 5, 8 };
    for (int a = 0; a < 3; a++) {
        cc_mesh m;
        CHECK(cc_cage_star(vals[a], 3, &m, &e) == SB_OK);
        double *q = malloc((size_t)3 * m.nv * sizeof *q);
        unsigned long seed = 99;
        for (int i = 0; i < m.nv; i++) {
            q[3 * i] = m.st[2 * i];
            q[3 * i + 1] = m.st[2 * i + 1];
            q[3 * i + 2] = 0.3 * rnd(&seed);
        }
        double dp = 0, dt = 0, dn = 0;
        for (int j = 0; j < vals[a]; j++) {
            int fa = star_center_face(j, 3), fb = star_center_face((j + 1) % vals[a], 3);
            for (int p = 0; p < 4; p++) {
                double t = 0.1 + 0.25 * p, x[2][6][3] = { { { 0 } } };
                for (int s = 0; s < 2; s++) {
                    int k, idx[CC_MAX_BASIS];
                    double W[6 * CC_MAX_BASIS];
                    CHECK(cc_face_basis(&m, s ? fb : fa, s ? t : 0.0, s ? 0.0 : t, &k, idx, W, CC_MAX_BASIS, &e) == SB_OK);
                    for (int r = 0; r < 3; r++)
                        for (int i = 0; i < k; i++)
                            for (int c = 0; c < 3; c++) x[s][r][c] += W[r * k + i] * q[3 * idx[i] + c];
                }
                double n[2][3];
                for (int s = 0; s < 2; s++) {
                    double *xu = x[s][1], *xv = x[s][2];
                    n[s][0] = xu[1] * xv[2] - xu[2] * xv[1];
                    n[s][1] = xu[2] * xv[0] - xu[0] * xv[2];
                    n[s][2] = xu[0] * xv[1] - xu[1] * xv[0];
                    double l = sqrt(n[s][0] * n[s][0] + n[s][1] * n[s][1] + n[s][2] * n[s][2]);
                    for (int c = 0; c < 3; c++) n[s][c] /= l;
                }
                for (int c = 0; c < 3; c++) {
                    dp = fmax(dp, fabs(x[0][0][c] - x[1][0][c]));
                    dt = fmax(dt, fabs(x[0][2][c] - x[1][1][c]));   /* x_v on A = x_u on B */
                    dn = fmax(dn, fabs(n[0][c] - n[1][c]));
                }
            }
        }
        CHECK_MSG(dp < 1e-13 && dt < 1e-12 && dn < 1e-11, "valence %d: position %g tangent %g normal %g",
                  vals[a], dp, dt, dn);
        free(q);
        cc_mesh_free(&m);
    }
}

/* §6: tables precomputed once per face configuration and shared between
 * faces with the same canonical local cage must equal direct evaluation */
SB_TEST(quadrature_tables_match_direct_evaluation)
{
    cc_err e = { "" };
    for (int a = 0; a < 5; a++) {
        static const int vals[4] = { 3, 5, 6, 8 };
        cc_mesh m;
        CHECK((a < 4 ? cc_cage_star(vals[a], 4, &m, &e) : cc_cage_multi(&m, &e)) == SB_OK);
        cc_quad Q;
        int st = cc_quad_build(&Q, &m, 3, &e);
        CHECK_MSG(st == SB_OK, "%s", e.msg);
        if (st) {
            cc_mesh_free(&m);
            continue;
        }
        int irregular = 0;
        double d = 0, W[6 * CC_MAX_BASIS];
        for (int el = 0; el < Q.ne; el++) {
            int k0 = Q.eoff[el + 1] - Q.eoff[el], k, idx[CC_MAX_BASIS];
            irregular += Q.ecfg[el] != 0;
            for (int q = 0; q < Q.nq; q++) {
                CHECK(cc_face_basis(&m, Q.face[el], Q.gp[q % 3], Q.gp[q / 3], &k, idx, W, CC_MAX_BASIS, &e) == SB_OK);
                CHECK(k == k0 && memcmp(idx, Q.enode + Q.eoff[el], sizeof(int) * (size_t)k) == 0);
                sb_shell_basis b = cc_quad_basis(&Q, el, q);
                const double *rows[6] = { b.N, b.N1, b.N2, b.N11, b.N12, b.N22 };
                for (int r = 0; r < 6; r++)
                    for (int i = 0; i < k; i++) d = fmax(d, fabs(rows[r][i] - W[r * k + i]));
            }
        }
        printf("    cage %d: %d elements, %d irregular, %d configurations, max table error %.1e\n", a, Q.ne,
               irregular, Q.ncfg, d);
        CHECK(d < 1e-14);
        CHECK(Q.ncfg < irregular + 1);       /* configurations are shared */
        cc_quad_free(&Q);
        cc_mesh_free(&m);
    }
}

SB_TEST(bad_points_are_errors)
{
    cc_err e = { "" };
    cc_mesh m;
    CHECK(cc_cage_star(5, 3, &m, &e) == SB_OK);
    int k, idx[CC_MAX_BASIS];
    double W[6 * CC_MAX_BASIS];
    CHECK(cc_face_basis(&m, 0, 1.5, 0.5, &k, idx, W, CC_MAX_BASIS, &e) == SB_ERR_INPUT);
    CHECK(cc_face_basis(&m, -1, 0.5, 0.5, &k, idx, W, CC_MAX_BASIS, &e) == SB_ERR_INPUT);
    CHECK(cc_face_basis(&m, 0, 0.0, 0.0, &k, idx, W, CC_MAX_BASIS, &e) == SB_ERR_INPUT);   /* the EV itself */
    CHECK(strlen(e.msg) > 0);
    cc_mesh_free(&m);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(partition_of_unity),
        SB_CASE(linear_reproduction),
        SB_CASE(derivatives_by_finite_differences),
        SB_CASE(fast_path_and_local_subdivision_equal_opensubdiv),
        SB_CASE(c1_across_extraordinary_edge),
        SB_CASE(quadrature_tables_match_direct_evaluation),
        SB_CASE(bad_points_are_errors),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
