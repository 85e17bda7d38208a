/* cc.h — private header of the Catmull–Clark subdivision discretization
 * (method "rmtr", RMTR paper 000_7a0c4f9a28355e8c, §5–§6).
 *
 * Pieces, one job per file:
 *   cc_csr.c      small row-compressed matrices (S, Q) and their products
 *   cc_mesh.c     quad control cages: topology (edges, adjacency, valence)
 *   cc_cage.c     cage builders: square / L-shape with one ghost ring (§5.2.1),
 *                 test cages with extraordinary vertices (star, cube)
 *   cc_subdiv.c   one Catmull–Clark step by the rules (5.12)–(5.15), (A.1)–(A.2)
 *   cc_hier.c     the level hierarchy (subdivide, drop the outer ghost ring)
 *   cc_osd_shim.* OpenSubdiv through extern "C" (S and limit stencils)
 *   cc_reverse.c  reverse subdivision Q (5.19)–(5.21), App. B, App. C
 *   cc_lsq.c      least-squares projection (5.18) with CHOLMOD on S^T S
 *   cc_basis.c    basis functions and derivatives (B-spline fast path,
 *                 local subdivision next to extraordinary vertices)
 *   cc_quad.c     per-level quadrature tables (§6: precomputed once)
 *   cc_level.c    one level: reference geometry, lookup, projection
 *   cc_penalty.c  boundary penalty (3.6), point penalties, line/point loads
 *   cc_energy.c   energy / gradient / Hessian and mass of a level
 *   cc_method.c   the sb_method_type table sb_method_subdiv ("rmtr")
 *   cc_method.h   private state of the method (levels, tables, points)
 *
 * Cages are quad meshes (every face has 4 vertices, counter-clockwise).  A
 * face is parametrized by (u,v) in [0,1]^2, u along fv[0]->fv[1], v along
 * fv[0]->fv[3] (the ptex convention of OpenSubdiv). */
#ifndef CC_H
#define CC_H

#include <stddef.h>
#include "sb_common.h"

