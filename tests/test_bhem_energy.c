/* test_bhem_energy.c — BHEM energy, gradient and Hessian (finite-difference
 * checks through the whole method), rest state, rigid-motion invariance,
 * mass matrix, loads and constrained-dof sets. */
#include "test_bhem_common.h"

#include <math.h>

#define CYL "{\"type\": \"cylinder\", \"radius\": 0.3, \"angle\": [-40, 40], \"length\": 0.6}"

typedef struct tb_sys {
    sb_pattern *pat;
    sb_matrix H;
} tb_sys;

static int sys_init(tb_sys *s, bhem_state *S, int level)
{
    int n = sb_method_bhem.n_dofs(S, level), bs = sb_method_bhem.block_size(S, level);
    sb_pattern_builder *pb = sb_pattern_builder_new(n / bs, bs);
    if (!pb) return SB_ERR_NOMEM;
    int rc = sb_method_bhem.pattern(S, level, pb);
    int rc2 = sb_pattern_builder_finish(pb, &s->pat);
    if (rc || rc2) return rc ? rc : rc2;
    return sb_matrix_init(&s->H, s->pat);
}
static void sys_free(tb_sys *s)
{
    sb_matrix_free(&s->H);
    sb_pattern_free(s->pat);
}

static void full_step(tb_method *m, double load, double motion)
{
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1;
    si.n_steps = 1;
    for (int k = 0; k < SB_SCENE_MAX_LOADS; k++) si.load_factor[k] = load;
    for (int k = 0; k < SB_SCENE_MAX_BCS; k++) si.motion_factor[k] = motion;
    sb_method_bhem.set_step(m->S, &si);
}

/* FD check of gradient and Hessian at a random perturbation of the rest state. */
static void fd_check(sb_test_state *T, const char *json, const char *hess, double amp, int expect_psd)
{
    const char *sets[] = { hess, NULL };
    tb_method m;
    int rc = tb_create(&m, json, 3, 1, sets);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    full_step(&m, 1.0, 0.0);
    int n = sb_method_bhem.n_dofs(m.S, 0);
    double *x = malloc(sizeof(double) * n), *v = malloc(sizeof(double) * n), *xp = malloc(sizeof(double) * n);
    double *g = calloc(n, sizeof(double)), *gp = calloc(n, sizeof(double)), *gm = calloc(n, sizeof(double));
    double *Hv = malloc(sizeof(double) * n);
    unsigned long long st = 12345;
    sb_method_bhem.initial(m.S, 0, x);
    for (int i = 0; i < n; i++) x[i] += amp * tb_rand(&st);
    for (int i = 0; i < n; i++) v[i] = tb_rand(&st);
    tb_sys sys;
    CHECK_EQ_INT(sys_init(&sys, m.S, 0), SB_OK);
    double f, fp, fm;
    CHECK_EQ_INT(sb_method_bhem.energy(m.S, 0, x, &f, g, &sys.H), SB_OK);
    /* gradient: central difference of f along v */
    double e = 1e-6, gv = sb_dot(n, g, v);
    for (int i = 0; i < n; i++) xp[i] = x[i] + e * v[i];
    sb_method_bhem.energy(m.S, 0, xp, &fp, gp, NULL);
    for (int i = 0; i < n; i++) xp[i] = x[i] - e * v[i];
    sb_method_bhem.energy(m.S, 0, xp, &fm, gm, NULL);
    double fd = (fp - fm) / (2 * e);
    CHECK_MSG(fabs(fd - gv) <= 1e-6 * fabs(gv) + 1e-12, "%s: g.v = %.12g, FD %.12g", hess, gv, fd);
    CHECK(fabs(gv) > 1e-8);
    /* Hessian: H v against the central difference of g */
    sb_matrix_symv(&sys.H, v, Hv);
    double num = 0, den = 0;
    for (int i = 0; i < n; i++) {
        double d = (gp[i] - gm[i]) / (2 * e);
        num += (d - Hv[i]) * (d - Hv[i]);
        den += d * d;
    }
    double rel = sqrt(num / den);
    if (strstr(hess, "exact")) CHECK_MSG(rel < 1e-6, "exact Hessian: |Hv - FD| / |FD| = %g", rel);
    else CHECK_MSG(rel > 1e-6, "%s Hessian equals the exact one (rel %g)", hess, rel);
    if (expect_psd) CHECK_MSG(sb_dot(n, v, Hv) >= -1e-12 * sb_norm2(n, Hv) * sb_norm2(n, v), "psd: v.Hv < 0");
    sys_free(&sys);
    free(x); free(v); free(xp); free(g); free(gp); free(gm); free(Hv);
    tb_free(&m);
}

