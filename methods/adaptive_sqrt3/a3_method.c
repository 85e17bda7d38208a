/* a3_method.c — adaptive_sqrt3 as an sb_method_type: parameters, the scenes
 * it refuses (one sentence, before any work), creation, step data and the
 * operation table.  The model and its assumptions: a3.h.
 *
 * Resolution: --res N = N cells along s (method.cells_t or --res NxM along
 * t) of the grid parameter, triangulated by core/mesh (method.mesh).  This
 * is the full-resolution model: every triangle of that mesh is simulated. */
#include "a3.h"
#include "sb_surface.h"
#include "sb_contact_mesh.h"
#include "sb_context.h"
#include "sb_memory.h"

#include <limits.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const mesh_choices[] = { "alternate", "regular", "crossed", NULL };

const sb_param_def a3_params[] = {
    { "mesh", SB_PARAM_CHOICE, 0, 0, 0, mesh_choices,
      "triangulation of the grid: alternate (alternating diagonals), regular (one diagonal direction), crossed "
      "(4 triangles per cell)" },
    { "cells_t", SB_PARAM_INT, 0, 0, SB_SCENE_MAX_RESOLUTION, NULL, "cells along t (0 = same as --res)" },
    { "Es", SB_PARAM_REAL, 0, 0, 1e15, NULL,
      "shear stiffness E_s of Eq. 9 in N/m (0 = the isotropic value 4 mu h = 2 Y h / (1 + nu) for the tensor "
      "shear strain of Eq. 7; the sqrt3 paper's curtain uses 1000)" },
    { "Ey_ratio", SB_PARAM_REAL, 1, 1e-6, 1e6, NULL,
      "E_y / E_x of Eq. 9 (orthotropy; E_x = Y h, nu_yx = nu E_y / E_x so that C is symmetric)" },
    { "adaptive", SB_PARAM_INT, 1, 0, 1, NULL,
      "1: sqrt3 refinement / coarsening from the --res mesh by the curvature criterion (§5); 0: the full "
      "resolution, every triangle refined to method.max_generation for the whole run" },
    { "max_generation", SB_PARAM_INT, 6, 0, 20, NULL, "g_max: the finest sqrt3 generation (paper: 6; 2 generations triple the triangles)" },
    { "adapt_every", SB_PARAM_INT, 5, 0, 1000000, NULL, "adapt the mesh before every this many steps (paper: 5; 0 = never)" },
    { "curv_base", SB_PARAM_REAL, 2, 0, 1e12, NULL, "l_base of Eq. 23: refine generation 0 above this mean curvature |c| (1/m)" },
    { "curv_max", SB_PARAM_REAL, 20, 0, 1e12, NULL, "l_gmax of Eq. 23: the refinement limit at generation g_max (1/m)" },
    { "coarsen_fraction", SB_PARAM_REAL, 0.5, 0, 1, NULL, "coarsen below this fraction of the refinement limit of the generation" },
    { NULL, SB_PARAM_REAL, 0, 0, 0, NULL, NULL }
};

static void a3_destroy(void *state) { a3_free(state); }

/* a resolved parameter by full key, or def when the set does not declare it */
static double pval(const sb_paramset *ps, const char *key, double def)
{
    if (ps)
        for (int i = 0; i < ps->n; i++)
            if (strcmp(ps->v[i].key, key) == 0) return ps->v[i].value;
    return def;
}

