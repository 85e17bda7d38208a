/* sb_render.h — `shellbench render`: a ray-traced picture of a run's surface.
 *
 * Data flow: record -> scene + method rebuilt -> the method's surface for the
 * recorded state (sb_surface.h: Bézier patches or triangles) -> world (BVH
 * over the primitives, ground plane, obstacles) -> camera rays with Sobol
 * samples per pixel -> first hits (ray–patch intersection by the BHEM
 * paper's algorithms, sb_bezier_ray.h) -> shading with a key light and its
 * shadows -> labels -> PNG.  docs/render.md describes the command. */
#ifndef SB_RENDER_H
#define SB_RENDER_H

#include "sb_bezier_ray.h"
#include "sb_surface.h"
#include "sb_material.h"
#include "sb_scene.h"   /* SB_SCENE_MAX_OBSTACLES */

typedef enum { SB_COLOR_NONE = 0, SB_COLOR_CURVATURE, SB_COLOR_STRAIN, SB_COLOR_SOFTENING, SB_COLOR_COUNT } sb_color_kind;
extern const char *const sb_color_names[];   /* "none", "curvature", "strain", "softening", NULL */

/* An obstacle drawn with the surface (and shadowing it), in world
 * coordinates at the pose of the drawn step: the record path
 * (sb_render_scene_obstacles) maps every obstacle of a scene
 * (docs/contact.md) to one of these.
 *   sphere:  centre c, radius r;
 *   box:     [lo, hi] in its own frame, world x = m + R (y - m) with m the
 *            box centre (lo + hi) / 2; R is used only when rotated = 1;
 *   capsule: the points within r of the segment a-b;
 *   plane:   the plane through c with unit normal n (free side), drawn as a
 *            bounded square patch (half side `extent`, 0 = 1.3 x the
 *            surface's bounding radius) centred at the foot of the
 *            perpendicular from the surface's centre;
 *   mesh:    nt triangles tris over nv world-space vertices verts (borrowed:
 *            the caller keeps them alive while the world exists). */
typedef enum { SB_OBSTACLE_SPHERE = 0, SB_OBSTACLE_BOX, SB_OBSTACLE_CAPSULE, SB_OBSTACLE_PLANE,
               SB_OBSTACLE_MESH } sb_obstacle_kind;
typedef struct sb_obstacle {
    sb_obstacle_kind kind;
    double c[3], r;          /* sphere; plane: c a point; capsule: r */
    double lo[3], hi[3];     /* box */
    int rotated;             /* box: R applies */
    double R[9];             /* box: rotation, row-major */
    double a[3], b[3];       /* capsule axis ends */
    double n[3];             /* plane normal */
    double extent;           /* plane: half side of the drawn square (0: automatic) */
    int nv, nt;              /* mesh */
    const double *verts;
    const int *tris;
} sb_obstacle;
/* Room for every obstacle a scene can have: the record path draws all of a
 * scene's obstacles (at most SB_SCENE_MAX_OBSTACLES, sb_scene.h). */
#define SB_RENDER_MAX_OBSTACLES SB_SCENE_MAX_OBSTACLES

typedef struct sb_render_options {
    int width, height;       /* pixels */
    int spp;                 /* samples per pixel (Sobol points, gsl_qrng_sobol) */
    sb_isect_kind isect;     /* ray–patch algorithm for Bézier patches */
    sb_color_kind color;
    /* camera: orbit about the centre of the surface's bounding box ... */
    double azimuth, elevation;   /* degrees; azimuth from +x towards +y, elevation above the xy plane */
    double zoom;                 /* 1 = the bounding sphere fills the view */
    double fov;                  /* degrees, vertical field of view */
    /* ... or an explicit eye and target (use_eye = 1) */
    int use_eye;
    double eye[3], at[3];
    int shadows;             /* 1: key-light shadows */
    int ground;              /* 1: a ground plane under the surface */
    double eps_rel;          /* intersection precision relative to the bounding-box diagonal */
    char title[256];         /* top-left label ("" = none) */
    char subtitle[256];      /* second label line ("" = none) */
    int n_obstacles;
    sb_obstacle obstacles[SB_RENDER_MAX_OBSTACLES];
} sb_render_options;

/* 640x480, 16 spp, newton, no colour field, azimuth -60, elevation 30, zoom 1,
 * fov 30, shadows, ground, eps_rel 1e-6. */
