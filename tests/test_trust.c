/* test_trust.c — issue 27, "no silent wrong answers": every defect the issue
 * reproduced on the landed main, as a regression test that fails on the old
 * code (docs/trust.md).  Runs go through sb_run_execute, the path of
 * `shellbench run`. */
#include "sb_test.h"
#include "run_json.h"
#include "sb_record.h"
#include "sb_record_io.h"
#include "sb_method.h"
#include "sb_context.h"
#include "../methods/rmtr/cc_method.h"

#include <jansson.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[64];

typedef struct outcome {
    int code;
    json_t *summary;      /* NULL when the run wrote none */
    char *err;            /* everything the run wrote to stderr */
} outcome;

static void outcome_free(outcome *o)
{
    json_decref(o->summary);
    free(o->err);
    memset(o, 0, sizeof *o);
}

/* One run of SCENE (a path, or relative to the repository root) with up to 8
 * --set assignments (NULL-terminated); out: record path or NULL (none). */
static outcome run_full(const char *scene, const char *method, const char *solver, int res, int levels,
                        const char *out, int resume, int strict, const char *const *sets)
{
    char path[1024];
    if (scene[0] == '/') snprintf(path, sizeof path, "%s", scene);
    else snprintf(path, sizeof path, "%s/%s", sb_test_root(), scene);
    int n = 0;
    while (sets && sets[n]) n++;
    sb_run_request req;
    memset(&req, 0, sizeof req);
    req.scene = path;
    req.method = method;
    req.solver = solver;
    req.res = res;
    req.levels = levels;
    req.out = out ? out : "none";
    req.quiet = 1;
    req.resume = resume;
    req.strict = strict;
    req.n_sets = n;
    req.sets = sets;
    outcome o = { 0, NULL, NULL };
    size_t len = 0;
    FILE *err = open_memstream(&o.err, &len);
    FILE *devnull = fopen("/dev/null", "w");
    char *js = NULL;
    o.code = sb_run_execute(&req, devnull ? devnull : stdout, err ? err : stderr, &js);
    if (devnull) fclose(devnull);
    if (err) fclose(err);
    json_error_t e;
    o.summary = js ? json_loads(js, 0, &e) : NULL;
    free(js);
    if (!o.err) o.err = calloc(1, 1);
    return o;
}

static outcome run1(const char *scene, const char *method, const char *solver, int res, const char *const *sets)
{
    return run_full(scene, method, solver, res, 1, NULL, 0, 0, sets);
}

static const char *str(json_t *o, const char *k)
{
    const char *s = json_string_value(json_object_get(o, k));
    return s ? s : "(none)";
}

static double num(json_t *o, const char *k)
{
    json_t *v = json_object_get(o, k);
    return v && json_is_number(v) ? json_number_value(v) : NAN;
}

static json_t *probe(json_t *o, const char *name) { return json_object_get(json_object_get(o, "probes"), name); }

static double disp(json_t *o, const char *name, int k)
{
    return json_number_value(json_array_get(json_object_get(probe(o, name), "displacement"), k));
}

/* ---- item 4: scale-aware stopping ------------------------------------- */

/* A linear scene of another scale: on main `tr` stopped as "stalled" after
 * 12 iterations (bhem) or ran 2,000+ (rmtr with a stiff penalty) while
 * lsnewton took 2-3; now both stop at the limiting accuracy within a few. */
