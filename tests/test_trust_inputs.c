/* test_trust_inputs.c — issue 37, items 3, 4, 6 and 11: what a run trusts
 * without looking (docs/trust.md).  Each test failed on the code before
 * its fix:
 *
 *   3  a reference without a checksum was used silently: one flipped
 *      exponent bit in trampoline.h5's /final/sample_pos gave exit 0 and an
 *      error 10x too large.  The bundled references are sealed now; a
 *      damaged one is refused by its checksum, an unsealed one unless
 *      --allow-unsealed-reference says so.
 *   4  --strict was bypassed on resume: `run --resume --strict` on the
 *      finished record of a validation failure exited 0, and so did a
 *      `sweep --strict --resume` that skipped it.
 *   6  --resume ignored an edited OBJ obstacle (exit 0, another result).
 *   11 a reference computed with other obstacles passed `check` and the
 *      start of the run, and the run only warned at its end (exit 0). */
#include "sb_test.h"
#include "cli_sh.h"
#include "run_json.h"
#include "sb_record.h"
#include "sb_record_io.h"
#include "sb_reference.h"

#include <hdf5.h>
#include <jansson.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[64];
static char out_buf[16384], err_buf[16384];

/* `shellbench ARGS` from the repository root; exit status, stdout/stderr in the buffers */
static int sh(const char *args)
{
    return sb_sh(out_buf, sizeof out_buf, err_buf, sizeof err_buf, "cd %s && OPENBLAS_NUM_THREADS=1 %s %s",
                 sb_test_root(), sb_test_bin(), args);
}

static int copy_file(const char *from, const char *to)
{
    FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
    if (!a || !b) {
        if (a) fclose(a);
        if (b) fclose(b);
        return -1;
    }
    char buf[1 << 15];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, a)) > 0) fwrite(buf, 1, n, b);
    fclose(a);
    return fclose(b);
}

/* a copy of the scene file SRC (relative to the root) at DST with its
 * reference set to FILE (NULL: unchanged) and, when steps > 0, its steps */
static json_t *scene_copy(const char *src, const char *dst, const char *file, int steps)
{
    char p[1024];
    snprintf(p, sizeof p, "%s/%s", sb_test_root(), src);
    json_error_t e;
    json_t *o = json_load_file(p, 0, &e);
    if (!o) return NULL;
    if (file) json_object_set_new(o, "reference", json_pack("{s:s, s:s}", "type", "file", "file", file));
    if (steps > 0) json_object_set_new(json_object_get(o, "time"), "steps", json_integer(steps));
    json_dump_file(o, dst, JSON_INDENT(1));
    return o;
}

/* ---- item 3: sealed references ------------------------------------------ */

/* the offset in the file of double `i` of `dset` (contiguous), or -1; *v its value */
static long dset_offset(const char *path, const char *dset, int i, double *v)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) return -1;
    hid_t d = H5Dopen2(f, dset, H5P_DEFAULT);
    haddr_t a = d >= 0 ? H5Dget_offset(d) : HADDR_UNDEF;
    static double buf[3 * 2001 * 2001 / 64];
    hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
    const hssize_t np = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : 0;
    if (sp >= 0) H5Sclose(sp);
    if (d >= 0 && np > i && np <= (hssize_t)(sizeof buf / sizeof *buf) &&
        H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0)
        *v = buf[i];
    if (d >= 0) H5Dclose(d);
    H5Fclose(f);
    /* H5Dget_offset gives the position in the file (the user block included) */
    return a == HADDR_UNDEF ? -1 : (long)a + 8L * i;
}

/* PATH, a sealed record, made a record without a checksum (format version
 * 1): the user block cleared and the version set back, as the bundled
 * references were before issue 37 */
static int unseal(const char *path)
{
    hid_t h = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t a = h >= 0 ? H5Aopen(h, "format_version", H5P_DEFAULT) : -1;
    long one = 1;
    int bad = a < 0 || H5Awrite(a, H5T_NATIVE_LONG, &one) < 0;
    if (a >= 0) H5Aclose(a);
    if (h >= 0) H5Fclose(h);
    FILE *f = fopen(path, "r+b");
    static const char zeros[SB_RECORD_USERBLOCK];
    bad |= !f || fwrite(zeros, 1, sizeof zeros, f) != sizeof zeros;
    if (f) bad |= fclose(f) != 0;
    return bad ? -1 : 0;
}

