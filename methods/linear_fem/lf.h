/* lf.h — private declarations of linear_fem, the triangle-mesh discrete
 * shell baseline (issue 21): piecewise-linear positions on the shared mesh
 * layer (core/mesh), a constant-strain membrane and a discrete second
 * fundamental form per triangle, both fed to the shared section law
 * sb_shell_section (core/shell) exactly as the Hermite and subdivision
 * methods feed it their strains.
 *
 * Bending models (method.bending):
 *
 *  midedge  Midedge-normal shape operator (Grinspun, Gingold, Reisman & Zorin
 *           2006; the formulation of Weischedel 2012 and Chen, Desbrun et
 *           al. 2018).  Every edge carries a unit "midedge normal" n_i at
 *           right angles to it, at angle alpha_i from the face normal of
 *           triangle T (towards the outward in-plane edge normal m_i).
 *           Interpolating the three midedge normals linearly over T
 *           (Crouzeix–Raviart, n = sum (1 - 2 lambda_i) n_i) and taking
 *           b_ab = -x_,a . n_,b in the barycentric coordinates
 *           (x_,1 = p1 - p0, x_,2 = p2 - p0) gives exactly
 *             b = [[w0 + w1, w0], [w0, w0 + w2]],   w_i = -2 h_i sin(alpha_i),
 *           h_i the altitude of T on edge i (own derivation, see lf_element.c);
 *           we take w_i = -2 h_i alpha_i (the angle, not its sine: same to
 *           third order, and bounded below under end moments).
 *           Director data (method.director):
 *             edge     alpha_i = psi_e / 2 + sigma_i phi_e with one scalar
 *                      dof phi_e per edge (the midedge normal's rotation away
 *                      from the average of the two face normals; psi_e the
 *                      signed dihedral angle, sigma_i = +-1 the side).  In the
 *                      linear regime this is the Morley plate element, which
 *                      converges to Kirchhoff–Love on arbitrary triangulations;
 *                      this is the default.
 *             average  phi_e = 0: the midedge normal is the normalized average
 *                      of the two face normals (no extra dofs).  Consistent
 *                      only where the two triangles of every edge form a
 *                      parallelogram (the `regular` mesh, small slopes): on
 *                      alternating diagonals the twist term and on jittered
 *                      meshes the whole shape operator carry O(1) errors, so
 *                      it is NOT expected to converge there (the bench shows it).
 *           Boundary edges: free -> alpha = sigma phi (edge) or 0 (average):
 *           zero moment in the edge variant; clamped -> alpha = the angle from
 *           the face normal to the clamp's normal (the reference face normal,
 *           rotated with a moving clamp), phi held; symmetry -> alpha = the
 *           angle to the normal of the symmetry plane's trace, phi held.
 *
 *  hinge    Discrete shells (Grinspun, Hirani, Desbrun & Schröder 2003):
 *           one energy per interior edge from its dihedral angle theta,
 *             E_e = R_e Psi(0, B_e),  B_e = kappa_e/2 m m^T (local frame),
 *             kappa_e = -(theta - theta_bar) l_e / R_e,  R_e = A_1 + A_2,
 *           with Psi the shared section law and m the reference in-plane
 *           normal of the edge.  For StVK E_e = (D/2) (theta - theta_bar)^2
 *           l_e^2 / (A_1 + A_2) — the Grinspun et al. 2003 form
 *           k (theta - theta_bar)^2 |e|^2 / A_e with A_e = (A_1 + A_2)/3 and
 *           k = D/6, calibrated (our assumption) so that cylindrical bending
 *           along a grid axis of the right-triangle meshes gives exactly the
 *           plate energy (D/2) kappa^2.  The hinge sees only normal curvatures
 *           across edges: it has no Poisson coupling and its stiffness depends
 *           on the mesh (on the regular mesh a cylinder bent along the
 *           diagonal is twice as stiff, the twist stiffness is 3/(1 - nu)
 *           times the plate's), so it is known NOT to converge to
 *           Kirchhoff–Love on general meshes (Wardetzky et al. 2007; the bench
 *           reports the limit it reaches).  Membrane and bending are separate
 *           (no membrane–bending coupling of nonlinear laws; exact for StVK).
 *           Clamped / symmetry edges get a ghost hinge with the mirror image of
 *           their triangle: theta = the angle to the clamp / symmetry normal,
 *           R = A_T.  Free and simply supported edges carry no hinge.
 *
 * Known limits (measured, results/linear_fem_report.md): edge directors
 * roll a strip under the fixed-axis end moment exactly up to ~1.85 pi, where
 * the planar state becomes unstable (smallest Hessian eigenvalue crosses zero
 * at ~1.88 pi, mesh independent); averaged directors and the hinge fail to
 * converge on alternate / jittered meshes (the hinge on every mesh); with
 * denim's softening law the fine triangle meshes localize strain.
 *
 * DOFs: 3 per vertex (dof 3 v + c) then, for midedge with edge directors,
 * one per edge (dof 3 nv + e); the pattern then uses blocks of 1.  Level 0 is
 * the coarsest; level l+1 is the 1-to-4 refinement of level l. */