SB_TEST(linear_scene_converges_in_a_few_iterations)
{
    const char *methods[] = { "bhem", "rmtr" };
    for (int m = 0; m < 2; m++) {
        for (int s = 0; s < 2; s++) {
            const char *solver = s ? "tr" : "lsnewton";
            outcome o = run1("tests/scenes/plate_10m.json", methods[m], solver, 8, NULL);
            CHECK_MSG(o.code == 0 && o.summary, "%s/%s: exit %d %s", methods[m], solver, o.code, o.err);
            if (o.summary) {
                CHECK_MSG(num(o.summary, "iterations") <= 4, "%s/%s: %g iterations (%s)", methods[m], solver,
                          num(o.summary, "iterations"), str(o.summary, "reason"));
                CHECK_MSG(strcmp(str(o.summary, "validation"), "passed") == 0, "%s/%s: validation %s",
                          methods[m], solver, str(o.summary, "validation"));
            }
            outcome_free(&o);
        }
    }
    /* the paper's rule keeps its meaning for the reproductions: there the
     * absolute gtol is below the round-off floor of this scene's ||g|| */
    static const char *const paper[] = { "run.stop=paper", NULL };
    outcome o = run1("tests/scenes/plate_10m.json", "bhem", "tr", 8, paper);
    CHECK_MSG(o.code == 1 && !strcmp(str(o.summary, "reason"), "stalled"), "paper rule: exit %d, %s", o.code,
              str(o.summary, "reason"));
    outcome_free(&o);
}

/* The relative gradient test must not accept a non-physical state: from a
 * start perturbed by 1e3 m main reported "converged (grad_tol)" with
 * ||g|| = 1.8e7 (gtol_rel ||g_0||, ||g_0|| ~ 1e16). */
SB_TEST(relative_gradient_test_bounded)
{
    static const char *const scaled[] = { "run.perturb=1e3", NULL };
    static const char *const paper[] = { "run.perturb=1e3", "run.stop=paper", NULL };
    outcome ref = run1("bench/scenes/plate_clamped.json", "bhem", "tr", 4, NULL);
    CHECK(ref.code == 0 && ref.summary);
    for (int k = 0; k < 2; k++) {
        outcome o = run1("bench/scenes/plate_clamped.json", "bhem", "tr", 4, k ? paper : scaled);
        CHECK(o.summary != NULL);
        if (o.summary && ref.summary) {
            if (o.code == 0)   /* converged: then to the solution */
                CHECK_MSG(fabs(disp(o.summary, "center", 2) / disp(ref.summary, "center", 2) - 1) < 1e-6,
                          "%s: converged (%s) at w = %g, not the solution %g", k ? "paper" : "scaled",
                          str(o.summary, "reason"), disp(o.summary, "center", 2), disp(ref.summary, "center", 2));
            else
                CHECK_MSG(!strcmp(str(o.summary, "reason"), "strain_bound"), "%s: %s", k ? "paper" : "scaled",
                          str(o.summary, "reason"));
        }
        outcome_free(&o);
    }
    outcome_free(&ref);
}

/* Pressure 1e308: main recorded line_search_failed with ||g|| = inf. */
SB_TEST(nonfinite_state_is_nonfinite)
{
    const char *solvers[] = { "lsnewton", "tr" };
    for (int s = 0; s < 2; s++) {
        outcome o = run1("tests/scenes/pressure_1e308.json", "bhem", solvers[s], 4, NULL);
        CHECK_MSG(o.code == 1 && !strcmp(str(o.summary, "reason"), "nonfinite"), "%s: exit %d, %s", solvers[s],
                  o.code, str(o.summary, "reason"));
        outcome_free(&o);
    }
}

/* ---- item 5: the linearized solver's single step, judged ---------------- */
SB_TEST(linearized_step_is_judged)
{
    const char *bad[] = { "tests/scenes/membrane_gravity_1e6.json", "tests/scenes/membrane_dt_1e6.json" };
    const char *methods[] = { "bhem", "rmtr" };
    for (int m = 0; m < 2; m++) {
        for (int k = 0; k < 2; k++) {
            outcome o = run1(bad[k], methods[m], "linearized", 4, NULL);
            CHECK_MSG(o.code == 1 && o.summary && strcmp(str(o.summary, "status"), "converged") != 0,
                      "%s on %s: exit %d, %s (f = %g)", methods[m], bad[k], o.code, str(o.summary, "reason"),
                      num(o.summary, "f"));
            outcome_free(&o);
        }
        /* (rmtr at 8 x 8: at 4 x 4 its penalty leaves this soft sheet's edges 10 % of the sag) */
        outcome o = run1("tests/scenes/membrane_dt_small.json", methods[m], "linearized", m ? 8 : 4, NULL);
        CHECK_MSG(o.code == 0 && !strcmp(str(o.summary, "reason"), "single_step"), "%s small dt: exit %d, %s",
                  methods[m], o.code, str(o.summary, "reason"));
        outcome_free(&o);
    }
}

