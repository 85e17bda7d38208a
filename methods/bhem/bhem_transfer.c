/* bhem_transfer.c — nested hierarchy by uniform refinement of the patch grid.
 *
 * Prolongation I: the fine generalized coordinates are the values and
 * (patch-scaled) derivatives of the coarse Hermite interpolant at the fine
 * nodes.  Bicubic Hermite spaces on a uniformly refined grid are nested, so
 * I reproduces the coarse surface exactly.  Per direction, a fine node sits
 * at local coordinate th in {0, 1/2, 1} of a coarse patch and
 *   x_f       = sum_{p,r} w_{p,r}(th)        q_c(p,r)      (BHEM Eq. 31)
 *   h_f x_f,s = sum_{p,r} 1/2 w'_{p,r}(th)   q_c(p,r)      (Eq. 34; h_f = h_c/2)
 * and the 2D operator is the tensor product of the two 1D stencils.
 * Restriction R = I^T.  Projection P = injection at the coarse nodes (with the
 * derivative scaling undone: x 1, derivatives x2, mixed x4), so P I = id. */
#include "bhem.h"
#include "sb_galerkin.h"

#include <stdlib.h>
#include <string.h>

typedef struct st1 { int idx, ord; double w; } st1;

/* 1D stencil of fine grid index i_f, derivative order rf, coarse patches nc */
static int stencil_1d(int i_f, int rf, int nc, st1 out[4])
{
    int ic = i_f / 2;
    if (ic > nc - 1) ic = nc - 1;
    double th = 0.5 * i_f - ic;
    int n = 0;
    for (int p = 0; p < 2; p++)
        for (int r = 0; r < 2; r++) {
            double w, dw;
            bhem_hermite_1d(p, r, th, &w, &dw, NULL);
            double v = rf ? 0.5 * dw : w;
            if (v == 0.0) continue;
            out[n].idx = ic + p;
            out[n].ord = r;
            out[n].w = v;
            n++;
        }
    return n;
}

int bhem_transfer_build(bhem_state *S, int lc)
{
    bhem_level *C = &S->lv[lc], *F = &S->lv[lc + 1];
    int rows = 4 * F->n_nodes;
    C->p_ptr = malloc(sizeof(int) * (size_t)(rows + 1));
    C->p_col = malloc(sizeof(int) * (size_t)rows * 16);
    C->p_w = malloc(sizeof(double) * (size_t)rows * 16);
    if (!C->p_ptr || !C->p_col || !C->p_w) return SB_ERR_NOMEM;
    int nz = 0;
    C->p_ptr[0] = 0;
    for (int nf = 0; nf < F->n_nodes; nf++)
        for (int kind = 0; kind < 4; kind++) {
            int rf = kind & 1, sf = kind >> 1;
            st1 a[4], b[4];
            int na = stencil_1d(F->node_i[nf], rf, C->n1, a);
            int nb = stencil_1d(F->node_j[nf], sf, C->n2, b);
            for (int jb = 0; jb < nb; jb++)
                for (int ia = 0; ia < na; ia++) {
                    int node = bhem_node_at(S, C, a[ia].idx, b[jb].idx);
                    if (node < 0)
                        return bhem_fail(S, SB_ERR_INTERNAL, "prolongation: coarse node (%d,%d) of level %d is inactive",
                                         a[ia].idx, b[jb].idx, lc);
                    C->p_col[nz] = 4 * node + a[ia].ord + 2 * b[jb].ord;
                    C->p_w[nz] = a[ia].w * b[jb].w;
                    nz++;
                }
            C->p_ptr[4 * nf + kind + 1] = nz;
        }
    return SB_OK;
}

int bhem_prolong(const bhem_state *S, int lc, const double *xc, double *xf)
{
    const bhem_level *C = &S->lv[lc];
    int rows = 4 * S->lv[lc + 1].n_nodes;
    for (int r = 0; r < rows; r++) {
        double v[3] = { 0, 0, 0 };
        for (int k = C->p_ptr[r]; k < C->p_ptr[r + 1]; k++) {
            const double *q = xc + 3 * C->p_col[k];
            for (int c = 0; c < 3; c++) v[c] += C->p_w[k] * q[c];
        }
        for (int c = 0; c < 3; c++) xf[3 * r + c] = v[c];
    }
    return SB_OK;
}

int bhem_restrict(const bhem_state *S, int lc, const double *gf, double *gc)
{
    const bhem_level *C = &S->lv[lc];
    int rows = 4 * S->lv[lc + 1].n_nodes;
    for (int k = 0; k < C->n_dofs; k++) gc[k] = 0.0;
    for (int r = 0; r < rows; r++)
        for (int k = C->p_ptr[r]; k < C->p_ptr[r + 1]; k++) {
            double *q = gc + 3 * C->p_col[k];
            for (int c = 0; c < 3; c++) q[c] += C->p_w[k] * gf[3 * r + c];
        }
    return SB_OK;
}

int bhem_project(const bhem_state *S, int lc, const double *xf, double *xc)
{
    const bhem_level *C = &S->lv[lc], *F = &S->lv[lc + 1];
    static const double scale[4] = { 1.0, 2.0, 2.0, 4.0 };
    for (int nc = 0; nc < C->n_nodes; nc++) {
        int nf = bhem_node_at(S, F, 2 * C->node_i[nc], 2 * C->node_j[nc]);
        if (nf < 0) return bhem_fail(S, SB_ERR_INTERNAL, "projection: fine node of coarse node %d is inactive", nc);
        for (int k = 0; k < 12; k++) xc[12 * nc + k] = scale[k / 3] * xf[12 * nf + k];
    }
    return SB_OK;
}

/* I as a dof-level matrix (sb_method_type.prolong_matrix, for Galerkin
 * coarse Hessians and pcg-mg): row 3r + c holds the weights of the stencil
 * of fine row r on the coarse dofs 3 p_col[k] + c.  Exactly what probing
 * prolong() with unit vectors gives (sb_problem.c, the fallback), so the
 * Galerkin products do not move: columns increasing within a row, weights
 * of a repeated coarse dof (periodic seams) summed in stencil order from
 * +0, exact zeros left out; in O(nnz) instead of O(n_c n_f). */
int bhem_prolong_matrix(const bhem_state *S, int lc, sb_csr *I)
{
    const bhem_level *C = &S->lv[lc];
    const int rows = 4 * S->lv[lc + 1].n_nodes;
    const long nz = C->p_ptr[rows];
    int rc = sb_csr_alloc(I, 3 * rows, C->n_dofs, 3 * nz);
    if (rc) return rc;
    long q = 0;
    for (int r = 0; r < rows; r++) {
        const int k0 = C->p_ptr[r], k1 = C->p_ptr[r + 1];
        for (int c = 0; c < 3; c++) {
            /* the stencil's coarse nodes in increasing order (insertion sort,
             * stable: equal columns keep stencil order), summed, zeros out */
            int ord[16], m = 0;
            for (int k = k0; k < k1 && m < 16; k++) {
                int j = m;
                while (j > 0 && C->p_col[ord[j - 1]] > C->p_col[k]) { ord[j] = ord[j - 1]; j--; }
                ord[j] = k;
                m++;
            }
            for (int a = 0; a < m;) {
                const int col = C->p_col[ord[a]];
                double v = 0.0;
                for (; a < m && C->p_col[ord[a]] == col; a++) v += C->p_w[ord[a]];
                if (v == 0.0) continue;
                I->ci[q] = 3 * col + c;
                I->v[q++] = v;
            }
            I->rp[3 * r + c + 1] = q;
        }
    }
    return SB_OK;
}
