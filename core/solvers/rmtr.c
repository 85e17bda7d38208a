/* rmtr.c — recursive multilevel trust region (RMTR paper Alg. 4.2 with the
 * radius update of Alg. 4.3), generic over any method with a nested level
 * hierarchy (prolongation I, restriction R = I^T, projection P).
 *
 * One iterate() is one V-cycle on the finest level L.  On level l < L the
 * model is the coarse objective with the first-order coupling term
 *     h^l(x) = f^l(x) + <dg^l, x - x0^l>,  dg^l = R g^{l+1} - grad f^l(x0^l)   (Eq. 4.3-4.4)
 * so that grad h^l(x0^l) = R g^{l+1}                                             (Eq. 4.5).
 * Smoothing: mu1 / mu2 trust-region steps with Steihaug–Toint CG on every
 * level but the coarsest, where the subproblem is solved by dogleg with
 * CHOLMOD.  The paper (§7.3) runs 10 CG iterations per smoothing step
 * (smoother_cg_iter=10, smoother_rtol=0).  ASSUMPTION (ours, the default):
 * CG stops at a tenfold residual reduction, ||r|| <= 0.1 ||g||, or at 200
 * iterations, so the smoothing keeps pace with the conditioning of the level
 * (Fig. 9: cond(H) grows like h^-4); with a fixed 10 iterations the
 * V-cycle's contraction near a solution degrades from level to level
 * (docs/rmtr.md "Smoother stopping rule").
 *
 * Assumptions where the paper is silent or ambiguous (docs/rmtr.md):
 *  - Alg. 4.3 line 4 as printed ("if ||x_i - x_0||_l > (1-eps) Delta^{l+1}
 *    then delta = Delta^{l+1} - ||x_i - x_0||_l", delta = 0 otherwise)
 *    contradicts §4.3.1, which says delta is zero when the condition is NOT
 *    met because no further correction fits.  We implement the reading that
 *    keeps the coarse iterates inside the fine radius (Gratton et al. 2008):
 *    delta = Delta^{l+1} - ||x_i - x_0||_l while ||x_i - x_0||_l <= (1-eps)
 *    Delta^{l+1}, else 0 (the level stops).
 *  - The level norm (4.9) ||I...I s||_2 is evaluated exactly (by prolongation
 *    to the finest level) for the radius bound; inside the subproblem solver
 *    the Euclidean norm on level l is used with the radius divided by
 *    c_l = ||I_l^L 1|| / ||1|| (exact for constant corrections), so no
 *    fine-level work is done per CG iteration.
 *  - Each level's radius starts from the finer level's radius at the time of
 *    the recursive call (Alg. 4.2 line 4); the finest radius persists across
 *    V-cycles and is reset to Delta_0 at the start of every time step.
 *  - Coarse gradient tolerance eps_g^l = solver.gtol_coarse on every level.
 *  - solver.coarse_model (not in the paper): "nonlinear" is Eq. 4.3-4.4;
 *    "galerkin" replaces f^l by the quadratic model with the Galerkin Hessian
 *        h^l(x0 + d) = <R g^{l+1}, d> + 1/2 d^T (R H^{l+1} I) d
 *    (Gratton, Sartenaer & Toint 2008, cited by the paper as [24]), with
 *    H^L the finest Hessian assembled at the iterate the recursion starts
 *    from; "corrected" keeps the coarse objective and adds the second-order
 *    correction, h^l = f^l + <dg, d> + 1/2 d^T (R H^{l+1} I - H^l(x0)) d, so
 *    that its Hessian at x0 is the Galerkin one; "auto" (default) is galerkin
 *    when the product fits every coarse sparsity pattern
 *    (sb_problem_galerkin_prepare), else nonlinear.
 *  - solver.coarse_radius (not in the paper; default "fine", the paper's):
 *    "own" gives the top level a second radius for its coarse corrections.
 *    The coarse level then starts from, and is bounded by (Eq. 4.7-4.8),
 *    max(own radius, fine radius) instead of the fine radius; the own radius
 *    follows the multilevel ratio (4.11) with the rules of Alg. 4.3 lines
 *    1-3, the fine radius the smoothing steps only.  Reason: in the
 *    nonconvex first step of the hard scenes the fine radius settles at about
 *    one element, and under the paper's rule the coarse corrections are held
 *    to it too (docs/rmtr.md "Coarse radius").  ASSUMPTION: the own radius
 *    starts at Delta_0 whenever the fine one does (every step, every level of
 *    the nested start); acceptance still needs rho > eta1.
 *  - solver.nested (not in the paper; default: the first step of a run):
 *    nested iteration over the levels before the finest V-cycles, see
 *    promote(); its V-cycles on coarser top levels are outer iterations
 *    reported with their level (docs/rmtr.md "Nested start").
 *  - solver.krylov (not in the paper; default off): finest-level trust-region
 *    steps by Steihaug–Toint CG preconditioned by one linear V-cycle of the
 *    same hierarchy, see krylov_iterate() and docs/krylov.md. */
#include "sb_solver.h"
#include "sb_trs.h"
#include "sb_krylov.h"
#include "sb_context.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const coarse_model_names[] = { "auto", "nonlinear", "galerkin", "corrected", NULL };
enum { MODEL_AUTO = 0, MODEL_NONLINEAR = 1, MODEL_GALERKIN = 2, MODEL_CORRECTED = 3 };
static const char *const coarse_radius_names[] = { "fine", "own", NULL };
static const char *const krylov_names[] = { "off", "auto", "always", NULL };
static const char *const krylov_boundary_names[] = { "vcycle", "krylov", NULL };
enum { KRYLOV_OFF = 0, KRYLOV_AUTO = 1, KRYLOV_ALWAYS = 2 };
enum { KRYLOV_BOUNDARY_VCYCLE = 0, KRYLOV_BOUNDARY_KRYLOV = 1 };