/* The bundled references carry checksums; a copy of trampoline.h5 with one
 * exponent bit of /final/sample_pos flipped is refused by `check`, at the
 * start of a run and by a study's error, each naming the file; an unsealed
 * copy is refused unless --allow-unsealed-reference. */
SB_TEST(reference_flipped_bit_and_unsealed_refused)
{
    static const char *const refs[] = { "trampoline", "trampoline-check", "drooping", "drooping-check", "drape",
                                        "drape-check", "reentrant_corner", NULL };
    for (int k = 0; refs[k]; k++) {
        char p[512], err[1024];
        int sealed = 0;
        snprintf(p, sizeof p, "%s/results/references/%s.h5", sb_test_root(), refs[k]);
        CHECK_MSG(sb_record_verify(p, &sealed, err, sizeof err) == SB_OK && sealed, "%s: not sealed (%s)", p, err);
    }
    char src[512], flipped[512], unsealed[512], scene[512], cmd[2048];
    snprintf(src, sizeof src, "%s/results/references/trampoline.h5", sb_test_root());
    snprintf(flipped, sizeof flipped, "%s/flipped.h5", tmpdir);
    snprintf(unsealed, sizeof unsealed, "%s/unsealed.h5", tmpdir);
    CHECK(copy_file(src, flipped) == 0 && copy_file(src, unsealed) == 0);
    /* the bit: the highest exponent bit of the x coordinate of sample 1
     * (0.05 m becomes 0.05 * 2^1024) */
    double first = 0;
    long at = dset_offset(flipped, "/final/sample_pos", 3, &first);
    CHECK_MSG(at > 0, "no contiguous /final/sample_pos in %s", flipped);
    if (at <= 0) return;
    FILE *f = fopen(flipped, "r+b");
    unsigned char bytes[8];
    double check_first = 0;
    CHECK(f && fseek(f, at, SEEK_SET) == 0 && fread(bytes, 1, 8, f) == 8);
    memcpy(&check_first, bytes, 8);
    CHECK_MSG(check_first == first, "offset %ld holds %g, the dataset's first value is %g", at, check_first, first);
    bytes[7] ^= 0x40;   /* little endian: byte 7 holds the sign and the top 7 exponent bits */
    CHECK(fseek(f, at, SEEK_SET) == 0 && fwrite(bytes, 1, 8, f) == 8);
    if (f) fclose(f);
    /* as HDF5 reads it: the value changed by orders of magnitude */
    double now = 0;
    dset_offset(flipped, "/final/sample_pos", 3, &now);
    CHECK_MSG(first != 0 && (fabs(now / first) > 1e100 || fabs(now / first) < 1e-100), "%g -> %g", first, now);

    snprintf(scene, sizeof scene, "%s/tramp_flipped.json", tmpdir);
    json_decref(scene_copy("bench/scenes/trampoline.json", scene, flipped, 0));
    snprintf(cmd, sizeof cmd, "check %s", scene);
    int rc = sh(cmd);
    CHECK_MSG(rc == 2 && strstr(err_buf, flipped) && strstr(err_buf, "does not match its checksum"), "check: %d %s", rc,
              err_buf);
    snprintf(cmd, sizeof cmd, "run --scene %s --method bhem --solver lsnewton --res 4 --out none --summary json --quiet",
             scene);
    rc = sh(cmd);
    CHECK_MSG(rc == 2 && !out_buf[0] && strstr(err_buf, flipped) && strstr(err_buf, "does not match its checksum"),
              "run: %d %s", rc, err_buf);
    /* the option does not let a damaged sealed file through */
    snprintf(cmd, sizeof cmd, "check --allow-unsealed-reference %s", scene);
    CHECK_EQ_INT(sh(cmd), 2);
    /* what the end of a run and the study reports read */
    sb_refrec ref;
    char msg[2048];
    double st[2] = { 0, 0 };
    CHECK(sb_refrec_load_opt(flipped, "trampoline", "{}", 1, st, 1, &ref, msg, sizeof msg) != SB_OK &&
          strstr(msg, "checksum"));

    CHECK(unseal(unsealed) == 0);
    snprintf(scene, sizeof scene, "%s/tramp_unsealed.json", tmpdir);
    json_decref(scene_copy("bench/scenes/trampoline.json", scene, unsealed, 0));
    snprintf(cmd, sizeof cmd, "check %s", scene);
    rc = sh(cmd);
    CHECK_MSG(rc == 2 && strstr(err_buf, unsealed) && strstr(err_buf, "carries no checksum") &&
              strstr(err_buf, "--allow-unsealed-reference"), "check unsealed: %d %s", rc, err_buf);
    snprintf(cmd, sizeof cmd, "check --allow-unsealed-reference %s", scene);
    rc = sh(cmd);
    CHECK_MSG(rc == 0, "check --allow-unsealed-reference: %d %s", rc, err_buf);
    snprintf(cmd, sizeof cmd, "run --scene %s --method bhem --solver lsnewton --res 4 --out none --summary json --quiet",
             scene);
    rc = sh(cmd);
    CHECK_MSG(rc == 2 && !out_buf[0] && strstr(err_buf, "carries no checksum"), "run unsealed: %d %s", rc, err_buf);
    snprintf(cmd, sizeof cmd, "run --scene %s --method bhem --solver lsnewton --res 4 --out none --summary json --quiet "
             "--allow-unsealed-reference", scene);
    rc = sh(cmd);
    CHECK_MSG(rc == 0 && strstr(out_buf, "\"kind\": \"field\""), "run --allow-unsealed-reference: %d %s %s", rc,
              out_buf, err_buf);
    CHECK(sb_refrec_load(unsealed, "trampoline", "{}", 1, st, &ref, msg, sizeof msg) != SB_OK &&
          strstr(msg, "carries no checksum"));
}

