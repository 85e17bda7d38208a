/* test_sparse.c — block patterns, scatter maps and the element gather against dense assembly;
 * CHOLMOD wrapper: solve accuracy, NOT_POSDEF detection, shifted factorization. */
#include "sb_test.h"
#include "sb_context.h"
#include "sb_linsolve.h"
#include "sb_schwarz.h"
#include "sb_galerkin.h"

#include <stdlib.h>
#include <string.h>

static unsigned rng_state = 12345u;
static double urand(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (rng_state >> 8) / 16777216.0;
}

/* Random elements (with repeated and missing nodes), dense reference vs pattern. */
static void check_assembly(sb_test_state *T, int nn, int bs, int ne, int kmax)
{
    sb_pattern_builder *pb = sb_pattern_builder_new(nn, bs);
    int *nodes = malloc((size_t)ne * kmax * sizeof(int)), *ks = malloc((size_t)ne * sizeof(int));
    for (int e = 0; e < ne; e++) {
        ks[e] = 1 + (int)(urand() * kmax);
        if (ks[e] > kmax) ks[e] = kmax;
        for (int a = 0; a < ks[e]; a++) {
            double u = urand();
            nodes[e * kmax + a] = u < 0.05 ? -1 : (int)(urand() * nn);    /* -1: no node */
        }
        if (ks[e] >= 2 && urand() < 0.3) nodes[e * kmax + 1] = nodes[e * kmax];  /* repeated node */
        CHECK_EQ_INT(sb_pattern_builder_add(pb, ks[e], nodes + e * kmax), 0);
    }
    sb_pattern *pat;
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pat), 0);
    int n = nn * bs;
    CHECK_EQ_INT(pat->n, n);
    long maxcol = 0;
    for (int c = 0; c < n; c++)
        if (pat->colptr[c + 1] - pat->colptr[c] > maxcol) maxcol = pat->colptr[c + 1] - pat->colptr[c];
    CHECK_EQ_INT(pat->map_width, maxcol <= 256 ? 1 : 2);
    sb_matrix A;
    sb_matrix_init(&A, pat);
    double *dense = calloc((size_t)n * n, sizeof(double));
    for (int e = 0; e < ne; e++) {
        int m = bs * ks[e];
        double *Ke = malloc((size_t)m * m * sizeof(double));
        for (int i = 0; i < m; i++)
            for (int j = 0; j <= i; j++) Ke[i * m + j] = Ke[j * m + i] = urand() - 0.5;
        sb_matrix_add_element(&A, e, Ke);
        for (int a = 0; a < ks[e]; a++)
            for (int b = 0; b < ks[e]; b++) {
                int na = nodes[e * kmax + a], nb = nodes[e * kmax + b];
                if (na < 0 || nb < 0) continue;
                for (int i = 0; i < bs; i++)
                    for (int j = 0; j < bs; j++) dense[(na * bs + i) * n + nb * bs + j] += Ke[(bs * a + i) * m + bs * b + j];
            }
        free(Ke);
    }
    /* compare every stored entry, and that the pattern holds every nonzero */
    double maxerr = 0, stored = 0, total = 0;
    for (int c = 0; c < n; c++)
        for (long q = pat->colptr[c]; q < pat->colptr[c + 1]; q++) {
            int r = pat->rowind[q];
            CHECK(r <= c);
            if (q > pat->colptr[c]) CHECK(pat->rowind[q - 1] < r);
            maxerr = fmax(maxerr, fabs(A.val[q] - dense[r * n + c]));
            stored += fabs(dense[r * n + c]);
        }
    for (int r = 0; r < n; r++)
        for (int c = r; c < n; c++) total += fabs(dense[r * n + c]);
    CHECK(maxerr < 1e-12);
    CHECK_NEAR(stored, total, 1e-9 * (1 + total));
    for (int c = 0; c < n; c++) CHECK_EQ_INT(pat->rowind[pat->diag[c]], c);
    /* symv against dense */
    double *x = malloc((size_t)n * sizeof(double)), *y = malloc((size_t)n * sizeof(double));
    for (int i = 0; i < n; i++) x[i] = urand() - 0.5;
    sb_matrix_symv(&A, x, y);
    double err = 0;
    for (int r = 0; r < n; r++) {
        double s = 0;
        for (int c = 0; c < n; c++) s += dense[r < c ? r * n + c : c * n + r] * x[c];
        err = fmax(err, fabs(s - y[r]));
    }
    CHECK(err < 1e-12);
    /* gather (sb_matrix_get_element): every element's submatrix of the assembled matrix */
    double gerr = 0;
    for (int e = 0; e < ne; e++) {
        int m = bs * ks[e];
        double *Ke = malloc((size_t)m * m * sizeof(double));
        sb_matrix_get_element(&A, e, Ke);
        for (int a = 0; a < ks[e]; a++)
            for (int b = 0; b < ks[e]; b++) {
                int na = nodes[e * kmax + a], nb = nodes[e * kmax + b];
                for (int i = 0; i < bs; i++)
                    for (int j = 0; j < bs; j++) {
                        double want = na < 0 || nb < 0 ? 0.0 : dense[(na * bs + i) * n + nb * bs + j];
                        gerr = fmax(gerr, fabs(Ke[(bs * a + i) * m + bs * b + j] - want));
                    }
            }
        free(Ke);
    }
    CHECK_MSG(gerr < 1e-12, "gather error %g", gerr);
    free(x); free(y); free(dense); free(nodes); free(ks);
    sb_matrix_free(&A);
    sb_pattern_free(pat);
}