void sb_render_options_default(sb_render_options *o);

typedef struct sb_render_stats {
    double seconds;          /* rendering (world build excluded), wall clock */
    double cpu_seconds;      /* the same in process CPU time (what benches compare) */
    double build_seconds;    /* BVH and field range */
    long primary_rays, shadow_rays;
    long tri_tests;
    sb_isect_counts isect;   /* Bézier-patch work (sb_bezier_ray.h) */
    double field_lo, field_hi;   /* colour scale: 1st and 99th percentile of the sampled field (NaN without) */
    double field_min, field_max; /* extremes of the sampled field */
    double soft_fraction;        /* softening: fraction of samples that are soft */
} sb_render_stats;

typedef struct sb_image {
    int w, h;
    float *rgb;              /* linear RGB, 3 w h, row 0 at the top */
} sb_image;

int  sb_image_alloc(sb_image *im, int w, int h);
void sb_image_free(sb_image *im);
/* 8-bit RGB PNG (sRGB-encoded) with tEXt chunks key[i] = val[i] (n_text may
 * be 0).  Returns 0 or -1 with a message in err. */
int  sb_image_write_png(const sb_image *im, const char *path, int n_text, const char *const *key,
                        const char *const *val, char *err, size_t errlen);
/* tEXt chunk `key` of a PNG written by sb_image_write_png, and its size
 * (w, h): 0, or -1 when absent or unreadable. */
int  sb_image_png_text(const char *path, const char *key, char *val, size_t len, int *w, int *h);

/* Render surface s (mat: the scene's material for strain / softening
 * colours, may be NULL for none/curvature).  Returns SB_OK; SB_ERR_INPUT
 * (empty or non-finite surface, a colour the surface cannot give) or
 * SB_ERR_NOMEM with a sentence in err. */
int sb_render_surface(const sb_surface *s, const sb_material *mat, const sb_render_options *o, sb_image *img,
                      sb_render_stats *st, char *err, size_t errlen);

/* ---- records ---------------------------------------------------------- */

/* Append the obstacles of scene sc at their pose of `step` (motion ramps,
 * sb_obstacle_motion_factor) to o.  Mesh obstacles need their vertices
 * moved: *mesh_verts receives one malloc'd block holding them (free it after
 * rendering; NULL when there are none).  o has room for every obstacle of a
 * scene (SB_RENDER_MAX_OBSTACLES = SB_SCENE_MAX_OBSTACLES), so all of them
 * are appended when o starts without obstacles; only obstacles the caller
 * put into o before can leave too little room.  Returns the number of the
 * scene's obstacles left out for want of room (0 when o->n_obstacles was 0),
 * or -1 when out of memory. */
int sb_render_scene_obstacles(const sb_scene *sc, int step, sb_render_options *o, double **mesh_verts);


/* Which state of a record to draw: step -1 = the final state (exact, from
 * /final/x and the method's surface); step k >= 0 = the recorded surface of
 * step k (/steps/sample_pos, a triangulation of the sample grid). */
typedef struct sb_render_request {
    const char *record;
    const char *out;         /* PNG path */
    int step;
    sb_render_options opt;
    int quiet;
} sb_render_request;

/* Render a record to a PNG.  Returns SB_OK, SB_ERR_INPUT (a record that
 * cannot be rendered: missing data, unknown method; one sentence naming the
 * file in err), SB_ERR_IO or SB_ERR_NOMEM.  st may be NULL; info (may be
 * NULL) receives one line saying what was drawn. */
int sb_render_record(const sb_render_request *rq, sb_render_stats *st, char *info, size_t infolen,
                     char *err, size_t errlen);

/* The one-call entry point for reports: the final state of the record at
 * PATH as a w x h PNG at OUT with the defaults (8 samples per pixel).
 * Returns SB_OK or an error as sb_render_record, with the sentence in err. */
int sb_render_record_png(const char *path, const char *out, int w, int h, char *err, size_t errlen);

/* `shellbench render ...` (core/cli/main.c dispatches here); returns the
 * exit code (0 ok, 2 input error, 3 internal error). */
int sb_render_main(int argc, char **argv);

/* how pixel samples are drawn, recorded in each image (issue 31) */
#define SB_RENDER_SAMPLES "Sobol points (gsl_qrng_sobol, 4-D) with a per-pixel Cranley-Patterson rotation from the SplitMix64 hash of the pixel index"

#endif
