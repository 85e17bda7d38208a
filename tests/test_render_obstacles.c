/* test_render_obstacles.c — the renderer draws every obstacle kind of a
 * scene (sphere, rotated box, capsule, plane, OBJ mesh) at its pose of the
 * rendered step: a scene with one of each, mapped by
 * sb_render_scene_obstacles at step 2 of a 4-step motion ramp (f = 1/2),
 * is hit by rays where the analytic geometry of the moved obstacle says
 * (distance and normal), misses where it says, and shadows; and a scene
 * with as many obstacles as a scene can have (64 spheres in a row, more
 * than the 16 the renderer once held) has every one drawn. */
#include "sb_test.h"
#include "sb_render_world.h"
#include "sb_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SCENE \
    "{\"name\": \"o\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1]}," \
    "\"material\": {\"model\": \"stvk\", \"young\": 1e5, \"poisson\": 0.3, \"thickness\": 0.001, \"density\": 0.2}," \
    "\"loads\": [{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]}]," \
    "\"time\": {\"mode\": \"dynamic\", \"dt\": 0.01, \"steps\": 5}," \
    "\"obstacles\": [" \
    "{\"type\": \"sphere\", \"center\": [0.5, 0.5, -0.3], \"radius\": 0.2," \
    "  \"motion\": {\"translation\": [0, 0, 0.1], \"ramp_steps\": 4}}," \
    "{\"type\": \"box\", \"center\": [2, 0, 0], \"half_extents\": [0.3, 0.2, 0.1]," \
    "  \"motion\": {\"rotation\": {\"axis\": [0, 0, 1], \"center\": [2, 0, 0], \"angle\": 30}, \"ramp_steps\": 4}}," \
    "{\"type\": \"capsule\", \"from\": [-1, 1, 0], \"to\": [-1, 3, 0], \"radius\": 0.1," \
    "  \"motion\": {\"translation\": [0, 0, 0.2], \"ramp_steps\": 4}}," \
    "{\"type\": \"plane\", \"point\": [0, 0, -1], \"normal\": [0, 0.6, 0.8]," \
    "  \"motion\": {\"translation\": [0, 0, 0.4], \"ramp_steps\": 4}}," \
    "{\"type\": \"mesh\", \"file\": \"cube.obj\"," \
    "  \"motion\": {\"translation\": [0, -2, 0], \"rotation\": {\"axis\": [0, 0, 1], \"center\": [0, 0, 0], \"angle\": 90}," \
    "             \"ramp_steps\": 4}}]," \
    "\"contact\": {\"dhat\": 0.001}}"

typedef struct fixture {
    sb_scene sc;
    sb_surface s;
    double vert[9];
    int tri[3];
    sb_render_options o;
    double *mv;
    sb_world w;
} fixture;

/* the obstacles of scene `json` (n_expect of them) at step 2 around a small
 * triangle far from them (the plane's drawn square is centred under the
 * surface) */
