/* sb_mesh.h — the shared triangle-mesh layer: indexed triangles with edge
 * adjacency over a scene's domain, for every triangle discretization
 * (linear_fem, adaptive_sqrt3) and for contact geometry.
 *
 * Coordinates.  A vertex carries the grid parameter (s,t) of the scene
 * (sb_scene.h), its material coordinates xi = sb_domain_map(s,t) and its
 * reference position X = chart(xi).  Triangles are straight in (s,t) and
 * counter-clockwise there; every triangle also keeps the (s,t) of its three
 * corners ("unwrapped" coordinates), which differ from the vertex's own
 * (s,t) only across a seam where vertices were identified (a full annulus, a
 * closed cylinder, the centre of an annulus with r_in = 0): interpolation,
 * point location and refinement use the corner coordinates, so they are right
 * on both sides of a seam.
 *
 * Adjacency.  Edge e joins edge_v[2e] -> edge_v[2e+1] in the counter-clockwise
 * order of its first triangle edge_t[2e]; its second triangle edge_t[2e+1]
 * (-1 on the boundary) runs it the other way.  edge_k[2e+j] is the corner of
 * triangle edge_t[2e+j] opposite the edge, so the "opposite vertices" of an
 * interior edge are tri[3 edge_t[2e+j] + edge_k[2e+j]], j = 0, 1.  Corner k
 * of a triangle faces edge tri_edge[3t+k], which runs corner k+1 -> k+2
 * (mod 3) counter-clockwise.
 *
 * Generations (for adaptive refinement, issue 22): vgen / tgen count the
 * refinement steps that created a vertex / triangle (0 = the generated mesh).
 *
 * Every array is owned by the mesh; sizes nv, nt, ne with capacities for
 * meshes that grow (sb_mesh_reserve).  No global state. */
#ifndef SB_MESH_H
#define SB_MESH_H

#include "sb_scene.h"

enum {
    SB_MESH_V_BOUNDARY = 1u << 0,   /* on a boundary edge */
    SB_MESH_V_PINNED = 1u << 1,     /* kept in place by jitter / flips (scene point parts, seams) */
    SB_MESH_V_SEAM = 1u << 2        /* identified with another grid vertex (seam, collapsed edge) */
};

typedef struct sb_mesh {
    int nv, nt, ne;
    int cap_v, cap_t, cap_e;
    /* vertices */
    double *st;              /* 2 nv: grid parameter (s,t) */
    double *xi;              /* 2 nv: material coordinates */
    double *X;               /* 3 nv: reference position chart(xi) */
    int *vgen;               /* nv */
    unsigned char *vflag;    /* nv: SB_MESH_V_* */
    /* triangles */
    int *tri;                /* 3 nt: vertices, counter-clockwise in (s,t) */
    double *tri_st;          /* 6 nt: (s,t) of each corner */
    int *tri_edge;           /* 3 nt: edge opposite corner k */
    int *tgen;               /* nt */
    /* edges */
    int *edge_v;             /* 2 ne */
    int *edge_t;             /* 2 ne: second = -1 on the boundary */
    int *edge_k;             /* 2 ne: corner opposite the edge in each triangle */
    unsigned *edge_part;     /* ne: bit p = boundary edge on named part p (sb_domain_part_names) */
    /* seams kept open (sb_mesh_from_domain): bit 0 the s = 0 / 1 seam, bit 1 the
     * t = 0 / 1 seam, set when the chart closes the surface there but a
     * condition or load names one of the two edges (a slit; docs/scene_format.md) */
    unsigned slit;
} sb_mesh;

void sb_mesh_init(sb_mesh *m);
void sb_mesh_free(sb_mesh *m);
/* Grow the arrays to hold at least nv vertices, nt triangles, ne edges
 * (contents kept).  SB_OK or SB_ERR_NOMEM. */