static const sb_param_def rmtr_params[] = {
    { "eta1", SB_PARAM_REAL, 0.1, 0, 1, NULL, "accept when rho > eta1 (RMTR paper Table 2)" },
    { "eta2", SB_PARAM_REAL, 0.75, 0, 1, NULL, "enlarge when rho > eta2 (Table 2)" },
    { "gamma1", SB_PARAM_REAL, 0.5, 1e-6, 1, NULL, "shrink factor (Table 2)" },
    { "gamma2", SB_PARAM_REAL, 2.0, 1, 1e6, NULL, "enlarge factor (Table 2)" },
    { "delta0", SB_PARAM_REAL, 1.0, 1e-300, 1e300, NULL, "initial finest radius of every step (Table 2)" },
    { "mu1", SB_PARAM_INT, 1, 0, 100, NULL, "pre-smoothing steps (Table 2)" },
    { "mu2", SB_PARAM_INT, 1, 0, 100, NULL, "post-smoothing steps (Table 2)" },
    { "eps_delta", SB_PARAM_REAL, 1e-3, 0, 1, NULL, "epsilon^Delta of Alg. 4.3 (Table 2)" },
    { "smoother_cg_iter", SB_PARAM_INT, 200, 1, 1e6, NULL,
      "at most this many Steihaug–Toint CG iterations per smoothing step (paper §7.3: 10, with smoother_rtol=0)" },
    { "coarse_trs", SB_PARAM_CHOICE, 0, 0, 0, sb_trs_names, "coarsest-level subproblem solver (§7.3: dogleg)" },
    { "indefinite", SB_PARAM_CHOICE, 1, 0, 0, sb_trs_indefinite_names,
      "coarsest-level dogleg on an indefinite Hessian: shift or cauchy (the paper's configuration)" },
    { "smoother_rtol", SB_PARAM_REAL, 0.1, -1, 1, NULL,
      "ST-CG smoother stops at ||r|| <= smoother_rtol ||g|| (-1: inexact-Newton forcing min(0.5, sqrt||g||); 0: always smoother_cg_iter iterations, the paper's)" },
    { "smoother_precond", SB_PARAM_CHOICE, 4, 0, 0, sb_trs_precond_names,
      "ST-CG smoother preconditioner: schwarz (additive Schwarz on element patches), none (the paper's), jacobi, block (node-block Jacobi), sgs (symmetric block Gauss-Seidel)" },
    { "coarse_model", SB_PARAM_CHOICE, 0, 0, 0, coarse_model_names,
      "coarse models: nonlinear (the coarse objective + first-order term, Eq. 4.3-4.4, the paper's), galerkin "
      "(quadratic with the Galerkin Hessian I^T H I: second-order consistent), corrected (nonlinear + "
      "1/2 d^T (I^T H I - H^l(x0)) d: second-order consistent, keeps the coarse nonlinearity) or auto (galerkin "
      "where every coarse pattern holds I^T H I, else nonlinear; the record's solver_info says which)" },
    { "gtol_coarse", SB_PARAM_REAL, 1e-7, 0, 1e10, NULL, "eps_g^l: stop smoothing on a level when ||grad h^l|| is below" },
    { "nested", SB_PARAM_INT, 1, 0, 2, NULL,
      "nested-iteration start (not in the paper): solve the step on levels 0..1, prolongate the correction, "
      "solve on 0..2, ... and start the finest V-cycles from there; 0 off, 1 the first step of the run (the start "
      "from rest), 2 every step; coarse V-cycles are recorded with their level" },
    { "nested_gtol", SB_PARAM_REAL, 1e-4, 0, 1e10, NULL,
      "nested start: a coarse top level is solved until ||grad f^l|| < nested_gtol" },
    { "nested_max_iter", SB_PARAM_INT, 1000, 1, 1e9, NULL, "nested start: at most this many V-cycles per coarse top level" },
    { "coarse_radius", SB_PARAM_CHOICE, 0, 0, 0, coarse_radius_names,
      "radius of the top level's coarse corrections (not in the paper's choice): fine (Alg. 4.2 line 4: the fine "
      "radius, the paper's) or own (a radius of their own, updated by the multilevel ratio Eq. 4.11, never below "
      "the fine one)" },
    { "krylov", SB_PARAM_CHOICE, 0, 0, 0, krylov_names,
      "Krylov acceleration (issue 38, not in the paper; docs/krylov.md): off (plain V-cycles), auto (once a V-cycle's "
      "correction lies inside half the finest radius, finest-level Steihaug-Toint CG preconditioned by one symmetric "
      "linear V-cycle, back to V-cycles on the boundary, negative curvature, a capped or a rejected step) or always "
      "(every finest-level iteration is such a step)" },
    { "krylov_max_iter", SB_PARAM_INT, 200, 1, 1e6, NULL, "Krylov acceleration: at most this many CG iterations per step" },
    { "krylov_rtol", SB_PARAM_REAL, 0.1, -1, 0.5, NULL,
      "Krylov acceleration: CG stops at ||H s + g|| <= krylov_rtol ||g|| (default 0.1, measured: docs/krylov.md); "
      "-1: Eisenstat-Walker forcing (choice 2)" },
    { "krylov_boundary", SB_PARAM_CHOICE, 0, 0, 0, krylov_boundary_names,
      "Krylov acceleration, auto: after an accepted Krylov step that ended on the trust-region boundary with rho > "
      "eta2 (the radius grew), vcycle goes back to the V-cycles, krylov takes another Krylov step" },
    { "krylov_sweeps", SB_PARAM_INT, 1, 1, 20, NULL,
      "Krylov acceleration: block Gauss-Seidel sweeps before (forward) and after (backward) each coarse correction" },
    { NULL, 0, 0, 0, 0, NULL, NULL }
};

typedef struct rlevel {
    int n;
    double *x0, *x, *g, *dg, *s, *xt, *tmp, *gt;
    double *d, *hd;      /* Galerkin models: x - x0 and H (x - x0) */
    double *xs;          /* nested start: the step's start projected to this level */
    sb_matrix E;         /* corrected models: R H^{l+1} I - H^l(x0) (coarse pattern) */
    double f;            /* h^l(x) */
    double ared_sum;     /* h^l(x0) - h^l(x): sum of the accepted steps' actual reductions */
    double delta;
    double cnorm;        /* c_l: norm scaling of the level to the finest space */
    sb_trs trs;
    int fresh;           /* H or g changed since the last subproblem solve */
    int hess_ok;         /* H holds the Hessian at x (assembled lazily, see local_tr) */
} rlevel;

typedef struct rmtr_state {
    int nl, L;
    double *fa, *fb;          /* finest-level scratch for the level-norm bound */
    double eta1, eta2, gamma1, gamma2, delta0, eps_delta, gtol;
    int mu1, mu2, cg_iter;
    int galerkin;             /* coarse models are quadratic with H^l = R H^{l+1} I */
    int corrected;            /* coarse objective + first- and second-order corrections */
    int model_param;          /* MODEL_* as requested */
    int precond;              /* smoother preconditioner (index into sb_trs_precond_names) */
    rlevel lv[SB_MAX_LEVELS];
    int nested;               /* nested-iteration start (solver.nested: 0 off, 1 first step, 2 every step) */
    int L_fine;               /* the finest level; R->L is the current top, < L_fine while nesting */
    int top_cycles;           /* V-cycles run on the current top level */
    int top_stalled;          /* of them, the last ones in a row at the top level's round-off limit */
    double xtol_rel;          /* run.xtol_rel: that limit, relative to ||x|| */
    int stall_iter;           /* run.stall_iter: so many of them end a coarse top level */
    int nested_max;
    double nested_gtol;
    double cn[SB_MAX_LEVELS][SB_MAX_LEVELS];   /* cn[top][l]: c_l of level l when `top` is the finest */
    double consistency_err;   /* max relative |grad h^l(x0) - R g^{l+1}| seen (Eq. 4.5) */
    int own_coarse_radius;    /* solver.coarse_radius = own */
    double dc;                /* the top level's coarse-correction radius (own) */
    /* solver.krylov (issue 38): finest-level Steihaug-Toint CG preconditioned
     * by one symmetric linear V-cycle (sb_precond_mg.c), see krylov_iterate() */
    int kmode;                /* KRYLOV_* */
    int kr_alloc;             /* kr holds workspaces */
    sb_krylov kr;
    int k_max;                /* CG iterations per step */
    double k_rtol;            /* fixed relative tolerance, < 0: Eisenstat-Walker */
    double k_eta, k_gprev;    /* the forcing term and the ||g|| it was taken at */
    int k_next;               /* auto: the next finest iteration is a Krylov step */
    int k_boundary_krylov;    /* solver.krylov_boundary = krylov */
    int k_setup;              /* the preconditioner was set up for the current finest Hessian */
} rmtr_state;

enum { COARSE_UNUSABLE = 100 };   /* internal: a coarse level could not build its model */

double sb_rmtr_consistency_error(const void *state) { return ((const rmtr_state *)state)->consistency_err; }

