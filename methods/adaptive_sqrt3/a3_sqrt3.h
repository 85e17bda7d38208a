/* a3_sqrt3.h — sqrt3 refinement and coarsening of a triangle mesh (sqrt3
 * paper §5, after Kobbelt's sqrt3 subdivision), for adaptive_sqrt3.
 *
 * Operations (§5.1):
 *   SPLIT   an even-generation triangle (g) gets a vertex at its centroid
 *           (1-to-3); the three children have generation g + 1 and each
 *           keeps the parent's edge it contains as its mate edge.
 *   FLIP    two odd triangles of the same generation whose mate edge is
 *           their common edge flip it (it then joins the two centroids);
 *           both become g + 1 (even, no mate).
 *   BSPLIT  an odd triangle (g) whose mate edge lies on the boundary cannot
 *           flip: the boundary edge is split into three equal parts
 *           (the boundary two-step rule, Fig. 5); the middle child gets
 *           g + 3, the two others g + 2 with the parent's other two edges
 *           as their mate edges.
 * The generation difference across an interior edge stays <= 1: an
 * operation whose result would break it first refines the neighbours that
 * hold it back (recursively, as §5.1 describes for mates), or is not done.
 *
 * Representation (our choice; the paper stores generations and mate bits
 * per face and undoes operations locally): every triangle ever created is
 * an immutable record (corners, generation, mate corner) with an alive bit;
 * an operation kills its inputs and makes its outputs alive; undoing it
 * (coarsening, §5.2: flip back, 3-to-1 join, boundary join) does the
 * reverse.  A triangle remembers the operation that consumed it, so
 * refining it again re-applies that same operation: the records are
 * bounded by the full refinement tree, and coarsening everything restores
 * the base mesh exactly (same triangles, same order).  Coarsening undoes
 * an operation only when its outputs are alive, after flipping back the
 * flips that consumed its children (the paper's "flip back, then 3-to-1
 * join"); it is not done when that would break the generation rule.
 * Domains with identified seams are not supported (refused).
 *
 * Vertices carry the grid parameter (s,t); a vertex is alive while an alive
 * triangle uses it.  The mesh of the alive triangles, in record order, is
 * exported to sb_mesh with a map to the forest's vertex ids. */
#ifndef A3_SQRT3_H
#define A3_SQRT3_H

#include "sb_mesh.h"
#include "sb_blob.h"

enum { A3_OP_SPLIT = 0, A3_OP_FLIP = 1, A3_OP_BSPLIT = 2 };

typedef struct a3_ftri {
    int v[3];
    int gen;
    signed char mate;         /* corner opposite the mate edge (odd generations), -1 none */
    unsigned char alive;
    int child_op;             /* the operation that consumes it (-1 none yet) */
} a3_ftri;

typedef struct a3_op {
    int kind, applied;
    int n_in, n_out, n_vnew;
    int in[2], out[3], vnew[2];
} a3_op;

typedef struct a3_forest {
    int nt, cap_t, nv, cap_v, nop, cap_op;
    a3_ftri *t;
    a3_op *op;
    double *st;               /* 2 nv */
    int *vref;                /* nv: alive triangles using the vertex */
    int *vgen;
    unsigned char *vbnd;      /* nv: on the domain boundary */
    int *vpar;                /* 3 nv: the vertices it was interpolated from (-1: base vertex) */
    double *vw;               /* 3 nv: their weights (centroid 1/3 each; boundary split 2/3, 1/3) */
    /* edge hash of the alive triangles: key (min v, max v) -> two triangles */
    long long *hkey;
    int *hval;                /* 2 per slot */
    int hcap, hused;
    int nt0;                  /* base triangles (records 0 .. nt0-1) */
    int max_gen;
} a3_forest;

/* From a base mesh without seams; SB_ERR_UNSUPPORTED for seams. */
int  a3_forest_init(a3_forest *F, const sb_mesh *m, int max_gen);
void a3_forest_free(a3_forest *F);
/* Refine alive triangle t one operation further (split, flip with its mate,
 * or boundary split; neighbours first when the generation rule asks).
 * 1 done, 0 not possible (max generation, rule), negative error. */
int  a3_forest_refine(a3_forest *F, int t);
/* Undo operation k (SPLIT or BSPLIT) after flipping back the flips that
 * consumed its children.  1 done, 0 not possible, negative error. */
int  a3_forest_coarsen(a3_forest *F, int k);
/* Refine every alive triangle below max_gen until none can be (uniform). */
int  a3_forest_refine_all(a3_forest *F);
/* Undo every operation (the base mesh again). */
int  a3_forest_coarsen_all(a3_forest *F);
/* Generation rule and alive-edge manifoldness; 0 or -1 with a sentence. */
int  a3_forest_check(const a3_forest *F, char *msg, size_t len);
/* The alive mesh: sb_mesh (geometry from the scene, boundary parts tagged)
 * and vmap[new vertex] = forest vertex (caller frees). */
int  a3_forest_mesh(const a3_forest *F, const sb_scene *sc, sb_mesh *m, int **vmap);
/* The whole forest (vertices with their parents and weights, every
 * triangle record, every operation) as a blob for checkpoints; the vertex
 * use counts and the edge map are not stored (load rebuilds them from the
 * alive triangles).  SB_OK or SB_ERR_NOMEM. */
int  a3_forest_save(const a3_forest *F, sb_blob *b);
/* Replace F (made from the same base mesh and max generation) by a saved
 * forest; validated first (SB_ERR_INPUT with a sentence in msg, F
 * untouched), then checked (a3_forest_check).  A loaded forest refines and
 * coarsens exactly as the saved one would have. */
int  a3_forest_load(a3_forest *F, const sb_blob *b, char *msg, size_t len);
/* the alive triangle across edge (a, b), other than t; -1 on the boundary */
int  a3_forest_across(const a3_forest *F, int a, int b, int t);

#endif