SB_TEST(pattern_bs1) { check_assembly(T, 40, 1, 60, 4); }
SB_TEST(pattern_bs3) { check_assembly(T, 30, 3, 40, 6); }
SB_TEST(pattern_bs12) { check_assembly(T, 12, 12, 10, 4); }
/* the scatter map's width follows the longest column: 1 byte above, 2 bytes here */
SB_TEST(pattern_two_byte_map)
{
    rng_state = 777u;
    check_assembly(T, 120, 3, 60, 40);
    sb_pattern_builder *pb = sb_pattern_builder_new(120, 3);
    int nd[90];   /* one element of 90 nodes: its last column has 270 entries */
    for (int a = 0; a < 90; a++) nd[a] = a;
    sb_pattern_builder_add(pb, 90, nd);
    sb_pattern *pat;
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pat), 0);
    CHECK_EQ_INT(pat->map_width, 2);
    sb_pattern_free(pat);
}

/* a star (node N-1 coupled to every node, as a constraint or a rigid body
 * would): its column has more than 65,536 entries, so 4-byte offsets */
SB_TEST(pattern_four_byte_map_on_a_star)
{
    const int N = 70000;
    sb_pattern_builder *pb = sb_pattern_builder_new(N, 1);
    for (int i = 0; i + 1 < N; i++) {
        int nd[2] = { i, N - 1 };
        CHECK_EQ_INT(sb_pattern_builder_add(pb, 2, nd), 0);
    }
    sb_pattern *pat;
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pat), 0);
    CHECK_EQ_INT(pat->map_width, 4);
    sb_matrix A;
    CHECK_EQ_INT(sb_matrix_init(&A, pat), 0);
    for (int i = 0; i + 1 < N; i++) {
        const double Ke[4] = { 1.0, 0.5 + i, 0.5 + i, 2.0 };
        sb_matrix_add_element(&A, i, Ke);
    }
    int bad = 0;
    for (int i = 0; i + 1 < N; i++) {
        const long q = sb_pattern_find(pat, i, N - 1), d = sb_pattern_find(pat, i, i);
        if (q < 0 || d < 0 || A.val[q] != 0.5 + i || A.val[d] != 1.0) bad++;
        double Ke[4];
        sb_matrix_get_element(&A, i, Ke);
        if (Ke[1] != 0.5 + i || Ke[2] != 0.5 + i || Ke[0] != 1.0 || Ke[3] != 2.0 * (N - 1)) bad++;
    }
    CHECK_EQ_INT(bad, 0);
    CHECK_EQ_INT(A.val[pat->diag[N - 1]] == 2.0 * (N - 1), 1);
    sb_matrix_free(&A);
    sb_pattern_free(pat);
}

/* 1-D Laplacian with a Dirichlet-like diagonal: SPD, known solution */
static sb_pattern *chain(int n)
{
    sb_pattern_builder *pb = sb_pattern_builder_new(n, 1);
    for (int i = 0; i + 1 < n; i++) { int nd[2] = { i, i + 1 }; sb_pattern_builder_add(pb, 2, nd); }
    sb_pattern *p;
    sb_pattern_builder_finish(pb, &p);
    return p;
}

