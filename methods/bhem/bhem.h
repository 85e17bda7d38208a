/* bhem.h — private declarations of the bicubic Hermite element method
 * (BHEM paper 001_…, Ni, Chen et al.).
 *
 * Discretization (BHEM paper §4.1, Fig. 6): a structured grid of n1 x n2
 * patches over the grid parameter (s,t) in [0,1]^2 (sb_scene.h), mapped onto
 * the scene's reference surface by the chart.  Every node carries four
 * generalized coordinates, each a 3-vector ("kinds"):
 *
 *   kind 0: x          kind 1: hs x_,s      kind 2: ht x_,t      kind 3: hs ht x_,st
 *
 * with hs = 1/n1, ht = 1/n2 the patch size in (s,t).  The derivatives are
 * stored scaled by the patch size, i.e. as derivatives w.r.t. the local patch
 * coordinate theta = (s - s_min)/hs.  Then Eq. (14)-(15) hold exactly as printed,
 * x = sum w_{pq,rs}(theta1,theta2) x_{pq,rs} with the weights of Eq. (31)
 * (the paper's x_{pq,rs} are derivatives w.r.t. xi while its weights are
 * functions of theta: the Delta xi factor is implied; we make it explicit by
 * the scaling).  All generalized coordinates then have units of length and
 * comparable magnitude, which keeps Euclidean trust regions and gradient
 * norms meaningful (BHEM paper §8, "Loss functions").
 *
 * DOF layout: dof = 12*node + 3*kind + c, nodes numbered compactly over the
 * active nodes (s fastest), periodic seams identified (§4.2).  Element
 * (patch) local basis index I = 4*corner + kind, corner = p + 2q for the
 * patch corner (s_min + p hs, t_min + q ht); element dof 3*I + c. */
#ifndef BHEM_H
#define BHEM_H

#include "sb_method.h"
#include "sb_geometry.h"
#include "sb_shell.h"

#define BHEM_NQ1 4                  /* Gauss–Legendre points per direction (App. A) */
#define BHEM_NQP (BHEM_NQ1 * BHEM_NQ1)
#define BHEM_NB 16                  /* basis functions per patch */
#define BHEM_NED 48                 /* dofs per patch */

/* ---- basis (bhem_basis.c) ---------------------------------------------- */

/* 1D Hermite weight w_{p,r}(theta) of BHEM Eq. (31) and its first and second
 * derivatives w.r.t. theta (Eq. 34 and its derivative). */
void bhem_hermite_1d(int p, int r, double th, double *w, double *dw, double *ddw);

/* Basis of one patch at local coordinates (th1, th2) in [0,1]^2: values and
 * derivatives w.r.t. the grid parameter (s,t) (patch size hs x ht).  Any of
 * the output arrays (16 long) may be NULL. */
void bhem_basis_eval(double th1, double th2, double hs, double ht,
                     double *N, double *N1, double *N2, double *N11, double *N12, double *N22);

/* Gauss–Legendre rule with BHEM_NQ1 points on [0,1] (BHEM App. A, Eq. 37-38). */
void bhem_gauss_rule(double x[BHEM_NQ1], double w[BHEM_NQ1]);

/* Basis tabulated at the BHEM_NQP quadrature points of a patch. */
typedef struct bhem_qp_basis {
    double N[BHEM_NB], N1[BHEM_NB], N2[BHEM_NB], N11[BHEM_NB], N12[BHEM_NB], N22[BHEM_NB];
} bhem_qp_basis;

/* ---- constrained dofs (bhem_bc.c) -------------------------------------- */

typedef struct bhem_con {
    int dof;          /* global dof */
    int bc;           /* scene bc index of a moving bc, -1 = held at the reference */
} bhem_con;

/* ---- end-moment quadrature point (bhem_loads.c) ----------------------- */

