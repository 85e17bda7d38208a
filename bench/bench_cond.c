/* bench_cond.c — condition number of the Hessian against dofs (RMTR paper
 * Fig. 9 left): trampoline, subdivision method, dt = 1, the Hessian of the
 * incremental potential at the converged first step.  lambda_max by power
 * iteration on H, lambda_min by inverse power iteration with the CHOLMOD
 * factor (H is positive definite at a minimizer; a failed factorization is
 * reported as indefinite).
 *
 *   bench_cond [SCENE] [MAX_RES]          cond against dofs (default trampoline, 32)
 *   bench_cond SCENE RES sigma            cond against the penalty exponent
 *                                         sigma = 3..7 at one resolution (Fig. 9 right)
 *   bench_cond parts SCENE RES [KEY=VAL ...] [trace]
 *                                         issue 43: the 2-norm condition number of H
 *                                         and of its parts, one CSV line per matrix
 *                                         (see bench_cond_parts below)
 *
 * The first two modes are kept as they made results/rmtr/cond*.md (power
 * and inverse iteration: estimates from inside the spectrum).  `parts`
 * measures it properly: exact eigenvalues by LAPACK at small sizes, Lanczos
 * with residual bounds above. */
#include "bench_rmtr_setup.h"
#include "sb_context.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double rayleigh_power(sb_problem *p, int F, int n, int inverse, int iters, double *v, double *w)
{
    double lam = 0;
    for (int i = 0; i < n; i++) v[i] = 1.0 + 0.1 * sin(1.7 * i);   /* deterministic start */
    sb_scal(n, 1.0 / sb_norm2(n, v), v);
    for (int k = 0; k < iters; k++) {
        if (inverse) {
            if (sb_problem_solve(p, F, v, w) != SB_OK) return NAN;
        } else {
            sb_problem_hess_mult(p, F, v, w);
        }
        double nw = sb_norm2(n, w);
        if (!(nw > 0)) return NAN;
        lam = sb_dot(n, v, w);                          /* Rayleigh quotient of H or H^{-1} */
        sb_copy(n, w, v);
        sb_scal(n, 1.0 / nw, v);
    }
    return inverse ? 1.0 / lam : lam;
}

