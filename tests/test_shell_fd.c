/* test_shell_fd.c — finite-difference verification of the Kirchhoff–Love
 * kernel (sb_shell.c): gradient and exact Hessian for StVK and denim, random
 * deformed states, four bases (bicubic B-spline, bicubic Hermite, Taylor jet,
 * random weights with k = 40 and k = SB_SHELL_MAX_BASIS), central differences
 * over four step sizes h0 4^-s with the O(h^2) error decay asserted (>= 8x per
 * step until the roundoff floor), and the smallest-step error below 1e-5. */
#include "sb_test.h"
#include "test_shell_bases.h"

#include <stdlib.h>

typedef struct fd_case {
    sb_material m;
    int npts;                        /* quadrature points of the "element" */
    tb_basis b[4];
    sb_shell_ref r[4];
    sb_hess_kind kind;
    sb_shell_work *w;
} fd_case;

static double elem_energy(const fd_case *c, const double *q, double *g, double *H)
{
    double e = 0;
    for (int p = 0; p < c->npts; p++) {
        sb_shell_basis v = tb_view(&c->b[p]);
        e += sb_shell_energy(&c->m, &c->r[p], &v, q, g, H, c->kind, c->w);
    }
    return e;
}

/* relative FD errors of gradient (from energies) and Hessian (from gradients) */
static void fd_err(const fd_case *c, const double *q, double h, double *eg, double *eh)
{
    const int n = 3 * c->b[0].k;
    double *x = malloc(sizeof(double) * n), *g = calloc(n, sizeof(double));
    double *H = calloc((size_t)n * n, sizeof(double));
    double *gp = malloc(sizeof(double) * n), *gm = malloc(sizeof(double) * n);
    memcpy(x, q, sizeof(double) * n);
    elem_energy(c, q, g, H);
    double gmax = 0, hmax = 0, ge = 0, he = 0;
    for (int i = 0; i < n; i++) gmax = fmax(gmax, fabs(g[i]));
    for (int i = 0; i < n * n; i++) hmax = fmax(hmax, fabs(H[i]));
    for (int j = 0; j < n; j++) {
        memset(gp, 0, sizeof(double) * n);
        memset(gm, 0, sizeof(double) * n);
        x[j] = q[j] + h;
        const double fp = elem_energy(c, x, gp, NULL);
        x[j] = q[j] - h;
        const double fm = elem_energy(c, x, gm, NULL);
        x[j] = q[j];
        ge = fmax(ge, fabs((fp - fm) / (2 * h) - g[j]));
        for (int i = 0; i < n; i++) he = fmax(he, fabs((gp[i] - gm[i]) / (2 * h) - H[(size_t)i * n + j]));
    }
    *eg = ge / gmax;
    *eh = he / hmax;
    free(x);
    free(g);
    free(H);
    free(gp);
    free(gm);
}

static void check_case(sb_test_state *T, const fd_case *c, const double *q, double h0, const char *what)
{
    double eg[4], eh[4];
    for (int s = 0; s < 4; s++) fd_err(c, q, h0 / pow(4.0, s), &eg[s], &eh[s]);
    for (int s = 0; s < 3; s++) {
        CHECK_MSG(eg[s + 1] <= eg[s] / 8 || eg[s + 1] < 1e-9, "%s: gradient FD error %.3g -> %.3g", what,
                  eg[s], eg[s + 1]);
        CHECK_MSG(eh[s + 1] <= eh[s] / 8 || eh[s + 1] < 1e-9, "%s: Hessian FD error %.3g -> %.3g", what,
                  eh[s], eh[s + 1]);
    }
    CHECK_MSG(eg[3] < 1e-5 && eh[3] < 1e-5, "%s: FD errors %.3g %.3g", what, eg[3], eh[3]);
    if (getenv("SB_VERBOSE"))
        printf("    %s: grad err %.2e %.2e %.2e %.2e, hess err %.2e %.2e %.2e %.2e\n", what, eg[0], eg[1], eg[2],
               eg[3], eh[0], eh[1], eh[2], eh[3]);
}

