/* sb_simd.h — the short double vectors of the fast shell kernel
 * (sb_shell_elem.c, sb_section_fast.c), as GCC/Clang vector extensions.
 *
 * The width follows the build's instruction set: 2 doubles (SSE2, the
 * x86-64 baseline of the default, portable build), 4 with AVX, 8 with
 * AVX-512 (`make NATIVE=1`, -march=native).  Arithmetic on these types is
 * element-wise IEEE arithmetic, so the default build computes the same bits
 * on every x86-64 machine; the native build may contract a*b+c into FMA
 * (-ffp-contract=fast) and so gives other round-off (docs/performance.md). */
#ifndef SB_SIMD_H
#define SB_SIMD_H

#include <stdint.h>
#include <string.h>

#if defined(__AVX512F__)
#define SB_VL 8
#elif defined(__AVX__)
#define SB_VL 4
#else
#define SB_VL 2
#endif

typedef double sb_vd __attribute__((vector_size(8 * SB_VL)));

/* Files compiled once per vector width (Makefile VEC_SRC: sb_elem_tile.c,
 * sb_section_denim.c) name their functions with the width's suffix:
 * SB_VEC_FN(f) is f_base in the build's own compile, f_avx2 and f_avx512
 * in the others (sb_shell_isa.c dispatches). */
#ifndef SB_VEC_SUFFIX
#define SB_VEC_SUFFIX base
#endif
#define SB_VEC_CAT_(a, b) a##_##b
#define SB_VEC_CAT(a, b) SB_VEC_CAT_(a, b)
#define SB_VEC_FN(name) SB_VEC_CAT(name, SB_VEC_SUFFIX)
typedef int64_t sb_vi __attribute__((vector_size(8 * SB_VL)));
typedef uint64_t sb_vu __attribute__((vector_size(8 * SB_VL)));

/* unaligned load / store (memcpy compiles to one vector move) */
static inline sb_vd sb_vload(const double *p)
{
    sb_vd v;
    memcpy(&v, p, sizeof v);
    return v;
}
static inline void sb_vstore(double *p, sb_vd v) { memcpy(p, &v, sizeof v); }
static inline sb_vd sb_vbcast(double a)
{
    sb_vd v;
#pragma GCC unroll 8
    for (int l = 0; l < SB_VL; l++) v[l] = a;
    return v;
}
static inline sb_vi sb_vasint(sb_vd v)
{
    sb_vi i;
    memcpy(&i, &v, sizeof i);
    return i;
}
static inline sb_vd sb_vasdbl(sb_vi i)
{
    sb_vd v;
    memcpy(&v, &i, sizeof v);
    return v;
}
/* p[0] = p[1] = x in one 2-wide store (the SSE2 tiles' pre-broadcast
 * operands, sb_elem_tile.c) */
typedef double sb_v2d __attribute__((vector_size(16)));
static inline sb_v2d sb_v2load(const double *p)
{
    sb_v2d v;
    memcpy(&v, p, sizeof v);
    return v;
}
static inline void sb_store_pair(double *p, double x)
{
    const sb_v2d v = { x, x };
    memcpy(p, &v, sizeof v);
}
/* m ? a : b with m a comparison result (all bits set where true) */
static inline sb_vd sb_vselect(sb_vi m, sb_vd a, sb_vd b)
{
    const sb_vi ib = sb_vasint(b);
    return sb_vasdbl(ib ^ ((sb_vasint(a) ^ ib) & m));
}

#endif