/* The scenes this model cannot honour (a3.h), refused with one sentence. */
static int refuse(a3_state *S, const sb_scene *sc)
{
    if (sc->chart.kind != SB_CHART_PLANE)
        return a3_fail(S, SB_ERR_UNSUPPORTED, "scene %s: the reference surface is curved, but the isometric bending "
                       "model (Eq. 18-19) needs a flat rest state; use a plane geometry", sc->name);
    for (int b = 0; b < sc->n_bcs; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind == SB_BC_MOVING && bc->slide)
            return a3_fail(S, SB_ERR_UNSUPPORTED, "scene %s: boundary[%d] is a sliding pin (\"slide\"), a point held "
                           "between vertices, which the adaptive mesh (whose vertices change) does not impose",
                           sc->name, b);
        if (bc->kind == SB_BC_CLAMPED || bc->kind == SB_BC_SYMMETRY || (bc->kind == SB_BC_MOVING && bc->clamp_tangent))
            return a3_fail(S, SB_ERR_UNSUPPORTED, "scene %s: boundary[%d] (%s) prescribes a rotation, which the vertex-only "
                           "model cannot impose (use fixed, moving without clamp_tangent, or free)", sc->name, b,
                           bc->kind == SB_BC_CLAMPED ? "clamped" : bc->kind == SB_BC_SYMMETRY ? "symmetry"
                                                                                               : "moving with clamp_tangent");
    }
    for (int k = 0; k < sc->n_loads; k++) {
        const sb_load *ld = &sc->loads[k];
        if (ld->kind == SB_LOAD_PRESSURE || ld->kind == SB_LOAD_END_MOMENT)
            return a3_fail(S, SB_ERR_UNSUPPORTED, "scene %s: loads[%d] (%s) is not supported (gravity, line and point "
                           "loads are)", sc->name, k, ld->kind == SB_LOAD_PRESSURE ? "pressure" : "end_moment");
    }
    const sb_material_spec *mt = &sc->material;
    if (mt->kind == SB_MAT_DENIM) {
        if (!(mt->thickness > 0.0) || !(mt->density >= 0.0) || !(mt->denim.k[0] > 0.0) || !(mt->denim.k[2] > 0.0) ||
            !(mt->denim.k[3] > 0.0) || !(mt->denim.k[1] * mt->denim.k[1] < mt->denim.k[0] * mt->denim.k[2]))
            return a3_fail(S, SB_ERR_INPUT, "scene %s: the denim law's small-strain tangent (k_1, k_2, k_3, k_4 of "
                           "Table 1) must be positive definite, with thickness > 0 and density >= 0", sc->name);
        return SB_OK;
    }
    if (!(mt->thickness > 0.0) || !(mt->young > 0.0) || !(mt->density >= 0.0) || !(mt->poisson > -1.0 && mt->poisson < 0.5))
        return a3_fail(S, SB_ERR_INPUT, "scene %s: material needs thickness > 0, young > 0, density >= 0 and "
                       "-1 < poisson < 0.5", sc->name);
    return SB_OK;
}

/* The refinement limits that cannot work (issue 40), refused before any
 * work with one sentence naming the key: Eq. 23's limits must not decrease
 * with the generation (the paper: "successively increasing limits"; a
 * decreasing l_g would refine every triangle above l_base straight to
 * g_max), and the coarsening limit, coarsen_fraction x l_g (§5.3: "a
 * fraction of the refinement limit of the same generation"), must lie below
 * the refinement limit l_g, else the operation a refinement just applied
 * satisfies its own coarsening test and the mesh can flip between the two at
 * every adaptation.  SB_OK, or SB_ERR_INPUT with the sentence in buf. */