/* cond(H) of SCENE at resolution res and penalty exponent sigma; 0 or an exit code */
static int measure(const char *scene_name, int res, double sigma, int *n_out, double *lmin_out, double *lmax_out,
                   int *conv)
{
    sb_context ctx;
    sb_context_init(&ctx);
    sb_scene sc;
    if (bench_load_scene("bench_cond", scene_name, &sc)) return 2;
    const sb_method_type *mt = sb_method_find("rmtr");
    const sb_solver_type *st = sb_solver_find("lsnewton");
    bench_add_params(&ctx, mt, st);
    char set[64], perr[256];
    snprintf(set, sizeof set, "method.sigma=%g", sigma);
    /* the stopping rule results/rmtr/cond*.md were computed with (docs/trust.md) */
    if (sb_paramset_set(&ctx.params, "run.stop=paper", perr, sizeof perr) ||
        sb_paramset_set(&ctx.params, set, perr, sizeof perr)) {
        fprintf(stderr, "bench_cond: %s\n", perr);
        return 2;
    }
    void *ms = calloc(1, mt->state_size), *ss = calloc(1, st->state_size);
    sb_method_config cfg = { res, 1, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    if (mt->create(ms, &sc, &cfg) || sb_problem_create(&ctx, mt, ms, &sc, &p) || st->alloc(ss, p, &ctx.params)) {
        fprintf(stderr, "bench_cond: set-up failed: %s\n", ctx.err);
        return 3;
    }
    int n = sb_problem_n(p, 0);
    double *x = malloc(n * sizeof(double)), *x0 = malloc(n * sizeof(double)), *v0 = calloc(n, sizeof(double));
    double *v = malloc(n * sizeof(double)), *w = malloc(n * sizeof(double)), *g = malloc(n * sizeof(double));
    mt->initial(ms, 0, x);
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1; si.n_steps = sc.time.steps; si.dt = sc.time.dt; si.t = sc.time.dt;
    for (int i = 0; i < sc.n_loads; i++) si.load_factor[i] = sb_load_factor(&sc, &sc.loads[i], 1);
    for (int i = 0; i < sc.n_bcs; i++) si.motion_factor[i] = sb_bc_motion_factor(&sc, &sc.bcs[i], 1);
    sb_problem_begin_step(p, &si, x, v0, x0);
    int it; double f, gn;
    sb_reason why = sb_solve_step(st, ss, p, &ctx.params, 1, x0, &it, &f, &gn);
    sb_problem_eval(p, 0, x0, &f, g, sb_problem_hessian(p, 0));
    double lmax = rayleigh_power(p, 0, n, 0, 300, v, w), lmin = NAN;
    if (sb_problem_factor(p, 0, 0.0) == SB_OK) lmin = rayleigh_power(p, 0, n, 1, 100, v, w);
    *lmin_out = lmin; *lmax_out = lmax; *n_out = n; *conv = sb_reason_converged(why);
    fflush(stdout);
    free(x); free(x0); free(v0); free(v); free(w); free(g);
    st->free(ss);
    free(ss);
    sb_problem_free(p);
    mt->destroy(ms);
    free(ms);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
    return 0;
}

static int bench_cond_parts(int argc, char **argv);

int main(int argc, char **argv)
{
    if (argc > 1 && !strcmp(argv[1], "parts")) return bench_cond_parts(argc - 1, argv + 1);
    const char *scene_name = argc > 1 ? argv[1] : "trampoline";
    int max_res = argc > 2 ? atoi(argv[2]) : 32;
    int n, conv, rc;
    double lmin, lmax;
    if (argc > 3 && !strcmp(argv[3], "sigma")) {
        printf("| sigma | dofs | lambda_min | lambda_max | cond(H) |\n|--:|--:|--:|--:|--:|\n");
        for (int k = 3; k <= 7; k++) {
            if ((rc = measure(scene_name, max_res, k, &n, &lmin, &lmax, &conv))) return rc;
            printf("| %d | %d | %.3g | %.3g | %.2g%s |\n", k, n, lmin, lmax, lmax / lmin, conv ? "" : " (step not converged)");
            fflush(stdout);
        }
        return 0;
    }
    static const double paper[] = { 1e8, 1e9, 1e10, 1e11, 1e12, 1e13 };
    printf("| dofs | lambda_min | lambda_max | cond(H) | paper (Fig. 9) |\n|--:|--:|--:|--:|--:|\n");
    for (int res = 4, k = 0; res <= max_res; res *= 2, k++) {
        if ((rc = measure(scene_name, res, 5.0, &n, &lmin, &lmax, &conv))) return rc;
        printf("| %d | %.3g | %.3g | %.2g%s | %.0e |\n", n, lmin, lmax, lmax / lmin,
               conv ? "" : " (step not converged)", k < 6 ? paper[k] : NAN);
        fflush(stdout);
    }
    return 0;
}

/* ---- bench_cond parts: the condition number of H and of its parts (issue 43) ----
 *
 * At the converged first step of SCENE at RES elements per side (lsnewton,
 * the paper's stopping rule), the Hessian of the incremental potential
 *     H = M/dt^2 + K_el + K_pen        (DESIGN.md; RMTR paper (3.2), (3.6))
 * with M the consistent mass, K_el the Hessian of the shell energy (denim,
 * Eq. 3.3-3.4, plus the linear gravity term, whose Hessian is 0) and K_pen
 * the Hessian of the boundary penalty beta/2 ||x - b||^2 (Eq. 3.6, beta =
 * h^-sigma).  K_pen is found as K(beta) - K(beta = 0): a second copy of the
 * method with method.beta_scale = 0 evaluated at the same x.  Every matrix
 * is measured in the 2-norm, cond_2 = lambda_max / lambda_min (symmetric):
 *   n <= dense_max: every eigenvalue by LAPACK dsyevd (exact to round-off),
 *                   and cond_1 = ||A||_1 ||A^-1||_1 by Cholesky + inverse;
 *   above:          Lanczos with full reorthogonalization, lambda_max on A,
 *                   lambda_min on A^-1 through the CHOLMOD factor
 *                   (shift-invert), each Ritz value with its residual bound.
 * Output: one CSV line per matrix; `trace` adds the Lanczos convergence
 * history of H as comment lines ("# trace ...").
 *
 *   bench_cond parts SCENE RES [method.K=V | solver.K=V | run.K=V ...]
 *              [tag=NAME] [dense_max=N] [lanczos=KMAX] [both] [trace] [modes] [only=MATRIX] [split]
 *              [state=initial] [header]
 *   split: also K_mem and K_bend (rows) and the terms' shares of H's extreme eigenvalues ("# split", below) */
#include "sb_eigen.h"

typedef struct cond_op { sb_matrix *A; sb_problem *p; } cond_op;

static int op_mult(void *c, const double *x, double *y)
{
    sb_matrix_symv(((cond_op *)c)->A, x, y);
    return SB_OK;
}

static int op_solve(void *c, const double *x, double *y)
{
    return sb_problem_solve(((cond_op *)c)->p, 0, x, y);
}

/* the n x n full column-major copy of a symmetric pattern matrix (upper CSC) */
static double *dense_of(const sb_matrix *A)
{
    const sb_pattern *P = A->pat;
    const int n = P->n;
    double *D = calloc((size_t)n * n, sizeof *D);
    if (!D) return NULL;
    for (int j = 0; j < n; j++)
        for (long q = P->colptr[j]; q < P->colptr[j + 1]; q++) {
            int i = P->rowind[q];
            D[i + (size_t)j * n] = A->val[q];
            D[j + (size_t)i * n] = A->val[q];
        }
    return D;
}

typedef struct cond_row {
    double lmin, lmax, cond1, rel_min, rel_max;
    int steps_min, steps_max, dense;
} cond_row;

static void measure_dense(const sb_matrix *A, cond_row *r)
{
    const int n = A->pat->n;
    double *D = dense_of(A), *w = malloc((size_t)n * sizeof *w);
    r->dense = 1;
    r->lmin = r->lmax = r->cond1 = NAN;
    if (D && w && sb_eig_dense_sym(n, D, w) == SB_OK) {
        r->lmin = w[0];
        r->lmax = w[n - 1];
    }
    free(D);
    D = dense_of(A);
    if (D && r->lmin > 0) r->cond1 = sb_cond1_dense_spd(n, D);
    free(D);
    free(w);
}

/* Lanczos: lambda_max on A; lambda_min on A^-1 when A factors (positive
 * definite), else the smallest Ritz value of A itself (then an estimate
 * from inside the spectrum, flagged by its residual) */
static void measure_lanczos(sb_problem *p, sb_matrix *A, int kmax, cond_row *r, FILE *trace, const char *name)
{
    const int n = A->pat->n;
    cond_op c = { A, p };
    double *h[8];
    for (int i = 0; i < 8; i++) h[i] = calloc((size_t)kmax, sizeof(double));
    sb_lanczos_result a = { .hist_theta_max = h[0], .hist_res_max = h[1], .hist_theta_min = h[2], .hist_res_min = h[3] };
    sb_lanczos_result b = { .hist_theta_max = h[4], .hist_res_max = h[5], .hist_theta_min = h[6], .hist_res_min = h[7] };
    r->dense = 0;
    r->cond1 = NAN;
    r->lmax = r->lmin = NAN;
    if (sb_lanczos_extreme(n, op_mult, &c, kmax, 1e-10, NULL, &a) == SB_OK) {
        r->lmax = a.theta_max;
        r->rel_max = a.res_max / fabs(a.theta_max);
        r->steps_max = a.steps;
    }
    sb_matrix *H = sb_problem_hessian(p, 0);
    memcpy(H->val, A->val, (size_t)A->pat->nnz * sizeof *H->val);
    if (sb_problem_factor(p, 0, 0.0) == SB_OK &&
        sb_lanczos_extreme(n, op_solve, &c, kmax, 1e-10, NULL, &b) == SB_OK && b.theta_max > 0) {
        r->lmin = 1.0 / b.theta_max;                       /* 1 / largest eigenvalue of A^-1 */
        r->rel_min = b.res_max / b.theta_max;              /* relative, same for lambda and 1/lambda to first order */
        r->steps_min = b.steps;
    } else {
        r->lmin = a.theta_min;                             /* not positive definite */
        r->rel_min = a.res_min / fmax(fabs(a.theta_min), 1e-300);
        r->steps_min = -a.steps;
    }
    if (trace) {
        for (int k = 0; k < a.steps || k < b.steps; k++)
            fprintf(trace, "# trace,%s,%d,%.10g,%.3g,%.10g,%.3g\n", name, k + 1,
                    k < a.steps ? h[0][k] : NAN, k < a.steps ? h[1][k] / fabs(h[0][k]) : NAN,
                    k < b.steps && h[4][k] > 0 ? 1.0 / h[4][k] : NAN,
                    k < b.steps && h[4][k] > 0 ? h[5][k] / h[4][k] : NAN);
    }
    for (int i = 0; i < 8; i++) free(h[i]);
}

/* Where the extreme eigenvectors of H live: the share of |v|^2 on ghost
 * control points (reference position outside the domain [0,a] x [0,b]),
 * and on the out-of-plane (z) components.  Printed as comment lines. */
static void describe_modes(const sb_matrix *A, const double *X, double a, double b)
{
    const int n = A->pat->n;
    double *D = dense_of(A), *w = malloc((size_t)n * sizeof *w);
    if (D && w && sb_eig_dense_sym_vec(n, D, w) == SB_OK) {
        const int which[4] = { 0, 1, 2, n - 1 };
        for (int k = 0; k < 4; k++) {
            const double *v = D + (size_t)which[k] * n;
            double ghost = 0, z = 0, corner = 0;
            for (int i = 0; i < n / 3; i++) {
                double x = X[3 * i], y = X[3 * i + 1], e = 1e-9;
                double m = v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2];
                int ox = x < -e || x > a + e, oy = y < -e || y > b + e;
                if (ox || oy) ghost += m;
                if (ox && oy) corner += m;
                z += v[3 * i + 2] * v[3 * i + 2];
            }
            printf("# mode,lambda_%d,%.10g,ghost %.3f,corner ghosts %.3f,z %.3f\n", which[k] + 1, w[which[k]], ghost,
                   corner, z);
        }
    }
    free(D);
    free(w);
}