static void rmtr_free(void *st)
{
    rmtr_state *R = st;
    free(R->fa);
    free(R->fb);
    for (int l = 0; l < R->nl; l++) {
        rlevel *V = &R->lv[l];
        free(V->x0); free(V->x); free(V->g); free(V->dg); free(V->s); free(V->xt); free(V->tmp); free(V->gt);
        free(V->d); free(V->hd); free(V->xs);
        sb_matrix_free(&V->E);
        sb_trs_free(&V->trs);
    }
    if (R->kr_alloc) sb_krylov_free(&R->kr);
}

/* ||I_l^L v||_2 (free dofs) for v in lv[l].tmp; uses the tmp of finer levels */
static int prolonged_norm(rmtr_state *R, sb_problem *p, int l, double *out)
{
    const double *cur = R->lv[l].tmp;
    for (int k = l; k < R->L; k++) {
        int rc = sb_problem_prolong(p, k, cur, R->lv[k + 1].tmp);
        if (rc) return rc;
        cur = R->lv[k + 1].tmp;
    }
    *out = sb_problem_norm(p, R->L, cur);
    return SB_OK;
}

/* out = I_l^L v (finest level), through the tmp vectors of the levels */
static int prolong_to_finest(rmtr_state *R, sb_problem *p, int l, const double *v, double *out)
{
    sb_copy(R->lv[l].n, v, R->lv[l].tmp);
    const double *cur = R->lv[l].tmp;
    for (int k = l; k < R->L; k++) {
        int rc = sb_problem_prolong(p, k, cur, R->lv[k + 1].tmp);
        if (rc) return rc;
        cur = R->lv[k + 1].tmp;
    }
    sb_copy(R->lv[R->L].n, cur, out);
    return SB_OK;
}

/* Eq. (4.7)-(4.8): scale a coarse step s so that the prolongated iterate
 * correction I(x + tau s - x0) stays inside the fine radius `bound`; returns
 * tau in (0, 1] (1 when s already fits).  Exact in the level norm (4.9). */
static int fit_in_bound(rmtr_state *R, sb_problem *p, int l, double bound, double *tau)
{
    rlevel *V = &R->lv[l];
    const int nf = R->lv[R->L].n;
    *tau = 1.0;
    for (int i = 0; i < V->n; i++) V->xt[i] = V->x[i] - V->x0[i];
    int rc = prolong_to_finest(R, p, l, V->xt, R->fa);
    if (!rc) rc = prolong_to_finest(R, p, l, V->s, R->fb);
    if (rc) return rc;
    sb_problem_constrain(p, R->L, R->fa);
    sb_problem_constrain(p, R->L, R->fb);
    double aa = sb_dot(nf, R->fa, R->fa), ab = sb_dot(nf, R->fa, R->fb), bb = sb_dot(nf, R->fb, R->fb);
    if (aa + 2 * ab + bb <= bound * bound || bb <= 0) return SB_OK;
    /* largest root of bb tau^2 + 2 ab tau + (aa - bound^2) = 0 */
    double disc = ab * ab + bb * (bound * bound - aa);
    double t = (-ab + sqrt(disc > 0 ? disc : 0)) / bb;
    *tau = t > 0 ? (t < 1 ? t : 1) : 0;
    return SB_OK;
}

/* c_l = ||I_l^L 1|| / ||1|| (free dofs) */
static int level_norm_scale(rmtr_state *R, sb_problem *p, int l, double *out)
{
    rlevel *V = &R->lv[l];
    for (int i = 0; i < V->n; i++) V->tmp[i] = 1.0;
    sb_problem_constrain(p, l, V->tmp);
    double n0 = sb_problem_norm(p, l, V->tmp), nf;
    int rc = prolonged_norm(R, p, l, &nf);
    *out = n0 > 0 && nf > 0 ? nf / n0 : 1.0;
    return rc;
}

static int rmtr_alloc(void *st, sb_problem *p, const sb_paramset *ps)
{
    rmtr_state *R = st;
    R->nl = sb_problem_levels(p);
    R->L = R->nl - 1;
    if (!sb_problem_has_hierarchy(p))
        return sb_error(sb_problem_context(p), SB_ERR_UNSUPPORTED, "rmtr needs at least two levels of a hierarchy");
    R->eta1 = sb_param(ps, "solver.eta1");
    R->eta2 = sb_param(ps, "solver.eta2");
    R->gamma1 = sb_param(ps, "solver.gamma1");
    R->gamma2 = sb_param(ps, "solver.gamma2");
    R->delta0 = sb_param(ps, "solver.delta0");
    R->eps_delta = sb_param(ps, "solver.eps_delta");
    R->mu1 = sb_param_int(ps, "solver.mu1");
    R->mu2 = sb_param_int(ps, "solver.mu2");
    R->cg_iter = sb_param_int(ps, "solver.smoother_cg_iter");
    R->gtol = sb_param(ps, "solver.gtol_coarse");
    R->model_param = sb_param_int(ps, "solver.coarse_model");
    R->galerkin = R->model_param == MODEL_GALERKIN || R->model_param == MODEL_AUTO;
    R->corrected = R->model_param == MODEL_CORRECTED;
    R->precond = sb_param_int(ps, "solver.smoother_precond");
    const sb_trs_type *coarse = sb_trs_by_index(sb_param_int(ps, "solver.coarse_trs"));
    for (int l = 0; l < R->nl; l++) {
        rlevel *V = &R->lv[l];
        V->n = sb_problem_n(p, l);
        size_t b = (size_t)V->n * sizeof(double);
        V->x0 = malloc(b); V->x = malloc(b); V->g = malloc(b); V->dg = calloc(1, b);
        V->s = malloc(b); V->xt = malloc(b); V->tmp = malloc(b); V->gt = malloc(b);
        V->d = malloc(b); V->hd = malloc(b); V->xs = malloc(b);
        if (!V->x0 || !V->x || !V->g || !V->dg || !V->s || !V->xt || !V->tmp || !V->gt || !V->d || !V->hd || !V->xs)
            return SB_ERR_NOMEM;
        int rc = sb_trs_alloc(&V->trs, l == 0 ? coarse : &sb_trs_stcg, V->n);
        if (rc) return rc;
        sb_trs_set_cg_rtol(&V->trs, sb_param(ps, "solver.smoother_rtol"));
        sb_trs_set_cg_precond(&V->trs, sb_param_int(ps, "solver.smoother_precond"));
        sb_trs_set_shift_indefinite(&V->trs, sb_param_int(ps, "solver.indefinite"));
    }
    R->fa = malloc((size_t)R->lv[R->L].n * sizeof(double));
    R->fb = malloc((size_t)R->lv[R->L].n * sizeof(double));
    if (!R->fa || !R->fb) return SB_ERR_NOMEM;
    R->nested = R->L >= 2 ? sb_param_int(ps, "solver.nested") : 0;
    R->nested_gtol = sb_param(ps, "solver.nested_gtol");
    R->nested_max = sb_param_int(ps, "solver.nested_max_iter");
    R->xtol_rel = sb_param(ps, "run.xtol_rel");
    R->stall_iter = sb_param_int(ps, "run.stall_iter");
    R->own_coarse_radius = sb_param_int(ps, "solver.coarse_radius") == 1;
    R->L_fine = R->L;
    /* c_l for every top level a nested start can run on (R->L is the top) */
    for (int top = R->nested ? 1 : R->L; top <= R->L_fine; top++) {
        R->L = top;
        for (int l = 0; l <= top; l++) {
            int rc = level_norm_scale(R, p, l, &R->cn[top][l]);
            if (rc) return rc;
        }
    }
    for (int l = 0; l < R->nl; l++) R->lv[l].cnorm = R->cn[R->L][l];
    /* Galerkin products (I^T H I) for the galerkin and corrected models */
    for (int l = 0; (R->galerkin || R->corrected) && l < R->L; l++) {
        int rc = sb_problem_galerkin_prepare(p, l);
        if (rc == SB_ERR_UNSUPPORTED && R->model_param == MODEL_AUTO) {
            /* auto: this hierarchy's coarse patterns cannot hold I^T H I */
            sb_context *ctx = sb_problem_context(p);
            ctx->status = SB_OK;
            ctx->err[0] = '\0';
            R->galerkin = 0;
            break;
        }
        if (!rc && R->corrected) rc = sb_matrix_init(&R->lv[l].E, sb_problem_hessian(p, l)->pat);
        if (rc) return rc;
    }
    R->kmode = sb_param_int(ps, "solver.krylov");
    if (R->kmode != KRYLOV_OFF) {
        /* the V-cycle preconditioner over all levels of the hierarchy; its
         * alloc refuses a hierarchy without Galerkin products (with a sentence) */
        R->k_max = sb_param_int(ps, "solver.krylov_max_iter");
        R->k_rtol = sb_param(ps, "solver.krylov_rtol");
        R->k_boundary_krylov = sb_param_int(ps, "solver.krylov_boundary") == KRYLOV_BOUNDARY_KRYLOV;
        sb_precond_opts o = { .mg_sweeps = sb_param_int(ps, "solver.krylov_sweeps"), .mg_lag = 1, .amg_strength = 0.5 };
        sb_context *kctx = sb_problem_context(p);
        for (int l = 0; l < R->L_fine; l++)
            if (sb_problem_galerkin_prepare(p, l))
                return sb_error(kctx, SB_ERR_UNSUPPORTED, "solver.krylov=%s needs Galerkin coarse operators I^T H I on "
                                "every level (its preconditioner is a V-cycle of them), but the pattern of level %d of "
                                "method %s cannot hold them: use solver.krylov=off with this method",
                                krylov_names[R->kmode], l, sb_problem_method_type(p)->name);
        R->kr_alloc = 1;
        int rc = sb_krylov_alloc(&R->kr, p, R->L_fine, &sb_precond_mg, &o);
        if (rc) {
            sb_context *ctx = sb_problem_context(p);
            char msg[sizeof ctx->err];
            snprintf(msg, sizeof msg, "%s", ctx->err);
            return sb_error(ctx, rc, "solver.krylov=%s: %s", krylov_names[R->kmode], msg);
        }
    }
    return SB_OK;
}

