/* sb_shell_elem_psd.c — Hessian kind PSD with the fast kernel (issue 30):
 * the strain-space projections of the section tangent and the membrane
 * stress, and sb_shell_element_psd, which keeps an element Hessian that is
 * already PSD (sb_psd_check) and otherwise subtracts from the exact one
 * what the strain-space projection removes (docs/performance.md, "PSD
 * Hessians"). */
#include "sb_shell_batch.h"

#include <math.h>
#include <string.h>

/* ---- section tangent and membrane stress projections (kind PSD) ---------- */

/* Eigenvalues of the symmetric n x n A (row-major, n <= 6) by cyclic Jacobi
 * rotations; V (n x n, row-major) gets the eigenvectors as columns. */
static void jacobi_eig(int n, double *A, double *V)
{
    for (int i = 0; i < n * n; i++) V[i] = 0.0;
    for (int i = 0; i < n; i++) V[i * n + i] = 1.0;
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = 0.0, diag = 0.0;
        for (int i = 0; i < n; i++) {
            diag += A[i * n + i] * A[i * n + i];
            for (int j = i + 1; j < n; j++) off += A[i * n + j] * A[i * n + j];
        }
        if (!(off > 1e-30 * diag)) break;   /* converged to ~1e-15 relative (also for NaN: give up) */
        for (int p = 0; p < n; p++)
            for (int q = p + 1; q < n; q++) {
                const double apq = A[p * n + q];
                if (apq == 0.0) continue;
                /* Golub & Van Loan, Algorithm 8.4.1 (symmetric Schur 2 x 2) */
                const double tau = (A[q * n + q] - A[p * n + p]) / (2.0 * apq);
                const double t = (tau >= 0 ? 1.0 : -1.0) / (fabs(tau) + sqrt(1.0 + tau * tau));
                const double c = 1.0 / sqrt(1.0 + t * t), s = t * c;
                for (int k = 0; k < n; k++) {   /* A <- A J (columns p, q) */
                    const double akp = A[k * n + p], akq = A[k * n + q];
                    A[k * n + p] = c * akp - s * akq;
                    A[k * n + q] = s * akp + c * akq;
                }
                for (int k = 0; k < n; k++) {   /* A <- J^T A (rows p, q) */
                    const double apk = A[p * n + k], aqk = A[q * n + k];
                    A[p * n + k] = c * apk - s * aqk;
                    A[q * n + k] = s * apk + c * aqk;
                }
                for (int k = 0; k < n; k++) {
                    const double vkp = V[k * n + p], vkq = V[k * n + q];
                    V[k * n + p] = c * vkp - s * vkq;
                    V[k * n + q] = s * vkp + c * vkq;
                }
            }
    }
}

/* 1 when the LDL^T pivots of the symmetric n x n C (n <= 6) are all
 * positive: C is positive definite */
int sb_elem_pos_def(int n, const double *C)
{
    double L[36];
    memcpy(L, C, sizeof(double) * n * n);
    for (int j = 0; j < n; j++) {
        const double piv = L[j * n + j];
        if (!(piv > 0.0)) return 0;
        for (int i = j + 1; i < n; i++) {
            const double l = L[i * n + j] / piv;
            for (int k = j + 1; k <= i; k++) L[i * n + k] -= l * L[k * n + j];
            L[i * n + j] = l;
        }
    }
    return 1;
}

/* C (n x n symmetric, n <= 6) <- its positive semidefinite part.  A matrix
 * whose LDL^T pivots are all positive is positive definite and kept as it
 * is (every StVK section, denim where it is convex). */
void sb_elem_psd_part(int n, double *C)
{
    if (sb_elem_pos_def(n, C)) return;
    double A[36], V[36];
    memcpy(A, C, sizeof(double) * n * n);
    jacobi_eig(n, A, V);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double s = 0.0;
            for (int l = 0; l < n; l++) {
                const double lam = A[l * n + l];
                if (lam > 0.0) s += V[i * n + l] * lam * V[j * n + l];
            }
            C[i * n + j] = s;
        }
}

int sb_elem_neg_eig(int n, const double *C, double *lam, double *vec)
{
    double A[36], V[36];
    memcpy(A, C, sizeof(double) * n * n);
    jacobi_eig(n, A, V);
    int m = 0;
    for (int l = 0; l < n; l++)
        if (A[l * n + l] < 0.0) {
            lam[m] = A[l * n + l];
            for (int i = 0; i < n; i++) vec[n * m + i] = V[i * n + l];
            m++;
        }
    return m;
}

/* the Z rows of one point in the 3-slot jet (x,1 x,2 mu); the (mu, mu)
 * block is zero, so the mu row has 2 terms */
static void zrows3(double Kd[9][9], double *const *u, int kp, double *Z0, size_t zstride)
{
    for (int pr = 0; pr < 6; pr++) {
        const int cc = pc[pr], d = pd[pr];
#pragma GCC unroll 3
        for (int s = 0; s < 3; s++) {
            sb_vd kv[3];
#pragma GCC unroll 3
            for (int t = 0; t < 3; t++) kv[t] = sb_vbcast(s <= t ? Kd[3 * s + cc][3 * t + d] : Kd[3 * t + d][3 * s + cc]);
            double *zs = Z0 + pr * zstride + (size_t)s * kp;
            if (s < 2)
                for (int J = 0; J < kp; J += SB_VL)
                    sb_vstore(zs + J, kv[0] * sb_vload(u[0] + J) + kv[1] * sb_vload(u[1] + J) +
                                          kv[2] * sb_vload(u[2] + J));
            else
                for (int J = 0; J < kp; J += SB_VL)
                    sb_vstore(zs + J, kv[0] * sb_vload(u[0] + J) + kv[1] * sb_vload(u[1] + J));
        }
    }
}