/* ---- split: which energy term sets each extreme eigenvalue of H (issue 43) ----
 *
 * For a unit eigenvector v of H = M/dt^2 + K_el + K_pen its eigenvalue is the
 * sum of the terms' Rayleigh quotients,
 *     lambda = v'(M/dt^2)v + v'K_mem v + v'K_bend v + v'K_pen v,
 * so each term's share says which one sets lambda.  K_el is split into
 * membrane and bending by its dependence on the thickness at the same x: the
 * section energy is int_{-tau/2}^{tau/2} psi(A - 2 xi B) dxi (RMTR paper Eq.
 * 3.3-3.4 through the thickness, E(xi) = A - 2 xi B; the Gauss rule in xi is
 * symmetric), so at fixed x only odd powers of tau occur:
 *     K_el(tau) = tau K_1 + tau^3 K_3 + O(tau^5)
 * (tau K_1: the membrane strain A alone; tau^3 K_3 = d2/dx2 of
 * (tau^3/6) psi''(A)[B, B]: bending).  Two more copies of the method (beta =
 * 0) at tau/2 and tau/4 give
 *     K_bend = 4/3 (K_el(tau) - 2 K_el(tau/2))      (O(tau^5) dropped)
 *     K_bend' = 16/15 (K_el(tau) - 4 K_el(tau/4))   (a check: the two differ
 *                                                    by the O(tau^5) rest)
 *     K_mem = K_el - K_bend.
 * Assumption where the paper is silent: none; this is a property of the
 * discretization (6 Gauss points through the thickness, sb_material.c).
 * Output: "# split" comment lines
 *     # split,WHICH,lambda,mass,membrane,bending,penalty,bending_check,relres,ghost
 * WHICH = min / max (the extreme eigenvectors: dense dsyevd or the Lanczos
 * Ritz vectors, relres their relative residual) and, at dense sizes,
 * smooth = the smallest eigenvalue whose eigenvector has less than half of
 * |v|^2 on the ghost control points (the lowest mode of the cloth itself). */