/* h^l(x) (and its gradient / Hessian); Eq. (4.3), or with Galerkin models
 * (l < L) the quadratic h^l(x) = <gc, d> + 1/2 d^T H^l d, d = x - x0, whose
 * Hessian H^l = R H^{l+1} I was set on entering the level */
static int h_eval(rmtr_state *R, sb_problem *p, int l, const double *x, double *f, double *g, int hess)
{
    rlevel *V = &R->lv[l];
    if (R->galerkin && l < R->L) {
        for (int i = 0; i < V->n; i++) V->d[i] = x[i] - V->x0[i];
        sb_problem_hess_mult(p, l, V->d, V->hd);
        double lin = 0, quad = 0;
        for (int i = 0; i < V->n; i++) {
            lin += V->dg[i] * V->d[i];
            quad += V->d[i] * V->hd[i];
        }
        *f = lin + 0.5 * quad;
        if (g)
            for (int i = 0; i < V->n; i++) g[i] = V->dg[i] + V->hd[i];
        return isfinite(*f) ? SB_OK : SB_NONFINITE;
    }
    int rc = sb_problem_eval(p, l, x, f, g, hess ? sb_problem_hessian(p, l) : NULL);
    if (rc < 0) return rc;
    if (l < R->L) {
        double lin = 0;
        for (int i = 0; i < V->n; i++) lin += V->dg[i] * (x[i] - V->x0[i]);
        *f += lin;
        if (g) sb_axpy(V->n, 1.0, V->dg, g);
        if (R->corrected) {
            /* + 1/2 d^T E d: the model's Hessian at x0 is the Galerkin one */
            for (int i = 0; i < V->n; i++) V->d[i] = x[i] - V->x0[i];
            sb_matrix_symv(&V->E, V->d, V->hd);
            *f += 0.5 * sb_dot(V->n, V->d, V->hd);
            if (g) sb_axpy(V->n, 1.0, V->hd, g);
            if (hess) sb_matrix_axpy(sb_problem_hessian(p, l), 1.0, &V->E);
        }
    }
    return rc;
}

/* ||x - x0||_l, Eq. (4.9): the correction prolongated to the finest level */
static int level_norm(rmtr_state *R, sb_problem *p, int l, const double *x, double *out)
{
    rlevel *V = &R->lv[l];
    for (int i = 0; i < V->n; i++) V->tmp[i] = x[i] - V->x0[i];
    return prolonged_norm(R, p, l, out);
}

/* Alg. 4.3 (see the header for the reading of line 4). */
static int radius_update(rmtr_state *R, sb_problem *p, int l, double rho, double bound)
{
    rlevel *V = &R->lv[l];
    double d = V->delta;
    double dplus = rho < R->eta1 ? R->gamma1 * d : rho > R->eta2 ? R->gamma2 * d : d;
    if (dplus > 1e300) dplus = 1e300;   /* keep the radius finite (the paper's radius is unbounded) */
    if (l == R->L || !isfinite(bound)) {
        V->delta = dplus;
        return SB_OK;
    }
    double nrm;
    int rc = level_norm(R, p, l, V->x, &nrm);
    if (rc) return rc;
    double delta = nrm <= (1.0 - R->eps_delta) * bound ? bound - nrm : 0.0;
    V->delta = fmin(dplus, delta);
    return SB_OK;
}

/* rho of the trial point V->xt = V->x + V->s with h^l(xt) = ft and predicted
 * reduction pred (Eq. 4.2 / 4.11); from gradients when f - ft is round-off.
 * *have_gt = 1 when V->gt then holds grad h^l(xt). */
static int trial_ratio(rmtr_state *R, sb_problem *p, int l, int trial_rc, double ft, double pred, double *rho,
                       int *have_gt)
{
    rlevel *V = &R->lv[l];
    *have_gt = 0;
    *rho = sb_tr_ratio(trial_rc, V->f, ft, pred);
    if (trial_rc != SB_OK || !sb_tr_ared_unreliable(V->f, ft, pred)) return SB_OK;
    double f2;
    int rc = h_eval(R, p, l, V->xt, &f2, V->gt, 0);
    if (rc < 0) return rc;
    *have_gt = rc == SB_OK;
    *rho = rc == SB_OK ? sb_tr_ratio_grad(V->n, V->g, V->gt, V->s, pred) : -INFINITY;
    return SB_OK;
}

/* h^l at the trial point V->xt = V->x + V->s and its ratio against the
 * predicted reduction pred.  A Galerkin level l < L is a quadratic that is
 * its own model, and the next coarser model is its exact restriction
 * (h^{l-1}(x0 + d) = h^l(x + I d) - h^l(x)), so rho = 1 there by
 * construction: it is set, not computed from a difference of nearly equal
 * values; only the finest level's ratio carries information. */