/* ---- item 4: the recorded verdict on resume ------------------------------ */

/* bhem on the clamped plate at 2 x 2 converges with validation failed: exit
 * 0, with --strict 5.  Resumed or skipped, the record says the same. */
SB_TEST(strict_verdict_read_from_the_record)
{
    char rec[256], dir[256], cmd[2048];
    snprintf(rec, sizeof rec, "%s/strict.h5", tmpdir);
    snprintf(dir, sizeof dir, "%s/strict_sweep", tmpdir);
    const char *run = "run --scene bench/scenes/plate_clamped.json --method bhem --solver tr --res 2 --quiet";
    snprintf(cmd, sizeof cmd, "%s --out %s --strict", run, rec);
    CHECK_EQ_INT(sh(cmd), 5);
    snprintf(cmd, sizeof cmd, "%s --out %s --resume --strict", run, rec);
    int rc = sh(cmd);
    CHECK_MSG(rc == 5, "run --resume --strict on the finished record: exit %d (%s)", rc, err_buf);
    snprintf(cmd, sizeof cmd, "%s --out %s --resume", run, rec);
    CHECK_EQ_INT(sh(cmd), 0);
    const char *sweep = "sweep --scenes bench/scenes/plate_clamped.json --methods bhem --solvers tr --res 2";
    snprintf(cmd, sizeof cmd, "%s --dir %s --strict", sweep, dir);
    CHECK_EQ_INT(sh(cmd), 5);
    snprintf(cmd, sizeof cmd, "%s --dir %s --strict --resume", sweep, dir);
    rc = sh(cmd);
    CHECK_MSG(rc == 5 && strstr(out_buf, "skipped (recorded: converged, validation failed)"),
              "sweep --strict --resume: exit %d, %s", rc, out_buf);
    snprintf(cmd, sizeof cmd, "%s --dir %s --resume", sweep, dir);
    CHECK_EQ_INT(sh(cmd), 0);
}

/* ---- item 6: obstacle meshes in the resume identity ---------------------- */

/* the mesh-obstacle scene (cloth on a cube from an OBJ file) copied into
 * DIR with `steps` steps; returns the scene path in buf */
static void mesh_scene(const char *dir, int steps, char *buf, size_t len)
{
    char p[512], obj[512];
    mkdir(dir, 0755);
    snprintf(buf, len, "%s/cloth_mesh.json", dir);
    json_decref(scene_copy("tests/scenes/contact/cloth_mesh_impulse.json", buf, NULL, steps));
    snprintf(p, sizeof p, "%s/tests/scenes/contact/box_top.obj", sb_test_root());
    snprintf(obj, sizeof obj, "%s/box_top.obj", dir);
    copy_file(p, obj);
}

