/* test_lf_transfer.c — linear_fem's nested hierarchy: projection after
 * prolongation is the identity, restriction is the adjoint of prolongation,
 * the prolongation matrix equals prolong(), prolongation reproduces the coarse
 * surface exactly, and RMTR with Galerkin coarse models solves a plate to the
 * same answer as Newton on the same mesh. */
#include "test_lf_common.h"
#include "sb_galerkin.h"
#include "sb_geometry.h"
#include "sb_run.h"
#include "run_json.h"

#include <math.h>

#define LSHAPE "{\"type\": \"l_shape\", \"origin\": [0, 0], \"size\": [1, 1], \"notch\": [0.3, 0.3], \"notch_corner\": \"11\"}"

static void check_hierarchy(sb_test_state *T, const char *const *sets, const char *what)
{
    const char *json = TL_SCENE(LSHAPE, TL_PLANE, TL_STVK, "[{\"type\": \"clamped\", \"on\": [\"notch_s\"]}]", "[]");
    tl_method m;
    int rc = tl_create(&m, json, 8, 3, sets);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    unsigned long long st = 77;
    for (int lc = 0; lc < 2; lc++) {
        const int nc = m.S->lv[lc].n_dofs, nf = m.S->lv[lc + 1].n_dofs;
        double *xc = malloc(sizeof(double) * nc), *yc = malloc(sizeof(double) * nc), *xf = malloc(sizeof(double) * nf);
        double *yf = malloc(sizeof(double) * nf), *zf = malloc(sizeof(double) * nf);
        for (int i = 0; i < nc; i++) xc[i] = tl_rand(&st);
        for (int i = 0; i < nf; i++) yf[i] = tl_rand(&st);
        sb_method_linear_fem.prolong(m.S, lc, xc, xf);
        sb_method_linear_fem.project(m.S, lc, xf, yc);
        double err = 0;
        for (int i = 0; i < nc; i++) err = fmax(err, fabs(yc[i] - xc[i]));
        CHECK_MSG(err == 0.0, "%s level %d: |P I x - x| = %g", what, lc, err);
        /* <I xc, yf> = <xc, R yf> */
        sb_method_linear_fem.restrict_adj(m.S, lc, yf, yc);
        CHECK_NEAR(sb_dot(nf, xf, yf), sb_dot(nc, xc, yc), 1e-12 * (1 + fabs(sb_dot(nf, xf, yf))));
        /* the matrix equals the operator */
        sb_csr I;
        CHECK_EQ_INT(sb_method_linear_fem.prolong_matrix(m.S, lc, &I), SB_OK);
        CHECK_EQ_INT(I.nr, nf);
        CHECK_EQ_INT(I.nc, nc);
        double merr = 0;
        for (int r = 0; r < nf; r++) {
            double v = 0;
            for (long k = I.rp[r]; k < I.rp[r + 1]; k++) {
                v += I.v[k] * xc[I.ci[k]];
                if (k > I.rp[r]) CHECK(I.ci[k] > I.ci[k - 1]);
            }
            merr = fmax(merr, fabs(v - xf[r]));
        }
        CHECK_MSG(merr < 1e-15, "%s: prolong_matrix differs from prolong by %g", what, merr);
        sb_csr_free(&I);
        /* exact on the coarse space: the prolonged surface is the coarse one */
        const int np = 200;
        double *stp = malloc(sizeof(double) * 2 * np), *pc = malloc(sizeof(double) * 3 * np), *pf = malloc(sizeof(double) * 3 * np);
        int k = 0;
        while (k < np) {
            const double s = 0.5 + 0.5 * tl_rand(&st), t = 0.5 + 0.5 * tl_rand(&st);
            if (!sb_domain_contains_st(&m.scene.domain, s, t)) continue;
            stp[2 * k] = s;
            stp[2 * k + 1] = t;
            k++;
        }
        CHECK_EQ_INT(sb_method_linear_fem.eval_points(m.S, lc, xc, np, stp, pc), SB_OK);
        CHECK_EQ_INT(sb_method_linear_fem.eval_points(m.S, lc + 1, xf, np, stp, pf), SB_OK);
        double eerr = 0;
        for (int i = 0; i < 3 * np; i++) eerr = fmax(eerr, fabs(pc[i] - pf[i]));
        CHECK_MSG(eerr < 1e-13, "%s level %d: prolonged surface differs by %g", what, lc, eerr);
        /* the prolonged reference is the fine reference (plane chart): zero energy */
        sb_method_linear_fem.initial(m.S, lc, xc);
        sb_method_linear_fem.prolong(m.S, lc, xc, xf);
        sb_method_linear_fem.initial(m.S, lc + 1, zf);
        double rerr = 0, f;
        for (int i = 0; i < nf; i++) rerr = fmax(rerr, fabs(xf[i] - zf[i]));
        CHECK_MSG(rerr < 1e-15, "%s: I x_ref differs from the fine reference by %g", what, rerr);
        sb_method_linear_fem.energy(m.S, lc + 1, xf, &f, NULL, NULL);
        CHECK_NEAR(f, 0.0, 1e-14);
        free(stp); free(pc); free(pf);
        free(xc); free(yc); free(xf); free(yf); free(zf);
    }
    tl_free(&m);
}

