/* sb_elem_tile.c — the batched products of the fast shell kernel,
 * H^cd = Wt^T Z^cd (sb_shell_elem.c, point 2 of its header) and the Gram
 * product G^T G of the PSD difference (sb_shell_elem_psd.c): about 40 % of
 * an exact element Hessian at k = 16 and 70 % at k = 40.
 *
 * This file is compiled once per vector width: as part of the library with
 * the build's own flags (suffix "base": SSE2, 2 doubles, in the default
 * build), and in the default build again with -mavx2 (suffix "avx2", 4
 * doubles) and with -mavx512f (suffix "avx512", 8 doubles), both with
 * -ffp-contract=off.  sb_shell_isa.c picks the widest the CPU runs.
 *
 * Why the wider variants give the same bits: every output entry
 * C[I][J] = sum_r A[r][I] B[r][J] is accumulated in one vector lane, from
 * +0.0, over r = 0, 1, ..., R-1 in that order, one IEEE multiply and one
 * IEEE add per term (no fused multiply-add: AVX2 is enabled without FMA,
 * and contraction is off for AVX-512).  The tile shape only decides which
 * entries share a register, not the operations on any entry, so all three
 * variants compute identical results (tests/test_shell_isa.c compares them
 * bit for bit on exact, pseudo and PSD element Hessians). */
#include "sb_shell_batch.h"

/* register tile: MR rows x NV vectors of SB_VL columns (8 accumulators of
 * SSE2 or AVX2, 8 of AVX-512 with 8 rows) */
#if SB_VL <= 4
#define MR 4
#define NV 2
#else
#define MR 8
#define NV 1
#endif
#define NR (NV * SB_VL)
#if MR > KPAD || NR > KPAD
#error "the tile must divide the padding KPAD of sb_shell_batch.h"
#endif

/* One MR x NR tile of C = A^T B (A, B: R x kp, row-major), written to C
 * (row stride kp) at (I0, J0).  The loop over the inner dimension keeps the
 * MR x NV vector accumulators in registers.  With SSE2 (no broadcast load)
 * A is read from its pre-broadcast copy Ab (each entry twice), so that a
 * broadcast is one aligned load, folded into the multiply; AVX2 and
 * AVX-512 broadcast from A itself. */
static inline void tile(int R, int kp, const double *A, const double *Ab, const double *B, int I0, int J0,
                        double *C)
{
    sb_vd acc[MR][NV];
#pragma GCC unroll 8
    for (int i = 0; i < MR; i++)
#pragma GCC unroll 8
        for (int v = 0; v < NV; v++) acc[i][v] = sb_vbcast(0.0);
#if SB_VL == 2
    (void)A;
    const sb_vd *ab = (const sb_vd *)(Ab + 2 * I0);   /* 16-byte aligned: kp and I0 are even */
    const int astep = kp;                            /* in vectors */
#else
    (void)Ab;
    const double *a = A + I0;
    const int astep = kp;
#endif
    const double *b = B + J0;
    for (int rr = 0; rr < R; rr++, b += kp) {
        sb_vd bv[NV];
#pragma GCC unroll 8
        for (int v = 0; v < NV; v++) bv[v] = sb_vload(b + v * SB_VL);
#pragma GCC unroll 8
        for (int i = 0; i < MR; i++) {
#if SB_VL == 2
            const sb_vd av = ab[i];
#else
            const sb_vd av = sb_vbcast(a[i]);
#endif
#pragma GCC unroll 8
            for (int v = 0; v < NV; v++) acc[i][v] += av * bv[v];
        }
#if SB_VL == 2
        ab += astep;
#else
        a += astep;
#endif
    }
#pragma GCC unroll 8
    for (int i = 0; i < MR; i++)
#pragma GCC unroll 8
        for (int v = 0; v < NV; v++) sb_vstore(C + (size_t)(I0 + i) * kp + J0 + v * SB_VL, acc[i][v]);
}

/* Z^cd rows of one point: Z[s][J] = sum_t K[3s+c][3t+d] W_t^J for the 6
 * component pairs, the blocks of K below the block diagonal read from above
 * it (K symmetric).  Each entry is ((((k0 w0 + k1 w1) + k2 w2) + k3 w3) +
 * k4 w4) in one lane at every width.  SSE2: the 150 coefficients are
 * broadcast once into kb, then each vector of columns J loads the 5 basis
 * rows once for all 30 output rows; wider vectors broadcast each
 * coefficient from memory inside the multiply instead (the same values). */
void SB_VEC_FN(sb_elem_zrows)(double K[15][15], const double *Wp, int kp, double *Z0, size_t zstride)
{
#if SB_VL == 2
    sb_vd kb[30][5];
#else
    double kb[30][5];
#endif
    for (int pr = 0; pr < 6; pr++) {
        const int cc = pc[pr], d = pd[pr];
#pragma GCC unroll 5
        for (int s = 0; s < 5; s++)
#pragma GCC unroll 5
            for (int t = 0; t < 5; t++) {
                const double kst = s <= t ? K[3 * s + cc][3 * t + d] : K[3 * t + d][3 * s + cc];
#if SB_VL == 2
                kb[5 * pr + s][t] = sb_vbcast(kst);
#else
                kb[5 * pr + s][t] = kst;
#endif
            }
    }
    for (int J = 0; J < kp; J += SB_VL) {
        const sb_vd w0 = sb_vload(Wp + J), w1 = sb_vload(Wp + kp + J), w2 = sb_vload(Wp + 2 * kp + J),
                    w3 = sb_vload(Wp + 3 * kp + J), w4 = sb_vload(Wp + 4 * kp + J);
        for (int pr = 0; pr < 6; pr++) {
            double *Zp = Z0 + pr * zstride + J;
#pragma GCC unroll 5
            for (int s = 0; s < 5; s++) {
                const int row = 5 * pr + s;
                sb_vstore(Zp + (size_t)s * kp, kb[row][0] * w0 + kb[row][1] * w1 + kb[row][2] * w2 +
                                                   kb[row][3] * w3 + kb[row][4] * w4);
            }
        }
    }
}

/* H^cd = Wt^T Z^cd for the 6 component pairs; the diagonal pairs only on
 * and above their diagonal tiles (H^cc is symmetric) */
void SB_VEC_FN(sb_elem_products)(int R, int kp, sb_shell_batch *w)
{
    const size_t zstride = (size_t)5 * w->nqmax * kp;
    for (int pr = 0; pr < 6; pr++) {
        const double *Zp = w->Z + pr * zstride;
        double *Hp = w->Hc + (size_t)pr * kp * kp;
        const int sym = pc[pr] == pd[pr];
        for (int I0 = 0; I0 < kp; I0 += MR)
            for (int J0 = sym ? I0 / NR * NR : 0; J0 < kp; J0 += NR) tile(R, kp, w->Wt, w->Wb, Zp, I0, J0, Hp);
    }
}

/* C = G^T G on and above its diagonal tiles */
void SB_VEC_FN(sb_elem_gram)(int R, int n, const double *G, const double *Gb, double *C)
{
    for (int I0 = 0; I0 < n; I0 += MR)
        for (int J0 = I0 / NR * NR; J0 < n; J0 += NR) tile(R, n, G, Gb, G, I0, J0, C);
}