/* ---- errors ------------------------------------------------------------ */
typedef struct cc_err { char msg[256]; } cc_err;
/* Stores a message (when e != NULL) and returns status. */
int cc_fail(cc_err *e, int status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* ---- row-compressed sparse matrices ------------------------------------ */
typedef struct cc_csr {
    int nr, nc;
    int *rp;        /* nr+1 */
    int *ci;        /* column indices, sorted within a row */
    double *v;
    long cap;       /* allocated entries (builder) */
} cc_csr;

/* Start an empty matrix; rows are then appended in order with cc_csr_row. */
int  cc_csr_init(cc_csr *A, int nr, int nc, long cap);
/* Append the next row (duplicates are summed, columns sorted, zeros kept). */
int  cc_csr_row(cc_csr *A, int row, int n, const int *cols, const double *vals);
void cc_csr_free(cc_csr *A);
/* y = A x on interleaved vectors with `dim` components per row/column. */
void cc_csr_apply(const cc_csr *A, int dim, const double *x, double *y);
/* y = A^T x (interleaved). */
void cc_csr_apply_t(const cc_csr *A, int dim, const double *x, double *y);
/* B = rows `rows[0..n)` of A. */
int  cc_csr_select_rows(const cc_csr *A, int n, const int *rows, cc_csr *B);
/* Entry (i,j) or 0. */
double cc_csr_get(const cc_csr *A, int i, int j);

/* Small sparse row accumulator (setup only, never in energy loops). */
typedef struct cc_row { int n, cap; int *c; double *v; } cc_row;
int  cc_row_add(cc_row *r, int col, double val);
int  cc_row_axpy(cc_row *r, double a, const cc_row *x);
void cc_row_free(cc_row *r);

/* ---- quad cages --------------------------------------------------------- */
typedef struct cc_mesh {
    int nv, nf, ne;
    int *fv;            /* 4 nf: face vertices, counter-clockwise */
    unsigned char *dom; /* nf: 1 = face of the simulated domain, 0 = ghost face */
    double *st;         /* 2 nv: grid parameter (s,t) of the control point */
    int *grid;          /* 2 nv or NULL: integer grid coordinates (structured cages) */
    int *cell;          /* 2 nf or NULL: grid cell (i,j) of the face (structured cages) */
    /* topology, built by cc_mesh_topology() */
    int *fe;            /* 4 nf: fe[4f+k] = edge (fv[4f+k], fv[4f+(k+1)%4]) */
    int *ev;            /* 2 ne */
    int *ef;            /* 2 ne: incident faces, ef[2e+1] = -1 on a boundary edge */
    int *efk;           /* 2 ne: local index of e in ef[2e], ef[2e+1] */
    int *val;           /* nv: valence (number of incident edges) */
    unsigned char *bnd; /* nv: 1 = vertex on the cage boundary */
    int *vfo, *vf;      /* vertex -> incident faces (CSR, nv+1 / 4 nf) */
    int *veo, *ve;      /* vertex -> incident edges (CSR, nv+1 / 2 ne) */
} cc_mesh;

/* Allocate fv, dom, st (and grid/cell when structured != 0), zeroed. */
int  cc_mesh_alloc(cc_mesh *m, int nv, int nf, int structured);
/* Build edges and adjacency from fv; rejects non-manifold or inconsistently
 * oriented cages, unused vertices, and boundary vertices with more than two
 * boundary edges. */
int  cc_mesh_topology(cc_mesh *m, cc_err *e);
void cc_mesh_free(cc_mesh *m);
/* Sub-cage made of faces[0..n) (vertices renumbered by first appearance);
 * vmap (m->nv, may be NULL) gets new index or -1; inv (n_out verts, may be
 * NULL, size >= 4n) gets the old index of every new vertex. */
int  cc_mesh_extract(const cc_mesh *m, int n, const int *faces, cc_mesh *out,
                     int *vmap, int *inv, cc_err *e);
/* Local index (0..3) of vertex v in face f, or -1. */
int  cc_face_corner(const cc_mesh *m, int f, int v);

/* ---- cage builders (cc_cage.c) ----------------------------------------- */
/* Structured cage over lines sl[0..ns] (in s) and tl[0..nt] (in t), strictly
 * increasing.  notch_corner = SB_CORNER_* or -1; the notch removes the cells
 * i in [ns-nns, ns) (corner 10/11) or [0, nns) (00/01), likewise in t.  Adds
 * every cell sharing a vertex with a domain cell as ghost face (§5.2.1).  The
 * control parameters (s,t) are the 1D natural-spline control values whose
 * cubic B-spline limit interpolates the lines, so the limit boundary passes
 * through the boundary control points (ghost = mirror image, App. B of the
 * paper assumes the same) and every line of the cage is exact. */
int  cc_cage_grid(const double *sl, int ns, const double *tl, int nt,
                  int notch_corner, int nns, int nnt, cc_mesh *m, cc_err *e);
/* Coarse lines for n elements on [0,1] with a line at `cut` (0 < cut < 1):
 * m = round(n*w) >= 1 elements on the side of width w, uniform on each side.
 * cut <= 0 gives uniform lines.  lines holds n+1 values. */
int  cc_cage_lines(int n, double cut, int notch_high, double *lines, int *n_notch);
/* Test cage: a disc of `valence` sectors of k x k quads around one
 * extraordinary vertex (valence 3..SB_SHELL_MAX valence); the outer ring of
 * faces is ghost, the rest domain.  Planar, radius ~1. */
int  cc_cage_star(int valence, int k, cc_mesh *m, cc_err *e);
/* Test cage: the closed cube (8 vertices of valence 3, all faces domain). */
int  cc_cage_cube(cc_mesh *m, cc_err *e);
/* Test cage: several stars glued in a strip, containing extraordinary
 * vertices of valences 3, 5 and 6 at once (structure documented in cc_cage.c). */
int  cc_cage_multi(cc_mesh *m, cc_err *e);

/* ---- subdivision (cc_subdiv.c) ----------------------------------------- */
/* One uniform Catmull–Clark step of the whole cage.  Fine vertices: vertex
 * points [0,nv), edge points [nv,nv+ne), face points [nv+ne, nv+ne+nf).  Fine
 * face 4f+k is the child of face f at corner k, with vertex order chosen so
 * that its (u,v) frame is the parent's frame scaled by 2 (cc_child_offset).
 * S (fine x coarse) by (5.12)–(5.15) inside, (A.1)–(A.2) on the cage boundary.
 * Fine st = S st; grid/cell are refined when present. */
int  cc_subdivide(const cc_mesh *c, cc_mesh *f, cc_csr *S, cc_err *e);
/* Offset (iu,iv) in {0,1}^2 of child k in the parent's (u,v) frame. */
void cc_child_offset(int k, int *iu, int *iv);
/* Keep the domain faces and every face sharing a vertex with one (the ghost
 * ring); vmap (full->nv) gets the kept index or -1. */
int  cc_keep_ring(const cc_mesh *full, cc_mesh *kept, int *vmap, cc_err *e);

/* ---- hierarchy (cc_hier.c) ---------------------------------------------- */
#define CC_MAX_LEVELS SB_MAX_LEVELS
typedef struct cc_hier {
    int nlev;
    cc_mesh mesh[CC_MAX_LEVELS];     /* level 0 = coarsest */
    cc_csr S[CC_MAX_LEVELS];         /* S[l]: level l -> l+1 (rows: level l+1) */
    int *vmap[CC_MAX_LEVELS];        /* vmap[l]: full subdivision of level l -> level l+1 index or -1 */
} cc_hier;
/* Takes ownership of *coarse.  use_osd: S from OpenSubdiv (else the C rules). */
int  cc_hier_build(cc_hier *h, cc_mesh *coarse, int nlev, int use_osd, cc_err *e);
void cc_hier_free(cc_hier *h);
/* S of one full subdivision step from OpenSubdiv, in cc_subdivide's ordering. */
int  cc_osd_subdiv_matrix(const cc_mesh *c, cc_csr *S, cc_err *e);

/* ---- transfers (cc_reverse.c, cc_lsq.c) --------------------------------- */
/* Q (coarse x fine) with Q S = I: (5.19)–(5.21) at interior vertices of
 * valence != 3, (B.2) for ghost points and valence 3 (App. B, C), (B.4) for
 * corner ghost points.  vmap as in cc_hier. */
int  cc_reverse_build(const cc_mesh *c, const cc_mesh *f, const int *vmap, cc_csr *Q, cc_err *e);
/* Restriction-based projection D^{-1} S^T, D = diag(S^T 1) (row-normalized). */
int  cc_restrict_scaled_build(const cc_csr *S, cc_csr *P, cc_err *e);

typedef struct cc_lsq cc_lsq;
/* Factor S^T S once (CHOLMOD, own common). */
int  cc_lsq_create(const cc_csr *S, cc_lsq **out, cc_err *e);
/* qc = (S^T S)^{-1} S^T qf, interleaved with dim <= 3 components. */
int  cc_lsq_apply(cc_lsq *P, int dim, const double *qf, double *qc);
void cc_lsq_free(cc_lsq *P);

/* ---- basis (cc_basis.c) -------------------------------------------------- */
#define CC_MAX_BASIS 64     /* = SB_SHELL_MAX_BASIS */
/* Uniform cubic B-spline basis b[4] and derivatives at u in [0,1]. */
void cc_bspline1(double u, double b[4], double d1[4], double d2[4]);
/* Regular patch basis, index a + 4 b (a along u): W[6][16] = N, Nu, Nv, Nuu, Nuv, Nvv. */
void cc_bspline_patch(double u, double v, double W[6][16]);
/* Face whose four vertices are interior with valence 4. */
int  cc_face_regular(const cc_mesh *m, int f);
/* The 4x4 control points of a regular face, idx[a + 4b]. */
int  cc_face_gather16(const cc_mesh *m, int f, int idx[16]);
/* Basis functions of any face at (u,v) (not at an extraordinary corner):
 * writes k control indices and W (6 x k, row r = derivative r). Regular faces
 * use the B-spline; others are subdivided locally until (u,v) lies in a
 * regular sub-patch (exact, §5.2).  Setup-time routine (allocates). */
int  cc_face_basis(const cc_mesh *m, int f, double u, double v, int *k, int *idx,
                   double *W, int max, cc_err *e);
/* Canonical local cage of face f (its one-ring; face 0 = f in f's frame),
 * inv[i] = cage index of local vertex i (at most max). */
int  cc_face_local(const cc_mesh *m, int f, cc_mesh *L, int *inv, int max, cc_err *e);
/* Basis of face 0 of a local cage at (u,v): W (6 x L->nv), overwritten. */
int  cc_local_basis(const cc_mesh *L, double u, double v, double *W, cc_err *e);

/* ---- limit stencils from OpenSubdiv (tests, cross-checks) --------------- */
/* Dense limit stencils W[(6*p + r)*nv + I] at np points (face[p], uv[2p]). */
int  cc_osd_limit_dense(const cc_mesh *m, int np, const int *face, const double *uv,
                        double *W, cc_err *e);

#endif
