/* sb_trs.c — the two trust-region subproblem solvers and the counted wrapper. */
#include "sb_trs.h"
#include "sb_precond.h"
#include "sb_context.h"
#include "sb_schwarz.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const sb_trs_names[] = { "dogleg", "stcg", NULL };
const char *const sb_trs_indefinite_names[] = { "cauchy", "shift", NULL };
const char *const sb_trs_precond_names[] = { "none", "jacobi", "block", "sgs", "schwarz", NULL };

const sb_trs_type *sb_trs_by_index(int i) { return i == 1 ? &sb_trs_stcg : &sb_trs_dogleg; }

int sb_trs_alloc(sb_trs *t, const sb_trs_type *type, int n)
{
    t->type = type;
    t->state = calloc(1, type->state_size);
    if (!t->state) return SB_ERR_NOMEM;
    int rc = type->alloc(t->state, n);
    if (rc) {
        type->free(t->state);
        free(t->state);
        t->state = NULL;
    }
    return rc;
}

void sb_trs_free(sb_trs *t)
{
    if (t->state) {
        t->type->free(t->state);
        free(t->state);
    }
    t->state = NULL;
}

int sb_trs_solve(sb_trs *t, sb_problem *p, int level, const double *g, double delta, int fresh,
                 int max_iter, double *s, sb_trs_result *r)
{
    double t0 = sb_problem_clock(p);
    memset(r, 0, sizeof *r);
    int rc = t->type->solve(t->state, p, level, g, delta, fresh, max_iter, s, r);
    sb_problem_count_qp_since(p, level, t0);
    return rc;
}

double sb_tr_ratio(int trial_status, double f, double f_trial, double pred)
{
    if (trial_status != SB_OK || !isfinite(f_trial) || !(pred > 0.0)) return -INFINITY;
    double ared = f - f_trial;
    double noise = 100.0 * DBL_EPSILON * fmax(fabs(f), fabs(f_trial));
    if (fabs(ared) <= noise && pred <= noise) return 1.0;
    return ared / pred;
}

int sb_tr_ared_unreliable(double f, double f_trial, double pred)
{
    return isfinite(f_trial) && pred > 0.0 && pred <= 1e4 * DBL_EPSILON * fmax(fabs(f), fabs(f_trial));
}

double sb_tr_ratio_grad(int n, const double *g, const double *g_trial, const double *s, double pred)
{
    if (!(pred > 0.0) || !sb_all_finite(n, g_trial)) return -INFINITY;
    double ared = -0.5 * (sb_dot(n, g, s) + sb_dot(n, g_trial, s));
    return ared / pred;
}

/* Step to the boundary: largest tau >= 0 with ||z + tau d|| = delta. */
static double to_boundary(int n, const double *z, const double *d, double delta)
{
    double dd = sb_dot(n, d, d), zd = sb_dot(n, z, d), zz = sb_dot(n, z, z);
    if (dd <= 0.0) return 0.0;
    double disc = zd * zd + dd * (delta * delta - zz);
    if (disc < 0.0) disc = 0.0;
    /* numerically stable root of dd tau^2 + 2 zd tau + (zz - delta^2) = 0 */
    if (zd <= 0.0) return (-zd + sqrt(disc)) / dd;
    return (delta * delta - zz) / (zd + sqrt(disc));
}

/* ------------------------------------------------------------------ dogleg */
typedef struct dogleg_state {
    int n;
    double *sn;     /* Newton point -H^{-1} g (when H is PD) */
    double *sc;     /* Cauchy point along -g (unconstrained minimizer on the ray) */
    double *hg;     /* H g */
    double gHg, gg;
    int have_newton;
    int factor_rc;          /* status of the last factorization (-1: none yet) */
    int shift_indefinite;   /* 1: Newton point of H + tau I when H is indefinite */
    double shift;           /* tau of the last factorization */
} dogleg_state;

