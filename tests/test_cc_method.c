/* test_cc_method.c — the rmtr method table (sb_method_subdiv): sizes,
 * gradient and Hessian against finite differences, the boundary penalty
 * (3.6) against its closed form, gravity and mass totals, moving corners,
 * eval_points, transfers, and bad input. */
#include "sb_test.h"
#include "sb_method.h"
#include "sb_geometry.h"
#include "sb_material.h"

#include <stdlib.h>
#include <string.h>

extern const sb_method_type sb_method_subdiv;

enum { SC_TRAMPOLINE, SC_DRAPE, SC_LSHAPE, SC_FREE };

static void make_scene(sb_scene *sc, int kind, int gravity)
{
    memset(sc, 0, sizeof *sc);
    snprintf(sc->name, sizeof sc->name, "cc_test_%d", kind);
    sc->domain.kind = kind == SC_LSHAPE ? SB_DOMAIN_L_SHAPE : SB_DOMAIN_RECTANGLE;
    sc->domain.size[0] = sc->domain.size[1] = 1.0;
    if (kind == SC_LSHAPE) {
        sc->domain.notch[0] = sc->domain.notch[1] = 0.3;
        sc->domain.notch_corner = SB_CORNER_11;
    }
    sc->chart.kind = SB_CHART_PLANE;
    sb_material_spec_denim(&sc->material);
    sc->time.mode = SB_TIME_QUASI_STATIC;
    sc->time.steps = 1;
    if (gravity) {
        sc->n_loads = 1;
        sc->loads[0].kind = SB_LOAD_GRAVITY;
        sc->loads[0].vec[2] = -9.81;
    }
    sb_bc *bc = &sc->bcs[0];
    if (kind == SC_TRAMPOLINE || kind == SC_LSHAPE) {
        static const char *sq[4] = { "left", "right", "bottom", "top" }, *ls[2] = { "notch_s", "notch_t" };
        int np = kind == SC_LSHAPE ? 2 : 4;
        sc->n_bcs = 1;
        bc->kind = SB_BC_FIXED;
        bc->components = 7;
        bc->n_parts = np;
        for (int i = 0; i < np; i++) sb_domain_edge_part(&sc->domain, kind == SC_LSHAPE ? ls[i] : sq[i], &bc->parts[i]);
    } else if (kind == SC_DRAPE) {
        sc->n_bcs = 2;
        for (int i = 0; i < 2; i++) {
            bc = &sc->bcs[i];
            bc->kind = SB_BC_MOVING;
            bc->components = 7;
            bc->n_parts = 1;
            bc->parts[0].kind = SB_PART_POINT;
            snprintf(bc->parts[0].name, sizeof bc->parts[0].name, "point_%d", i);
            bc->parts[0].xi[0] = bc->parts[0].st[0] = i;
            bc->parts[0].xi[1] = bc->parts[0].st[1] = 1.0;
            bc->translation[0] = i ? -0.2 : 0.2;
        }
    }
}

static void *create_ps(const sb_scene *sc, int res, int levels, int *rc, const sb_paramset *ps)
{
    void *st = calloc(1, sb_method_subdiv.state_size);
    sb_method_config cfg = { res, levels, ps, NULL, 0 };
    *rc = sb_method_subdiv.create(st, sc, &cfg);
    if (*rc) {
        free(st);
        return NULL;
    }
    return st;
}

static void *create(const sb_scene *sc, int res, int levels, int *rc) { return create_ps(sc, res, levels, rc, NULL); }

static void destroy(void *st)
{
    if (!st) return;
    sb_method_subdiv.destroy(st);
    free(st);
}

static void step(void *st, double f)
{
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1;
    si.n_steps = 1;
    for (int i = 0; i < SB_SCENE_MAX_LOADS; i++) si.load_factor[i] = 1.0;
    for (int i = 0; i < SB_SCENE_MAX_BCS; i++) si.motion_factor[i] = f;
    sb_method_subdiv.set_step(st, &si);
}

