/* cc_method.h — private state of the subdivision method "rmtr": per-level
 * quadrature tables, reference configuration, penalty and load points,
 * transfers.  See cc.h for the geometric pieces. */
#ifndef CC_METHOD_H
#define CC_METHOD_H

#include "cc.h"
#include "sb_method.h"
#include "sb_geometry.h"
#include "sb_shell.h"

/* ---- quadrature (cc_quad.c) --------------------------------------------- */
typedef struct cc_cfg {         /* basis tables of one face configuration (§6) */
    int k;                      /* control points */
    int nfv, *fv;               /* canonical local cage (the key); none for the regular patch */
    double *tab;                /* nq x 6 x k: tab[(6 q + r) k + i] */
} cc_cfg;

typedef struct cc_quad {
    int ng, nq;                 /* Gauss points per direction, per face */
    double gp[8], gw[8];        /* points and weights on [0,1] */
    int ncfg, capcfg;
    cc_cfg *cfg;                /* cfg[0] = regular bicubic patch */
    int ne;                     /* elements = domain faces */
    int *face, *ecfg;           /* ne */
    int *eoff, *enode;          /* control points of element e: enode[eoff[e] .. eoff[e+1]) */
} cc_quad;

int  cc_quad_build(cc_quad *Q, const cc_mesh *m, int ng, cc_err *e);
void cc_quad_free(cc_quad *Q);
sb_shell_basis cc_quad_basis(const cc_quad *Q, int e, int q);

/* ---- boundary / load points (cc_penalty.c) ------------------------------ */
enum { CC_PT_PENALTY = 0, CC_PT_LINE_LOAD = 1, CC_PT_POINT_LOAD = 2, CC_PT_SLOPE = 3 };

typedef struct cc_pt {
    int elem, kind, src;        /* element, CC_PT_*, scene bc / load index */
    unsigned mask;              /* penalized components (bit c) */
    double w;                   /* Gauss weight x reference arc length; 1 for a point */
    double X[3];                /* reference position x(xi) */
    double b[3];                /* penalty target b, or force density / force, at this step */
    double n[3];                /* slope penalty: reference unit normal N */
    double inv_len;             /* slope penalty: 1 / |dX/dc| (theta = dx/dc . N / |dX/dc|) */
    long off;                   /* basis values N_I (k of the element) at ptN[off] */
} cc_pt;

/* ---- one level ---------------------------------------------------------- */
typedef struct cc_level {
    const cc_mesh *mesh;        /* owned by the hierarchy */
    int nv;
    double *X;                  /* 3 nv: reference control points */
    cc_quad quad;
    int *felem;                 /* nf: element of a domain face, -1 for ghost faces */
    sb_shell_ref *ref;          /* ne x nq */
    double h, beta;             /* mesh size (m) and penalty beta = scale h^-sigma (3.6) */
    int npt;
    cc_pt *pt;                  /* sorted by element */
    double *ptN;
    int *ept;                   /* ne+1: points of element e: pt[ept[e] .. ept[e+1]) */
    /* structured lookup (grid parameter -> face) */
    int i0, j0, ni, nj;         /* grid vertex ranges: i in [i0, i0+ni) */
    double *sx, *ty;            /* control parameter per grid column / row */
    int *cellface;              /* (ni-1) x (nj-1) grid cells -> domain face or -1 */
    /* projection onto this level from level+1 */
    cc_csr P;                   /* reverse subdivision Q or scaled restriction */
    cc_lsq *lsq;
} cc_level;

typedef enum { CC_PROJ_REVERSE = 0, CC_PROJ_LSQ = 1, CC_PROJ_RESTRICT = 2 } cc_proj_kind;

typedef struct cc_state {
    const sb_scene *scene;
    struct sb_context *ctx;
    sb_material mat;
    cc_hier hier;
    cc_level lv[CC_MAX_LEVELS];
    int nlev;
    int n_coarse, n_fine;       /* elements along s on the coarsest / finest level */
    int nt_coarse, nt_fine;     /* elements along t (--res NxM; equal to the above by default) */
    /* parameters */
    cc_proj_kind proj;
    sb_hess_kind hess;
    int lumped, ng, use_osd, beta_finest;
    int beta_paper;             /* method.beta_rule = paper: beta = beta_scale h^-sigma */
    double sigma, beta_scale;
    double beta_factor;         /* cc_beta_factor(): 1 for the paper's cloth (and the paper rule) */
    /* step data */
    double load_factor[SB_SCENE_MAX_LOADS];
    double motion_factor[SB_SCENE_MAX_BCS];
    /* element workspace (allocated once) */
    sb_shell_work *work;
    double *Ke, *ge, *qe, *psd;
    /* assembly (issue 30): method.kernel, run.threads, per-thread scratch */
    sb_kernel_kind kernel;
    sb_shell_isa isa;   /* run.vectors: the fast kernel's vector width */
    int threads;
    sb_elem_scratch *tw;
    struct sb_assembler *assembler;
} cc_state;

extern const sb_param_def cc_params[];

/* cc_method.c */
int  cc_state_fail(const cc_state *S, int status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* cc_level.c: reference geometry, quadrature, structured lookup, projection */
int  cc_level_build(cc_state *S, int l, cc_err *e);
/* Level l's reference geometry L->ref, built at its first use (coarse levels); SB_OK or SB_ERR_NOMEM. */
int  cc_level_ref(cc_state *S, int l);
void cc_level_free(cc_level *L);
/* Face and (u,v) of grid parameter (s,t) on a structured level. */
int  cc_level_locate(const cc_level *L, double s, double t, int *face, double *u, double *v);
int  cc_level_element_of_face(const cc_level *L, int face);
/* cc_penalty.c */
int  cc_points_build(cc_state *S, int l, cc_err *e);
void cc_points_update(cc_state *S, int l);
/* Energy of the points of element e (penalty (3.6), line/point loads). */
double cc_points_energy(const cc_state *S, const cc_level *L, int e, const double *qe, double *ge, double *Ke);
/* cc_beta.c: the scale-aware penalty factor (docs/trust.md) */
int  cc_beta_factor(const cc_state *S, double *factor, cc_err *e);
int  cc_penalty_violation(const cc_state *S, int l, const double *x, sb_penalty_report *r);
/* cc_energy.c */
int  cc_energy(cc_state *S, int l, const double *x, double *f, double *g, sb_matrix *H);
int  cc_mass(cc_state *S, int l, sb_matrix *M);
int  cc_material_state(cc_state *S, int l, const double *x, sb_material_state *ms);
/* cc_render.c: the limit surface as Bézier patches (sb_surface.h) */
struct sb_surface;
int  cc_surface(void *state, int level, const double *x, struct sb_surface *out);

/* contact sample points (cc_contact.c, docs/contact.md) */
struct sb_contact_points;
int cc_contact_points(void *state, int level, int per_side, struct sb_contact_points *cp);

#endif
