/* sb_problem.c — the per-step incremental potential on top of a method, with
 * Dirichlet elimination and all event / work-unit counting (sb_problem.h). */
#include "sb_problem.h"
#include "sb_context.h"
#include "sb_galerkin.h"
#include "sb_contact.h"
#include "sb_pin.h"
#include "sb_self.h"
#include "sb_impulse.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A mass matrix held by its nonzeros alone, for a method whose mass is
 * much sparser than the Hessian pattern it is assembled on (linear_fem: its
 * consistent mass couples only the same position component of a
 * triangle's corners, about 7 % of the pattern's entries at 261,251 dofs,
 * docs/solvers.md "Memory").  Columns in the pattern's order, rows
 * ascending within them, the diagonal (when nonzero) last as in the
 * pattern, so the sums below run in the order of the full matrix's. */
typedef struct sparse_mass {
    long *cp;                 /* n+1 */
    void *off;                /* each entry's offset within its column of the level pattern (its row:
                               * the pattern's rowind there), in w bytes: 1, 2 or 4, the fewest that
                               * hold the longest column (sb_pattern_offset_width, sb_offset_get) */
    int w;
    double *val;
} sparse_mass;

typedef struct level_data {
    int n;
    sb_pattern *pat;
    sb_matrix H;              /* Hessian of Phi at the last assembly */
    sb_linsolve *lin;         /* created on first factorization (analysis once) */
    sb_matrix M;              /* mass (dynamic) on the level pattern, unless held as Ms */
    sparse_mass Ms;           /* the mass by its nonzeros (Ms.val != NULL; then M.val == NULL) */
    sb_matrix D;              /* alpha M + beta K(x_n), lagged (dynamic with damping) */
    const sb_dirichlet *bc;
    unsigned char *fixed;     /* n */
    long *zero_pos, n_zero;   /* off-diagonal positions in constrained rows/columns */
    long *diag_pos, n_diag;   /* diagonal positions of constrained dofs */
    double *xhat, *xn;        /* inertia data */
    double *tmp;              /* n */
    sb_galerkin *gal;         /* H = I^T H_{l+1} I (built on first use) */
    sb_contact *contact;      /* barrier + friction of the level (NULL: the scene has no obstacles) */
    sb_pins *pins;            /* sliding pins of the level (NULL: none; sb_pin.h) */
} level_data;

struct sb_problem {
    sb_context *ctx;
    const sb_method_type *mt;
    void *ms;
    const sb_scene *scene;
    int nl;
    int step;                  /* sb_problem_step */
    level_data lv[SB_MAX_LEVELS];
    int dynamic, damping;
    double dt, ray_a, ray_b;
    double *scale_x, *scale_g;  /* sb_problem_force_scale (finest level, allocated on first use) */
    int self;                   /* self-contact on every level (contact.self) */
    int pattern_changed;        /* a level's pattern was replaced (sb_problem_take_pattern_change) */
    /* contact.model "impulse": the finest level's contact sample points,
     * for the end-of-step measurements only (no energy, no filter; issue 37:
     * what the response left between its points) */
    sb_contact *watch;
};

static void mass_free(sparse_mass *S)
{
    free(S->cp); free(S->off); free(S->val);
    memset(S, 0, sizeof *S);
}

static void level_free(sb_problem *p, level_data *L)
{
    (void)p;
    sb_contact_free(L->contact);
    sb_pins_free(L->pins);
    sb_galerkin_free(L->gal);
    sb_linsolve_free(L->lin);
    sb_matrix_free(&L->H);
    sb_matrix_free(&L->M);
    mass_free(&L->Ms);
    sb_matrix_free(&L->D);
    sb_pattern_free(L->pat);
    free(L->fixed);
    free(L->zero_pos);
    free(L->diag_pos);
    free(L->xhat);
    free(L->xn);
    free(L->tmp);
}

void sb_problem_free(sb_problem *p)
{
    if (!p) return;
    for (int l = 0; l < p->nl; l++) level_free(p, &p->lv[l]);
    sb_contact_free(p->watch);
    free(p->scale_x);
    free(p->scale_g);
    free(p);
}

static int level_setup(sb_problem *p, int l);
/* Contact (docs/contact.md): a scene with obstacles adds the barrier and
 * friction of sb_contact to Phi on every level, at the method's sample
 * points; a scene without obstacles builds nothing here (no cost, the same
 * arithmetic as before). */
static int contact_create(sb_problem *p)
{
    const sb_scene *sc = p->scene;
    if (sc->n_obstacles == 0) return SB_OK;
    if (sc->contact.model == SB_CONTACT_IMPULSE) {
        /* the papers' own response after each accepted step (sb_run.c); no
         * barrier terms, the contact objects stay empty */
        if (!p->mt->impulse_response)
            return sb_error(p->ctx, SB_ERR_UNSUPPORTED, "scene %s asks for contact.model \"impulse\" but method %s "
                            "has no impulse-based collision response", sc->name, p->mt->name);
        if (!p->dynamic)
            return sb_error(p->ctx, SB_ERR_UNSUPPORTED, "scene %s asks for contact.model \"impulse\", which acts on "
                            "the velocities of a dynamic scene; a static scene has none (use the barrier)", sc->name);
        if (sc->contact.self && !(p->mt->flags & SB_METHOD_IMPULSE_SELF))
            return sb_error(p->ctx, SB_ERR_UNSUPPORTED, "scene %s asks for self-contact (contact.self) with "
                            "contact.model \"impulse\", but method %s's impulse response handles obstacles only "
                            "(use the barrier model for its self-contact)", sc->name, p->mt->name);
        sb_contact_free(p->watch);
        p->watch = NULL;
        if (p->mt->contact_points) {
            sb_contact_points cp;
            memset(&cp, 0, sizeof cp);
            int rc = p->mt->contact_points(p->ms, p->nl - 1, sc->contact.samples, &cp);
            if (!rc) rc = sb_contact_create(sc, &cp, &p->watch);
            sb_contact_points_free(&cp);
            if (rc) return sb_error(p->ctx, rc < 0 ? rc : SB_ERR_INTERNAL, "method %s: contact sample points failed",
                                    p->mt->name);
        }
        return SB_OK;
    }
    if (!p->mt->contact_points)
        return sb_error(p->ctx, SB_ERR_UNSUPPORTED, "scene %s has obstacles but method %s provides no contact "
                        "sample points", sc->name, p->mt->name);
    for (int l = 0; l < p->nl; l++) {
        sb_contact_points cp;
        memset(&cp, 0, sizeof cp);
        int rc = p->mt->contact_points(p->ms, l, sc->contact.samples, &cp);
        if (!rc) rc = sb_contact_create(sc, &cp, &p->lv[l].contact);
        sb_contact_points_free(&cp);
        if (rc) return rc < 0 ? sb_error(p->ctx, rc, "method %s: contact sample points of level %d failed",
                                         p->mt->name, l)
                              : sb_error(p->ctx, SB_ERR_INTERNAL, "contact set-up of level %d failed", l);
        if (!sc->contact.self) continue;
        /* self-contact (docs/contact.md "Self-contact"): the triangles between
           the sample points, checked at the reference state */
        double *xref = malloc((size_t)p->lv[l].n * sizeof *xref);
        if (!xref) return sb_error(p->ctx, SB_ERR_NOMEM, "out of memory (self-contact)");
        char why[512] = "";
        rc = p->mt->initial(p->ms, l, xref);
        if (!rc) rc = sb_contact_self_setup(p->lv[l].contact, xref, why, sizeof why);
        free(xref);
        if (rc == SB_ERR_UNSUPPORTED)
            return sb_error(p->ctx, rc, "scene %s asks for self-contact (contact.self), which method %s cannot "
                            "honour on level %d: %s", sc->name, p->mt->name, l, why);
        if (rc) return sb_error(p->ctx, rc < 0 ? rc : SB_ERR_INTERNAL, "self-contact set-up of level %d failed", l);
        p->self = 1;
    }
    return SB_OK;
}

