/* bhem_method.c — the bicubic Hermite element method as an sb_method_type
 * (BHEM paper 001_…): creation from a scene, levels, step data, and the
 * operation table `sb_method_bhem`. */
#include "bhem.h"
#include "sb_context.h"
#include "sb_assemble.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const hess_choices[] = { "exact", "pseudo", "psd", NULL };

const sb_param_def bhem_params[] = {
    { "hessian", SB_PARAM_CHOICE, 0, 0, 0, hess_choices,
      "Hessian of the elastic energy: exact, pseudo (BHEM §6.1, strain second derivatives dropped) "
      "or psd (exact, eigenvalues clamped per patch)" },
    { "imperfection", SB_PARAM_REAL, 0.0, 0.0, 1.0, NULL,
      "amplitude (m) of a smooth deterministic out-of-plane imperfection of the reference surface "
      "(symmetry breaking for buckling scenes; 0 = none)" },
    { "cells_t", SB_PARAM_INT, 0, 0, SB_SCENE_MAX_RESOLUTION, NULL,
      "patches along t on the finest level (0 = same as --res; --res NxM says the same)" },
    { "kernel", SB_PARAM_CHOICE, 0, 0, 0, sb_kernel_names,
      "shell kernel: fast (patch-batched, sb_shell_element) or reference (per point, the arithmetic of the "
      "committed records; docs/reproducibility.md)" },
    { NULL, SB_PARAM_REAL, 0, 0, 0, NULL, NULL }
};

static void bhem_destroy(void *state)
{
    bhem_state *S = state;
    for (int l = 0; l < SB_MAX_LEVELS; l++) bhem_level_free(&S->lv[l]);
    if (S->work) sb_shell_work_free(S->work);
    free(S->Ke);
    free(S->psd_work);
    S->work = NULL;
    S->Ke = S->psd_work = NULL;
    for (int t = 0; S->tw && t < S->threads; t++) sb_elem_scratch_free(&S->tw[t]);
    free(S->tw);
    S->tw = NULL;
    bhem_impulse_free(S->imp);
    S->imp = NULL;
    sb_assembler_free(S->assembler);
    S->assembler = NULL;
}

static int read_params(bhem_state *S, const sb_method_config *cfg, int *cells_t)
{
    S->hess = SB_HESS_EXACT;
    S->imperfection = 0.0;
    *cells_t = 0;
    S->kernel = SB_KERNEL_FAST;
    S->threads = sb_param_int_or(cfg->params, "run.threads", 1);
    if (S->threads > 1 && !sb_assemble_have_threads())
        return bhem_fail(S, SB_ERR_INPUT, "run.threads = %d: this build has no OpenMP (build with make OPENMP=-fopenmp)",
                         S->threads);
    char msg[256];
    if (sb_shell_isa_from_params(cfg->params, &S->isa, msg, sizeof msg)) return bhem_fail(S, SB_ERR_INPUT, "%s", msg);
    if (!cfg->params) return SB_OK;
    if (strcmp(sb_param_choice(cfg->params, "method.kernel"), "reference") == 0) S->kernel = SB_KERNEL_REFERENCE;
    const char *h = sb_param_choice(cfg->params, "method.hessian");
    if (strcmp(h, "pseudo") == 0) S->hess = SB_HESS_PSEUDO;
    else if (strcmp(h, "psd") == 0) S->hess = SB_HESS_PSD;
    S->imperfection = sb_param(cfg->params, "method.imperfection");
    *cells_t = sb_param_int(cfg->params, "method.cells_t");
    if (!(S->imperfection >= 0.0)) return bhem_fail(S, SB_ERR_INPUT, "method.imperfection must be >= 0");
    return SB_OK;
}

/* Patches (n, m) of the finest level, with the checks every size of
 * create() relies on: at most SB_SCENE_MAX_RESOLUTION per side (so n*m,
 * 12 (n+1)(m+1) dofs and 48 n m element dofs fit in int), divisible by
 * 2^(levels-1). */