int  sb_mesh_reserve(sb_mesh *m, int nv, int nt, int ne);
/* Deep copy (dst initialised or freed first by the caller). */
int  sb_mesh_copy(const sb_mesh *src, sb_mesh *dst);

/* Edges and adjacency from tri[] (replaces any edges).  SB_ERR_INPUT when
 * the triangles are not an orientable manifold with consistent orientation
 * (an edge shared by three triangles, or twice in the same direction). */
int  sb_mesh_build_edges(sb_mesh *m);
/* Every structural invariant: indices in range, no repeated corner,
 * positive (s,t) area, tri_edge / edge_v / edge_t / edge_k consistent,
 * orientation, boundary flags.  SB_OK, or SB_ERR_INTERNAL with a sentence. */
int  sb_mesh_check(const sb_mesh *m, char *msg, size_t len);

/* Flip interior edge e (the diagonal of the quadrilateral of its two
 * triangles), updating adjacency locally: the two triangles keep their
 * indices and generations, the edge keeps its index.  SB_ERR_INPUT for a
 * boundary edge or a seam edge (corner coordinates disagree).  Does not test
 * convexity: see sb_mesh_flip_valid. */
int  sb_mesh_flip(sb_mesh *m, int e);
/* 1 when flipping e leaves both triangles with positive (s,t) area. */
int  sb_mesh_flip_valid(const sb_mesh *m, int e);

/* vertex -> triangles (CSR, ptr nv+1, idx 3 nt); caller frees both. */
int  sb_mesh_vertex_triangles(const sb_mesh *m, int **ptr, int **idx);

static inline int sb_mesh_edge_opp(const sb_mesh *m, int e, int j)
{
    const int t = m->edge_t[2 * e + j];
    return t < 0 ? -1 : m->tri[3 * t + m->edge_k[2 * e + j]];
}
/* signed (s,t) area of triangle t (corner coordinates) */
double sb_mesh_tri_area_st(const sb_mesh *m, int t);

/* ---- meshes of scene domains (sb_mesh_domain.c) ------------------------ */
typedef enum {
    SB_MESH_ALTERNATE = 0,   /* alternating diagonals (checkerboard) */
    SB_MESH_REGULAR = 1,     /* every diagonal from (s0,t0) to (s1,t1) */
    SB_MESH_CROSSED = 2,     /* 4 triangles per cell around its centre */
    SB_MESH_JITTER = 3       /* alternate, interior vertices jittered, then Delaunay flips */
} sb_mesh_pattern;
extern const char *const sb_mesh_pattern_names[];   /* "alternate", "regular", "crossed", "jitter", NULL */

typedef struct sb_mesh_spec {
    int n_s, n_t;            /* cells along s and t (each >= 1) */
    sb_mesh_pattern pattern;
    double jitter;           /* JITTER: amplitude as a fraction of the local cell size, [0, 0.45] */
    unsigned long seed;      /* JITTER: seed of the generator */
} sb_mesh_spec;

/* Triangulate the scene's domain (see sb_mesh_domain.c for the grid lines,
 * the notch and the annulus), reference positions from its chart, vertices
 * with the same reference position identified (seams), boundary parts
 * tagged, jitter applied.  On failure a sentence in err and SB_ERR_INPUT.
 * *rng_name receives the generator's name for JITTER (else NULL). */
int  sb_mesh_from_domain(const sb_scene *sc, const sb_mesh_spec *spec, sb_mesh *m, const char **rng_name,
                         char *err, size_t errlen);
/* xi and X of every vertex from its (s,t) (after moving vertices). */
void sb_mesh_set_geometry(sb_mesh *m, const sb_scene *sc);
/* Tag vertex boundary flags and the named parts of boundary edges. */
void sb_mesh_tag_boundary(sb_mesh *m, const sb_scene *sc);