static int dogleg_alloc(void *st, int n)
{
    dogleg_state *d = st;
    d->n = n;
    d->factor_rc = -1;
    d->sn = malloc((size_t)n * sizeof(double));
    d->sc = malloc((size_t)n * sizeof(double));
    d->hg = malloc((size_t)n * sizeof(double));
    return d->sn && d->sc && d->hg ? SB_OK : SB_ERR_NOMEM;
}

static void dogleg_free(void *st)
{
    dogleg_state *d = st;
    free(d->sn);
    free(d->sc);
    free(d->hg);
}

static double model_reduction(sb_problem *p, int level, const double *g, const double *s, double *tmp)
{
    int n = sb_problem_n(p, level);
    sb_problem_hess_mult(p, level, s, tmp);
    return -(sb_dot(n, g, s) + 0.5 * sb_dot(n, s, tmp));
}

/* Dogleg (Nocedal & Wright, Numerical Optimization, §4.1; RMTR paper §7.3):
 * the Newton point by a sparse direct solve when H is positive definite,
 * otherwise the Cauchy point (safe for indefinite H: along -g to the
 * boundary when g^T H g <= 0).  With shift_indefinite (solver option
 * "indefinite=shift", not in the paper) an indefinite H gives instead the
 * Newton point of H + tau I, tau = 1e-8 max|H_ij| grown 10x until the
 * factorization succeeds (Nocedal & Wright Alg. 3.3); the predicted
 * reduction is always that of the true model, so the ratio test stays exact. */
static int dogleg_solve(void *st, sb_problem *p, int level, const double *g, double delta, int fresh,
                        int max_iter, double *s, sb_trs_result *r)
{
    (void)max_iter;
    dogleg_state *d = st;
    const int n = d->n;
    if (fresh) {
        sb_problem_hess_mult(p, level, g, d->hg);
        d->gg = sb_dot(n, g, g);
        d->gHg = sb_dot(n, g, d->hg);
        d->have_newton = 0;
        int rc = d->factor_rc;
        if (!(fresh & SB_TRS_SAME_H) || rc < 0) {
            /* a new H: factor it (the factor is kept while only g changes) */
            d->shift = 0.0;
            rc = sb_problem_factor(p, level, 0.0);
            if (rc < 0) return rc;
            if (rc == SB_NOT_POSDEF && d->shift_indefinite) {
                double scale = sb_matrix_norm_max(sb_problem_hessian(p, level));
                double tau = 1e-8 * (scale > 0 ? scale : 1.0);
                for (int k = 0; k < 40 && rc == SB_NOT_POSDEF; k++, tau *= 10) {
                    rc = sb_problem_factor(p, level, tau);
                    d->shift = tau;
                }
                if (rc < 0) return rc;
            }
            d->factor_rc = rc;
        }
        if (rc == SB_OK) {
            for (int i = 0; i < n; i++) d->sc[i] = -g[i];
            rc = sb_problem_solve(p, level, d->sc, d->sn);
            if (rc < 0) return rc;
            d->have_newton = rc == SB_OK;
        }
        if (d->gHg > 0.0) {
            double a = d->gg / d->gHg;          /* Cauchy step length, unconstrained */
            for (int i = 0; i < n; i++) d->sc[i] = -a * g[i];
        }
    }
    double gnorm = sqrt(d->gg);
    r->iters = 1;
    r->posdef = d->have_newton;
    if (gnorm == 0.0) {
        memset(s, 0, (size_t)n * sizeof *s);
        r->pred = 0.0;
        return SB_OK;
    }
    double snn = d->have_newton ? sb_norm2(n, d->sn) : INFINITY;
    if (d->have_newton && snn <= delta) {
        sb_copy(n, d->sn, s);
        r->newton = 1;
    } else {
        double scn = d->gHg > 0.0 ? sb_norm2(n, d->sc) : INFINITY;
        if (scn >= delta || !d->have_newton) {
            /* steepest descent to the boundary (or the interior Cauchy point) */
            double a = scn < delta ? 1.0 : delta / gnorm;
            if (scn < delta) sb_copy(n, d->sc, s);
            else for (int i = 0; i < n; i++) s[i] = -a * g[i];
            r->boundary = scn >= delta;
        } else {
            /* dogleg: s = sc + tau (sn - sc) with ||s|| = delta */
            for (int i = 0; i < n; i++) s[i] = d->sn[i] - d->sc[i];
            double tau = to_boundary(n, d->sc, s, delta);
            for (int i = 0; i < n; i++) s[i] = d->sc[i] + tau * s[i];
            r->boundary = 1;
        }
    }
    r->snorm = sb_norm2(n, s);
    /* predicted reduction, exact: -(g^T s + 1/2 s^T H s); hg is free scratch
     * once g^T H g is cached */
    r->pred = model_reduction(p, level, g, s, d->hg);
    return SB_OK;
}