/* reference surfaces */
static void href_map(double u, double v, double x[3], double xu[3], double xv[3], double xuv[3])
{
    /* skewed, doubly curved patch: x = (0.5u + 0.1v, 0.4v, 0.1u^2 - 0.05v^2 + 0.03uv) */
    x[0] = 0.5 * u + 0.1 * v;   x[1] = 0.4 * v; x[2] = 0.1 * u * u - 0.05 * v * v + 0.03 * u * v;
    xu[0] = 0.5;                xu[1] = 0;      xu[2] = 0.2 * u + 0.03 * v;
    xv[0] = 0.1;                xv[1] = 0.4;    xv[2] = -0.1 * v + 0.03 * u;
    xuv[0] = 0;                 xuv[1] = 0;     xuv[2] = 0.03;
}

enum { B_BSPLINE, B_HERMITE, B_TAYLOR, B_RANDOM40, B_RANDOMMAX };
static const char *bname[] = { "bspline", "hermite", "taylor", "random40", "random64" };

/* builds the case and the reference control values Xq; returns k */
static int setup(fd_case *c, int basis, double *Xq, unsigned long long *s)
{
    static const double pts[4][2] = { { 0.21, 0.33 }, { 0.78, 0.15 }, { 0.4, 0.81 }, { 0.9, 0.6 } };
    int k = 0;
    c->npts = basis >= B_TAYLOR ? 1 : 4;
    for (int p = 0; p < c->npts; p++) {
        switch (basis) {
        case B_BSPLINE: tb_bspline(&c->b[p], pts[p][0], pts[p][1]); break;
        case B_HERMITE: tb_hermite(&c->b[p], pts[p][0], pts[p][1]); break;
        case B_TAYLOR: tb_taylor(&c->b[p]); break;
        case B_RANDOM40: tb_random(&c->b[p], 40, s); break;
        default: tb_random(&c->b[p], SB_SHELL_MAX_BASIS, s); break;
        }
    }
    k = c->b[0].k;
    switch (basis) {
    case B_BSPLINE:
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++) {
                double *X = Xq + 3 * (i + 4 * j);
                X[0] = 0.4 * i + 0.05 * j;
                X[1] = 0.35 * j;
                X[2] = 0.06 * sin(1.3 * i) * cos(0.7 * j);
            }
        break;
    case B_HERMITE: tb_hermite_dofs(href_map, Xq); break;
    case B_TAYLOR: {
        double y[6][3] = { { 0, 0, 0 }, { 0.5, 0.05, 0.1 }, { -0.1, 0.45, 0.05 },
                           { 0.1, -0.2, 0.8 }, { 0.0, 0.1, -0.3 }, { 0.2, 0.0, 0.5 } };
        memcpy(Xq, y, sizeof y);
        break;
    }
    default:
        for (int i = 0; i < 3 * k; i++) Xq[i] = tb_rand(s, -1, 1);
        break;
    }
    for (int p = 0; p < c->npts; p++) {
        sb_shell_basis v = tb_view(&c->b[p]);
        sb_shell_ref_init_basis(&c->r[p], &v, Xq, 0.35, 0.25);
    }
    return k;
}

