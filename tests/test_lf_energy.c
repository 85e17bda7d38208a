/* test_lf_energy.c — linear_fem energy, gradient and Hessian: finite
 * differences of the geometric derivatives and of the whole method at random
 * deformed states (StVK and denim, midedge with edge / averaged directors and
 * hinge, exact / pseudo / psd), rest state, rigid-motion invariance, the hinge
 * calibration, mass, load resultants, the end moment and the bc sets. */
#include "test_lf_common.h"
#include "sb_geometry.h"

#include <math.h>

/* ---- geometric pieces ---------------------------------------------------- */

static void fd_vec_fun(sb_test_state *T, const char *name, double (*fn)(const double *, double *, double *),
                       const double *w0)
{
    double g[9], H[81], w[9], gp[9], gm[9];
    fn(w0, g, H);
    const double h = 1e-6;
    double gerr = 0, gnorm = 0, herr = 0, hnorm = 0;
    for (int i = 0; i < 9; i++) {
        memcpy(w, w0, sizeof w);
        w[i] += h;
        const double fp = fn(w, gp, NULL);
        w[i] -= 2 * h;
        const double fm = fn(w, gm, NULL);
        gerr = fmax(gerr, fabs((fp - fm) / (2 * h) - g[i]));
        gnorm = fmax(gnorm, fabs(g[i]));
        for (int j = 0; j < 9; j++) {
            herr = fmax(herr, fabs((gp[j] - gm[j]) / (2 * h) - H[9 * j + i]));
            hnorm = fmax(hnorm, fabs(H[9 * j + i]));
        }
    }
    CHECK_MSG(gerr <= 1e-7 * gnorm, "%s gradient: FD error %g (|g| %g)", name, gerr, gnorm);
    CHECK_MSG(herr <= 1e-6 * hnorm, "%s Hessian: FD error %g (|H| %g)", name, herr, hnorm);
    for (int i = 0; i < 9; i++)
        for (int j = 0; j < 9; j++) CHECK(H[9 * i + j] == H[9 * j + i]);
}

static double angle_fn(const double *w, double *g, double *H) { return lf_angle(w, w + 3, w + 6, g, H); }
static double ratio_fn(const double *w, double *g, double *H) { return lf_ratio(w, w + 6, g, H); }

SB_TEST(test_geometry_derivatives)
{
    unsigned long long st = 99;
    for (int k = 0; k < 5; k++) {
        double w[9];
        for (int i = 0; i < 9; i++) w[i] = tl_rand(&st) + (i == 6 ? 2.0 : 0.0);
        fd_vec_fun(T, "angle", angle_fn, w);
        fd_vec_fun(T, "ratio", ratio_fn, w);
    }
    /* the angle is the rotation about +e taking u to v */
    const double u[3] = { 0, 0, 1 }, e[3] = { 0, 2, 0 };
    const double a = 0.7, v[3] = { sin(a), 0, cos(a) };   /* rotation about +y by a maps z to (sin a, 0, cos a) */
    CHECK_NEAR(lf_angle(u, v, e, NULL, NULL), a, 1e-15);
}

/* ---- the whole method ------------------------------------------------------ */

#define FD_BC "[{\"type\": \"clamped\", \"on\": [\"left\"]}, {\"type\": \"symmetry\", \"on\": [\"bottom\"], \"normal\": \"y\"}]"
#define FD_LOADS                                                                                   \
    "[{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]},"                                   \
    " {\"type\": \"pressure\", \"pressure\": 30, \"follower\": true},"                             \
    " {\"type\": \"end_moment\", \"on\": [\"right\"], \"moment_per_length\": 0.7, \"axis\": [0, 1, 0]}]"