/* ---- item 3: the rmtr penalty ------------------------------------------ */

/* On the RMTR paper's four scenes the scaled rule gives the paper's beta
 * bit for bit on every level, so the committed reproductions keep their
 * meaning. */
SB_TEST(penalty_beta_is_the_papers_on_its_cloth)
{
    const char *scenes[] = { "trampoline", "drooping", "reentrant_corner", "drape" };
    const sb_method_type *mt = sb_method_find("rmtr");
    CHECK(mt != NULL);
    if (!mt) return;
    for (int s = 0; s < 4; s++) {
        char path[1024], err[1024];
        snprintf(path, sizeof path, "%s/bench/scenes/%s.json", sb_test_root(), scenes[s]);
        sb_scene sc;
        CHECK_MSG(sb_scene_load(path, &sc, err, sizeof err) == SB_OK, "%s", err);
        double beta[2][3];
        for (int rule = 0; rule < 2; rule++) {
            sb_context ctx;
            sb_context_init(&ctx);
            sb_paramset_add(&ctx.params, "method", mt->params);
            CHECK(sb_paramset_set(&ctx.params, rule ? "method.beta_rule=paper" : "method.beta_rule=scaled", err,
                                  sizeof err) == SB_OK);
            cc_state *S = calloc(1, mt->state_size);
            sb_method_config cfg = { 16, 3, &ctx.params, &ctx, 0 };
            CHECK_MSG(mt->create(S, &sc, &cfg) == SB_OK, "%s: %s", scenes[s], ctx.err);
            for (int l = 0; l < 3; l++) beta[rule][l] = S->lv[l].beta;
            CHECK(rule == 1 || S->beta_factor == 1.0);
            mt->destroy(S);
            free(S);
            sb_context_free(&ctx);
        }
        CHECK_MSG(memcmp(beta[0], beta[1], sizeof beta[0]) == 0, "%s: scaled beta %.17g, paper %.17g", scenes[s],
                  beta[0][2], beta[1][2]);
        if (s == 0) CHECK_EQ_INT(beta[1][2], 1048576);   /* 16^5: the square's h = 1/16 */
        sb_scene_free(&sc);
    }
}

/* A 10 m steel plate and a 10 m cantilever: with the paper's h^-5 main
 * answered 762 m (plate) and a strip hanging straight down (cantilever),
 * "converged".  The scaled beta solves them; the paper's rule is now
 * reported as penalty_violated. */
