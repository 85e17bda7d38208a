/* sb_cholmod_alloc.c — CHOLMOD's memory on transparent huge pages
 * (sb_cholmod_alloc.h).
 *
 * Why (issue 42, measured in docs/scaling.md): a supernodal factor of 1e5-1e6
 * dofs is 0.4-10 GB touched once per factorization.  On 4 kB pages its first
 * factorization spends seconds in page faults (expensive in a virtual machine)
 * and every factorization in TLB misses; with the kernel's transparent huge
 * pages in "madvise" mode (Debian's default) only memory asked for with
 * madvise(MADV_HUGEPAGE) gets 2 MB pages, which glibc's malloc never asks
 * for unless GLIBC_TUNABLES=glibc.malloc.hugetlb=1.  Measured on the bhem
 * plate at 199,692 dofs, on the shared 2-core machine: the three
 * factorizations of lsnewton took 18.7 s on 4 kB pages, 15.6 s with every
 * allocation on huge pages (the glibc tunable), 16.1 s with these hooks;
 * at 1.24e6 dofs beside two other large runs no gain was measurable
 * (docs/scaling.md).
 *
 * How: SuiteSparse 5's allocator hooks (SuiteSparse_config, one per process;
 * set once, every context sets the same functions) point here.  Every block
 * carries a 16-byte header with its size and kind, so free and realloc know
 * what they hold: a block of at least SB_HUGE_MIN bytes is an anonymous
 * mapping advised MADV_HUGEPAGE (zero-filled by the kernel), a smaller one
 * comes from malloc.  Placement only: no arithmetic changes, so every count
 * and record is bit-identical to the plain allocator's.  Not under
 * AddressSanitizer (its own allocator must see every block). */
#include "sb_cholmod_alloc.h"

#include <SuiteSparse_config.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#if defined(__SANITIZE_ADDRESS__)
#define SB_HUGE_OFF 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SB_HUGE_OFF 1
#endif
#endif

enum { SB_HUGE_MIN = 4 << 20, HEADER = 16 };
enum { KIND_HEAP = 0x5B4EA9, KIND_MAP = 0x5B3A9E };

typedef struct { size_t size; size_t kind; } block_header;

static void *block_alloc(size_t size, int zero)
{
    if (size > SIZE_MAX - HEADER - (2u << 20)) return NULL;
    block_header *h;
    if (size >= SB_HUGE_MIN) {
        const size_t len = size + HEADER;
        void *p = mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) return NULL;
#ifdef MADV_HUGEPAGE
        madvise(p, len, MADV_HUGEPAGE);   /* advice: refused (THP off) costs nothing */
#endif
        h = p;
        h->kind = KIND_MAP;
    } else {
        h = zero ? calloc(1, size + HEADER) : malloc(size + HEADER);
        if (!h) return NULL;
        h->kind = KIND_HEAP;
    }
    h->size = size;
    return (char *)h + HEADER;
}

static void block_free(void *p)
{
    if (!p) return;
    block_header *h = (block_header *)((char *)p - HEADER);
    if (h->kind == KIND_MAP) munmap(h, h->size + HEADER);
    else free(h);
}

static void *hook_malloc(size_t size) { return block_alloc(size ? size : 1, 0); }

static void *hook_calloc(size_t n, size_t size)
{
    if (size && n > SIZE_MAX / size) return NULL;
    const size_t bytes = n * size;
    return block_alloc(bytes > 0 ? bytes : 1, 1);
}

static void *hook_realloc(void *p, size_t size)
{
    if (!p) return hook_malloc(size);
    if (!size) size = 1;
    block_header *h = (block_header *)((char *)p - HEADER);
    if (h->kind == KIND_HEAP && size < SB_HUGE_MIN) {
        block_header *n = realloc(h, size + HEADER);
        if (!n) return NULL;
        n->size = size;
        return (char *)n + HEADER;
    }
    void *q = block_alloc(size, 0);
    if (!q) return NULL;   /* realloc's contract: the old block stays valid */
    memcpy(q, p, h->size < size ? h->size : size);
    block_free(p);
    return q;
}

__attribute__((constructor)) static void install_at_start(void) { sb_cholmod_alloc_install(); }

void sb_cholmod_alloc_install(void)
{
#ifndef SB_HUGE_OFF
    SuiteSparse_config.malloc_func = hook_malloc;
    SuiteSparse_config.calloc_func = hook_calloc;
    SuiteSparse_config.realloc_func = hook_realloc;
    SuiteSparse_config.free_func = block_free;
#endif
}