/* the cube's top face 5 cm lower */
static void edit_obj(const char *dir)
{
    char obj[512], cmd[1024];
    snprintf(obj, sizeof obj, "%s/box_top.obj", dir);
    snprintf(cmd, sizeof cmd, "sed -i 's/ -0\\.1$/ -0.15/' %s", obj);
    if (system(cmd)) {}
}

SB_TEST(resume_refuses_an_edited_obstacle_mesh)
{
    char dir[256], scene[512], rec[512], cmd[2048];
    snprintf(dir, sizeof dir, "%s/objres", tmpdir);
    mesh_scene(dir, 4, scene, sizeof scene);
    snprintf(rec, sizeof rec, "%s/mesh.h5", dir);
    char run[1400];
    snprintf(run, sizeof run, "run --scene %s --method bhem --solver lsnewton --res 2 --out %s --quiet", scene, rec);
    snprintf(cmd, sizeof cmd, "%s --stop-after-steps 2", run);
    CHECK_EQ_INT(sh(cmd), 4);
    /* the checkpoint names the meshes' contents */
    char sums[1024], err[1024], part[600];
    snprintf(part, sizeof part, "%s.partial", rec);
    CHECK(sb_record_read_mesh_sums(part, sums, sizeof sums, err, sizeof err) == SB_OK && strstr(sums, "nv 8 nt 12 crc64 "));
    edit_obj(dir);
    snprintf(cmd, sizeof cmd, "%s --resume", run);
    int rc = sh(cmd);
    CHECK_MSG(rc == 2 && strstr(err_buf, part) && strstr(err_buf, "obstacle meshes changed"), "resume after the edit: %d %s",
              rc, err_buf);
    CHECK(access(part, F_OK) == 0);   /* nothing lost */
    /* the same mesh again: resumed */
    snprintf(cmd, sizeof cmd, "sed -i 's/ -0\\.15$/ -0.1/' %s/box_top.obj", dir);
    if (system(cmd)) {}
    snprintf(cmd, sizeof cmd, "%s --resume", run);
    rc = sh(cmd);
    CHECK_MSG(rc == 0, "resume with the original mesh: %d %s", rc, err_buf);
}

/* ---- item 11: a reference with other obstacles --------------------------- */

SB_TEST(reference_with_other_obstacles_refused_everywhere)
{
    char dir[256], scene[512], ref[512], cmd[2048], other[512];
    snprintf(dir, sizeof dir, "%s/objref", tmpdir);
    mesh_scene(dir, 2, scene, sizeof scene);
    snprintf(ref, sizeof ref, "%s/ref.h5", dir);
    snprintf(cmd, sizeof cmd, "run --scene %s --method bhem --solver lsnewton --res 2 --out %s --quiet", scene, ref);
    CHECK_EQ_INT(sh(cmd), 0);
    /* the same scene pointing at it: accepted, and an error measured */
    char same[512];
    snprintf(same, sizeof same, "%s/same.json", dir);
    json_error_t e;
    json_t *o = json_load_file(scene, 0, &e);
    CHECK(o != NULL);
    if (!o) return;
    json_object_set_new(o, "reference", json_pack("{s:s, s:s}", "type", "file", "file", ref));
    json_dump_file(o, same, JSON_INDENT(1));
    snprintf(cmd, sizeof cmd, "check %s", same);
    int rc = sh(cmd);
    CHECK_MSG(rc == 0, "check of the scene its reference was made of: %d %s", rc, err_buf);
    /* other obstacles: the cube with friction */
    json_t *obs = json_object_get(o, "obstacles");
    json_object_set_new(json_array_get(obs, 0), "friction", json_real(0.5));
    snprintf(other, sizeof other, "%s/other.json", dir);
    json_dump_file(o, other, JSON_INDENT(1));
    json_decref(o);
    snprintf(cmd, sizeof cmd, "check %s", other);
    rc = sh(cmd);
    CHECK_MSG(rc == 2 && strstr(err_buf, ref) && strstr(err_buf, "another scene") && strstr(err_buf, "/obstacles"),
              "check: %d %s", rc, err_buf);
    snprintf(cmd, sizeof cmd, "run --scene %s --method bhem --solver lsnewton --res 2 --out none --summary json --quiet",
             other);
    rc = sh(cmd);
    CHECK_MSG(rc == 2 && !out_buf[0] && strstr(err_buf, "another scene") && !strstr(err_buf, "step 1"),
              "run start: %d %s", rc, err_buf);
    /* the end of a run (and a study's report) says the same */
    char *text = NULL;
    size_t n = 0;
    FILE *f = fopen(other, "rb");
    if (f) {
        fseek(f, 0, SEEK_END);
        n = (size_t)ftell(f);
        fseek(f, 0, SEEK_SET);
        text = calloc(n + 1, 1);
        if (text && fread(text, 1, n, f) != n) text[0] = 0;
        fclose(f);
    }
    sb_refrec rr;
    char msg[2048];
    double st[2] = { 0, 0 };
    CHECK(text && sb_refrec_load(ref, "cloth_mesh_impulse", text, 1, st, &rr, msg, sizeof msg) == SB_ERR_INPUT &&
          strstr(msg, "/obstacles"));
    free(text);
    /* the same scene text with an edited OBJ file: other mesh contents */
    edit_obj(dir);
    snprintf(cmd, sizeof cmd, "check %s", same);
    rc = sh(cmd);
    CHECK_MSG(rc == 2 && strstr(err_buf, "other obstacle meshes"), "check after the OBJ edit: %d %s", rc, err_buf);
    snprintf(cmd, sizeof cmd, "run --scene %s --method bhem --solver lsnewton --res 2 --out none --quiet", same);
    rc = sh(cmd);
    CHECK_MSG(rc == 2 && strstr(err_buf, "other obstacle meshes"), "run after the OBJ edit: %d %s", rc, err_buf);
}