SB_TEST(penalty_scale_aware_and_violation_recorded)
{
    const char *scenes[] = { "tests/scenes/plate_10m.json", "tests/scenes/cantilever_10m.json" };
    const char *probes[] = { "center", "tip" };
    static const char *const paper[] = { "method.beta_rule=paper", NULL };
    for (int s = 0; s < 2; s++) {
        outcome o = run1(scenes[s], "rmtr", "lsnewton", 8, NULL);
        CHECK_MSG(o.code == 0 && !strcmp(str(o.summary, "validation"), "passed"), "%s: exit %d, %s, validation %s",
                  scenes[s], o.code, str(o.summary, "reason"), str(o.summary, "validation"));
        json_t *pe = json_object_get(o.summary, "penalty");
        CHECK(pe && num(pe, "relative") < 0.05 && num(pe, "beta") > 1e8);
        outcome_free(&o);
        o = run1(scenes[s], "rmtr", "lsnewton", 8, paper);
        CHECK_MSG(o.code == 1 && !strcmp(str(o.summary, "reason"), "penalty_violated"), "%s (paper beta): exit %d, %s",
                  scenes[s], o.code, str(o.summary, "reason"));
        if (o.summary) {
            CHECK(num(json_object_get(o.summary, "penalty"), "relative") > 0.5);
            CHECK(fabs(json_number_value(json_object_get(probe(o.summary, probes[s]), "rel_error"))) > 10);
        }
        outcome_free(&o);
    }
    /* dimensionally consistent: the 10 m steel plate is the 1 m plate scaled, and
     * so are its penalty and the relative violation */
    outcome a = run1("bench/scenes/plate_clamped.json", "rmtr", "lsnewton", 8, NULL);
    outcome b = run1("tests/scenes/plate_10m.json", "rmtr", "lsnewton", 8, NULL);
    if (a.summary && b.summary) {
        CHECK_REL(num(json_object_get(a.summary, "penalty"), "relative"),
                  num(json_object_get(b.summary, "penalty"), "relative"), 1e-3);
        CHECK_REL(json_number_value(json_object_get(probe(a.summary, "center"), "signed_error")) + 1,
                  json_number_value(json_object_get(probe(b.summary, "center"), "signed_error")) + 1, 1e-4);
    }
    outcome_free(&a);
    outcome_free(&b);
}

/* ---- item 6: validation ------------------------------------------------- */
SB_TEST(validation_recorded_and_strict)
{
    /* main: rel_error 0.0246 against tol 0.01 and nothing said (the paper's
     * beta on the clamped plate at 8 x 8) */
    static const char *const paper[] = { "method.beta_rule=paper", NULL };
    char rec[256];
    snprintf(rec, sizeof rec, "%s/val.h5", tmpdir);
    outcome o = run_full("bench/scenes/plate_clamped.json", "rmtr", "tr", 8, 1, rec, 0, 0, paper);
    CHECK(o.summary != NULL);
    if (o.summary) {
        json_t *c = probe(o.summary, "center");
        CHECK(!strcmp(str(o.summary, "validation"), "failed"));
        CHECK(json_is_false(json_object_get(c, "passed")));
        CHECK(num(c, "signed_error") > 0.01);   /* too soft: the deflection is too large */
        CHECK_EQ_INT(json_array_size(json_object_get(c, "checks")), 1);
    }
    sb_record_summary s;
    char err[1024];
    CHECK_MSG(sb_record_read_summary(rec, &s, err, sizeof err) == SB_OK, "%s", err);
    CHECK(strcmp(s.validation, "failed") == 0);
    sb_record_summary_free(&s);
    outcome_free(&o);
    /* converged but out of tolerance (2 x 2 patches): exit 0, with --strict 5 */
    for (int strict = 0; strict < 2; strict++) {
        o = run_full("bench/scenes/plate_clamped.json", "bhem", "tr", 2, 1, NULL, 0, strict, NULL);
        CHECK_MSG(o.code == (strict ? SB_EXIT_VALIDATION : 0), "strict %d: exit %d", strict, o.code);
        CHECK(!strcmp(str(o.summary, "status"), "converged") && !strcmp(str(o.summary, "validation"), "failed"));
        outcome_free(&o);
    }
    /* several components per probe, each judged */
    o = run1("tests/scenes/cantilever_10m.json", "bhem", "lsnewton", 8, NULL);
    json_t *checks = json_object_get(probe(o.summary, "tip"), "checks");
    CHECK_EQ_INT(json_array_size(checks), 2);
    CHECK(!strcmp(str(json_array_get(checks, 1), "component"), "norm"));
    CHECK(json_is_true(json_object_get(json_array_get(checks, 1), "passed")));
    outcome_free(&o);
}

/* ---- item 7: checksums --------------------------------------------------- */

