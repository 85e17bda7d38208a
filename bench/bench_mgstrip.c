/* bench_mgstrip.c — issue 38, docs/krylov.md "Why: the penalty defeats the
 * V-cycle": does an energy-minimizing coarse space remove the penalty's
 * effect on pcg-mg over the subdivision hierarchy?
 *
 *   build/bench/bench_mgstrip SCENE RES LEVELS [COARSE] [strip=pen] [thresh=T] [tag=NAME]
 *                             [method.K=V ...] [header]
 *
 * rmtr method, the Hessian H of the first Newton iteration of step 1 (at the
 * step's initial iterate, as lsnewton + pcg-mg meets it), dense.  A two-grid
 * preconditioner between the finest level F = LEVELS-1 and level COARSE
 * (default F-1; the prolongation P is the product of the method's own
 * prolongations, applied to unit vectors): forward node-block Gauss–Seidel,
 * an exact coarse solve with P^T H P, backward node-block Gauss–Seidel — the
 * pcg-mg V-cycle on two levels (core/linalg/sb_precond_mg.c).  CG on
 * H s = -g to ||r|| <= 1e-6 ||g|| (cap 3,000), counted, with
 *
 *   plain   P;
 *   strip   P' = (I - Z A_SS^{-1} Z^T H) P: the coarse functions' values on
 *           the "strip" S (strip=pen: every dof the penalty term touches,
 *           from the diagonal of H minus H at beta = 0; else the dofs whose
 *           diagonal exceeds T (10) times the median of their component's)
 *           replaced by the H-harmonic extension of their values
 *           elsewhere, i.e. the coarse space made H-orthogonal to the strip
 *           (the energy-minimizing coarse space of AMGe and of
 *           Vaněk–Mandel–Brezina's smoothed aggregation, restricted to S;
 *           with P' the coarse operator is P^T S_H P with S_H the Schur
 *           complement of H_SS);
 *   strip+  the same, and the strip solved exactly after the forward and
 *           before the backward sweep (a symmetric multiplicative correction,
 *           docs/krylov.md's "stiff strip" experiment, on top of P').
 *
 * Both variants keep the preconditioner symmetric; P' has full column rank
 * when P has and H is SPD.  Dense: for sizes up to a few thousand dofs
 * (a measurement, not a solver). */
#include "bench_rmtr_setup.h"
#include "sb_context.h"
#include "sb_run_state.h"
#include "sb_scene.h"
#include "sb_solver.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, double *b,
             const int *ldb, int *info);

typedef struct twogrid {
    int n, nc, bs, ns;
    const double *H;     /* n x n, column-major (symmetric) */
    double *P;           /* n x nc */
    double *Ac;          /* nc x nc Cholesky factor */
    double *Dinv;        /* n/bs blocks of bs x bs, inverted */
    int *S;              /* strip dofs (ns), or NULL */
    double *Ass;         /* ns x ns Cholesky factor */
    double *t, *tc, *ts; /* scratch */
} twogrid;

static int chol(int n, double *a) { int info; dpotrf_("L", &n, a, &n, &info); return info; }
static void chol_solve(int n, const double *a, double *b) { int one = 1, info; dpotrs_("L", &n, &one, a, &n, b, &n, &info); }

static void matvec(int n, const double *H, const double *x, double *y)
{
    for (int i = 0; i < n; i++) y[i] = 0.0;
    for (int j = 0; j < n; j++) {
        const double xj = x[j];
        if (xj == 0.0) continue;
        const double *c = H + (size_t)j * n;
        for (int i = 0; i < n; i++) y[i] += c[i] * xj;
    }
}

/* one Gauss–Seidel sweep over the node blocks, forward (dir 1) or backward */
static void gs_sweep(const twogrid *T, const double *b, double *x, int dir)
{
    const int n = T->n, bs = T->bs, nb = n / bs;
    for (int k = 0; k < nb; k++) {
        const int blk = dir > 0 ? k : nb - 1 - k;
        double r[12];
        for (int a = 0; a < bs; a++) {
            const int i = blk * bs + a;
            double s = b[i];
            for (int j = 0; j < n; j++) s -= T->H[(size_t)j * n + i] * x[j];   /* H symmetric: row i = column i */
            r[a] = s;
        }
        const double *Di = T->Dinv + (size_t)blk * bs * bs;
        for (int a = 0; a < bs; a++) {
            double s = 0.0;
            for (int c = 0; c < bs; c++) s += Di[a * bs + c] * r[c];
            x[blk * bs + a] += s;
        }
    }
}

/* x += Z A_SS^{-1} Z^T (b - H x): the exact strip solve */
static void strip_solve(const twogrid *T, const double *b, double *x)
{
    matvec(T->n, T->H, x, T->t);
    for (int k = 0; k < T->ns; k++) T->ts[k] = b[T->S[k]] - T->t[T->S[k]];
    chol_solve(T->ns, T->Ass, T->ts);
    for (int k = 0; k < T->ns; k++) x[T->S[k]] += T->ts[k];
}