static int limits_check(const sb_paramset *ps, char *buf, size_t len)
{
    const double lb = pval(ps, "method.curv_base", 2), lm = pval(ps, "method.curv_max", 20);
    const double cf = pval(ps, "method.coarsen_fraction", 0.5);
    if (lm < lb) {
        snprintf(buf, len, "method.curv_max = %g is below method.curv_base = %g: the refinement limits of Eq. 23 "
                 "must not decrease with the generation (a triangle refined above l_base would be refined on to "
                 "g_max); choose curv_max >= curv_base", lm, lb);
        return SB_ERR_INPUT;
    }
    if (!(cf < 1.0)) {
        snprintf(buf, len, "method.coarsen_fraction = %g puts the coarsening limit (coarsen_fraction x l_g) at or "
                 "above the refinement limit l_g of the same generation, so a refinement could be undone by the "
                 "next adaptation; choose a fraction below 1", cf);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

/* The mesh refined to g_max from the base mesh's triangles and vertices (a
 * split at every odd generation adds a vertex per triangle and triples
 * them, the flips after it add none: a3_estimate). */
static void refined_size(double *nt, double *nv, int gens)
{
    for (int g = 0; g < gens; g += 2) {
        *nv += *nt;
        *nt *= 3.0;
    }
}

static void fill_size(sb_method_size *sz, double nt, double nv, int n_loads)
{
    memset(sz, 0, sizeof *sz);
    sz->levels = 1;
    sz->bs = 3;
    sz->nodes[0] = nv;
    sz->elements[0] = nt + 1.5 * nt;
    sz->nodes_per_element = 4;
    sz->stencil = 11;
    sz->method_bytes = nt * 1500.0 + nv * (260.0 + 24.0 * n_loads);
}

/* sb_method_type.estimate (sb_memory.h): the mesh create() builds, from the
 * sizes alone (nothing is allocated).  The base mesh has (n+1)(m+1)
 * vertices (and one per cell for `crossed`), 2 triangles per cell (4
 * crossed); the full resolution (method.adaptive = 0) refines every
 * triangle to method.max_generation: a split (odd generation) adds a vertex
 * per triangle and triples them, the flips after it add none (boundary
 * splits a few: measured on the curtain at generation 4, 128 -> 1152
 * triangles, 81 -> 625 vertices, counted 593).  An adaptive run starts on the
 * base mesh and is estimated there (its refinement follows the curvature
 * during the run).  Dofs 3 per vertex; elements the triangles (3 nodes) and
 * the interior bending edges (4 nodes, about 1.5 per triangle); the node
 * stencil of the triangles and the bending edges' flaps is linear_fem's
 * hinge stencil (11).  The method's own bytes per triangle: its rest data
 * (K_e, 360 bytes), bending edges, the sqrt3 forest's records and edge map,
 * the sb_mesh with its edges and locator; per vertex the reference, masses,
 * loads, the forest's parents and weights (260 bytes + 24 per load).  The
 * 1500 bytes per triangle are fitted to the peak resident size of the
 * curtain (one step, linearized) at --res 200 and 400: estimate / peak
 * 1.01 and 0.97 (docs/cli.md "Sizes and memory"). */
static int a3_estimate(const sb_scene *scene, const sb_method_config *cfg, sb_method_size *sz)
{
    const sb_paramset *ps = cfg->params;
    const int n = cfg->res > 0 ? cfg->res : (scene->default_res > 0 ? scene->default_res : 16);
    const int ct = (int)pval(ps, "method.cells_t", 0);
    const int m = cfg->res_t > 0 ? cfg->res_t : ct > 0 ? ct : n;
    if (n > SB_SCENE_MAX_RESOLUTION || m > SB_SCENE_MAX_RESOLUTION)
        return sb_error(cfg->ctx, SB_ERR_INPUT, "adaptive_sqrt3: %d x %d cells requested, at most %d per side are "
                        "supported", n, m, SB_SCENE_MAX_RESOLUTION);
    char msg[512];
    if (limits_check(ps, msg, sizeof msg)) return sb_error(cfg->ctx, SB_ERR_INPUT, "adaptive_sqrt3: %s", msg);
    const int crossed = (int)pval(ps, "method.mesh", 0) == 2;
    const int adaptive = (int)pval(ps, "method.adaptive", 1), gmax = (int)pval(ps, "method.max_generation", 6);
    const double cells = (double)n * m, nv0 = ((double)n + 1) * ((double)m + 1) + (crossed ? cells : 0);
    const double nt0 = (crossed ? 4.0 : 2.0) * cells;
    double nt = nt0, nv = nv0;
    if (!adaptive) refined_size(&nt, &nv, gmax);
    fill_size(sz, nt, nv, scene->n_loads);
    if (adaptive) {
        /* An adaptive run may refine every triangle to g_max (a curvature
         * above every limit everywhere), so the fully refined mesh must fit
         * too: refused here, naming method.max_generation, instead of
         * running out of memory mid-run (issue 40).  The run's own memory
         * check then estimates the base mesh the run starts from.  The
         * sample grid and probes are left out of this bound (small). */
        double ntf = nt0, nvf = nv0;
        refined_size(&ntf, &nvf, gmax);
        sb_method_size szf;
        fill_size(&szf, ntf, nvf, scene->n_loads);
        sb_memory_run mr = { scene->time.mode == SB_TIME_DYNAMIC, scene->time.steps, 0, 0, 0, SB_SUPERNODES_CHOLMOD, 0, 0 };
        sb_memory_estimate est, base;
        sb_memory_estimate_run(sz, &mr, &base);
        sb_memory_estimate_run(&szf, &mr, &est);
        const double given = pval(ps, "run.max_memory", 0.0) * 1e9;
        const double limit = given > 0 ? given : sb_memory_physical();
        /* a base mesh over the limit is the core's refusal (sb_memory_check) */
        const int base_fits = !(limit > 0 && base.bytes > limit) && base.dofs <= INT_MAX && base.nnz <= INT_MAX;
        if (base_fits && (!(ntf * 3.0 <= INT_MAX) || !(est.dofs <= INT_MAX) || !(est.nnz <= INT_MAX) || (limit > 0 && est.bytes > limit))) {
            char need[32], have[32];
            sb_memory_format(est.bytes, need, sizeof need);
            sb_memory_format(limit, have, sizeof have);
            return sb_error(cfg->ctx, SB_ERR_INPUT, "adaptive_sqrt3: method.max_generation = %d on the %d x %d base mesh "
                            "allows %.3g triangles (%.3g dofs) when the criterion refines everywhere, which would need "
                            "about %s of memory (limit %s%s) or exceed the int indices; lower method.max_generation or "
                            "the base resolution", gmax, n, m, ntf, 3.0 * nvf, need, have,
                            given > 0 ? ", run.max_memory" : ", the machine's physical memory");
        }
    }
    return SB_OK;
}

static int a3_create(void *state, const sb_scene *scene, const sb_method_config *cfg)
{
    a3_state *S = state;
    memset(S, 0, sizeof *S);
    S->scene = scene;
    S->ctx = cfg->ctx;
    const sb_paramset *ps = cfg->params;
    S->pattern = (int)pval(ps, "method.mesh", 0);
    S->cells_t = (int)pval(ps, "method.cells_t", 0);
    S->res = cfg->res > 0 ? cfg->res : (scene->default_res > 0 ? scene->default_res : 16);
    if (cfg->res_t > 0 && S->cells_t > 0 && cfg->res_t != S->cells_t)
        return a3_fail(S, SB_ERR_INPUT, "--res %dx%d and method.cells_t=%d say different things about the cells along t",
                       S->res, cfg->res_t, S->cells_t);
    if (cfg->res_t > 0) S->cells_t = cfg->res_t;
    if (S->cells_t <= 0) S->cells_t = S->res;
    if (S->res > SB_SCENE_MAX_RESOLUTION || S->cells_t > SB_SCENE_MAX_RESOLUTION)
        return a3_fail(S, SB_ERR_INPUT, "%d x %d cells requested, at most %d per side are supported", S->res, S->cells_t,
                       SB_SCENE_MAX_RESOLUTION);
    if (cfg->levels > 1)
        return a3_fail(S, SB_ERR_UNSUPPORTED, "--levels %d asks for a hierarchy, which adaptive_sqrt3 has not", cfg->levels);
    int rc = refuse(S, scene);
    if (rc) return rc;
    S->adaptive = (int)pval(ps, "method.adaptive", 1);
    S->max_gen = (int)pval(ps, "method.max_generation", 6);
    S->adapt_every = (int)pval(ps, "method.adapt_every", 5);
    S->curv_base = pval(ps, "method.curv_base", 2);
    S->curv_max = pval(ps, "method.curv_max", 20);
    S->coarsen_frac = pval(ps, "method.coarsen_fraction", 0.5);
    char msg[512];
    if (limits_check(ps, msg, sizeof msg)) return a3_fail(S, SB_ERR_INPUT, "%s", msg);
    /* Eq. 9 from the scene's material (mapping: a3.h) */
    const sb_material_spec *mt = &scene->material;
    const double h = mt->thickness;
    if (mt->kind == SB_MAT_DENIM) {
        /* the denim law's tangent at zero strain (RMTR paper Eq. 3.3-3.4 with
         * phi_j'(0) = 1): psi = k1/2 E11^2 + k2 E11 E22 + k3/2 E22^2 + k4 E12^2,
         * so C = h [[k1, k2, 0], [k2, k3, 0], [0, 0, 2 k4]] in the warp/weft
         * frame (assumption: the sqrt3 model is linear, the softening of the
         * fitted law is not modelled); method.Es overrides E_s, Ey_ratio is
         * ignored.  Bending: D = h^3 (k1 + k3) / 24, the mean of warp and weft
         * (the isometric model has one bending stiffness). */
        const double *k = mt->denim.k;
        S->Ex = h * k[0];
        S->Ey = h * k[2];
        S->nu_xy = k[1] / k[2];
        S->nu_yx = k[1] / k[0];
        S->Es = pval(ps, "method.Es", 0.0) > 0.0 ? pval(ps, "method.Es", 0.0) : 2.0 * h * k[3];
        const double C[9] = { h * k[0], h * k[1], 0, h * k[1], h * k[2], 0, 0, 0, S->Es };
        memcpy(S->C, C, sizeof C);
        S->kb = h * h * h * (k[0] + k[2]) / 24.0 / 3.0;
    } else {
        const double Y = mt->young, nu = mt->poisson;
        S->Ex = Y * h;
        S->Ey = pval(ps, "method.Ey_ratio", 1.0) * S->Ex;
        S->nu_xy = nu;
        S->nu_yx = nu * S->Ey / S->Ex;
        S->Es = pval(ps, "method.Es", 0.0) > 0.0 ? pval(ps, "method.Es", 0.0) : 2.0 * Y * h / (1.0 + nu);
        const double d = 1.0 - S->nu_xy * S->nu_yx;
        const double C[9] = { S->Ex / d, S->Ex * S->nu_yx / d, 0, S->Ey * S->nu_xy / d, S->Ey / d, 0, 0, 0, S->Es };
        memcpy(S->C, C, sizeof C);
        /* bending stiffness factor k_b = D / 3 (assumption, a3.h) */
        S->kb = Y * h * h * h / (12.0 * (1.0 - nu * nu)) / 3.0;
    }
    rc = a3_build(S);
    if (rc) {
        if (rc == SB_ERR_NOMEM) a3_fail(S, rc, "out of memory building the %d x %d mesh", S->res, S->cells_t);
        a3_free(S);
        return rc;
    }
    return SB_OK;
}

static int a3_n_levels(const void *state) { (void)state; return 1; }
static int a3_n_dofs(const void *state, int level) { return level == 0 ? ((const a3_state *)state)->n_dofs : 0; }
static int a3_block_size(const void *state, int level) { (void)state; (void)level; return 3; }

/* element node lists in the order a3_energy adds its blocks */
static int a3_pattern(const void *state, int level, sb_pattern_builder *pb)
{
    const a3_state *S = state;
    (void)level;
    for (int t = 0; t < S->nt; t++) {
        int rc = sb_pattern_builder_add(pb, 3, S->tri[t].v);
        if (rc) return rc;
    }
    for (int k = 0; k < S->n_edge; k++) {
        int rc = sb_pattern_builder_add(pb, 4, S->edge[k].v);
        if (rc) return rc;
    }
    return SB_OK;
}

static int a3_initial(const void *state, int level, double *x)
{
    const a3_state *S = state;
    (void)level;
    memcpy(x, S->x_ref, sizeof(double) * (size_t)S->n_dofs);
    return SB_OK;
}

static int a3_set_step(void *state, const sb_step_info *si)
{
    a3_state *S = state;
    for (int k = 0; k < S->scene->n_loads; k++) S->load_factor[k] = si->load_factor[k];
    for (int b = 0; b < S->scene->n_bcs; b++) S->motion_factor[b] = si->motion_factor[b];
    a3_bc_update(S);
    a3_loads_update(S);
    return SB_OK;
}

static const sb_dirichlet *a3_dirichlet(const void *state, int level)
{
    const a3_state *S = state;
    (void)level;
    return S->n_con ? &S->dir : NULL;
}

static int a3_energy_op(void *state, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    (void)level;
    return a3_energy(state, x, f, g, H);
}

static int a3_mass_op(void *state, int level, sb_matrix *M)
{
    (void)level;
    return a3_mass(state, M);
}

static int a3_eval(const void *state, int level, const double *x, int np, const double *st, double *pos)
{
    const a3_state *S = state;
    (void)level;
    for (int p = 0; p < np; p++) {
        double b[3];
        const int t = sb_mesh_locate(&S->mesh, &S->loc, st[2 * p], st[2 * p + 1], b);
        if (t < 0)
            return a3_fail(S, SB_ERR_INPUT, "point (s,t) = (%g,%g) lies outside the mesh", st[2 * p], st[2 * p + 1]);
        const int *v = S->mesh.tri + 3 * t;
        for (int c = 0; c < 3; c++)
            pos[3 * p + c] = b[0] * x[3 * v[0] + c] + b[1] * x[3 * v[1] + c] + b[2] * x[3 * v[2] + c];
    }
    return SB_OK;
}

/* the triangles themselves (the discretization is piecewise linear) */
static int a3_surface(void *state, int level, const double *x, sb_surface *out)
{
    a3_state *S = state;
    (void)level;
    const sb_mesh *m = &S->mesh;
    if (sb_surface_alloc_tris(out, m->nv, m->nt, 1, 1) ||
        !(out->tri_st = malloc((size_t)(m->nt ? m->nt : 1) * 6 * sizeof(double))))
        return SB_ERR_NOMEM;
    memcpy(out->vert, x, (size_t)m->nv * 3 * sizeof(double));
    memcpy(out->vert_ref, S->x_ref, (size_t)m->nv * 3 * sizeof(double));
    memcpy(out->vert_st, m->st, (size_t)m->nv * 2 * sizeof(double));
    memcpy(out->tri, m->tri, (size_t)m->nt * 3 * sizeof(int));
    memcpy(out->tri_st, m->tri_st, (size_t)m->nt * 6 * sizeof(double));
    snprintf(out->what, sizeof out->what, "%d triangles of the adaptive_sqrt3 mesh (exact)", m->nt);
    return SB_OK;
}

/* checkpoints of adaptive runs (sb_method.h save_mesh / restore_mesh): the
 * sqrt3 forest is the whole discretization; the model is rebuilt from it
 * from scratch, as after every adaptation (a3_adapt.c) */
static int a3_save_mesh(const void *state, sb_blob *b)
{
    const a3_state *S = state;
    return a3_forest_save(&S->forest, b);
}

static int a3_restore_mesh(void *state, const sb_blob *b)
{
    a3_state *S = state;
    char msg[256];
    int rc = a3_forest_load(&S->forest, b, msg, sizeof msg);
    if (rc) return a3_fail(S, rc, "%s", msg);
    a3_free_model(S);
    return a3_build_model(S);
}

/* contact sample points (docs/contact.md): the vertices of the current mesh
 * and the per_side-fold barycentric subdivision points of its triangles, as
 * linear_fem's; the core re-creates them after every adaptation
 * (sb_problem_rebuild).  Every point's terms lie in one triangle, whose three
 * vertices the membrane couples in the pattern (a3_pattern). */
static int a3_contact_points(void *state, int level, int per_side, sb_contact_points *cp)
{
    (void)level;
    const a3_state *S = state;
    return sb_contact_points_mesh(&S->mesh, per_side, cp);
}

static void a3_describe(const void *state, char *buf, size_t len)
{
    const a3_state *S = state;
    snprintf(buf, len, "%dx%d %s base mesh, %s (max generation %d): %d vertices, %d triangles, %d bending edges; "
             "corotational orthotropic membrane E_x %g, E_y %g, E_s %g N/m, nu_xy %g; isometric bending k_b %g; "
             "Voronoi lumped mass", S->res, S->cells_t, mesh_choices[S->pattern],
             S->adaptive ? "sqrt3-adaptive" : "full resolution", S->max_gen, S->nv, S->nt, S->n_edge, S->Ex,
             S->Ey, S->Es, S->nu_xy, S->kb);
}

const sb_method_type sb_method_adaptive_sqrt3 = {
    .name = "adaptive_sqrt3",
    .description = "Bender & Deul corotational triangle cloth (orthotropic membrane, isometric bending, Voronoi "
                   "masses) on a sqrt3-adaptive mesh; lagged rotations: linearized solver only",
    .state_size = sizeof(a3_state),
    .params = a3_params,
    .flags = SB_METHOD_RES_ST | SB_METHOD_IMPULSE_SELF,
    .create = a3_create,
    .destroy = a3_destroy,
    .estimate = a3_estimate,
    .n_levels = a3_n_levels,
    .n_dofs = a3_n_dofs,
    .block_size = a3_block_size,
    .pattern = a3_pattern,
    .initial = a3_initial,
    .set_step = a3_set_step,
    .dirichlet = a3_dirichlet,
    .energy = a3_energy_op,
    .mass = a3_mass_op,
    .impulse_response = a3_impulse_response,
    .eval_points = a3_eval,
    .describe = a3_describe,
    .surface = a3_surface,
    .adapt = a3_adapt,
    .adapt_state = a3_adapt_state,
    .save_mesh = a3_save_mesh,
    .restore_mesh = a3_restore_mesh,
    .contact_points = a3_contact_points,
};