/* CRC-64/XZ check value (the "123456789" test vector) */
SB_TEST(crc64_check_value)
{
    CHECK(sb_crc64(0, "123456789", 9) == 0x995DC9BBDF1939FAull);
    CHECK(sb_crc64(sb_crc64(0, "1234", 4), "56789", 5) == 0x995DC9BBDF1939FAull);
}

static int copy_file(const char *from, const char *to, long flip_at, int flip_bit, const unsigned char *bytes, int nb)
{
    FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
    if (!a || !b) { if (a) fclose(a); if (b) fclose(b); return -1; }
    long i = 0;
    int c;
    while ((c = fgetc(a)) != EOF) {
        if (flip_at >= 0 && i == flip_at && nb == 0) c ^= 1 << flip_bit;
        if (flip_at >= 0 && i >= flip_at && i < flip_at + nb) c = bytes[i - flip_at];
        fputc(c, b);
        i++;
    }
    fclose(a);
    return fclose(b);
}

/* A killed run's checkpoint with random bit flips: on main 12 of 16 copies
 * resumed, 4 to a different state, one (2 bytes changed in /resume/x) to
 * f = 2.2e62 "converged".  Now every altered copy is refused (exit 2, a
 * sentence naming the checksum) before any work; the intact one resumes. */
SB_TEST(altered_checkpoint_refused)
{
    static const char *const sets[] = { "run.checkpoint=0", NULL };
    char out[256], partial[300];
    snprintf(out, sizeof out, "%s/ck.h5", tmpdir);
    snprintf(partial, sizeof partial, "%s.partial", out);
    outcome o = run_full("tests/scenes/membrane_dynamic.json", "fixture_membrane", "tr", 8, 1, out, 0, 0, sets);
    CHECK_EQ_INT(o.code, 0);
    outcome_free(&o);
    /* a checkpoint after step 1 of 3 */
    sb_run_request dummy;
    (void)dummy;
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd %s && %s run --scene tests/scenes/membrane_dynamic.json --method fixture_membrane "
             "--solver tr --res 8 --out %s/ck2.h5 --stop-after-steps 1 --quiet 2>/dev/null", sb_test_root(),
             sb_test_bin(), tmpdir);
    CHECK_EQ_INT(WEXITSTATUS(system(cmd)), 4);
    char src[300];
    snprintf(src, sizeof src, "%s/ck2.h5.partial", tmpdir);
    struct stat st;
    CHECK(stat(src, &st) == 0);
    /* /resume/x's bytes in the file */
    long xoff = -1, xlen = 0;
    {
        hid_t f = H5Fopen(src, H5F_ACC_RDONLY, H5P_DEFAULT);
        hid_t d = f < 0 ? -1 : H5Dopen2(f, "/resume/x", H5P_DEFAULT);
        if (d >= 0) {
            xoff = (long)H5Dget_offset(d);
            xlen = (long)H5Dget_storage_size(d);
            H5Dclose(d);
        }
        if (f >= 0) H5Fclose(f);
    }
    CHECK(xoff > SB_RECORD_USERBLOCK && xlen > 8);
    unsigned long long z = 27;
    int refused = 0, copies = 0;
    for (int k = 0; k < 20 && st.st_size > 0; k++) {
        z = z * 6364136223846793005ull + 1442695040888963407ull;   /* a fixed LCG: reproducible flips */
        long at;
        int nb = 0;
        unsigned char two[2];
        if (k < 16) {
            at = SB_RECORD_USERBLOCK + (long)((z >> 17) % (unsigned long long)(st.st_size - SB_RECORD_USERBLOCK));
        } else {
            /* the worst case: 2 bytes changed in /resume/x */
            at = xoff + (long)((z >> 17) % (unsigned long long)(xlen - 2));
            two[0] = (unsigned char)(z >> 40);
            two[1] = (unsigned char)(z >> 48);
            nb = 2;
        }
        char dst[400], rec[300];
        snprintf(rec, sizeof rec, "%s/flip%d.h5", tmpdir, k);
        snprintf(dst, sizeof dst, "%s.partial", rec);
        CHECK(copy_file(src, dst, at, (int)((z >> 9) % 8), two, nb) == 0);
        outcome r = run_full("tests/scenes/membrane_dynamic.json", "fixture_membrane", "tr", 8, 1, rec, 1, 0, NULL);
        copies++;
        int ok = r.code == 2 && strstr(r.err, "checksum") != NULL && access(rec, F_OK) != 0;
        refused += ok;
        CHECK_MSG(ok, "copy %d (byte %ld): exit %d, %s", k, at, r.code, r.err);
        outcome_free(&r);
    }
    CHECK_EQ_INT(refused, copies);
    /* the intact checkpoint resumes to the uninterrupted run's state */
    outcome r = run_full("tests/scenes/membrane_dynamic.json", "fixture_membrane", "tr", 8, 1, NULL, 0, 0, NULL);
    snprintf(cmd, sizeof cmd, "%s/ck2.h5", tmpdir);
    outcome q = run_full("tests/scenes/membrane_dynamic.json", "fixture_membrane", "tr", 8, 1, cmd, 1, 0, NULL);
    CHECK_MSG(q.code == 0 && r.summary && q.summary && num(r.summary, "f") == num(q.summary, "f"),
              "resume: exit %d %s", q.code, q.err);
    outcome_free(&r);
    outcome_free(&q);
}

