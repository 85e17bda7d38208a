/* test_adapt.c — meshes that change during a run (sb_method.h adapt,
 * core/problem/sb_run_adapt.c), through exactly the `shellbench run` path
 * with the test fixture fixture_chain (a hanging spring chain that doubles
 * its nodes at every adaptation): events adapt and analyze counted across
 * adaptations, per-step dofs in the record's history, the state continuous
 * through an adaptation (identical to a run without it up to the first
 * one), every single-level solver working, hierarchy solvers and resume
 * refused with a sentence. */
#include "sb_test.h"
#include "run_json.h"
#include "sb_method.h"
#include "sb_solver.h"

#include <hdf5.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static json_t *run_chain(const char *solver, const char *every, const char *out, int resume, int *code)
{
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/chain_adaptive.json", sb_test_root());
    const char *sets[] = { every, NULL };
    sb_run_request rq;
    memset(&rq, 0, sizeof rq);
    rq.scene = scene;
    rq.method = "fixture_chain";
    rq.solver = solver;
    rq.out = out;
    rq.quiet = 1;
    rq.n_sets = 1;
    rq.sets = sets;
    rq.resume = resume;
    return sb_test_run_json(&rq, code);
}

static long count(json_t *o, const char *ev)
{
    return (long)json_integer_value(json_object_get(json_object_get(o, "counts"), ev));
}

static int read_dset(const char *path, const char *name, hid_t type, void *buf, size_t nmax)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) return -1;
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    int rc = -1;
    if (d >= 0) {
        hid_t sp = H5Dget_space(d);
        hssize_t n = H5Sget_simple_extent_npoints(sp);
        if (n > 0 && (size_t)n <= nmax && H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0) rc = (int)n;
        H5Sclose(sp);
        H5Dclose(d);
    }
    H5Fclose(f);
    return rc;
}

SB_TEST(test_adaptive_run)
{
    char pa[256], pb[256];
    snprintf(pa, sizeof pa, "/tmp/sb_test_adapt_a_%d.h5", (int)getpid());
    snprintf(pb, sizeof pb, "/tmp/sb_test_adapt_b_%d.h5", (int)getpid());
    int code = -1;
    json_t *a = run_chain("lsnewton", "method.adapt_every=2", pa, 0, &code);
    CHECK_EQ_INT(code, 0);
    json_t *b = run_chain("lsnewton", "method.adapt_every=0", pb, 0, &code);
    CHECK_EQ_INT(code, 0);
    if (a && b) {
        /* adaptations before steps 3 and 5: 5 -> 9 -> 17 nodes, one analysis per pattern */
        CHECK_EQ_INT(count(a, "adapt"), 2);
        CHECK_EQ_INT(count(a, "analyze"), 3);
        CHECK_EQ_INT(count(b, "adapt"), 0);
        CHECK_EQ_INT(count(b, "analyze"), 1);
        CHECK_EQ_INT(json_integer_value(json_object_get(a, "dofs")), 51);
        int dofs[16] = { 0 };
        CHECK_EQ_INT(read_dset(pa, "/history/steps/dofs", H5T_NATIVE_INT, dofs, 16), 6);
        const int expect[6] = { 15, 15, 27, 27, 51, 51 };
        for (int k = 0; k < 6; k++) CHECK_EQ_INT(dofs[k], expect[k]);
        /* probe trajectories (steps 0..6 x 2 probes x 3): identical up to the
         * first adaptation, different after it (the finer chain sags otherwise) */
        double ta[42], tb[42];
        CHECK_EQ_INT(read_dset(pa, "/probes/trajectory", H5T_NATIVE_DOUBLE, ta, 42), 42);
        CHECK_EQ_INT(read_dset(pb, "/probes/trajectory", H5T_NATIVE_DOUBLE, tb, 42), 42);
        for (int k = 0; k < 3 * 6; k++) CHECK(ta[k] == tb[k]);
        CHECK(fabs(ta[6 * 6] - tb[6 * 6]) > 1e-6);   /* the tip's x: the chain's stretch */
        /* the final state in the record is the final mesh's: its last node is the tip probe */
        double xf[64];
        CHECK_EQ_INT(read_dset(pa, "/final/x", H5T_NATIVE_DOUBLE, xf, 64), 51);
        for (int c = 0; c < 3; c++) CHECK_NEAR(xf[48 + c], ta[6 * 6 + c], 1e-12);
        /* the tip falls and stays finite */
        CHECK(ta[6 * 6 + 2] < -1e-3 && isfinite(ta[6 * 6 + 2]));
    }
    if (a) json_decref(a);
    if (b) json_decref(b);
    /* every single-level solver runs the adaptive method */
    const char *solvers[] = { "tr", "linearized", "damped" };
    for (int k = 0; k < 3; k++) {
        json_t *o = run_chain(solvers[k], "method.adapt_every=2", "none", 0, &code);
        CHECK_MSG(code == 0 || (k == 2 && code == 1), "solver %s: exit %d", solvers[k], code);
        if (o) {
            CHECK_EQ_INT(count(o, "adapt"), 2);
            json_decref(o);
        }
    }
    /* --resume with nothing to resume runs from step 1 (study sweeps ask every
     * run to resume), and gives the uninterrupted run's answer */
    char pc[300], part[320];
    snprintf(pc, sizeof pc, "/tmp/sb_test_adapt_c_%d.h5", (int)getpid());
    json_t *o = run_chain("lsnewton", "method.adapt_every=2", pc, 1, &code);
    CHECK_EQ_INT(code, 0);
    if (o) {
        CHECK_EQ_INT(count(o, "adapt"), 2);
        CHECK_EQ_INT(json_integer_value(json_object_get(o, "dofs")), 51);
        json_decref(o);
    }
    remove(pc);
    /* a checkpoint to continue from is refused before any work (an adaptive
     * run's mesh is not in checkpoints yet) and left as it was */
    snprintf(part, sizeof part, "%s.partial", pc);
    FILE *f = fopen(part, "w");
    CHECK(f && fputs("a checkpoint", f) >= 0);
    if (f) fclose(f);
    o = run_chain("lsnewton", "method.adapt_every=2", pc, 1, &code);
    CHECK_EQ_INT(code, 2);
    if (o) json_decref(o);
    CHECK(access(part, F_OK) == 0 && access(pc, F_OK) != 0);
    remove(part);
    remove(pa);
    remove(pb);
}

SB_TEST(test_hierarchy_solver_refused)
{
    const sb_method_type *mt = sb_method_find("fixture_chain");
    const sb_solver_type *st = sb_solver_find("rmtr");
    CHECK(mt && st);
    if (!mt || !st) return;
    char err[512] = "";
    CHECK(sb_run_combination_check(mt, st, 2, err, sizeof err) == SB_ERR_UNSUPPORTED);
    CHECK_MSG(strstr(err, "rmtr") && strstr(err, "fixture_chain") && strstr(err, "adaptive"), "message: %s", err);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(test_adaptive_run),
        SB_CASE(test_hierarchy_solver_refused),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
