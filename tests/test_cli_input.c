/* test_cli_input.c — issue 28 items 5-6 and issue 27's /dev/stdin: scene
 * files that are hostile or odd.  Control characters from a scene reach
 * messages escaped (one line, nothing a terminal would act on); `check` on
 * a FIFO does not block; a record given as a scene is named as one; a
 * UTF-8 byte-order mark is skipped; `check` keeps stdout for results and
 * prints errors on stderr; `run --scene /dev/stdin` reads a pipe. */
#include "cli_sh.h"
#include "sb_common.h"
#include "sb_test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256], err[8192], out[1 << 16];

static void write_file(const char *path, const char *bytes, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(bytes, 1, n, f);
        fclose(f);
    }
}

/* no byte a terminal acts on: C0 controls but the final newline, DEL, C1 */
static int terminal_safe(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    for (; *p; p++) {
        if (*p == '\n') continue;
        if (*p < 0x20 || *p == 0x7F || *p == 0x9B || (p[0] == 0xC2 && p[1] >= 0x80 && p[1] < 0xA0)) return 0;
        /* bidi embeddings, overrides and isolates: U+202A..U+202E, U+2066..U+2069 */
        if (p[0] == 0xE2 && ((p[1] == 0x80 && p[2] >= 0xAA && p[2] <= 0xAE) || (p[1] == 0x81 && p[2] >= 0xA6 && p[2] <= 0xA9)))
            return 0;
    }
    return 1;
}

static int lines(const char *s)
{
    int n = 0;
    for (; *s; s++) n += *s == '\n';
    return n;
}

SB_TEST(control_characters_escaped)
{
    const char *bin = sb_test_bin();
    char p[512];
    /* a name with an escape sequence and a newline (JSON escapes): refused by the name rule */
    snprintf(p, sizeof p, "%s/esc_name.json", tmpdir);
    const char *a = "{\"name\": \"x\\u001b[2J\\u001b]0;pwned\\u0007\\nsecond line\\u009b31m\"}";
    write_file(p, a, strlen(a));
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check %s", bin, p), 2);
    CHECK_MSG(terminal_safe(err) && lines(err) == 1 && strstr(err, "\\x1b[2J") && strstr(err, "\\n") &&
              strstr(err, "\\u009b"), "%s", err);
    /* raw control bytes in the file: jansson quotes them back */
    snprintf(p, sizeof p, "%s/esc_raw.json", tmpdir);
    const char raw[] = "{\"name\": \"a\x1b[31mred\x07\"}";
    write_file(p, raw, sizeof raw - 1);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check %s", bin, p), 2);
    CHECK_MSG(terminal_safe(err) && lines(err) == 1, "%s", err);
    /* a file name with control characters (the user's own, still escaped) */
    snprintf(p, sizeof p, "%s/bad\x1b[1mname.json", tmpdir);
    write_file(p, "[]", 2);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check '%s'", bin, p), 2);
    CHECK_MSG(terminal_safe(err) && strstr(err, "\\x1b[1m"), "%s", err);
    /* and in the run's messages: an edge name from the scene */
    snprintf(p, sizeof p, "%s/edge.json", tmpdir);
    char scene[4096];
    FILE *f = fopen("bench/scenes/trampoline.json", "r");
    if (!f) {
        snprintf(scene, sizeof scene, "%s/bench/scenes/trampoline.json", sb_test_root());
        f = fopen(scene, "r");
    }
    size_t n = f ? fread(scene, 1, sizeof scene - 1, f) : 0;
    if (f) fclose(f);
    scene[n] = 0;
    char *on = strstr(scene, "\"left\"");
    CHECK(on != NULL);
    if (on) {
        char mod[4200];
        snprintf(mod, sizeof mod, "%.*s\"le\\u001b[5mft\"%s", (int)(on - scene), scene, on + 6);
        write_file(p, mod, strlen(mod));
        CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s run --scene %s --method bhem --solver tr --out none", bin, p), 2);
        CHECK_MSG(terminal_safe(err) && strstr(err, "\\x1b[5m"), "%s", err);
    }
    /* unknown method names from the command line likewise */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s run --scene trampoline --method \"$(printf 'a\\033[2Jb')\" "
                       "--solver tr --out none", bin), 2);
    CHECK_MSG(terminal_safe(err) && strstr(err, "\\x1b[2J"), "%s", err);
}