/* ---- item 2: a closed annulus whose seam edges carry conditions -------- */

/* A clamp on `start` and a load on `end` of a 360-degree annulus: main
 * merged the two edges, put the load on the clamp and reported converged
 * with zero displacement.  The seam now stays open (a slit): the result is
 * the limit of a 359.9-degree sector's. */
SB_TEST(slit_annulus_keeps_its_slit)
{
    outcome a = run1("tests/scenes/annulus_slit.json", "bhem", "lsnewton", 8, NULL);
    outcome b = run1("tests/scenes/annulus_open.json", "bhem", "lsnewton", 8, NULL);
    CHECK(a.code == 0 && b.code == 0 && a.summary && b.summary);
    if (a.summary && b.summary) {
        CHECK_MSG(disp(a.summary, "end_mid", 2) > 0.01, "slit annulus: w = %g", disp(a.summary, "end_mid", 2));
        CHECK_REL(disp(a.summary, "end_mid", 2), disp(b.summary, "end_mid", 2), 1e-3);
        CHECK(strstr(str(a.summary, "method_info"), "slit") != NULL);
    }
    outcome_free(&a);
    outcome_free(&b);
}

/* ---- item 8: reference files --------------------------------------------- */

/* a copy of bench/scenes/plate_clamped.json with reference {type: file, file: FILE} */
static void ref_scene(const char *scene_path, const char *file)
{
    char src[1024], err[1024];
    snprintf(src, sizeof src, "%s/bench/scenes/plate_clamped.json", sb_test_root());
    json_error_t e;
    json_t *o = json_load_file(src, 0, &e);
    json_object_set_new(o, "reference", json_pack("{s:s, s:s}", "type", "file", "file", file));
    json_dump_file(o, scene_path, JSON_INDENT(1));
    json_decref(o);
    (void)err;
}

/* `check` and the run refuse, before any work, a reference that is missing,
 * a directory, /dev/zero, a JSON file, a record of another scene or of
 * another sample grid, an unfinished checkpoint or a run that did not
 * converge; main accepted them (check) and only warned at the end. */