const sb_trs_type sb_trs_dogleg = { "dogleg", sizeof(dogleg_state), dogleg_alloc, dogleg_free, dogleg_solve };

/* ---------------------------------------------------- Steihaug–Toint CG */
typedef struct stcg_state {
    int n;
    double rtol;        /* < 0: forcing term min(0.5, sqrt||g||) */
    int precond;        /* 0 none, 1 Jacobi, 2 block Jacobi, 3 symmetric block Gauss–Seidel */
    int bs;             /* block size of binv (0: not yet allocated) */
    double *r, *d, *Hd, *z, *dinv, *binv, *w;
    const sb_matrix *H; /* the level's Hessian (block Gauss–Seidel sweeps) */
    sb_schwarz schwarz; /* precond 4: additive Schwarz on element patches */
} stcg_state;

/* y_b = Binv_b t for the node block starting at b0 */
static inline void block_solve(int bs, const double *A, const double *t, double *y)
{
    for (int i = 0; i < bs; i++) {
        double v = 0.0;
        for (int j = 0; j < bs; j++) v += A[i * bs + j] * t[j];
        y[i] = v;
    }
}

/* Symmetric block Gauss–Seidel preconditioner z = M^{-1} r with
 * M = (D + L) D^{-1} (D + U), D the node blocks of H, L = U^T the strictly
 * block-lower part: a forward sweep (D + L) y = r, then a backward sweep
 * z = y - D^{-1} U z.  H is stored upper CSC, so the forward sweep reads the
 * column of each dof above its block and the backward sweep scatters each
 * finished block's column into w.  M is SPD when D is, so preconditioned CG
 * keeps its descent properties (Saad, Iterative Methods, §10.2). */
static void sgs_apply(const stcg_state *c, const double *r, double *z)
{
    const int n = c->n, bs = c->bs;
    const sb_pattern *pat = c->H->pat;
    const double *val = c->H->val;
    double t[12], *w = c->w;
    for (int b0 = 0; b0 < n; b0 += bs) {           /* forward: (D + L) z = r */
        for (int j = b0; j < b0 + bs; j++) {
            double v = r[j];
            for (long k = pat->colptr[j]; k < pat->colptr[j + 1]; k++) {
                const int i = pat->rowind[k];
                if (i >= b0) break;
                v -= val[k] * z[i];
            }
            t[j - b0] = v;
        }
        block_solve(bs, c->binv + (size_t)b0 * bs, t, z + b0);
    }
    memset(w, 0, (size_t)n * sizeof *w);
    for (int b0 = n - bs; b0 >= 0; b0 -= bs) {     /* backward: z = y - D^{-1} U z */
        block_solve(bs, c->binv + (size_t)b0 * bs, w + b0, t);
        for (int j = b0; j < b0 + bs; j++) {
            z[j] -= t[j - b0];
            const double zj = z[j];
            for (long k = pat->colptr[j]; k < pat->colptr[j + 1]; k++) {
                const int i = pat->rowind[k];
                if (i >= b0) break;
                w[i] += val[k] * zj;
            }
        }
    }
}

