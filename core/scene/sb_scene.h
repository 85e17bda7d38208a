/* sb_scene.h — what is simulated: plain data read from a JSON scene file.
 * Every method receives an identical sb_scene.  See docs/scene_format.md.
 *
 * Coordinates.  A scene lives on a domain in material coordinates
 * xi = (xi1, xi2) in metres.  Structured methods use the *grid parameter*
 * (s, t) in [0,1]^2, mapped onto the domain by sb_domain_map() (rectangle and
 * L-shape: the bounding box; annulus sector: s radial, t angular).  The
 * reference surface is X(xi) = chart(xi), see sb_geometry.h. */
#ifndef SB_SCENE_H
#define SB_SCENE_H

#include "sb_common.h"

#define SB_SCENE_MAX_LOADS 16
#define SB_SCENE_MAX_BCS 32
#define SB_SCENE_MAX_PROBES 32
#define SB_SCENE_MAX_PARTS 8
/* elements per side: the scene's "resolution", --res and method.cells_t */
#define SB_SCENE_MAX_RESOLUTION 4096

/* ---- domain ---------------------------------------------------------- */
typedef enum { SB_DOMAIN_RECTANGLE, SB_DOMAIN_L_SHAPE, SB_DOMAIN_ANNULUS_SECTOR } sb_domain_kind;

/* Corners of the bounding box, counter-clockwise from (x0,y0). */
enum { SB_CORNER_00 = 0, SB_CORNER_10 = 1, SB_CORNER_11 = 2, SB_CORNER_01 = 3 };

typedef struct sb_domain {
    sb_domain_kind kind;
    double origin[2];      /* rectangle, L-shape: lower-left corner of the bounding box */
    double size[2];        /* rectangle, L-shape: width (xi1) and height (xi2) */
    double notch[2];       /* L-shape: size of the removed rectangle */
    int notch_corner;      /* L-shape: SB_CORNER_* where the notch is cut */
    double center[2];      /* annulus sector: centre in xi */
    double r_in, r_out;    /* annulus sector radii, 0 <= r_in < r_out */
    double theta[2];       /* annulus sector angle range (radians, theta[0] < theta[1]) */
} sb_domain;

/* ---- reference geometry chart ----------------------------------------- */
typedef enum { SB_CHART_PLANE, SB_CHART_CYLINDER, SB_CHART_SPHERE } sb_chart_kind;

typedef struct sb_chart {
    sb_chart_kind kind;
    /* The chart maps the domain's bounding box [x0,x1]x[y0,y1] linearly onto
     * its parameter ranges (see sb_geometry.c):
     *   plane:    X = (xi1, xi2, 0)
     *   cylinder: axis along e_y:  phi = angle[0] + u*(angle[1]-angle[0]),
     *             X = (R sin phi, v*length, R cos phi)      (u,v in [0,1])
     *   sphere:   theta = polar[0]+v*(..), phi = azimuth[0]+u*(..),
     *             X = R (sin th cos ph, sin th sin ph, cos th) */
    double radius;
    double angle[2];       /* cylinder angle range (rad) */
    double length;         /* cylinder length along its axis */
    double polar[2];       /* sphere polar range (rad) */
    double azimuth[2];     /* sphere azimuth range (rad) */
} sb_chart;

/* ---- material --------------------------------------------------------- */
typedef enum { SB_MAT_STVK, SB_MAT_DENIM } sb_material_kind;

#define SB_DENIM_MAX_TERMS 5
typedef struct sb_denim_params {
    /* RMTR paper Eq. (3.3)-(3.4), Table 1.  k in Pa (Table 1 gives MPa; the
     * parser converts), mu/alpha dimensionless.  mu[j][0] is NOT in Table 1:
     * it is taken as 1 - sum_{i>=2} mu[j][i] so that phi_j'(0) = 1 (assumption,
     * see docs/scene_format.md).  A scene may override any entry. */
    double k[4];
    int d[4];
    double mu[4][SB_DENIM_MAX_TERMS];
    double alpha[4][SB_DENIM_MAX_TERMS];
    /* beyond the fitted range (docs/denim.md "Denim beyond the fit"): 0 extend each
     * phi_j linearly past the maximum of phi_j' (default), 1 inadmissible (NaN) */
    int beyond_fit;
} sb_denim_params;

typedef struct sb_material_spec {
    sb_material_kind kind;
    double young, poisson;      /* stvk */
    sb_denim_params denim;      /* denim */
    double thickness;           /* m */
    double density;             /* areal density, kg/m^2 */
    double warp_angle;          /* rad, warp direction measured from the first
                                   covariant base vector a_1 in the tangent plane */
} sb_material_spec;

