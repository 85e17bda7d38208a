/* sb_hash.h — uniform-grid spatial hash of axis-aligned boxes (Teschner,
 * Heidelberger, Müller, Pomeranets & Gross 2003, "Optimized Spatial Hashing
 * for Collision Detection of Deformable Objects", §3-4: cells of a uniform
 * grid mapped to a hash table by (i p1 xor j p2 xor k p3) mod size).  Boxes
 * of one set are entered into every cell they overlap; a query box visits
 * the boxes of the cells it overlaps, each once.  No global state. */
#ifndef SB_HASH_H
#define SB_HASH_H

typedef struct sb_hash {
    double cell;          /* cell edge length */
    int size;             /* buckets */
    int *start;           /* size + 1: entries of bucket b are start[b] .. start[b+1]-1 */
    int *id;              /* entries: box index */
    int *mark;            /* per box: the last query that visited it */
    int n, stamp;
} sb_hash;

/* Enter n boxes (lo, hi: 3n each) with the given cell size; SB_OK or SB_ERR_NOMEM. */
int  sb_hash_build(sb_hash *h, int n, const double *lo, const double *hi, double cell);
void sb_hash_free(sb_hash *h);
/* Call fn(data, i) once for every box i whose cells overlap the query box;
 * returns the first nonzero value of fn (and stops), else 0. */
int  sb_hash_query(sb_hash *h, const double lo[3], const double hi[3], int (*fn)(void *data, int i), void *data);

#endif
