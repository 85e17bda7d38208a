/* cc_method.c — the Catmull–Clark subdivision discretization as an
 * sb_method_type: `sb_method_subdiv`, registry name "rmtr" (DESIGN.md).
 *
 * Resolution: --res N = N x N elements (faces) of the domain's grid
 * parameter (s,t) on the finest level (--res NxM: N along s, M along t), --levels L nested levels; the coarsest
 * level has N / 2^(L-1) elements per side (N must be divisible by 2^(L-1)),
 * every level carries one ring of ghost faces (§5.2.1).  The RMTR paper's
 * levels 1..6 (147 ... 51,483 dofs) are --res 4, 8, 16, 32, 64, 128; its
 * multilevel runs always start from the 4 x 4 cage, e.g. Table 4 with 3
 * levels = --res 16 --levels 3.  L-shape: the coarse lines are uniform on
 * either side of the notch line (cc_cage_lines), so the notch is exact.
 * DOFs: 3 per control point, dof 3 I + c; level 0 is the coarsest.
 * Boundary conditions: penalty (3.6) in the energy; dirichlet() is NULL.
 * Penalty on coarse levels (ASSUMPTION, the paper only says "beta = h^-sigma,
 * h the mesh size"): by default every level uses the finest level's h, so a
 * coarse level is the fine problem restricted to the nested subspace (its
 * Hessian at the reference equals S^T H_fine S, tests/test_cc_method.c); with
 * per-level h ("penalty_h=level") the coarse boundary is 2^(5(L-l)) times
 * softer and RMTR rejected most coarse corrections in our trampoline runs.
 * With Galerkin coarse models (the solver's default) no coarse energy enters
 * a V-cycle: penalty_h then only decides which problem the nested start
 * solves on a coarser top level, the fine problem restricted (finest) or the
 * level's own discretization (level, the classical full-multigrid choice). */
#include "cc_method.h"
#include "sb_assemble.h"
#include "sb_context.h"
#include "sb_galerkin.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const proj_choices[] = { "reverse", "lsq", "restrict", NULL };
static const char *const hess_choices[] = { "exact", "pseudo", "psd", NULL };
static const char *const mass_choices[] = { "consistent", "lumped", NULL };
static const char *const subdiv_choices[] = { "osd", "rules", NULL };
static const char *const penh_choices[] = { "finest", "level", NULL };
static const char *const beta_rule_choices[] = { "scaled", "paper", NULL };

const sb_param_def cc_params[] = {
    { "projection", SB_PARAM_CHOICE, 0, 0, 0, proj_choices,
      "fine-to-coarse iterate transfer: reverse subdivision (RMTR §5.3.2, App. B/C), lsq = (S^T S)^-1 S^T "
      "(5.18), restrict = row-normalized S^T (keeps constants only)" },
    { "sigma", SB_PARAM_REAL, 5.0, 0.0, 20.0, NULL, "penalty exponent: beta ~ h^-sigma (RMTR §3.1, §7.1)" },
    { "beta_scale", SB_PARAM_REAL, 1.0, 0.0, 1e30, NULL, "factor on the penalty beta of method.beta_rule" },
    { "beta_rule", SB_PARAM_CHOICE, 0, 0, 0, beta_rule_choices,
      "penalty beta: scaled = beta_scale (S / S_p) (l / l_p)^sigma h^-sigma with S = k_m / l + D / l^3 the scene's "
      "membrane and bending stiffness over its diameter l, S_p, l_p those of the paper's 1 m denim cloth (there "
      "exactly the paper's beta; docs/trust.md), or paper = beta_scale h^-sigma (h in m, RMTR §3.1)" },
    { "penalty_h", SB_PARAM_CHOICE, 0, 0, 0, penh_choices,
      "h in beta = h^-sigma: the finest level's on every level (finest: coarse models are Galerkin, "
      "S^T H S = H_c) or each level's own mesh size (level); with Galerkin coarse models only the nested start's "
      "coarse problems use it" },
    { "gauss", SB_PARAM_INT, 3, 2, 6, NULL, "Gauss points per direction on each face (and along boundary edges)" },
    { "hessian", SB_PARAM_CHOICE, 0, 0, 0, hess_choices,
      "Hessian of the elastic energy: exact, pseudo (strain second derivatives dropped) or psd (clamped per element)" },
    { "mass", SB_PARAM_CHOICE, 0, 0, 0, mass_choices, "mass matrix: consistent or row-sum lumped" },
    { "subdiv", SB_PARAM_CHOICE, 0, 0, 0, subdiv_choices,
      "subdivision matrix from OpenSubdiv (RMTR §6) or from the rules (5.12)-(5.15) in C (identical, tested)" },
    { "n_thick", SB_PARAM_INT, 0, 0, 8, NULL, "Gauss points through the thickness (0 = material default)" },
    { "kernel", SB_PARAM_CHOICE, 0, 0, 0, sb_kernel_names,
      "shell kernel: fast (element-batched, sb_shell_element) or reference (per point, the arithmetic of the "
      "committed records; docs/reproducibility.md)" },
    { NULL, SB_PARAM_REAL, 0, 0, 0, NULL, NULL }
};