/* ---- jitter and Delaunay flips (sb_mesh_jitter.c) ----------------------- */
/* Displace every vertex that is neither on the boundary nor pinned by up to
 * amp times its local edge spacing along s and t (uniform, GSL generator
 * gsl_rng_mt19937 seeded with `seed`); displacements that would invert a
 * triangle are halved until none does.  Then sb_mesh_delaunay. */
int  sb_mesh_jitter(sb_mesh *m, const sb_scene *sc, double amp, unsigned long seed, const char **rng_name);
/* Lawson flips until every interior edge is locally Delaunay in material
 * coordinates xi (opposite angles sum to at most pi).  Returns the number of
 * flips (>= 0) or a negative status. */
int  sb_mesh_delaunay(sb_mesh *m, const sb_scene *sc);

/* ---- boundary parts (sb_mesh_parts.c) ------------------------------------ */
/* Vertices on a part (edge: the segment in (s,t); point: the vertex at the
 * point).  Writes up to m->nv indices into out, returns the count. */
int  sb_mesh_part_vertices(const sb_mesh *m, const sb_part *p, int *out);
/* Boundary edges with both corners on an edge part; count, indices in out. */
int  sb_mesh_part_edges(const sb_mesh *m, const sb_part *p, int *out);
/* The vertex at a point part, or -1 when no vertex lies there. */
int  sb_mesh_point_vertex(const sb_mesh *m, const sb_part *p);
/* A line load of force per reference length vec[3] on boundary edges
 * (indices from sb_mesh_part_edges), lumped: each edge gives half of
 * |X_b - X_a| vec to each of its two vertices' entries of b (3 per vertex);
 * exact for the linear elements' consistent load of a constant density. */
void sb_mesh_lump_line_load(const sb_mesh *m, const int *edges, int ne, const double vec[3], double *b);

/* ---- point location (sb_mesh_locate.c) ----------------------------------- */
typedef struct sb_mesh_locator {
    int nb_s, nb_t;          /* buckets over [0,1]^2 in (s,t) */
    int *ptr, *tri;          /* CSR: triangles overlapping each bucket */
} sb_mesh_locator;

int  sb_mesh_locator_build(const sb_mesh *m, sb_mesh_locator *L);
void sb_mesh_locator_free(sb_mesh_locator *L);
/* Triangle containing (s,t) and its barycentric coordinates (corner order,
 * clamped to >= 0 and renormalised for points within round-off of an edge),
 * or -1 when the point lies outside the mesh. */
int  sb_mesh_locate(const sb_mesh *m, const sb_mesh_locator *L, double s, double t, double bary[3]);

/* ---- nested 1-to-4 refinement (sb_mesh_refine.c) ------------------------- */
/* Fine vertex v < nv_c is coarse vertex v; fine vertex nv_c + e is the
 * midpoint (in the corner (s,t)) of coarse edge e.  Coarse triangle k with
 * corners (v0, v1, v2) and edge midpoints m0, m1, m2 (m_i opposite v_i)
 * becomes fine triangles 4k..4k+3 = (v0,m2,m1), (m2,v1,m0), (m1,m0,v2),
 * (m0,m1,m2). */
typedef struct sb_mesh_refinement {
    int nv_c, ne_c, nt_c;
    int *edge_half;          /* 2 ne_c: fine halves of coarse edge e, [0] at edge_v[2e] */
    int *edge_parent;        /* ne_f: coarse edge that fine edge halves, -1 for interior edges */
    int *edge_tri;           /* ne_f: coarse triangle of an interior fine edge, -1 for halves */
    int *edge_corner;        /* ne_f: for an interior edge, the corner of edge_tri it is parallel to
                                (it joins the midpoints of the two other edges), -1 for halves */
} sb_mesh_refinement;

int  sb_mesh_refine4(const sb_mesh *c, const sb_scene *sc, sb_mesh *f, sb_mesh_refinement *r);
void sb_mesh_refinement_free(sb_mesh_refinement *r);

#endif