/* A study's runs and report take an unsealed reference only with
 * --allow-unsealed-reference (sweep --study, report --study). */
SB_TEST(study_unsealed_reference_needs_the_option)
{
    char src[512], ref[512], scene[512], study[512], cmd[2048], md[600];
    snprintf(src, sizeof src, "%s/results/references/trampoline.h5", sb_test_root());
    snprintf(ref, sizeof ref, "%s/study_unsealed.h5", tmpdir);
    CHECK(copy_file(src, ref) == 0 && unseal(ref) == 0);
    snprintf(scene, sizeof scene, "%s/tramp_study.json", tmpdir);
    json_decref(scene_copy("bench/scenes/trampoline.json", scene, ref, 0));
    snprintf(study, sizeof study, "%s/unsealed_study.json", tmpdir);
    FILE *f = fopen(study, "w");
    CHECK(f != NULL);
    if (!f) return;
    fprintf(f, "{\"study\": \"unsealed\", \"records\": \"%s/strec\", \"scenes\": [{\"scene\": \"%s\", \"solution\": \"unique\"}],\n"
               " \"methods\": [\"bhem\"], \"solvers\": [\"lsnewton\"], \"res\": [4]}\n", tmpdir, scene);
    fclose(f);
    snprintf(cmd, sizeof cmd, "sweep --study %s --quiet --allow-unsealed-reference", study);
    int rc = sh(cmd);
    CHECK_MSG(rc == 0, "sweep --study --allow-unsealed-reference: %d %s %s", rc, out_buf, err_buf);
    snprintf(md, sizeof md, "%s/strec/report.md", tmpdir);
    snprintf(cmd, sizeof cmd, "report --study %s --deterministic && cat %s", study, md);
    rc = sh(cmd);
    CHECK_MSG(rc == 0 && strstr(out_buf, "carries no checksum"), "report --study: %d %s", rc, err_buf);
    snprintf(cmd, sizeof cmd, "report --study %s --deterministic --allow-unsealed-reference && cat %s", study, md);
    rc = sh(cmd);
    CHECK_MSG(rc == 0 && !strstr(out_buf, "carries no checksum"), "report --study --allow-unsealed-reference: %d %s",
              rc, err_buf);
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_trust_inputs_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(reference_flipped_bit_and_unsealed_refused),
        SB_CASE(strict_verdict_read_from_the_record),
        SB_CASE(resume_refuses_an_edited_obstacle_mesh),
        SB_CASE(reference_with_other_obstacles_refused_everywhere),
        SB_CASE(study_unsealed_reference_needs_the_option),
        SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