/* e = B r: the symmetric two-grid cycle */
static void apply(const twogrid *T, int strip, const double *r, double *e)
{
    const int n = T->n, nc = T->nc;
    for (int i = 0; i < n; i++) e[i] = 0.0;
    gs_sweep(T, r, e, 1);
    if (strip) strip_solve(T, r, e);
    matvec(n, T->H, e, T->t);
    for (int i = 0; i < n; i++) T->t[i] = r[i] - T->t[i];
    for (int c = 0; c < nc; c++) {
        const double *pc = T->P + (size_t)c * n;
        double s = 0.0;
        for (int i = 0; i < n; i++) s += pc[i] * T->t[i];
        T->tc[c] = s;
    }
    chol_solve(nc, T->Ac, T->tc);
    for (int c = 0; c < nc; c++) {
        const double *pc = T->P + (size_t)c * n;
        for (int i = 0; i < n; i++) e[i] += pc[i] * T->tc[c];
    }
    if (strip) strip_solve(T, r, e);
    gs_sweep(T, r, e, -1);
}

static int pcg(const twogrid *T, int strip, const double *b, double rtol, int cap)
{
    const int n = T->n;
    double *x = calloc(n, sizeof *x), *r = malloc(n * sizeof *r), *z = malloc(n * sizeof *z);
    double *d = malloc(n * sizeof *d), *q = malloc(n * sizeof *q);
    double bn = 0.0, rz = 0.0;
    if (n <= 0 || !x || !r || !z || !d || !q) {
        free(x); free(r); free(z); free(d); free(q);
        return -1;
    }
    for (int i = 0; i < n; i++) r[i] = b[i], bn += b[i] * b[i];
    bn = sqrt(bn);
    apply(T, strip, r, z);
    for (int i = 0; i < n; i++) d[i] = z[i], rz += r[i] * z[i];
    int it = 0;
    for (; it < cap; it++) {
        double rn = 0.0;
        for (int i = 0; i < n; i++) rn += r[i] * r[i];
        if (sqrt(rn) <= rtol * bn) break;
        matvec(n, T->H, d, q);
        double dq = 0.0;
        for (int i = 0; i < n; i++) dq += d[i] * q[i];
        if (!(dq > 0)) { it = -it - 1; break; }   /* not SPD */
        const double a = rz / dq;
        for (int i = 0; i < n; i++) x[i] += a * d[i], r[i] -= a * q[i];
        apply(T, strip, r, z);
        double rz1 = 0.0;
        for (int i = 0; i < n; i++) rz1 += r[i] * z[i];
        for (int i = 0; i < n; i++) d[i] = z[i] + rz1 / rz * d[i];
        rz = rz1;
    }
    free(x); free(r); free(z); free(d); free(q);
    return it;
}

