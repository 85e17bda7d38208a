/* sb_krylov.c — preconditioned CG with Steihaug–Toint truncation and the
 * Eisenstat–Walker forcing terms (sb_krylov.h). */
#include "sb_krylov.h"
#include "sb_context.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const sb_linear_names[] = { "cholmod", "pcg-jacobi", "pcg-mg", "pcg-amg", NULL };

int sb_linear_kind(const char *name)
{
    if (!name) return -1;
    if (!strcmp(name, "cholmod")) return SB_LINEAR_CHOLMOD;
    if (!strcmp(name, "pcg")) return SB_LINEAR_PCG_LEGACY;
    if (!strcmp(name, "pcg-jacobi")) return SB_LINEAR_PCG_JACOBI;
    if (!strcmp(name, "pcg-mg")) return SB_LINEAR_PCG_MG;
    if (!strcmp(name, "pcg-amg")) return SB_LINEAR_PCG_AMG;
    return -1;
}

const sb_precond_type *sb_linear_precond(int kind)
{
    switch (kind) {
    case SB_LINEAR_PCG_JACOBI: return &sb_precond_jacobi;
    case SB_LINEAR_PCG_MG: return &sb_precond_mg;
    case SB_LINEAR_PCG_AMG: return &sb_precond_amg;
    default: return NULL;
    }
}

/* Eisenstat & Walker 1996, choice 2 (gamma 0.9, alpha 2) with the
 * safeguards of their §3; floor 1e-10 */
static double forcing_ew2(double ratio, double gprev, double eta_prev)
{
    const double gamma = 0.9, alpha = 2.0, eta_max = 0.9, eta0 = 0.5, eta_min = 1e-10;
    if (!(gprev > 0.0) || !(eta_prev > 0.0)) return eta0;
    double eta = gamma * pow(ratio, alpha);
    double safe = gamma * pow(eta_prev, alpha);
    if (safe > 0.1) eta = fmax(eta, safe);
    eta = fmin(eta, eta_max);
    return fmax(eta, eta_min);
}

double sb_forcing_ew2(double gnorm, double gprev, double eta_prev)
{
    return forcing_ew2(gprev > 0.0 ? gnorm / gprev : 1.0, gprev, eta_prev);
}

/* choice 2 on min(||g_k||/||g_{k-1}||, ||s_{k-1}||/||s_{k-2}||) (sb_krylov.h) */
double sb_forcing_ew2_steps(double gnorm, double gprev, double snorm, double sprev, double eta_prev)
{
    double ratio = gprev > 0.0 ? gnorm / gprev : 1.0;
    if (sprev > 0.0 && snorm >= 0.0) ratio = fmin(ratio, snorm / sprev);
    return forcing_ew2(ratio, gprev, eta_prev);
}

double sb_forcing_floor(double eta, double gnorm, double gstop)
{
    const double eta_max = 0.9;   /* forcing_ew2's */
    if (!(gstop > 0.0) || !(gnorm > 0.0)) return eta;
    return fmax(eta, fmin(eta_max, 0.5 * gstop / gnorm));   /* Kelley (1995) Eq. (6.20) */
}

void sb_noise_floor_reset(sb_noise_floor *nf)
{
    nf->measured = 0;
    nf->level = nf->zeta = 0.0;
}

/* z = M^{-1} r, counted as the preconditioner's work */
static void precond_apply(sb_krylov *k, sb_problem *p, const double *r, double *z)
{
    const double t0 = sb_problem_krylov_begin(p);
    k->type->apply(k->pstate, p, r, z);
    sb_problem_count_krylov(p, k->level, 0, t0);
}

int sb_noise_floor_apply(sb_noise_floor *nf, sb_krylov *k, int have_m, sb_problem *p, const double *x, const double *g,
                         double gnorm, double gstop, double *w_x, double *w_g, double *w_h, double *eta)
{
    if (nf->on && have_m && !nf->measured && *eta < 0.1) {
        nf->measured = 1;
        int rc = sb_problem_gradient_noise(p, k->level, x, g, w_x, w_g, w_h, &nf->level, NULL);
        if (rc < 0) return rc;
        if (rc != SB_OK) nf->level = 0.0;   /* a non-finite neighbour: no level */
        if (nf->level > 0.0) {              /* w_h holds a vector of the level */
            precond_apply(k, p, w_h, k->z);
            nf->zeta = sb_problem_norm(p, k->level, k->z);
        }
    }
    if (nf->on && have_m && nf->zeta > 0.0) {
        precond_apply(k, p, g, k->z);
        const double gm = sb_problem_norm(p, k->level, k->z);
        if (gm > 0.0 && isfinite(gm)) *eta = fmax(*eta, fmin(0.9, 0.5 * nf->zeta / gm));
    }
    *eta = sb_forcing_floor(*eta, gnorm, gstop);
    return SB_OK;
}

