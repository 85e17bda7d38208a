/* fuzz_scene.c — libFuzzer harness of the scene parser (`make fuzz`,
 * docs/cli.md "Fuzzing").  Every input must give SB_OK or an error with a
 * one-line, terminal-safe message; a scene that parses must be one every
 * method's size estimate (sb_method_type.estimate) and the memory check
 * handle without overflow.  Seeds: bench/scenes, tests/scenes, tests/scenes_bad. */
#include "sb_memory.h"
#include "sb_method.h"
#include "sb_scene.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void check_message(const char *m)
{
    for (const unsigned char *p = (const unsigned char *)m; *p; p++)
        if (*p < 0x20 || *p == 0x7F || (p[0] == 0xC2 && p[1] >= 0x80 && p[1] < 0xA0)) {
            fprintf(stderr, "fuzz_scene: unescaped control character 0x%02x in message: %s\n", *p, m);
            abort();
        }
    if (strncmp(m, "fuzz.json:", 10) != 0) {
        fprintf(stderr, "fuzz_scene: message without FILE:LINE:COL: %s\n", m);
        abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sb_scene sc;
    char err[2048] = "";
    int rc = sb_scene_parse_buffer((const char *)data, size, "fuzz.json", &sc, err, sizeof err);
    if (rc != SB_OK) {
        check_message(err);
        return 0;
    }
    /* sizes a run of this scene would ask for, at its resolution and the limit */
    for (int i = 0; i < sb_method_count(); i++) {
        const sb_method_type *mt = sb_method_at(i);
        if (!mt->estimate) continue;
        const int res[] = { 0, sc.default_res, SB_SCENE_MAX_RESOLUTION };
        for (int r = 0; r < 3; r++)
            for (int levels = 1; levels <= 3; levels++) {
                sb_method_config cfg = { .res = res[r], .levels = levels, .params = NULL, .ctx = NULL, .res_t = 0 };
                sb_memory_run mr = { sc.time.mode == SB_TIME_DYNAMIC, sc.time.steps, sc.n_probes, 21, levels > 1 };
                double bytes;
                char msg[1024];
                sb_memory_check_method(mt, &sc, &cfg, &mr, 0, "fuzz", &bytes, msg, sizeof msg);
            }
    }
    sb_scene_free(&sc);
    return 0;
}
