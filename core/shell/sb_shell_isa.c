/* sb_shell_isa.c — which vector width the fast kernel's products and denim
 * section law run at (sb_elem_tile.c, sb_section_denim.c), chosen per batch
 * from what the CPU runs.
 *
 * The default build is the portable x86-64 baseline (SSE2); its products
 * and the denim section law (sb_section_denim.c) are also compiled for AVX2 and AVX-512 (Makefile: SB_VEC_VARIANTS), and
 * a batch uses the widest the CPU and the operating system support
 * (__builtin_cpu_supports checks both).  The variants compute the same
 * bits (sb_elem_tile.c, header), so records do not depend on the machine's
 * vector width; only the speed does.  `make NATIVE=1` compiles everything
 * for the build machine and has the base variant only. */
#include "sb_shell_batch.h"

#include <stdio.h>
#include <string.h>

const char *const sb_vector_choices[] = { "auto", "sse2", "avx2", "avx512", NULL };

const char *sb_shell_isa_name(sb_shell_isa isa)
{
    switch (isa) {
#ifdef SB_VEC_VARIANTS
    case SB_ISA_BASE: return "sse2";
#else
    case SB_ISA_BASE: return "native";
#endif
    case SB_ISA_AVX2: return "avx2";
    case SB_ISA_AVX512: return "avx512";
    }
    return "?";
}

int sb_shell_isa_supported(sb_shell_isa isa)
{
    switch (isa) {
    case SB_ISA_BASE: return 1;
#ifdef SB_VEC_VARIANTS
    case SB_ISA_AVX2: return __builtin_cpu_supports("avx2") ? 1 : 0;
    case SB_ISA_AVX512: return __builtin_cpu_supports("avx512f") ? 1 : 0;
#else
    case SB_ISA_AVX2:
    case SB_ISA_AVX512: return 0;
#endif
    }
    return 0;
}

sb_shell_isa sb_shell_isa_best(void)
{
    if (sb_shell_isa_supported(SB_ISA_AVX512)) return SB_ISA_AVX512;
    if (sb_shell_isa_supported(SB_ISA_AVX2)) return SB_ISA_AVX2;
    return SB_ISA_BASE;
}

sb_shell_isa sb_shell_batch_isa(const sb_shell_batch *w) { return w ? w->isa : SB_ISA_BASE; }

int sb_shell_batch_set_isa(sb_shell_batch *w, sb_shell_isa isa)
{
    if (!w || (unsigned)isa >= SB_ISA_COUNT) return SB_ERR_INPUT;
    if (!sb_shell_isa_supported(isa)) return SB_ERR_UNSUPPORTED;
    w->isa = isa;
    return SB_OK;
}

int sb_shell_isa_from_params(const sb_paramset *ps, sb_shell_isa *isa, char *msg, size_t len)
{
    *isa = sb_shell_isa_best();
    const char *v = ps ? sb_param_choice(ps, "run.vectors") : "";
    if (!v[0] || strcmp(v, "auto") == 0) return SB_OK;
#ifdef SB_VEC_VARIANTS
    const sb_shell_isa want = strcmp(v, "sse2") == 0 ? SB_ISA_BASE : strcmp(v, "avx2") == 0 ? SB_ISA_AVX2 : SB_ISA_AVX512;
    if (sb_shell_isa_supported(want)) {
        *isa = want;
        return SB_OK;
    }
    snprintf(msg, len, "run.vectors = %s: this CPU does not run %s (it runs up to %s; use auto)", v, v,
             sb_shell_isa_name(sb_shell_isa_best()));
#else
    snprintf(msg, len, "run.vectors = %s: this build (make NATIVE=1) compiles the kernel for its own machine only; "
             "use auto", v);
#endif
    return SB_ERR_INPUT;
}

/* the base variant of the default build is SSE2, whose tiles read A from
 * its pre-broadcast copy */
int sb_elem_wants_broadcast(const sb_shell_batch *w) { return SB_VL == 2 && w->isa == SB_ISA_BASE; }

/* The variants' functions, one constant table per width (the default
 * build's others exist only with SB_VEC_VARIANTS; a missing entry falls back
 * to the base width, which set_isa never lets a batch choose anyway). */
typedef struct sb_vec_ops {
    double (*element)(const sb_material *, int, const sb_shell_ref *, const sb_shell_basis *, const double *, double *,
                      double *, sb_hess_kind, sb_shell_batch *);
    void (*scatter)(int, int, const sb_shell_batch *, double *, double);
    void (*products)(int, int, sb_shell_batch *);
    void (*gram)(int, int, const double *, const double *, double *);
    double (*denim)(SB_SECTION_DENIM_ARGS);
} sb_vec_ops;

#define SB_VEC_OPS(sfx)                                                                                          \
    { sb_elem_element_##sfx, sb_elem_scatter_##sfx, sb_elem_products_##sfx, sb_elem_gram_##sfx,                   \
      sb_section_denim_##sfx }
static const sb_vec_ops vec_ops[SB_ISA_COUNT] = {
    [SB_ISA_BASE] = SB_VEC_OPS(base),
#ifdef SB_VEC_VARIANTS
    [SB_ISA_AVX2] = SB_VEC_OPS(avx2),
    [SB_ISA_AVX512] = SB_VEC_OPS(avx512),
#endif
};

static const sb_vec_ops *ops_of(sb_shell_isa isa)
{
    return (unsigned)isa < SB_ISA_COUNT && vec_ops[isa].element ? &vec_ops[isa] : &vec_ops[SB_ISA_BASE];
}

double sb_elem_element(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b, const double *q,
                       double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w)
{
    return ops_of(w ? w->isa : SB_ISA_BASE)->element(m, nq, r, b, q, grad, hess, kind, w);
}

void sb_elem_scatter(int k, int kp, const sb_shell_batch *w, double *hess, double sign)
{
    ops_of(w->isa)->scatter(k, kp, w, hess, sign);
}

void sb_elem_products(int R, int kp, sb_shell_batch *w) { ops_of(w->isa)->products(R, kp, w); }

void sb_elem_gram(int R, int n, sb_shell_batch *w) { ops_of(w->isa)->gram(R, n, w->G, w->Gb, w->C3); }

double sb_section_denim_isa(sb_shell_isa isa, const sb_material *m, const double A[3], const double B[3],
                            double sA[3], double sB[3], double C[36])
{
    return ops_of(isa)->denim(m, A, B, sA, sB, C);
}