int cc_state_fail(const cc_state *S, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sb_verror(S ? S->ctx : NULL, status, "rmtr", fmt, ap);
    va_end(ap);
    return status;
}

static void cc_destroy(void *state)
{
    cc_state *S = state;
    for (int l = 0; l < CC_MAX_LEVELS; l++) cc_level_free(&S->lv[l]);
    cc_hier_free(&S->hier);
    if (S->work) sb_shell_work_free(S->work);
    free(S->Ke);
    free(S->ge);
    free(S->qe);
    free(S->psd);
    S->work = NULL;
    S->Ke = S->ge = S->qe = S->psd = NULL;
    for (int t = 0; S->tw && t < S->threads; t++) sb_elem_scratch_free(&S->tw[t]);
    free(S->tw);
    S->tw = NULL;
    sb_assembler_free(S->assembler);
    S->assembler = NULL;
}

static double param(const sb_method_config *cfg, const char *name)
{
    char key[SB_NAME_LEN];
    snprintf(key, sizeof key, "method.%s", name);
    if (cfg->params)
        for (int i = 0; i < cfg->params->n; i++)
            if (strcmp(cfg->params->v[i].key, key) == 0) return cfg->params->v[i].value;
    for (const sb_param_def *d = cc_params; d->name; d++)
        if (strcmp(d->name, name) == 0) return d->def;
    return 0;
}

/* Coarse cage of the scene's domain with n x nt elements (s x t). */
static int coarse_cage(const sb_scene *sc, int n, int nt_, cc_mesh *m, cc_err *e)
{
    double sl[4097], tl[4097];
    if (n < 1 || n > 4096 || nt_ < 1 || nt_ > 4096)
        return cc_fail(e, SB_ERR_INPUT, "coarsest level of %d x %d elements is out of range", n, nt_);
    const sb_domain *d = &sc->domain;
    if (d->kind == SB_DOMAIN_ANNULUS_SECTOR && (d->theta[1] - d->theta[0] >= 6.283185307 || d->r_in <= 0))
        return cc_fail(e, SB_ERR_UNSUPPORTED, "annulus sectors must be open (angle < 2 pi) with r_in > 0 for rmtr");
    double s01[2], t01[2];
    if (d->kind != SB_DOMAIN_L_SHAPE || !sb_domain_notch_st(d, s01, t01)) {
        cc_cage_lines(n, 0, 0, sl, NULL);
        cc_cage_lines(nt_, 0, 0, tl, NULL);
        return cc_cage_grid(sl, n, tl, nt_, -1, 0, 0, m, e);
    }
    int corner = d->notch_corner, hs = corner == SB_CORNER_10 || corner == SB_CORNER_11;
    int ht = corner == SB_CORNER_11 || corner == SB_CORNER_01, ns, nt;
    if (cc_cage_lines(n, hs ? s01[0] : s01[1], hs, sl, &ns) || cc_cage_lines(nt_, ht ? t01[0] : t01[1], ht, tl, &nt))
        return cc_fail(e, SB_ERR_INPUT, "an L-shape needs at least 2 coarse elements per side (got %d x %d)", n, nt_);
    return cc_cage_grid(sl, n, tl, nt_, corner, ns, nt, m, e);
}

