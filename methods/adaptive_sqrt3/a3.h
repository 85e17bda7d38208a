/* a3.h — private declarations of adaptive_sqrt3: Bender & Deul's
 * corotational triangle cloth model (paper 003, "sqrt3 paper" below) on the
 * shared triangle-mesh layer (core/mesh).  This file states the model and
 * every choice the paper leaves open.
 *
 * What is implemented (issue 22, priority 1): the model at full resolution
 * (every triangle of the generated mesh is simulated; there is no refinement
 * or coarsening yet, so the mesh is fixed for a run):
 *
 *  membrane  orthotropic linear elasticity (Eq. 5-10) in the corotational
 *            formulation (Eq. 11-17).  Per triangle (a, b, c) the rest
 *            positions are projected once into 2D, x0bar (Eq. 13).  At a
 *            state x the plane vectors p_x, p_y (Eq. 11) give P (Eq. 12),
 *            T (Eq. 14), F = T S^-1 and its rotation R by the 2D polar
 *            decomposition; R_p = P^T R (Eq. 15) and
 *              f_e = -R_p K_e (R_p^T x - x0bar)         (Eq. 16-17)
 *            with K_e = A_e B_e^T C B_e (Eq. 10), C of Eq. 9.
 *            What the method returns to the core (sb_method.h):
 *              E  = sum_e 1/2 u^T K_e u,  u = R_p^T x - x0bar  (R at x)
 *              g  = sum_e R_p K_e u       (= -f_e, the paper's force)
 *              H  = sum_e R_p K_e R_p^T   (K_e^R of Eq. 16: the rotation is
 *                                          lagged, its derivative dropped)
 *            g is NOT the gradient of E for an orthotropic C (the rotation's
 *            derivative does not cancel; tests/test_a3_energy.c measures it),
 *            and H is not the derivative of g.  So the method does not carry
 *            SB_METHOD_POTENTIAL: only single-step solvers (linearized, i.e.
 *            the linear implicit Euler of Eq. 21) run it; the others are
 *            refused by sb_run_combination_check with a sentence.
 *  bending   the isometric model of Bergou et al. (Eq. 18-19): per interior
 *            edge a constant Q(e) = 3/(A_0 + A_1) k^T k (x I_3), from the
 *            rest mesh's cotangents, E_b = (k_b / 2) sum_e x^T Q(e) x.
 *            The paper gives no stiffness factor k_b.  Assumption: k_b = D/3,
 *            D = Y h^3 / (12 (1 - nu^2)), so that for small dihedral angles
 *            E_e = (D/2) theta^2 l_e^2 / (A_0 + A_1): linear_fem's hinge
 *            calibration (plate energy for cylindrical bending across
 *            grid-aligned edges; tests check it on a cylinder).  The model
 *            assumes a flat rest state (Bergou: isometric deformations of a
 *            flat sheet), so non-planar reference charts are refused.
 *            Boundary edges carry no bending (free edges).
 *  damping   Rayleigh D = alpha M + beta K (Eq. 20): done by the core
 *            (sb_problem.c) with K = the H above at x_n.
 *  mass      lumped, hybrid Voronoi areas (Meyer et al.; Alg. 1, Eq. 1, 3)
 *            of the rest mesh times the areal density rho.
 *  time      the core's linearized solver is one Newton step on the
 *            incremental potential from x_n: (M/dt^2 + D/dt + K) dx = ...,
 *            which is Eq. 21 multiplied by dt^2 with dx = dt (v + dv).
 *
 * Material mapping (assumption; the paper writes C in membrane stiffnesses
 * N/m): the scene's StVK material gives E_x = E_y = Y h, nu_xy = nu_yx = nu.
 * Eq. 7 puts 1/2 into the shear row of B (gamma = tensor shear strain), so
 * the isotropic law needs E_s = 4 mu h = 2 Y h / (1 + nu); that is the
 * default of method.Es (0).  method.Es > 0 sets E_s in N/m (the paper's
 * curtain: 1000 N/m), method.Ey_ratio scales E_y (orthotropy).  The 2D rest
 * frame of every triangle is the material's warp/weft frame (chart
 * direction d/ds rotated by material.warp_angle in the triangle's plane), so
 * C of Eq. 9 acts in its own axes; R absorbs the frame's rotation.
 *
 * Denim (RMTR paper Eq. 3.3-3.4): its small-strain tangent,
 * C = h [[k1, k2, 0], [k2, k3, 0], [0, 0, 2 k4]], and D = h^3 (k1 + k3) / 24
 * (a3_method.c); the fitted law's nonlinearity is not modelled.
 *
 * Refused with one sentence (exit 2): non-planar charts,
 * clamped / symmetry bcs and moving bcs with clamp_tangent (no rotational
 * dofs, no boundary bending), pressure and end-moment loads, point parts that
 * are not mesh vertices.
 *
 * DOFs: 3 per vertex, dof 3 v + c; one level; pattern = the triangles, then
 * the interior edges (4-vertex bending stencils, Fig. 3). */
#ifndef A3_H
#define A3_H

#include "sb_method.h"
#include "sb_mesh.h"
#include "a3_sqrt3.h"

