/* test_bhem_derivative.c — the moving boundary's "derivative" key (issue 39,
 * the umbrella of BHEM Fig. 5: nodal positions and first derivatives
 * prescribed, BHEM §4.2 Neumann constraints):
 *   - bhem eliminates exactly the named nodal derivatives ("s", "t", "st")
 *     and prescribes them rotated with the motion, x_,s = R X_,s;
 *   - a strip whose two nodes at s = 0 turn with their derivative along s
 *     converges to the known minimizer, the rigid rotation (zero energy);
 *   - every other method refuses the scene before any work (no record),
 *     with a sentence naming the key, in `run` and in `sweep`. */
#include "cli_sh.h"
#include "test_bhem_common.h"

#include <math.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#define PT_SCENE(deriv)                                                                                             \
    TB_SCENE("{\"type\": \"rectangle\", \"origin\": [-0.5, -0.5], \"size\": [1, 1]}", TB_PLANE, TB_STVK,             \
             "[{\"type\": \"moving\", \"at\": [0, 0], \"derivative\": \"" deriv "\","                               \
             "  \"rotation\": {\"axis\": [0, 0, 1], \"center\": [0, 0, 0], \"angle\": 90}}]", "[]")

static void set_motion(tb_method *m, double f)
{
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = 1;
    si.n_steps = 1;
    for (int k = 0; k < SB_SCENE_MAX_BCS; k++) si.motion_factor[k] = f;
    sb_method_bhem.set_step(m->S, &si);
}

/* the eliminated dofs of the centre node per kind, and their values at half
 * the motion (45 degrees about e_z) */
SB_TEST(eliminates_the_named_derivatives)
{
    static const char *const jsons[3] = { PT_SCENE("s"), PT_SCENE("t"), PT_SCENE("st") };
    static const int n_con[3] = { 6, 6, 9 };
    for (int w = 0; w < 3; w++) {
        tb_method m;
        int rc = tb_create(&m, jsons[w], 4, 1, NULL);
        CHECK_EQ_INT(rc, SB_OK);
        if (rc) continue;
        const bhem_level *L = &m.S->lv[0];
        CHECK_EQ_INT(L->n_con, n_con[w]);
        set_motion(&m, 0.5);
        const sb_dirichlet *D = sb_method_bhem.dirichlet(m.S, 0);
        int node = bhem_node_at(m.S, L, 2, 2), seen[4] = { 0 };
        double xs[3] = { 0 }, xt[3] = { 0 };
        for (int k = 0; k < D->n; k++) {
            int d = D->dofs[k], kind = (d % 12) / 3;
            CHECK_EQ_INT(d / 12, node);
            seen[kind]++;
            if (kind == 0) CHECK_NEAR(D->values[k], 0.0, 1e-15);   /* the centre of the rotation */
            if (kind == 1) xs[d % 3] = D->values[k];
            if (kind == 2) xt[d % 3] = D->values[k];
        }
        unsigned want = (unsigned)w + 1u;
        CHECK_EQ_INT(seen[0], 3);
        CHECK_EQ_INT(seen[1], (want & 1u) ? 3 : 0);
        CHECK_EQ_INT(seen[2], (want & 2u) ? 3 : 0);
        CHECK_EQ_INT(seen[3], 0);                                    /* the mixed derivative stays free */
        double c = cos(M_PI / 4) * 0.25;                             /* patch-scaled: h = 1/4 */
        if (want & 1u) { CHECK_NEAR(xs[0], c, 1e-15); CHECK_NEAR(xs[1], c, 1e-15); CHECK_NEAR(xs[2], 0.0, 1e-15); }
        if (want & 2u) { CHECK_NEAR(xt[0], -c, 1e-15); CHECK_NEAR(xt[1], c, 1e-15); CHECK_NEAR(xt[2], 0.0, 1e-15); }
        tb_free(&m);
    }
}

/* the tip probe's displacement from a run's JSON summary */
static int tip_displacement(const char *json, double u[3])
{
    const char *p = strstr(json, "\"tip\"");
    if (!p || !(p = strstr(p, "\"displacement\"")) || !(p = strchr(p, '['))) return -1;
    return sscanf(p, "[ %lf , %lf , %lf", &u[0], &u[1], &u[2]) == 3 ? 0 : -1;
}

static char out[1 << 16], err[8192];

/* known minimizer: the rigid rotation by 30 degrees about e_y through the
 * origin carries the tip (1, 0.1, 0) to (cos 30, 0.1, -sin 30) */
SB_TEST(strip_turns_rigidly)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    int rc = sb_sh(out, sizeof out, err, sizeof err,
                   "cd %s && %s run --scene tests/scenes/derivative_strip.json --method bhem --solver lsnewton "
                   "--out none --summary json --quiet", root, bin);
    CHECK_MSG(rc == 0, "exit %d: %s", rc, err);
    double u[3];
    CHECK(tip_displacement(out, u) == 0);
    const double a = M_PI / 6;
    CHECK_NEAR(u[0], cos(a) - 1.0, 1e-8);
    CHECK_NEAR(u[1], 0.0, 1e-8);
    CHECK_NEAR(u[2], -sin(a), 1e-8);
    CHECK(strstr(out, "\"converged\"") != NULL);
    /* the minimizer is rigid: zero energy at the end */
    const char *f = strstr(out, "\"f\":");
    double fv = 1.0;
    CHECK(f && sscanf(f + 4, " %lf", &fv) == 1 && fabs(fv) < 1e-12);
}

/* every other method: exit 2 before any work (no record written), the
 * sentence names the key and the method; a sweep leaves the pair out */
SB_TEST(other_methods_refuse)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    static const char *const methods[] = { "linear_fem", "rmtr", "adaptive_sqrt3" };
    char rec[128];
    snprintf(rec, sizeof rec, "/tmp/sb_deriv_refused_%d.h5", (int)getpid());
    for (int i = 0; i < 3; i++) {
        unlink(rec);
        int rc = sb_sh(out, sizeof out, err, sizeof err,
                       "cd %s && %s run --scene tests/scenes/derivative_strip.json --method %s --solver linearized "
                       "--out %s --quiet", root, bin, methods[i], rec);
        CHECK_EQ_INT(rc, 2);
        CHECK_MSG(strstr(err, "\"derivative\"") && strstr(err, methods[i]) && strstr(err, "derivative_strip.json"),
                  "%s", err);
        struct stat st;
        CHECK(stat(rec, &st) != 0);
    }
    unlink(rec);
    char dir[128];
    snprintf(dir, sizeof dir, "/tmp/sb_deriv_sweep_%d", (int)getpid());
    int rc = sb_sh(out, sizeof out, err, sizeof err,
                   "cd %s && %s sweep --scenes tests/scenes/derivative_strip.json --methods bhem,linear_fem "
                   "--solvers lsnewton --res 4 --dir %s; e=$?; rm -rf %s; exit $e", root, bin, dir, dir);
    CHECK_MSG(rc == 0, "exit %d: %s %s", rc, out, err);
    CHECK_MSG(strstr(err, "left out") && strstr(err, "linear_fem") && strstr(err, "\"derivative\""), "%s", err);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(eliminates_the_named_derivatives), SB_CASE(strip_turns_rigidly), SB_CASE(other_methods_refuse), SB_END
    };
    return sb_test_main(argc, argv, cases);
}