/* ---- boundary parts --------------------------------------------------- */
/* A part is a named edge of the domain or a single material point.  Edges are
 * segments in the grid parameter (s,t): s=0 "left" ("inner" for annulus),
 * s=1 "right" ("outer"), t=0 "bottom" ("start"), t=1 "top" ("end"); the
 * L-shape adds "notch_s" (the notch edge at constant s) and "notch_t" (at
 * constant t).  On an L-shape the outer edges are clipped by the notch. */
typedef enum { SB_PART_EDGE, SB_PART_POINT } sb_part_kind;

typedef struct sb_part {
    sb_part_kind kind;
    char name[SB_NAME_LEN]; /* edge name, or "point_N" for the N-th part given by "at" */
    double st0[2], st1[2];  /* edge: segment in (s,t), axis-aligned, st0 < st1 componentwise */
    double xi[2];           /* point: material coordinates */
    double st[2];           /* point: grid parameter of xi */
} sb_part;

/* ---- motion schedules (docs/scene_format.md "Schedules") ---------------- */
/* A piecewise-linear motion factor f(t) through keyframes (t_k, f_k):
 * "schedule": [[t_0, f_0], [t_1, f_1], ...] on a moving boundary or an
 * obstacle's motion, t in seconds (dynamic scenes) or load steps
 * (quasi-static), strictly increasing from t_0 >= 0; f = 0 at t = 0 (a
 * keyframe at t = 0 must have f = 0; before t_0 > 0 the factor runs linearly
 * from (0, 0)), f_k after the last keyframe.  n = 0: no schedule (the ramp). */
#define SB_SCHEDULE_MAX 32
typedef struct sb_schedule {
    int n;
    double t[SB_SCHEDULE_MAX];
    double f[SB_SCHEDULE_MAX];
} sb_schedule;

/* ---- loads ------------------------------------------------------------ */
typedef enum {
    SB_LOAD_GRAVITY,     /* vec = acceleration (m/s^2); force density = density * vec */
    SB_LOAD_PRESSURE,    /* value = pressure (Pa) along the surface normal a_3 */
    SB_LOAD_LINE,        /* vec = force per unit reference length (N/m) on each part */
    SB_LOAD_POINT,       /* vec = force (N) at each point part */
    SB_LOAD_END_MOMENT   /* value = moment per unit reference length (N m / m) on each
                            edge part, about axis `vec` (unit), conservative: E = -m * theta */
} sb_load_kind;

typedef struct sb_load {
    sb_load_kind kind;
    double vec[3];
    double value;
    int follower;        /* pressure: 1 = follows the deformed normal, 0 = dead load on
                            the reference normal */
    int n_parts;
    sb_part parts[SB_SCENE_MAX_PARTS];
    int ramp_steps;      /* factor = min(1, step/ramp_steps); 0 = dynamic scenes: constant
                            (full from step 1), quasi-static scenes: step/steps (linear
                            over all load steps).  See sb_load_factor(). */
} sb_load;

/* ---- boundary conditions ---------------------------------------------- */
typedef enum {
    SB_BC_FIXED,      /* position held at the reference (components mask) */
    SB_BC_CLAMPED,    /* position and tangent plane held */
    SB_BC_SYMMETRY,   /* symmetry plane with normal e_axis through the part:
                         normal displacement and rotation about the in-plane edge
                         direction vanish */
    SB_BC_MOVING,     /* prescribed rigid motion: x = c + R(f*angle)(X - c) + f*translation,
                         f = min(1, step/ramp_steps) (dynamic: t/(ramp_steps*dt)) */
    SB_BC_FREE
} sb_bc_kind;

typedef struct sb_bc {
    sb_bc_kind kind;
    int n_parts;
    sb_part parts[SB_SCENE_MAX_PARTS];
    unsigned components;     /* fixed/moving: bit 0 = x, 1 = y, 2 = z (default 7) */
    int axis;                /* symmetry: 0, 1, 2 */
    double translation[3];   /* moving */
    double rot_axis[3];      /* moving: unit axis (zero vector = no rotation) */
    double rot_center[3];
    double rot_angle;        /* rad, total */
    int ramp_steps;          /* moving: 0 = all steps */
    sb_schedule schedule;    /* moving: n > 0 replaces the ramp (sb_schedule_factor) */
    int clamp_tangent;       /* moving: also prescribe the (rotated) tangents */
    unsigned derivative;     /* moving, scene key "derivative" ("s", "t", "st"): bit 0 = the nodal first
                                derivative along s, bit 1 = along t is prescribed, rotated with the
                                motion (x_,s = R X_,s).  Nodal derivatives are generalized coordinates
                                of Hermite elements only (BHEM paper §4.2, "Neumann constraints"):
                                methods without SB_METHOD_NODAL_DERIVATIVES refuse the scene before
                                any work (sb_run_scene_method_check) */
    /* moving point, "slide" (docs/scene_format.md "Sliding pins"): the pinned
     * material point runs from the "at" point (st of parts[0]) to slide_st as
     * the motion factor runs from 0 to 1, and is held by a penalty spring of
     * slide_stiffness N/m at its moved reference position (core sb_pin.c) */
    int slide;
    double slide_xi[2], slide_st[2];
    double slide_stiffness;
} sb_bc;