static int ratio_of_trial(rmtr_state *R, sb_problem *p, int l, double pred, double *ft, double *rho, int *have_gt)
{
    rlevel *V = &R->lv[l];
    *have_gt = 0;
    if (R->galerkin && l < R->L) {
        *ft = V->f - pred;
        *rho = pred > 0 && isfinite(pred) ? 1.0 : -INFINITY;
        return SB_OK;
    }
    int rc = h_eval(R, p, l, V->xt, ft, NULL, 0);
    if (rc < 0) return rc;
    return trial_ratio(R, p, l, rc, *ft, pred, rho, have_gt);
}

/* Move to the accepted trial point V->xt (h^l = ft there): f and g at the new
 * x, from trial_ratio's gradient when it has one; the Hessian is stale. */
static int accept_trial(rmtr_state *R, sb_problem *p, int l, double ft, int have_gt)
{
    rlevel *V = &R->lv[l];
    sb_copy(V->n, V->xt, V->x);
    if (R->galerkin && l < R->L) {
        /* a quadratic model's Hessian is constant: only g changed (unless a
         * new H is still waiting for its first subproblem solve) */
        V->hess_ok = 1;
        V->fresh = V->fresh == 1 ? 1 : 1 | SB_TRS_SAME_H;
    } else {
        V->hess_ok = 0;
        V->fresh = 1;
    }
    if (have_gt) {
        V->f = ft;
        sb_copy(V->n, V->gt, V->g);
        return SB_OK;
    }
    int rc = h_eval(R, p, l, V->x, &V->f, V->g, 0);
    return rc < 0 ? rc : rc == SB_NONFINITE ? SB_NONFINITE : SB_OK;
}

/* Local_TR (Alg. 4.1) with mu steps on level l; bound = Delta^{l+1} */
static int local_tr(rmtr_state *R, sb_problem *p, int l, int mu, double bound, int *lin_iters)
{
    rlevel *V = &R->lv[l];
    const int max_cg = l == 0 ? 0 : R->cg_iter;
    for (int it = 0; it < mu; it++) {
        /* coarse levels stop at eps_g^l; the finest level's stopping is the core loop's (Eq. 7.1) */
        if (V->delta <= 0.0 || (l < R->L && sb_problem_norm(p, l, V->g) <= R->gtol)) break;
        int rc;
        if (!V->hess_ok) {
            /* the Hessian is assembled only when a subproblem needs it: after an
             * accepted step only the gradient is formed, since the next use of
             * the point may be a restriction or a coarse correction */
            if ((rc = h_eval(R, p, l, V->x, &V->f, V->g, 1)) < 0) return rc;
            V->hess_ok = 1;
            V->fresh = 1;
        }
        sb_trs_result tr;
        rc = sb_trs_solve(&V->trs, p, l, V->g, V->delta / V->cnorm, V->fresh, max_cg, V->s, &tr);
        if (rc < 0) return rc;
        V->fresh = 0;
        *lin_iters += tr.iters;
        if (l < R->L && isfinite(bound)) {
            double tau, gs = sb_dot(V->n, V->g, V->s);
            if ((rc = fit_in_bound(R, p, l, bound, &tau))) return rc;
            if (tau < 1.0) {
                /* m(tau s) from g^T s and s^T H s = -2 (pred + g^T s) */
                double sHs = -2.0 * (tr.pred + gs);
                sb_scal(V->n, tau, V->s);
                tr.pred = -(tau * gs + 0.5 * tau * tau * sHs);
            }
        }
        {
            /* contact step filter (docs/contact.md): shorten a step that would
             * carry a sample point of this level into an obstacle, m(tau s) as above */
            double tau = sb_problem_step_bound(p, l, V->x, V->s);
            if (tau < 1.0) {
                double gs = sb_dot(V->n, V->g, V->s), sHs = -2.0 * (tr.pred + gs);
                sb_scal(V->n, tau, V->s);
                tr.pred = -(tau * gs + 0.5 * tau * tau * sHs);
            }
        }
        for (int i = 0; i < V->n; i++) V->xt[i] = V->x[i] + V->s[i];
        double ft, rho;
        int have_gt = 0;
        if ((rc = ratio_of_trial(R, p, l, tr.pred, &ft, &rho, &have_gt))) return rc;
        if (rho > R->eta1) {
            V->ared_sum += rho * tr.pred;      /* = f - ft when that difference is reliable */
            if ((rc = accept_trial(R, p, l, ft, have_gt))) return rc;
        }
        if ((rc = radius_update(R, p, l, rho, bound))) return rc;
    }
    return SB_OK;
}

/* Alg. 4.2 on level l.  On entry V->x0 holds the initial iterate, V->delta its
 * radius; for l < L, gc holds R g^{l+1}.  On exit V->x is the result. */
