/* sb_method.h — a discretization of a scene, as a constant table of function
 * pointers plus a private state blob (GSL "type" style).
 *
 * DOFs.  A method works on a full DOF vector x in R^n per level (positions,
 * or Hermite generalized coordinates).  Dirichlet-type constraints (fixed,
 * clamped, symmetry, moving) are reported as a constant set of constrained DOF
 * indices with time-dependent values; the core eliminates them (gradient
 * entries zeroed, Hessian rows/columns replaced by identity).  Penalty-type
 * boundary conditions (RMTR paper Eq. 3.6) are part of the method's energy.
 *
 * The energy a method returns is E_elastic + E_external + E_penalty at the
 * step set by set_step(); the core adds inertia and damping (DESIGN.md). */
#ifndef SB_METHOD_H
#define SB_METHOD_H

#include "sb_scene.h"
#include "sb_params.h"
#include "sb_sparse.h"
#include "sb_material_state.h"
#include "sb_blob.h"

struct sb_context;
struct sb_csr;
struct sb_surface;
struct sb_contact_points;
struct sb_impulse_stats;

enum {
    SB_METHOD_HIERARCHY = 1u << 0,    /* provides prolong / restrict_adj / project */
    SB_METHOD_POTENTIAL = 1u << 1,    /* energy is a true potential (all solvers apply) */
    SB_METHOD_TEST_FIXTURE = 1u << 2, /* test fixture, not a real discretization */
    SB_METHOD_RES_ST = 1u << 3,       /* honours sb_method_config.res_t (--res NxM) */
    SB_METHOD_IMPULSE_SELF = 1u << 4, /* impulse_response also resolves self-collision (contact.self) */
    SB_METHOD_NODAL_DERIVATIVES = 1u << 5, /* nodes carry first derivatives as generalized coordinates
                                              (Hermite): honours a moving bc's "derivative" key */
    SB_METHOD_PENALTY_BCS = 1u << 6   /* every boundary condition by penalty (dirichlet() is NULL): no
                                         constrained dofs, so no lifting of boundary motion (its
                                         factorization is not in the memory estimate) */
};

/* The most terms point_terms may return (16 Hermite/B-spline functions). */
#define SB_POINT_TERMS_MAX 16

typedef struct sb_method_config {
    int res;                    /* finest resolution (elements per side); 0 = method default */
    int levels;                 /* levels in the hierarchy (>= 1) */
    const sb_paramset *params;  /* resolved "method.*" parameters */
    struct sb_context *ctx;     /* for error messages */
    int res_t;                  /* elements along t when they differ from res (--res NxM); 0 = res;
                                   only for methods with SB_METHOD_RES_ST */
} sb_method_config;

/* What the current step prescribes.  Ramps are computed once by the core. */
typedef struct sb_step_info {
    int step;                   /* 1-based */
    int n_steps;
    double t;                   /* time at the end of the step (quasi-static: step index) */
    double dt;                  /* 0 for quasi-static */
    double load_factor[SB_SCENE_MAX_LOADS];   /* per scene load */
    double motion_factor[SB_SCENE_MAX_BCS];   /* per scene bc (moving) */
} sb_step_info;

typedef struct sb_dirichlet {
    int n;                      /* number of constrained dofs (constant over a run) */
    const int *dofs;            /* sorted, unique */
    const double *values;       /* prescribed values at the current step */
} sb_dirichlet;


/* How far a state violates the constraints a method imposes by penalty
 * (optional op penalty_violation; run.penalty_tol, docs/trust.md). */
typedef struct sb_penalty_report {
    int points;                 /* penalty points evaluated (0: the scene has none) */
    double beta;                /* penalty factor of the level (the method's units) */
    double position_max;        /* max |x - b| over position constraints (m) */
    double rotation_max;        /* max |theta| over rotation (slope) constraints (rad) */
} sb_penalty_report;
/* The size of the discretization `create` would build, from the scene and
 * the config alone (no allocation): the core refuses a run that cannot fit
 * before any work (sb_memory.h).  Counts are doubles so that an absurd
 * request is measured, not overflowed. */