typedef struct a3_tri {
    int v[3];                 /* corners a, b, c */
    double x0[6];             /* rest positions in 2D (Eq. 13): a at the origin */
    double K[36];             /* K_e = A_e B^T C B (Eq. 10), 6 x 6 */
    double area;              /* A_e, rest area */
} a3_tri;

typedef struct a3_edge {      /* interior edge e0 of Fig. 3 */
    int v[4];                 /* x0, x1 (the edge), x2 (opposite in t0), x3 (opposite in t1) */
    double k[4];              /* Eq. 19 */
    double q;                 /* k_b * 3 / (A_0 + A_1) (Eq. 18 with the stiffness factor) */
} a3_edge;

typedef struct a3_con { int dof; int bc; } a3_con;   /* bc of a moving constraint, -1 held */

typedef struct a3_state {
    const sb_scene *scene;
    struct sb_context *ctx;
    int res, cells_t, pattern;
    double C[9];              /* Eq. 9, row-major */
    double Ex, Ey, Es, nu_xy, nu_yx;
    double kb;                /* bending stiffness factor (k_b = D/3) */
    /* adaptivity (a3_adapt.c, a3_sqrt3.h) */
    int adaptive, max_gen, adapt_every;
    double curv_base, curv_max, coarsen_frac;
    a3_forest forest;
    int *vmap;                /* mesh vertex -> forest vertex */
    int *tmap;                /* mesh triangle -> forest triangle */
    double *x_new, *v_new;    /* the state mapped by the last adaptation */
    int n_adapt_changes;
    sb_mesh mesh;
    sb_mesh_locator loc;
    int nv, nt, n_edge, n_dofs;
    double *x_ref;            /* 3 nv */
    a3_tri *tri;
    a3_edge *edge;
    double *mass;             /* nv: rho A_hybrid (Alg. 1, Eq. 3) */
    /* boundary conditions */
    int n_con;
    a3_con *con;
    int *con_dofs;
    double *con_vals;
    sb_dirichlet dir;
    /* dead loads */
    double *load_vec;         /* n_loads x n_dofs, unit factor */
    double *f_ext;
    double load_factor[SB_SCENE_MAX_LOADS];
    double motion_factor[SB_SCENE_MAX_BCS];
} a3_state;

int a3_fail(const a3_state *S, int status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* ---- elements (a3_element.c) ---------------------------------------------- */
/* Rest data of a triangle from its rest corners X (3 x 3) and the warp
 * direction w (unit, in the triangle's plane).  SB_ERR_INPUT if degenerate. */
int    a3_tri_init(a3_tri *T, const double *Xa, const double *Xb, const double *Xc, const double w[3],
                   const double C[9]);
/* Corotational membrane (Eq. 11-17) at the corners' positions q[9]:
 * E = 1/2 u^T K u, g[9] += R_p K u, H[81] += R_p K R_p^T (when non-NULL).
 * Rp (3 x 2, row-major) receives R_p when non-NULL; a given Rp_fixed (not
 * NULL) is used instead of the one at q (the frozen-rotation energy, whose
 * g and H are its exact derivatives).  Returns E (NaN when the current
 * triangle is degenerate). */
double a3_membrane(const a3_tri *T, const double *q, const double *Rp_fixed, double *Rp, double *g, double *H);
/* cotangent weights k (Eq. 19) of the edge x0-x1 with opposite x2 (t0), x3 (t1) */
void   a3_bend_weights(const double *X0, const double *X1, const double *X2, const double *X3, double k[4]);
/* Isometric bending of one edge (Eq. 18): E = q/2 |sum k_i x_i|^2, g[12], H[144] += */
double a3_bend(const a3_edge *e, const double *q12, double *g, double *H);
/* hybrid Voronoi areas of the corners of triangle (Xa, Xb, Xc) (Alg. 1, Eq. 1) */
void   a3_voronoi(const double *Xa, const double *Xb, const double *Xc, double A[3]);

/* ---- model data (a3_build.c) ---------------------------------------------- */
/* base mesh, sqrt3 forest (refined to max_gen unless adaptive), model */
int  a3_build(a3_state *S);
/* the model on the forest's current mesh (mesh, x_ref, triangles, edges,
 * masses, bcs, loads), built from scratch */
int  a3_build_model(a3_state *S);
void a3_free_model(a3_state *S);
void a3_free(a3_state *S);

/* ---- adaptation (a3_adapt.c) ------------------------------------------------ */
/* mean curvature |c(x_i)| of every mesh vertex (Eq. 22; 0 on the boundary) */
int  a3_curvature(const a3_state *S, const double *x, double *c);
int  a3_adapt(void *state, const double *x, const double *v, int *changed);
int  a3_adapt_state(void *state, double *x, double *v);
void a3_bc_update(a3_state *S);
void a3_loads_update(a3_state *S);

/* ---- assembly (a3_energy.c) ----------------------------------------------- */
int  a3_energy(a3_state *S, const double *x, double *f, double *g, sb_matrix *H);
int  a3_mass(a3_state *S, sb_matrix *M);

/* ---- Bridson et al. 2002 collision response (a3_impulse.c) ---------------- */
struct sb_impulse_stats;
int  a3_impulse_response(void *state, const sb_scene *scene, double dt, double t1, const double *x0, double *x1,
                         struct sb_impulse_stats *st);

extern const sb_param_def a3_params[];
extern const sb_method_type sb_method_adaptive_sqrt3;

#endif