/* Sliding pins (sb_pin.h) on every level; none for a scene without them. */
static int pins_create(sb_problem *p)
{
    for (int l = 0; l < p->nl; l++) {
        sb_pins_free(p->lv[l].pins);
        p->lv[l].pins = NULL;
        int rc = sb_pins_create(p->ctx, p->mt, p->ms, p->scene, l, &p->lv[l].pins);
        if (rc) return rc;
    }
    return SB_OK;
}

double sb_problem_pin_violation(const sb_problem *p, const double *x, int *n_pins)
{
    const level_data *L = &p->lv[p->nl - 1];
    *n_pins = sb_pins_count(L->pins);
    return sb_pins_violation(L->pins, x);
}

int sb_problem_create(sb_context *ctx, const sb_method_type *mt, void *ms, const sb_scene *scene,
                      sb_problem **out)
{
    *out = NULL;
    sb_problem *p = calloc(1, sizeof *p);
    if (!p) return sb_error(ctx, SB_ERR_NOMEM, "out of memory creating the problem");
    p->ctx = ctx;
    p->mt = mt;
    p->ms = ms;
    p->scene = scene;
    p->nl = mt->n_levels(ms);
    if (p->nl < 1 || p->nl > SB_MAX_LEVELS) {
        int nl = p->nl;
        free(p);
        return sb_error(ctx, SB_ERR_INTERNAL, "method %s reports %d levels", mt->name, nl);
    }
    p->dynamic = scene->time.mode == SB_TIME_DYNAMIC;
    p->dt = p->dynamic ? scene->time.dt : 0.0;
    p->ray_a = p->dynamic ? scene->time.rayleigh_alpha : 0.0;
    p->ray_b = p->dynamic ? scene->time.rayleigh_beta : 0.0;
    p->damping = p->dynamic && (p->ray_a != 0.0 || p->ray_b != 0.0);
    ctx->stats.n_levels = p->nl;
    int rc = SB_OK;
    for (int l = 0; l < p->nl; l++)
        if ((rc = level_setup(p, l))) goto fail;
    if ((rc = contact_create(p))) goto fail;
    if ((rc = pins_create(p))) goto fail;
    *out = p;
    return SB_OK;
fail:
    sb_problem_free(p);
    return rc;
}

/* After an adaptation (sb_method.h adapt): every level's data built anew
 * from the method's current dofs, pattern, Dirichlet set and mass; the
 * symbolic analysis follows at the next factorization (counted there). */
int sb_problem_rebuild(sb_problem *p)
{
    for (int l = 0; l < p->nl; l++) {
        level_free(p, &p->lv[l]);
        memset(&p->lv[l], 0, sizeof p->lv[l]);
    }
    free(p->scale_x);
    free(p->scale_g);
    p->scale_x = p->scale_g = NULL;
    int rc = SB_OK;
    for (int l = 0; l < p->nl && rc == SB_OK; l++) rc = level_setup(p, l);
    if (rc == SB_OK) rc = contact_create(p);   /* the sample points follow the new mesh */
    if (rc == SB_OK) rc = pins_create(p);
    return rc;
}

/* M by its nonzeros when they are at most half of the pattern's entries
 * (9 bytes an entry, 8 + a 1-byte offset, against 8 for every pattern
 * entry; linear_fem's consistent mass is 7-14 % of its pattern, bhem's a
 * third: a node pair couples the same component of the 4 jets, 48 of 144
 * entries); M is then freed.  Out of memory keeps M as it is. */
static void mass_compact(level_data *L)
{
    const sb_pattern *pat = L->pat;
    long nz = 0;
    for (long q = 0; q < pat->nnz; q++) nz += L->M.val[q] != 0.0;
    if (2 * nz > pat->nnz) return;
    sparse_mass S = { 0 };
    S.w = sb_pattern_offset_width(pat);
    if (!S.w) return;
    S.cp = malloc(((size_t)pat->n + 1) * sizeof *S.cp);
    S.off = malloc((size_t)(nz ? nz : 1) * (size_t)S.w);
    S.val = malloc((size_t)(nz ? nz : 1) * sizeof *S.val);
    if (!S.cp || !S.off || !S.val) { mass_free(&S); return; }
    long k = 0;
    S.cp[0] = 0;
    for (int c = 0; c < pat->n; c++) {
        for (long q = pat->colptr[c]; q < pat->colptr[c + 1]; q++)
            if (L->M.val[q] != 0.0) {
                sb_offset_set(S.off, S.w, k, q - pat->colptr[c]);
                S.val[k++] = L->M.val[q];
            }
        S.cp[c + 1] = k;
    }
    sb_matrix_free(&L->M);
    L->Ms = S;
}

static int mass_built(const level_data *L) { return L->M.val || L->Ms.val; }

int sb_problem_element_maps(sb_problem *p, int level)
{
    const int rc = sb_pattern_ensure_maps(p->lv[level].pat);
    return rc ? sb_error(p->ctx, rc, "%s (element scatter maps of level %d)",
                         rc == SB_ERR_NOMEM ? "out of memory" : "a pattern inconsistent with its elements", level)
              : SB_OK;
}

/* The mass matrix of level l (dynamic scenes), built once at its first use. */
static int level_mass(sb_problem *p, int l)
{
    level_data *L = &p->lv[l];
    if (mass_built(L)) return SB_OK;
    int rc = sb_problem_element_maps(p, l);
    if (rc) return rc;
    if ((rc = sb_matrix_init(&L->M, L->pat))) return sb_error(p->ctx, SB_ERR_NOMEM, "out of memory (mass matrix, level %d)", l);
    if ((rc = p->mt->mass(p->ms, l, &L->M))) {
        sb_matrix_free(&L->M);
        return sb_error(p->ctx, rc < 0 ? rc : SB_ERR_INTERNAL, "method %s: mass matrix of level %d failed", p->mt->name, l);
    }
    mass_compact(L);
    return SB_OK;
}

/* A += alpha M, A on the level pattern */
static void mass_axpy(const level_data *L, sb_matrix *A, double alpha)
{
    if (L->M.val) {
        sb_matrix_axpy(A, alpha, &L->M);
        return;
    }
    const sparse_mass *S = &L->Ms;
    const long *cp = L->pat->colptr;
    for (int c = 0; c < L->n; c++)
        for (long k = S->cp[c]; k < S->cp[c + 1]; k++) A->val[cp[c] + sb_offset_get(S->off, S->w, k)] += alpha * S->val[k];
}