typedef struct split_mats { const sb_matrix *M, *Ke, *Kh, *Kq, *Kpen; double idt2; } split_mats;

static double quad(const sb_matrix *A, const double *v, double *w)
{
    const int n = A->pat->n;
    sb_matrix_symv(A, v, w);
    return sb_dot(n, v, w);
}

static double ghost_share(int n, const double *v, const double *X, double a, double b)
{
    double g = 0, e = 1e-9;
    for (int i = 0; i < n / 3; i++) {
        double x = X[3 * i], y = X[3 * i + 1];
        if (x < -e || x > a + e || y < -e || y > b + e)
            g += v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2];
    }
    return g;
}

static void split_line(const char *which, double lam, double relres, const double *v, const split_mats *S,
                       const double *X, double a, double b, double *w)
{
    const int n = S->Ke->pat->n;
    double m = S->M ? S->idt2 * quad(S->M, v, w) : 0.0;
    double ke = quad(S->Ke, v, w), kh = quad(S->Kh, v, w), kq = quad(S->Kq, v, w);
    double bend = 4.0 / 3.0 * (ke - 2.0 * kh), bend2 = 16.0 / 15.0 * (ke - 4.0 * kq);
    double pen = quad(S->Kpen, v, w);
    printf("# split,%s,%.10g,%.6g,%.6g,%.6g,%.6g,%.6g,%.3g,%.3f\n", which, lam, m, ke - bend, bend, pen, bend2, relres,
           ghost_share(n, v, X, a, b));
}