static void fd_method(sb_test_state *T, const char *material, const char *bending, const char *director,
                      const char *hess, const char *mesh)
{
    char json[4096];
    snprintf(json, sizeof json, TL_SCENE(TL_RECT, TL_CYL, "%s", FD_BC, FD_LOADS), material);
    const char *sets[] = { bending, director, hess, mesh, NULL };
    tl_method m;
    int rc = tl_create(&m, json, 3, 1, sets);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    tl_step(&m, 1.0, 0.0);
    const int n = sb_method_linear_fem.n_dofs(m.S, 0), nv3 = 3 * m.S->lv[0].nv;
    double *x = malloc(sizeof(double) * n), *v = malloc(sizeof(double) * n), *xp = malloc(sizeof(double) * n);
    double *g = calloc(n, sizeof(double)), *gp = calloc(n, sizeof(double)), *gm = calloc(n, sizeof(double));
    double *Hv = malloc(sizeof(double) * n);
    unsigned long long st = 12345;
    sb_method_linear_fem.initial(m.S, 0, x);
    for (int i = 0; i < n; i++) x[i] += (i < nv3 ? 0.01 : 0.2) * tl_rand(&st);
    for (int i = 0; i < n; i++) v[i] = tl_rand(&st);
    tl_sys sys;
    CHECK_EQ_INT(tl_sys_init(&sys, m.S, 0), SB_OK);
    double f, fp, fm;
    CHECK_EQ_INT(sb_method_linear_fem.energy(m.S, 0, x, &f, g, &sys.H), SB_OK);
    const double e = 1e-6, gv = sb_dot(n, g, v);
    for (int i = 0; i < n; i++) xp[i] = x[i] + e * v[i];
    sb_method_linear_fem.energy(m.S, 0, xp, &fp, gp, NULL);
    for (int i = 0; i < n; i++) xp[i] = x[i] - e * v[i];
    sb_method_linear_fem.energy(m.S, 0, xp, &fm, gm, NULL);
    const double fd = (fp - fm) / (2 * e);
    CHECK_MSG(fabs(fd - gv) <= 1e-6 * fabs(gv) + 1e-12, "%s %s %s %s: g.v = %.12g, FD %.12g", material, bending,
              director, hess, gv, fd);
    CHECK(fabs(gv) > 1e-8);
    sb_matrix_symv(&sys.H, v, Hv);
    double num = 0, den = 0;
    for (int i = 0; i < n; i++) {
        const double d = (gp[i] - gm[i]) / (2 * e);
        num += (d - Hv[i]) * (d - Hv[i]);
        den += d * d;
    }
    const double rel = sqrt(num / den);
    if (strstr(hess, "exact"))
        CHECK_MSG(rel < 1e-6, "%s %s %s %s: |Hv - FD| / |FD| = %g", material, bending, director, mesh, rel);
    else if (strstr(hess, "pseudo"))
        CHECK_MSG(rel > 1e-6, "pseudo Hessian equals the exact one (rel %g)", rel);
    else
        CHECK_MSG(sb_dot(n, v, Hv) >= -1e-12 * sb_norm2(n, Hv) * sb_norm2(n, v), "psd: v.Hv < 0");
    tl_sys_free(&sys);
    free(x); free(v); free(xp); free(g); free(gp); free(gm); free(Hv);
    tl_free(&m);
}

static const char *const MAT[2] = { TL_STVK, TL_DENIM };

SB_TEST(test_fd_midedge_edge)
{
    for (int k = 0; k < 2; k++) {
        fd_method(T, MAT[k], "method.bending=midedge", "method.director=edge", "method.hessian=exact", "method.mesh=alternate");
        fd_method(T, MAT[k], "method.bending=midedge", "method.director=edge", "method.hessian=exact", "method.mesh=jitter");
    }
}
SB_TEST(test_fd_midedge_average)
{
    for (int k = 0; k < 2; k++)
        fd_method(T, MAT[k], "method.bending=midedge", "method.director=average", "method.hessian=exact", "method.mesh=crossed");
}
SB_TEST(test_fd_hinge)
{
    for (int k = 0; k < 2; k++) {
        fd_method(T, MAT[k], "method.bending=hinge", "method.director=edge", "method.hessian=exact", "method.mesh=alternate");
        fd_method(T, MAT[k], "method.bending=hinge", "method.director=edge", "method.hessian=exact", "method.mesh=jitter");
    }
}
SB_TEST(test_fd_pseudo_psd)
{
    fd_method(T, TL_STVK, "method.bending=midedge", "method.director=edge", "method.hessian=pseudo", "method.mesh=alternate");
    fd_method(T, TL_STVK, "method.bending=hinge", "method.director=edge", "method.hessian=pseudo", "method.mesh=alternate");
    fd_method(T, TL_DENIM, "method.bending=midedge", "method.director=edge", "method.hessian=psd", "method.mesh=alternate");
    fd_method(T, TL_DENIM, "method.bending=hinge", "method.director=edge", "method.hessian=psd", "method.mesh=regular");
}