#ifndef LF_H
#define LF_H

#include "sb_method.h"
#include "sb_mesh.h"
#include "sb_shell.h"

#define LF_NSLOT 6            /* positions in a triangle element: 3 corners + 3 opposite vertices */
#define LF_NED_MAX 21         /* element dofs: 18 positions + 3 edge directors */

enum { LF_BEND_MIDEDGE = 0, LF_BEND_HINGE = 1 };
enum { LF_DIR_EDGE = 0, LF_DIR_AVERAGE = 1 };
enum { LF_EDGE_FREE = 0, LF_EDGE_INTERIOR = 1, LF_EDGE_CLAMP = 2, LF_EDGE_SYM = 3 };

/* ---- geometry derivatives (lf_geom.c) ------------------------------------ */

/* How a 3-vector w of an element depends on its points P_s (3 each): either
 * a triangle normal w = P_x x P_y + P_y x P_z + P_z x P_x (bilinear), or a
 * linear map w = sum_k B_k P_slot[k], or a constant. */
typedef struct lf_dep {
    int kind;                 /* LF_DEP_CONST, LF_DEP_NORMAL, LF_DEP_LINEAR */
    int n;                    /* terms */
    int slot[3];
    double B[3][9];           /* LINEAR: 3x3 row-major blocks; NORMAL: filled by lf_dep_normal */
} lf_dep;
enum { LF_DEP_CONST = 0, LF_DEP_NORMAL = 1, LF_DEP_LINEAR = 2 };

void lf_dep_normal(lf_dep *d, const double *P, int sx, int sy, int sz);   /* P: 3 per slot */
void lf_dep_edge(lf_dep *d, int sa, int sb);                             /* w = P_b - P_a */
void lf_dep_cross_edge(lf_dep *d, int sa, int sb, const double g[3]);    /* w = (P_b - P_a) x g */
/* Chain rule: F(w0, w1, w2) with gradient g[9] and Hessian H[81] (rows and
 * columns w0, w1, w2) to the points.  Accumulates G[3 ns] and K[3ns x 3ns]
 * (row-major, leading dimension ld) when non-NULL. */
void lf_chain(const lf_dep dep[3], const double g[9], const double *H, int ld, double *G, double *K);

/* Signed angle from u to v about e (u, v at right angles to e):
 * psi = atan2((u x v).e, |e| u.v), with gradient g[9] and Hessian H[81]
 * w.r.t. (u, v, e) when non-NULL. */
double lf_angle(const double u[3], const double v[3], const double e[3], double *g, double *H);
/* |u| / |e|, gradient g[9] and Hessian H[81] w.r.t. (u, ., e) (v slot zero). */
double lf_ratio(const double u[3], const double e[3], double *g, double *H);