int sb_krylov_f_noise(double f, double f_trial, double pred)
{
    const double scale = 1e7 * DBL_EPSILON * fmax(fabs(f), fabs(f_trial));
    return isfinite(f_trial) && pred > 0.0 && pred <= scale && fabs(f_trial - f) <= scale;
}

int sb_krylov_alloc(sb_krylov *k, sb_problem *p, int level, const sb_precond_type *type, const sb_precond_opts *o)
{
    memset(k, 0, sizeof *k);
    k->n = sb_problem_n(p, level);
    k->level = level;
    k->type = type;
    const size_t n = (size_t)k->n;
    k->r = malloc(n * sizeof(double));
    k->z = malloc(n * sizeof(double));
    k->d = malloc(n * sizeof(double));
    k->Hd = malloc(n * sizeof(double));
    k->diag0 = malloc(n * sizeof(double));
    k->pstate = calloc(1, type->state_size);
    if (!k->r || !k->z || !k->d || !k->Hd || !k->diag0 || !k->pstate) return SB_ERR_NOMEM;
    int rc = type->alloc(k->pstate, p, level, o);
    if (rc) {
        type->free(k->pstate);
        free(k->pstate);
        k->pstate = NULL;
    }
    return rc;
}

void sb_krylov_free(sb_krylov *k)
{
    if (k->pstate) {
        k->type->free(k->pstate);
        free(k->pstate);
    }
    free(k->r); free(k->z); free(k->d); free(k->Hd); free(k->diag0);
    memset(k, 0, sizeof *k);
}

int sb_krylov_setup(sb_krylov *k, sb_problem *p)
{
    const double t0 = sb_problem_krylov_begin(p);
    int rc = k->type->setup(k->pstate, p);
    sb_problem_count_krylov(p, k->level, 0, t0);
    return rc;
}

int sb_krylov_shift(sb_krylov *k, sb_problem *p, double shift)
{
    sb_matrix *H = sb_problem_hessian(p, k->level);
    const long *dg = H->pat->diag;
    if (!k->shifted)
        for (int i = 0; i < k->n; i++) k->diag0[i] = H->val[dg[i]];
    for (int i = 0; i < k->n; i++) H->val[dg[i]] = k->diag0[i] + shift;
    k->shifted = 1;
    return SB_OK;
}

void sb_krylov_unshift(sb_krylov *k, sb_problem *p)
{
    if (!k->shifted) return;
    sb_matrix *H = sb_problem_hessian(p, k->level);
    for (int i = 0; i < k->n; i++) H->val[H->pat->diag[i]] = k->diag0[i];
    k->shifted = 0;
}

/* largest tau >= 0 with ||s + tau d|| = delta */
static double to_boundary(int n, const double *s, const double *d, double delta)
{
    double dd = sb_dot(n, d, d), sd = sb_dot(n, s, d), ss = sb_dot(n, s, s);
    if (dd <= 0.0) return 0.0;
    double disc = sd * sd + dd * (delta * delta - ss);
    if (disc < 0.0) disc = 0.0;
    if (sd <= 0.0) return (-sd + sqrt(disc)) / dd;
    return (delta * delta - ss) / (sd + sqrt(disc));
}