/* rest state: zero energy and gradient (curved reference, clamp and symmetry
 * edges); rigid motions of a free surface, StVK and denim: zero energy and gradient */
SB_TEST(test_rest_and_rigid_motion)
{
    const char *bend[3][2] = { { "method.bending=midedge", "method.director=edge" },
                               { "method.bending=midedge", "method.director=average" },
                               { "method.bending=hinge", "method.director=edge" } };
    /* k: StVK free, denim clamped + symmetry (rest state only), denim free */
    for (int b = 0; b < 3; b++)
        for (int k = 0; k < 3; k++) {
            char json[4096];
            snprintf(json, sizeof json, TL_SCENE(TL_RECT, TL_CYL, "%s", "%s", "[]"), MAT[k ? 1 : 0],
                     k == 1 ? FD_BC : "[{\"type\": \"fixed\", \"on\": [\"left\"]}]");
            const char *sets[] = { bend[b][0], bend[b][1], "method.mesh=jitter", NULL };
            tl_method m;
            int rc = tl_create(&m, json, 4, 1, sets);
            CHECK_EQ_INT(rc, SB_OK);
            if (rc) continue;
            const int n = sb_method_linear_fem.n_dofs(m.S, 0), nv = m.S->lv[0].nv;
            double *x = malloc(sizeof(double) * n), *y = malloc(sizeof(double) * n), *g = calloc(n, sizeof(double)), f;
            sb_method_linear_fem.initial(m.S, 0, x);
            CHECK_EQ_INT(sb_method_linear_fem.energy(m.S, 0, x, &f, g, NULL), SB_OK);
            CHECK_NEAR(f, 0.0, 1e-14);
            CHECK_MSG(sb_norm2(n, g) < 1e-9, "%s %s: rest gradient %g", bend[b][0], bend[b][1], sb_norm2(n, g));
            if (k != 1) {   /* free surface (a fixed bc does not enter the energy) */
                double R[9], ax[3] = { 0.3, -0.5, 0.8 }, an = sqrt(0.98);
                for (int c = 0; c < 3; c++) ax[c] /= an;
                sb_rotation(ax, 1.1, R);
                memcpy(y, x, sizeof(double) * n);
                for (int v = 0; v < nv; v++)
                    for (int c = 0; c < 3; c++) {
                        y[3 * v + c] = 0.7 * (c + 1);
                        for (int d = 0; d < 3; d++) y[3 * v + c] += R[3 * c + d] * x[3 * v + d];
                    }
                memset(g, 0, sizeof(double) * n);
                CHECK_EQ_INT(sb_method_linear_fem.energy(m.S, 0, y, &f, g, NULL), SB_OK);
                CHECK_MSG(fabs(f) < 1e-12, "%s %s %s: rigid-motion energy %g", k ? "denim" : "stvk", bend[b][0],
                          bend[b][1], f);
                CHECK_MSG(sb_norm2(n, g) < 1e-8, "%s %s %s: rigid-motion gradient %g", k ? "denim" : "stvk",
                          bend[b][0], bend[b][1], sb_norm2(n, g));
                for (int i = 0; i < 3 * nv; i++) y[i] = 1.01 * x[i];
                sb_method_linear_fem.energy(m.S, 0, y, &f, NULL, NULL);
                CHECK(f > 1e-3);
            }
            free(x); free(y); free(g);
            tl_free(&m);
        }
}

/* Hinge calibration: cylindrical bending z = kappa x^2 / 2 along a grid axis
 * of the regular mesh gives (D/2) kappa^2 per unit area on every interior
 * hinge, i.e. E = (D/2) kappa^2 (1 - 1/N) on the unit square (no hinge on
 * the free edges).  Small kappa: the membrane part is O(kappa^4). */