/* ---- time ------------------------------------------------------------- */
typedef enum { SB_TIME_QUASI_STATIC, SB_TIME_DYNAMIC } sb_time_mode;

typedef struct sb_time_spec {
    sb_time_mode mode;
    int steps;               /* load steps (quasi-static) or time steps (dynamic) */
    double dt;               /* dynamic only */
    double rayleigh_alpha;   /* dynamic: D = alpha M + beta K */
    double rayleigh_beta;
} sb_time_spec;

/* ---- probes and reference --------------------------------------------- */
#define SB_PROBE_MAX_CHECKS 4

/* One expected value of a probe: a component of the displacement x - X at
 * the FINAL step with a relative tolerance (docs/trust.md "Validation"). */
typedef struct sb_probe_check {
    int component;           /* 0,1,2 = x,y,z displacement; 3 = norm; -1 = full vector */
    double value[3];         /* expected value (in [0] unless component -1) */
    double tol;              /* relative tolerance, in (0, 1] */
} sb_probe_check;

typedef struct sb_probe {
    char name[SB_NAME_LEN];
    double xi[2];            /* material point */
    double st[2];            /* its grid parameter */
    int n_checks;            /* expected values ("expected": an object or an array of them) */
    sb_probe_check checks[SB_PROBE_MAX_CHECKS];
    /* the first check, as the fields readers of one expected value use */
    int has_expected;
    int expected_component;  /* 0,1,2 = x,y,z displacement; 3 = norm of displacement;
                                -1 = full displacement vector */
    double expected[3];      /* expected displacement x - X at the FINAL step
                                (component in [0] unless -1) */
    double tol;              /* relative tolerance for "expected" (checked: docs/trust.md) */
} sb_probe;

typedef enum { SB_REF_NONE, SB_REF_PROBES, SB_REF_FILE } sb_reference_kind;

typedef struct sb_reference {
    sb_reference_kind kind;  /* PROBES: error = max probe rel_error;
                                FILE: error = RMS/max of |x - x_ref| / diameter on the sample grid */
    char file[512];          /* FILE: HDF5 run record (resolved relative to the scene file) */
    char note[256];          /* where the reference value comes from */
} sb_reference;

/* "methods": {"NAME": {"resolution": N or [N, M], "set": {"method.KEY": V}}}:
 * how a discretization is bundled with the scene (sb_scene_methods.c) */
#define SB_SCENE_MAX_METHODS 8
#define SB_SCENE_MAX_METHOD_SETS 6
typedef struct sb_scene_method {
    char method[SB_NAME_LEN];
    int res, res_t;          /* 0: the scene's "resolution" */
    int n_sets;
    char sets[SB_SCENE_MAX_METHOD_SETS][96];   /* "method.KEY=VALUE", applied before --set */
} sb_scene_method;
/* ---- obstacles and contact (docs/contact.md) ------------------------- */
#define SB_SCENE_MAX_OBSTACLES 64
typedef enum { SB_OBST_SPHERE, SB_OBST_PLANE, SB_OBST_BOX, SB_OBST_CAPSULE, SB_OBST_MESH } sb_obstacle_shape;

typedef struct sb_obstacle_spec {
    sb_obstacle_shape kind;
    char name[SB_NAME_LEN];
    double center[3];        /* sphere, box: centre */
    double radius;           /* sphere, capsule */
    double point[3];         /* plane: a point on it */
    double normal[3];        /* plane: unit normal pointing to the free side */
    double half[3];          /* box: half extents along x, y, z (axis-aligned at rest) */
    double a[3], b[3];       /* capsule: the two ends of its axis segment */
    char file[512];          /* mesh: OBJ path as given (relative to the scene file) */
    int nv, nt;              /* mesh: vertices and triangles (owned, freed by sb_scene_free) */
    double *verts;           /* 3 nv */
    int *tris;               /* 3 nt */
    double friction;         /* Coulomb coefficient mu >= 0 */
    /* rigid motion like a moving boundary: pose(f) x = c + R(f angle)(x - c) + f translation,
       f = sb_obstacle_motion_factor (0 at step 0) */
    double translation[3];
    double rot_axis[3];      /* unit (zero: no rotation) */
    double rot_center[3];
    double rot_angle;        /* rad, total */
    int ramp_steps;          /* 0 = all steps */
    sb_schedule schedule;    /* n > 0 replaces the ramp (sb_schedule_factor) */
    int moving;
} sb_obstacle_spec;