/* dofs, pattern, work arrays and (dynamic) mass of level l */
static int level_setup(sb_problem *p, int l)
{
    sb_context *ctx = p->ctx;
    const sb_method_type *mt = p->mt;
    void *ms = p->ms;
    const sb_scene *scene = p->scene;
    int rc = SB_OK;
    {
        level_data *L = &p->lv[l];
        L->n = mt->n_dofs(ms, l);
        int bs = mt->block_size(ms, l);
        if (L->n <= 0 || bs <= 0 || L->n % bs) {
            rc = sb_error(ctx, SB_ERR_INTERNAL, "method %s: level %d has %d dofs in blocks of %d",
                          mt->name, l, L->n, bs);
            goto fail;
        }
        ctx->stats.n_dofs[l] = L->n;
        sb_pattern_builder *pb = sb_pattern_builder_new(L->n / bs, bs);
        if (!pb) { rc = sb_error(ctx, SB_ERR_NOMEM, "out of memory (pattern)"); goto fail; }
        rc = mt->pattern(ms, l, pb);
        if (rc) { sb_pattern_builder_finish(pb, &L->pat); sb_pattern_free(L->pat); L->pat = NULL; goto fail; }
        /* a coarser level's scatter maps at its first assembly
         * (sb_problem_element_maps): never with lsnewton, tr, damped or
         * linearized, whose coarse matrices are Galerkin products */
        if (l < p->nl - 1) sb_pattern_builder_lazy_maps(pb);
        rc = sb_pattern_builder_finish(pb, &L->pat);
        if (rc) { sb_error(ctx, rc, "building the sparsity pattern of level %d failed", l); goto fail; }
        ctx->stats.matrix_nnz[l] = L->pat->nnz;
        if ((rc = sb_matrix_init(&L->H, L->pat))) goto nomem;
        L->fixed = calloc((size_t)L->n, 1);
        L->tmp = malloc((size_t)L->n * sizeof *L->tmp);
        if (!L->fixed || !L->tmp) goto nomem;
        if (p->dynamic) {
            L->xhat = calloc((size_t)L->n, sizeof *L->xhat);
            L->xn = calloc((size_t)L->n, sizeof *L->xn);
            if (!L->xhat || !L->xn) goto nomem;
            if (!mt->mass) {
                rc = sb_error(ctx, SB_ERR_UNSUPPORTED, "scene %s is dynamic but method %s provides no mass matrix",
                              scene->name, mt->name);
                goto fail;
            }
            /* the finest level's mass now; a coarser level's at its first use
             * (level_mass): only the rmtr solver's coarse energies and the
             * damping read it, and lsnewton, tr or damped with pcg-mg (whose
             * coarse Hessians are Galerkin products) never do (issue 38: a
             * third of the finest mass matrix's memory) */
            if (l == p->nl - 1 && (rc = level_mass(p, l))) goto fail;
            if (p->damping && (rc = sb_matrix_init(&L->D, L->pat))) goto nomem;
        }
    }
    return SB_OK;
nomem:
    rc = sb_error(ctx, SB_ERR_NOMEM, "out of memory creating the problem");
fail:
    return rc;
}

int sb_problem_levels(const sb_problem *p) { return p->nl; }
int sb_problem_n(const sb_problem *p, int level) { return p->lv[level].n; }
int sb_problem_finest(const sb_problem *p) { return p->nl - 1; }

int sb_problem_step(const sb_problem *p) { return p->step; }
int sb_problem_has_hierarchy(const sb_problem *p)
{
    return p->nl > 1 && (p->mt->flags & SB_METHOD_HIERARCHY);
}
sb_context *sb_problem_context(sb_problem *p) { return p->ctx; }
const sb_method_type *sb_problem_method_type(const sb_problem *p) { return p->mt; }
void *sb_problem_method_state(sb_problem *p) { return p->ms; }

/* Constrained set: constant over a run, so positions are computed once. */
static int build_constraints(sb_problem *p, level_data *L)
{
    const sb_dirichlet *bc = L->bc;
    memset(L->fixed, 0, (size_t)L->n);
    if (!bc) return SB_OK;
    for (int i = 0; i < bc->n; i++) {
        if (bc->dofs[i] < 0 || bc->dofs[i] >= L->n)
            return sb_error(p->ctx, SB_ERR_INTERNAL, "method %s: constrained dof %d out of range", p->mt->name,
                            bc->dofs[i]);
        L->fixed[bc->dofs[i]] = 1;
    }
    const sb_pattern *pat = L->pat;
    long nz = 0, nd = 0;
    for (int c = 0; c < pat->n; c++)
        for (long q = pat->colptr[c]; q < pat->colptr[c + 1]; q++) {
            int r = pat->rowind[q];
            if (!(L->fixed[r] || L->fixed[c])) continue;
            if (r == c) nd++;
            else nz++;
        }
    free(L->zero_pos);
    free(L->diag_pos);
    L->zero_pos = malloc((size_t)(nz ? nz : 1) * sizeof *L->zero_pos);
    L->diag_pos = malloc((size_t)(nd ? nd : 1) * sizeof *L->diag_pos);
    if (!L->zero_pos || !L->diag_pos) return sb_error(p->ctx, SB_ERR_NOMEM, "out of memory (constraints)");
    L->n_zero = L->n_diag = 0;
    for (int c = 0; c < pat->n; c++)
        for (long q = pat->colptr[c]; q < pat->colptr[c + 1]; q++) {
            int r = pat->rowind[q];
            if (!(L->fixed[r] || L->fixed[c])) continue;
            if (r == c) L->diag_pos[L->n_diag++] = q;
            else L->zero_pos[L->n_zero++] = q;
        }
    return SB_OK;
}

void sb_problem_constrain(const sb_problem *p, int level, double *v)
{
    const level_data *L = &p->lv[level];
    if (!L->bc) return;
    for (int i = 0; i < L->bc->n; i++) v[L->bc->dofs[i]] = 0.0;
}

void sb_problem_impose(const sb_problem *p, int level, double *x)
{
    const level_data *L = &p->lv[level];
    if (!L->bc) return;
    for (int i = 0; i < L->bc->n; i++) x[L->bc->dofs[i]] = L->bc->values[i];
}

double sb_problem_norm(const sb_problem *p, int level, const double *v)
{
    const level_data *L = &p->lv[level];
    double s = 0.0;
    for (int i = 0; i < L->n; i++)
        if (!L->fixed[i]) s += v[i] * v[i];
    return sqrt(s);
}

/* obstacle poses of the step and the friction lagged at x_n on every level
 * (coarse levels: x_n projected, as the inertia data are) */
static int self_repattern(sb_problem *p, int l);

/* self-contact of level l at the start of a step: the candidate set at x0
 * (margin from the inertial prediction xhat, or NULL) and the pattern */
static int self_begin_step(sb_problem *p, int l, const double *x0, const double *xhat)
{
    sb_self *S = sb_contact_self(p->lv[l].contact);
    if (!S) return SB_OK;
    int rc = sb_self_begin_step(S, x0, xhat);
    return rc ? rc : self_repattern(p, l);
}

static int contact_begin_step(sb_problem *p, const sb_step_info *si, const double *x_n, const double *v_n,
                              const double *x0)
{
    const int F = p->nl - 1;
    if (!p->lv[F].contact) return SB_OK;
    double t0 = sb_stats_begin(&p->ctx->stats);
    int rc = sb_contact_begin_step(p->lv[F].contact, si->step, p->dt, x_n);
    double *xhat = NULL;
    if (!rc && p->self && p->dynamic && v_n) {
        /* the inertial prediction x_n + dt v_n sizes the self-contact margin */
        xhat = malloc((size_t)p->lv[F].n * sizeof *xhat);
        if (!xhat) rc = SB_ERR_NOMEM;
        else
            for (int i = 0; i < p->lv[F].n; i++) xhat[i] = x0[i] + p->dt * v_n[i];
    }
    if (!rc) rc = self_begin_step(p, F, x0, xhat);
    const double *xf = x_n, *x0f = x0, *xhf = xhat;
    double *buf[2][3] = { { NULL, NULL, NULL }, { NULL, NULL, NULL } };
    for (int l = F - 1; l >= 0 && !rc; l--) {
        if (!(p->mt->flags & SB_METHOD_HIERARCHY)) break;
        double **b = buf[l % 2];
        for (int k = 0; k < 3; k++) { free(b[k]); b[k] = NULL; }
        const int nc = p->lv[l].n;
        b[0] = malloc((size_t)nc * sizeof(double));
        if (p->self) {
            b[1] = malloc((size_t)nc * sizeof(double));
            if (xhf) b[2] = malloc((size_t)nc * sizeof(double));
        }
        if (!b[0] || (p->self && !b[1]) || (xhf && !b[2])) { rc = SB_ERR_NOMEM; break; }
        if ((rc = p->mt->project(p->ms, l, xf, b[0]))) break;
        rc = sb_contact_begin_step(p->lv[l].contact, si->step, p->dt, b[0]);
        if (!rc && p->self) {
            rc = p->mt->project(p->ms, l, x0f, b[1]);
            if (!rc && xhf) rc = p->mt->project(p->ms, l, xhf, b[2]);
            if (!rc) rc = self_begin_step(p, l, b[1], xhf ? b[2] : NULL);
        }
        xf = b[0];
        x0f = b[1];
        xhf = b[2];
    }
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 3; k++) free(buf[i][k]);
    free(xhat);
    sb_stats_event(&p->ctx->stats, F, SB_EV_COLLIDE, t0);
    if (rc) return sb_error(p->ctx, rc < 0 ? rc : SB_ERR_INTERNAL, "contact: starting step %d failed", si->step);
    return SB_OK;
}

