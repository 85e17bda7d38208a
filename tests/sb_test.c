#include "sb_test.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void sb_test_fail(sb_test_state *T, const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    T->failed++;
    fprintf(stdout, "    FAIL %s:%d: ", file, line);
    va_start(ap, fmt);
    vfprintf(stdout, fmt, ap);
    va_end(ap);
    fputc('\n', stdout);
    fflush(stdout);
}

const char *sb_test_root(void)
{
    const char *r = getenv("SB_ROOT");
    return r && *r ? r : ".";
}

const char *sb_test_bin(void)
{
    const char *b = getenv("SB_BIN");
    return b && *b ? b : "build/shellbench";
}

double sb_rel_err(double a, double b)
{
    double d = fabs(b) > 1e-300 ? fabs(b) : 1e-300;
    return fabs(a - b) / d;
}

int sb_test_main(int argc, char **argv, const sb_test_case *cases)
{
    const char *name = strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0];
    const char *only = argc > 1 ? argv[1] : NULL;
    int passed = 0, failed = 0;
    for (const sb_test_case *c = cases; c->name; c++) {
        if (only && !strstr(c->name, only)) continue;
        sb_test_state T = { 0, 0 };
        c->fn(&T);
        if (T.failed == 0 && T.checks > 0) {
            passed++;
            printf("ok - %s (%d checks)\n", c->name, T.checks);
        } else {
            failed++;
            printf("not ok - %s (%d of %d checks failed)\n", c->name, T.failed, T.checks);
        }
        fflush(stdout);
    }
    printf("%s: %d passed, %d failed\n", name, passed, failed);
    return failed ? 1 : 0;
}