typedef struct sb_contact_spec {
    double dhat;             /* barrier activation distance (m), IPC's d-hat */
    double kappa;            /* barrier stiffness per unit reference area (Pa/m) */
    double eps_v;            /* friction smoothing velocity (m/s), IPC's epsilon_v */
    int samples;             /* sample points per element side (smooth methods) */
    double filter;           /* fraction of the time of impact a step may take, (0, 1) */
    int model;               /* SB_CONTACT_BARRIER (default) or SB_CONTACT_IMPULSE */
    int self;                /* 1: self-contact too ("self": true) */
} sb_contact_spec;

/* contact.model (docs/contact.md): "barrier" = the IPC barrier in Phi for every
 * method; "impulse" = the papers' own post-step collision response (Bridson et
 * al. 2002 / Bender & Deul §6 for triangle methods, BHEM §5.2/§6.2 for bhem),
 * through the method op impulse_response */
enum { SB_CONTACT_BARRIER = 0, SB_CONTACT_IMPULSE = 1 };

typedef struct sb_scene {
    char name[SB_NAME_LEN];
    char path[512];          /* file it was read from */
    char *json_text;         /* the file's text verbatim (recorded); owned */
    char description[512];
    sb_domain domain;
    sb_chart chart;
    sb_material_spec material;
    int n_loads;  sb_load loads[SB_SCENE_MAX_LOADS];
    int n_bcs;    sb_bc bcs[SB_SCENE_MAX_BCS];
    sb_time_spec time;
    int n_probes; sb_probe probes[SB_SCENE_MAX_PROBES];
    sb_reference reference;
    int default_res;         /* suggested resolution (elements per side) when --res is absent */
    int default_res_t;       /* "resolution": [N, M]: M elements along t (0: as default_res) */
    int n_methods;
    sb_scene_method methods[SB_SCENE_MAX_METHODS];
    int n_obstacles; sb_obstacle_spec obstacles[SB_SCENE_MAX_OBSTACLES];
    sb_contact_spec contact; /* meaningful when n_obstacles > 0 */
} sb_scene;

/* Parse and validate.  On error returns SB_ERR_INPUT and writes
 * "FILE:LINE:COLUMN: at /json/path: what is wrong" into err. */
int sb_scene_load(const char *path, sb_scene *scene, char *err, size_t errlen);
int sb_scene_parse_string(const char *text, const char *path_for_messages,
                          sb_scene *scene, char *err, size_t errlen);
/* The same for len bytes that may hold anything (what sb_scene_load does
 * with a file's contents: NUL bytes, a byte-order mark, an HDF5 file). */
int sb_scene_parse_buffer(const char *bytes, size_t len, const char *path_for_messages,
                          sb_scene *scene, char *err, size_t errlen);
void sb_scene_free(sb_scene *scene);
/* Resolve a scene name ("trampoline") or path to a file path. */
int sb_scene_resolve(const char *name_or_path, char *path, size_t len);
/* A project file by its path relative to the project root (e.g.
 * "results/references/trampoline.h5"), looked for where bundled scenes are
 * (working directory, $SB_ROOT, the executable's parent); SB_OK when found. */
int sb_project_file(const char *rel, char *path, size_t len);

/* The scene's settings for `method` (its "methods" entry), or NULL. */
const sb_scene_method *sb_scene_method_find(const sb_scene *sc, const char *method);
/* The resolution `method` is bundled at: its "methods" entry's, else the
 * scene's "resolution", else 8 (res_t 0: as res). */
void sb_scene_bundled_res(const sb_scene *sc, const char *method, int *res, int *res_t);

/* Ramp factors at step n (1-based) of the scene's time spec. */
double sb_load_factor(const sb_scene *s, const sb_load *ld, int step);
double sb_bc_motion_factor(const sb_scene *s, const sb_bc *bc, int step);
/* f(t) of a schedule with n > 0 keyframes (piecewise linear, see sb_schedule) */
double sb_schedule_factor(const sb_schedule *sch, double t);
double sb_obstacle_motion_factor(const sb_scene *s, const sb_obstacle_spec *o, int step);

#endif