/* Self-contact couples the dofs of distant elements, outside the method's
 * pattern (docs/contact.md "Self-contact: sparsity"): when a candidate pair
 * of the step couples two nodes the level's pattern lacks, the pattern is
 * rebuilt as the method's pattern plus one element per candidate pair, the
 * level's matrices are re-created on it (mass recomputed, constraints
 * re-indexed), and the symbolic analysis follows at the next factorization
 * (counted there as event analyze); the solver is told through
 * sb_problem_take_pattern_change.  A set whose couplings are all in the
 * pattern changes nothing. */
static int pair_nodes(const sb_contact_points *P, const int pts[4], int bs, int *nodes, int cap)
{
    int m = 0;
    for (int u = 0; u < 4; u++)
        for (int a = P->off[pts[u]]; a < P->off[pts[u] + 1]; a++)
            for (int c = 0; c < 3; c++) {   /* the three dofs of the term (bs may be 1) */
                const int nd = (P->dof[a] + c) / bs;
                int k = 0;
                while (k < m && nodes[k] != nd) k++;
                if (k == m && m < cap) nodes[m++] = nd;
            }
    return m;
}

static int self_repattern(sb_problem *p, int l)
{
    level_data *L = &p->lv[l];
    sb_self *S = sb_contact_self(L->contact);
    const sb_contact_points *P = sb_contact_points_of(L->contact);
    const int bs = L->pat->bs, npairs = sb_self_n_pairs(S);
    enum { CAP = 1024 };
    int nodes[CAP], need = 0;
    for (int k = 0; k < npairs && !need; k++) {
        int pts[4];
        sb_self_pair_points(S, k, pts);
        const int m = pair_nodes(P, pts, bs, nodes, CAP);
        for (int i = 0; i < m && !need; i++)
            for (int j = i; j < m && !need; j++)
                if (sb_pattern_find(L->pat, nodes[i] * bs, nodes[j] * bs) < 0) need = 1;
    }
    if (!need) return SB_OK;
    sb_pattern_builder *pb = sb_pattern_builder_new(L->n / bs, bs);
    if (!pb) return SB_ERR_NOMEM;
    int rc = p->mt->pattern(p->ms, l, pb);
    for (int k = 0; k < npairs && !rc; k++) {
        int pts[4];
        sb_self_pair_points(S, k, pts);
        const int m = pair_nodes(P, pts, bs, nodes, CAP);
        rc = sb_pattern_builder_add(pb, m, nodes);
    }
    sb_pattern *pat = NULL;
    int rc2 = sb_pattern_builder_finish(pb, &pat);
    if (rc || rc2) { sb_pattern_free(pat); return rc ? rc : rc2; }
    sb_matrix_free(&L->H);
    sb_matrix_free(&L->M);
    mass_free(&L->Ms);
    sb_matrix_free(&L->D);
    sb_linsolve_free(L->lin);
    L->lin = NULL;
    for (int k = 0; k < p->nl; k++) {   /* Galerkin products refer to the patterns of two levels */
        sb_galerkin_free(p->lv[k].gal);
        p->lv[k].gal = NULL;
    }
    sb_pattern_free(L->pat);
    L->pat = pat;
    p->ctx->stats.matrix_nnz[l] = pat->nnz;
    if ((rc = sb_matrix_init(&L->H, pat))) return rc;
    if (p->dynamic) {
        if ((rc = level_mass(p, l))) return rc;
        if (p->damping && (rc = sb_matrix_init(&L->D, pat))) return rc;
    }
    if (L->bc && (rc = build_constraints(p, L))) return rc;
    sb_contact_pattern_changed(L->contact);
    p->pattern_changed = 1;
    return SB_OK;
}

int sb_problem_take_pattern_change(sb_problem *p)
{
    const int c = p->pattern_changed;
    p->pattern_changed = 0;
    return c;
}

int sb_problem_self_measure(sb_problem *p, const double *x, int *pairs, int *active, double *min_distance,
                            int *crossings)
{
    double mm;
    return sb_problem_self_measure_ex(p, x, pairs, active, min_distance, crossings, &mm);
}

int sb_problem_self_measure_ex(sb_problem *p, const double *x, int *pairs, int *active, double *min_distance,
                               int *crossings, double *max_move)
{
    level_data *L = &p->lv[p->nl - 1];
    if (!L->contact || !sb_contact_self(L->contact)) return 0;
    sb_contact_report r;
    sb_contact_measure(L->contact, x, &r);
    *pairs = r.self_pairs;
    *active = r.self_active;
    *min_distance = r.self_min_distance;
    *crossings = r.self_crossings;
    *max_move = r.self_max_move;
    return 1;
}

