/* lf_method.c — linear_fem as an sb_method_type: parameters, creation from a
 * scene, levels, step data and the operation table (see lf.h for the model).
 *
 * Resolution: --res N = N cells along s (and method.cells_t, default N, along
 * t) of the grid parameter on the finest level (sb_mesh_domain.c); with
 * --levels L the coarsest level has N / 2^(L-1) cells and is the one the
 * pattern (and the jitter) is applied to, the finer levels being its 1-to-4
 * refinements.  So `alternate`, `crossed` and `jitter` meshes depend on L:
 * --levels 1 puts the pattern at the finest level itself (`regular` is the
 * same for every L). */
#include "lf.h"
#include "sb_context.h"
#include "sb_galerkin.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const mesh_choices[] = { "alternate", "regular", "crossed", "jitter", NULL };
static const char *const bend_choices[] = { "midedge", "hinge", NULL };
static const char *const dir_choices[] = { "edge", "average", NULL };
static const char *const hess_choices[] = { "exact", "pseudo", "psd", NULL };
static const char *const mass_choices[] = { "consistent", "lumped", NULL };

const sb_param_def lf_params[] = {
    { "mesh", SB_PARAM_CHOICE, 0, 0, 0, mesh_choices,
      "triangulation of the coarsest level: alternate (alternating diagonals), regular (one diagonal "
      "direction), crossed (4 triangles per cell), jitter (alternate with interior vertices displaced by "
      "method.jitter of the cell size, seeded by run.seed, then Delaunay flips)" },
    { "jitter", SB_PARAM_REAL, 0.3, 0.0, 0.45, NULL,
      "mesh=jitter: displacement of interior vertices as a fraction of the local cell size (uniform per direction)" },
    { "bending", SB_PARAM_CHOICE, 0, 0, 0, bend_choices,
      "bending model: midedge (midedge-normal shape operator fed to the section law) or hinge (Grinspun et al. "
      "2003 dihedral-angle discrete shells, calibrated to the plate stiffness)" },
    { "director", SB_PARAM_CHOICE, 0, 0, 0, dir_choices,
      "midedge normals: edge (one rotation dof per edge; Morley-type, converges on any mesh) or average (the "
      "normalized mean of the two face normals, no extra dofs; consistent only on the regular mesh)" },
    { "hessian", SB_PARAM_CHOICE, 0, 0, 0, hess_choices,
      "Hessian: exact, pseudo (second derivatives of the bending strains dropped) or psd (exact, eigenvalues "
      "clamped per element)" },
    { "mass", SB_PARAM_CHOICE, 0, 0, 0, mass_choices, "mass matrix: consistent (rho A/12 (1 + delta_ij)) or lumped (rho A/3)" },
    { "cells_t", SB_PARAM_INT, 0, 0, SB_SCENE_MAX_RESOLUTION, NULL, "cells along t on the finest level (0 = same as --res)" },
    { "imperfection", SB_PARAM_REAL, 0.0, 0.0, 1.0, NULL,
      "amplitude (m) of the smooth deterministic out-of-plane imperfection of the reference surface that bhem's "
      "method.imperfection uses (the same field of the grid parameter, core/scene/sb_imperfection.c; buckling scenes)" },
    { "n_thick", SB_PARAM_INT, 0, 0, 8, NULL, "Gauss points through the thickness (0 = material default)" },
    { NULL, SB_PARAM_REAL, 0, 0, 0, NULL, NULL }
};

static void lf_destroy(void *state)
{
    lf_state *S = state;
    for (int l = 0; l < SB_MAX_LEVELS; l++) lf_level_free(&S->lv[l]);
    free(S->Ke);
    free(S->psd_work);
    S->Ke = S->psd_work = NULL;
}

/* a resolved parameter by full key, or def when the set does not declare it */
static double pval(const sb_paramset *ps, const char *key, double def)
{
    if (ps)
        for (int i = 0; i < ps->n; i++)
            if (strcmp(ps->v[i].key, key) == 0) return ps->v[i].value;
    return def;
}

static int choice(const sb_paramset *ps, const char *name)
{
    char key[SB_NAME_LEN];
    snprintf(key, sizeof key, "method.%s", name);
    return (int)pval(ps, key, 0.0);
}

/* sb_method_type.estimate (sb_memory.h): the meshes of every level as
 * lf_level_build makes them: (n+1)(m+1) vertices (and one per cell for
 * `crossed`), 2 triangles per cell (4 crossed), V + F - 1 edges; dofs 3 per
 * vertex and, with edge directors, 1 per edge (block size 1 then).  The node
 * stencils are measured on trampoline --res 32 (alternate and crossed): 17.8
 * and 18.2 vertices for midedge with averaged directors (2-ring: 19), 10.5
 * and 10.7 for hinges (11), 50.8 and 51.5 dofs with edge directors (53). */