static void split_terms(sb_problem *p, sb_matrix *H, const split_mats *S, int dense_max, int kmax, const double *X,
                        double a, double b)
{
    const int n = H->pat->n;
    double *w = malloc((size_t)n * sizeof *w);
    if (n <= dense_max) {
        double *D = dense_of(H), *lam = malloc((size_t)n * sizeof *lam);
        if (D && lam && w && sb_eig_dense_sym_vec(n, D, lam) == SB_OK) {
            split_line("min", lam[0], 0.0, D, S, X, a, b, w);
            split_line("max", lam[n - 1], 0.0, D + (size_t)(n - 1) * n, S, X, a, b, w);
            for (int j = 0; j < n; j++)
                if (ghost_share(n, D + (size_t)j * n, X, a, b) < 0.5) {
                    char tag[32];
                    snprintf(tag, sizeof tag, "smooth_%d", j + 1);
                    split_line(tag, lam[j], 0.0, D + (size_t)j * n, S, X, a, b, w);
                    break;
                }
        }
        free(D);
        free(lam);
        free(w);
        return;
    }
    double *vmax = malloc((size_t)n * sizeof *vmax), *vmin = malloc((size_t)n * sizeof *vmin);
    cond_op c = { H, p };
    sb_lanczos_result ra, rb;
    memset(&ra, 0, sizeof ra);
    memset(&rb, 0, sizeof rb);
    ra.vec_max = vmax;
    rb.vec_max = vmin;                         /* the largest Ritz value of H^-1: lambda_min of H */
    if (w && vmax && vmin && sb_lanczos_extreme(n, op_mult, &c, kmax, 1e-10, NULL, &ra) == SB_OK)
        split_line("max", ra.theta_max, ra.res_max / fabs(ra.theta_max), vmax, S, X, a, b, w);
    sb_matrix *Hp = sb_problem_hessian(p, 0);
    memcpy(Hp->val, H->val, (size_t)H->pat->nnz * sizeof *Hp->val);
    if (w && vmax && vmin && sb_problem_factor(p, 0, 0.0) == SB_OK &&
        sb_lanczos_extreme(n, op_solve, &c, kmax, 1e-10, NULL, &rb) == SB_OK && rb.theta_max > 0)
        split_line("min", 1.0 / rb.theta_max, rb.res_max / rb.theta_max, vmin, S, X, a, b, w);
    free(vmax);
    free(vmin);
    free(w);
}

/* split: K_bend and K_mem from two more copies of the method at tau/2 and
 * tau/4 (beta = 0, the same x), their extreme eigenvalues as CSV rows, then
 * the shares of H's extreme eigenvalues ("# split" lines).  0, or nonzero
 * when a copy cannot be set up. */