SB_TEST(cholmod_solve_and_not_posdef)
{
    sb_context ctx;
    CHECK_EQ_INT(sb_context_init(&ctx), 0);
    const int n = 200;
    sb_pattern *pat = chain(n);
    sb_matrix A;
    sb_matrix_init(&A, pat);
    double K[4] = { 1, -1, -1, 1 };
    for (int e = 0; e + 1 < n; e++) sb_matrix_add_element(&A, e, K);
    sb_matrix_add(&A, 0, 0, 1.0);                 /* makes it SPD */
    sb_linsolve *ls;
    CHECK_EQ_INT(sb_linsolve_create(&ctx, 0, &A, &ls), 0);
    CHECK_EQ_INT(sb_linsolve_factor(ls, 0.0), SB_OK);
    double *xs = malloc(n * sizeof(double)), *b = malloc(n * sizeof(double)), *x = malloc(n * sizeof(double));
    for (int i = 0; i < n; i++) xs[i] = sin(0.1 * i);
    sb_matrix_symv(&A, xs, b);
    CHECK_EQ_INT(sb_linsolve_solve(ls, b, x), SB_OK);
    double err = 0;
    for (int i = 0; i < n; i++) err = fmax(err, fabs(x[i] - xs[i]));
    CHECK(err < 1e-8);
    CHECK(sb_linsolve_nnz_l(ls) >= n);
    CHECK(sb_linsolve_flops(ls) > 0);
    /* make it indefinite: the factorization reports NOT_POSDEF, not an error */
    sb_matrix_add(&A, n / 2, n / 2, -10.0);
    CHECK_EQ_INT(sb_linsolve_factor(ls, 0.0), SB_NOT_POSDEF);
    CHECK_EQ_INT(ctx.stats.not_posdef, 1);
    /* a large enough shift repairs it: (A + 20 I) is SPD */
    CHECK_EQ_INT(sb_linsolve_factor(ls, 20.0), SB_OK);
    sb_matrix_symv(&A, xs, b);
    for (int i = 0; i < n; i++) b[i] += 20.0 * xs[i];
    CHECK_EQ_INT(sb_linsolve_solve(ls, b, x), SB_OK);
    err = 0;
    for (int i = 0; i < n; i++) err = fmax(err, fabs(x[i] - xs[i]));
    CHECK(err < 1e-10);
    CHECK_EQ_INT(ctx.stats.ev[0][SB_EV_ANALYZE].count, 1);      /* analysis once */
    CHECK_EQ_INT(ctx.stats.ev[0][SB_EV_FACTORIZE].count, 3);
    free(xs); free(b); free(x);
    sb_linsolve_free(ls);
    sb_matrix_free(&A);
    sb_pattern_free(pat);
    sb_context_free(&ctx);
}

SB_TEST(params_validation)
{
    static const char *const ch[] = { "a", "b", NULL };
    static const sb_param_def defs[] = {
        { "x", SB_PARAM_REAL, 0.5, 0, 1, NULL, "" },
        { "k", SB_PARAM_INT, 3, 1, 10, NULL, "" },
        { "c", SB_PARAM_CHOICE, 1, 0, 0, ch, "" },
        { NULL, 0, 0, 0, 0, NULL, NULL },
    };
    sb_paramset ps;
    sb_paramset_init(&ps);
    CHECK_EQ_INT(sb_paramset_add(&ps, "solver", defs), 0);
    char err[512];
    CHECK_NEAR(sb_param(&ps, "solver.x"), 0.5, 0);
    CHECK(strcmp(sb_param_choice(&ps, "solver.c"), "b") == 0);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.x=0.25", err, sizeof err), 0);
    CHECK_NEAR(sb_param(&ps, "solver.x"), 0.25, 0);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.x=1.5", err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "[0, 1]") != NULL);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.k=2.5", err, sizeof err), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.x=abc", err, sizeof err), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.x=nan", err, sizeof err), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.c=z", err, sizeof err), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.c=a", err, sizeof err), 0);
    CHECK_EQ_INT(sb_param_int(&ps, "solver.c"), 0);
    CHECK_EQ_INT(sb_paramset_set(&ps, "noequals", err, sizeof err), SB_ERR_INPUT);
    CHECK_EQ_INT(sb_paramset_set(&ps, "solver.y=1", err, sizeof err), SB_ERR_INPUT);
    CHECK(strstr(err, "unknown parameter") != NULL);
}