SB_TEST(test_hinge_calibration)
{
    const char *json = TL_SCENE("{\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1]}", TL_PLANE, TL_STVK,
                                "[{\"type\": \"fixed\", \"at\": [0, 0]}]", "[]");
    const char *sets[] = { "method.bending=hinge", "method.mesh=regular", NULL };
    tl_method m;
    const int N = 8;
    int rc = tl_create(&m, json, N, 1, sets);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    const double kappa = 1e-6, D = 1e5 * 1e-6 / (12 * (1 - 0.09));
    const int n = m.S->lv[0].n_dofs;
    double *x = malloc(sizeof(double) * n), f;
    for (int dir = 0; dir < 2; dir++) {
        sb_method_linear_fem.initial(m.S, 0, x);
        for (int v = 0; v < m.S->lv[0].nv; v++) x[3 * v + 2] = 0.5 * kappa * x[3 * v + dir] * x[3 * v + dir];
        sb_method_linear_fem.energy(m.S, 0, x, &f, NULL, NULL);
        CHECK_REL(f, 0.5 * D * kappa * kappa * (N - 1.0) / N, 1e-6);
    }
    free(x);
    tl_free(&m);
}

/* 1^T M 1 per component = areal density x area (consistent and lumped) */
SB_TEST(test_mass_total)
{
    const char *mass[2] = { "method.mass=consistent", "method.mass=lumped" };
    for (int k = 0; k < 2; k++) {
        const char *json = TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]", "[]");
        const char *sets[] = { mass[k], "method.mesh=jitter", NULL };
        tl_method m;
        int rc = tl_create(&m, json, 5, 1, sets);
        CHECK_EQ_INT(rc, SB_OK);
        if (rc) continue;
        tl_sys sys;
        CHECK_EQ_INT(tl_sys_init(&sys, m.S, 0), SB_OK);
        CHECK_EQ_INT(sb_method_linear_fem.mass(m.S, 0, &sys.H), SB_OK);
        const int n = m.S->lv[0].n_dofs;
        double *v = calloc(n, sizeof(double)), *Mv = malloc(sizeof(double) * n);
        for (int c = 0; c < 3; c++) {
            memset(v, 0, sizeof(double) * n);
            for (int i = c; i < 3 * m.S->lv[0].nv; i += 3) v[i] = 1.0;
            sb_matrix_symv(&sys.H, v, Mv);
            CHECK_REL(sb_dot(n, v, Mv), 0.5 * 0.6, 1e-13);
        }
        free(v); free(Mv);
        tl_sys_free(&sys);
        tl_free(&m);
    }
}

static void resultant(const lf_level *L, const double *b, double F[3])
{
    F[0] = F[1] = F[2] = 0.0;
    for (int v = 0; v < L->nv; v++)
        for (int c = 0; c < 3; c++) F[c] += b[3 * v + c];
}

SB_TEST(test_load_resultants)
{
    const char *json = TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]",
        "[{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]},"
        " {\"type\": \"pressure\", \"pressure\": -3},"
        " {\"type\": \"line\", \"on\": [\"right\"], \"force_per_length\": [0, 1, 2]},"
        " {\"type\": \"point\", \"at\": [0.37, 0.21], \"force\": [4, 0, -1]}]");
    tl_method m;
    int rc = tl_create(&m, json, 4, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    const lf_level *L = &m.S->lv[0];
    double F[3];
    resultant(L, L->load_vec, F);
    CHECK_REL(F[2], -9.81 * 0.5 * 0.6, 1e-13);
    resultant(L, L->load_vec + L->n_dofs, F);
    CHECK_REL(F[2], -3 * 0.6, 1e-13);
    resultant(L, L->load_vec + 2 * L->n_dofs, F);
    CHECK_REL(F[1], 0.6, 1e-13);
    CHECK_REL(F[2], 1.2, 1e-13);
    resultant(L, L->load_vec + 3 * L->n_dofs, F);
    CHECK_REL(F[0], 4.0, 1e-13);
    CHECK_REL(F[2], -1.0, 1e-13);
    /* the point load's work on a linear displacement equals F . u(point) */
    const int n = L->n_dofs;
    double *x = malloc(sizeof(double) * n), f, f0;
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.load_factor[3] = 1.0;
    sb_method_linear_fem.set_step(m.S, &si);
    sb_method_linear_fem.initial(m.S, 0, x);
    for (int v = 0; v < L->nv; v++) {
        x[3 * v] += 0.2 * L->mesh.xi[2 * v] - 0.1 * L->mesh.xi[2 * v + 1];
        x[3 * v + 2] += 0.3 * L->mesh.xi[2 * v] + 0.5 * L->mesh.xi[2 * v + 1];
    }
    sb_method_linear_fem.energy(m.S, 0, x, &f, NULL, NULL);
    si.load_factor[3] = 0.0;
    sb_method_linear_fem.set_step(m.S, &si);
    sb_method_linear_fem.energy(m.S, 0, x, &f0, NULL, NULL);
    CHECK_NEAR(f - f0, -(4.0 * (0.2 * 0.37 - 0.1 * 0.21) - 1.0 * (0.3 * 0.37 + 0.5 * 0.21)), 1e-12);
    free(x);
    tl_free(&m);
}