/* ---- reference data ------------------------------------------------------ */

typedef struct lf_tri {
    int v[3];                 /* corners */
    int o[3];                 /* vertex opposite edge i across it, -1 if none */
    int e[3];                 /* mesh edge opposite corner i */
    signed char sigma[3];     /* +1 when the triangle runs edge i in the edge's orientation */
    signed char kind[3];      /* LF_EDGE_* */
    short bc[3];              /* scene bc of a clamp / symmetry edge, -1 */
    double c[3];              /* alpha_i = c_i psi_i + sigma_i phi_i */
    double gv[3][3];          /* clamp: ghost normal (current); symmetry: sign x plane normal */
    double gv0[3][3];         /* clamp: ghost normal at the reference */
    double bbar[3];           /* reference b (11, 22, 12) */
    sb_shell_ref ref;         /* metric, frame T, dA = area */
} lf_tri;

typedef struct lf_hinge {
    int v[4];                 /* Pa, Pb (edge, in t0's orientation), Pc (opposite in t0), Pd (t1) or -1 */
    int tri;                  /* t0 */
    int edge;
    signed char kind;         /* LF_EDGE_INTERIOR, _CLAMP, _SYM */
    short bc;
    double gv[3], gv0[3];     /* ghost (clamp normal / symmetry sign x axis) */
    double theta_bar;
    double coef;              /* l_e / R_e */
    double R;                 /* A_1 + A_2 (interior), A_T (ghost) */
    double Bdir[3];           /* local-frame bending strain per unit kappa: (m1^2, m2^2, m1 m2) / 2 */
} lf_hinge;

typedef struct lf_mq {         /* end-moment edge (one per boundary edge of the part) */
    int tri, slot;            /* triangle and the corner opposite the edge */
    int edge, load;
    double weight;            /* reference edge length */
    double axis[3], ub[3], e2[3], theta_b;
} lf_mq;

typedef struct lf_con { int dof; int bc; } lf_con;   /* bc of a moving constraint, -1 held */

typedef struct lf_level {
    sb_mesh mesh;
    sb_mesh_locator loc;
    sb_mesh_refinement rf;    /* level >= 1: the refinement that made this level */
    int nv, ne, nt, n_dofs;
    int n_hinge;
    double *x_ref;            /* n_dofs */
    lf_tri *tri;
    lf_hinge *hinge;
    /* boundary conditions */
    int n_con;
    lf_con *con;
    int *con_dofs;
    double *con_vals;
    sb_dirichlet dir;
    /* loads */
    double *load_vec;         /* n_loads x n_dofs */
    double *f_ext;
    int n_mq;
    lf_mq *mq;
    int *tri_mq;              /* nt + 1 offsets into mq (sorted by triangle) */
    int rebranch;
    /* prolongation from the next coarser level: fine dof rows */
    int *p_ptr, *p_col;
    double *p_w;
} lf_level;

typedef struct lf_state {
    const sb_scene *scene;
    struct sb_context *ctx;
    sb_material mat;
    sb_shell_isa isa;           /* vector width of the section law (run.vectors) */
    int bending, director, pattern, lumped;
    sb_hess_kind hess;
    double jitter;
    double imperfection;      /* m: out-of-plane reference noise (sb_imperfection.c), 0 = none */
    unsigned long seed;
    const char *rng_name;
    int n_levels, res, cells_t;
    int edge_dofs;            /* midedge with edge directors */
    lf_level lv[SB_MAX_LEVELS];
    double load_factor[SB_SCENE_MAX_LOADS];
    double motion_factor[SB_SCENE_MAX_BCS];
    double p_follow;          /* follower pressure at the current step */
    /* element scratch */
    double qe[LF_NED_MAX], ge[LF_NED_MAX];
    double *Ke, *psd_work;
} lf_state;