/* SPD matrix assembled from random SPD element blocks (B^T B + I per element). */
static void spd_assemble(sb_matrix *A, const sb_pattern *pat)
{
    sb_matrix_zero(A);
    for (int e = 0; e < pat->n_elems; e++) {
        int k;
        sb_pattern_elem_nodes(pat, e, &k);
        int m = pat->bs * k;
        double *B = malloc((size_t)m * m * sizeof(double)), *K = calloc((size_t)m * m, sizeof(double));
        for (int i = 0; i < m * m; i++) B[i] = urand() - 0.5;
        for (int i = 0; i < m; i++)
            for (int j = 0; j < m; j++) {
                double v = i == j ? 1.0 : 0.0;
                for (int q = 0; q < m; q++) v += B[q * m + i] * B[q * m + j];
                K[i * m + j] = v;
            }
        sb_matrix_add_element(A, e, K);
        free(B); free(K);
    }
}

/* Additive Schwarz on element patches: one patch holding every node is the
 * exact inverse; overlapping patches give a symmetric positive definite M^{-1}. */
SB_TEST(schwarz_preconditioner)
{
    const int nn = 7, bs = 3, n = nn * bs;
    int all[7] = { 0, 1, 2, 3, 4, 5, 6 };
    sb_pattern_builder *pb = sb_pattern_builder_new(nn, bs);
    CHECK_EQ_INT(sb_pattern_builder_add(pb, nn, all), 0);
    sb_pattern *pat;
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pat), 0);
    sb_matrix A;
    sb_matrix_init(&A, pat);
    spd_assemble(&A, pat);
    sb_schwarz S;
    memset(&S, 0, sizeof S);
    CHECK_EQ_INT(sb_schwarz_setup(&S, &A), 0);
    double r[21], z[21], Az[21], u[21], Mu[21];
    for (int i = 0; i < n; i++) r[i] = urand() - 0.5;
    sb_schwarz_apply(&S, r, z);
    sb_matrix_symv(&A, z, Az);
    double err = 0;
    for (int i = 0; i < n; i++) err = fmax(err, fabs(Az[i] - r[i]));
    CHECK_MSG(err < 1e-10, "single patch: |A M^-1 r - r| = %g", err);
    sb_schwarz_free(&S);
    sb_matrix_free(&A);
    sb_pattern_free(pat);
    /* overlapping patches along a chain */
    pb = sb_pattern_builder_new(nn, bs);
    for (int e = 0; e + 2 < nn; e++) CHECK_EQ_INT(sb_pattern_builder_add(pb, 3, all + e), 0);
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pat), 0);
    sb_matrix_init(&A, pat);
    spd_assemble(&A, pat);
    memset(&S, 0, sizeof S);
    CHECK_EQ_INT(sb_schwarz_setup(&S, &A), 0);
    for (int i = 0; i < n; i++) u[i] = urand() - 0.5;
    sb_schwarz_apply(&S, r, z);
    sb_schwarz_apply(&S, u, Mu);
    double a = 0, b = 0, c = 0;
    for (int i = 0; i < n; i++) { a += u[i] * z[i]; b += r[i] * Mu[i]; c += u[i] * Mu[i]; }
    CHECK_MSG(fabs(a - b) < 1e-12 * (fabs(a) + 1), "u.M^-1 r = %g, r.M^-1 u = %g", a, b);
    CHECK(c > 0);
    sb_schwarz_free(&S);
    sb_matrix_free(&A);
    sb_pattern_free(pat);
}


/* Galerkin product S^T H S on the coarse pattern against dense arithmetic:
 * fine = a 1D chain of nf nodes (tridiagonal-block pattern), coarse = every
 * other node with linear interpolation (bandwidth 1 after the product), with
 * fixed fine and coarse dofs left out; then a coarse pattern too small for
 * the product must be refused. */