static int bhem_grid_size(const sb_scene *scene, const sb_method_config *cfg, int cells_t, int *n, int *m,
                          int *levels, char *msg, size_t len)
{
    *n = cfg->res > 0 ? cfg->res : (scene->default_res > 0 ? scene->default_res : 8);
    /* along t: --res NxM (the core passes a scene's "resolution": [N, M] alike), or method.cells_t */
    if (cfg->res_t > 0 && cells_t > 0 && cfg->res_t != cells_t) {
        snprintf(msg, len, "--res %dx%d and method.cells_t=%d say different things about the patches along t", *n,
                 cfg->res_t, cells_t);
        return SB_ERR_INPUT;
    }
    *m = cfg->res_t > 0 ? cfg->res_t : cells_t > 0 ? cells_t : *n;
    *levels = cfg->levels > 0 ? cfg->levels : 1;
    if (*levels > SB_MAX_LEVELS) {
        snprintf(msg, len, "%d levels requested, at most %d are supported", *levels, SB_MAX_LEVELS);
        return SB_ERR_INPUT;
    }
    if (*n > SB_SCENE_MAX_RESOLUTION || *m > SB_SCENE_MAX_RESOLUTION) {
        snprintf(msg, len, "%d x %d patches requested, at most %d per side are supported", *n, *m,
                 SB_SCENE_MAX_RESOLUTION);
        return SB_ERR_INPUT;
    }
    int div = 1 << (*levels - 1);
    if (*n % div || *m % div) {
        snprintf(msg, len, "--res %d (x %d) patches cannot be coarsened %d times: the resolution must be divisible by "
                 "2^(levels-1) = %d", *n, *m, *levels - 1, div);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

/* sb_method_type.estimate: the grid of every level, counted as create()
 * allocates it (bhem_grid.c, bhem_loads.c, bhem_transfer.c); masked
 * (L-shape) and identified (periodic) nodes are counted as present. */
static int bhem_estimate(const sb_scene *scene, const sb_method_config *cfg, sb_method_size *sz)
{
    int n, m, levels, cells_t = cfg->params ? sb_param_int(cfg->params, "method.cells_t") : 0;
    char msg[256];
    if (bhem_grid_size(scene, cfg, cells_t, &n, &m, &levels, msg, sizeof msg))
        return sb_error(cfg->ctx, SB_ERR_INPUT, "bhem: %s", msg);
    memset(sz, 0, sizeof *sz);
    sz->levels = levels;
    sz->bs = 12;
    sz->nodes_per_element = 4;
    sz->stencil = 9;
    sz->prolong_per_dof = 6.0;    /* measured: 5.4-5.8 at 3e3 dofs, growing towards 6 */
    double bytes = 0;
    for (int l = 0; l < levels; l++) {
        int sh = levels - 1 - l;
        double n1 = n >> sh, n2 = m >> sh, nodes = (n1 + 1) * (n2 + 1), ne = n1 * n2, dofs = 12 * nodes;
        sz->nodes[l] = nodes;
        sz->elements[l] = ne;
        /* the consistent mass couples a node pair's jets of the same component: 48 of a block's 144 entries,
         * 30 of the diagonal block's upper 78 (held by its nonzeros, sb_problem.c) */
        sz->mass_nnz[l] = nodes * (0.5 * (sz->stencil - 1) * 48.0 + 30.0);
        bytes += nodes * 3 * sizeof(int) + ne * (2 + BHEM_NED) * sizeof(int);   /* node ids, cells, elements */
        bytes += ne * BHEM_NQP * sizeof(sb_shell_ref);                          /* quadrature reference data */
        if (l + 1 < levels) sz->coarse_energy_bytes += ne * BHEM_NQP * sizeof(sb_shell_ref);   /* released after set-up */
        bytes += dofs * (2 + scene->n_loads) * sizeof(double);                   /* x_ref, f_ext, load vectors */
        if (l + 1 < levels) bytes += 4 * 4 * nodes * 4 * (sizeof(int) + sizeof(double));   /* prolongation rows */
    }
    sz->method_bytes = bytes;
    return SB_OK;
}

static int bhem_create(void *state, const sb_scene *scene, const sb_method_config *cfg)
{
    bhem_state *S = state;
    memset(S, 0, sizeof *S);
    S->scene = scene;
    S->ctx = cfg->ctx;
    int cells_t, rc = read_params(S, cfg, &cells_t);
    if (rc) return rc;
    int n, m, levels;
    char msg[256];
    if (bhem_grid_size(scene, cfg, cells_t, &n, &m, &levels, msg, sizeof msg))
        return bhem_fail(S, SB_ERR_INPUT, "%s", msg);
    if (scene->material.thickness <= 0.0 || scene->material.density < 0.0)
        return bhem_fail(S, SB_ERR_INPUT, "material thickness must be > 0 and density >= 0");
    if ((rc = sb_material_init(&S->mat, &scene->material, 0))) {
        bhem_fail(S, rc < 0 ? rc : SB_ERR_INPUT, "material initialisation failed (status %d)", rc);
        return rc < 0 ? rc : SB_ERR_INPUT;
    }
    S->n_levels = levels;
    S->Ke = malloc(sizeof(double) * BHEM_NED * BHEM_NED);
    S->psd_work = malloc(sizeof(double) * (sb_psd_work_size(BHEM_NED) + 1));
    S->work = sb_shell_work_new();
    if (!S->Ke || !S->psd_work || !S->work) { bhem_destroy(S); return SB_ERR_NOMEM; }
    /* assembly: per-thread scratch; terms per patch: shell and follower
     * pressure per point, end moments */
    S->tw = calloc((size_t)S->threads, sizeof *S->tw);
    if (!S->tw) { bhem_destroy(S); return SB_ERR_NOMEM; }
    for (int t = 0; t < S->threads; t++)
        if (sb_elem_scratch_init(&S->tw[t], BHEM_NB, BHEM_NQP, S->isa)) { bhem_destroy(S); return SB_ERR_NOMEM; }
    if (!(S->assembler = sb_assembler_new(S->threads, BHEM_NED, 2 * BHEM_NQP + 2))) { bhem_destroy(S); return SB_ERR_NOMEM; }
    if ((rc = bhem_detect_periodic(S))) { bhem_destroy(S); return rc; }
    for (int l = 0; l < levels && rc == SB_OK; l++) {
        bhem_level *L = &S->lv[l];
        int sh = levels - 1 - l;
        rc = bhem_level_build(S, L, n >> sh, m >> sh);
        if (!rc) rc = bhem_level_quadrature(S, L);
        if (!rc) rc = bhem_bc_build(S, L);
        if (!rc) rc = bhem_loads_build(S, L);
    }
    for (int l = 0; l + 1 < levels && rc == SB_OK; l++) rc = bhem_transfer_build(S, l);
    /* the coarser levels' quadrature data (sb_shell_ref per point, 75 bytes:
     * 23 MB at 250,000 dofs) is read only by their own energy and mass, which
     * the rmtr solver evaluates and lsnewton, tr, damped and linearized
     * (Galerkin coarse Hessians) never do: released once set-up has checked
     * the surface and built the loads, built again at first use
     * (bhem_level_ensure_quadrature; the memory estimate's
     * coarse_energy_bytes) */
    for (int l = 0; l + 1 < levels && rc == SB_OK; l++) {
        free(S->lv[l].ref);
        S->lv[l].ref = NULL;
    }
    if (rc) {
        if (rc == SB_ERR_NOMEM) bhem_fail(S, rc, "out of memory building %dx%d patches", n, m);
        bhem_destroy(S);
        return rc;
    }
    return SB_OK;
}

static int bhem_n_levels(const void *state) { return ((const bhem_state *)state)->n_levels; }

static int bhem_n_dofs(const void *state, int level)
{
    const bhem_state *S = state;
    return level >= 0 && level < S->n_levels ? S->lv[level].n_dofs : 0;
}

static int bhem_block_size(const void *state, int level)
{
    (void)state;
    (void)level;
    return 12;   /* x, hs x_s, ht x_t, hs ht x_st: 4 x 3 per node */
}

/* Patch node lists (corner order p + 2q).  With 12 dofs per node the local
 * dof 12*corner + 3*kind + c equals the kernel's 3*I + c, I = 4*corner + kind. */
static int bhem_pattern(const void *state, int level, sb_pattern_builder *pb)
{
    const bhem_state *S = state;
    const bhem_level *L = &S->lv[level];
    for (int e = 0; e < L->n_elems; e++) {
        const int *d = L->elem_dofs + (size_t)e * BHEM_NED;
        int nodes[4];
        for (int c = 0; c < 4; c++) nodes[c] = d[12 * c] / 12;
        int rc = sb_pattern_builder_add(pb, 4, nodes);
        if (rc) return rc;
    }
    return SB_OK;
}

static int bhem_initial(const void *state, int level, double *x)
{
    const bhem_state *S = state;
    const bhem_level *L = &S->lv[level];
    memcpy(x, L->x_ref, sizeof(double) * (size_t)L->n_dofs);
    return SB_OK;
}

static int bhem_set_step(void *state, const sb_step_info *si)
{
    bhem_state *S = state;
    const sb_scene *sc = S->scene;
    for (int k = 0; k < sc->n_loads; k++) S->load_factor[k] = si->load_factor[k];
    for (int b = 0; b < sc->n_bcs; b++) S->motion_factor[b] = si->motion_factor[b];
    for (int l = 0; l < S->n_levels; l++) {
        bhem_bc_update(S, &S->lv[l]);
        bhem_loads_update(S, &S->lv[l]);
        S->lv[l].rebranch = 1;
    }
    return SB_OK;
}

static const sb_dirichlet *bhem_dirichlet(const void *state, int level)
{
    const bhem_state *S = state;
    const bhem_level *L = &S->lv[level];
    return L->n_con ? &L->dir : NULL;
}

static int bhem_energy_op(void *state, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    return bhem_energy(state, level, x, f, g, H);
}

static int bhem_material_state_op(void *state, int level, const double *x, sb_material_state *ms)
{
    return bhem_material_state(state, level, x, ms);
}

static int bhem_mass_op(void *state, int level, sb_matrix *M)
{
    bhem_state *S = state;
    return bhem_mass(S, &S->lv[level], M);
}

static int bhem_eval_points(const void *state, int level, const double *x, int np, const double *st, double *pos)
{
    const bhem_state *S = state;
    return bhem_eval(S, &S->lv[level], x, np, st, pos);
}

/* Sliding pins (sb_method.h point_terms): x(st) = sum_I N_I(th) q_I over the
 * 16 Hermite functions of the patch containing st (BHEM Eq. 16). */
static int bhem_point_terms(const void *state, int level, const double st[2], int *dof, double *w)
{
    const bhem_state *S = state;
    const bhem_level *L = &S->lv[level];
    double th1, th2, N[BHEM_NB];
    const int e = bhem_locate(L, st[0], st[1], &th1, &th2);
    if (e < 0) return SB_ERR_INPUT;
    bhem_basis_eval(th1, th2, L->hs, L->ht, N, NULL, NULL, NULL, NULL, NULL);
    for (int I = 0; I < BHEM_NB; I++) {
        dof[I] = L->elem_dofs[(size_t)e * BHEM_NED + 3 * I];
        w[I] = N[I];
    }
    return BHEM_NB;
}

static int bhem_prolong_op(void *state, int lc, const double *xc, double *xf) { return bhem_prolong(state, lc, xc, xf); }
static int bhem_restrict_op(void *state, int lc, const double *gf, double *gc) { return bhem_restrict(state, lc, gf, gc); }
static int bhem_prolong_matrix_op(const void *state, int lc, struct sb_csr *I) { return bhem_prolong_matrix(state, lc, I); }
static int bhem_project_op(void *state, int lc, const double *xf, double *xc) { return bhem_project(state, lc, xf, xc); }

static void bhem_describe(const void *state, char *buf, size_t len)
{
    const bhem_state *S = state;
    const bhem_level *L = &S->lv[S->n_levels - 1];
    snprintf(buf, len, "%dx%d bicubic Hermite patches (%d active), %d dofs, %d level%s, %s Hessian%s%s%s%s, %s kernel%s%s",
             L->n1, L->n2, L->n_elems, L->n_dofs, S->n_levels, S->n_levels > 1 ? "s" : "", hess_choices[S->hess],
             S->periodic_s ? ", periodic in s" : "", S->periodic_t ? ", periodic in t" : "",
             S->slit_s ? ", closed in s but slit (conditions on its seam edges)" : "",
             S->slit_t ? ", closed in t but slit (conditions on its seam edges)" : "", sb_kernel_names[S->kernel],
             S->kernel == SB_KERNEL_FAST ? " at vectors " : "", S->kernel == SB_KERNEL_FAST ? sb_shell_isa_name(S->isa) : "");
}

const sb_method_type sb_method_bhem = {
    .name = "bhem",
    .description = "bicubic Hermite element method (Ni, Chen et al.): C1 Hermite patches, 12 dofs per node",
    .state_size = sizeof(bhem_state),
    .params = bhem_params,
    .flags = SB_METHOD_HIERARCHY | SB_METHOD_POTENTIAL | SB_METHOD_RES_ST | SB_METHOD_NODAL_DERIVATIVES,
    .create = bhem_create,
    .destroy = bhem_destroy,
    .n_levels = bhem_n_levels,
    .n_dofs = bhem_n_dofs,
    .block_size = bhem_block_size,
    .pattern = bhem_pattern,
    .initial = bhem_initial,
    .set_step = bhem_set_step,
    .dirichlet = bhem_dirichlet,
    .energy = bhem_energy_op,
    .mass = bhem_mass_op,
    .material_state = bhem_material_state_op,
    .eval_points = bhem_eval_points,
    .prolong = bhem_prolong_op,
    .restrict_adj = bhem_restrict_op,
    .project = bhem_project_op,
    .prolong_matrix = bhem_prolong_matrix_op,
    .estimate = bhem_estimate,
    .describe = bhem_describe,
    .surface = bhem_surface,
    .contact_points = bhem_contact_points,
    .point_terms = bhem_point_terms,
    .impulse_response = bhem_impulse_response,
};