typedef struct sb_method_size {
    int levels;
    int bs;                          /* dofs per node */
    double nodes[SB_MAX_LEVELS];     /* per level, coarsest first */
    double elements[SB_MAX_LEVELS];
    int nodes_per_element;           /* the most nodes an element couples (4 Hermite, 16 B-spline) */
    int stencil;                     /* the most nodes one node couples with, itself included */
    double method_bytes;             /* the method's own data: geometry, quadrature, transfers */
    double coarse_energy_bytes;      /* of it, what only a coarser level's own energy reads, built
                                        at its first use (rmtr: the coarse reference geometry):
                                        counted for the rmtr solver alone */
    double prolong_per_dof;          /* mean nonzeros of a fine dof's row of the prolongation
                                        between consecutive levels (0: counted as 1) */
    double mass_nnz[SB_MAX_LEVELS];  /* upper-triangle nonzeros of the mass matrix of a level when at
                                        most a quarter of its pattern's (sb_problem.c holds it by them,
                                        16 bytes each); 0: held on the pattern */
} sb_method_size;

typedef struct sb_method_type {
    const char *name;
    const char *description;
    size_t state_size;
    const sb_param_def *params;     /* "method.*" parameters, may be NULL */
    unsigned flags;

    int  (*create)(void *state, const sb_scene *scene, const sb_method_config *cfg);
    void (*destroy)(void *state);

    int  (*n_levels)(const void *state);
    int  (*n_dofs)(const void *state, int level);           /* level 0 = coarsest */
    /* DOFs per node of the level (3 for control points, 12 for Hermite nodes);
     * n_dofs = block_size * nodes. */
    int  (*block_size)(const void *state, int level);
    /* Add the element node lists of `level` to the builder (sb_sparse.h), in
     * the order energy()/mass() add their element blocks with
     * sb_matrix_add_element(). */
    int  (*pattern)(const void *state, int level, sb_pattern_builder *pb);
    /* Reference configuration (also the default initial state). */
    int  (*initial)(const void *state, int level, double *x);
    /* Prepare loads and boundary data for a step (all levels). */
    int  (*set_step)(void *state, const sb_step_info *si);
    /* Constrained dofs and their values at the current step; NULL if none. */
    const sb_dirichlet *(*dirichlet)(const void *state, int level);
    /* f = E(x); g += dE/dx and H += d2E/dx2 when non-NULL (the core zeroes
     * them first).  Returns SB_OK or SB_NONFINITE (recorded outcome). */
    int  (*energy)(void *state, int level, const double *x, double *f, double *g, sb_matrix *H);
    /* Add the mass matrix into M (dynamic scenes). */
    int  (*mass)(void *state, int level, sb_matrix *M);
    /* Positions at grid parameters st[2*np] into pos[3*np]. */
    int  (*eval_points)(const void *state, int level, const double *x, int np,
                        const double *st, double *pos);

    /* hierarchy (flags & SB_METHOD_HIERARCHY); coarse level lc -> lc+1 */
    int  (*prolong)(void *state, int lc, const double *xc, double *xf);      /* I */
    int  (*restrict_adj)(void *state, int lc, const double *gf, double *gc);  /* R = I^T */
    int  (*project)(void *state, int lc, const double *xf, double *xc);      /* P, P I = id */
    /* optional: I as a dof-level row-compressed matrix (fine rows, coarse
     * columns), filled with sb_csr_alloc (sb_galerkin.h); used once per run
     * for Galerkin coarse models.  NULL: the core probes prolong() instead. */
    int  (*prolong_matrix)(const void *state, int lc, struct sb_csr *S);

    /* optional: the material state of x on `level` (sb_material_state);
     * SB_OK, or SB_NONFINITE when some point could not be evaluated */
    int  (*material_state)(void *state, int level, const double *x, sb_material_state *ms);

    /* optional: the violation of the penalty-imposed constraints at x on
     * `level` (NULL: the method eliminates its constraints) */
    int  (*penalty_violation)(void *state, int level, const double *x, sb_penalty_report *r);
    /* optional: the sizes create() would build (sb_method_size); SB_OK, or
     * SB_ERR_INPUT with a sentence in cfg->ctx when the request cannot be
     * built at all.  NULL: the core measures the created method instead. */
    int  (*estimate)(const sb_scene *scene, const sb_method_config *cfg, sb_method_size *size);

    /* optional: one line describing the discretization ("8x8 Hermite patches") */
    void (*describe)(const void *state, char *buf, size_t len);

    /* optional: the surface of x on `level` for rendering (sb_surface.h):
     * the discretization's exact primitives (bicubic Bézier patches or
     * triangles) with the reference configuration in the same
     * parametrization; out starts zeroed, the caller frees it with
     * sb_surface_free().  NULL: `shellbench render` triangulates eval_points
     * on a grid instead (docs/render.md). */
    int  (*surface)(void *state, int level, const double *x, struct sb_surface *out);

    /* optional, adaptive meshes (issue 22; single-level methods only): the
     * run calls adapt(x, v) before step k when k - 1 is a positive multiple
     * of the parameter method.adapt_every (which the method declares; 0 =
     * never; a declared method.adaptive = 0 also means never).  The method may change its discretization; then it sets
     * *changed = 1 and holds x and v mapped onto its new dofs, which
     * adapt_state writes (n_dofs(0) each).  The core then re-queries dofs,
     * pattern, Dirichlet set and mass, redoes the symbolic analysis and
     * re-allocates the solver (sb_problem_rebuild); counted as event adapt. */
    int  (*adapt)(void *state, const double *x, const double *v, int *changed);
    int  (*adapt_state)(void *state, double *x, double *v);
    /* optional, adaptive meshes: what the method's current discretization
     * is (its mesh and whatever later adaptations need) as a blob of
     * integers and doubles for checkpoints (b starts zeroed; the caller
     * frees it with sb_blob_free), and restore_mesh, which rebuilds that
     * discretization from a blob of the same run before --resume continues
     * (afterwards the core re-queries dofs, pattern, Dirichlet set and mass
     * as after an adaptation).  A restored method must adapt later exactly
     * as the saved one would have (a resumed run equals an uninterrupted
     * one bit for bit).  SB_ERR_INPUT with a sentence for a blob it cannot
     * use.  Without them an adaptive run refuses --resume and
     * --stop-after-steps and writes no checkpoints. */
    int  (*save_mesh)(const void *state, sb_blob *b);
    int  (*restore_mesh)(void *state, const sb_blob *b);
    /* optional: the contact sample points of `level` (sb_contact_points.h,
     * docs/contact.md) — smooth methods a grid of per_side x per_side points
     * per element through their basis, triangle methods their vertices;
     * cp starts zeroed.  NULL: the method cannot run scenes with obstacles
     * (refused at set-up). */
    int  (*contact_points)(void *state, int level, int per_side, struct sb_contact_points *cp);
    /* optional (contact.model = "impulse", issue 25): the paper's own
     * collision response after an accepted step of a dynamic scene.  x0 is
     * the state at t_n, x1 the step's result at t_{n+1} (finest level, n_dofs
     * of the last level); the method corrects x1 in place so that its surface
     * moves from x0 to x1 without passing through an obstacle (or itself,
     * with contact.self); the run's velocity (x1 - x0)/dt follows.  Counts
     * into *st (core/contact/sb_impulse.h).  NULL: the method cannot run
     * contact.model = "impulse" (refused at set-up with a sentence). */
    int  (*impulse_response)(void *state, const struct sb_scene *scene, double dt, double t1, const double *x0,
                             double *x1, struct sb_impulse_stats *st);
    /* optional (sliding pins, core/problem/sb_pin.h): the basis of `level`
     * at grid parameter st as terms x(st) = sum_a w[a] (x[dof[a]], x[dof[a]+1],
     * x[dof[a]+2]), at most SB_POINT_TERMS_MAX, all within one element of the
     * level's pattern.  Returns the number of terms, or SB_ERR_INPUT when st
     * lies outside the domain.  NULL: the method holds nodes only (a scene
     * with a sliding pin is refused with a sentence). */
    int  (*point_terms)(const void *state, int level, const double st[2], int *dof, double *w);
    /* issue 38: the dofs of `level` that the method's penalty terms couple
     * (boundary conditions imposed by penalty): mask[i] = 1, else 0 (mask has
     * n_dofs(level) entries).  Returns how many are marked.  pcg-mg solves
     * them exactly inside its V-cycle (core/linalg/sb_precond_mg.c,
     * docs/krylov.md).  NULL: the method has no penalty terms. */
    int  (*penalty_support)(const void *state, int level, unsigned char *mask);
} sb_method_type;

/* registry (core/problem/sb_registry.c) */
const sb_method_type *sb_method_find(const char *name);
int sb_method_count(void);
const sb_method_type *sb_method_at(int i);

#endif