typedef struct bhem_mq {
    int elem;                 /* patch the point belongs to */
    int load;                 /* scene load index */
    double dN[BHEM_NB];       /* d N_I / d(cross parameter): cross tangent d = sum dN_I q_I */
    double weight;            /* Gauss weight * reference arc length factor */
    double axis[3];           /* unit rotation axis a */
    double ub[3], e2[3];      /* branch frame: ub unit, perpendicular to a; e2 = a x ub */
    double theta_b;           /* angle of ub relative to the reference tangent (unwrapped) */
} bhem_mq;

/* ---- one level of the nested hierarchy ---------------------------------- */

typedef struct bhem_level {
    int n1, n2;               /* patches along s and t */
    double hs, ht;            /* patch size in (s,t) */
    int nn1, nn2;             /* grid nodes along s and t (n+1) */
    int *node_id;             /* nn1*nn2: compact node index, -1 = inactive (notch) */
    int *node_i, *node_j;     /* n_nodes: grid position of each compact node (representative) */
    int n_nodes, n_dofs;
    int n_elems;
    int *elem_cell;           /* n_elems: cell index i + n1*j */
    int *elem_dofs;           /* n_elems*48 */
    int *cell_elem;           /* n1*n2: element of each cell, -1 = inactive (notch) */
    double *x_ref;            /* n_dofs: reference generalized coordinates (incl. imperfection) */
    sb_shell_ref *ref;        /* n_elems*BHEM_NQP */
    bhem_qp_basis qb[BHEM_NQP];
    double qw[BHEM_NQP];      /* quadrature weights in (s,t) (hs*ht*w_a*w_b) */
    /* boundary conditions */
    int n_con;
    bhem_con *con;
    int *con_dofs;
    double *con_vals;
    sb_dirichlet dir;
    /* loads */
    double *load_vec;         /* n_loads x n_dofs: generalized forces of dead loads (or NULL rows) */
    double *f_ext;            /* n_dofs: sum of factor_k * load_vec_k at the current step */
    int n_mq;
    bhem_mq *mq;              /* end-moment points, sorted by element */
    int *elem_mq;             /* n_elems+1 offsets into mq */
    int rebranch;             /* 1: next energy() re-centres the angle branches */
    /* prolongation to level+1: rows = 4*n_nodes(fine) "node kinds" */
    int *p_ptr, *p_col;       /* CSR over fine node-kinds -> coarse node-kinds */
    double *p_w;
} bhem_level;

typedef struct bhem_state {
    const sb_scene *scene;
    struct sb_context *ctx;
    sb_material mat;
    sb_hess_kind hess;
    double imperfection;      /* m, amplitude of the out-of-plane reference noise */
    int n_levels;
    int periodic_s, periodic_t;
    int slit_s, slit_t;         /* a closed surface whose seam edges carry conditions: kept open */
    bhem_level lv[SB_MAX_LEVELS];
    /* step data */
    double load_factor[SB_SCENE_MAX_LOADS];
    double motion_factor[SB_SCENE_MAX_BCS];
    int has_follower, has_moment;
    /* scratch (allocated once) */
    sb_shell_work *work;
    double qe[BHEM_NED], ge[BHEM_NED];
    double *Ke;               /* 48*48 */
    double *psd_work;
    /* assembly (issue 30): method.kernel, run.threads, per-thread scratch */
    sb_kernel_kind kernel;
    sb_shell_isa isa;   /* run.vectors: the fast kernel's vector width */
    int threads;
    sb_elem_scratch *tw;
    struct sb_assembler *assembler;
    /* contact.model = "impulse" (bhem_impulse.c): built at the first call */
    struct bhem_impulse *imp;
} bhem_state;