SB_TEST(reference_file_validated)
{
    char good[256], other[256], grid[256], notconv[256], part[256], cmd[2048];
    snprintf(good, sizeof good, "%s/ref_good.h5", tmpdir);
    snprintf(other, sizeof other, "%s/ref_other.h5", tmpdir);
    snprintf(grid, sizeof grid, "%s/ref_grid.h5", tmpdir);
    snprintf(notconv, sizeof notconv, "%s/ref_notconv.h5", tmpdir);
    snprintf(part, sizeof part, "%s/ref_part.h5", tmpdir);
    static const char *const one_iter[] = { "run.max_iter=1", NULL };
    outcome o = run_full("bench/scenes/plate_clamped.json", "bhem", "lsnewton", 4, 1, good, 0, 0, NULL);
    CHECK_EQ_INT(o.code, 0);
    outcome_free(&o);
    o = run_full("bench/scenes/plate_simply_supported.json", "bhem", "lsnewton", 2, 1, other, 0, 0, NULL);
    outcome_free(&o);
    o = run_full("bench/scenes/plate_clamped.json", "bhem", "lsnewton", 2, 1, notconv, 0, 0, one_iter);
    CHECK_EQ_INT(o.code, 1);
    outcome_free(&o);
    snprintf(cmd, sizeof cmd, "cd %s && %s run --scene bench/scenes/plate_clamped.json --method bhem --solver lsnewton "
             "--res 4 --samples 11 --out %s --quiet 2>/dev/null && %s run --scene tests/scenes/membrane_dynamic.json "
             "--method fixture_membrane --solver tr --res 4 --out %s --stop-after-steps 1 --quiet 2>/dev/null",
             sb_test_root(), sb_test_bin(), grid, sb_test_bin(), part);
    CHECK_EQ_INT(WEXITSTATUS(system(cmd)), 4);
    char partial[300];
    snprintf(partial, sizeof partial, "%s.partial", part);
    const struct { const char *file, *says; } bad[] = {
        { "missing.h5", "No such file" },
        { "/tmp", "not a regular file" },
        { "/dev/zero", "not a regular file" },
        { "PLATE_JSON", "not an HDF5 file" },
        { other, "another scene" },
        { grid, "sample grid" },
        { partial, "unfinished" },
        { notconv, "did not converge" },
    };
    char plate_json[1024];
    snprintf(plate_json, sizeof plate_json, "%s/bench/scenes/plate_clamped.json", sb_test_root());
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        char scene[256];
        snprintf(scene, sizeof scene, "%s/refscene%zu.json", tmpdir, k);
        ref_scene(scene, strcmp(bad[k].file, "PLATE_JSON") ? bad[k].file : plate_json);
        /* check: exit 2 with a sentence (the grid is only known at run time) */
        static char text[4096];
        snprintf(cmd, sizeof cmd, "%s check %s 2>&1", sb_test_bin(), scene);
        FILE *pp = popen(cmd, "r");
        size_t got = pp ? fread(text, 1, sizeof text - 1, pp) : 0;
        text[got] = 0;
        int rc = pp ? WEXITSTATUS(pclose(pp)) : -1;
        if (strcmp(bad[k].says, "sample grid") != 0)
            CHECK_MSG(rc == 2 && strstr(text, bad[k].says), "check of reference %s: exit %d, %s", bad[k].file, rc, text);
        /* the run: exit 2 before any work, the sentence on stderr */
        o = run1(scene, "bhem", "lsnewton", 4, NULL);
        CHECK_MSG(o.code == 2 && o.summary == NULL && strstr(o.err, bad[k].says), "run against reference %s: exit %d, %s",
                  bad[k].file, o.code, o.err);
        outcome_free(&o);
    }
    /* a good reference: accepted, and the error computed against it */
    char scene[256];
    snprintf(scene, sizeof scene, "%s/refgood.json", tmpdir);
    ref_scene(scene, good);
    o = run1(scene, "bhem", "lsnewton", 2, NULL);
    CHECK_MSG(o.code == 0 && !strcmp(str(json_object_get(o.summary, "error"), "kind"), "field"), "good reference: %d %s",
              o.code, o.err);
    outcome_free(&o);
}

/* ---- --res NxM ----------------------------------------------------------- */