/* End moment: a rigid rotation of the strip about the axis by phi gives
 * E = -m * length * phi, continuous past 2 pi when stepped (branch unwrap). */
SB_TEST(test_end_moment_unwrap)
{
    const char *json = TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "[{\"type\": \"fixed\", \"on\": [\"left\"]}]",
        "[{\"type\": \"end_moment\", \"on\": [\"right\"], \"moment_per_length\": 2.0, \"axis\": [0, -1, 0]}]");
    const char *models[3][2] = { { "method.bending=midedge", NULL }, { "method.director=average", NULL },
                                 { "method.bending=hinge", NULL } };
    for (int k = 0; k < 3; k++) {
        tl_method m;
        int rc = tl_create(&m, json, 4, 1, models[k]);
        CHECK_EQ_INT(rc, SB_OK);
        if (rc) continue;
        const int n = m.S->lv[0].n_dofs, nv = m.S->lv[0].nv;
        double *x = malloc(sizeof(double) * n), *y = malloc(sizeof(double) * n), f;
        sb_method_linear_fem.initial(m.S, 0, x);
        double ax[3] = { 0, -1, 0 }, R[9];
        for (int s = 1; s <= 7; s++) {
            const double phi = 0.9 * s;
            tl_step(&m, 1.0, 0.0);
            sb_rotation(ax, phi, R);
            memcpy(y, x, sizeof(double) * n);
            for (int v = 0; v < nv; v++)
                for (int c = 0; c < 3; c++) {
                    y[3 * v + c] = 0.0;
                    for (int d = 0; d < 3; d++) y[3 * v + c] += R[3 * c + d] * x[3 * v + d];
                }
            CHECK_EQ_INT(sb_method_linear_fem.energy(m.S, 0, y, &f, NULL, NULL), SB_OK);
            CHECK_MSG(fabs(f + 2.0 * 0.6 * phi) < 1e-10, "model %d, phi %g: E = %.12g, expected %.12g", k, phi, f,
                      -2.0 * 0.6 * phi);
        }
        free(x); free(y);
        tl_free(&m);
    }
}

