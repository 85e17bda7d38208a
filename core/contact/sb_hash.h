/* sb_hash.h — spatial hashing of primitives' bounding boxes
 * (Teschner et al. 2003), the broad phase of sb_bridson.c. */
#ifndef SB_HASH_H
#define SB_HASH_H

typedef struct sb_hash {
    double cell;              /* grid cell size */
    int size;                 /* hash table entries */
    int *start;               /* size + 1 offsets into item */
    int *item;                /* primitive ids by bucket */
    int nbig, *big;           /* primitives covering too many cells: always candidates */
    int n, *ids;              /* the primitives entered */
    const double *boxes;      /* 6 per primitive id (lo xyz, hi xyz); not owned */
    int cap_start, cap_item, cap_big, cap_ids;   /* allocated lengths: a rebuild reuses them */
} sb_hash;

typedef struct sb_idlist { int n, cap; int *v; } sb_idlist;

/* Enter primitives ids[0..n) with boxes (6 per id, indexed by id), replacing
 * what H held (a zeroed H, or one built before: its arrays are reused and
 * grown only when too short).  0 or -1 (out of memory). */
int  sb_hash_build(sb_hash *H, int n, const int *ids, const double *boxes, double cell);
void sb_hash_free(sb_hash *H);
/* The primitives whose boxes overlap box into out (reset first); stamp[id]
 * == mark marks those already returned (the caller changes mark per query).
 * 0 or -1 (out of memory). */
int  sb_hash_query(const sb_hash *H, const double *box, int *stamp, int mark, sb_idlist *out);

/* sb_hash_query, then fn(data, id) for each primitive found (scratch holds
 * the list); the first nonzero value of fn is returned, -1 when out of
 * memory, else 0. */
int  sb_hash_visit(const sb_hash *H, const double *box, int *stamp, int mark, sb_idlist *scratch,
                   int (*fn)(void *data, int id), void *data);

#endif