static void run_fd(sb_test_state *T, sb_material_kind mk, double thickness, double amp, int nstates)
{
    unsigned long long s = 12345 + (unsigned)mk * 77 + (unsigned long long)(thickness * 1000);
    for (int basis = B_BSPLINE; basis <= B_RANDOMMAX; basis++) {
        fd_case c;
        memset(&c, 0, sizeof c);
        sb_material_spec sp;
        if (mk == SB_MAT_DENIM) {
            sb_material_spec_denim(&sp);
        } else {
            memset(&sp, 0, sizeof sp);
            sp.kind = SB_MAT_STVK;
            sp.young = 1.0e6;
            sp.poisson = 0.3;
        }
        sp.thickness = thickness;
        sp.density = 1.0;
        CHECK_EQ_INT(sb_material_init(&c.m, &sp, 0), SB_OK);
        c.kind = SB_HESS_EXACT;
        c.w = sb_shell_work_new();
        double Xq[3 * SB_SHELL_MAX_BASIS], q[3 * SB_SHELL_MAX_BASIS];
        const int k = setup(&c, basis, Xq, &s);
        for (int p = 0; p < c.npts; p++) CHECK(isfinite(c.r[p].dA) && c.r[p].dA > 0);
        /* random basis: the control values are not a surface; keep them small */
        const double a = basis >= B_RANDOM40 ? 0.3 * amp : amp;
        for (int st = 0; st < (basis == B_RANDOMMAX ? 1 : nstates); st++) {
            double R[9], ax[3] = { tb_rand(&s, -1, 1), tb_rand(&s, -1, 1), tb_rand(&s, -1, 1) }, t0[3] = { 0.1, -0.2, 0.3 };
            const double nrm = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
            for (int i = 0; i < 3; i++) ax[i] /= nrm;
            tb_rotation(ax, tb_rand(&s, -3, 3), R);
            for (int i = 0; i < 3 * k; i++) q[i] = Xq[i] + a * tb_rand(&s, -1, 1);
            /* a rigid translation moves positions only: Hermite and Taylor control values
             * include derivatives, so only the B-spline (partition of unity) is translated */
            if (basis != B_BSPLINE) t0[0] = t0[1] = t0[2] = 0.0;
            tb_apply(R, t0, q, q, k);
            char what[96];
            snprintf(what, sizeof what, "%s %s h=%g state %d", mk == SB_MAT_DENIM ? "denim" : "stvk",
                     bname[basis], thickness, st);
            check_case(T, &c, q, 1e-3, what);
        }
        sb_shell_work_free(c.w);
    }
}

/* thick StVK: bending and membrane of the same order, so both are verified */
SB_TEST(fd_stvk_thick) { run_fd(T, SB_MAT_STVK, 0.8, 0.08, 2); }
/* thin StVK: the membrane dominated regime */
SB_TEST(fd_stvk_thin) { run_fd(T, SB_MAT_STVK, 0.01, 0.08, 1); }
/* denim, default 6 thickness points, thick enough for bending to show */
SB_TEST(fd_denim) { run_fd(T, SB_MAT_DENIM, 0.05, 0.03, 2); }

/* bending alone: a flat reference bent isometrically has (nearly) no membrane
 * strain, so the energy and its derivatives are bending-dominated even for a
 * thin shell.  Taylor basis, x = cylinder jet plus small random perturbation. */
SB_TEST(fd_bending_dominated)
{
    unsigned long long s = 99;
    for (int mk = 0; mk < 2; mk++) {
        fd_case c;
        memset(&c, 0, sizeof c);
        sb_material_spec sp;
        if (mk) {
            sb_material_spec_denim(&sp);
        } else {
            memset(&sp, 0, sizeof sp);
            sp.kind = SB_MAT_STVK;
            sp.young = 1e6;
            sp.poisson = 0.25;
            sp.thickness = 1e-3;
        }
        sb_material_init(&c.m, &sp, 0);
        c.npts = 1;
        c.kind = SB_HESS_EXACT;
        c.w = sb_shell_work_new();
        tb_taylor(&c.b[0]);
        const double X[18] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
        sb_shell_basis v = tb_view(&c.b[0]);
        sb_shell_ref_init_basis(&c.r[0], &v, X, 0.2, 1.0);
        /* cylinder of radius 0.1 about e2: x1 = e1, x11 = e3 / R */
        double q[18] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 10.0, 0, 0, 0, 0, 0, 0 };
        for (int i = 9; i < 18; i++) q[i] += tb_rand(&s, -1, 1);
        check_case(T, &c, q, 1e-4, mk ? "denim bending" : "stvk bending");
        sb_shell_work_free(c.w);
    }
}