static int rmtr_level(rmtr_state *R, sb_problem *p, int l, const double *gc, double bound, int *lin_iters,
                      int *accepted_coarse)
{
    rlevel *V = &R->lv[l];
    int rc;
    sb_copy(V->n, V->x0, V->x);
    V->ared_sum = 0.0;
    if (l < R->L && R->galerkin) {
        /* Galerkin model: h^l(x0 + d) = <R g^{l+1}, d> + 1/2 d^T (R H^{l+1} I) d,
         * first- and second-order consistent (Gratton, Sartenaer & Toint 2008) */
        if ((rc = sb_problem_galerkin_hessian(p, l))) return rc;
        sb_copy(V->n, gc, V->dg);
        sb_copy(V->n, gc, V->g);
        V->f = 0.0;
        V->hess_ok = 1;
        V->fresh = 1;
    } else if (l < R->L) {
        /* line 1: dg = R g^{l+1} - grad f^l(x0) (Eq. 4.4) */
        memset(V->dg, 0, (size_t)V->n * sizeof(double));
        sb_matrix *H = sb_problem_hessian(p, l);
        if (R->corrected) {
            /* E = R H^{l+1} I - H^l(x0): second-order consistency of the
             * corrected model h^l = f^l + <dg, d> + 1/2 d^T E d */
            if ((rc = sb_problem_galerkin_hessian(p, l))) return rc;
            memcpy(V->E.val, H->val, (size_t)H->pat->nnz * sizeof(double));
        }
        rc = sb_problem_eval(p, l, V->x, &V->f, V->g, R->corrected ? H : NULL);
        V->hess_ok = 0;
        if (rc < 0) return rc;
        if (R->corrected && rc == SB_OK) {
            sb_matrix_axpy(&V->E, -1.0, H);
            sb_matrix_axpy(H, 1.0, &V->E);     /* H holds the model Hessian at x0 */
            V->hess_ok = 1;
        }
        /* the projected iterate may be inadmissible on this level (a coarse
         * surface through projected control points can exceed the material's
         * admissible strain): no coarse model, the finer level goes on without
         * a correction */
        if (rc == SB_NONFINITE) return COARSE_UNUSABLE;
        for (int i = 0; i < V->n; i++) V->dg[i] = gc[i] - V->g[i];
        /* first-order consistency check (Eq. 4.5) through the model evaluation itself */
        rc = h_eval(R, p, l, V->x, &V->f, V->g, 0);
        if (rc < 0) return rc;
        /* relative to the terms that cancel: dg = gc - grad f is formed in floating point */
        double num = 0, den = 0;
        for (int i = 0; i < V->n; i++) {
            num += (V->g[i] - gc[i]) * (V->g[i] - gc[i]);
            den += gc[i] * gc[i] + V->dg[i] * V->dg[i];
        }
        double e = den > 0 ? sqrt(num / den) : sqrt(num);
        if (e > R->consistency_err) R->consistency_err = e;
        V->fresh = 1;
    }
    /* line 2: pre-smoothing */
    if ((rc = local_tr(R, p, l, R->mu1, bound, lin_iters))) return rc;
    if (l > 0) {
        rlevel *C = &R->lv[l - 1];
        if ((R->galerkin || R->corrected) && !V->hess_ok) {
            /* the Galerkin coarse Hessian needs this level's Hessian at x */
            if ((rc = h_eval(R, p, l, V->x, &V->f, V->g, 1)) < 0) return rc;
            if (rc == SB_NONFINITE) return rc;
            V->hess_ok = 1;
            V->fresh = 1;
        }
        /* line 4: recursion from P x, with R grad h^l and the current radius */
        if ((rc = sb_problem_project(p, l - 1, V->x, C->x0))) return rc;
        /* R grad h^l goes to C->xt: read only at the coarse level's entry */
        if ((rc = sb_problem_restrict(p, l - 1, V->g, C->xt))) return rc;
        /* the coarse level starts from, and is bounded by, the fine radius
         * (Alg. 4.2 line 4), or on the top level with coarse_radius = own by
         * the coarse corrections' own radius, never below the fine one */
        const int own = l == R->L && R->own_coarse_radius;
        const double cb = own ? fmax(R->dc, V->delta) : V->delta;
        C->delta = cb;
        rc = rmtr_level(R, p, l - 1, C->xt, cb, lin_iters, accepted_coarse);
        if (rc == COARSE_UNUSABLE) goto post_smoothing;
        if (rc) return rc;
        /* coarse reduction h^{l-1}(x0) - h^{l-1}(x_end) (denominator of Eq. 4.11),
         * summed over the coarse level's accepted steps: the same telescoping
         * sum as the difference of the end values, but each term is the step's
         * own actual reduction — from gradients where f - f_trial is round-off
         * (sb_tr_ared_unreliable) — so it stays meaningful near the solution */
        double cred = C->ared_sum;
        /* line 5: prolongate the correction (Eq. 4.10) */
        for (int i = 0; i < C->n; i++) C->tmp[i] = C->x[i] - C->x0[i];
        if ((rc = sb_problem_prolong(p, l - 1, C->tmp, V->s))) return rc;
        for (int i = 0; i < V->n; i++) V->xt[i] = V->x[i] + V->s[i];
        /* line 6: multilevel ratio (Eq. 4.11) */
        double ft, rho = -INFINITY;
        int have_gt = 0;
        /* contact step filter (docs/contact.md): a prolongated correction that
         * would carry a fine sample point into an obstacle is rejected like a
         * failed ratio test (its coarse reduction is not that of a shortened step) */
        if (sb_problem_step_bound(p, l, V->x, V->s) >= 1.0 &&
            (rc = ratio_of_trial(R, p, l, cred, &ft, &rho, &have_gt)))
            return rc;
        if (rho > R->eta1) {                    /* lines 7-8 */
            V->ared_sum += rho * cred;
            if ((rc = accept_trial(R, p, l, ft, have_gt))) return rc;
            if (l == R->L) (*accepted_coarse)++;
        }
        if (own)   /* the standard update (Alg. 4.3 lines 1-3) of the coarse radius; the fine one stays */
            R->dc = fmin(rho < R->eta1 ? R->gamma1 * cb : rho > R->eta2 ? R->gamma2 * cb : cb, 1e300);
        else if ((rc = radius_update(R, p, l, rho, bound))) return rc;   /* line 12 */
        if (l < R->L && sb_problem_norm(p, l, V->g) <= R->gtol) return SB_OK;   /* lines 13-14 */
    }
post_smoothing:
    /* line 17: post-smoothing */
    return local_tr(R, p, l, R->mu2, bound, lin_iters);
}

/* Make `top` the finest level of the V-cycles (a nested start runs them on
 * the levels 0..top < L_fine first): the level norms (4.9) end at `top`. */
static void set_top(rmtr_state *R, int top)
{
    R->L = top;
    R->top_cycles = 0;
    R->top_stalled = 0;
    for (int l = 0; l <= top; l++) R->lv[l].cnorm = R->cn[top][l];
}

/* Start V-cycles on the top level from V->x: f, g (and H when hess) there,
 * radius Delta_0 (Table 2). */
static int start_top(rmtr_state *R, sb_problem *p, int hess)
{
    rlevel *V = &R->lv[R->L];
    V->delta = R->delta0;
    R->dc = R->delta0;
    int rc = sb_problem_eval(p, R->L, V->x, &V->f, V->g, hess ? sb_problem_hessian(p, R->L) : NULL);
    V->fresh = 1;
    V->hess_ok = hess;
    return rc;
}

/* Nested start (solver.nested; not in the paper, the classical nested
 * iteration of multigrid): the step's start x_s is projected to every level
 * (x_s^l = P x_s^{l+1}, prescribed values imposed); the step's own problem on
 * level l (f^l with the step data distributed to the level, §6) is solved by
 * V-cycles on the levels 0..l, and its correction is prolongated as the
 * start of level l+1:  x^{l+1} = x_s^{l+1} + I (x^l - x_s^l).  A prolongated
 * start that is not admissible or not lower than x_s^{l+1} is dropped
 * (ASSUMPTION: the nested start must never make a level's start worse). */
static int promote(rmtr_state *R, sb_problem *p, double *x)
{
    const int lc = R->L, lf = lc + 1;
    rlevel *C = &R->lv[lc], *F = &R->lv[lf];
    int rc;
    double fs = F->f;           /* f^{L_fine}(x_s), from rmtr_set */
    if (lf < R->L_fine) {
        rc = sb_problem_eval(p, lf, F->xs, &fs, NULL, NULL);
        if (rc < 0) return rc;
        if (rc == SB_NONFINITE) fs = INFINITY;
    }
    for (int i = 0; i < C->n; i++) C->tmp[i] = C->x[i] - C->xs[i];
    if ((rc = sb_problem_prolong(p, lc, C->tmp, F->s))) return rc;
    for (int i = 0; i < F->n; i++) F->x[i] = F->xs[i] + F->s[i];
    sb_problem_impose(p, lf, F->x);
    set_top(R, lf);
    rc = start_top(R, p, 1);
    if (rc < 0) return rc;
    if (rc == SB_NONFINITE || !(F->f < fs)) {
        sb_copy(F->n, F->xs, F->x);
        if ((rc = start_top(R, p, 1)) < 0) return rc;
    }
    if (rc == SB_NONFINITE && lf < R->L_fine) {
        /* the projected start is not admissible on this level either: the
         * finest level starts from the step's own start, as without nesting */
        F = &R->lv[R->L_fine];
        set_top(R, R->L_fine);
        sb_copy(F->n, F->xs, F->x);
        if ((rc = start_top(R, p, 1)) < 0) return rc;
    }
    if (R->L == R->L_fine) sb_copy(F->n, F->x, x);
    return rc;
}