int sb_problem_begin_step(sb_problem *p, const sb_step_info *si, const double *x_n, const double *v_n, double *x0)
{
    p->step = si->step;
    int rc = p->mt->set_step(p->ms, si);
    if (rc) return rc < 0 ? rc : sb_error(p->ctx, SB_ERR_INTERNAL, "method %s: set_step failed", p->mt->name);
    for (int l = 0; l < p->nl; l++) {
        level_data *L = &p->lv[l];
        if (L->pins && (rc = sb_pins_set_step(L->pins, si)))
            return sb_error(p->ctx, rc < 0 ? rc : SB_ERR_INTERNAL, "method %s: a sliding pin's point at step %d "
                            "could not be evaluated on level %d", p->mt->name, si->step, l);
        const sb_dirichlet *bc = p->mt->dirichlet ? p->mt->dirichlet(p->ms, l) : NULL;
        int first = si->step <= 1 || L->bc == NULL;
        if (bc && (first || bc->n != L->bc->n)) {
            L->bc = bc;
            if ((rc = build_constraints(p, L))) return rc;
        }
        L->bc = bc;
    }
    const int F = p->nl - 1;
    sb_copy(p->lv[F].n, x_n, x0);
    sb_problem_impose(p, F, x0);
    if ((rc = contact_begin_step(p, si, x_n, v_n, x0))) return rc;
    if (!p->dynamic) return SB_OK;

    /* xhat = x_n + dt v_n on the finest level; coarse levels get projections
     * of x_n and xhat (assumption: the paper distributes per-step data to
     * every level (§6) without saying how; projection keeps the coarse
     * inertia term a discretization of the same motion). */
    level_data *Lf = &p->lv[F];
    sb_copy(Lf->n, x_n, Lf->xn);
    for (int i = 0; i < Lf->n; i++) Lf->xhat[i] = x_n[i] + p->dt * v_n[i];
    for (int l = F - 1; l >= 0; l--) {
        if (!(p->mt->flags & SB_METHOD_HIERARCHY)) break;
        double t0 = sb_stats_begin(&p->ctx->stats);
        if ((rc = p->mt->project(p->ms, l, p->lv[l + 1].xn, p->lv[l].xn)) ||
            (rc = p->mt->project(p->ms, l, p->lv[l + 1].xhat, p->lv[l].xhat)))
            return sb_error(p->ctx, rc < 0 ? rc : SB_ERR_INTERNAL, "projection to level %d failed", l);
        sb_stats_event(&p->ctx->stats, l, SB_EV_TRANSFER, t0);
    }
    if (!p->damping) return SB_OK;
    /* Rayleigh damping D = alpha M + beta K(x_n), K lagged at the start of
     * the step (assumption; √3-adaptive paper Eq. 20 uses the same D with K
     * of the linearization point). */
    for (int l = 0; l < p->nl; l++) {
        level_data *L = &p->lv[l];
        sb_matrix_zero(&L->D);
        if (p->ray_b != 0.0) {
            double f = 0.0;
            double t0 = sb_stats_begin(&p->ctx->stats);
            if ((rc = sb_problem_element_maps(p, l))) return rc;
            rc = p->mt->energy(p->ms, l, L->xn, &f, NULL, &L->D);
            sb_stats_event(&p->ctx->stats, l, SB_EV_HESSIAN, t0);
            if (rc) return rc;
            sb_scal((int)L->pat->nnz, p->ray_b, L->D.val);
        }
        if (p->ray_a != 0.0) {
            if ((rc = level_mass(p, l))) return rc;
            mass_axpy(L, &L->D, p->ray_a);
        }
    }
    return SB_OK;
}

/* d^T A d for symmetric A stored as its upper triangle, and g += scale A d
 * (when g is non-NULL), in one pass over the columns. */
static double quad_form(const sb_matrix *A, const double *d, double scale, double *g)
{
    const sb_pattern *pat = A->pat;
    double quad = 0.0;
    for (int c = 0; c < pat->n; c++) {
        long end = pat->colptr[c + 1] - 1;          /* the diagonal closes each column */
        double acc = 0.0;
        for (long q = pat->colptr[c]; q < end; q++) {
            int r = pat->rowind[q];
            double v = A->val[q];
            acc += v * d[r];
            if (g) g[r] += scale * v * d[c];
        }
        acc += A->val[end] * d[c];
        quad += d[c] * (2.0 * acc - A->val[end] * d[c]);
        if (g) g[c] += scale * acc;
    }
    return quad;
}

/* d^T M d and g += scale M d for the mass held by its nonzeros: the sums
 * of quad_form in the same order (the entries it skips are zeros) */
static double mass_quad_form(const level_data *L, const double *d, double scale, double *g)
{
    if (L->M.val) return quad_form(&L->M, d, scale, g);
    const sparse_mass *S = &L->Ms;
    double quad = 0.0;
    for (int c = 0; c < L->n; c++) {
        double acc = 0.0, dv = 0.0;
        const int *rows = L->pat->rowind + L->pat->colptr[c];
        for (long k = S->cp[c]; k < S->cp[c + 1]; k++) {
            const int r = rows[sb_offset_get(S->off, S->w, k)];
            const double v = S->val[k];
            if (r == c) { dv = v; continue; }   /* the diagonal closes the column */
            acc += v * d[r];
            if (g) g[r] += scale * v * d[c];
        }
        acc += dv * d[c];
        quad += d[c] * (2.0 * acc - dv * d[c]);
        if (g) g[c] += scale * acc;
    }
    return quad;
}

static int eval_impl(sb_problem *p, int level, const double *x, double *f, double *g, sb_matrix *H, int eliminate);

int sb_problem_eval(sb_problem *p, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    return eval_impl(p, level, x, f, g, H, 1);
}

static void eliminate_hessian(const level_data *L, sb_matrix *H)
{
    for (long i = 0; i < L->n_zero; i++) H->val[L->zero_pos[i]] = 0.0;
    for (long i = 0; i < L->n_diag; i++) H->val[L->diag_pos[i]] = 1.0;
}

/* Lifting of prescribed boundary motion (assumption, docs/problem.md "Moving
 * boundaries"): when constrained values jump from x_n to their new values,
 * the elimination start x0 moves those dofs alone, which can tear the first
 * ring of elements (a denim state beyond its admissible strain, or a huge
 * energy).  The lifted start solves K_ff dx_f = -K_fc dx_c with the Hessian
 * of Phi at x_n: the linear elastic response of the free dofs to the
 * boundary increment.  It is used only when its energy is finite and not
 * above that of the plain start. */
int sb_problem_lift(sb_problem *p, const double *x_n, double *x0, sb_linear_solve_fn solve, void *state)
{
    const int F = p->nl - 1;
    level_data *L = &p->lv[F];
    const int n = L->n;
    if (!L->bc || !L->bc->n) return SB_OK;
    /* no lifting with self-contact: the lifted start would not pass through
       the self-contact step filter (docs/contact.md) */
    if (p->self) return SB_OK;
    double *d = calloc((size_t)n, sizeof *d), *r = malloc((size_t)n * sizeof *r);
    double *xl = malloc((size_t)n * sizeof *xl);
    if (!d || !r || !xl) { free(d); free(r); free(xl); return SB_ERR_NOMEM; }
    int moved = 0, rc;
    for (int i = 0; i < L->bc->n; i++) {
        int k = L->bc->dofs[i];
        d[k] = x0[k] - x_n[k];
        if (d[k] != 0.0) moved = 1;
    }
    if (!moved) goto out;
    double f;
    rc = eval_impl(p, F, x_n, &f, NULL, &L->H, 0);
    if (rc != SB_OK) goto out;                    /* no lifting from a bad x_n */
    sb_matrix_symv(&L->H, d, r);                  /* K d: K_fc dx_c on free rows */
    for (int i = 0; i < n; i++) r[i] = L->fixed[i] ? 0.0 : r[i];   /* g = K_fc dx_c, free rows */
    eliminate_hessian(L, &L->H);
    /* the run's own linear solver where it has one (issue 38: a Krylov path
     * never factors the finest Hessian, also not here): xl = -H^{-1} g */
    rc = solve ? solve(state, p, r, xl) : SB_ERR_UNSUPPORTED;
    if (rc == SB_ERR_UNSUPPORTED) {
        for (int i = 0; i < n; i++) r[i] = -r[i];
        rc = sb_problem_factor(p, F, 0.0);
        if (rc != SB_OK) goto out;                /* indefinite at x_n: keep the plain start */
        if (sb_problem_solve(p, F, r, xl) != SB_OK) goto out;
    } else if (rc != SB_OK) {
        goto out;                                 /* indefinite, capped: keep the plain start */
    }
    for (int i = 0; i < n; i++) xl[i] = L->fixed[i] ? x0[i] : x_n[i] + xl[i];
    double f0, fl;
    int r0 = eval_impl(p, F, x0, &f0, NULL, NULL, 1);
    int rl = eval_impl(p, F, xl, &fl, NULL, NULL, 1);
    if (rl == SB_OK && isfinite(fl) && (r0 != SB_OK || !isfinite(f0) || fl <= f0)) sb_copy(n, xl, x0);
out:
    free(d);
    free(r);
    free(xl);
    return SB_OK;
}