int sb_krylov_solve(sb_krylov *k, sb_problem *p, const double *g, double delta, double rtol, int max_iter,
                    double *s, sb_krylov_result *res)
{
    const double t0 = sb_problem_krylov_begin(p);
    const int n = k->n, level = k->level;
    double *r = k->r, *z = k->z, *d = k->d, *Hd = k->Hd;
    const sb_matrix *H = sb_problem_hessian(p, level);
    memset(res, 0, sizeof *res);
    memset(s, 0, (size_t)n * sizeof *s);
    sb_copy(n, g, r);                       /* r = H s + g */
    int precond = 1, rc = SB_OK;
    rc = k->type->apply(k->pstate, p, r, z);
    if (rc < 0) return rc;
    double rz = sb_dot(n, r, z);
    const double g0 = sb_norm2(n, g);
    double rnorm = g0;
    if (!(rz > 0.0) && g0 > 0.0) {
        /* M not positive definite on r: plain CG (a restart) keeps the
         * iteration valid; recorded */
        precond = 0;
        res->precond_restart = 1;
        sb_copy(n, r, z);
        rz = sb_dot(n, r, r);
    }
    for (int i = 0; i < n; i++) d[i] = -z[i];
    const double tol = rtol * g0;
    const int finite_radius = isfinite(delta);
    res->status = SB_KRYLOV_CAP;
    int it = 0;
    if (max_iter <= 0) max_iter = n;
    const int ztest = k->ztol > 0.0;
    double znorm = ztest ? sb_norm2(n, z) : 0.0;
    while (1) {
        if (rnorm <= tol) { res->status = SB_KRYLOV_CONVERGED; break; }
        /* the correction test (after an iteration, so that s is a step;
         * only while z is the preconditioner's: a restart's z = r is no
         * estimate of the error) */
        if (ztest && precond && it > 0 && znorm <= k->ztol) {
            res->status = SB_KRYLOV_CONVERGED;
            res->by_correction = 1;
            break;
        }
        if (it >= max_iter) break;
        sb_matrix_symv(H, d, Hd);
        it++;
        const double dHd = sb_dot(n, d, Hd), dd = sb_dot(n, d, d);
        if (!(dHd > 0.0)) {
            /* negative (or zero) curvature along d */
            res->curvature = dd > 0.0 ? dHd / dd : 0.0;
            res->status = SB_KRYLOV_NEGCURV;
            if (finite_radius) {
                sb_axpy(n, to_boundary(n, s, d, delta), d, s);
                res->status = SB_KRYLOV_BOUNDARY;
            }
            break;
        }
        const double alpha = rz / dHd;
        if (finite_radius) {
            const double ss = sb_dot(n, s, s), sd = sb_dot(n, s, d);
            if (ss + 2 * alpha * sd + alpha * alpha * dd >= delta * delta) {
                sb_axpy(n, to_boundary(n, s, d, delta), d, s);
                res->status = SB_KRYLOV_BOUNDARY;
                break;
            }
        }
        sb_axpy(n, alpha, d, s);
        sb_axpy(n, alpha, Hd, r);
        rnorm = sb_norm2(n, r);
        double beta;
        if (precond) {
            rc = k->type->apply(k->pstate, p, r, z);
            if (rc < 0) return rc;
        } else sb_copy(n, r, z);
        double rz1 = sb_dot(n, r, z);
        if (ztest) znorm = sb_norm2(n, z);
        if (precond && !(rz1 > 0.0) && rnorm > 0.0) {
            precond = 0;
            res->precond_restart = 1;
            sb_copy(n, r, z);
            rz1 = sb_dot(n, r, r);
            beta = 0.0;                       /* restart */
        } else beta = rz1 / rz;
        rz = rz1;
        for (int i = 0; i < n; i++) d[i] = -z[i] + beta * d[i];
    }
    res->iters = it;
    res->znorm = znorm;
    res->relres = g0 > 0.0 ? rnorm / g0 : 0.0;
    res->snorm = sb_norm2(n, s);
    sb_matrix_symv(H, s, Hd);
    res->pred = -(sb_dot(n, g, s) + 0.5 * sb_dot(n, s, Hd));
    sb_problem_count_krylov(p, level, it, t0);
    return SB_OK;
}

void sb_krylov_describe(const sb_krylov *k, char *buf, size_t len)
{
    char pd[400] = "";
    if (k->type->describe && k->pstate) k->type->describe(k->pstate, pd, sizeof pd);
    snprintf(buf, len, "linear solve: %s (CG preconditioned by %s)", k->type->name, pd);
}

int sb_krylov_solve_to(sb_krylov *k, sb_problem *p, const double *g, double rtol, int max_iter, double *s)
{
    int rc = sb_krylov_setup(k, p);
    if (rc) return rc;
    sb_krylov_result res;
    rc = sb_krylov_solve(k, p, g, INFINITY, rtol, max_iter, s, &res);
    return rc ? rc : res.status == SB_KRYLOV_CONVERGED ? SB_OK : SB_NOT_POSDEF;
}