static int lf_estimate(const sb_scene *scene, const sb_method_config *cfg, sb_method_size *sz)
{
    const sb_paramset *ps = cfg->params;
    const int n = cfg->res > 0 ? cfg->res : (scene->default_res > 0 ? scene->default_res : 16);
    const int m = cfg->res_t > 0 ? cfg->res_t   /* --res NxM */
                : (int)pval(ps, "method.cells_t", 0) > 0 ? (int)pval(ps, "method.cells_t", 0) : n;
    const int levels = cfg->levels > 0 ? cfg->levels : 1;
    const int bending = choice(ps, "bending"), crossed = choice(ps, "mesh") == 2;
    const int edge_dofs = bending == LF_BEND_MIDEDGE && choice(ps, "director") == LF_DIR_EDGE;
    if (levels > SB_MAX_LEVELS || n > SB_SCENE_MAX_RESOLUTION || m > SB_SCENE_MAX_RESOLUTION)
        return sb_error(cfg->ctx, SB_ERR_INPUT, "linear_fem: %d x %d cells with %d levels requested, at most %d per side "
                        "and %d levels are supported", n, m, levels, SB_SCENE_MAX_RESOLUTION, SB_MAX_LEVELS);
    memset(sz, 0, sizeof *sz);
    sz->levels = levels;
    sz->bs = edge_dofs ? 1 : 3;
    sz->nodes_per_element = edge_dofs ? LF_NED_MAX : 6;
    sz->stencil = edge_dofs ? 53 : bending == LF_BEND_HINGE ? 11 : 19;
    sz->prolong_per_dof = 1.75;   /* per component: a vertex 1 coarse node, an edge midpoint 2 */
    double bytes = 0;
    for (int l = 0; l < levels; l++) {
        const int sh = levels - 1 - l;
        const double n1 = n >> sh, n2 = m >> sh, cells = n1 * n2;
        const double nv = (n1 + 1) * (n2 + 1) + (crossed ? cells : 0), nt = (crossed ? 4 : 2) * cells;
        const double ne = nv + nt - 1, dofs = 3 * nv + (edge_dofs ? ne : 0);
        sz->nodes[l] = edge_dofs ? dofs : nv;
        sz->elements[l] = nt + (bending == LF_BEND_HINGE ? ne : 0);
        /* the consistent mass couples the same component of an edge's ends:
         * 3 (nv + ne) upper entries, 7-14 % of the pattern (sb_problem.c) */
        sz->mass_nnz[l] = 3.0 * (nv + ne);
        bytes += nt * (sizeof(lf_tri) + 64) + ne * (bending == LF_BEND_HINGE ? sizeof(lf_hinge) : 0) + nv * 96 + ne * 32;
        bytes += dofs * (2 + scene->n_loads) * sizeof(double);                                 /* x_ref, f_ext, loads */
        if (l > 0) bytes += dofs * 6 * (sizeof(int) + sizeof(double));                         /* prolongation rows */
    }
    sz->method_bytes = bytes;
    return SB_OK;
}