static int eval_impl(sb_problem *p, int level, const double *x, double *f, double *g, sb_matrix *H, int eliminate)
{
    level_data *L = &p->lv[level];
    const int n = L->n;
    sb_event ev = H ? SB_EV_HESSIAN : g ? SB_EV_GRADIENT : SB_EV_ENERGY;
    double t0 = sb_stats_begin(&p->ctx->stats);
    if (g) memset(g, 0, (size_t)n * sizeof *g);
    if (H) sb_matrix_zero(H);
    double e = 0.0;
    int rc = H ? sb_problem_element_maps(p, level) : SB_OK;
    if (rc) return rc;
    rc = p->mt->energy(p->ms, level, x, &e, g, H);
    if (rc < 0) return rc;
    if (L->pins && rc == SB_OK && sb_pins_energy(L->pins, x, &e, g, H))
        return sb_error(p->ctx, SB_ERR_INTERNAL, "method %s: a sliding pin of level %d couples dofs outside the "
                        "method's sparsity pattern", p->mt->name, level);
    if (L->contact && rc == SB_OK) {
        /* contact barrier and lagged friction (docs/contact.md), timed as
         * the event "collide" (also inside this evaluation's own time) */
        double tc = sb_stats_begin(&p->ctx->stats);
        rc = sb_contact_energy(L->contact, x, &e, g, H);
        sb_stats_event(&p->ctx->stats, level, SB_EV_COLLIDE, tc);
        if (rc == SB_ERR_NOMEM) return sb_error(p->ctx, rc, "out of memory (contact Hessian, level %d)", level);
        if (rc < 0)
            return sb_error(p->ctx, rc, "method %s: a contact sample point of level %d couples dofs outside the "
                            "method's sparsity pattern", p->mt->name, level);
    }
    if (p->dynamic) {
        const int mrc = level_mass(p, level);   /* at its first use */
        if (mrc) return mrc;
        /* inertia: 1/(2 dt^2) (x - xhat)^T M (x - xhat)  (DESIGN.md) */
        const double idt2 = 1.0 / (p->dt * p->dt);
        double *d = L->tmp;
        for (int i = 0; i < n; i++) d[i] = x[i] - L->xhat[i];
        e += 0.5 * idt2 * mass_quad_form(L, d, idt2, g);
        if (H) mass_axpy(L, H, idt2);
        if (p->damping) {
            /* Rayleigh damping: 1/(2 dt) (x - x_n)^T D (x - x_n) */
            const double idt = 1.0 / p->dt;
            for (int i = 0; i < n; i++) d[i] = x[i] - L->xn[i];
            e += 0.5 * idt * quad_form(&L->D, d, idt, g);
            if (H) sb_matrix_axpy(H, idt, &L->D);
        }
    }
    /* Dirichlet elimination */
    if (L->bc && eliminate) {
        if (g) sb_problem_constrain(p, level, g);
        if (H) eliminate_hessian(L, H);
    }
    *f = e;
    sb_stats *st = &p->ctx->stats;
    sb_stats_event(st, level, ev, t0);
    if (H) st->work_assembly += (double)n / (double)p->lv[p->nl - 1].n;   /* RMTR paper Eq. (7.3) */
    if (rc == SB_NONFINITE || !isfinite(e) || (g && !sb_all_finite(n, g))) return SB_NONFINITE;
    return rc;
}

int sb_problem_force_scale(sb_problem *p, double *F)
{
    const int Fl = p->nl - 1;
    level_data *L = &p->lv[Fl];
    const int n = L->n;
    *F = INFINITY;
    if (!p->scale_x) {
        p->scale_x = malloc((size_t)n * sizeof *p->scale_x);
        p->scale_g = malloc((size_t)n * sizeof *p->scale_g);
        if (!p->scale_x || !p->scale_g) return sb_error(p->ctx, SB_ERR_NOMEM, "out of memory (force scale)");
    }
    int rc = p->mt->initial(p->ms, Fl, p->scale_x);
    if (rc < 0) return rc;
    double t0 = sb_stats_begin(&p->ctx->stats), e = 0.0;
    memset(p->scale_g, 0, (size_t)n * sizeof *p->scale_g);
    rc = p->mt->energy(p->ms, Fl, p->scale_x, &e, p->scale_g, NULL);
    sb_stats_event(&p->ctx->stats, Fl, SB_EV_GRADIENT, t0);
    if (rc < 0) return rc;
    sb_problem_constrain(p, Fl, p->scale_g);
    double f = sb_problem_norm(p, Fl, p->scale_g);
    if (rc == SB_NONFINITE || !isfinite(f)) return SB_NONFINITE;
    *F = f;
    return SB_OK;
}

int sb_problem_method_energy(sb_problem *p, const double *x, double *e)
{
    const int Fl = p->nl - 1;
    double t0 = sb_stats_begin(&p->ctx->stats);
    *e = 0.0;
    int rc = p->mt->energy(p->ms, Fl, x, e, NULL, NULL);
    sb_stats_event(&p->ctx->stats, Fl, SB_EV_ENERGY, t0);
    if (rc < 0) return rc;
    return rc == SB_NONFINITE || !isfinite(*e) ? SB_NONFINITE : SB_OK;
}

sb_matrix *sb_problem_hessian(sb_problem *p, int level) { return &p->lv[level].H; }

int sb_problem_has_contact(const sb_problem *p) { return p->lv[p->nl - 1].contact != NULL; }

int sb_problem_has_impulse(const sb_problem *p)
{
    return p->scene->n_obstacles > 0 && p->scene->contact.model == SB_CONTACT_IMPULSE && p->dynamic;
}

int sb_problem_impulse(sb_problem *p, double t1, const double *x0, double *x1, sb_impulse_stats *st)
{
    const int F = p->nl - 1;
    double t0 = sb_stats_begin(&p->ctx->stats);
    int rc = p->mt->impulse_response(p->ms, p->scene, p->dt, t1, x0, x1, st);
    sb_stats_event(&p->ctx->stats, F, SB_EV_COLLIDE, t0);
    if (rc == SB_ERR_NOMEM) return sb_error(p->ctx, rc, "out of memory (impulse collision response)");
    if (rc < 0) return sb_error(p->ctx, rc, "method %s: impulse collision response failed", p->mt->name);
    return rc;
}

double sb_problem_step_bound(sb_problem *p, int level, const double *x, const double *d)
{
    level_data *L = &p->lv[level];
    if (!L->contact) return 1.0;
    double t0 = sb_stats_begin(&p->ctx->stats);
    double a = sb_contact_step_bound(L->contact, x, d);
    sb_stats_event(&p->ctx->stats, level, SB_EV_COLLIDE, t0);
    return a;
}

int sb_problem_contact_separate(sb_problem *p, int step, double *x, int *moved)
{
    level_data *L = &p->lv[p->nl - 1];
    *moved = 0;
    if (!L->contact) return 0;
    double t0 = sb_stats_begin(&p->ctx->stats);
    unsigned char *fixed = calloc((size_t)L->n, 1);
    if (!fixed) return sb_error(p->ctx, SB_ERR_NOMEM, "out of memory (contact separation)");
    const sb_dirichlet *bc = p->mt->dirichlet ? p->mt->dirichlet(p->ms, p->nl - 1) : NULL;
    for (int i = 0; bc && i < bc->n; i++)
        if (bc->dofs[i] >= 0 && bc->dofs[i] < L->n) fixed[bc->dofs[i]] = 1;
    /* assumption (docs/contact.md "Adaptive meshes"): a hundredth of dhat,
     * far below the resting distance (about dhat / 10), so that only points
     * the new mesh put inside or onto an obstacle move */
    int left = sb_contact_separate(L->contact, step, x, fixed, 0.01 * p->scene->contact.dhat, moved);
    free(fixed);
    sb_stats_event(&p->ctx->stats, p->nl - 1, SB_EV_COLLIDE, t0);
    return left;
}

