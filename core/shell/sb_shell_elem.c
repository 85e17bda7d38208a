/* sb_shell_elem.c — the fast Kirchhoff–Love kernel: energy, gradient and
 * Hessian of a whole element (all its quadrature points at once), the same
 * quantities as summing sb_shell_energy() over the points (sb_shell.c, the
 * reference kernel, whose steps 1–4 and notation this file follows), in
 * another summation order.
 *
 * What it exploits (measured in bench/bench_shell.c, docs/performance.md):
 *
 * 1. Kronecker structure.  With W_p (5 x k) the basis derivative rows
 *    (N1, N2, N11, N12, N22) of point p and K_p (15 x 15) the Hessian in the
 *    local jet y = (x_,1 x_,2 x_,11 x_,12 x_,22), the element Hessian is
 *        H = sum_p (W_p^T (x) I3) K_p (W_p (x) I3),
 *    i.e. for each component pair (c, d) the k x k matrix
 *        H^cd = sum_p W_p^T K_p^cd W_p = Wt^T Z^cd,
 *    with K_p^cd the 5 x 5 block of components (c, d), Wt = [W_1; ...; W_nq]
 *    (5 nq x k) and Z^cd = [K_1^cd W_1; ...] (5 nq x k).  Symmetry: H^dc =
 *    (H^cd)^T, so only the 6 pairs c <= d are formed, and H^cc only on and
 *    above its diagonal tiles.  Per point this is 22.5 k^2 + 150 k
 *    multiply-adds against the reference's 22.5 k^2 + 247.5 k plus 9 k^2
 *    read-modify-writes of the 3k x 3k matrix per point.
 * 2. Batching quadrature points.  The nq points of an element enter one
 *    product Wt^T Z^cd (inner dimension 5 nq: 45 for 3 x 3 Gauss points,
 *    80 for 4 x 4), computed by register-blocked tiles of MR x NR outputs
 *    on vectors of SB_VL doubles (sb_simd.h): no branches and no memory
 *    traffic for the outputs inside the loop over the inner dimension, and
 *    the 3k x 3k element matrix is written once per element, not per point.
 * 3. Sparsity of the strain Jacobian J = d(A, B)/dy (6 x 15: the membrane
 *    rows touch x_,1 and x_,2 only, a bending row x_,1, x_,2 and its own
 *    x_,ab along n), so J^T D J costs ~700 flops instead of ~2,500.
 * 4. Allocation-free: every buffer lives in sb_shell_batch (one per
 *    thread), rows padded with zeros to a multiple of the tile width.
 *
 * Hessian kinds: EXACT and PSEUDO as in sb_shell.c.  PSD here is the
 * strain-space projection (issue 30): per point, the section tangent
 * (6 x 6, material frame) and the membrane stress resultant (2 x 2) are
 * clamped to their positive semidefinite parts and the bending second
 * derivatives are dropped (they have a zero v-v block next to a nonzero
 * x-v block, so they are indefinite whenever a bending moment acts; BHEM
 * paper §6.1 drops them for its pseudo Hessian).  Every point then adds
 * (W (x) I3)^T (J^T D+ J + S+ (x) I3) (W (x) I3), a sum of congruences of
 * PSD matrices: the element Hessian is PSD by construction.  The methods
 * use it only for elements whose exact Hessian fails sb_psd_check(), so
 * that a PSD element Hessian is kept exactly (sb_shell_elem_psd.c). */
#include "sb_shell_batch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const sb_kernel_names[] = { "fast", "reference", NULL };

static void *alloc64(size_t ndouble)
{
    size_t bytes = (ndouble * sizeof(double) + 63) / 64 * 64;
    void *p = aligned_alloc(64, bytes ? bytes : 64);
    if (p) memset(p, 0, bytes ? bytes : 64);
    return p;
}

sb_shell_batch *sb_shell_batch_new(int kmax, int nqmax)
{
    if (kmax < 1 || kmax > SB_SHELL_MAX_BASIS || nqmax < 1 || nqmax > SB_SHELL_MAX_QP) return NULL;
    sb_shell_batch *w = calloc(1, sizeof *w);
    if (!w) return NULL;
    w->kmax = kmax;
    w->nqmax = nqmax;
    w->kpmax = sb_elem_round_up(kmax, KPAD);
    w->isa = sb_shell_isa_best();
    const size_t kp = (size_t)w->kpmax, r = 5 * (size_t)nqmax;
    w->Wt = alloc64(r * kp);
    w->Wb = alloc64(2 * r * kp);
    w->Z = alloc64(6 * r * kp);
    w->Hc = alloc64(6 * kp * kp);
    w->Gt = alloc64(3 * r);
    w->qd = alloc64(3 * kp);
    w->gd = alloc64(3 * kp);
    w->kd = alloc64((size_t)KD * nqmax);
    w->G = alloc64(6 * r / 5 * 3 * kp);
    w->Gb = alloc64(2 * 6 * r / 5 * 3 * kp);
    w->C3 = alloc64(9 * kp * kp);
    if (!w->kd || !w->G || !w->Gb || !w->C3 || !w->Wt || !w->Wb || !w->Z || !w->Hc || !w->Gt || !w->qd || !w->gd) {
        sb_shell_batch_free(w);
        return NULL;
    }
    return w;
}

void sb_shell_batch_free(sb_shell_batch *w)
{
    if (!w) return;
    free(w->Wt);
    free(w->Wb);
    free(w->Z);
    free(w->Hc);
    free(w->Gt);
    free(w->qd);
    free(w->gd);
    free(w->kd);
    free(w->G);
    free(w->Gb);
    free(w->C3);
    free(w);
}

double sb_shell_element(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,
                        const double *q, double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w)
{
    if (w) w->keep = w->store = 0;
    return sb_elem_element(m, nq, r, b, q, grad, hess, kind, w);
}

double sb_shell_element_into(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,
                             const double *q, double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w)
{
    if (!w) return NAN;
    w->keep = 0;
    w->store = 1;
    const double e = sb_elem_element(m, nq, r, b, q, grad, hess, kind, w);
    w->store = 0;
    return e;
}

/* ---- per-thread scratch of a method ------------------------------------------------ */

int sb_elem_scratch_init(sb_elem_scratch *s, int kmax, int nqmax, sb_shell_isa isa)
{
    memset(s, 0, sizeof *s);
    const int n = 3 * kmax;
    s->work = sb_shell_work_new();
    s->batch = sb_shell_batch_new(kmax, nqmax);
    s->qe = calloc((size_t)n, sizeof *s->qe);
    s->Kx = calloc((size_t)n * n, sizeof *s->Kx);
    s->psd = calloc(sb_psd_work_size(n) + 1, sizeof *s->psd);
    s->b = calloc((size_t)nqmax, sizeof *s->b);
    if (!s->work || !s->batch || !s->qe || !s->Kx || !s->psd || !s->b) return SB_ERR_NOMEM;
    return sb_shell_batch_set_isa(s->batch, isa);
}

void sb_elem_scratch_free(sb_elem_scratch *s)
{
    if (!s) return;
    sb_shell_work_free(s->work);
    sb_shell_batch_free(s->batch);
    free(s->qe);
    free(s->Kx);
    free(s->psd);
    free(s->b);
    memset(s, 0, sizeof *s);
}