static int rmtr_set(void *st, sb_problem *p, const double *x, sb_iterate_info *info)
{
    rmtr_state *R = st;
    set_top(R, R->L_fine);
    rlevel *V = &R->lv[R->L];
    sb_copy(V->n, x, V->x);
    R->k_next = R->k_setup = 0;     /* every step starts with V-cycles, the forcing afresh */
    R->k_eta = R->k_gprev = 0.0;
    const int nested = R->nested == 2 || (R->nested == 1 && sb_problem_step(p) <= 1);
    /* with a nested start the finest Hessian is first needed at the prolongated start */
    int rc = start_top(R, p, !nested);
    info->f = V->f;
    info->gnorm = sb_problem_norm(p, R->L, V->g);
    info->delta = V->delta;
    if (rc != SB_OK || !nested) return rc;
    sb_copy(V->n, x, V->xs);
    for (int l = R->L_fine - 1; l >= 1; l--) {
        if ((rc = sb_problem_project(p, l, R->lv[l + 1].xs, R->lv[l].xs))) return rc;
        sb_problem_impose(p, l, R->lv[l].xs);
    }
    set_top(R, 1);
    sb_copy(R->lv[1].n, R->lv[1].xs, R->lv[1].x);
    rc = start_top(R, p, 1);
    if (rc == SB_NONFINITE) {
        /* the projected start is not admissible on level 1: no nested start
         * (the finest level's start above is untouched) */
        set_top(R, R->L_fine);
        return SB_OK;
    }
    return rc;
}

/* Krylov acceleration (solver.krylov, issue 38; not in the RMTR paper).
 * One finest-level trust-region iteration (Alg. 4.1 with the radius update
 * of Alg. 4.3 lines 1-3, Delta^{L+1} = infinity on the finest level) whose
 * subproblem  min g^T s + 1/2 s^T H s, ||s||_2 <= Delta  is solved by
 * Steihaug–Toint CG (Steihaug 1983, Toint 1981; Nocedal & Wright Alg. 7.2)
 * preconditioned by one linear V-cycle B over the same hierarchy: Galerkin
 * coarse operators I^T H I (the Hessians of the Galerkin coarse models of
 * Gratton, Sartenaer & Toint 2008 at the same point), forward block
 * Gauss–Seidel before and backward after the coarse correction, CHOLMOD on
 * the coarsest level (sb_precond_mg.c).  B is symmetric, and positive
 * definite when H is (R^{-1} + R^{-T} - H = D, Xu & Zikatanov 2002), so CG
 * stays valid; where it is not (indefinite H), CG restarts without it
 * (sb_krylov.c, recorded) and negative curvature ends the step on the
 * boundary as Steihaug–Toint does.
 *
 * Why: after the nonconvex start of the hard scenes the V-cycles are a
 * stationary linear multigrid iteration on a nearly singular Hessian (rho ~ 1,
 * radius inactive, ||g|| x 0.97 per V-cycle, docs/rmtr.md); the few soft
 * modes behind that rate are what a Krylov method around the same V-cycle
 * removes in a few iterations (Saad, Iterative Methods, §13.1 on
 * multigrid as a preconditioner).
 *
 * ASSUMPTIONS (the paper is silent, docs/krylov.md):
 *  - the trust region is Euclidean in the finest dofs (the level norm 4.9 at
 *    l = L); the preconditioner does not change the norm (sb_krylov.c);
 *  - CG stops at ||H s + g|| <= eta ||g||, eta = solver.krylov_rtol (0.1;
 *    -1: the Eisenstat–Walker forcing term, choice 2, of the current ||g||),
 *    or at solver.krylov_max_iter iterations: the truncated step is judged by
 *    the ratio test like any other (recorded as krylov_status 1).  Why 0.1
 *    and not Eisenstat–Walker (measured, docs/krylov.md): in the nonconvex
 *    phases ||g|| rises and falls, choice 2 sits at 0.5-0.9, and a step of
 *    one or two CG iterations (a preconditioned gradient step) mostly ends
 *    on the boundary; at 0.1 the hard scenes took 18-24 % fewer finest
 *    iterations and 20-30 % fewer CG iterations at 3 and 4 levels;
 *  - a rejected Krylov step sets Delta = gamma1 min(Delta, ||s||) (Conn,
 *    Gould & Toint, Trust-Region Methods, §17.1 allow any Delta+ <= gamma1
 *    Delta): the finest radius of the V-cycles is often far larger than
 *    any step (inactive), and halving it alone would take hundreds of
 *    rejections before a boundary step of Steihaug–Toint fits;
 *  - auto: a Krylov step follows a finest V-cycle whose correction was
 *    accepted and lay inside half its radius (the criterion of
 *    has_correction, radius inactive), and another Krylov step follows a
 *    Krylov step that was accepted and ended inside the radius with CG
 *    converged (with solver.krylov_boundary = krylov also one accepted on
 *    the boundary with rho > eta2, measured in docs/krylov.md); anything
 *    else (boundary, negative curvature, cap, rejection) returns to the
 *    V-cycles, whose coarse corrections handle the nonconvex phases.  Every
 *    step starts with V-cycles. */
static int krylov_iterate(rmtr_state *R, sb_problem *p, double *x, sb_iterate_info *info)
{
    const int L = R->L;
    rlevel *V = &R->lv[L];
    const int n = V->n;
    int rc;
    if (!V->hess_ok) {
        if ((rc = h_eval(R, p, L, V->x, &V->f, V->g, 1)) < 0) return rc;
        V->hess_ok = 1;
        V->fresh = 1;
        R->k_setup = 0;
    }
    const double gnorm = sb_problem_norm(p, L, V->g);
    if (!R->k_setup) {
        /* the preconditioner of the Hessian at x (coarse Galerkin operators,
         * block inverses, coarsest factor), once per iterate; the forcing
         * term of this iterate, kept while its steps are rejected */
        R->k_eta = R->k_rtol >= 0.0 ? R->k_rtol : sb_forcing_ew2(gnorm, R->k_gprev, R->k_eta);
        R->k_gprev = gnorm;
        if ((rc = sb_krylov_setup(&R->kr, p)) < 0) return rc;
        R->k_setup = 1;
    }
    const double t0 = sb_now();
    sb_krylov_result kr;
    rc = sb_krylov_solve(&R->kr, p, V->g, V->delta, R->k_eta, R->k_max, V->s, &kr);
    sb_problem_count_qp(p, L, sb_now() - t0);
    if (rc < 0) return rc;
    double pred = kr.pred, snorm = kr.snorm;
    int interior = kr.status == SB_KRYLOV_CONVERGED;
    {
        /* contact step filter (docs/contact.md), m(tau s) as in local_tr */
        double tau = sb_problem_step_bound(p, L, V->x, V->s);
        if (tau < 1.0) {
            double gs = sb_dot(n, V->g, V->s), sHs = -2.0 * (pred + gs);
            sb_scal(n, tau, V->s);
            pred = -(tau * gs + 0.5 * tau * tau * sHs);
            snorm *= tau;
            interior = 0;
        }
    }
    for (int i = 0; i < n; i++) V->xt[i] = V->x[i] + V->s[i];
    /* Eq. (4.2); from gradients where f - f_trial is round-off (the Krylov
     * paths' test, sb_krylov_f_noise, as tr.c) */
    double ft;
    int have_gt = 0;
    rc = h_eval(R, p, L, V->xt, &ft, NULL, 0);
    if (rc < 0) return rc;
    double rho = sb_tr_ratio(rc, V->f, ft, pred);
    if (rc == SB_OK && (sb_krylov_f_noise(V->f, ft, pred) || sb_tr_ared_unreliable(V->f, ft, pred))) {
        double f2;
        rc = h_eval(R, p, L, V->xt, &f2, V->gt, 0);
        if (rc < 0) return rc;
        have_gt = rc == SB_OK;
        rho = rc == SB_OK ? sb_tr_ratio_grad(n, V->g, V->gt, V->s, pred) : -INFINITY;
    }
    const double f_old = V->f, delta_old = V->delta;
    int accepted = 0;
    if (rho > R->eta1) {
        if ((rc = accept_trial(R, p, L, ft, have_gt)) < 0) return rc;
        if (rc == SB_NONFINITE) info->fail = SB_REASON_NONFINITE;
        accepted = 1;
        R->k_setup = 0;
    }
    /* Alg. 4.3 lines 1-3 on the finest level (see the assumption on rejection) */
    if (rho < R->eta1) V->delta = R->gamma1 * fmin(V->delta, snorm > 0 ? snorm : V->delta);
    else if (rho > R->eta2) V->delta = fmin(R->gamma2 * V->delta, 1e300);
    R->k_next = accepted && (interior || (R->k_boundary_krylov && kr.status == SB_KRYLOV_BOUNDARY && rho > R->eta2));
    info->level = L;
    info->f = V->f;
    info->df = accepted ? f_old - V->f : 0.0;
    info->accepted = accepted;
    info->step_norm = accepted ? snorm : 0.0;
    info->rho = 0;                   /* no coarse corrections in this iteration */
    info->gnorm = sb_problem_norm(p, L, V->g);
    info->delta = V->delta;
    info->linear_iters = kr.iters;
    info->linear_rtol = R->k_eta;
    info->linear_status = (int)kr.status;
    info->has_correction = interior && snorm < 0.5 * delta_old;
    info->correction = snorm;
    sb_copy(n, V->x, x);
    return SB_OK;
}