static double rnd(unsigned long *s)
{
    *s = *s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(*s >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

SB_TEST(sizes_and_levels)
{
    sb_scene sc;
    make_scene(&sc, SC_TRAMPOLINE, 1);
    int rc;
    void *st = create(&sc, 16, 3, &rc);
    CHECK_MSG(st != NULL, "create failed: %d", rc);
    if (!st) return;
    CHECK_EQ_INT(sb_method_subdiv.n_levels(st), 3);
    CHECK_EQ_INT(sb_method_subdiv.n_dofs(st, 0), 147);
    CHECK_EQ_INT(sb_method_subdiv.n_dofs(st, 1), 363);
    CHECK_EQ_INT(sb_method_subdiv.n_dofs(st, 2), 1083);
    CHECK(sb_method_subdiv.dirichlet(st, 2) == NULL);
    char buf[256];
    sb_method_subdiv.describe(st, buf, sizeof buf);
    CHECK(strstr(buf, "1083") != NULL);
    destroy(st);
}

/* directional derivative and Hessian-vector product against central differences */
static void fd_check(sb_test_state *T, const sb_scene *sc, int res, int levels, int level, double amp)
{
    int rc;
    void *st = create(sc, res, levels, &rc);
    CHECK_MSG(st != NULL, "create failed: %d", rc);
    if (!st) return;
    step(st, 0.5);
    int n = sb_method_subdiv.n_dofs(st, level);
    sb_pattern_builder *pb = sb_pattern_builder_new(n / 3, 3);
    sb_pattern *pat = NULL;
    CHECK(sb_method_subdiv.pattern(st, level, pb) == SB_OK);
    CHECK(sb_pattern_builder_finish(pb, &pat) == SB_OK);
    sb_matrix H;
    sb_matrix_init(&H, pat);
    double *x = malloc(sizeof(double) * n * 6), *d = x + n, *g = x + 2 * n, *gp = x + 3 * n, *gm = x + 4 * n, *Hd = x + 5 * n;
    unsigned long seed = 7;
    sb_method_subdiv.initial(st, level, x);
    for (int i = 0; i < n; i++) {
        x[i] += amp * rnd(&seed);
        d[i] = rnd(&seed);
    }
    double f, fp, fm;
    memset(g, 0, sizeof(double) * n);
    sb_matrix_zero(&H);
    CHECK(sb_method_subdiv.energy(st, level, x, &f, g, &H) == SB_OK);
    sb_matrix_symv(&H, d, Hd);
    double gd = sb_dot(n, g, d), best_g = 1e300, best_h = 1e300;
    for (double h = 1e-4; h >= 1e-8; h *= 0.1) {
        sb_axpy(n, h, d, x);
        memset(gp, 0, sizeof(double) * n);
        sb_method_subdiv.energy(st, level, x, &fp, gp, NULL);
        sb_axpy(n, -2 * h, d, x);
        memset(gm, 0, sizeof(double) * n);
        sb_method_subdiv.energy(st, level, x, &fm, gm, NULL);
        sb_axpy(n, h, d, x);
        best_g = fmin(best_g, fabs((fp - fm) / (2 * h) - gd) / fabs(gd));
        double num = 0, den = 0;
        for (int i = 0; i < n; i++) {
            double r = (gp[i] - gm[i]) / (2 * h) - Hd[i];
            num += r * r;
            den += Hd[i] * Hd[i];
        }
        best_h = fmin(best_h, sqrt(num / den));
    }
    printf("    FD level %d (%d dofs): gradient rel. err %.2e, Hessian rel. err %.2e\n", level, n, best_g, best_h);
    CHECK(best_g < 1e-6);
    CHECK(best_h < 1e-5);
    free(x);
    sb_matrix_free(&H);
    sb_pattern_free(pat);
    destroy(st);
}

SB_TEST(gradient_and_hessian_by_fd)
{
    sb_scene sc;
    make_scene(&sc, SC_TRAMPOLINE, 1);
    fd_check(T, &sc, 8, 2, 1, 2e-3);
    make_scene(&sc, SC_DRAPE, 1);
    fd_check(T, &sc, 8, 2, 0, 5e-3);
    make_scene(&sc, SC_LSHAPE, 1);
    fd_check(T, &sc, 8, 2, 1, 2e-3);
    /* clamped (left, bottom) and symmetry (right, normal e_x) edges: the slope penalty */
    make_scene(&sc, SC_TRAMPOLINE, 1);
    sc.bcs[0].kind = SB_BC_CLAMPED;
    sc.bcs[0].n_parts = 2;
    sc.n_bcs = 2;
    sc.bcs[1] = sc.bcs[0];
    sc.bcs[1].kind = SB_BC_SYMMETRY;
    sc.bcs[1].axis = 0;
    sc.bcs[1].n_parts = 1;
    sb_domain_edge_part(&sc.domain, "right", &sc.bcs[1].parts[0]);
    fd_check(T, &sc, 8, 2, 1, 2e-3);
}

/* Rigid lift by dz of the reference: elastic energy 0, the edge penalty is
 * beta/2 dz^2 |d omega| with beta = h^-5 (3.6); gravity pulls with rho g A. */
SB_TEST(penalty_and_gravity_closed_form)
{
    sb_scene sc;
    make_scene(&sc, SC_TRAMPOLINE, 0);
    int rc;
    void *st = NULL;
    for (int per_level = 0; per_level < 2; per_level++) {
        sb_paramset ps;
        sb_paramset_init(&ps);
        sb_paramset_add(&ps, "method", sb_method_subdiv.params);
        char err[256];
        if (per_level) CHECK(sb_paramset_set(&ps, "method.penalty_h=level", err, sizeof err) == SB_OK);
        st = create_ps(&sc, 8, 2, &rc, &ps);
        CHECK(st != NULL);
        if (!st) return;
        step(st, 1.0);
        for (int l = 0; l < 2; l++) {
            int n = sb_method_subdiv.n_dofs(st, l);
            double *x = malloc(sizeof(double) * n), f;
            sb_method_subdiv.initial(st, l, x);
            CHECK(sb_method_subdiv.energy(st, l, x, &f, NULL, NULL) == SB_OK);
            CHECK_NEAR(f, 0.0, 1e-12);
            for (int i = 2; i < n; i += 3) x[i] += 1e-3;
            CHECK(sb_method_subdiv.energy(st, l, x, &f, NULL, NULL) == SB_OK);
            /* beta/2 dz^2 |d omega|, beta = h^-5 with the finest h (default) or the level's */
            double h = per_level ? 1.0 / (4 << l) : 1.0 / 8, beta = pow(h, -5.0);
            CHECK_REL(f, 0.5 * beta * 1e-6 * 4.0, 1e-10);
            free(x);
        }
        if (per_level == 0) destroy(st);
    }
    destroy(st);
    make_scene(&sc, SC_TRAMPOLINE, 1);
    st = create(&sc, 8, 1, &rc);
    CHECK(st != NULL);
    if (!st) return;
    step(st, 1.0);
    int n = sb_method_subdiv.n_dofs(st, 0);
    double *x = malloc(sizeof(double) * 2 * n), *g = x + n, f;
    sb_method_subdiv.initial(st, 0, x);
    memset(g, 0, sizeof(double) * n);
    CHECK(sb_method_subdiv.energy(st, 0, x, &f, g, NULL) == SB_OK);
    double gz = 0;
    for (int i = 2; i < n; i += 3) gz += g[i];
    CHECK_REL(gz, 0.4 * 9.81 * 1.0, 1e-12);        /* dE/dz summed = weight rho g A */
    /* mass: 1^T M_x 1 = rho A */
    sb_pattern_builder *pb = sb_pattern_builder_new(n / 3, 3);
    sb_pattern *pat = NULL;
    sb_method_subdiv.pattern(st, 0, pb);
    sb_pattern_builder_finish(pb, &pat);
    sb_matrix M;
    sb_matrix_init(&M, pat);
    sb_matrix_zero(&M);
    CHECK(sb_method_subdiv.mass(st, 0, &M) == SB_OK);
    for (int i = 0; i < n; i++) x[i] = i % 3 == 0;
    sb_matrix_symv(&M, x, g);
    CHECK_REL(sb_dot(n, x, g), 0.4, 1e-12);
    sb_matrix_free(&M);
    sb_pattern_free(pat);
    free(x);
    destroy(st);
}

/* drape corners: at the reference, after set_step(f = 1), the two point
 * penalties give beta/2 (0.2^2) each, on every level of the hierarchy (§6:
 * boundary data distributed to all levels each step) */
SB_TEST(moving_corners)
{
    sb_scene sc;
    make_scene(&sc, SC_DRAPE, 0);
    int rc;
    void *st = create(&sc, 8, 2, &rc);
    CHECK(st != NULL);
    if (!st) return;
    for (int l = 0; l < 2; l++) {
        int n = sb_method_subdiv.n_dofs(st, l);
        double *x = malloc(sizeof(double) * n), f;
        sb_method_subdiv.initial(st, l, x);
        step(st, 0.0);
        CHECK(sb_method_subdiv.energy(st, l, x, &f, NULL, NULL) == SB_OK);
        CHECK_NEAR(f, 0.0, 1e-12);
        step(st, 1.0);
        CHECK(sb_method_subdiv.energy(st, l, x, &f, NULL, NULL) == SB_OK);
        CHECK_REL(f, 2 * 0.5 * pow(0.125, -5.0) * 0.04, 1e-12);
        step(st, 0.5);
        CHECK(sb_method_subdiv.energy(st, l, x, &f, NULL, NULL) == SB_OK);
        CHECK_REL(f, 2 * 0.5 * pow(0.125, -5.0) * 0.01, 1e-12);
        free(x);
    }
    destroy(st);
}

/* eval_points at the reference returns (s, t, 0), also on the L-shape's
 * notch edges; the hierarchy's transfers: P I = id for reverse and lsq */
SB_TEST(eval_points_and_transfers)
{
    sb_scene sc;
    for (int kind = 0; kind < 2; kind++) {
        make_scene(&sc, kind ? SC_LSHAPE : SC_TRAMPOLINE, 1);
        int rc;
        void *st = create(&sc, 8, 2, &rc);
        CHECK(st != NULL);
        if (!st) return;
        int n = sb_method_subdiv.n_dofs(st, 1);
        double *x = malloc(sizeof(double) * n);
        sb_method_subdiv.initial(st, 1, x);
        double pts[] = { 0, 0, 1, 0, 0.5, 0.5, 0.7, 0.85, 0.85, 0.7, 0.7, 0.7, 0.123, 0.987, 0.33, 0.66 };
        double pos[24];
        CHECK(sb_method_subdiv.eval_points(st, 1, x, 8, pts, pos) == SB_OK);
        double err = 0;
        for (int p = 0; p < 8; p++)
            err = fmax(err, fabs(pos[3 * p] - pts[2 * p]) + fabs(pos[3 * p + 1] - pts[2 * p + 1]) + fabs(pos[3 * p + 2]));
        CHECK(err < 1e-13);
        if (kind) {
            double out[2] = { 0.9, 0.9 };
            CHECK(sb_method_subdiv.eval_points(st, 1, x, 1, out, pos) == SB_ERR_INPUT);
        }
        int nc = sb_method_subdiv.n_dofs(st, 0);
        double *xc = malloc(sizeof(double) * 2 * nc), *xp = malloc(sizeof(double) * n);
        sb_method_subdiv.initial(st, 0, xc);
        sb_method_subdiv.prolong(st, 0, xc, xp);
        double d = 0;
        for (int i = 0; i < n; i++) d = fmax(d, fabs(xp[i] - x[i]));
        CHECK(d < 1e-14);                 /* nested reference configuration */
        unsigned long seed = 3;
        for (int i = 0; i < nc; i++) xc[i] = rnd(&seed);
        sb_method_subdiv.prolong(st, 0, xc, xp);
        sb_method_subdiv.project(st, 0, xp, xc + nc);
        d = 0;
        for (int i = 0; i < nc; i++) d = fmax(d, fabs(xc[nc + i] - xc[i]));
        CHECK(d < 1e-12);
        free(xc); free(xp); free(x);
        destroy(st);
    }
}

/* the three projection choices: lsq is a projection too, restrict keeps
 * constants (translations) only */
SB_TEST(projection_choices)
{
    static const char *set[3] = { "method.projection=reverse", "method.projection=lsq", "method.projection=restrict" };
    sb_scene sc;
    make_scene(&sc, SC_TRAMPOLINE, 1);
    for (int c = 0; c < 3; c++) {
        sb_paramset ps;
        sb_paramset_init(&ps);
        sb_paramset_add(&ps, "method", sb_method_subdiv.params);
        char err[256];
        CHECK(sb_paramset_set(&ps, set[c], err, sizeof err) == SB_OK);
        int rc;
        void *st = create_ps(&sc, 8, 2, &rc, &ps);
        CHECK(st != NULL);
        if (!st) return;
        int nc = sb_method_subdiv.n_dofs(st, 0), nf = sb_method_subdiv.n_dofs(st, 1);
        double *xc = malloc(sizeof(double) * (2 * nc + nf)), *yc = xc + nc, *xf = yc + nc;
        unsigned long seed = 5;
        for (int i = 0; i < nc; i++) xc[i] = i % 3 == 1 ? 0.25 : rnd(&seed);
        sb_method_subdiv.prolong(st, 0, xc, xf);
        CHECK(sb_method_subdiv.project(st, 0, xf, yc) == SB_OK);
        double d = 0, dy = 0;
        for (int i = 0; i < nc; i++) {
            d = fmax(d, fabs(yc[i] - xc[i]));
            if (i % 3 == 1) dy = fmax(dy, fabs(yc[i] - 0.25));
        }
        if (c < 2) CHECK(d < 1e-12);
        else CHECK(d > 1e-3 && dy < 1e-14);
        free(xc);
        destroy(st);
    }
}

/* Galerkin property of the hierarchy: with the finest h in every level's
 * penalty and Gauss rules exact for the reference Hessian (4 points), the
 * coarse Hessian at the reference equals S^T H_fine S.  Checks S, nested
 * reference geometry, quadrature and the boundary penalty at once. */
static void hessian_of(void *st, int level, sb_pattern **pat, sb_matrix *H)
{
    int n = sb_method_subdiv.n_dofs(st, level);
    sb_pattern_builder *pb = sb_pattern_builder_new(n / 3, 3);
    sb_method_subdiv.pattern(st, level, pb);
    sb_pattern_builder_finish(pb, pat);
    sb_matrix_init(H, *pat);
    sb_matrix_zero(H);
    double *x = malloc(sizeof(double) * 2 * n), f;
    sb_method_subdiv.initial(st, level, x);
    memset(x + n, 0, sizeof(double) * n);
    sb_method_subdiv.energy(st, level, x, &f, x + n, H);
    free(x);
}

SB_TEST(galerkin_coarse_hessian)
{
    /* square: affine reference, 4 Gauss points are exact; L-shape: the
     * non-uniform spline map makes the metric rational, so only the
     * quadrature error remains (6 points) */
    static const char *gauss[2] = { "method.gauss=4", "method.gauss=6" };
    static const double tol[2] = { 1e-13, 1e-8 };
    for (int kind = 0; kind < 2; kind++) {
        sb_paramset ps;
        sb_paramset_init(&ps);
        sb_paramset_add(&ps, "method", sb_method_subdiv.params);
        char err[256];
        CHECK(sb_paramset_set(&ps, gauss[kind], err, sizeof err) == SB_OK);
        CHECK(sb_paramset_set(&ps, "method.penalty_h=finest", err, sizeof err) == SB_OK);
        sb_scene sc;
        make_scene(&sc, kind ? SC_LSHAPE : SC_TRAMPOLINE, 1);
        sc.material.kind = SB_MAT_STVK;
        sc.material.young = 1e6;
        sc.material.poisson = 0.3;
        int rc;
        void *st = create_ps(&sc, 8, 2, &rc, &ps);
        CHECK(st != NULL);
        if (!st) return;
        step(st, 1.0);
        sb_pattern *pf, *pc;
        sb_matrix Hf, Hc;
        hessian_of(st, 1, &pf, &Hf);
        hessian_of(st, 0, &pc, &Hc);
        int nf = sb_method_subdiv.n_dofs(st, 1), nc = sb_method_subdiv.n_dofs(st, 0);
        double *v = malloc(sizeof(double) * (2 * nc + 2 * nf)), *a = v + nc, *vf = a + nc, *hf = vf + nf;
        unsigned long seed = 11;
        for (int i = 0; i < nc; i++) v[i] = rnd(&seed);
        sb_method_subdiv.prolong(st, 0, v, vf);
        sb_matrix_symv(&Hf, vf, hf);
        sb_method_subdiv.restrict_adj(st, 0, hf, a);          /* S^T H_f S v */
        sb_matrix_symv(&Hc, v, hf);                            /* H_c v (hf reused, nc <= nf) */
        double num = 0, den = 0;
        for (int i = 0; i < nc; i++) {
            num += (a[i] - hf[i]) * (a[i] - hf[i]);
            den += hf[i] * hf[i];
        }
        printf("    %s: |S^T H_f S v - H_c v| / |H_c v| = %.2e\n", kind ? "L-shape" : "square", sqrt(num / den));
        CHECK(sqrt(num / den) < tol[kind]);
        free(v);
        sb_matrix_free(&Hf);
        sb_matrix_free(&Hc);
        sb_pattern_free(pf);
        sb_pattern_free(pc);
        destroy(st);
    }
}

SB_TEST(bad_input)
{
    sb_scene sc;
    make_scene(&sc, SC_TRAMPOLINE, 1);
    int rc;
    void *st = create(&sc, 6, 3, &rc);             /* 6 not divisible by 4 */
    CHECK(st == NULL && rc == SB_ERR_INPUT);
    make_scene(&sc, SC_LSHAPE, 1);
    st = create(&sc, 4, 3, &rc);                   /* L-shape needs >= 2 coarse elements */
    CHECK(st == NULL && rc == SB_ERR_INPUT);
    make_scene(&sc, SC_TRAMPOLINE, 1);
    sc.bcs[0].kind = SB_BC_MOVING;                 /* prescribed tangents: not by this method */
    sc.bcs[0].clamp_tangent = 1;
    st = create(&sc, 4, 1, &rc);
    CHECK(st == NULL && rc == SB_ERR_UNSUPPORTED);
    make_scene(&sc, SC_TRAMPOLINE, 1);
    sc.material.thickness = -1;
    st = create(&sc, 4, 1, &rc);
    CHECK(st == NULL && rc < 0);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(sizes_and_levels),
        SB_CASE(gradient_and_hessian_by_fd),
        SB_CASE(penalty_and_gravity_closed_form),
        SB_CASE(moving_corners),
        SB_CASE(eval_points_and_transfers),
        SB_CASE(projection_choices),
        SB_CASE(galerkin_coarse_hessian),
        SB_CASE(bad_input),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