/* error helper: stores the message in the context (if any) and returns status */
int bhem_fail(const bhem_state *S, int status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* ---- grid (bhem_grid.c) -------------------------------------------------- */
/* Build level geometry: mask, periodic identification, dofs, elements and the
 * exact reference generalized coordinates from the chart. */
int  bhem_level_build(bhem_state *S, bhem_level *L, int n1, int n2);
/* Quadrature tables and reference quantities per patch quadrature point. */
int  bhem_level_quadrature(bhem_state *S, bhem_level *L);
/* the level's quadrature data (L->ref) when it was released (coarser levels
 * after set-up, bhem_method.c): built again at first use */
int  bhem_level_ensure_quadrature(bhem_state *S, bhem_level *L);
void bhem_level_free(bhem_level *L);
/* Node index (compact) of grid node (i,j), -1 if inactive; wraps periodic seams. */
int  bhem_node_at(const bhem_state *S, const bhem_level *L, int i, int j);
/* Locate (s,t): patch (element) and local coordinates; returns -1 outside. */
int  bhem_locate(const bhem_level *L, double s, double t, double *th1, double *th2);
/* Seam detection on the scene geometry: sets S->periodic_s / periodic_t. */
int  bhem_detect_periodic(bhem_state *S);
/* Gather the 48 element values of x. */
void bhem_gather(const bhem_level *L, int e, const double *x, double *qe);
/* Evaluate positions at grid parameters st[2*np] into pos[3*np]. */
int  bhem_eval(const bhem_state *S, const bhem_level *L, const double *x, int np,
               const double *st, double *pos);

/* ---- boundary conditions (bhem_bc.c) --------------------------------------- */
int  bhem_bc_build(bhem_state *S, bhem_level *L);
void bhem_bc_update(bhem_state *S, bhem_level *L);

/* ---- loads and mass (bhem_loads.c) ------------------------------------ */
int  bhem_loads_build(bhem_state *S, bhem_level *L);
void bhem_loads_update(bhem_state *S, bhem_level *L);
int  bhem_mass(bhem_state *S, bhem_level *L, sb_matrix *M);
/* End-moment potential of the points of element e: energy, and accumulation
 * into element gradient ge / Hessian Ke (48x48) when non-NULL.  Returns NaN
 * if the cross tangent is parallel to the axis. */
double bhem_moment_element(bhem_state *S, bhem_level *L, int e, const double *qe,
                           double *ge, double *Ke);
/* Re-centre the angle branches at state x (see bhem_loads.c). */
void bhem_moment_rebranch(bhem_state *S, bhem_level *L, const double *x);

/* ---- energy (bhem_energy.c) --------------------------------------------- */
int  bhem_energy(bhem_state *S, int level, const double *x, double *f, double *g, sb_matrix *H);
int  bhem_material_state(bhem_state *S, int level, const double *x, sb_material_state *ms);

/* ---- hierarchy (bhem_transfer.c) ---------------------------------------- */
int  bhem_transfer_build(bhem_state *S, int lc);
int  bhem_prolong(const bhem_state *S, int lc, const double *xc, double *xf);
int  bhem_restrict(const bhem_state *S, int lc, const double *gf, double *gc);
struct sb_csr;
int  bhem_prolong_matrix(const bhem_state *S, int lc, struct sb_csr *I);
int  bhem_project(const bhem_state *S, int lc, const double *xf, double *xc);

/* ---- rendering (bhem_ray.c) ------------------------------------------------ */
struct sb_surface;
/* The patches of x on `level` as Bézier patches, with the reference (sb_surface.h). */
int  bhem_surface(void *state, int level, const double *x, struct sb_surface *out);
/* Patch e of x as a Bézier patch (SB_BEZ_N doubles; u = theta1, v = theta2). */
void bhem_patch_bezier(const bhem_level *L, int e, const double *x, double *P);

/* ---- impulse-based collision response (bhem_impulse.c, BHEM §5.2, §6.2) -- */
struct bhem_impulse;
struct sb_impulse_stats;
int  bhem_impulse_response(void *state, const sb_scene *scene, double dt, double t1, const double *x0, double *x1,
                           struct sb_impulse_stats *st);
void bhem_impulse_free(struct bhem_impulse *I);

/* ---- creation (bhem_method.c) ------------------------------------------- */
extern const sb_param_def bhem_params[];
extern const sb_method_type sb_method_bhem;

/* contact sample points (bhem_contact.c, docs/contact.md) */
struct sb_contact_points;
int bhem_contact_points(void *state, int level, int per_side, struct sb_contact_points *cp);

#endif