static int rmtr_iterate(void *st, sb_problem *p, double *x, sb_iterate_info *info)
{
    rmtr_state *R = st;
    if (R->L == R->L_fine && (R->kmode == KRYLOV_ALWAYS || (R->kmode == KRYLOV_AUTO && R->k_next)))
        return krylov_iterate(R, p, x, info);
    const int top = R->L;
    rlevel *V = &R->lv[top];
    double f_old = V->f, delta_old = V->delta;
    /* the top level keeps f, g, H of x from the previous cycle (h^L = f^L) */
    sb_copy(V->n, V->x, V->x0);
    int lin = 0, acc = 0;
    int rc = rmtr_level(R, p, top, NULL, INFINITY, &lin, &acc);
    if (rc < 0) return rc;
    double sn = 0;
    for (int i = 0; i < V->n; i++) sn += (V->x[i] - V->x0[i]) * (V->x[i] - V->x0[i]);
    info->level = top;
    info->step_norm = sqrt(sn);
    info->f = V->f;
    info->df = f_old - V->f;
    info->accepted = sn > 0;
    info->rho = acc;                 /* number of accepted coarse corrections on the top level */
    info->gnorm = sb_problem_norm(p, top, V->g);
    info->delta = V->delta;
    info->linear_iters = lin;
    /* a V-cycle correction well inside the cycle's radius was not limited by
     * it (ASSUMPTION for the limiting-accuracy test, sb_solve.c: the steps of
     * the cycle are then as the model asked) */
    info->has_correction = sn > 0 && info->step_norm < 0.5 * delta_old;
    info->correction = info->step_norm;
    if (R->kmode != KRYLOV_OFF) {
        /* the V-cycle overwrote the coarse Hessians and the coarsest factor
         * the preconditioner lives in; auto: a Krylov step next when the
         * radius was inactive (see krylov_iterate) */
        R->k_setup = 0;
        R->k_next = top == R->L_fine && rc == SB_OK && info->has_correction;
    }
    if (top == R->L_fine) {
        if (rc == SB_NONFINITE) info->fail = SB_REASON_NONFINITE;
        sb_copy(V->n, V->x, x);
        return SB_OK;
    }
    /* a V-cycle of the nested start: move up when the level is solved, out of
     * cycles, or failed (then with the last admissible iterate) */
    R->top_cycles++;
    /* ... or when it is at its round-off limit: run.stall_iter cycles in a
     * row whose accepted correction, or (rejected) whose radius, is below
     * run.xtol_rel ||x^l||, as the finest level's stalled test (sb_solve.c).
     * ASSUMPTION (issue 42): the level is then solved as far as it can be.
     * The absolute nested_gtol alone is not reachable on every level: the
     * penalty's gradient beta (x - b) has a round-off floor near
     * beta eps ||x||, and beta ~ h^-5 (cc_penalty.c); the simply supported
     * plate at res 256 on 6 levels spent the whole iteration cap on level 1
     * (res 16) at ||g|| ~ 2.5e-4 with a radius of 1e-13. */
    const double xl = sb_norm2(V->n, V->x);
    const int tiny = (info->accepted ? info->step_norm : V->delta) <= R->xtol_rel * xl;
    R->top_stalled = tiny ? R->top_stalled + 1 : 0;
    const int stalled = R->xtol_rel > 0 && R->stall_iter > 0 && R->top_stalled >= R->stall_iter;
    if (rc == SB_NONFINITE || info->gnorm < R->nested_gtol || R->top_cycles >= R->nested_max || stalled) {
        rc = promote(R, p, x);
        if (rc < 0) return rc;
        if (rc == SB_NONFINITE) info->fail = SB_REASON_NONFINITE;
    }
    return SB_OK;
}

static void rmtr_describe(const void *st, char *buf, size_t len)
{
    const rmtr_state *R = st;
    snprintf(buf, len, "%d levels; coarse models %s%s; smoother mu1=%d mu2=%d x %d ST-CG (%s); coarsest dogleg; "
             "nested start: %s; coarse radius %s",
             R->nl, R->galerkin ? "galerkin (I^T H I)" : R->corrected ? "corrected (Eq. 4.3-4.4 + 1/2 d^T (I^T H I - H^l) d)"
             : "nonlinear (Eq. 4.3-4.4)",
             R->model_param == MODEL_AUTO ? " (auto)" : "", R->mu1, R->mu2, R->cg_iter, sb_trs_precond_names[R->precond],
             R->nested == 2 ? "every step" : R->nested == 1 ? "first step" : "off",
             R->own_coarse_radius ? "own" : "fine");
    if (R->kmode != KRYLOV_OFF) {
        size_t k = strlen(buf);
        char kd[512], rt[32];
        sb_krylov_describe(&R->kr, kd, sizeof kd);
        if (R->k_rtol >= 0) snprintf(rt, sizeof rt, "%g", R->k_rtol);
        else snprintf(rt, sizeof rt, "Eisenstat-Walker");
        if (k < len)
            snprintf(buf + k, len - k, "; Krylov acceleration %s: finest-level Steihaug-Toint %s, at most %d CG "
                     "iterations, rtol %s", krylov_names[R->kmode], kd, R->k_max, rt);
    }
}

const sb_solver_type sb_solver_rmtr = {
    "rmtr", "recursive multilevel trust region V-cycles, RMTR paper Alg. 4.2 + 4.3 (needs a hierarchy)",
    sizeof(rmtr_state), rmtr_params, SB_SOLVER_TRUST_REGION | SB_SOLVER_NEEDS_HIERARCHY,
    rmtr_alloc, rmtr_set, rmtr_iterate, rmtr_free, rmtr_describe,
    NULL,   /* the lifting factors with CHOLMOD (its coarsest level does too) */
};