static int bench_split(const sb_scene *sc, const sb_method_type *mt, sb_method_config *cfg2, const double *x0,
                       sb_matrix *H, const sb_matrix *Kf, const sb_matrix *Ke, const sb_matrix *M, double idt2,
                       sb_problem *p, int dense_max, int kmax, const double *X, const char *tag, int res, double h,
                       int conv, double gn)
{
    const sb_pattern *pat = H->pat;
    sb_scene s2 = *sc, s4 = *sc;                 /* shallow copies: only the thickness differs */
    s2.material.thickness = 0.5 * sc->material.thickness;
    s4.material.thickness = 0.25 * sc->material.thickness;
    void *m2 = calloc(1, mt->state_size), *m4 = calloc(1, mt->state_size);
    if (!m2 || !m4 || mt->create(m2, &s2, cfg2)) { free(m2); free(m4); return 1; }
    if (mt->create(m4, &s4, cfg2)) { mt->destroy(m2); free(m2); free(m4); return 1; }
    sb_matrix Kh, Kq, Kpen, Kb, Km;
    sb_matrix_init(&Kh, pat); sb_matrix_init(&Kq, pat); sb_matrix_init(&Kpen, pat);
    sb_matrix_init(&Kb, pat); sb_matrix_init(&Km, pat);
    double e;
    sb_matrix_zero(&Kh); sb_matrix_zero(&Kq);
    mt->energy(m2, 0, x0, &e, NULL, &Kh);        /* K_el(tau/2) */
    mt->energy(m4, 0, x0, &e, NULL, &Kq);        /* K_el(tau/4) */
    sb_matrix_zero(&Kpen); sb_matrix_axpy(&Kpen, 1.0, Kf); sb_matrix_axpy(&Kpen, -1.0, Ke);
    sb_matrix_zero(&Kb); sb_matrix_axpy(&Kb, 4.0 / 3.0, Ke); sb_matrix_axpy(&Kb, -8.0 / 3.0, &Kh);
    sb_matrix_zero(&Km); sb_matrix_axpy(&Km, 1.0, Ke); sb_matrix_axpy(&Km, -1.0, &Kb);
    const int n = pat->n;
    const sb_matrix *V[2] = { &Km, &Kb };
    const char *name[2] = { "K_mem", "K_bend" };
    for (int v = 0; v < 2; v++) {              /* lambda_max of each part; lambda_min where it factors */
        cond_row r;
        memset(&r, 0, sizeof r);
        sb_matrix A;
        sb_matrix_init(&A, pat);
        sb_matrix_zero(&A);
        sb_matrix_axpy(&A, 1.0, V[v]);
        if (n <= dense_max) measure_dense(&A, &r);
        else measure_lanczos(p, &A, kmax, &r, NULL, name[v]);
        double cond2 = r.lmin > 0 ? r.lmax / r.lmin : NAN;
        printf("%s,%s,%d,%d,%.6g,%s,%.10g,%.10g,%.6g,%.6g,%s,%d,%d,%.3g,%.3g,%d,%.3g\n", sc->name, tag, res, n, h,
               name[v], r.lmin, r.lmax, cond2, r.cond1, r.dense ? "dense" : "lanczos", r.dense ? 0 : r.steps_min,
               r.dense ? 0 : r.steps_max, r.dense ? 0.0 : r.rel_min, r.dense ? 0.0 : r.rel_max, conv, gn);
        sb_matrix_free(&A);
    }
    split_mats S = { M, Ke, &Kh, &Kq, &Kpen, idt2 };
    split_terms(p, H, &S, dense_max, kmax, X, sc->domain.size[0], sc->domain.size[1]);
    fflush(stdout);
    sb_matrix_free(&Kh); sb_matrix_free(&Kq); sb_matrix_free(&Kpen); sb_matrix_free(&Kb); sb_matrix_free(&Km);
    mt->destroy(m2); mt->destroy(m4);
    free(m2); free(m4);
    return 0;
}