#define FD_SCENE TB_SCENE(TB_RECT, CYL, TB_STVK, "[{\"type\": \"clamped\", \"on\": [\"left\"]}]",                  \
    "[{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]},"                                                   \
    " {\"type\": \"pressure\", \"pressure\": 30, \"follower\": true},"                                             \
    " {\"type\": \"end_moment\", \"on\": [\"right\"], \"moment_per_length\": 0.7, \"axis\": [0, 1, 0]}]")

SB_TEST(test_fd_exact) { fd_check(T, FD_SCENE, "method.hessian=exact", 0.01, 0); }
SB_TEST(test_fd_pseudo) { fd_check(T, FD_SCENE, "method.hessian=pseudo", 0.01, 0); }
SB_TEST(test_fd_psd) { fd_check(T, FD_SCENE, "method.hessian=psd", 0.01, 1); }

/* rest state: zero energy and gradient; rigid motions: zero elastic energy */
SB_TEST(test_rest_and_rigid_motion)
{
    tb_method m;
    int rc = tb_create(&m, TB_SCENE(TB_RECT, CYL, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]", "[]"), 4, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    int n = sb_method_bhem.n_dofs(m.S, 0);
    double *x = malloc(sizeof(double) * n), *y = malloc(sizeof(double) * n), *g = calloc(n, sizeof(double)), f;
    sb_method_bhem.initial(m.S, 0, x);
    CHECK_EQ_INT(sb_method_bhem.energy(m.S, 0, x, &f, g, NULL), SB_OK);
    CHECK_NEAR(f, 0.0, 1e-15);
    CHECK(sb_norm2(n, g) < 1e-9);
    double R[9], ax[3] = { 0.3, -0.5, 0.8 }, an = sqrt(0.98);
    for (int c = 0; c < 3; c++) ax[c] /= an;
    sb_rotation(ax, 1.1, R);
    for (int k = 0; k < n; k += 3) {
        int kind = (k % 12) / 3;
        for (int c = 0; c < 3; c++) {
            y[k + c] = kind == 0 ? 0.7 * (c + 1) : 0.0;
            for (int d = 0; d < 3; d++) y[k + c] += R[3 * c + d] * x[k + d];
        }
    }
    memset(g, 0, sizeof(double) * n);
    CHECK_EQ_INT(sb_method_bhem.energy(m.S, 0, y, &f, g, NULL), SB_OK);
    CHECK_NEAR(f, 0.0, 1e-13);
    CHECK(sb_norm2(n, g) < 1e-8);
    /* and a stretch is not free */
    for (int k = 0; k < n; k++) y[k] = 1.01 * x[k];
    sb_method_bhem.energy(m.S, 0, y, &f, NULL, NULL);
    CHECK(f > 1e-3);
    free(x); free(y); free(g);
    tb_free(&m);
}

/* 1^T M 1 over one component of the position dofs = areal density x area (Eq. 20) */
SB_TEST(test_mass_total)
{
    const char *geo[2] = { TB_PLANE, CYL };
    double area[2] = { 0.6, 0.3 * (80.0 * M_PI / 180.0) * 0.6 };
    for (int k = 0; k < 2; k++) {
        char json[2048];
        snprintf(json, sizeof json, TB_SCENE(TB_RECT, "%s", TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]", "[]"), geo[k]);
        tb_method m;
        int rc = tb_create(&m, json, 4, 1, NULL);
        CHECK_EQ_INT(rc, SB_OK);
        if (rc) continue;
        tb_sys sys;
        CHECK_EQ_INT(sys_init(&sys, m.S, 0), SB_OK);
        CHECK_EQ_INT(sb_method_bhem.mass(m.S, 0, &sys.H), SB_OK);
        int n = sb_method_bhem.n_dofs(m.S, 0);
        double *v = calloc(n, sizeof(double)), *Mv = malloc(sizeof(double) * n);
        for (int c = 0; c < 3; c++) {
            memset(v, 0, sizeof(double) * n);
            for (int i = c; i < n; i += 12) v[i] = 1.0;
            sb_matrix_symv(&sys.H, v, Mv);
            CHECK_REL(sb_dot(n, v, Mv), 0.5 * area[k], k ? 1e-4 : 1e-13);   /* cylinder: O(h^4) area error */
        }
        /* M is positive definite: v^T M v > 0 for a random v */
        unsigned long long st = 5;
        for (int i = 0; i < n; i++) v[i] = tb_rand(&st);
        sb_matrix_symv(&sys.H, v, Mv);
        CHECK(sb_dot(n, v, Mv) > 0.0);
        free(v); free(Mv);
        sys_free(&sys);
        tb_free(&m);
    }
}

/* sum of a load vector over the x/y/z position dofs */
static void total_force(const bhem_level *L, const double *b, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    for (int n = 0; n < L->n_nodes; n++)
        for (int c = 0; c < 3; c++) out[c] += b[12 * n + c];
}

/* gravity, dead pressure, line and point loads: resultants (BHEM Eq. 19, 21) */
SB_TEST(test_load_resultants)
{
    const char *json = TB_SCENE(TB_RECT, TB_PLANE, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]",
        "[{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]},"
        " {\"type\": \"pressure\", \"pressure\": -3},"
        " {\"type\": \"line\", \"on\": [\"right\"], \"force_per_length\": [0, 1, 2]},"
        " {\"type\": \"point\", \"at\": [0.37, 0.21], \"force\": [4, 0, -1]}]");
    tb_method m;
    int rc = tb_create(&m, json, 4, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    bhem_level *L = &m.S->lv[0];
    double F[3];
    total_force(L, L->load_vec + 0 * L->n_dofs, F);
    CHECK_REL(F[2], -9.81 * 0.5 * 0.6, 1e-13);
    CHECK_NEAR(F[0], 0.0, 1e-14);
    total_force(L, L->load_vec + 1 * L->n_dofs, F);
    CHECK_REL(F[2], -3 * 0.6, 1e-13);
    total_force(L, L->load_vec + 2 * L->n_dofs, F);
    CHECK_REL(F[1], 0.6, 1e-13);
    CHECK_REL(F[2], 1.2, 1e-13);
    total_force(L, L->load_vec + 3 * L->n_dofs, F);
    CHECK_REL(F[0], 4.0, 1e-13);
    CHECK_REL(F[2], -1.0, 1e-13);
    /* the point load's work on a linear field u = (s,t) map equals F . u(point) */
    int n = L->n_dofs;
    double *x = malloc(sizeof(double) * n), f;
    sb_method_bhem.initial(m.S, 0, x);
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.load_factor[3] = 1.0;
    sb_method_bhem.set_step(m.S, &si);
    sb_method_bhem.energy(m.S, 0, x, &f, NULL, NULL);
    CHECK_NEAR(f, 0.0, 1e-15);   /* E_ext is measured from the reference */
    /* displacement u = (0.2 s t, 0, 0.3 s + 0.5 t), bicubic-exact: E = -F . u(point) */
    for (int nd = 0; nd < L->n_nodes; nd++) {
        double s = L->node_i[nd] * L->hs, t = L->node_j[nd] * L->ht, *q = x + 12 * nd;
        q[0] += 0.2 * s * t; q[3] += L->hs * 0.2 * t; q[6] += L->ht * 0.2 * s; q[9] += L->hs * L->ht * 0.2;
        q[2] += 0.3 * s + 0.5 * t; q[5] += L->hs * 0.3; q[8] += L->ht * 0.5;
    }
    double f0;
    sb_method_bhem.energy(m.S, 0, x, &f, NULL, NULL);
    si.load_factor[3] = 0.0;                      /* elastic part alone */
    sb_method_bhem.set_step(m.S, &si);
    sb_method_bhem.energy(m.S, 0, x, &f0, NULL, NULL);
    double sp = 0.37, tp = 0.21 / 0.6;
    CHECK_NEAR(f - f0, -(4.0 * 0.2 * sp * tp - 1.0 * (0.3 * sp + 0.5 * tp)), 1e-12);
    free(x);
    tb_free(&m);
}

/* End moment: rigid rotation of the loaded edge's tangent by phi gives
 * E = -m * length * phi, continuous past pi when stepped (branch unwrap). */
SB_TEST(test_end_moment_unwrap)
{
    const char *json = TB_SCENE(TB_RECT, TB_PLANE, TB_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]",
        "[{\"type\": \"end_moment\", \"on\": [\"right\"], \"moment_per_length\": 2.0, \"axis\": [0, -1, 0]}]");
    tb_method m;
    int rc = tb_create(&m, json, 2, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    bhem_level *L = &m.S->lv[0];
    int n = L->n_dofs;
    double *x = malloc(sizeof(double) * n), *y = malloc(sizeof(double) * n), f;
    sb_method_bhem.initial(m.S, 0, x);
    double ax[3] = { 0, -1, 0 }, R[9];
    for (int k = 1; k <= 7; k++) {
        double phi = 0.9 * k;                   /* up to 6.3 rad > 2 pi */
        full_step(&m, 1.0, 0.0);                 /* a new step re-centres the branch */
        sb_rotation(ax, phi, R);
        for (int i = 0; i < n; i += 3)
            for (int c = 0; c < 3; c++) {
                y[i + c] = 0.0;
                for (int d = 0; d < 3; d++) y[i + c] += R[3 * c + d] * x[i + d];
            }
        /* elastic energy of a rigid rotation is zero: E = -m * 0.6 * phi */
        CHECK_EQ_INT(sb_method_bhem.energy(m.S, 0, y, &f, NULL, NULL), SB_OK);
        CHECK_MSG(fabs(f + 2.0 * 0.6 * phi) < 1e-10, "phi %g: E = %.12g, expected %.12g", phi, f, -2.0 * 0.6 * phi);
    }
    free(x); free(y);
    tb_free(&m);
}

static int count_kind(const bhem_level *L, int kind, int comp)
{
    int c = 0;
    for (int k = 0; k < L->n_con; k++)
        if ((L->con_dofs[k] % 12) / 3 == kind && (comp < 0 || L->con_dofs[k] % 3 == comp)) c++;
    return c;
}

/* constrained-dof sets of each bc kind (BHEM §4.2) */
SB_TEST(test_bc_sets)
{
    tb_method m;
    const char *bcs[] = {
        "[{\"type\": \"clamped\", \"on\": [\"left\"]}]",
        "[{\"type\": \"fixed\", \"on\": [\"bottom\"], \"components\": \"z\"}]",
        "[{\"type\": \"symmetry\", \"on\": [\"left\"], \"normal\": \"x\"}]",
    };
    int expect[3][4] = { { 15, 5, 15, 5 }, { 5, 5, 0, 0 }, { 5, 10, 5, 10 } };   /* per kind, 5 nodes per edge */
    for (int b = 0; b < 3; b++) {
        char json[2048];
        snprintf(json, sizeof json, TB_SCENE(TB_RECT, TB_PLANE, TB_STVK, "%s", "[]"), bcs[b]);
        int rc = tb_create(&m, json, 4, 1, NULL);
        CHECK_EQ_INT(rc, SB_OK);
        if (rc) continue;
        const bhem_level *L = &m.S->lv[0];
        const sb_dirichlet *D = sb_method_bhem.dirichlet(m.S, 0);
        CHECK(D != NULL);
        for (int k = 1; D && k < D->n; k++) CHECK(D->dofs[k] > D->dofs[k - 1]);
        for (int kind = 0; kind < 4; kind++) CHECK_EQ_INT(count_kind(L, kind, -1), expect[b][kind]);
        if (b == 0) { CHECK_EQ_INT(count_kind(L, 1, 2), 5); CHECK_EQ_INT(count_kind(L, 1, 0), 0); CHECK_EQ_INT(count_kind(L, 3, 2), 5); }
        if (b == 2) { CHECK_EQ_INT(count_kind(L, 0, 0), 5); CHECK_EQ_INT(count_kind(L, 1, 0), 0); }
        tb_free(&m);
    }
}

/* moving point with clamp_tangent: the twisting cloth's centre node (BHEM
 * Fig. 18) gets its position and rotated first derivatives */
SB_TEST(test_moving_rotation)
{
    const char *json = TB_SCENE("{\"type\": \"rectangle\", \"origin\": [-0.5, -0.5], \"size\": [1, 1]}", TB_PLANE, TB_STVK,
        "[{\"type\": \"moving\", \"at\": [0, 0], \"clamp_tangent\": true,"
        "  \"rotation\": {\"axis\": [0, 0, 1], \"center\": [0, 0, 0], \"angle\": 90}}]", "[]");
    tb_method m;
    int rc = tb_create(&m, json, 4, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    const bhem_level *L = &m.S->lv[0];
    CHECK_EQ_INT(L->n_con, 9);
    full_step(&m, 0.0, 0.5);
    const sb_dirichlet *D = sb_method_bhem.dirichlet(m.S, 0);
    int node = bhem_node_at(m.S, L, 2, 2);
    double xs[3] = { 0 }, xt[3] = { 0 };
    for (int k = 0; k < D->n; k++) {
        int d = D->dofs[k];
        CHECK_EQ_INT(d / 12, node);
        if ((d % 12) / 3 == 1) xs[d % 3] = D->values[k];
        if ((d % 12) / 3 == 2) xt[d % 3] = D->values[k];
        if ((d % 12) / 3 == 0) CHECK_NEAR(D->values[k], 0.0, 1e-15);
    }
    double h = 0.25, c = cos(M_PI / 4) * h;
    CHECK_NEAR(xs[0], c, 1e-15); CHECK_NEAR(xs[1], c, 1e-15);
    CHECK_NEAR(xt[0], -c, 1e-15); CHECK_NEAR(xt[1], c, 1e-15);
    tb_free(&m);
    /* a point that is not a node is refused with a message */
    CHECK_EQ_INT(tb_create(&m, json, 3, 1, NULL), SB_ERR_INPUT);
    tb_free(&m);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_fd_exact), SB_CASE(test_fd_pseudo), SB_CASE(test_fd_psd), SB_CASE(test_rest_and_rigid_motion),
        SB_CASE(test_mass_total), SB_CASE(test_load_resultants), SB_CASE(test_end_moment_unwrap),
        SB_CASE(test_bc_sets), SB_CASE(test_moving_rotation), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
