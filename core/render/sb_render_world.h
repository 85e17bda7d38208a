/* sb_render_world.h — private to core/render: what rays are traced against
 * (the surface's primitives in a BVH, obstacles, the ground plane) and the
 * colour field over the surface. */
#ifndef SB_RENDER_WORLD_H
#define SB_RENDER_WORLD_H

#include "sb_render.h"
#include "sb_bvh.h"
#include "sb_shell.h"

enum { SB_HIT_NONE = 0, SB_HIT_PATCH, SB_HIT_TRIANGLE, SB_HIT_OBSTACLE, SB_HIT_GROUND };

/* Ray against one analytic obstacle (sphere, box, capsule, plane square):
 * 1 and the entry t in (r->tmin, tmax) with the outward unit normal n there,
 * else 0.  A ray starting inside a solid does not hit it. */
int sb_ray_obstacle(const sb_obstacle *ob, const double pu[3], const double pv[3], const sb_ray *r, double tmax,
                    double *t, double n[3]);

typedef struct sb_hit {
    int kind;
    int prim;            /* patch or triangle index, obstacle index */
    int tri;             /* mesh obstacle: its triangle */
    double t;
    double u, v;         /* patch parameters, or triangle barycentrics of vertices 1 and 2 */
    double p[3];         /* hit point */
    double n[3];         /* unit shading normal (surface orientation, not flipped) */
} sb_hit;

typedef struct sb_world {
    const sb_surface *s;
    const sb_material *mat;
    sb_isect_kind isect;
    double eps;                  /* absolute intersection precision */
    sb_bvh bvh;                  /* prims [0, n_patches) patches, then triangles */
    double *plo, *phi;           /* primitive boxes */
    double *vnormal;             /* 3 n_verts: smooth vertex normals */
    double *vcurv;               /* n_verts: mean curvature per vertex (curvature colour), or NULL */
    sb_bezier_ws *ws;
    sb_shell_work *shell;
    int n_obstacles;
    sb_obstacle obstacles[SB_RENDER_MAX_OBSTACLES];   /* copies; planes with their drawn square resolved */
    double plane_u[SB_RENDER_MAX_OBSTACLES][3];      /* planes: in-plane unit axes of the square */
    double plane_v[SB_RENDER_MAX_OBSTACLES][3];
    /* mesh obstacles: their triangles in a BVH of their own */
    sb_bvh mbvh;
    int n_mtri;
    int *mtri_obst, *mtri_tri;   /* obstacle index and triangle index of each */
    double *mlo, *mhi;
    int ground;
    double ground_z, grid;       /* ground height and its grid spacing */
    double lo[3], hi[3], centre[3], radius;
    long tri_tests;
    /* shadow-ray context */
    sb_hit *cur;
} sb_world;

int  sb_world_build(sb_world *w, const sb_surface *s, const sb_material *mat, const sb_render_options *o,
                    char *err, size_t errlen);
void sb_world_free(sb_world *w);
/* Nearest hit in (r->tmin, tmax) of the surface, obstacles and ground;
 * any = 1: any occluder (shadow rays; the ground is not an occluder).
 * Returns 1 if hit, 0 if not, -1 on out of memory. */
int  sb_world_intersect(sb_world *w, const sb_ray *r, double tmax, int any, sb_hit *h);

/* Colour field at a surface hit (sb_render_field.c): the scalar for kind
 * (curvature: mean curvature, 1/m; strain: the larger principal membrane
 * Green–Lagrange strain; softening: the smallest
 * relative eigenvalue of the membrane tangent, < 0 = soft).  Returns 0, or
 * -1 when it cannot be evaluated there (degenerate point). */
int  sb_field_at(sb_world *w, sb_color_kind kind, int hit_kind, int prim, double u, double v, double *val);
/* Can the surface give this colour?  0 yes, else -1 with the reason in err. */
int  sb_field_check(const sb_surface *s, const sb_material *mat, sb_color_kind kind, char *err, size_t errlen);
/* Per-vertex mean curvature of a triangle surface (cotangent formula). */
int  sb_field_vertex_curvature(const sb_surface *s, const double *vnormal, double *curv);

/* ---- text (sb_font.c) --------------------------------------------------- */
/* Draw text with its top-left corner at (x, y) in colour rgb (linear), scale
 * = pixel size of a font dot; returns the width drawn.  Characters outside
 * printable ASCII are drawn as '?'. */
int  sb_font_draw(sb_image *im, int x, int y, int scale, const char *text, const float rgb[3]);
int  sb_font_width(const char *text, int scale);
int  sb_font_height(int scale);

#endif
