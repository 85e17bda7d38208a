/* sb_impulse.h — statistics of the impulse-based collision response
 * (contact.model = "impulse", docs/contact.md): Bridson, Fedkiw & Anderson
 * 2002 (triangle methods, Bender & Deul §6) and BHEM §5.2/§6.2 (bhem).  One
 * struct per run, summed over steps; recorded under /final/contact. */
#ifndef SB_IMPULSE_H
#define SB_IMPULSE_H

typedef struct sb_impulse_stats {
    long proximity_impulses;   /* repulsion impulses applied (point-triangle, edge-edge, point-obstacle) */
    long ccd_tests;            /* continuous collision tests evaluated (after culling) */
    long ccd_hits;             /* collisions found by CCD and resolved by an impulse */
    long ccd_iterations;       /* CCD passes (at most 5 per step before impact zones) */
    long impact_zones;         /* rigid impact zones formed */
    long unresolved_steps;     /* steps that ended with a collision left (recorded, never silent) */
    long counted_steps;        /* steps these counts cover (all of a resumed run's since 2026-12-06 builds) */
    long broad_queries;        /* spatial-hash box queries (sb_bridson.c's broad phase; 0 where there is none) */
    long broad_candidates;     /*   primitives they returned (overlapping boxes), before the narrow phase */
} sb_impulse_stats;

/* the counts in a fixed order: the checkpoint's /resume/impulse_counts,
 * and the names under which /final/contact and the summary's `contact`
 * object hold them */
enum { SB_IMPULSE_N_COUNTS = 9 };
static const char *const sb_impulse_count_names[SB_IMPULSE_N_COUNTS] = {
    "proximity_impulses", "ccd_tests", "ccd_hits", "ccd_iterations", "impact_zones", "unresolved_steps",
    "counted_steps", "broad_queries", "broad_candidates" };
static inline void sb_impulse_to_array(const sb_impulse_stats *s, long a[SB_IMPULSE_N_COUNTS])
{
    a[0] = s->proximity_impulses; a[1] = s->ccd_tests; a[2] = s->ccd_hits; a[3] = s->ccd_iterations;
    a[4] = s->impact_zones; a[5] = s->unresolved_steps; a[6] = s->counted_steps; a[7] = s->broad_queries;
    a[8] = s->broad_candidates;
}
static inline void sb_impulse_from_array(sb_impulse_stats *s, const long a[SB_IMPULSE_N_COUNTS])
{
    s->proximity_impulses = a[0]; s->ccd_tests = a[1]; s->ccd_hits = a[2]; s->ccd_iterations = a[3];
    s->impact_zones = a[4]; s->unresolved_steps = a[5]; s->counted_steps = a[6]; s->broad_queries = a[7];
    s->broad_candidates = a[8];
}

#endif