/* constrained dofs of each bc kind; refusals */
SB_TEST(test_bc_sets)
{
    const char *bcs[3] = { "[{\"type\": \"clamped\", \"on\": [\"left\"]}]",
                           "[{\"type\": \"fixed\", \"on\": [\"bottom\"], \"components\": \"z\"}]",
                           "[{\"type\": \"symmetry\", \"on\": [\"left\"], \"normal\": \"x\"}]" };
    /* 4 x 4 cells: 5 vertices and 4 edges per side */
    const int expect_edge[3] = { 5 * 3 + 4, 5, 5 + 4 }, expect_avg[3] = { 15, 5, 5 };
    for (int b = 0; b < 3; b++)
        for (int d = 0; d < 2; d++) {
            char json[2048];
            snprintf(json, sizeof json, TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "%s", "[]"), bcs[b]);
            const char *sets[] = { d ? "method.director=average" : "method.director=edge", NULL };
            tl_method m;
            int rc = tl_create(&m, json, 4, 1, sets);
            CHECK_EQ_INT(rc, SB_OK);
            if (rc) continue;
            const sb_dirichlet *D = sb_method_linear_fem.dirichlet(m.S, 0);
            CHECK(D != NULL);
            if (D) {
                CHECK_EQ_INT(D->n, d ? expect_avg[b] : expect_edge[b]);
                for (int k = 1; k < D->n; k++) CHECK(D->dofs[k] > D->dofs[k - 1]);
            }
            tl_free(&m);
        }
    /* clamping a point, or a point that is no vertex: refused before any work */
    tl_method m;
    CHECK_EQ_INT(tl_create(&m, TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "[{\"type\": \"clamped\", \"at\": [0, 0]}]", "[]"),
                           4, 1, NULL), SB_ERR_UNSUPPORTED);
    tl_free(&m);
    CHECK_EQ_INT(tl_create(&m, TL_SCENE(TL_RECT, TL_PLANE, TL_STVK,
                           "[{\"type\": \"moving\", \"at\": [0, 0], \"clamp_tangent\": true, \"translation\": [0, 0, 1]}]",
                           "[]"), 4, 1, NULL), SB_ERR_UNSUPPORTED);
    tl_free(&m);
    CHECK_EQ_INT(tl_create(&m, TL_SCENE(TL_RECT, TL_PLANE, TL_STVK, "[{\"type\": \"fixed\", \"at\": [0.33, 0.2]}]", "[]"),
                           4, 1, NULL), SB_ERR_INPUT);
    tl_free(&m);
}

/* a moving clamp rotates its ghost normals and its vertices */
SB_TEST(test_moving_clamp)
{
    const char *json = TL_SCENE(TL_RECT, TL_PLANE, TL_STVK,
        "[{\"type\": \"moving\", \"on\": [\"left\"], \"clamp_tangent\": true,"
        "  \"rotation\": {\"axis\": [0, 1, 0], \"center\": [0, 0, 0], \"angle\": 90}}]", "[]");
    tl_method m;
    int rc = tl_create(&m, json, 4, 1, NULL);
    CHECK_EQ_INT(rc, SB_OK);
    if (rc) return;
    tl_step(&m, 0.0, 1.0);
    const lf_level *L = &m.S->lv[0];
    int found = 0;
    for (int t = 0; t < L->nt; t++)
        for (int i = 0; i < 3; i++)
            if (L->tri[t].kind[i] == LF_EDGE_CLAMP) {
                /* reference normal +z rotated by 90 degrees about +y: +x */
                CHECK_NEAR(L->tri[t].gv[i][0], 1.0, 1e-14);
                CHECK_NEAR(L->tri[t].gv[i][2], 0.0, 1e-14);
                found++;
            }
    CHECK_EQ_INT(found, 4);
    /* the rigidly rotated plate is stress free: zero energy */
    const int n = L->n_dofs;
    double *x = malloc(sizeof(double) * n), f, R[9], ax[3] = { 0, 1, 0 };
    sb_method_linear_fem.initial(m.S, 0, x);
    sb_rotation(ax, M_PI / 2, R);
    for (int v = 0; v < L->nv; v++) {
        double p[3] = { x[3 * v], x[3 * v + 1], x[3 * v + 2] };
        for (int c = 0; c < 3; c++) x[3 * v + c] = R[3 * c] * p[0] + R[3 * c + 1] * p[1] + R[3 * c + 2] * p[2];
    }
    sb_method_linear_fem.energy(m.S, 0, x, &f, NULL, NULL);
    CHECK_NEAR(f, 0.0, 1e-12);
    const sb_dirichlet *D = sb_method_linear_fem.dirichlet(m.S, 0);
    for (int k = 0; D && k < D->n; k++)
        if (D->dofs[k] < 3 * L->nv) CHECK_NEAR(D->values[k], x[D->dofs[k]], 1e-14);
    free(x);
    tl_free(&m);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_geometry_derivatives), SB_CASE(test_fd_midedge_edge), SB_CASE(test_fd_midedge_average),
        SB_CASE(test_fd_hinge), SB_CASE(test_fd_pseudo_psd), SB_CASE(test_rest_and_rigid_motion),
        SB_CASE(test_hinge_calibration), SB_CASE(test_mass_total), SB_CASE(test_load_resultants),
        SB_CASE(test_end_moment_unwrap), SB_CASE(test_bc_sets), SB_CASE(test_moving_clamp), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
