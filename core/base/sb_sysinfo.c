/* sb_sysinfo.c — machine and build facts (see sb_sysinfo.h). */
#include "sb_sysinfo.h"

#include <ctype.h>
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifndef SB_BUILD_ID
#define SB_BUILD_ID "unknown"
#endif

static void copy_str(char *buf, size_t len, const char *s)
{
    if (!buf || len == 0) return;
    snprintf(buf, len, "%s", s);
}

void sb_sysinfo_cpu_model(char *buf, size_t len)
{
    copy_str(buf, len, "unknown");
    if (!buf || len == 0) return;
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        /* x86: "model name\t: Intel(R) ..."; the field is absent on some
         * architectures, where "unknown" stays. */
        if (strncmp(line, "model name", 10) != 0) continue;
        const char *colon = strchr(line, ':');
        if (!colon) continue;
        const char *v = colon + 1;
        while (*v == ' ' || *v == '\t') v++;
        size_t n = strlen(v);
        while (n > 0 && isspace((unsigned char)v[n - 1])) n--;
        if (n == 0) continue;
        if (n >= len) n = len - 1;
        memcpy(buf, v, n);
        buf[n] = 0;
        break;
    }
    fclose(f);
}

int sb_sysinfo_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n >= 1 ? (int)n : 1;
}

void sb_sysinfo_now_iso(char *buf, size_t len)
{
    if (!buf || len == 0) return;
    time_t t = time(NULL);
    struct tm tm;
    if (!gmtime_r(&t, &tm) || strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm) == 0)
        copy_str(buf, len, "unknown");
}

void sb_sysinfo_build_id(char *buf, size_t len)
{
    const char *id = SB_BUILD_ID;
    copy_str(buf, len, id[0] ? id : "unknown");
}

void sb_sysinfo_blas_core(char *buf, size_t len)
{
    /* asked of the library already loaded (CHOLMOD's BLAS), never loading
     * one: libblas.so.3 is OpenBLAS's when Debian's alternative points there */
    static const char *const libs[] = { "libopenblas.so.0", "libblas.so.3" };
    copy_str(buf, len, "unknown");
    for (size_t i = 0; i < sizeof libs / sizeof libs[0]; i++) {
        void *h = dlopen(libs[i], RTLD_LAZY | RTLD_NOLOAD);
        if (!h) continue;
        char *(*corename)(void) = (char *(*)(void))dlsym(h, "openblas_get_corename");
        const char *name = corename ? corename() : NULL;
        if (name && name[0]) copy_str(buf, len, name);
        dlclose(h);
        if (name && name[0]) return;
    }
}

void sb_sysinfo_hostname(char *buf, size_t len)
{
    if (!buf || len == 0) return;
    if (gethostname(buf, len) != 0) {
        copy_str(buf, len, "unknown");
        return;
    }
    buf[len - 1] = 0;   /* gethostname may truncate without a terminator */
}