/* Elements per side of the finest level, with the checks every size of
 * create() relies on: at most SB_SCENE_MAX_RESOLUTION (so the cages'
 * vertex, face and quadrature counts fit in int), divisible by 2^(levels-1). */
static int cc_grid_size(const sb_scene *scene, const sb_method_config *cfg, int *n, int *nt, int *levels, char *msg,
                        size_t len)
{
    *levels = cfg->levels > 0 ? cfg->levels : 1;
    *n = cfg->res > 0 ? cfg->res : (scene->default_res > 0 ? scene->default_res : 16);
    *nt = cfg->res_t > 0 ? cfg->res_t : *n;   /* --res NxM: N along s, M along t */
    if (*levels > CC_MAX_LEVELS) {
        snprintf(msg, len, "%d levels requested, at most %d are supported", *levels, CC_MAX_LEVELS);
        return SB_ERR_INPUT;
    }
    if (*n > SB_SCENE_MAX_RESOLUTION || *nt > SB_SCENE_MAX_RESOLUTION) {
        snprintf(msg, len, "--res %dx%d elements requested, at most %d per side are supported", *n, *nt,
                 SB_SCENE_MAX_RESOLUTION);
        return SB_ERR_INPUT;
    }
    if (*n % (1 << (*levels - 1)) || *nt % (1 << (*levels - 1))) {
        snprintf(msg, len, "--res %dx%d cannot be coarsened %d times: both must be divisible by 2^(levels-1) = %d",
                 *n, *nt, *levels - 1, 1 << (*levels - 1));
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

/* sb_method_type.estimate: the cages of every level (the domain's n_l x n_l
 * faces and one ghost ring, cc_cage.c, cc_hier.c) with their topology,
 * subdivision and projection matrices, quadrature tables (cc_quad.c) and
 * reference data (cc_level.c); boundary points are left out (O(n_l)). */
static int cc_estimate(const sb_scene *scene, const sb_method_config *cfg, sb_method_size *sz)
{
    int n, nt, levels;
    char msg[256];
    if (cc_grid_size(scene, cfg, &n, &nt, &levels, msg, sizeof msg)) return sb_error(cfg->ctx, SB_ERR_INPUT, "rmtr: %s", msg);
    const double ng = param(cfg, "gauss"), nq = ng * ng;
    memset(sz, 0, sizeof *sz);
    sz->levels = levels;
    sz->bs = 3;
    sz->nodes_per_element = 16;   /* the bicubic B-spline patch of a regular face */
    sz->stencil = 49;             /* control points sharing a face support: 7 x 7 */
    sz->prolong_per_dof = 6.25;   /* Catmull-Clark per component: vertex 9, edge 6, face 4 coarse points */
    double bytes = 0;
    for (int l = 0; l < levels; l++) {
        double nl = (double)(n >> (levels - 1 - l)), ml = (double)(nt >> (levels - 1 - l));
        double nv = (nl + 3) * (ml + 3), nf = (nl + 2) * (ml + 2), ne = nl * ml;
        sz->nodes[l] = nv;
        sz->elements[l] = ne;
        bytes += nv * (2 * sizeof(double) + 2 * sizeof(int) + 4 * 3 * sizeof(int) + 3 * sizeof(double));  /* st, grid, topology, X */
        bytes += nf * (4 + 4 + 2 + 4 + 2) * sizeof(int);                                                    /* fv, fe, cell, vf, felem */
        bytes += ne * (16 + 4) * sizeof(int) + ne * nq * sizeof(sb_shell_ref);                             /* quadrature, reference */
        if (l < levels - 1) sz->coarse_energy_bytes += ne * nq * sizeof(sb_shell_ref);                     /* cc_level_ref */
        bytes += nv * 10 * (sizeof(int) + sizeof(double));       /* S onto this level (about 6 entries a row) and P from it */
    }
    sz->method_bytes = bytes;
    return SB_OK;
}

static int cc_create(void *state, const sb_scene *scene, const sb_method_config *cfg)
{
    cc_state *S = state;
    memset(S, 0, sizeof *S);
    S->scene = scene;
    S->ctx = cfg->ctx;
    S->proj = (cc_proj_kind)(int)param(cfg, "projection");
    S->sigma = param(cfg, "sigma");
    S->beta_scale = param(cfg, "beta_scale");
    S->ng = (int)param(cfg, "gauss");
    int h = (int)param(cfg, "hessian");
    S->hess = h == 1 ? SB_HESS_PSEUDO : h == 2 ? SB_HESS_PSD : SB_HESS_EXACT;
    S->lumped = (int)param(cfg, "mass") == 1;
    S->use_osd = (int)param(cfg, "subdiv") == 0;
    S->beta_finest = (int)param(cfg, "penalty_h") == 0;
    S->beta_paper = (int)param(cfg, "beta_rule") == 1;
    S->kernel = (sb_kernel_kind)(int)param(cfg, "kernel");
    S->threads = sb_param_int_or(cfg->params, "run.threads", 1);
    if (S->threads > 1 && !sb_assemble_have_threads())
        return cc_state_fail(S, SB_ERR_INPUT, "run.threads = %d: this build has no OpenMP (build with make OPENMP=-fopenmp)",
                             S->threads);
    char msg[256];
    if (sb_shell_isa_from_params(cfg->params, &S->isa, msg, sizeof msg)) return cc_state_fail(S, SB_ERR_INPUT, "%s", msg);
    if (sb_material_init_msg(&S->mat, &scene->material, (int)param(cfg, "n_thick"), msg, sizeof msg) != SB_OK)
        return cc_state_fail(S, SB_ERR_INPUT, "material: %s", msg);
    int n, nt, levels;
    if (cc_grid_size(scene, cfg, &n, &nt, &levels, msg, sizeof msg)) return cc_state_fail(S, SB_ERR_INPUT, "%s", msg);
    S->n_fine = n;
    S->n_coarse = n >> (levels - 1);
    S->nt_fine = nt;
    S->nt_coarse = nt >> (levels - 1);
    cc_err e = { "" };
    int rc = cc_beta_factor(S, &S->beta_factor, &e);
    if (rc) return cc_state_fail(S, rc, "%s", e.msg);
    cc_mesh cage;
    int st = coarse_cage(scene, S->n_coarse, S->nt_coarse, &cage, &e);
    if (!st) st = cc_hier_build(&S->hier, &cage, levels, S->use_osd, &e);
    if (!st) S->nlev = levels;
    for (int l = levels - 1; l >= 0 && !st; l--) st = cc_level_build(S, l, &e);   /* finest first (penalty_h) */
    if (!st) {
        int kmax = 0;
        for (int l = 0; l < levels; l++)
            for (int el = 0; el < S->lv[l].quad.ne; el++) {
                int k = S->lv[l].quad.eoff[el + 1] - S->lv[l].quad.eoff[el];
                kmax = k > kmax ? k : kmax;
            }
        int nm = 3 * kmax;
        S->Ke = malloc((size_t)nm * nm * sizeof *S->Ke);
        S->ge = malloc((size_t)nm * sizeof *S->ge);
        S->qe = malloc((size_t)nm * sizeof *S->qe);
        S->psd = malloc((sb_psd_work_size(nm) + 1) * sizeof *S->psd);
        S->work = sb_shell_work_new();
        if (!S->Ke || !S->ge || !S->qe || !S->psd || !S->work) st = cc_fail(&e, SB_ERR_NOMEM, "out of memory");
        /* assembly: per-thread scratch, and energy terms per element of the
         * reference order (shell, gravity, each pressure load per point; points) */
        int n_press = 0;
        for (int i = 0; i < scene->n_loads; i++) n_press += scene->loads[i].kind == SB_LOAD_PRESSURE;
        const int nq = S->ng * S->ng, max_terms = nq * (2 + n_press) + 2;
        S->tw = calloc((size_t)S->threads, sizeof *S->tw);
        if (!st && !S->tw) st = cc_fail(&e, SB_ERR_NOMEM, "out of memory");
        for (int t = 0; !st && t < S->threads; t++)
            if (sb_elem_scratch_init(&S->tw[t], kmax, nq, S->isa)) st = cc_fail(&e, SB_ERR_NOMEM, "out of memory");
        if (!st && !(S->assembler = sb_assembler_new(S->threads, nm, max_terms)))
            st = cc_fail(&e, SB_ERR_NOMEM, "out of memory");
    }
    if (st) {
        cc_state_fail(S, st, "%s", e.msg[0] ? e.msg : "cannot build the subdivision hierarchy");
        cc_destroy(S);
        return st;
    }
    return SB_OK;
}

static int cc_n_levels(const void *state) { return ((const cc_state *)state)->nlev; }

static int cc_n_dofs(const void *state, int level)
{
    const cc_state *S = state;
    return level >= 0 && level < S->nlev ? 3 * S->lv[level].nv : 0;
}

static int cc_block_size(const void *state, int level)
{
    (void)state;
    (void)level;
    return 3;
}

static int cc_pattern(const void *state, int level, sb_pattern_builder *pb)
{
    const cc_state *S = state;
    const cc_quad *Q = &S->lv[level].quad;
    for (int el = 0; el < Q->ne; el++) {
        int st = sb_pattern_builder_add(pb, Q->eoff[el + 1] - Q->eoff[el], Q->enode + Q->eoff[el]);
        if (st) return st;
    }
    return SB_OK;
}

static int cc_initial(const void *state, int level, double *x)
{
    const cc_state *S = state;
    memcpy(x, S->lv[level].X, (size_t)3 * S->lv[level].nv * sizeof *x);
    return SB_OK;
}

static int cc_set_step(void *state, const sb_step_info *si)
{
    cc_state *S = state;
    memcpy(S->load_factor, si->load_factor, sizeof S->load_factor);
    memcpy(S->motion_factor, si->motion_factor, sizeof S->motion_factor);
    for (int l = 0; l < S->nlev; l++) cc_points_update(S, l);   /* boundary data on every level, §6 */
    return SB_OK;
}

/* every control point of an element that holds a position or slope penalty
 * point (cc_penalty.c), all three components: the band along the penalized
 * boundary (ghost, boundary and first interior rows) */
static int cc_penalty_support(const void *state, int level, unsigned char *mask)
{
    const cc_state *S = state;
    if (level < 0 || level >= S->nlev) return 0;
    const cc_level *L = &S->lv[level];
    memset(mask, 0, (size_t)3 * L->nv);
    for (int k = 0; k < L->npt; k++) {
        const cc_pt *p = &L->pt[k];
        if (p->kind != CC_PT_PENALTY && p->kind != CC_PT_SLOPE) continue;
        for (int a = L->quad.eoff[p->elem]; a < L->quad.eoff[p->elem + 1]; a++)
            memset(mask + 3 * L->quad.enode[a], 1, 3);
    }
    int marked = 0;
    for (int i = 0; i < 3 * L->nv; i++) marked += mask[i];
    return marked;
}

static const sb_dirichlet *cc_dirichlet(const void *state, int level)
{
    (void)state;
    (void)level;
    return NULL;   /* penalty method (3.6) */
}

static int cc_energy_op(void *state, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    return cc_energy(state, level, x, f, g, H);
}

static int cc_mass_op(void *state, int level, sb_matrix *M) { return cc_mass(state, level, M); }

static int cc_material_state_op(void *state, int level, const double *x, sb_material_state *ms)
{
    return cc_material_state(state, level, x, ms);
}

static int cc_eval_points(const void *state, int level, const double *x, int np, const double *st, double *pos)
{
    const cc_state *S = state;
    const cc_level *L = &S->lv[level];
    int idx[CC_MAX_BASIS], k, f;
    double W[6 * CC_MAX_BASIS], u, v;
    cc_err e = { "" };
    for (int p = 0; p < np; p++) {
        if (cc_level_locate(L, st[2 * p], st[2 * p + 1], &f, &u, &v))
            return cc_state_fail(S, SB_ERR_INPUT, "point (s,t) = (%g, %g) is outside the domain", st[2 * p], st[2 * p + 1]);
        int rc = cc_face_basis(L->mesh, f, u, v, &k, idx, W, CC_MAX_BASIS, &e);
        if (rc) return cc_state_fail(S, rc, "%s", e.msg);
        for (int c = 0; c < 3; c++) {
            double s = 0;
            for (int a = 0; a < k; a++) s += W[a] * x[3 * idx[a] + c];
            pos[3 * p + c] = s;
        }
    }
    return SB_OK;
}

static int cc_prolong(void *state, int lc, const double *xc, double *xf)
{
    cc_state *S = state;
    cc_csr_apply(&S->hier.S[lc], 3, xc, xf);                 /* q^{l+1} = S q^l (5.11) */
    return SB_OK;
}

static int cc_restrict(void *state, int lc, const double *gf, double *gc)
{
    cc_state *S = state;
    cc_csr_apply_t(&S->hier.S[lc], 3, gf, gc);               /* R = S^T */
    return SB_OK;
}

/* I at dof level: row 3i+c of S (x) I_3 holds S(i,j) at column 3j+c */
static int cc_prolong_matrix(const void *state, int lc, sb_csr *A)
{
    const cc_state *S = state;
    const cc_csr *T = &S->hier.S[lc];
    int rc = sb_csr_alloc(A, 3 * T->nr, 3 * T->nc, 3L * T->rp[T->nr]);
    if (rc) return rc;
    long k = 0;
    for (int i = 0; i < T->nr; i++)
        for (int c = 0; c < 3; c++) {
            for (int q = T->rp[i]; q < T->rp[i + 1]; q++) {
                A->ci[k] = 3 * T->ci[q] + c;
                A->v[k++] = T->v[q];
            }
            A->rp[3 * i + c + 1] = k;
        }
    return SB_OK;
}

static int cc_project(void *state, int lc, const double *xf, double *xc)
{
    cc_state *S = state;
    cc_level *L = &S->lv[lc];
    if (L->lsq) return cc_lsq_apply(L->lsq, 3, xf, xc);
    cc_csr_apply(&L->P, 3, xf, xc);
    return SB_OK;
}

static void cc_describe(const void *state, char *buf, size_t len)
{
    const cc_state *S = state;
    const cc_level *L = &S->lv[S->nlev - 1];
    snprintf(buf, len,
             "Catmull-Clark subdivision, %d levels, %dx%d -> %dx%d elements (+ghost ring), %d dofs, %s projection, "
             "%s kernel%s%s",
             S->nlev, S->n_coarse, S->nt_coarse, S->n_fine, S->nt_fine, 3 * L->nv, proj_choices[S->proj],
             sb_kernel_names[S->kernel], S->kernel == SB_KERNEL_FAST ? " at vectors " : "",
             S->kernel == SB_KERNEL_FAST ? sb_shell_isa_name(S->isa) : "");
}

static int cc_penalty_violation_op(void *state, int level, const double *x, sb_penalty_report *r)
{
    return cc_penalty_violation(state, level, x, r);
}

const sb_method_type sb_method_subdiv = {
    .name = "rmtr",
    .description = "Catmull-Clark subdivision shell elements with level hierarchy, penalty BCs (RMTR paper §3, §5)",
    .state_size = sizeof(cc_state),
    .params = cc_params,
    .flags = SB_METHOD_HIERARCHY | SB_METHOD_POTENTIAL | SB_METHOD_RES_ST | SB_METHOD_PENALTY_BCS,
    .create = cc_create,
    .destroy = cc_destroy,
    .n_levels = cc_n_levels,
    .n_dofs = cc_n_dofs,
    .block_size = cc_block_size,
    .pattern = cc_pattern,
    .initial = cc_initial,
    .set_step = cc_set_step,
    .dirichlet = cc_dirichlet,
    .energy = cc_energy_op,
    .mass = cc_mass_op,
    .material_state = cc_material_state_op,
    .eval_points = cc_eval_points,
    .prolong = cc_prolong,
    .restrict_adj = cc_restrict,
    .project = cc_project,
    .prolong_matrix = cc_prolong_matrix,
    .estimate = cc_estimate,
    .penalty_violation = cc_penalty_violation_op,
    .penalty_support = cc_penalty_support,
    .describe = cc_describe,
    .surface = cc_surface,
    .contact_points = cc_contact_points,
};