static int lf_create(void *state, const sb_scene *scene, const sb_method_config *cfg)
{
    lf_state *S = state;
    memset(S, 0, sizeof *S);
    S->scene = scene;
    S->ctx = cfg->ctx;
    const sb_paramset *ps = cfg->params;
    S->pattern = choice(ps, "mesh");
    S->bending = choice(ps, "bending");
    S->director = choice(ps, "director");
    S->hess = (sb_hess_kind)choice(ps, "hessian");
    S->lumped = choice(ps, "mass");
    S->jitter = pval(ps, "method.jitter", 0.3);
    S->cells_t = (int)pval(ps, "method.cells_t", 0);
    S->imperfection = pval(ps, "method.imperfection", 0.0);
    if (!(S->imperfection >= 0.0)) return lf_fail(S, SB_ERR_INPUT, "method.imperfection must be >= 0");
    S->seed = (unsigned long)pval(ps, "run.seed", 1);
    char isa_msg[256];
    if (sb_shell_isa_from_params(ps, &S->isa, isa_msg, sizeof isa_msg)) return lf_fail(S, SB_ERR_INPUT, "%s", isa_msg);
    const int n_thick = (int)pval(ps, "method.n_thick", 0);
    S->edge_dofs = S->bending == LF_BEND_MIDEDGE && S->director == LF_DIR_EDGE;
    S->res = cfg->res > 0 ? cfg->res : (scene->default_res > 0 ? scene->default_res : 16);
    if (cfg->res_t > 0 && S->cells_t > 0 && cfg->res_t != S->cells_t)
        return lf_fail(S, SB_ERR_INPUT, "--res %dx%d and method.cells_t=%d say different things about the cells along t",
                       S->res, cfg->res_t, S->cells_t);
    if (cfg->res_t > 0) S->cells_t = cfg->res_t;   /* --res NxM: N along s, M along t */
    if (S->cells_t <= 0) S->cells_t = S->res;
    if (S->res > SB_SCENE_MAX_RESOLUTION || S->cells_t > SB_SCENE_MAX_RESOLUTION)   /* counts below stay in int */
        return lf_fail(S, SB_ERR_INPUT, "%d x %d cells requested, at most %d per side are supported", S->res,
                       S->cells_t, SB_SCENE_MAX_RESOLUTION);
    const int levels = cfg->levels > 0 ? cfg->levels : 1;
    if (levels > SB_MAX_LEVELS)
        return lf_fail(S, SB_ERR_INPUT, "%d levels requested, at most %d are supported", levels, SB_MAX_LEVELS);
    const int div = 1 << (levels - 1);
    if (S->res % div || S->cells_t % div)
        return lf_fail(S, SB_ERR_INPUT,
                       "--res %d (x %d cells) cannot be coarsened %d times: the resolution must be divisible by "
                       "2^(levels-1) = %d", S->res, S->cells_t, levels - 1, div);
    if (scene->material.thickness <= 0.0 || scene->material.density < 0.0)
        return lf_fail(S, SB_ERR_INPUT, "material thickness must be > 0 and density >= 0");
    int rc = sb_material_init(&S->mat, &scene->material, n_thick);
    if (rc) return lf_fail(S, rc < 0 ? rc : SB_ERR_INPUT, "material initialisation failed (status %d)", rc);
    S->n_levels = levels;
    const int n = LF_NED_MAX;
    S->Ke = malloc(sizeof(double) * n * n);
    S->psd_work = malloc(sizeof(double) * (sb_psd_work_size(n) + 1));
    if (!S->Ke || !S->psd_work) { lf_destroy(S); return SB_ERR_NOMEM; }
    for (int l = 0; l < levels && rc == SB_OK; l++) rc = lf_level_build(S, l);
    for (int l = 1; l < levels && rc == SB_OK; l++) rc = lf_transfer_build(S, l);
    if (rc) {
        if (rc == SB_ERR_NOMEM) lf_fail(S, rc, "out of memory building the %d x %d mesh", S->res, S->cells_t);
        lf_destroy(S);
        return rc;
    }
    return SB_OK;
}

static int lf_n_levels(const void *state) { return ((const lf_state *)state)->n_levels; }

static int lf_n_dofs(const void *state, int level)
{
    const lf_state *S = state;
    return level >= 0 && level < S->n_levels ? S->lv[level].n_dofs : 0;
}

static int lf_block_size(const void *state, int level)
{
    (void)level;
    return ((const lf_state *)state)->edge_dofs ? 1 : 3;
}

/* element node lists in the order lf_energy / lf_mass add their blocks */
static int lf_pattern(const void *state, int level, sb_pattern_builder *pb)
{
    const lf_state *S = state;
    const lf_level *L = &S->lv[level];
    int d[LF_NED_MAX], nodes[LF_NED_MAX];
    for (int t = 0; t < L->nt; t++) {
        const int n = lf_tri_dofs(S, L, t, d);
        int k = 0;
        if (S->edge_dofs)
            for (int a = 0; a < n; a++) nodes[k++] = d[a];
        else
            for (int a = 0; a < n; a += 3) nodes[k++] = d[a] < 0 ? -1 : d[a] / 3;
        int rc = sb_pattern_builder_add(pb, k, nodes);
        if (rc) return rc;
    }
    for (int h = 0; h < L->n_hinge; h++) {
        int rc = sb_pattern_builder_add(pb, 4, L->hinge[h].v);
        if (rc) return rc;
    }
    return SB_OK;
}

static int lf_initial(const void *state, int level, double *x)
{
    const lf_state *S = state;
    memcpy(x, S->lv[level].x_ref, sizeof(double) * (size_t)S->lv[level].n_dofs);
    return SB_OK;
}

static int lf_set_step(void *state, const sb_step_info *si)
{
    lf_state *S = state;
    const sb_scene *sc = S->scene;
    S->p_follow = 0.0;
    for (int k = 0; k < sc->n_loads; k++) {
        S->load_factor[k] = si->load_factor[k];
        if (sc->loads[k].kind == SB_LOAD_PRESSURE && sc->loads[k].follower)
            S->p_follow += si->load_factor[k] * sc->loads[k].value;
    }
    for (int b = 0; b < sc->n_bcs; b++) S->motion_factor[b] = si->motion_factor[b];
    for (int l = 0; l < S->n_levels; l++) {
        lf_bc_update(S, &S->lv[l]);
        lf_loads_update(S, &S->lv[l]);
        S->lv[l].rebranch = 1;
    }
    return SB_OK;
}