SB_TEST(test_hierarchy_edge)
{
    const char *sets[] = { "method.mesh=jitter", NULL };
    check_hierarchy(T, sets, "midedge/edge");
}
SB_TEST(test_hierarchy_average_hinge)
{
    const char *a[] = { "method.director=average", "method.mesh=crossed", NULL };
    check_hierarchy(T, a, "midedge/average");
    const char *h[] = { "method.bending=hinge", NULL };
    check_hierarchy(T, h, "hinge");
}

/* every interior fine director row of a coarse triangle has two entries */
SB_TEST(test_director_rows)
{
    const char *json = TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]", "[]");
    tl_method m;
    int rc = tl_create(&m, json, 4, 2, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    const lf_level *F = &m.S->lv[1];
    int halves = 0, inner = 0;
    for (int f = 0; f < F->ne; f++) {
        const int row = 3 * F->nv + f, len = F->p_ptr[row + 1] - F->p_ptr[row];
        if (F->rf.edge_parent[f] >= 0) { CHECK_EQ_INT(len, 1); halves++; }
        else { CHECK_EQ_INT(len, 2); inner++; }
    }
    CHECK_EQ_INT(halves, 2 * m.S->lv[0].ne);
    CHECK_EQ_INT(inner, 3 * m.S->lv[0].nt);
    tl_free(&m);
}

/* RMTR (Galerkin coarse models, nested start) against Newton on the same two-level mesh */
static double center_z(sb_test_state *T, const char *solver, int *code)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/bench/scenes/plate_clamped.json", sb_test_root());
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = path;
    rq.method = "linear_fem";
    rq.solver = solver;
    rq.res = 16;
    rq.levels = 2;
    rq.out = "none";
    rq.quiet = 1;
    json_t *o = sb_test_run_json(&rq, code);
    CHECK_MSG(o != NULL, "%s: no summary", solver);
    if (!o) return NAN;
    json_t *d = json_object_get(json_object_get(json_object_get(o, "probes"), "center"), "displacement");
    const double z = json_number_value(json_array_get(d, 2));
    json_decref(o);
    return z;
}

SB_TEST(test_rmtr_solver)
{
    int c1, c2;
    const double zn = center_z(T, "lsnewton", &c1), zr = center_z(T, "rmtr", &c2);
    CHECK_EQ_INT(c1, SB_EXIT_CONVERGED);
    CHECK_EQ_INT(c2, SB_EXIT_CONVERGED);
    CHECK_REL(zr, zn, 1e-4);
    printf("    plate_clamped 16 (2 levels): lsnewton w = %.6e, rmtr w = %.6e\n", zn, zr);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_hierarchy_edge), SB_CASE(test_hierarchy_average_hinge), SB_CASE(test_director_rows),
        SB_CASE(test_rmtr_solver), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