int lf_fail(const lf_state *S, int status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* element local dof of slot s (0..5), component c: 3 s + c; edge director i: 18 + i */
static inline int lf_ned(const lf_state *S) { return S->bending == LF_BEND_HINGE ? 9 : S->edge_dofs ? 21 : 18; }

/* ---- level (lf_level.c) ---------------------------------------------------- */
int  lf_level_build(lf_state *S, int l);
void lf_level_free(lf_level *L);
/* element dof list (global dofs, -1 missing) of triangle t; returns its length */
int  lf_tri_dofs(const lf_state *S, const lf_level *L, int t, int *d);
void lf_gather(const lf_state *S, const lf_level *L, int t, const double *x, double *qe);
int  lf_eval(const lf_state *S, const lf_level *L, const double *x, int np, const double *st, double *pos);
/* The mesh of x on `level` as render triangles (lf_render.c, sb_surface.h). */
struct sb_surface;
int  lf_surface(void *state, int level, const double *x, struct sb_surface *out);

/* ---- elements (lf_element.c) ----------------------------------------------- */
/* Triangle element: membrane (+ midedge bending unless hinge model), the
 * follower pressure and the end moments of the triangle.  Energy returned;
 * ge / Ke (lf_ned x lf_ned) accumulated when non-NULL. */
double lf_tri_energy(lf_state *S, lf_level *L, int t, const double *qe, double *ge, double *Ke);
/* Hinge element (12 dofs: Pa, Pb, Pc, Pd). */
double lf_hinge_energy(lf_state *S, const lf_hinge *h, const double *q12, double *g12, double *K12);
/* dihedral / ghost angle theta of a hinge at its 12 position values */
double lf_hinge_theta(const lf_hinge *h, const double *q12);
/* strains (local frame) of triangle t at qe (B = 0 for the hinge model) */
int  lf_tri_strains(lf_state *S, const lf_level *L, int t, const double *qe, double A[3], double B[3]);
/* reference b of a triangle at the reference positions (qe with phi = 0) */
void lf_tri_bending(const lf_state *S, const lf_tri *T, const double *qe, double b[3]);

/* ---- boundary conditions (lf_bc.c) ------------------------------------------ */
int  lf_bc_build(lf_state *S, lf_level *L);
void lf_bc_update(lf_state *S, lf_level *L);

/* ---- loads and mass (lf_loads.c) -------------------------------------------- */
int  lf_loads_build(lf_state *S, lf_level *L);
void lf_loads_update(lf_state *S, lf_level *L);
int  lf_mass(lf_state *S, lf_level *L, sb_matrix *M);
double lf_moment_energy(lf_state *S, lf_level *L, int t, const double *qe, double *ge, double *Ke);
void lf_moment_rebranch(lf_state *S, lf_level *L, const double *x);

/* ---- assembly (lf_energy.c) ---------------------------------------------------- */
int  lf_energy(lf_state *S, int level, const double *x, double *f, double *g, sb_matrix *H);
int  lf_material_state(lf_state *S, int level, const double *x, sb_material_state *ms);

/* ---- hierarchy (lf_transfer.c) ------------------------------------------------ */
int  lf_transfer_build(lf_state *S, int lf_fine);
int  lf_prolong(const lf_state *S, int lc, const double *xc, double *xf);
int  lf_restrict(const lf_state *S, int lc, const double *gf, double *gc);
int  lf_project(const lf_state *S, int lc, const double *xf, double *xc);
int  lf_prolong_matrix(const lf_state *S, int lc, struct sb_csr *I);

extern const sb_param_def lf_params[];
extern const sb_method_type sb_method_linear_fem;

/* contact sample points (lf_contact.c, docs/contact.md) */
struct sb_contact_points;
int lf_contact_points(void *state, int level, int per_side, struct sb_contact_points *cp);

/* Bridson et al. 2002 collision response (lf_impulse.c, sb_method.h impulse_response) */
struct sb_impulse_stats;
int lf_impulse_response(void *state, const sb_scene *scene, double dt, double t1, const double *x0, double *x1,
                        struct sb_impulse_stats *st);

#endif