static const char *obstacle_kind_name(const sb_obstacle_spec *o)
{
    static const char *const names[] = { "sphere", "plane", "box", "capsule", "mesh" };
    return (int)o->kind >= 0 && (int)o->kind < 5 ? names[o->kind] : "obstacle";
}

int sb_problem_contact_swept(sb_problem *p, int step, const double *x_n, char *why, size_t why_size)
{
    level_data *L = &p->lv[p->nl - 1];
    if (why_size) why[0] = '\0';
    if (!L->contact) return 0;
    /* not a separate collide event (the counts per step stay those of the
       docs): points x moving obstacles, nothing with static ones */
    sb_contact_sweep_hit h;
    const int n = sb_contact_sweep_check(L->contact, step, x_n, &h);
    if (!n) return 0;
    const sb_obstacle_spec *o = &p->scene->obstacles[h.obstacle];
    char e[SB_NAME_LEN * 4 + 8];
    snprintf(why, why_size,
             "step %d: obstacle \"%s\" (%s) moves through the cloth within the step: its motion over the step "
             "reaches %d contact sample point%s, first point %d (s = %.4g, t = %.4g) at (%.4g, %.4g, %.4g) m, %s "
             "%.3g of the step, %s; the barrier sees obstacles only at the step's end, so the cloth would be left "
             "on the wrong side unseen.  Use smaller steps (time.dt) or a slower motion (motion.ramp_steps)",
             step, sb_escape_copy(o->name, e, sizeof e), obstacle_kind_name(o), n, n == 1 ? "" : "s", h.point,
             h.st[0], h.st[1], h.x[0], h.x[1], h.x[2], h.when > 0 ? "touched after" : "inside it at",
             h.when, h.ends_inside ? "and it ends inside the obstacle" : "and it ends on the obstacle's far side");
    return n;
}

int sb_problem_contact_start_check(sb_problem *p, const double *x, char *why, size_t why_size)
{
    const int F = p->nl - 1;
    level_data *L = &p->lv[F];
    const sb_scene *sc = p->scene;
    if (why_size) why[0] = '\0';
    if (sc->n_obstacles == 0 || !p->mt->contact_points) return 0;
    sb_contact *c = L->contact, *tmp = NULL;
    if (!c) {   /* contact.model "impulse": the method's sample points, for this check only */
        sb_contact_points cp;
        memset(&cp, 0, sizeof cp);
        int rc = p->mt->contact_points(p->ms, F, sc->contact.samples, &cp);
        if (!rc) rc = sb_contact_create(sc, &cp, &tmp);
        sb_contact_points_free(&cp);
        if (rc) return sb_error(p->ctx, rc < 0 ? rc : SB_ERR_INTERNAL, "method %s: contact sample points failed",
                                p->mt->name);
        c = tmp;
    }
    sb_contact_sweep_hit h;
    const int n = sb_contact_inside_check(c, 0, x, &h);
    sb_contact_free(tmp);
    if (!n) return 0;
    const sb_obstacle_spec *o = &sc->obstacles[h.obstacle];
    char e[SB_NAME_LEN * 4 + 8];
    snprintf(why, why_size,
             "the cloth starts inside obstacle \"%s\" (%s): contact sample point %d (s = %.4g, t = %.4g) of "
             "method %s at (%.4g, %.4g, %.4g) m is %s it at the start (%d point%s in all); contact cannot start "
             "from there (infinite barrier energy, no side to push to).  Move the obstacle or the cloth apart",
             sb_escape_copy(o->name, e, sizeof e), obstacle_kind_name(o), h.point, h.st[0], h.st[1], p->mt->name,
             h.x[0], h.x[1], h.x[2], o->kind == SB_OBST_MESH ? "on a triangle of" : "inside", n, n == 1 ? "" : "s");
    return n;
}

int sb_problem_contact_report(sb_problem *p, const double *x, sb_contact_report *r, double *spacing)
{
    level_data *L = &p->lv[p->nl - 1];
    sb_contact *c = L->contact;
    if (!c && p->watch) {   /* impulse: the watch points, at the obstacles' poses of the step */
        c = p->watch;
        if (sb_contact_begin_step(c, p->step, 0.0, NULL)) return 0;
    }
    if (!c) return 0;
    /* a measurement of the step's end, timed with the record (event record), not as collide */
    sb_contact_measure(c, x, r);
    const sb_contact_points *P = sb_contact_points_of(c);
    double a = 0;
    for (int k = 0; k < P->n; k++) a += P->area[k];
    *spacing = P->n > 0 ? sqrt(a / P->n) : NAN;
    return r->points;
}

int sb_problem_contact_measure(sb_problem *p, const double *x, double *min_distance, int *active, int *inside)
{
    level_data *L = &p->lv[p->nl - 1];
    if (!L->contact) return 0;
    sb_contact_report r;
    sb_contact_measure(L->contact, x, &r);
    *min_distance = r.min_distance;
    *active = r.active;
    *inside = r.inside;
    return r.points;
}

int sb_problem_factor(sb_problem *p, int level, double shift)
{
    level_data *L = &p->lv[level];
    if (!L->lin) {
        int rc = sb_linsolve_create(p->ctx, level, &L->H, &L->lin);
        if (rc) return rc;
    }
    return sb_linsolve_factor(L->lin, shift);
}

const sb_linsolve *sb_problem_linsolve(const sb_problem *p, int level)
{
    return level >= 0 && level < p->nl ? p->lv[level].lin : NULL;
}

int sb_problem_solve(sb_problem *p, int level, const double *b, double *x)
{
    level_data *L = &p->lv[level];
    if (!L->lin) return sb_error(p->ctx, SB_ERR_INTERNAL, "solve before factorization on level %d", level);
    int rc = sb_linsolve_solve(L->lin, b, x);
    if (rc == SB_OK) sb_problem_constrain(p, level, x);
    return rc;
}

void sb_problem_hess_mult(sb_problem *p, int level, const double *x, double *y)
{
    sb_matrix_symv(&p->lv[level].H, x, y);
}

void sb_problem_hess_diag(const sb_problem *p, int level, double *d)
{
    const sb_matrix *H = &p->lv[level].H;
    for (int i = 0; i < p->lv[level].n; i++) d[i] = H->val[H->pat->diag[i]];
}

int sb_problem_block_size(const sb_problem *p, int level) { return p->lv[level].pat->bs; }

void sb_problem_hess_block_diag(const sb_problem *p, int level, double *B)
{
    const sb_matrix *H = &p->lv[level].H;
    const sb_pattern *pat = H->pat;
    const int bs = pat->bs, n = p->lv[level].n;
    for (int j = 0; j < n; j++) {
        const int b0 = j - j % bs;            /* first dof of the node */
        double *blk = B + (size_t)b0 * bs;    /* bs x bs, row-major */
        for (long k = pat->colptr[j]; k < pat->colptr[j + 1]; k++) {
            const int i = pat->rowind[k];
            if (i < b0) continue;
            if (i > j) break;
            blk[(i - b0) * bs + (j - b0)] = blk[(j - b0) * bs + (i - b0)] = H->val[k];
        }
    }
}

int sb_problem_prolong(sb_problem *p, int lc, const double *xc, double *xf)
{
    double t0 = sb_stats_begin(&p->ctx->stats);
    int rc = p->mt->prolong(p->ms, lc, xc, xf);
    sb_problem_constrain(p, lc + 1, xf);
    sb_stats_event(&p->ctx->stats, lc, SB_EV_TRANSFER, t0);
    return rc;
}