/* z = M^{-1} r for the smoother's preconditioner */
static void stcg_apply(const stcg_state *c, const double *r, double *z)
{
    const int n = c->n;
    if (c->precond == 0) {
        sb_copy(n, r, z);
        return;
    }
    if (c->precond == 3) {
        sgs_apply(c, r, z);
        return;
    }
    if (c->precond == 4) {
        sb_schwarz_apply(&c->schwarz, r, z);
        return;
    }
    if (c->precond == 2) {
        const int bs = c->bs;
        for (int b0 = 0; b0 < n; b0 += bs) {
            const double *A = c->binv + (size_t)b0 * bs;
            for (int i = 0; i < bs; i++) {
                double v = 0.0;
                for (int j = 0; j < bs; j++) v += A[i * bs + j] * r[b0 + j];
                z[b0 + i] = v;
            }
        }
        return;
    }
    for (int i = 0; i < n; i++) z[i] = c->dinv[i] * r[i];
}

static int stcg_setup_precond(stcg_state *c, sb_problem *p, int level)
{
    const int n = c->n;
    if (c->precond == 4) {
        const int rc = sb_problem_element_maps(p, level);
        return rc ? rc : sb_schwarz_setup(&c->schwarz, sb_problem_hessian(p, level));
    }
    sb_problem_hess_diag(p, level, c->dinv);
    for (int i = 0; i < n; i++) c->dinv[i] = c->dinv[i] > 0 ? 1.0 / c->dinv[i] : c->dinv[i] < 0 ? -1.0 / c->dinv[i] : 1.0;
    if (c->precond < 2) return SB_OK;
    const int bs = sb_problem_block_size(p, level);
    if (bs > 12 || n % bs) { c->precond = 1; return SB_OK; }
    if (!c->binv) {
        c->binv = malloc((size_t)n * bs * sizeof(double));
        c->w = malloc((size_t)n * sizeof(double));
        if (!c->binv || !c->w) return SB_ERR_NOMEM;
        c->bs = bs;
    }
    c->H = sb_problem_hessian(p, level);
    sb_problem_hess_block_diag(p, level, c->binv);
    for (int b0 = 0; b0 < n; b0 += bs) {
        double *A = c->binv + (size_t)b0 * bs;
        if (sb_spd_block_inverse(bs, A)) continue;
        /* an indefinite node block: Jacobi on that node */
        memset(A, 0, (size_t)bs * bs * sizeof(double));
        for (int i = 0; i < bs; i++) A[i * bs + i] = c->dinv[b0 + i];
    }
    return SB_OK;
}

static int stcg_alloc(void *st, int n)
{
    stcg_state *c = st;
    c->n = n;
    c->rtol = -1.0;
    c->r = malloc((size_t)n * sizeof(double));
    c->d = malloc((size_t)n * sizeof(double));
    c->Hd = malloc((size_t)n * sizeof(double));
    c->z = malloc((size_t)n * sizeof(double));
    c->dinv = malloc((size_t)n * sizeof(double));
    return c->r && c->d && c->Hd && c->z && c->dinv ? SB_OK : SB_ERR_NOMEM;
}

static void stcg_free(void *st)
{
    stcg_state *c = st;
    free(c->r);
    free(c->d);
    free(c->Hd);
    free(c->z);
    free(c->dinv);
    free(c->binv);
    free(c->w);
    sb_schwarz_free(&c->schwarz);
}

