/* sb_shell_batch.h — internals of the fast shell kernel shared by
 * sb_shell_elem.c (the element) and sb_shell_elem_psd.c (its PSD
 * treatment): the batch's layout and the helpers both use.  Not an API:
 * include only from core/shell. */
#ifndef SB_SHELL_BATCH_H
#define SB_SHELL_BATCH_H

#include "sb_shell.h"
#include "sb_simd.h"

#include <stddef.h>

/* rows of the batch are padded with zeros to a multiple of KPAD doubles,
 * which every register tile of sb_elem_tile.c divides (4 x 4 with SSE2,
 * 4 x 8 with AVX2, 8 x 8 with AVX-512) */
#define KPAD 8
#define SB_SHELL_MAX_QP 64

struct sb_shell_batch {
    int kmax, nqmax, kpmax;
    sb_shell_isa isa;   /* the products' vector width (sb_shell_isa.c) */
    double *Wt;   /* 5 nq x kp: basis derivative rows, zero padded */
    double *Wb;   /* isa SSE2: Wt with every entry twice, the tiles' broadcast operand */
    double *Z;    /* 6 x 5 nq x kp: K^cd W per point */
    double *Hc;   /* 6 x kp x kp: H^cd */
    double *Gt;   /* 5 nq x 3: local gradient de/dy per point */
    double *qd;   /* 3 x kp: control values by component */
    double *gd;   /* 3 x kp: gradient by component */
    int keep;     /* sb_shell_element_psd's exact pass: keep what the PSD difference needs */
    int store;    /* sb_shell_element_into: the scatter overwrites hess */
    double *kd;   /* nq x KD: per point the PSD difference (see point()) */
    double *G;    /* 6 nq x 3 kp: the PSD difference's rank-1 terms, one row per clamped eigenvalue */
    double *Gb;   /* isa SSE2: G with every entry twice (the tiles' broadcast operand) */
    double *C3;   /* 3 kp x 3 kp: their Gram matrix G^T G (on and above the diagonal tiles) */
};
/* per point: 5 blocks of 3 x 3 (0..44), h (45..47); where the section
 * tangent is not positive definite also the number m of its negative
 * eigenvalues (48) and m vectors u_l (49 + 15 l .., slot-major jet) with
 * J^T (D - D+) J = -sum_l u_l u_l^T; the flag "positive definite" (KD - 1) */
#define KD 144


static inline int sb_elem_round_up(int k, int m) { return (k + m - 1) / m * m; }

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static inline void skew3(const double *v, double S[9])
{
    S[0] = 0;     S[1] = -v[2]; S[2] = v[1];
    S[3] = v[2];  S[4] = 0;     S[5] = -v[0];
    S[6] = -v[1]; S[7] = v[0];  S[8] = 0;
}
static inline void mul33(const double *A, const double *B, double *C)
{
#pragma GCC unroll 3
    for (int i = 0; i < 3; i++)
#pragma GCC unroll 3
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

/* slots of the local jet and the bending component -> slot map (sb_shell.c) */
enum { S_X1 = 0, S_X2 = 1, S_X11 = 2, S_X12 = 3, S_X22 = 4 };
static const int bslot[3] = { S_X11, S_X22, S_X12 };
/* the 6 component pairs c <= d: diagonal ones first */
static const int pc[6] = { 0, 1, 2, 0, 0, 1 }, pd[6] = { 0, 1, 2, 1, 2, 2 };

/* the element: energy, gradient and Hessian of kind EXACT, PSEUDO or PSD;
 * with w->keep, what sb_shell_element_psd needs is kept per point */
double sb_elem_element(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b, const double *q,
                       double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w);
/* H^cd = Wt^T Z^cd for the 6 component pairs, inner dimension R rows, at
 * the batch's isa */
void sb_elem_products(int R, int kp, sb_shell_batch *w);
/* w->C3 (n x n) = G^T G on and above its diagonal tiles (w->G, w->Gb: R x n,
 * n a multiple of KPAD) */
void sb_elem_gram(int R, int n, sb_shell_batch *w);
/* does the batch's isa read the pre-broadcast copies Wb and Gb? */
int sb_elem_wants_broadcast(const sb_shell_batch *w);
/* the section law of the fast kernel at a given vector width (the same bits
 * at every width; sb_section_fast.c, sb_section_denim.c) */
double sb_section_fast_isa(sb_shell_isa isa, const sb_material *m, const double A[3], const double B[3],
                           double sA[3], double sB[3], double C[36]);
double sb_section_denim_isa(sb_shell_isa isa, const sb_material *m, const double A[3], const double B[3],
                            double sA[3], double sB[3], double C[36]);
/* The functions each vector width's compile defines (sb_elem_point.c,
 * sb_elem_tile.c, sb_section_denim.c, named by SB_VEC_FN), declared for the
 * widths base, avx2 and avx512; sb_shell_isa.c tables them. */
#define SB_SECTION_DENIM_ARGS const sb_material *m, const double A[3], const double B[3], double sA[3], double sB[3], double C[36]
#define SB_VEC_DECLARE(sfx)                                                                                          \
    double sb_section_denim_##sfx(SB_SECTION_DENIM_ARGS);                                                           \
    double sb_elem_element_##sfx(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,      \
                                 const double *q, double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w); \
    void sb_elem_scatter_##sfx(int k, int kp, const sb_shell_batch *w, double *hess, double sign);                 \
    void sb_elem_zrows_##sfx(double K[15][15], const double *Wp, int kp, double *Z0, size_t zstride);              \
    void sb_elem_products_##sfx(int R, int kp, sb_shell_batch *w);                                                 \
    void sb_elem_gram_##sfx(int R, int n, const double *G, const double *Gb, double *C);
SB_VEC_DECLARE(base)
SB_VEC_DECLARE(avx2)
SB_VEC_DECLARE(avx512)
/* hess (3k x 3k) += sign * the products, exactly symmetric */
void sb_elem_scatter(int k, int kp, const sb_shell_batch *w, double *hess, double sign);
/* C (n x n, n <= 6) positive definite?  And C <- its PSD part. */
int sb_elem_pos_def(int n, const double *C);
void sb_elem_psd_part(int n, double *C);
/* the negative eigenvalues of the symmetric n x n C (n <= 6) and their unit
 * eigenvectors (rows of vec); returns how many */
int sb_elem_neg_eig(int n, const double *C, double *lam, double *vec);

#endif