SB_TEST(escape_function)
{
    char s[64];
    snprintf(s, sizeof s, "a\x1b[0m\tb\nc");
    CHECK(sb_escape_controls(s, sizeof s) == 3 && strcmp(s, "a\\x1b[0m\\tb\\nc") == 0);
    snprintf(s, sizeof s, "\xC2\x9B" "31m \xEF\xBB\xBF \xFF");   /* C1 CSI, BOM, invalid byte */
    CHECK_MSG(sb_escape_controls(s, sizeof s) == 3 && strcmp(s, "\\u009b31m \\ufeff \\xff") == 0, "%s", s);
    snprintf(s, sizeof s, "caf\xC3\xA9 \xE2\x80\x96g\xE2\x80\x96");   /* UTF-8 text is kept */
    CHECK(sb_escape_controls(s, sizeof s) == 0 && strcmp(s, "caf\xC3\xA9 \xE2\x80\x96g\xE2\x80\x96") == 0);
    /* issue 37 item 12: the right-to-left override and the other bidi controls */
    snprintf(s, sizeof s, "a\xE2\x80\xAE" "b\xE2\x80\xAA\xE2\x81\xA6\xE2\x81\xA9" "c");
    CHECK_MSG(sb_escape_controls(s, sizeof s) == 4 && strcmp(s, "a\\u202eb\\u202a\\u2066\\u2069c") == 0, "%s", s);
    snprintf(s, sizeof s, "\xE2\x80\xA9\xE2\x80\xAF\xE2\x81\xA5\xE2\x81\xAA");   /* neighbours are kept */
    CHECK_MSG(sb_escape_controls(s, sizeof s) == 0, "%s", s);
    char small[8];
    snprintf(small, sizeof small, "\x01\x02\x03");   /* truncated to whole escapes' bytes */
    sb_escape_controls(small, sizeof small);
    CHECK(strlen(small) == 7 && strncmp(small, "\\x01\\x0", 7) == 0);
}

SB_TEST(fifo_hdf5_bom_and_streams)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char p[512];
    /* a FIFO without a writer blocked `check` forever */
    snprintf(p, sizeof p, "%s/scene.fifo", tmpdir);
    CHECK(mkfifo(p, 0644) == 0);
    int ec = sb_sh(out, sizeof out, err, sizeof err, "timeout 600 %s check %s", bin, p);
    CHECK_EQ_INT(ec, 2);
    CHECK_MSG(strstr(err, "FIFO") && strstr(err, "/dev/stdin"), "%s", err);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "timeout 600 %s run --scene %s --method bhem --solver tr --out none",
                       bin, p), 2);
    CHECK(strstr(err, "FIFO") != NULL);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check /dev/zero", bin), 2);
    CHECK(strstr(err, "character device") != NULL);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check %s", bin, tmpdir), 2);
    CHECK(strstr(err, "directory") != NULL);
    /* a run record given as a scene */
    snprintf(p, sizeof p, "%s/rec.h5", tmpdir);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "cd %s && %s run --scene trampoline --method bhem --solver tr --res 4 --quiet "
                       "--out %s", root, bin, p), 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check %s", bin, p), 2);
    CHECK_MSG(strstr(err, "HDF5 file (a run record?)") && !strstr(err, "NUL"), "%s", err);
    /* a UTF-8 byte-order mark is skipped */
    snprintf(p, sizeof p, "%s/bom.json", tmpdir);
    CHECK_EQ_INT(sb_sh(NULL, 0, NULL, 0, "printf '\\357\\273\\277' > %s && cat %s/bench/scenes/trampoline.json >> %s", p,
                       root, p), 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check %s", bin, p), 0);
    CHECK_MSG(strstr(out, ": ok (trampoline)") && err[0] == 0, "%s / %s", out, err);
    /* results on stdout, errors on stderr */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s check bench/scenes/drape.json "
                       "tests/scenes_bad/poisson_out_of_range.json", root, bin), 2);
    CHECK_MSG(strstr(out, "drape.json: ok") && !strstr(out, "poisson"), "stdout: %s", out);
    CHECK_MSG(strstr(err, "poisson_out_of_range.json:") && !strstr(err, "drape"), "stderr: %s", err);
}

SB_TEST(scene_from_stdin)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    /* `check /dev/stdin` worked, `run --scene /dev/stdin` said "not found" */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && cat bench/scenes/trampoline.json | %s check /dev/stdin",
                       root, bin), 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && cat bench/scenes/trampoline.json | %s run --scene "
                       "/dev/stdin --method bhem --solver tr --res 4 --out none --summary json --quiet", root, bin), 0);
    CHECK_MSG(strstr(out, "\"scene\": \"trampoline\""), "%s / %s", out, err);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s run --scene /dev/stdin --method bhem --solver tr "
                       "--res 4 --out none < bench/scenes/trampoline.json --quiet", root, bin), 0);
    /* a path that does not exist is still "not found" */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s run --scene %s/none.json --method bhem --solver tr", bin,
                       tmpdir), 2);
    CHECK(strstr(err, "not found") != NULL);
}