/* rmtr took square resolutions only; a strip needs N x M for every method,
 * recorded in the record and summary, and a scene may say "resolution": [N, M]. */
SB_TEST(res_n_by_m_for_every_method)
{
    const char *methods[] = { "bhem", "rmtr" };
    char rec[256];
    for (int m = 0; m < 2; m++) {
        snprintf(rec, sizeof rec, "%s/res_%s.h5", tmpdir, methods[m]);
        sb_run_request req;
        memset(&req, 0, sizeof req);
        char scene[1024];
        snprintf(scene, sizeof scene, "%s/tests/scenes/cantilever_10m.json", sb_test_root());
        req.scene = scene;
        req.method = methods[m];
        req.solver = "lsnewton";
        CHECK(sb_run_parse_res("16x4", &req.res, &req.res_t) == 0 && req.res == 16 && req.res_t == 4);
        req.out = rec;
        req.quiet = 1;
        int code;
        json_t *o = sb_test_run_json(&req, &code);
        CHECK_MSG(code == 0 && o && num(o, "res") == 16 && num(o, "res_t") == 4 &&
                  strstr(str(o, "method_info"), "16x4") && !strcmp(str(o, "validation"), "passed"),
                  "%s: exit %d, %s", methods[m], code, str(o, "method_info"));
        json_decref(o);
        sb_record_setup su;
        char err[1024];
        CHECK_MSG(sb_record_read_setup(rec, &su, err, sizeof err) == SB_OK, "%s", err);
        CHECK(su.res == 16 && su.res_t == 4);
        sb_record_setup_free(&su);
    }
    int r, t;
    CHECK(sb_run_parse_res("8", &r, &t) == 0 && r == 8 && t == 0);
    CHECK(sb_run_parse_res("8x8", &r, &t) == 0 && r == 8 && t == 0);
    CHECK(sb_run_parse_res("32\xC3\x97" "2", &r, &t) == 0 && r == 32 && t == 2);
    CHECK(sb_run_parse_res("8x0", &r, &t) != 0 && sb_run_parse_res("x4", &r, &t) != 0 &&
          sb_run_parse_res("8x4x2", &r, &t) != 0 && sb_run_parse_res("-8", &r, &t) != 0);
    /* a method that cannot: refused before any work */
    static const char *const none[] = { NULL };
    sb_run_request req;
    memset(&req, 0, sizeof req);
    char scene[1024];
    snprintf(scene, sizeof scene, "%s/tests/scenes/membrane_dynamic.json", sb_test_root());
    req.scene = scene;
    req.method = "fixture_membrane";
    req.solver = "tr";
    req.res = 8;
    req.res_t = 4;
    req.out = "none";
    req.quiet = 1;
    req.sets = none;
    int code;
    json_t *o = sb_test_run_json(&req, &code);
    CHECK(code == 2 && o == NULL);
    json_decref(o);
    /* the scene's [N, M]: strip_end_moment's [32, 2] */
    outcome q = run1("bench/scenes/strip_end_moment.json", "bhem", "lsnewton", 0, (const char *const[]){ "run.max_iter=1", NULL });
    CHECK_MSG(q.summary && strstr(str(q.summary, "method_info"), "32x2"), "%s", str(q.summary, "method_info"));
    outcome_free(&q);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_trust_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(linear_scene_converges_in_a_few_iterations),
        SB_CASE(relative_gradient_test_bounded),
        SB_CASE(nonfinite_state_is_nonfinite),
        SB_CASE(linearized_step_is_judged),
        SB_CASE(penalty_beta_is_the_papers_on_its_cloth),
        SB_CASE(penalty_scale_aware_and_violation_recorded),
        SB_CASE(validation_recorded_and_strict),
        SB_CASE(crc64_check_value),
        SB_CASE(altered_checkpoint_refused),
        SB_CASE(slit_annulus_keeps_its_slit),
        SB_CASE(reference_file_validated),
        SB_CASE(res_n_by_m_for_every_method),
        SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
