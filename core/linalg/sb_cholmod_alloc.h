/* sb_cholmod_alloc.h — CHOLMOD's (SuiteSparse's) allocations of 4 MB and
 * more on transparent huge pages (madvise), the rest from malloc
 * (sb_cholmod_alloc.c says why and what was measured). */
#ifndef SB_CHOLMOD_ALLOC_H
#define SB_CHOLMOD_ALLOC_H

/* Point SuiteSparse's allocator hooks here.  Idempotent; done before main
 * (a constructor), so that no block is ever allocated by one allocator and
 * freed by the other; sb_context_init calls it too, which links it in. */
void sb_cholmod_alloc_install(void);

#endif