static int open_scene(sb_test_state *T, fixture *F, const char *json, int n_expect)
{
    memset(F, 0, sizeof *F);
    char path[1024], err[1024];
    snprintf(path, sizeof path, "%s/tests/scenes/contact/inline.json", sb_test_root());
    int rc = sb_scene_parse_string(json, path, &F->sc, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    if (rc) return -1;
    const double v[9] = { 10, 10, 10, 11, 10, 10, 10, 11, 10 };
    memcpy(F->vert, v, sizeof v);
    F->tri[0] = 0; F->tri[1] = 1; F->tri[2] = 2;
    F->s.n_verts = 3;
    F->s.vert = F->vert;
    F->s.n_tris = 1;
    F->s.tri = F->tri;
    sb_render_options_default(&F->o);
    F->o.ground = 0;
    CHECK_EQ_INT(sb_render_scene_obstacles(&F->sc, 2, &F->o, &F->mv), 0);
    CHECK_EQ_INT(F->o.n_obstacles, n_expect);
    rc = sb_world_build(&F->w, &F->s, NULL, &F->o, err, sizeof err);
    CHECK_MSG(rc == 0, "%s", err);
    return rc ? -1 : 0;
}

/* the scene with one obstacle of each kind */
static int open_fixture(sb_test_state *T, fixture *F) { return open_scene(T, F, SCENE, 5); }

static void close_fixture(fixture *F)
{
    sb_world_free(&F->w);
    free(F->mv);
    F->s.vert = NULL;
    F->s.tri = NULL;
    sb_scene_free(&F->sc);
}

/* first hit of the ray o + t d: its kind, obstacle, t and normal */
static int trace(fixture *F, const double o[3], const double d[3], sb_hit *h)
{
    sb_ray r;
    if (sb_ray_init(&r, o, d, 0.0, INFINITY)) return -1;
    return sb_world_intersect(&F->w, &r, INFINITY, 0, h);
}

#define EXPECT_HIT(F, o, d, obst, t_expect, nx, ny, nz)                         \
    do {                                                                        \
        sb_hit h_;                                                              \
        CHECK_EQ_INT(trace(F, o, d, &h_), 1);                                   \
        CHECK_EQ_INT(h_.kind, SB_HIT_OBSTACLE);                                 \
        CHECK_EQ_INT(h_.prim, obst);                                            \
        CHECK_NEAR(h_.t, t_expect, 1e-9);                                       \
        CHECK_NEAR(h_.n[0], nx, 1e-9);                                          \
        CHECK_NEAR(h_.n[1], ny, 1e-9);                                          \
        CHECK_NEAR(h_.n[2], nz, 1e-9);                                          \
    } while (0)

static int misses(fixture *F, const double o[3], const double d[3])
{
    sb_hit h;
    return trace(F, o, d, &h) == 0;
}

SB_TEST(sphere_at_its_ramped_pose)
{
    fixture F;
    if (open_fixture(T, &F)) { close_fixture(&F); return; }
    /* centre (0.5, 0.5, -0.3 + 0.1/2): the top at z = -0.05 */
    const double o[3] = { 0.5, 0.5, 5 }, d[3] = { 0, 0, -1 };
    EXPECT_HIT(&F, o, d, 0, 5.05, 0, 0, 1);
    /* off-centre by 0.12: z = -0.25 + sqrt(0.2^2 - 0.12^2) */
    const double o2[3] = { 0.62, 0.5, 5 };
    EXPECT_HIT(&F, o2, d, 0, 5.25 - 0.16, 0.6, 0, 0.8);
    const double o3[3] = { 0.71, 0.5, 5 };
    CHECK(misses(&F, o3, d));
    close_fixture(&F);
}

SB_TEST(box_rotated_by_half_its_angle)
{
    fixture F;
    if (open_fixture(T, &F)) { close_fixture(&F); return; }
    const double a = 15.0 * M_PI / 180.0, ex[3] = { cos(a), sin(a), 0 };
    /* along its own x axis: the face at 0.3 from the centre, normal R e_x */
    const double o[3] = { 2 + 5 * ex[0], 5 * ex[1], 0 }, d[3] = { -ex[0], -ex[1], 0 };
    EXPECT_HIT(&F, o, d, 1, 4.7, ex[0], ex[1], 0);
    /* along the world x axis through the centre: the same face, 0.3 / cos 15 deg away */
    const double o2[3] = { 5, 0, 0 }, d2[3] = { -1, 0, 0 };
    EXPECT_HIT(&F, o2, d2, 1, 3 - 0.3 / cos(a), ex[0], ex[1], 0);
    /* from above, beside the rotated box where the unrotated one would be hit:
       world (2.28, -0.18) lies outside it (its local y is -0.246 < -0.2) */
    const double o3[3] = { 2.28, -0.18, 5 }, d3[3] = { 0, 0, -1 };
    CHECK(misses(&F, o3, d3));
    close_fixture(&F);
}

SB_TEST(capsule_side_and_end_caps)
{
    fixture F;
    if (open_fixture(T, &F)) { close_fixture(&F); return; }
    const double d[3] = { 0, 0, -1 };
    /* axis at z = 0.1 after the ramp: the side from above */
    const double o[3] = { -1, 2, 5 };
    EXPECT_HIT(&F, o, d, 2, 4.8, 0, 0, 1);
    /* beyond the end (-1, 3, 0.1): the end ball, z = 0.1 + sqrt(0.1^2 - 0.05^2) */
    const double s = sqrt(0.0075), o2[3] = { -1, 3.05, 5 };
    EXPECT_HIT(&F, o2, d, 2, 4.9 - s, 0, 0.05 / 0.1, s / 0.1);
    /* along the axis into the first end: t = 5 - 1 - 0.1 */
    const double o3[3] = { -1, -4, 0.1 }, d3[3] = { 0, 1, 0 };
    EXPECT_HIT(&F, o3, d3, 2, 4.9, 0, -1, 0);
    /* just beside the side */
    const double o4[3] = { -0.89, 2, 5 };
    CHECK(misses(&F, o4, d));
    close_fixture(&F);
}

SB_TEST(plane_is_a_bounded_square_under_the_surface)
{
    fixture F;
    if (open_fixture(T, &F)) { close_fixture(&F); return; }
    /* the plane 0.6 y + 0.8 (z + 0.8) = 0 (point moved up by 0.2); the square
       is centred at the foot of the perpendicular from the centre of the
       surface's bounding box */
    const double n[3] = { 0, 0.6, 0.8 }, c[3] = { 10.5, 10.5, 10 };
    const double h = 0.6 * c[1] + 0.8 * (c[2] + 0.8);
    double foot[3], o[3], d[3];
    for (int k = 0; k < 3; k++) {
        foot[k] = c[k] - h * n[k];
        o[k] = foot[k] + 2 * n[k];
        d[k] = -n[k];
    }
    EXPECT_HIT(&F, o, d, 3, 2.0, 0, 0.6, 0.8);
    /* from below too (the square is two-sided), the normal stays the plane's */
    double o2[3];
    for (int k = 0; k < 3; k++) o2[k] = foot[k] - 1.5 * n[k] + 0.2 * (k == 0);
    EXPECT_HIT(&F, o2, n, 3, 1.5, 0, 0.6, 0.8);
    /* bounded: 1.3 x the surface's bounding radius (half its diagonal, sqrt 2 / 2) */
    const double ext = 1.3 * sqrt(2.0) / 2;
    CHECK_NEAR(F.w.obstacles[3].extent, ext, 1e-12);
    double o3[3], o4[3];
    for (int k = 0; k < 3; k++) {
        o3[k] = o[k] + (k == 0 ? 0.98 * ext : 0);
        o4[k] = o[k] + (k == 0 ? 1.02 * ext : 0);
    }
    EXPECT_HIT(&F, o3, d, 3, 2.0, 0, 0.6, 0.8);
    CHECK(misses(&F, o4, d));
    close_fixture(&F);
}

SB_TEST(mesh_triangles_moved_and_rotated)
{
    fixture F;
    if (open_fixture(T, &F)) { close_fixture(&F); return; }
    /* the unit cube turned 45 degrees about z and moved to (0, -1, 0) */
    const double o[3] = { 0.1, -1.1, 5 }, d[3] = { 0, 0, -1 };
    EXPECT_HIT(&F, o, d, 4, 4.5, 0, 0, 1);
    /* across it at y = -0.95: its outline |x| + |y + 1| <= sqrt(2)/2, the face with normal (-1, 1, 0)/sqrt 2 */
    const double o2[3] = { -5, -0.95, 0.1 }, d2[3] = { 1, 0, 0 };
    const double r2 = sqrt(0.5);
    EXPECT_HIT(&F, o2, d2, 4, 5 - (r2 - 0.05), -r2, r2, 0);
    /* outside the turned outline but inside the unturned one: (0.45, -0.55) */
    const double o3[3] = { 0.45, -0.55, 5 };
    CHECK(misses(&F, o3, d));
    close_fixture(&F);
}

SB_TEST(obstacles_cast_shadows_and_render)
{
    fixture F;
    if (open_fixture(T, &F)) { close_fixture(&F); return; }
    /* any-hit (shadow) rays upward from under each solid obstacle */
    const double up[3] = { 0, 0, 1 };
    const double from[5][3] = { { 0.5, 0.5, -1 }, { 2, 0, -1 }, { -1, 2, -1 }, { 0, 0, 0 }, { 0, -1, -1 } };
    for (int i = 0; i < 5; i++) {
        sb_ray r;
        sb_hit h;
        double o[3];
        memcpy(o, from[i], sizeof o);
        if (i == 3) {   /* under the plane's square */
            const double n[3] = { 0, 0.6, 0.8 }, c[3] = { 10.5, 10.5, 10 };
            const double hh = 0.6 * c[1] + 0.8 * (c[2] + 0.8);
            for (int k = 0; k < 3; k++) o[k] = c[k] - (hh + 0.5) * n[k];
        }
        CHECK(sb_ray_init(&r, o, up, 0.0, INFINITY) == 0);
        CHECK_MSG(sb_world_intersect(&F.w, &r, INFINITY, 1, &h) == 1, "obstacle %d casts no shadow", i);
    }
    /* a picture of the five obstacles with the ground: every kind drawn
       through the shading path (hits counted by the renderer) */
    sb_render_options o = F.o;
    o.ground = 1;
    o.width = 48;
    o.height = 36;
    o.spp = 1;
    o.use_eye = 1;
    const double eye[3] = { 6, -8, 6 }, at[3] = { 0.5, 0, 0 };
    memcpy(o.eye, eye, sizeof eye);
    memcpy(o.at, at, sizeof at);
    sb_image img = { 0, 0, NULL };
    sb_render_stats st;
    char err[256];
    CHECK_EQ_INT(sb_render_surface(&F.s, NULL, &o, &img, &st, err, sizeof err), 0);
    CHECK(st.shadow_rays > 0);
    sb_image_free(&img);
    close_fixture(&F);
}

/* Sphere i of the row: centre (ROW_X0 + ROW_DX i, 0, 0), radius ROW_R. */
#define ROW_X0 2.0
#define ROW_DX 0.5
#define ROW_R 0.1

/* A scene with SB_SCENE_MAX_OBSTACLES spheres in a row along x (the most a
 * scene may have): every one is placed for the renderer and drawn.  Rays
 * straight down onto the 17th (the first beyond the renderer's former 16)
 * and the last sphere hit it at its top, t = height - ROW_R, normal +z; a
 * ray along the row from beyond its end hits the last sphere first, at
 * t = distance to the centre - ROW_R, normal +x. */
SB_TEST(every_obstacle_of_a_full_scene_is_drawn)
{
    enum { N = SB_SCENE_MAX_OBSTACLES };
    char json[16384];
    size_t len = (size_t)snprintf(json, sizeof json, "%s",
        "{\"name\": \"row\", \"domain\": {\"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [1, 1]},"
        "\"material\": {\"model\": \"stvk\", \"young\": 1e5, \"poisson\": 0.3, \"thickness\": 0.001, \"density\": 0.2},"
        "\"loads\": [{\"type\": \"gravity\", \"acceleration\": [0, 0, -9.81]}],"
        "\"time\": {\"mode\": \"dynamic\", \"dt\": 0.01, \"steps\": 5}, \"obstacles\": [");
    for (int i = 0; i < N && len < sizeof json; i++)
        len += (size_t)snprintf(json + len, sizeof json - len, "%s{\"type\": \"sphere\", \"center\": [%.17g, 0, 0], \"radius\": %g}",
                                i ? "," : "", ROW_X0 + ROW_DX * i, ROW_R);
    if (len < sizeof json) len += (size_t)snprintf(json + len, sizeof json - len, "], \"contact\": {\"dhat\": 0.001}}");
    CHECK(len < sizeof json);
    if (len >= sizeof json) return;

    fixture F;
    if (open_scene(T, &F, json, N)) { close_fixture(&F); return; }
    CHECK_EQ_INT(F.w.n_obstacles, N);
    const double d[3] = { 0, 0, -1 };
    const double o16[3] = { ROW_X0 + ROW_DX * 16, 0, 5 };
    EXPECT_HIT(&F, o16, d, 16, 5 - ROW_R, 0, 0, 1);
    const double xl = ROW_X0 + ROW_DX * (N - 1);
    const double ol[3] = { xl, 0, 5 };
    EXPECT_HIT(&F, ol, d, N - 1, 5 - ROW_R, 0, 0, 1);
    const double oe[3] = { xl + 3, 0, 0 }, de[3] = { -1, 0, 0 };
    EXPECT_HIT(&F, oe, de, N - 1, 3 - ROW_R, 1, 0, 0);
    /* between the last two spheres, nothing */
    const double om[3] = { xl - 0.5 * ROW_DX, 0, 5 };
    CHECK(misses(&F, om, d));

    /* room is short only after obstacles the caller put in first: one of
       its own leaves the scene's last out, and the count says so */
    sb_render_options o;
    sb_render_options_default(&o);
    o.n_obstacles = 1;
    o.obstacles[0] = F.o.obstacles[0];
    double *mv = NULL;
    CHECK_EQ_INT(sb_render_scene_obstacles(&F.sc, 2, &o, &mv), 1);
    CHECK_EQ_INT(o.n_obstacles, SB_RENDER_MAX_OBSTACLES);
    free(mv);
    close_fixture(&F);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(sphere_at_its_ramped_pose), SB_CASE(box_rotated_by_half_its_angle),
        SB_CASE(capsule_side_and_end_caps), SB_CASE(plane_is_a_bounded_square_under_the_surface),
        SB_CASE(mesh_triangles_moved_and_rotated), SB_CASE(obstacles_cast_shadows_and_render),
        SB_CASE(every_obstacle_of_a_full_scene_is_drawn), SB_END,
    };
    return sb_test_main(argc, argv, cases);
}
