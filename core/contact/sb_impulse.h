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
} sb_impulse_stats;

#endif
