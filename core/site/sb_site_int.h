/* sb_site_int.h — internal to core/site. */
#ifndef SB_SITE_INT_H
#define SB_SITE_INT_H

#include "sb_site.h"

/* the Vega modules a page with plots loads, in dependency order (NULL-ended) */
extern const char *const sb_site_vega_modules[];

/* The page of one record at rel (relative to the site root): summary,
 * convergence history, per-level counts and timings per event, probes
 * against expectations, links to the HDF5 and XDMF files.  back: the page
 * it was reached from (site-relative); label: its heading.  started
 * receives the record's start date.  0, or -1 (the record unreadable: a
 * warning; no page). */
int sb_site_run(sb_site *S, const char *record, const char *rel, const char *back, const char *label, char *started,
                size_t slen);

/* a relative link from the site page rel to the file `target` (relative to
 * the current directory); 0, or -1 when either cannot be resolved */
int sb_site_link(const sb_site *S, const char *rel, const char *target, char *buf, size_t len);

#endif