int sb_problem_restrict(sb_problem *p, int lc, const double *gf, double *gc)
{
    double t0 = sb_stats_begin(&p->ctx->stats);
    int rc = p->mt->restrict_adj(p->ms, lc, gf, gc);
    sb_problem_constrain(p, lc, gc);
    sb_stats_event(&p->ctx->stats, lc, SB_EV_TRANSFER, t0);
    return rc;
}

int sb_problem_project(sb_problem *p, int lc, const double *xf, double *xc)
{
    double t0 = sb_stats_begin(&p->ctx->stats);
    int rc = p->mt->project(p->ms, lc, xf, xc);
    sb_problem_impose(p, lc, xc);
    sb_stats_event(&p->ctx->stats, lc, SB_EV_TRANSFER, t0);
    return rc;
}

/* I as a dof-level matrix by probing prolong() with unit vectors (set-up,
 * once per run; for methods without prolong_matrix) */
static int probe_prolongation(sb_problem *p, int lc, sb_csr *S)
{
    const int nc = p->lv[lc].n, nf = p->lv[lc + 1].n;
    double *e = calloc((size_t)nc, sizeof *e), *y = malloc((size_t)nf * sizeof *y);
    long cap = 16L * nc, nz = 0;
    int *ti = malloc((size_t)cap * sizeof *ti), *tj = malloc((size_t)cap * sizeof *tj);
    double *tv = malloc((size_t)cap * sizeof *tv);
    int rc = !e || !y || !ti || !tj || !tv ? SB_ERR_NOMEM : SB_OK;
    for (int j = 0; j < nc && !rc; j++) {
        e[j] = 1.0;
        rc = p->mt->prolong(p->ms, lc, e, y);
        e[j] = 0.0;
        for (int i = 0; i < nf && !rc; i++) {
            if (y[i] == 0.0) continue;
            if (nz == cap) {
                cap *= 2;
                int *a = realloc(ti, (size_t)cap * sizeof *ti);
                if (a) ti = a;
                int *b = realloc(tj, (size_t)cap * sizeof *tj);
                if (b) tj = b;
                double *c = realloc(tv, (size_t)cap * sizeof *tv);
                if (c) tv = c;
                if (!a || !b || !c) { rc = SB_ERR_NOMEM; break; }
            }
            ti[nz] = i; tj[nz] = j; tv[nz++] = y[i];
        }
    }
    if (!rc) rc = sb_csr_alloc(S, nf, nc, nz);
    if (!rc) {
        /* counting sort by row; columns stay increasing within a row */
        for (long k = 0; k < nz; k++) S->rp[ti[k] + 1]++;
        for (int i = 0; i < nf; i++) S->rp[i + 1] += S->rp[i];
        long *next = malloc((size_t)nf * sizeof *next);
        if (!next) rc = SB_ERR_NOMEM;
        else {
            memcpy(next, S->rp, (size_t)nf * sizeof *next);
            for (long k = 0; k < nz; k++) {
                long d = next[ti[k]]++;
                S->ci[d] = tj[k];
                S->v[d] = tv[k];
            }
            free(next);
        }
    }
    free(e); free(y); free(ti); free(tj); free(tv);
    return rc;
}

static int galerkin_prepare(sb_problem *p, int lc, int lean);

int sb_problem_galerkin_prepare(sb_problem *p, int lc) { return galerkin_prepare(p, lc, 0); }
int sb_problem_galerkin_prepare_lean(sb_problem *p, int lc) { return galerkin_prepare(p, lc, 1); }

static int galerkin_prepare(sb_problem *p, int lc, int lean)
{
    if (lc < 0 || lc + 1 >= p->nl || !sb_problem_has_hierarchy(p))
        return sb_error(p->ctx, SB_ERR_INTERNAL, "Galerkin Hessian requested on level %d of %d", lc, p->nl);
    level_data *C = &p->lv[lc], *F = &p->lv[lc + 1];
    if (C->gal) return SB_OK;
    sb_csr S;
    int rc = p->mt->prolong_matrix ? p->mt->prolong_matrix(p->ms, lc, &S) : probe_prolongation(p, lc, &S);
    if (rc) return sb_error(p->ctx, rc, "method %s: prolongation matrix of level %d failed", p->mt->name, lc);
    if (S.nr != F->n || S.nc != C->n) {
        sb_csr_free(&S);
        return sb_error(p->ctx, SB_ERR_INTERNAL, "method %s: prolongation matrix of level %d has the wrong size",
                        p->mt->name, lc);
    }
    rc = (lean ? sb_galerkin_create_lean : sb_galerkin_create)(&S, F->pat, C->pat, F->fixed, C->fixed, &C->gal);
    sb_csr_free(&S);
    if (rc == SB_ERR_UNSUPPORTED)
        return sb_error(p->ctx, rc, "method %s: the Galerkin product I^T H I of level %d does not fit the level's "
                        "sparsity pattern (use solver.coarse_model=nonlinear or auto with this method)",
                        p->mt->name, lc);
    if (rc) return sb_error(p->ctx, rc, "out of memory (Galerkin product, level %d)", lc);
    return SB_OK;
}

int sb_problem_galerkin_hessian(sb_problem *p, int lc)
{
    int rc = sb_problem_galerkin_prepare(p, lc);
    if (rc) return rc;
    level_data *C = &p->lv[lc], *F = &p->lv[lc + 1];
    double t0 = sb_stats_begin(&p->ctx->stats);
    rc = sb_galerkin_product(C->gal, &F->H, &C->H);
    if (rc) return sb_error(p->ctx, SB_ERR_INTERNAL, "Galerkin product of level %d left the pattern", lc);
    if (C->bc) eliminate_hessian(C, &C->H);
    sb_stats_event(&p->ctx->stats, lc, SB_EV_GALERKIN, t0);
    return SB_OK;
}

void sb_problem_count_qp(sb_problem *p, int level, double seconds)
{
    sb_stats *st = &p->ctx->stats;
    st->ev[level][SB_EV_QP].count++;
    st->ev[level][SB_EV_QP].seconds += seconds;
    st->ev[level][SB_EV_QP].self += seconds;
    st->work_qp += (double)p->lv[level].n / (double)p->lv[p->nl - 1].n;   /* RMTR paper Eq. (7.3) */
}

double sb_problem_clock(sb_problem *p) { return sb_stats_begin(&p->ctx->stats); }

void sb_problem_count_qp_since(sb_problem *p, int level, double t0)
{
    sb_stats_event(&p->ctx->stats, level, SB_EV_QP, t0);
    p->ctx->stats.work_qp += (double)p->lv[level].n / (double)p->lv[p->nl - 1].n;   /* RMTR paper Eq. (7.3) */
}

void sb_problem_count_cg(sb_problem *p, int level, int iters)
{
    p->ctx->stats.ev[level][SB_EV_CG_ITER].count += iters;
}

/* A Krylov solve or its preconditioner's set-up is one `cg_iter` event,
 * begun with sb_problem_krylov_begin so that its exclusive seconds exclude
 * the events inside it (a coarse factorization, Galerkin products); the
 * event counts the CG iterations (0 for a set-up), not the calls */
double sb_problem_krylov_begin(sb_problem *p)
{
    return sb_stats_begin(&p->ctx->stats);
}

void sb_problem_count_krylov(sb_problem *p, int level, int iters, double t0)
{
    sb_stats_event(&p->ctx->stats, level, SB_EV_CG_ITER, t0);
    p->ctx->stats.ev[level < 0 || level >= SB_MAX_LEVELS ? 0 : level][SB_EV_CG_ITER].count += iters - 1;
}