static int cmp_dbl(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* the coarse operator P^T H P, factored */
static int coarse(twogrid *T)
{
    const int n = T->n, nc = T->nc;
    double *HP = malloc((size_t)n * nc * sizeof *HP);
    for (int c = 0; c < nc; c++) matvec(n, T->H, T->P + (size_t)c * n, HP + (size_t)c * n);
    for (int a = 0; a < nc; a++)
        for (int c = 0; c < nc; c++) {
            double s = 0.0;
            for (int i = 0; i < n; i++) s += T->P[(size_t)a * n + i] * HP[(size_t)c * n + i];
            T->Ac[(size_t)c * nc + a] = s;
        }
    free(HP);
    return chol(nc, T->Ac);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: bench_mgstrip SCENE RES LEVELS [COARSE] [thresh=T] [method.K=V ...] [header]\n");
        return 2;
    }
    const int res = atoi(argv[2]), levels = atoi(argv[3]);
    int lc = levels - 2, argi = 4;
    double thresh = 10.0;
    int pen_strip = 0;
    const char *tag = "scene";
    if (argc > 4 && argv[4][0] >= '0' && argv[4][0] <= '9') lc = atoi(argv[4]), argi = 5;
    sb_context ctx;
    sb_context_init(&ctx);
    sb_scene sc;
    char perr[256];
    if (bench_load_scene("bench_mgstrip", argv[1], &sc)) return 2;
    const sb_method_type *mt = sb_method_find("rmtr");
    const sb_solver_type *st = sb_solver_find("lsnewton");
    bench_add_params(&ctx, mt, st);
    for (int i = argi; i < argc; i++) {
        if (!strcmp(argv[i], "header")) {
            printf("scene,setting,res,levels,coarse,dofs,coarse_dofs,strip_rule,strip_dofs,cg_plain,cg_plain_strip_solve,cg_energy_min_P,"
                   "cg_energy_min_P_strip_solve\n");
            continue;
        }
        if (!strncmp(argv[i], "thresh=", 7)) { thresh = atof(argv[i] + 7); continue; }
        if (!strcmp(argv[i], "strip=pen")) { pen_strip = 1; continue; }
        if (!strncmp(argv[i], "tag=", 4)) { tag = argv[i] + 4; continue; }
        if (sb_paramset_set(&ctx.params, argv[i], perr, sizeof perr)) {
            fprintf(stderr, "bench_mgstrip: %s\n", perr);
            return 2;
        }
    }
    void *ms = calloc(1, mt->state_size);
    sb_method_config cfg = { res, levels, &ctx.params, &ctx, 0 };
    sb_problem *p = NULL;
    if (mt->create(ms, &sc, &cfg) || sb_problem_create(&ctx, mt, ms, &sc, &p)) {
        fprintf(stderr, "bench_mgstrip: set-up failed: %s\n", ctx.err);
        return 3;
    }
    const int F = sb_problem_finest(p), n = sb_problem_n(p, F);
    if (lc < 0 || lc >= F) { fprintf(stderr, "bench_mgstrip: COARSE must be in 0..%d\n", F - 1); return 2; }
    const int nc = sb_problem_n(p, lc);
    double *x = malloc(n * sizeof *x), *x0 = malloc(n * sizeof *x0), *v0 = calloc(n, sizeof *v0);
    double *g = malloc(n * sizeof *g);
    mt->initial(ms, F, x);
    sb_step_info si;
    sb_run_step_info(&sc, 1, &si);
    sb_problem_begin_step(p, &si, x, v0, x0);
    double f;
    sb_matrix *Hs = sb_problem_hessian(p, F);
    if (sb_problem_eval(p, F, x0, &f, g, Hs) != SB_OK) { fprintf(stderr, "bench_mgstrip: eval failed\n"); return 3; }
    /* dense H from the sparse upper triangle */
    double *H = calloc((size_t)n * n, sizeof *H), *e = calloc(n, sizeof *e), *col = malloc(n * sizeof *col);
    for (int j = 0; j < n; j++) {
        e[j] = 1.0;
        sb_matrix_symv(Hs, e, col);
        e[j] = 0.0;
        memcpy(H + (size_t)j * n, col, n * sizeof *col);
    }
    /* P: the prolongations from level lc to F applied to unit vectors */
    twogrid T;
    memset(&T, 0, sizeof T);
    T.n = n, T.nc = nc, T.H = H;
    T.bs = sb_problem_block_size(p, F);
    if (T.bs < 1 || T.bs > 12 || n % T.bs) T.bs = 1;
    T.P = malloc((size_t)n * nc * sizeof *T.P);
    double *u = malloc(n * sizeof *u), *w = malloc(n * sizeof *w);
    for (int c = 0; c < nc; c++) {
        memset(u, 0, nc * sizeof *u);
        u[c] = 1.0;
        for (int l = lc; l < F; l++) {
            sb_problem_prolong(p, l, u, w);
            memcpy(u, w, sb_problem_n(p, l + 1) * sizeof *u);
        }
        memcpy(T.P + (size_t)c * n, u, n * sizeof *u);
    }
    /* node-block Jacobi inverses */
    const int nb = n / T.bs;
    T.Dinv = malloc((size_t)nb * T.bs * T.bs * sizeof *T.Dinv);
    for (int k = 0; k < nb; k++) {
        double a[144];
        for (int r = 0; r < T.bs; r++)
            for (int c = 0; c < T.bs; c++) a[c * T.bs + r] = H[(size_t)(k * T.bs + c) * n + k * T.bs + r];
        if (chol(T.bs, a)) { fprintf(stderr, "bench_mgstrip: a diagonal block is not SPD\n"); return 3; }
        for (int c = 0; c < T.bs; c++) {
            double b[12] = { 0 };
            b[c] = 1.0;
            chol_solve(T.bs, a, b);
            for (int r = 0; r < T.bs; r++) T.Dinv[(size_t)k * T.bs * T.bs + r * T.bs + c] = b[r];
        }
    }
    T.Ac = malloc((size_t)nc * nc * sizeof *T.Ac);
    T.t = malloc(n * sizeof *T.t);
    T.tc = malloc(nc * sizeof *T.tc);
    for (int i = 0; i < n; i++) g[i] = -g[i];
    if (coarse(&T)) { fprintf(stderr, "bench_mgstrip: P^T H P is not SPD\n"); return 3; }
    const int it_plain = pcg(&T, 0, g, 1e-6, 3000);
    /* strip=pen: the dofs the penalty touches (its Hessian's diagonal, H at
     * beta against H at beta = 0, nonzero); else the stiff strip: diagonal
     * above thresh x the median of its component */
    double *dpen = NULL;
    if (pen_strip) {
        sb_context ctx0;
        sb_context_init(&ctx0);
        sb_paramset_add(&ctx0.params, "method", mt->params);
        for (int i = argi; i < argc; i++)
            if (!strncmp(argv[i], "method.", 7)) (void)sb_paramset_set(&ctx0.params, argv[i], perr, sizeof perr);
        (void)sb_paramset_set(&ctx0.params, "method.beta_scale=0", perr, sizeof perr);
        void *ms0 = calloc(1, mt->state_size);
        sb_method_config cfg0 = { res, levels, &ctx0.params, &ctx0, 0 };
        sb_matrix K0, K1;
        sb_matrix_init(&K0, Hs->pat);
        sb_matrix_init(&K1, Hs->pat);
        sb_matrix_zero(&K0);
        sb_matrix_zero(&K1);
        double e0;
        if (mt->create(ms0, &sc, &cfg0)) { fprintf(stderr, "bench_mgstrip: %s\n", ctx0.err); return 3; }
        mt->set_step(ms0, &si);
        mt->energy(ms0, F, x0, &e0, NULL, &K0);
        mt->energy(ms, F, x0, &e0, NULL, &K1);
        dpen = calloc(n, sizeof *dpen);
        for (int j = 0; j < n; j++) {
            e[j] = 1.0;
            sb_matrix_symv(&K1, e, col);
            dpen[j] = col[j];
            sb_matrix_symv(&K0, e, col);
            dpen[j] -= col[j];
            e[j] = 0.0;
        }
        sb_matrix_free(&K0);
        sb_matrix_free(&K1);
        mt->destroy(ms0);
        free(ms0);
        sb_context_free(&ctx0);
    }
    const int bs3 = T.bs >= 3 ? 3 : 1;
    double *dg = malloc(n * sizeof *dg), med[3];
    for (int c = 0; c < bs3; c++) {
        int m = 0;
        for (int i = c; i < n; i += bs3) dg[m++] = H[(size_t)i * n + i];
        qsort(dg, m, sizeof *dg, cmp_dbl);
        med[c] = dg[m / 2];
    }
    T.S = malloc(n * sizeof *T.S);
    for (int i = 0; i < n; i++)
        if (dpen ? fabs(dpen[i]) > 1e-12 * H[(size_t)i * n + i] : H[(size_t)i * n + i] > thresh * med[i % bs3])
            T.S[T.ns++] = i;
    free(dpen);
    int it_strip = -1, it_plus = -1, it_plain_plus = -1;
    if (T.ns > 0) {
        T.Ass = malloc((size_t)T.ns * T.ns * sizeof *T.Ass);
        for (int a = 0; a < T.ns; a++)
            for (int b = 0; b < T.ns; b++) T.Ass[(size_t)b * T.ns + a] = H[(size_t)T.S[b] * n + T.S[a]];
        if (chol(T.ns, T.Ass)) { fprintf(stderr, "bench_mgstrip: H_SS is not SPD\n"); return 3; }
        T.ts = malloc(T.ns * sizeof *T.ts);
        it_plain_plus = pcg(&T, 1, g, 1e-6, 3000);   /* the strip solve with the plain P */
        /* P' = P - Z A_SS^{-1} Z^T H P, column by column */
        for (int c = 0; c < nc; c++) {
            double *pc = T.P + (size_t)c * n;
            matvec(n, H, pc, T.t);
            for (int k = 0; k < T.ns; k++) T.ts[k] = T.t[T.S[k]];
            chol_solve(T.ns, T.Ass, T.ts);
            for (int k = 0; k < T.ns; k++) pc[T.S[k]] -= T.ts[k];
        }
        if (coarse(&T)) { fprintf(stderr, "bench_mgstrip: P'^T H P' is not SPD\n"); return 3; }
        it_strip = pcg(&T, 0, g, 1e-6, 3000);
        it_plus = pcg(&T, 1, g, 1e-6, 3000);
    }
    char strip_rule[32];
    if (pen_strip) snprintf(strip_rule, sizeof strip_rule, "pen");
    else snprintf(strip_rule, sizeof strip_rule, "%g", thresh);
    printf("%s,%s,%d,%d,%d,%d,%d,%s,%d,%d,%d,%d,%d\n", sc.name, tag, res, levels, lc, n, nc, strip_rule, T.ns, it_plain,
           it_plain_plus, it_strip, it_plus);
    free(H); free(e); free(col); free(u); free(w); free(dg); free(T.P); free(T.Dinv); free(T.Ac); free(T.t);
    free(T.tc); free(T.S); free(T.Ass); free(T.ts); free(x); free(x0); free(v0); free(g);
    sb_problem_free(p);
    mt->destroy(ms);
    free(ms);
    return 0;
}