/* pseudo Hessian: equals the exact one without bending stress, differs and
 * stays symmetric with it; PSD kind in the kernel is the exact Hessian */
SB_TEST(pseudo_and_psd_kinds)
{
    fd_case c;
    memset(&c, 0, sizeof c);
    sb_material_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.kind = SB_MAT_STVK;
    sp.young = 1e6;
    sp.poisson = 0.3;
    sp.thickness = 0.05;
    sb_material_init(&c.m, &sp, 0);
    c.w = sb_shell_work_new();
    unsigned long long s = 5;
    double Xq[48], q[48];
    /* flat B-spline reference, in-plane deformation: B = 0 */
    tb_bspline(&c.b[0], 0.3, 0.6);
    c.npts = 1;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            Xq[3 * (i + 4 * j)] = 0.3 * i;
            Xq[3 * (i + 4 * j) + 1] = 0.3 * j;
            Xq[3 * (i + 4 * j) + 2] = 0;
        }
    sb_shell_basis v = tb_view(&c.b[0]);
    sb_shell_ref_init_basis(&c.r[0], &v, Xq, 0.0, 1.0);
    for (int i = 0; i < 48; i++) q[i] = Xq[i] + (i % 3 == 2 ? 0 : 0.03 * tb_rand(&s, -1, 1));
    double He[48 * 48] = { 0 }, Hp[48 * 48] = { 0 }, Hs[48 * 48] = { 0 };
    sb_shell_energy(&c.m, &c.r[0], &v, q, NULL, He, SB_HESS_EXACT, c.w);
    sb_shell_energy(&c.m, &c.r[0], &v, q, NULL, Hp, SB_HESS_PSEUDO, c.w);
    sb_shell_energy(&c.m, &c.r[0], &v, q, NULL, Hs, SB_HESS_PSD, c.w);
    double d = 0, mx = 0;
    for (int i = 0; i < 48 * 48; i++) {
        d = fmax(d, fabs(He[i] - Hp[i]));
        mx = fmax(mx, fabs(He[i]));
    }
    CHECK(d <= 1e-14 * mx);
    CHECK(memcmp(He, Hs, sizeof He) == 0);
    /* out of plane: bending stress, the pseudo Hessian drops its 2nd-derivative term */
    for (int i = 0; i < 48; i++) q[i] = Xq[i] + 0.05 * tb_rand(&s, -1, 1);
    memset(He, 0, sizeof He);
    memset(Hp, 0, sizeof Hp);
    sb_shell_energy(&c.m, &c.r[0], &v, q, NULL, He, SB_HESS_EXACT, c.w);
    sb_shell_energy(&c.m, &c.r[0], &v, q, NULL, Hp, SB_HESS_PSEUDO, c.w);
    d = 0;
    mx = 0;
    double asym = 0;
    for (int i = 0; i < 48; i++)
        for (int j = 0; j < 48; j++) {
            d = fmax(d, fabs(He[48 * i + j] - Hp[48 * i + j]));
            mx = fmax(mx, fabs(He[48 * i + j]));
            asym = fmax(asym, fabs(Hp[48 * i + j] - Hp[48 * j + i]));
            asym = fmax(asym, fabs(He[48 * i + j] - He[48 * j + i]));
        }
    CHECK(d > 1e-8 * mx);
    CHECK(asym == 0.0);
    sb_shell_work_free(c.w);
}

static const sb_test_case cases[] = {
    SB_CASE(fd_stvk_thick),
    SB_CASE(fd_stvk_thin),
    SB_CASE(fd_denim),
    SB_CASE(fd_bending_dominated),
    SB_CASE(pseudo_and_psd_kinds),
    SB_END
};

int main(int argc, char **argv)
{
    return sb_test_main(argc, argv, cases);
}