SB_TEST(galerkin_product)
{
    const int bs = 2, nn_c = 6, nn_f = 2 * nn_c - 1, nf = bs * nn_f, nc = bs * nn_c;
    sb_pattern_builder *pb = sb_pattern_builder_new(nn_f, bs);
    for (int a = 0; a + 1 < nn_f; a++) {
        int e[2] = { a, a + 1 };
        sb_pattern_builder_add(pb, 2, e);
    }
    sb_pattern *pf, *pc, *pdiag;
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pf), 0);
    pb = sb_pattern_builder_new(nn_c, bs);
    for (int a = 0; a + 1 < nn_c; a++) {
        int e[2] = { a, a + 1 };
        sb_pattern_builder_add(pb, 2, e);
    }
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pc), 0);
    pb = sb_pattern_builder_new(nn_c, bs);
    for (int a = 0; a < nn_c; a++) sb_pattern_builder_add(pb, 1, &a);
    CHECK_EQ_INT(sb_pattern_builder_finish(pb, &pdiag), 0);
    /* H: random symmetric on the fine pattern */
    sb_matrix Hf, Hc;
    sb_matrix_init(&Hf, pf);
    sb_matrix_init(&Hc, pc);
    for (long k = 0; k < pf->nnz; k++) Hf.val[k] = urand() - 0.5;
    double *H = calloc((size_t)nf * nf, sizeof(double));
    for (int c = 0; c < nf; c++)
        for (long q = pf->colptr[c]; q < pf->colptr[c + 1]; q++)
            H[pf->rowind[q] * nf + c] = H[c * nf + pf->rowind[q]] = Hf.val[q];
    /* S: fine node 2a = coarse node a, 2a+1 = mean of a and a+1, per component */
    sb_csr S;
    CHECK_EQ_INT(sb_csr_alloc(&S, nf, nc, 2L * nf), 0);
    double *Sd = calloc((size_t)nf * nc, sizeof(double));
    long k = 0;
    for (int i = 0; i < nn_f; i++)
        for (int c = 0; c < bs; c++) {
            if (i % 2 == 0) {
                S.ci[k] = bs * (i / 2) + c; S.v[k++] = 1.0;
            } else {
                S.ci[k] = bs * (i / 2) + c; S.v[k++] = 0.5;
                S.ci[k] = bs * (i / 2 + 1) + c; S.v[k++] = 0.5;
            }
            S.rp[bs * i + c + 1] = k;
        }
    for (int i = 0; i < nf; i++)
        for (long q = S.rp[i]; q < S.rp[i + 1]; q++) Sd[i * nc + S.ci[q]] = S.v[q];
    unsigned char *ff = calloc((size_t)nf, 1), *fc = calloc((size_t)nc, 1);
    ff[3] = 1;      /* a fixed fine dof (an odd node's second component) */
    fc[0] = 1;      /* a fixed coarse dof */
    sb_galerkin *G;
    CHECK_EQ_INT(sb_galerkin_create(&S, pf, pc, ff, fc, &G), 0);
    CHECK_EQ_INT(sb_galerkin_product(G, &Hf, &Hc), 0);
    double maxerr = 0, maxval = 0;
    for (int J = 0; J < nc; J++)
        for (int K = J; K < nc; K++) {
            double ref = 0;
            if (!fc[J] && !fc[K])
                for (int i = 0; i < nf; i++)
                    for (int j = 0; j < nf; j++)
                        if (!ff[i] && !ff[j]) ref += Sd[i * nc + J] * H[i * nf + j] * Sd[j * nc + K];
            double got = 0;
            for (long q = pc->colptr[K]; q < pc->colptr[K + 1]; q++)
                if (pc->rowind[q] == J) got = Hc.val[q];
            if (fabs(got - ref) > maxerr) maxerr = fabs(got - ref);
            if (fabs(ref) > maxval) maxval = fabs(ref);
        }
    CHECK(maxval > 0.1);
    CHECK_MSG(maxerr < 1e-14, "max |S^T H S - dense| = %.3g", maxerr);
    /* the fixed arrays are read at each product: release the dof, entries appear */
    fc[0] = 0;
    CHECK_EQ_INT(sb_galerkin_product(G, &Hf, &Hc), 0);
    CHECK(Hc.val[pc->diag[0]] != 0.0);
    sb_galerkin_free(G);
    /* a diagonal-block coarse pattern cannot hold the product: refused at set-up */
    G = NULL;
    CHECK_EQ_INT(sb_galerkin_create(&S, pf, pdiag, NULL, NULL, &G), SB_ERR_UNSUPPORTED);
    CHECK(G == NULL);
    sb_csr_free(&S);
    sb_matrix_free(&Hf); sb_matrix_free(&Hc);
    sb_pattern_free(pf); sb_pattern_free(pc); sb_pattern_free(pdiag);
    free(H); free(Sd); free(ff); free(fc);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(pattern_bs1), SB_CASE(pattern_bs3), SB_CASE(pattern_bs12), SB_CASE(pattern_two_byte_map),
        SB_CASE(pattern_four_byte_map_on_a_star), SB_CASE(cholmod_solve_and_not_posdef),
        SB_CASE(params_validation), SB_CASE(schwarz_preconditioner), SB_CASE(galerkin_product), SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
