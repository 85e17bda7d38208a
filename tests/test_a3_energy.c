/* test_a3_energy.c — adaptive_sqrt3 at full resolution: finite differences
 * of the frozen-rotation membrane and the isometric bending (the parts that
 * are potentials), the measured mismatch of the lagged-rotation force with
 * the gradient of its energy (why the method is not a potential), rigid
 * motions (forces vanish; objectivity), Voronoi masses (Alg. 1, mass
 * conserved), the bending calibration on a cylinder, the refusals, and a
 * free fall through `shellbench run` with the linearized solver (the linear
 * implicit Euler of Eq. 21 moves a free sheet exactly like a particle). */
#include "sb_test.h"
#include "run_json.h"
#include "../methods/adaptive_sqrt3/a3.h"
#include "sb_geometry.h"
#include "sb_material.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* deterministic uniform numbers in [-1, 1) */
static double rnd(unsigned long long *st)
{
    *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*st >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

typedef struct a3m { sb_scene scene; sb_paramset ps; a3_state *S; } a3m;

static int a3m_create(a3m *m, const char *json, int res, const char *const *sets)
{
    char err[1024];
    memset(m, 0, sizeof *m);
    if (sb_scene_parse_string(json, "inline.json", &m->scene, err, sizeof err)) {
        printf("    scene: %s\n", err);
        return SB_ERR_INPUT;
    }
    sb_paramset_init(&m->ps);
    sb_paramset_add(&m->ps, "method", sb_method_adaptive_sqrt3.params);
    for (int i = 0; sets && sets[i]; i++)
        if (sb_paramset_set(&m->ps, sets[i], err, sizeof err)) {
            printf("    param: %s\n", err);
            return SB_ERR_INPUT;
        }
    m->S = calloc(1, sb_method_adaptive_sqrt3.state_size);
    if (!m->S) return SB_ERR_NOMEM;
    sb_method_config cfg = { res, 1, &m->ps, NULL, 0 };
    int rc = sb_method_adaptive_sqrt3.create(m->S, &m->scene, &cfg);
    if (rc) { free(m->S); m->S = NULL; }
    return rc;
}

static void a3m_free(a3m *m)
{
    if (m->S) {
        sb_method_adaptive_sqrt3.destroy(m->S);
        free(m->S);
    }
    sb_scene_free(&m->scene);
}

#define SCENE_FMT                                                                                          \
    "{\"name\": \"t\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [%g, %g]},"     \
    " \"geometry\": {\"type\": \"%s\"%s},"                                                                  \
    " \"material\": {\"model\": \"%s, \"thickness\": 0.001,"                                                \
    " \"density\": 0.1, \"warp_angle\": %g}, \"loads\": [%s], \"boundary\": [%s],"                         \
    " \"time\": {\"mode\": \"dynamic\", \"dt\": 0.005, \"steps\": %d}, \"probes\": [%s]}"

static void scene_json(char *buf, size_t len, const char *chart, const char *mat, double warp, const char *loads,
                       const char *bcs, int steps, const char *probes)
{
    snprintf(buf, len, SCENE_FMT, 1.0, 0.8, chart, strcmp(chart, "cylinder") ? "" : ", \"radius\": 1, \"angle\": [0, 40], \"length\": 1",
             strcmp(mat, "stvk") ? "denim\"" : "stvk\", \"young\": 1e6, \"poisson\": 0.33", warp, loads, bcs, steps, probes);
}

/* one random triangle and a random deformed state of it */
static void random_tri(unsigned long long *st, const double C[9], a3_tri *tr, double q[9])
{
    double X[9] = { 0, 0, 0, 1, 0.1, 0, 0.2, 0.9, 0 };
    for (int i = 0; i < 9; i++) X[i] += 0.2 * rnd(st);
    const double w[3] = { cos(0.3), sin(0.3), 0 };
    double Xz[9];
    memcpy(Xz, X, sizeof X);
    Xz[2] = Xz[5] = Xz[8] = 0.0;
    a3_tri_init(tr, Xz, Xz + 3, Xz + 6, w, C);
    for (int i = 0; i < 9; i++) q[i] = Xz[i] + 0.3 * rnd(st);
}

static void iso_C(double C[9], double Es_factor, double ey)
{
    const double Y = 1000, nu = 0.33, Ey = ey * Y, nyx = nu * ey, d = 1 - nu * nyx;
    const double Es = Es_factor * 2 * Y / (1 + nu);
    const double c[9] = { Y / d, Y * nyx / d, 0, Ey * nu / d, Ey / d, 0, 0, 0, Es };
    memcpy(C, c, sizeof c);
}

/* FD of g (against E) and H (against g) for the membrane with the rotation
 * frozen at the state's own R_p: exact derivatives expected */
SB_TEST(test_membrane_frozen_fd)
{
    unsigned long long st = 7;
    for (int k = 0; k < 6; k++) {
        double C[9], q[9], Rp[6], g[9] = { 0 }, H[81] = { 0 };
        iso_C(C, k % 2 ? 0.5 : 1.0, k < 3 ? 1.0 : 2.5);
        a3_tri tri;
        random_tri(&st, C, &tri, q);
        a3_membrane(&tri, q, NULL, Rp, NULL, NULL);
        a3_membrane(&tri, q, Rp, NULL, g, H);
        const double h = 1e-6;
        double gerr = 0, gn = 0, herr = 0, hn = 0;
        for (int i = 0; i < 9; i++) {
            double qp[9], qm[9], gp[9] = { 0 }, gm[9] = { 0 };
            memcpy(qp, q, sizeof qp);
            memcpy(qm, q, sizeof qm);
            qp[i] += h;
            qm[i] -= h;
            const double fp = a3_membrane(&tri, qp, Rp, NULL, gp, NULL), fm = a3_membrane(&tri, qm, Rp, NULL, gm, NULL);
            gerr = fmax(gerr, fabs((fp - fm) / (2 * h) - g[i]));
            gn = fmax(gn, fabs(g[i]));
            for (int j = 0; j < 9; j++) {
                herr = fmax(herr, fabs((gp[j] - gm[j]) / (2 * h) - H[9 * j + i]));
                hn = fmax(hn, fabs(H[9 * j + i]));
            }
        }
        CHECK_MSG(gerr <= 1e-6 * gn, "frozen membrane gradient: FD error %g (|g| %g)", gerr, gn);
        CHECK_MSG(herr <= 1e-6 * hn, "frozen membrane Hessian: FD error %g (|H| %g)", herr, hn);
        for (int i = 0; i < 9; i++)
            for (int j = 0; j < 9; j++) CHECK(fabs(H[9 * i + j] - H[9 * j + i]) <= 1e-12 * hn);
    }
}

/* The corotational force against the gradient of E(x) = 1/2 u^T K u with R
 * at x: equal for the isotropic C (the rotation's derivative cancels when
 * the stress commutes with the stretch), different for an orthotropic one:
 * the reason the method does not carry SB_METHOD_POTENTIAL. */
static double force_vs_gradient(const double C[9], unsigned long long seed)
{
    unsigned long long st = seed;
    double worst = 0;
    for (int k = 0; k < 5; k++) {
        double q[9], g[9] = { 0 };
        a3_tri tri;
        random_tri(&st, C, &tri, q);
        a3_membrane(&tri, q, NULL, NULL, g, NULL);
        double err = 0, gn = 0;
        for (int i = 0; i < 9; i++) {
            const double h = 1e-6;
            double qp[9], qm[9];
            memcpy(qp, q, sizeof qp);
            memcpy(qm, q, sizeof qm);
            qp[i] += h;
            qm[i] -= h;
            const double d = (a3_membrane(&tri, qp, NULL, NULL, NULL, NULL) - a3_membrane(&tri, qm, NULL, NULL, NULL, NULL)) / (2 * h);
            err = fmax(err, fabs(d - g[i]));
            gn = fmax(gn, fabs(g[i]));
        }
        worst = fmax(worst, err / gn);
    }
    return worst;
}

SB_TEST(test_corotational_not_a_potential)
{
    double C[9];
    iso_C(C, 1.0, 1.0);
    const double iso = force_vs_gradient(C, 11);
    iso_C(C, 1.0, 2.5);
    const double ortho = force_vs_gradient(C, 11);
    iso_C(C, 0.5, 1.0);
    const double shear = force_vs_gradient(C, 11);
    printf("    |f - dE/dx| / |f|: isotropic %.2e, E_y = 2.5 E_x %.2e, E_s halved %.2e\n", iso, ortho, shear);
    CHECK_MSG(iso < 1e-6, "isotropic corotational force is the gradient: mismatch %g", iso);
    CHECK_MSG(ortho > 1e-3, "orthotropic force should differ from the gradient: %g", ortho);
    CHECK_MSG(shear > 1e-3, "E_s off the isotropic value should differ from the gradient: %g", shear);
    CHECK(!(sb_method_adaptive_sqrt3.flags & SB_METHOD_POTENTIAL));
}

SB_TEST(test_bending_fd)
{
    unsigned long long st = 3;
    for (int k = 0; k < 4; k++) {
        double X[12] = { 0, 0, 0, 1, 0, 0, 0.4, 0.8, 0, 0.6, -0.7, 0 }, q[12], g[12] = { 0 }, H[144] = { 0 };
        for (int i = 0; i < 12; i++)
            if (i % 3 != 2) X[i] += 0.1 * rnd(&st);
        a3_edge e;
        memset(&e, 0, sizeof e);
        a3_bend_weights(X, X + 3, X + 6, X + 9, e.k);
        e.q = 0.7;
        /* a flat rest state has no bending energy and no force */
        CHECK(fabs(a3_bend(&e, X, NULL, NULL)) < 1e-28);
        for (int i = 0; i < 12; i++) q[i] = X[i] + 0.2 * rnd(&st);
        a3_bend(&e, q, g, H);
        double gerr = 0, gn = 0, herr = 0, hn = 0;
        for (int i = 0; i < 12; i++) {
            const double h = 1e-5;
            double qp[12], qm[12], gp[12] = { 0 }, gm[12] = { 0 };
            memcpy(qp, q, sizeof qp);
            memcpy(qm, q, sizeof qm);
            qp[i] += h;
            qm[i] -= h;
            const double fp = a3_bend(&e, qp, gp, NULL), fm = a3_bend(&e, qm, gm, NULL);
            gerr = fmax(gerr, fabs((fp - fm) / (2 * h) - g[i]));
            gn = fmax(gn, fabs(g[i]));
            for (int j = 0; j < 12; j++) {
                herr = fmax(herr, fabs((gp[j] - gm[j]) / (2 * h) - H[12 * j + i]));
                hn = fmax(hn, fabs(H[12 * j + i]));
            }
        }
        CHECK_MSG(gerr <= 1e-8 * gn, "bending gradient: FD error %g (|g| %g)", gerr, gn);
        CHECK_MSG(herr <= 1e-8 * hn, "bending Hessian: FD error %g (|H| %g)", herr, hn);
    }
}

/* The whole method under rigid motions of the reference, and objectivity
 * of a deformed state: forces rotate with the body. */
SB_TEST(test_rigid_motion)
{
    char js[2048];
    scene_json(js, sizeof js, "plane", "stvk", 0.4, "", "", 1, "");
    a3m m;
    const char *sets[] = { "method.Ey_ratio=2", "method.Es=700", NULL };
    CHECK(a3m_create(&m, js, 6, sets) == SB_OK);
    if (!m.S) return;
    a3_state *S = m.S;
    const int n = S->n_dofs;
    double *x = malloc(sizeof(double) * n), *g = calloc(n, sizeof(double)), *y = malloc(sizeof(double) * n);
    double *g2 = calloc(n, sizeof(double));
    double R[9];
    const double ax[3] = { 0.3, -0.5, 0.81 }, an = sqrt(0.09 + 0.25 + 0.81 * 0.81);
    const double axn[3] = { ax[0] / an, ax[1] / an, ax[2] / an };
    sb_rotation(axn, 2.1, R);
    for (int v = 0; v < S->nv; v++)
        for (int c = 0; c < 3; c++)
            x[3 * v + c] = R[3 * c] * S->x_ref[3 * v] + R[3 * c + 1] * S->x_ref[3 * v + 1] + R[3 * c + 2] * S->x_ref[3 * v + 2] + 0.3 * c;
    double f;
    CHECK(a3_energy(S, x, &f, g, NULL) == SB_OK);
    double gmax = 0;
    for (int i = 0; i < n; i++) gmax = fmax(gmax, fabs(g[i]));
    CHECK_MSG(fabs(f) < 1e-18 && gmax < 1e-9, "rigid motion: E %g, max |g| %g", f, gmax);
    /* objectivity: g(R x) = R g(x) for a deformed x */
    unsigned long long st = 5;
    for (int i = 0; i < n; i++) x[i] = S->x_ref[i] + 0.02 * rnd(&st);
    memset(g, 0, sizeof(double) * n);
    a3_energy(S, x, &f, g, NULL);
    for (int v = 0; v < S->nv; v++)
        for (int c = 0; c < 3; c++) y[3 * v + c] = R[3 * c] * x[3 * v] + R[3 * c + 1] * x[3 * v + 1] + R[3 * c + 2] * x[3 * v + 2];
    double f2;
    a3_energy(S, y, &f2, g2, NULL);
    double err = 0, gn = 0;
    for (int v = 0; v < S->nv; v++)
        for (int c = 0; c < 3; c++) {
            const double rg = R[3 * c] * g[3 * v] + R[3 * c + 1] * g[3 * v + 1] + R[3 * c + 2] * g[3 * v + 2];
            err = fmax(err, fabs(rg - g2[3 * v + c]));
            gn = fmax(gn, fabs(rg));
        }
    CHECK_REL(f2, f, 1e-10);
    CHECK_MSG(err <= 1e-10 * gn, "objectivity: |g(Rx) - R g(x)| %g (|g| %g)", err, gn);
    free(x); free(g); free(y); free(g2);
    a3m_free(&m);
}

SB_TEST(test_voronoi_mass)
{
    /* acute: Eq. 1 is the circumcentric split; the corner areas sum to the area */
    const double A0[3] = { 0, 0, 0 }, B0[3] = { 1, 0, 0 }, C0[3] = { 0.4, 0.8, 0 };
    double A[3];
    a3_voronoi(A0, B0, C0, A);
    CHECK_NEAR(A[0] + A[1] + A[2], 0.4, 1e-15);
    /* equilateral: a third each */
    const double E2[3] = { 0.5, sqrt(0.75), 0 };
    a3_voronoi(A0, B0, E2, A);
    for (int i = 0; i < 3; i++) CHECK_NEAR(A[i], sqrt(0.75) / 6, 1e-15);
    /* obtuse at C: Alg. 1 gives it half, the others a quarter */
    const double C1[3] = { 0.5, 0.1, 0 };
    a3_voronoi(A0, B0, C1, A);
    CHECK_NEAR(A[2], 0.025, 1e-15);
    CHECK_NEAR(A[0], 0.0125, 1e-15);
    CHECK_NEAR(A[1], 0.0125, 1e-15);
    /* the method: total mass rho * area on every mesh pattern */
    char js[2048];
    scene_json(js, sizeof js, "plane", "stvk", 0, "", "", 1, "");
    for (int p = 0; p < 3; p++) {
        char set[64];
        snprintf(set, sizeof set, "method.mesh=%s", p == 0 ? "alternate" : p == 1 ? "regular" : "crossed");
        const char *sets[] = { set, NULL };
        a3m m;
        CHECK(a3m_create(&m, js, 5, sets) == SB_OK);
        if (!m.S) continue;
        double tot = 0;
        for (int v = 0; v < m.S->nv; v++) {
            tot += m.S->mass[v];
            CHECK(m.S->mass[v] > 0);
        }
        CHECK_REL(tot, 0.1 * 0.8, 1e-13);
        a3m_free(&m);
    }
}

/* Cylindrical bending across grid-aligned edges: E_b = (D/2) kappa^2 times
 * the area around interior bending edges (the calibration k_b = D/3, a3.h). */
SB_TEST(test_bending_cylinder)
{
    char js[2048];
    scene_json(js, sizeof js, "plane", "stvk", 0, "", "", 1, "");
    const char *sets[] = { "method.mesh=regular", NULL };
    a3m m;
    const int N = 8;
    CHECK(a3m_create(&m, js, N, sets) == SB_OK);
    if (!m.S) return;
    a3_state *S = m.S;
    const double kappa = 0.05, Rr = 1.0 / kappa, D = 1e6 * 1e-9 / (12 * (1 - 0.33 * 0.33));
    double *x = malloc(sizeof(double) * S->n_dofs);
    for (int v = 0; v < S->nv; v++) {
        const double X = S->x_ref[3 * v], Y = S->x_ref[3 * v + 1];
        x[3 * v] = Rr * sin(X / Rr);
        x[3 * v + 1] = Y;
        x[3 * v + 2] = Rr * (1 - cos(X / Rr));
    }
    double Eb = 0;
    for (int k = 0; k < S->n_edge; k++) {
        double q[12];
        for (int i = 0; i < 4; i++) memcpy(q + 3 * i, x + 3 * S->edge[k].v[i], 3 * sizeof(double));
        Eb += a3_bend(&S->edge[k], q, NULL, NULL);
    }
    /* interior edges along t bend (N - 1 columns of N edges), each owning h_s h_t */
    const double hs = 1.0 / N, ht = 0.8 / N, expect = 0.5 * D * kappa * kappa * (N - 1) * N * hs * ht;
    printf("    cylinder kappa %g: E_b %.6e, (D/2) kappa^2 A_interior %.6e\n", kappa, Eb, expect);
    CHECK_REL(Eb, expect, 2e-3);
    free(x);
    a3m_free(&m);
}

/* denim: the small-strain tangent of the RMTR paper's law (a3_method.c) */
SB_TEST(test_denim_tangent)
{
    char js[2048];
    scene_json(js, sizeof js, "plane", "denim", 0, "", "", 1, "");
    a3m m;
    CHECK(a3m_create(&m, js, 2, NULL) == SB_OK);
    if (!m.S) return;
    const double h = m.scene.material.thickness, *k = m.scene.material.denim.k;
    CHECK_REL(m.S->C[0], h * k[0], 1e-15);
    CHECK_REL(m.S->C[1], h * k[1], 1e-15);
    CHECK_REL(m.S->C[3], h * k[1], 1e-15);
    CHECK_REL(m.S->C[4], h * k[2], 1e-15);
    CHECK_REL(m.S->C[8], 2 * h * k[3], 1e-15);
    /* against the shared material law: psi(E) h = 1/2 E^T C E for a small strain */
    sb_material mat;
    CHECK(sb_material_init(&mat, &m.scene.material, 0) == SB_OK);
    const double E[3] = { 1e-7, -0.6e-7, 0.4e-7 };
    const double lin = 0.5 * (m.S->C[0] * E[0] * E[0] + 2 * m.S->C[1] * E[0] * E[1] + m.S->C[4] * E[1] * E[1] +
                              m.S->C[8] * E[2] * E[2]);
    const double psi = h * sb_material_psi(&mat, E, NULL, NULL);
    CHECK_REL(psi, lin, 1e-5);
    a3m_free(&m);
}

SB_TEST(test_refusals)
{
    static const struct { const char *chart, *mat, *loads, *bcs; } bad[] = {
        { "cylinder", "stvk", "", "" },
        { "plane", "stvk", "", "{\"type\": \"clamped\", \"on\": [\"left\"]}" },
        { "plane", "stvk", "", "{\"type\": \"symmetry\", \"on\": [\"bottom\"], \"normal\": \"y\"}" },
        { "plane", "stvk", "{\"type\": \"pressure\", \"pressure\": 1}", "" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char js[2048];
        scene_json(js, sizeof js, bad[i].chart, bad[i].mat, 0, bad[i].loads, bad[i].bcs, 1, "");
        a3m m;
        const int rc = a3m_create(&m, js, 4, NULL);
        CHECK_MSG(rc == SB_ERR_UNSUPPORTED, "case %zu: status %d, expected a refusal", i, rc);
        a3m_free(&m);
    }
}

/* A free sheet under gravity, through `shellbench run` with the linearized
 * solver: the corotational forces of a rigid translation vanish, so the
 * linear implicit Euler gives x_n = n (n + 1) / 2 dt^2 g exactly; an
 * undamped pendulum-free check of the time integrator, mass and loads. */
SB_TEST(test_free_fall_run)
{
    char js[2048], path[256];
    scene_json(js, sizeof js, "plane", "stvk", 0, "{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]}", "", 6,
               "{\"name\": \"p\", \"at\": [0.3, 0.2]}");
    snprintf(path, sizeof path, "/tmp/sb_test_a3_fall_%d.json", (int)getpid());
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (!fp) return;
    fputs(js, fp);
    fclose(fp);
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = path;
    rq.method = "adaptive_sqrt3";
    rq.solver = "linearized";
    rq.res = 4;
    rq.out = "none";
    rq.quiet = 1;
    int code = -1;
    json_t *o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 0);
    if (o) {
        json_t *d = json_object_get(json_object_get(json_object_get(o, "probes"), "p"), "displacement");
        const double z = json_number_value(json_array_get(d, 2)), dt = 0.005, expect = -9.81 * dt * dt * 6 * 7 / 2;
        CHECK_REL(z, expect, 1e-9);
        CHECK(fabs(json_number_value(json_array_get(d, 0))) < 1e-12);
        json_decref(o);
    }
    /* a potential-based solver is refused before any work (exit 2) */
    rq.solver = "lsnewton";
    o = sb_test_run_json(&rq, &code);
    CHECK_EQ_INT(code, 2);
    if (o) json_decref(o);
    remove(path);
}

/* The linearized step by CHOLMOD and by preconditioned CG (the paper's
 * solver) on a hanging sheet: the same states to the CG tolerance, and CG
 * iterations counted. */
SB_TEST(test_pcg_matches_cholmod)
{
    char js[2048], path[256];
    scene_json(js, sizeof js, "plane", "stvk", 0.3, "{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]}",
               "{\"type\": \"fixed\", \"on\": [\"top\"]}", 8, "{\"name\": \"p\", \"at\": [0.3, 0]}");
    snprintf(path, sizeof path, "/tmp/sb_test_a3_pcg_%d.json", (int)getpid());
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (!fp) return;
    fputs(js, fp);
    fclose(fp);
    double z[2][3] = { { 0 } };
    long cg = -1;
    for (int k = 0; k < 2; k++) {
        const char *sets[] = { k ? "solver.linear=pcg" : "solver.linear=cholmod", "method.Ey_ratio=1.5", NULL };
        sb_run_request rq;
        memset(&rq, 0, sizeof rq);
        rq.scene = path;
        rq.method = "adaptive_sqrt3";
        rq.solver = "linearized";
        rq.res = 6;
        rq.out = "none";
        rq.quiet = 1;
        rq.n_sets = 2;
        rq.sets = sets;
        int code = -1;
        json_t *o = sb_test_run_json(&rq, &code);
        CHECK_EQ_INT(code, 0);
        if (!o) continue;
        json_t *d = json_object_get(json_object_get(json_object_get(o, "probes"), "p"), "displacement");
        for (int c = 0; c < 3; c++) z[k][c] = json_number_value(json_array_get(d, c));
        if (k) cg = (long)json_integer_value(json_object_get(json_object_get(o, "counts"), "cg_iter"));
        json_decref(o);
    }
    CHECK(fabs(z[0][2]) > 1e-3);
    for (int c = 0; c < 3; c++) CHECK_NEAR(z[1][c], z[0][c], 1e-8 * fabs(z[0][2]));
    CHECK(cg > 8);
    remove(path);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_membrane_frozen_fd),
        SB_CASE(test_corotational_not_a_potential),
        SB_CASE(test_bending_fd),
        SB_CASE(test_rigid_motion),
        SB_CASE(test_voronoi_mass),
        SB_CASE(test_bending_cylinder),
        SB_CASE(test_denim_tangent),
        SB_CASE(test_refusals),
        SB_CASE(test_free_fall_run),
        SB_CASE(test_pcg_matches_cholmod),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
