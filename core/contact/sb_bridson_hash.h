/* sb_bridson_hash.h — spatial hashing of primitives' bounding boxes
 * (Teschner et al. 2003), the broad phase of sb_bridson.c. */
#ifndef SB_BRIDSON_HASH_H
#define SB_BRIDSON_HASH_H

typedef struct sb_shash {
    double cell;              /* grid cell size */
    int size;                 /* hash table entries */
    int *start;               /* size + 1 offsets into item */
    int *item;                /* primitive ids by bucket */
    int nbig, *big;           /* primitives covering too many cells: always candidates */
    int n, *ids;              /* the primitives entered */
    const double *boxes;      /* 6 per primitive id (lo xyz, hi xyz); not owned */
} sb_shash;

typedef struct sb_idlist { int n, cap; int *v; } sb_idlist;

/* Enter primitives ids[0..n) with boxes (6 per id, indexed by id). 0 or -1
 * (out of memory). */
int  sb_shash_build(sb_shash *H, int n, const int *ids, const double *boxes, double cell);
void sb_shash_free(sb_shash *H);
/* The primitives whose boxes overlap box into out (reset first); stamp[id]
 * == mark marks those already returned (the caller changes mark per query).
 * 0 or -1 (out of memory). */
int  sb_shash_query(const sb_shash *H, const double *box, int *stamp, int mark, sb_idlist *out);

#endif
