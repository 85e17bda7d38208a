/* sb_surface.h — the surface of a discretization in the form the renderer
 * (and, later, contact geometry) consumes: what a method's optional
 * `surface` op (sb_method.h) fills for a state x.
 *
 * Two kinds of primitives, either or both:
 *   - bicubic Bézier patches (sb_bezier.h), the exact surface of spline
 *     methods: bhem's Hermite patches, rmtr's regular Catmull–Clark faces;
 *   - an indexed triangle list, the exact surface of triangle methods
 *     (linear_fem, adaptive meshes) and the tessellation fallback.
 * For each, the reference configuration in the same parametrization may be
 * given (patch_ref / vert_ref): the renderer then colours by membrane strain
 * and material softening through the shared shell kernel (sb_shell.h), in the
 * material frame of the scene (warp along the first parameter direction,
 * rotated by material.warp_angle).  Triangle strains need vert_st, the grid
 * parameter (s,t) of each vertex, or tri_st, that of each corner (the first
 * parameter direction of a triangle is d/ds). */
#ifndef SB_SURFACE_H
#define SB_SURFACE_H

typedef struct sb_surface {
    /* Bézier patches: 48 doubles each (sb_bezier.h layout), u along s, v along t */
    int n_patches;
    double *patch;        /* current */
    double *patch_ref;    /* reference, or NULL */
    double *patch_st;     /* 4 per patch: s0, s1, t0, t1, the grid-parameter box it covers, or NULL */
    /* indexed triangles, counter-clockwise seen from the +normal side */
    int n_verts, n_tris;
    double *vert;         /* 3 n_verts, current */
    double *vert_ref;     /* 3 n_verts, reference, or NULL */
    double *vert_st;      /* 2 n_verts grid parameters, or NULL */
    int *tri;             /* 3 n_tris */
    double *tri_st;       /* 6 n_tris: (s,t) of each corner, or NULL (then vert_st); needed where a
                             seam identifies vertices (sb_mesh.h "corner coordinates") */
    /* what the primitives are, one line ("64 Bézier patches (Hermite, exact)") */
    char what[160];
} sb_surface;

/* Allocate n patches (and the reference when with_ref, and patch_st); 0 or -1. */
int  sb_surface_alloc_patches(sb_surface *s, int n, int with_ref);
/* Allocate nv vertices and nt triangles (reference and st when asked); 0 or -1. */
int  sb_surface_alloc_tris(sb_surface *s, int nv, int nt, int with_ref, int with_st);
void sb_surface_free(sb_surface *s);

/* Bounding box of all primitives (control points bound the patches);
 * returns 0, or -1 for an empty surface or a non-finite coordinate. */
int  sb_surface_bounds(const sb_surface *s, double lo[3], double hi[3]);

#endif