static const sb_dirichlet *lf_dirichlet(const void *state, int level)
{
    const lf_state *S = state;
    return S->lv[level].n_con ? &S->lv[level].dir : NULL;
}

static int lf_energy_op(void *state, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    return lf_energy(state, level, x, f, g, H);
}

static int lf_mass_op(void *state, int level, sb_matrix *M)
{
    lf_state *S = state;
    return lf_mass(S, &S->lv[level], M);
}

static int lf_eval_op(const void *state, int level, const double *x, int np, const double *st, double *pos)
{
    const lf_state *S = state;
    return lf_eval(S, &S->lv[level], x, np, st, pos);
}

/* Sliding pins (sb_method.h point_terms): the barycentric weights of st in
 * its triangle (the linear interpolant of the vertex positions). */
static int lf_point_terms(const void *state, int level, const double st[2], int *dof, double *w)
{
    const lf_state *S = state;
    const lf_level *L = &S->lv[level];
    const int t = sb_mesh_locate(&L->mesh, &L->loc, st[0], st[1], w);
    if (t < 0) return SB_ERR_INPUT;
    for (int i = 0; i < 3; i++) dof[i] = 3 * L->mesh.tri[3 * t + i];
    return 3;
}

static int lf_material_state_op(void *state, int level, const double *x, sb_material_state *ms)
{
    return lf_material_state(state, level, x, ms);
}

static int lf_prolong_op(void *state, int lc, const double *xc, double *xf) { return lf_prolong(state, lc, xc, xf); }
static int lf_restrict_op(void *state, int lc, const double *gf, double *gc) { return lf_restrict(state, lc, gf, gc); }
static int lf_project_op(void *state, int lc, const double *xf, double *xc) { return lf_project(state, lc, xf, xc); }
static int lf_prolong_matrix_op(const void *state, int lc, sb_csr *I) { return lf_prolong_matrix(state, lc, I); }

static void lf_describe(const void *state, char *buf, size_t len)
{
    const lf_state *S = state;
    const lf_level *L = &S->lv[S->n_levels - 1];
    char jit[128] = "";
    if (S->pattern == SB_MESH_JITTER)
        snprintf(jit, sizeof jit, " (jitter %.2f, gsl_rng %s, seed %lu)", S->jitter, S->rng_name ? S->rng_name : "?",
                 S->seed);
    if (L->mesh.slit)   /* a closed surface whose seam edges carry conditions (docs/scene_format.md) */
        snprintf(jit + strlen(jit), sizeof jit - strlen(jit), ", closed in %s but slit",
                 L->mesh.slit == 3 ? "s and t" : L->mesh.slit == 1 ? "s" : "t");
    snprintf(buf, len, "%dx%d %s mesh%s: %d vertices, %d triangles, %d edges; %s bending%s; %d dofs, %d level%s, "
             "%s Hessian, %s mass", S->res, S->cells_t, mesh_choices[S->pattern], jit, L->nv, L->nt, L->ne,
             bend_choices[S->bending],
             S->bending == LF_BEND_MIDEDGE ? (S->edge_dofs ? " (edge directors)" : " (averaged directors)") : "",
             L->n_dofs, S->n_levels, S->n_levels > 1 ? "s" : "", hess_choices[S->hess], mass_choices[S->lumped]);
}

const sb_method_type sb_method_linear_fem = {
    .name = "linear_fem",
    .description = "linear triangle discrete shell: constant-strain membrane, midedge or hinge bending (core/mesh)",
    .state_size = sizeof(lf_state),
    .params = lf_params,
    .flags = SB_METHOD_HIERARCHY | SB_METHOD_POTENTIAL | SB_METHOD_RES_ST | SB_METHOD_IMPULSE_SELF,
    .create = lf_create,
    .estimate = lf_estimate,
    .destroy = lf_destroy,
    .n_levels = lf_n_levels,
    .n_dofs = lf_n_dofs,
    .block_size = lf_block_size,
    .pattern = lf_pattern,
    .initial = lf_initial,
    .set_step = lf_set_step,
    .dirichlet = lf_dirichlet,
    .energy = lf_energy_op,
    .mass = lf_mass_op,
    .impulse_response = lf_impulse_response,
    .eval_points = lf_eval_op,
    .prolong = lf_prolong_op,
    .restrict_adj = lf_restrict_op,
    .project = lf_project_op,
    .prolong_matrix = lf_prolong_matrix_op,
    .material_state = lf_material_state_op,
    .describe = lf_describe,
    .surface = lf_surface,
    .contact_points = lf_contact_points,
    .point_terms = lf_point_terms,
};