/* out and err together: terminal-safe, and the name shown escaped */
static void echoed_escaped(sb_test_state *T, int ec, int want_ec, const char *what)
{
    static char both[sizeof out + sizeof err];
    snprintf(both, sizeof both, "%s%s", out, err);
    CHECK_MSG(ec == want_ec, "%s: exit %d", what, ec);
    CHECK_MSG(terminal_safe(both) && strstr(both, "\\x1b[31m") && strstr(both, "\\u202e"), "%s: %s", what, both);
}

/* issue 37 item 12: every message that echoes input escapes it, with an
 * escape sequence and U+202E (right-to-left override) in each name */
SB_TEST(every_echo_escaped)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    const char *E = "X\x1b[31mY\xE2\x80\xAEZ", *J = "X\\u001b[31mY\\u202eZ";   /* raw, and as JSON text */
    char p[512];
    /* a missing record: inspect, render */
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "%s inspect '%s/%s.h5'", bin, tmpdir, E), 2, "inspect");
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "%s render '%s/%s.h5' --out %s/x.png", bin, tmpdir, E,
                            tmpdir), 2, "render");
    /* render's option values */
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "%s render r.h5 --color '%s'", bin, E), 2, "render --color");
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "%s render r.h5 --camera '%s'", bin, E), 2, "render --camera");
    /* reference of a scene name */
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s reference '%s'", tmpdir, bin, E), 2, "reference");
    /* a study file's name; a study's keys and values; its records directory on stdout */
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "%s sweep --study '%s/%s.json' --plan", bin, tmpdir, E), 2,
                   "sweep --study FILE");
    static const char *const study[] = {
        "{\"study\": \"s\", \"%s\": 1, \"records\": \"%s/r\", \"scenes\": [{\"scene\": \"trampoline\", \"solution\": "
        "\"unique\"}], \"methods\": [\"bhem\"], \"solvers\": [\"tr\"], \"res\": [4]}",
        "{\"study\": \"s\", \"records\": \"%s/r\", \"scenes\": [{\"scene\": \"trampoline\", \"solution\": \"unique\"}], "
        "\"methods\": [\"%s\"], \"solvers\": [\"tr\"], \"res\": [4]}",
        "{\"study\": \"s\", \"records\": \"%s/r\", \"scenes\": [{\"scene\": \"trampoline\", \"solution\": \"unique\"}], "
        "\"methods\": [\"bhem\"], \"solvers\": [\"tr\"], \"res\": [4], \"set\": {\"method.hessian\": \"%s\"}}",
        "{\"study\": \"s\", \"records\": \"%s/r%s\", \"scenes\": [{\"scene\": \"trampoline\", \"solution\": \"unique\"}], "
        "\"methods\": [\"bhem\"], \"solvers\": [\"tr\"], \"res\": [4]}",
    };
    for (int k = 0; k < 4; k++) {
        char text[1024];
        if (k == 0) snprintf(text, sizeof text, study[k], J, tmpdir);
        else if (k == 3) snprintf(text, sizeof text, study[k], tmpdir, J);
        else snprintf(text, sizeof text, study[k], tmpdir, J);
        snprintf(p, sizeof p, "%s/study%d.json", tmpdir, k);
        write_file(p, text, strlen(text));
        echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --study %s --plan", root, bin, p),
                       k == 3 ? 0 : 2, text);
    }
    /* a list sweep's records directory on stdout */
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s sweep --scenes tests/scenes/membrane_dynamic.json "
                            "--methods fixture_membrane --solvers lsnewton --res 2 --dir '%s/%s'", root, bin, tmpdir, E),
                   0, "sweep --dir");
    /* run: the record path it names at the end, and again when resumed */
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s run --scene tests/scenes/membrane_dynamic.json "
                            "--method fixture_membrane --solver lsnewton --res 2 --out '%s/%s/a.h5'", root, bin, tmpdir, E),
                   0, "run --out");
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s run --scene tests/scenes/membrane_dynamic.json "
                            "--method fixture_membrane --solver lsnewton --res 2 --out '%s/%s/a.h5' --resume", root, bin,
                            tmpdir, E), 0, "run --resume");
    /* regress: the baseline's and the suite's names */
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "%s regress --suite %s/study0.json --baseline '%s/%s.json' "
                            "--out %s/rg --no-history", bin, tmpdir, tmpdir, E, tmpdir), 2, "regress --baseline");
    echoed_escaped(T, sb_sh(out, sizeof out, err, sizeof err, "%s regress --suite '%s/%s.json' --baseline %s/none.json "
                            "--update-baseline --out %s/rg --no-history", bin, tmpdir, E, tmpdir, tmpdir), 2,
                   "regress --suite");
}