static int bench_cond_parts(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: bench_cond parts SCENE RES [method.K=V ...] [tag=NAME] [dense_max=N] "
                        "[lanczos=KMAX] [both] [trace] [header]\n");
        return 2;
    }
    const char *scene_name = argv[1];
    int res = atoi(argv[2]), dense_max = 1100, kmax = 150, both = 0, trace = 0, modes = 0, split = 0, at_initial = 0;
    const char *only = NULL;   /* only=NAME: measure that matrix alone (e.g. only=H at 51,483 dofs) */
    const char *tag = "paper";
    sb_context ctx, ctx2;
    sb_context_init(&ctx);
    sb_context_init(&ctx2);
    sb_scene sc;
    char perr[256];
    if (bench_load_scene("bench_cond", scene_name, &sc)) return 2;
    const sb_method_type *mt = sb_method_find("rmtr");
    const sb_solver_type *st = sb_solver_find("lsnewton");
    sb_context *cs[2] = { &ctx, &ctx2 };
    for (int k = 0; k < 2; k++) {
        bench_add_params(cs[k], mt, st);
        if (sb_paramset_set(&cs[k]->params, "run.stop=paper", perr, sizeof perr)) goto bad;
    }
    for (int i = 3; i < argc; i++) {
        if (!strncmp(argv[i], "tag=", 4)) tag = argv[i] + 4;
        else if (!strncmp(argv[i], "dense_max=", 10)) dense_max = atoi(argv[i] + 10);
        else if (!strncmp(argv[i], "lanczos=", 8)) kmax = atoi(argv[i] + 8);
        else if (!strcmp(argv[i], "both")) both = 1;
        else if (!strcmp(argv[i], "trace")) trace = 1;
        else if (!strcmp(argv[i], "modes")) modes = 1;
        else if (!strcmp(argv[i], "split")) split = 1;
        else if (!strcmp(argv[i], "state=initial")) at_initial = 1;
        else if (!strncmp(argv[i], "only=", 5)) only = argv[i] + 5;
        else if (!strcmp(argv[i], "header"))
            printf("scene,setting,res,dofs,h,variant,lambda_min,lambda_max,cond2,cond1,how,steps_min,steps_max,"
                   "relres_min,relres_max,step_converged,gnorm\n");
        else if (sb_paramset_set(&ctx.params, argv[i], perr, sizeof perr) ||
                 sb_paramset_set(&ctx2.params, argv[i], perr, sizeof perr)) goto bad;
    }
    if (sb_paramset_set(&ctx2.params, "method.beta_scale=0", perr, sizeof perr)) goto bad;
    void *ms = calloc(1, mt->state_size), *ms2 = calloc(1, mt->state_size), *ss = calloc(1, st->state_size);
    sb_method_config cfg = { res, 1, &ctx.params, &ctx, 0 }, cfg2 = { res, 1, &ctx2.params, &ctx2, 0 };
    sb_problem *p = NULL;
    if (mt->create(ms, &sc, &cfg) || mt->create(ms2, &sc, &cfg2) || sb_problem_create(&ctx, mt, ms, &sc, &p) ||
        st->alloc(ss, p, &ctx.params)) {
        fprintf(stderr, "bench_cond: set-up failed: %s %s\n", ctx.err, ctx2.err);
        return 3;
    }
    const int n = sb_problem_n(p, 0);
    double *x = malloc(n * sizeof(double)), *x0 = malloc(n * sizeof(double)), *v0 = calloc(n, sizeof(double));
    double *g = malloc(n * sizeof(double));
    mt->initial(ms, 0, x);
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1; si.n_steps = sc.time.steps; si.dt = sc.time.dt; si.t = sc.time.dt;
    for (int i = 0; i < sc.n_loads; i++) si.load_factor[i] = sb_load_factor(&sc, &sc.loads[i], 1);
    for (int i = 0; i < sc.n_bcs; i++) si.motion_factor[i] = sb_bc_motion_factor(&sc, &sc.bcs[i], 1);
    sb_problem_begin_step(p, &si, x, v0, x0);
    mt->set_step(ms2, &si);
    int it;
    double f, gn;
    /* state=initial: H at the first step's initial iterate (x_n, the flat
     * unstretched cloth, with the boundary at its prescribed values) instead
     * of at the converged step: the paper does not say at which x Fig. 9
     * measures H (issue 43); step_converged is then -1 */
    const int conv = at_initial ? -1 : sb_reason_converged(sb_solve_step(st, ss, p, &ctx.params, 1, x0, &it, &f, &gn));
    /* H of the problem (inertia included), and its parts */
    sb_problem_eval(p, 0, x0, &f, g, sb_problem_hessian(p, 0));
    gn = sb_norm2(n, g);
    const sb_pattern *pat = sb_problem_hessian(p, 0)->pat;
    sb_matrix Hp, Kf, Ke, M, A;
    sb_matrix_init(&Hp, pat); sb_matrix_init(&Kf, pat); sb_matrix_init(&Ke, pat);
    sb_matrix_init(&M, pat); sb_matrix_init(&A, pat);
    memcpy(Hp.val, sb_problem_hessian(p, 0)->val, (size_t)pat->nnz * sizeof(double));
    double e;
    sb_matrix_zero(&Kf); sb_matrix_zero(&Ke); sb_matrix_zero(&M);
    mt->energy(ms, 0, x0, &e, NULL, &Kf);                     /* K_el + K_pen */
    mt->energy(ms2, 0, x0, &e, NULL, &Ke);                    /* K_el (beta = 0) */
    const int dynamic = sc.time.mode == SB_TIME_DYNAMIC;
    const double idt2 = dynamic ? 1.0 / (sc.time.dt * sc.time.dt) : 0.0;
    if (dynamic) mt->mass(ms, 0, &M);
    /* check: the problem's H is M/dt^2 + K_el + K_pen to round-off */
    sb_matrix_zero(&A);
    sb_matrix_axpy(&A, 1.0, &Kf);
    sb_matrix_axpy(&A, idt2, &M);
    sb_matrix_axpy(&A, -1.0, &Hp);
    double chk = sb_matrix_norm_max(&A) / sb_matrix_norm_max(&Hp);
    if (!(chk < 1e-12)) fprintf(stderr, "bench_cond: H differs from M/dt^2 + K by %.3g (relative)\n", chk);
    /* variants: coefficients of K_el, K_pen = Kf - Ke, M/dt^2 */
    static const struct { const char *name; double ce, cp, cm; } V[] = {
        { "H", 1, 1, 1 },              /* the paper's H (Fig. 9): M/dt^2 + K_el + K_pen */
        { "H-pen", 1, 0, 1 },          /* without the penalty: M/dt^2 + K_el */
        { "K", 1, 1, 0 },              /* without the mass: K_el + K_pen (quasi-static) */
        { "K_el", 1, 0, 0 },           /* the shell alone */
        { "M/dt2", 0, 0, 1 },          /* the mass term alone */
        { "K_pen", 0, 1, 0 },          /* the penalty alone (singular: boundary only) */
    };
    const double h = sc.domain.size[0] / res;
    for (size_t v = 0; v < sizeof V / sizeof V[0]; v++) {
        if (!dynamic && V[v].cm != 0 && V[v].ce == 0) continue;
        if (only && strcmp(only, V[v].name)) continue;
        sb_matrix_zero(&A);
        sb_matrix_axpy(&A, V[v].ce, &Ke);
        if (V[v].cp != 0) { sb_matrix_axpy(&A, V[v].cp, &Kf); sb_matrix_axpy(&A, -V[v].cp, &Ke); }
        if (V[v].cm != 0) sb_matrix_axpy(&A, V[v].cm * idt2, &M);
        for (int pass = 0; pass < 2; pass++) {
            cond_row r;
            memset(&r, 0, sizeof r);
            if (pass == 0 && n <= dense_max) measure_dense(&A, &r);
            else if (pass == 1 || n > dense_max) measure_lanczos(p, &A, kmax, &r, trace && v == 0 ? stdout : NULL, V[v].name);
            else continue;
            double cond2 = r.lmin > 0 ? r.lmax / r.lmin : NAN;
            printf("%s,%s,%d,%d,%.6g,%s,%.10g,%.10g,%.6g,%.6g,%s,%d,%d,%.3g,%.3g,%d,%.3g\n", sc.name, tag, res, n, h,
                   V[v].name, r.lmin, r.lmax, cond2, r.cond1, r.dense ? "dense" : "lanczos", r.dense ? 0 : r.steps_min,
                   r.dense ? 0 : r.steps_max, r.dense ? 0.0 : r.rel_min, r.dense ? 0.0 : r.rel_max,
                   conv, gn);
            fflush(stdout);
            if (pass == 0 && !(both && n <= dense_max)) break;
        }
    }
    if (modes && n <= dense_max) describe_modes(&Hp, x, sc.domain.size[0], sc.domain.size[1]);
    if (split && bench_split(&sc, mt, &cfg2, x0, &Hp, &Kf, &Ke, dynamic ? &M : NULL, idt2, p, dense_max, kmax, x, tag,
                             res, h, conv, gn)) {
        fprintf(stderr, "bench_cond: split: set-up at tau/2, tau/4 failed: %s\n", ctx2.err);
    }
    sb_matrix_free(&Hp); sb_matrix_free(&Kf); sb_matrix_free(&Ke); sb_matrix_free(&M); sb_matrix_free(&A);
    free(x); free(x0); free(v0); free(g);
    st->free(ss);
    free(ss);
    sb_problem_free(p);
    mt->destroy(ms);
    mt->destroy(ms2);
    free(ms);
    free(ms2);
    sb_scene_free(&sc);
    sb_context_free(&ctx);
    sb_context_free(&ctx2);
    return 0;
bad:
    fprintf(stderr, "bench_cond: %s\n", perr);
    return 2;
}