/* Steihaug (1983) / Toint (1981) truncated CG (Nocedal & Wright Alg. 7.2),
 * stopped at max_iter iterations (RMTR paper §7.3: 10 as a smoother), at
 * ||r|| <= rtol ||g|| (rtol < 0: the forcing min(0.5, sqrt||g||); RMTR's
 * smoother default 0.1, docs/rmtr.md "Smoother stopping rule"), at negative
 * curvature or at the boundary.  Starts from s = 0, so without a preconditioner the first iterate
 * is the Cauchy point.  With a preconditioner M (Steihaug's original form)
 * the directions are M-conjugate; ASSUMPTION: the boundary test stays in the
 * Euclidean norm the trust region and RMTR's level norms (Eq. 4.9) use, so
 * ||s_k|| need not grow monotonically and the first crossing is taken. */
static int stcg_solve(void *st, sb_problem *p, int level, const double *g, double delta, int fresh,
                      int max_iter, double *s, sb_trs_result *res)
{
    stcg_state *c = st;
    const int n = c->n;
    double *r = c->r, *d = c->d, *Hd = c->Hd, *z = c->z;
    if (c->precond && fresh && !(fresh & SB_TRS_SAME_H)) {
        int rc = stcg_setup_precond(c, p, level);
        if (rc) return rc;
    }
    memset(s, 0, (size_t)n * sizeof *s);
    sb_copy(n, g, r);
    stcg_apply(c, r, z);
    for (int i = 0; i < n; i++) d[i] = -z[i];
    double rz = sb_dot(n, r, z);
    double rr = sb_dot(n, r, r), g0 = sqrt(rr);
    double tol = c->rtol < 0 ? g0 * fmin(0.5, sqrt(g0)) : g0 * c->rtol;
    int it = 0;
    if (max_iter <= 0) max_iter = n;
    while (it < max_iter && sqrt(rr) > tol) {
        sb_problem_hess_mult(p, level, d, Hd);
        it++;
        double dHd = sb_dot(n, d, Hd);
        if (dHd <= 0.0) {                         /* negative curvature: to the boundary */
            double tau = to_boundary(n, s, d, delta);
            sb_axpy(n, tau, d, s);
            res->boundary = 1;
            break;
        }
        double alpha = rz / dHd;
        /* would leave the region: stop on the boundary */
        double ss = sb_dot(n, s, s), sd = sb_dot(n, s, d), dd = sb_dot(n, d, d);
        if (ss + 2 * alpha * sd + alpha * alpha * dd >= delta * delta) {
            double tau = to_boundary(n, s, d, delta);
            sb_axpy(n, tau, d, s);
            res->boundary = 1;
            break;
        }
        sb_axpy(n, alpha, d, s);
        sb_axpy(n, alpha, Hd, r);
        rr = sb_dot(n, r, r);
        stcg_apply(c, r, z);
        double rz1 = sb_dot(n, r, z);
        double beta = rz1 / rz;
        rz = rz1;
        for (int i = 0; i < n; i++) d[i] = -z[i] + beta * d[i];
    }
    sb_problem_count_cg(p, level, it);
    res->newton = !res->boundary;
    res->iters = it;
    res->snorm = sb_norm2(n, s);
    sb_problem_hess_mult(p, level, s, Hd);
    res->pred = -(sb_dot(n, g, s) + 0.5 * sb_dot(n, s, Hd));
    return SB_OK;
}

const sb_trs_type sb_trs_stcg = { "stcg", sizeof(stcg_state), stcg_alloc, stcg_free, stcg_solve };

void sb_trs_set_shift_indefinite(sb_trs *t, int on)
{
    if (t->type == &sb_trs_dogleg && t->state) ((dogleg_state *)t->state)->shift_indefinite = on;
}

void sb_trs_set_cg_precond(sb_trs *t, int on)
{
    if (t->type == &sb_trs_stcg && t->state) ((stcg_state *)t->state)->precond = on;
}

void sb_trs_set_cg_rtol(sb_trs *t, double rtol)
{
    if (t->type == &sb_trs_stcg && t->state) ((stcg_state *)t->state)->rtol = rtol;
}
