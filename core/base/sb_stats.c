/* sb_stats.c — run statistics (see sb_stats.h). */
#include "sb_stats.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <time.h>

static const char *const event_names[SB_EV_COUNT] = {
    "energy", "gradient", "hessian", "analyze", "factorize", "solve",
    "cg_iter", "qp", "transfer", "adapt", "collide", "record", "galerkin", "checkpoint",
    "setup", "samples", "error", "progress", "solver",
};

const char *sb_event_name(sb_event e)
{
    return (int)e >= 0 && e < SB_EV_COUNT ? event_names[e] : "invalid";
}

double sb_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double sb_cpu_now(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void sb_stats_init(sb_stats *s) { memset(s, 0, sizeof *s); }

void sb_stats_free(sb_stats *s)
{
    free(s->iters);
    free(s->steps);
    memset(s, 0, sizeof *s);
}

void sb_stats_reset(sb_stats *s)
{
    int nl = s->n_levels;
    long nd[SB_MAX_LEVELS];
    memcpy(nd, s->n_dofs, sizeof nd);
    sb_iter_record *it = s->iters;
    size_t ci = s->cap_iters;
    sb_step_record *st = s->steps;
    size_t cs = s->cap_steps;
    memset(s, 0, sizeof *s);
    s->n_levels = nl;
    memcpy(s->n_dofs, nd, sizeof nd);
    s->iters = it;
    s->cap_iters = ci;
    s->steps = st;
    s->cap_steps = cs;
}

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return SB_OK;
    size_t nc = *cap ? *cap * 2 : 256;
    while (nc < need) nc *= 2;
    void *q = realloc(*p, nc * elem);
    if (!q) return SB_ERR_NOMEM;
    *p = q;
    *cap = nc;
    return SB_OK;
}

int sb_stats_push_iter(sb_stats *s, const sb_iter_record *r)
{
    if (grow((void **)&s->iters, &s->cap_iters, s->n_iters + 1, sizeof *r)) return SB_ERR_NOMEM;
    s->iters[s->n_iters++] = *r;
    return SB_OK;
}

int sb_stats_push_step(sb_stats *s, const sb_step_record *r)
{
    if (grow((void **)&s->steps, &s->cap_steps, s->n_steps + 1, sizeof *r)) return SB_ERR_NOMEM;
    s->steps[s->n_steps++] = *r;
    return SB_OK;
}

sb_event_stat sb_stats_event_total(const sb_stats *s, sb_event e)
{
    sb_event_stat t = { 0, 0.0, 0.0 };
    for (int l = 0; l < SB_MAX_LEVELS; l++) {
        t.count += s->ev[l][e].count;
        t.seconds += s->ev[l][e].seconds;
        t.self += s->ev[l][e].self;
    }
    return t;
}

double sb_stats_begin(sb_stats *s)
{
    double t0 = sb_now();
    if (s->depth >= 0 && s->depth < SB_STATS_DEPTH) {
        s->open_t0[s->depth] = t0;
        s->open_child[s->depth] = 0.0;
        s->depth++;
    }
    return t0;
}

void sb_stats_event(sb_stats *s, int level, sb_event e, double t0)
{
    const double incl = sb_now() - t0;
    double child = 0.0;
    if (level < 0 || level >= SB_MAX_LEVELS) level = 0;
    if (s->depth < 0 || s->depth > SB_STATS_DEPTH) s->depth = 0;
    /* the open event this closes; ones begun above it and never closed (an
     * error path) are dropped, the events closed inside them counting as
     * this one's */
    for (int k = s->depth - 1; k >= 0; k--)
        if (s->open_t0[k] == t0) {
            for (int j = k; j < s->depth; j++) child += s->open_child[j];
            s->depth = k;
            break;
        }
    if (s->depth > 0) s->open_child[s->depth - 1] += incl;
    s->ev[level][e].count++;
    s->ev[level][e].seconds += incl;
    s->ev[level][e].self += incl - child;
}

void sb_stats_close_all(sb_stats *s) { s->depth = 0; }

double sb_stats_self_total(const sb_stats *s, sb_event e)
{
    double t = 0.0;
    for (int l = 0; l < SB_MAX_LEVELS; l++) t += s->ev[l][e].self;
    return t;
}

double sb_peak_rss(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    double kb = -1.0;
    while (f && fgets(line, sizeof line, f))
        if (strncmp(line, "VmHWM:", 6) == 0) {
            kb = strtod(line + 6, NULL);
            break;
        }
    if (f) fclose(f);
    if (kb < 0) {
        struct rusage ru;
        kb = getrusage(RUSAGE_SELF, &ru) == 0 ? (double)ru.ru_maxrss : 0.0;
    }
    return 1024.0 * kb;
}

int sb_peak_rss_reset(void)
{
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (!f) return -1;
    int ok = fputs("5", f) >= 0;
    if (fclose(f)) ok = 0;
    return ok ? 0 : -1;
}

void sb_release_free_memory(void)
{
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}