static void psd_difference(int nq, const sb_shell_basis *b, sb_shell_batch *w, double *hess)
{
    const int k = b[0].k, kp = sb_elem_round_up(k, KPAD), n3 = 3 * k, n3p = 3 * kp;
    const size_t zstride = (size_t)5 * w->nqmax * kp;
    /* 1. the membrane and bending part of every point: 3-slot jet */
    int row = 0;
    for (int p = 0; p < nq; p++) {
        const double *kd = w->kd + (size_t)KD * p, *h = kd + 45;
        double *u[3];
        for (int s = 0; s < 3; s++) u[s] = w->Wt + (size_t)(row + s) * kp;
        for (int I = 0; I < kp; I++) {
            u[0][I] = I < k ? b[p].N1[I] : 0.0;
            u[1][I] = I < k ? b[p].N2[I] : 0.0;
            /* bending component i = 0, 1, 2 is x,11, x,22, x,12 (sb_shell.c bslot) */
            u[2][I] = I < k ? h[0] * b[p].N11[I] + h[1] * b[p].N22[I] + h[2] * b[p].N12[I] : 0.0;
        }
        if (sb_elem_wants_broadcast(w))
            for (int s = 0; s < 3; s++) {
                double *rb = w->Wb + (size_t)2 * (row + s) * kp;
                for (int I = 0; I < kp; I++) sb_store_pair(rb + 2 * I, u[s][I]);
            }
        /* the point's difference matrix, blocks on and above the block diagonal:
         * 3-slot (s, t): (0,0) B11, (0,1) B12, (0,2) M1, (1,1) B22, (1,2) -M2, (2,2) 0 */
        double Kd[9][9];
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                Kd[a][c] = kd[3 * a + c];
                Kd[a][3 + c] = kd[9 + 3 * a + c];
                Kd[a][6 + c] = kd[27 + 3 * a + c];
                Kd[3 + a][3 + c] = kd[18 + 3 * a + c];
                Kd[3 + a][6 + c] = kd[36 + 3 * a + c];
                Kd[6 + a][6 + c] = 0.0;
            }
        zrows3(Kd, u, kp, w->Z + (size_t)row * kp, zstride);
        row += 3;
    }
    sb_elem_products(row, kp, w);
    sb_elem_scatter(k, kp, w, hess, -1.0);

    /* 2. the clamped section tangents: hess += sum g g^T over the rank-1
     * terms, g_(I,c) = sum_s W_s^I u_l[s][c] (3k, padded to 3 kp), as one
     * Gram product G^T G; h_i h_j = h_j h_i, so the result is exactly
     * symmetric */
    int ng = 0;
    for (int p = 0; p < nq; p++) {
        const double *kd = w->kd + (size_t)KD * p;
        if (kd[KD - 1] != 0.0) continue;
        const double *src[5] = { b[p].N1, b[p].N2, b[p].N11, b[p].N12, b[p].N22 };
        for (int l = 0; l < (int)kd[48]; l++, ng++) {
            const double *ul = kd + 49 + 15 * l;
            double *g = w->G + (size_t)ng * n3p;
            for (int I = 0; I < k; I++)
                for (int c = 0; c < 3; c++)
                    g[3 * I + c] = src[0][I] * ul[c] + src[1][I] * ul[3 + c] + src[2][I] * ul[6 + c] +
                                   src[3][I] * ul[9 + c] + src[4][I] * ul[12 + c];
            for (int i = n3; i < n3p; i++) g[i] = 0.0;
            if (sb_elem_wants_broadcast(w)) {
                double *gb = w->Gb + (size_t)2 * ng * n3p;
                for (int i = 0; i < n3p; i++) sb_store_pair(gb + 2 * i, g[i]);
            }
        }
    }
    if (ng == 0) return;
    sb_elem_gram(ng, n3p, w);
    for (int i = 0; i < n3; i++) {
        const double *ci = w->C3 + (size_t)i * n3p;
        double *hi = hess + (size_t)i * n3;
        for (int j = i + 1; j < n3; j++) hess[(size_t)j * n3 + i] += ci[j];
        int j = i;
        for (; j + SB_VL <= n3; j += SB_VL) sb_vstore(hi + j, sb_vload(hi + j) + sb_vload(ci + j));
        for (; j < n3; j++) hi[j] += ci[j];
    }
}

/* kind PSD with the fast kernel (issue 30; see sb_shell.h) */
double sb_shell_element_psd(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,
                            const double *q, double *grad, double *hess, const double *Kx, int kx_used,
                            sb_shell_batch *w, double *work, int *path)
{
    int pth = 0;
    if (!w || !hess || !b || nq < 1 || nq > w->nqmax) {
        if (path) *path = -1;
        return NAN;
    }
    w->keep = 1;
    w->store = 0;
    const double e = sb_elem_element(m, nq, r, b, q, grad, hess, SB_HESS_EXACT, w);
    w->keep = 0;
    const int n = 3 * b[0].k;
    if (kx_used)
        for (size_t i = 0; i < (size_t)n * n; i++) hess[i] += Kx[i];
    if (!isfinite(e) || sb_psd_check(n, hess, work)) {
        pth = 0;   /* PSD already: kept exactly (or non-finite: reported by the energy) */
    } else if (!kx_used || sb_psd_check(n, Kx, work)) {
        /* the other terms are PSD: the shell part by the strain-space projection */
        psd_difference(nq, b, w, hess);
        pth = 1;
    } else {
        sb_psd_project(n, hess, work);   /* indefinite other terms: clamp the whole element */
        pth = 2;
    }
    if (path) *path = pth;
    return e;
}