/* issue 37 item 13: a message says what is wrong */
SB_TEST(messages_say_what_is_wrong)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    /* `reference nonexist` printed `scene "nonexist": ` and nothing after */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && %s reference nonexist", tmpdir, bin), 2);
    CHECK_MSG(strstr(err, "\"nonexist\" not found") && strstr(err, "bench/scenes/nonexist.json") &&
              strstr(err, "looked in") && lines(err) == 1, "%s", err);
    /* a FIFO given by a bare name was "not found" */
    char p[512];
    snprintf(p, sizeof p, "%s/fifoscene", tmpdir);
    CHECK(mkfifo(p, 0644) == 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && SB_ROOT=%s timeout 600 %s run --scene fifoscene "
                       "--method bhem --solver tr --out none", tmpdir, root, bin), 2);
    CHECK_MSG(strstr(err, "FIFO") && !strstr(err, "not found"), "%s", err);
    /* a bundled name is still found with a directory of that name in the way */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "cd %s && mkdir -p trampoline && SB_ROOT=%s %s check trampoline",
                       tmpdir, root, bin), 0);
}

/* issue 27: a scene bundles each method at its own resolution ("methods"),
 * with its own method.* settings; --res and --set win; names and keys the
 * registry does not know are refused by check and run, naming the file */
SB_TEST(scene_method_settings)
{
    const char *bin = sb_test_bin(), *root = sb_test_root();
    char path[512], cmd[2048];
    snprintf(path, sizeof path, "%s/bundled.json", tmpdir);
    snprintf(cmd, sizeof cmd, "sed 's/\"methods\": {.*/\"methods\": {\"bhem\": "
             "{\"resolution\": 4, \"set\": {\"method.hessian\": \"pseudo\"}}}/' %s/bench/scenes/plate_clamped.json > %s",
             root, path);
    CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "%s", cmd), 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check %s", bin, path), 0);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s run --scene %s --method bhem --solver lsnewton --out none "
                       "--summary json --quiet", bin, path), 0);
    CHECK_MSG(strstr(out, "\"res\": 4,") && strstr(out, "pseudo Hessian"), "%s / %s", out, err);
    /* the command line wins over the scene */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s run --scene %s --method bhem --solver lsnewton --res 2 "
                       "--set method.hessian=exact --out none --summary json --quiet", bin, path), 0);
    CHECK_MSG(strstr(out, "\"res\": 2,") && strstr(out, "exact Hessian"), "%s / %s", out, err);
    /* another method keeps the scene's own resolution */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s run --scene %s --method rmtr --solver lsnewton --out none "
                       "--summary json --quiet", bin, path), 0);
    CHECK_MSG(strstr(out, "\"res\": 16,"), "%s / %s", out, err);
    /* a method this build does not have, a parameter the method does not have */
    const char *bad[2][2] = { { "s/\"bhem\": {/\"bhem2\": {/", "not a method of this build" },
                              { "s/method.hessian/method.hesian/", "method.hesian" } };
    for (int i = 0; i < 2; i++) {
        char badp[600];
        snprintf(badp, sizeof badp, "%s/bad%d.json", tmpdir, i);
        CHECK_EQ_INT(sb_sh(NULL, 0, err, sizeof err, "sed '%s' %s > %s", bad[i][0], path, badp), 0);
        CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s check %s", bin, badp), 2);
        CHECK_MSG(strstr(err, bad[i][1]) && strstr(err, badp) && lines(err) == 1, "%s", err);
        CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s run --scene %s --method rmtr --solver lsnewton "
                           "--out none --quiet", bin, badp), 2);
        CHECK_MSG(strstr(err, bad[i][1]), "%s", err);
    }
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_cli_in_XXXXXX");
    if (!mkdtemp(tmpdir)) return 3;
    static const sb_test_case cases[] = {
        SB_CASE(control_characters_escaped), SB_CASE(escape_function), SB_CASE(fifo_hdf5_bom_and_streams),
        SB_CASE(scene_from_stdin), SB_CASE(scene_method_settings), SB_CASE(every_echo_escaped),
        SB_CASE(messages_say_what_is_wrong), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) {}
    return rc;
}
