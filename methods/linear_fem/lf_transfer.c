/* lf_transfer.c — the nested hierarchy of 1-to-4 refined meshes.
 *
 * Prolongation I (coarse -> fine, stored per fine level as rows of fine dofs):
 *   positions: a coarse vertex keeps its value, an edge midpoint gets the mean
 *   of the edge's ends (linear interpolation in (s,t): exact on the coarse
 *   space, which the fine mesh reproduces triangle by triangle);
 *   edge directors: the two halves of a coarse edge inherit its phi (the fine
 *   face normals there are the coarse ones, so the fine midedge normal equals
 *   the coarse one); an edge inside a coarse triangle C (joining the
 *   midpoints of edges j and k) gets the tilt of the coarse Crouzeix–Raviart
 *   normal field at its midpoint, n = (n_j + n_k)/2, linearised and restricted
 *   to the director part: phi_f = 1/2 sum_{j'} sigma_{C,j'} (m_j' . m_f) phi_j'
 *   (m the reference outward in-plane edge normals; the dihedral part of the
 *   coarse angles is not linear in the dofs and is left to the fine level).
 * Restriction R = I^T.  Projection P = injection: coarse vertices are fine
 * vertices with the same index, a coarse director is read from the first half
 * of its edge; so P I = id. */
#include "sb_vec3.h"
#include "lf.h"
#include "sb_galerkin.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


/* outward in-plane unit normal of the side running Xa -> Xb of a triangle with unit normal N */
static void side_normal(const double *Xa, const double *Xb, const double *N, double m[3])
{
    double t[3];
    for (int c = 0; c < 3; c++) t[c] = Xb[c] - Xa[c];
    const double l = sqrt(sb_dot3(t, t));
    for (int c = 0; c < 3; c++) t[c] /= l;
    sb_cross3(t, N, m);
}

int lf_transfer_build(lf_state *S, int l)
{
    lf_level *F = &S->lv[l];
    const lf_level *C = &S->lv[l - 1];
    const sb_mesh_refinement *r = &F->rf;
    const sb_mesh *mc = &C->mesh, *mf = &F->mesh;
    const long cap = 2L * F->n_dofs + 1;
    F->p_ptr = malloc(sizeof(int) * (size_t)(F->n_dofs + 1));
    F->p_col = malloc(sizeof(int) * (size_t)cap);
    F->p_w = malloc(sizeof(double) * (size_t)cap);
    if (!F->p_ptr || !F->p_col || !F->p_w) return SB_ERR_NOMEM;
    int nz = 0;
    F->p_ptr[0] = 0;
    for (int v = 0; v < F->nv; v++)
        for (int c = 0; c < 3; c++) {
            if (v < r->nv_c) {
                F->p_col[nz] = 3 * v + c;
                F->p_w[nz++] = 1.0;
            } else {
                const int e = v - r->nv_c;
                F->p_col[nz] = 3 * mc->edge_v[2 * e] + c;
                F->p_w[nz++] = 0.5;
                F->p_col[nz] = 3 * mc->edge_v[2 * e + 1] + c;
                F->p_w[nz++] = 0.5;
            }
            F->p_ptr[3 * v + c + 1] = nz;
        }
    if (S->edge_dofs)
        for (int f = 0; f < F->ne; f++) {
            const int row = 3 * F->nv + f;
            if (r->edge_parent[f] >= 0) {
                F->p_col[nz] = 3 * C->nv + r->edge_parent[f];
                F->p_w[nz++] = 1.0;
            } else if (r->edge_tri[f] >= 0 && r->edge_corner[f] >= 0) {
                const lf_tri *T = &C->tri[r->edge_tri[f]];
                const int l0 = r->edge_corner[f];
                /* m_f: outward normal of f in its first fine triangle */
                const int tf = mf->edge_t[2 * f];
                double mfv[3];
                side_normal(mf->X + 3 * mf->edge_v[2 * f], mf->X + 3 * mf->edge_v[2 * f + 1], F->tri[tf].ref.normal, mfv);
                for (int jj = 1; jj <= 2; jj++) {
                    const int j = (l0 + jj) % 3;
                    double mj[3];
                    side_normal(mc->X + 3 * T->v[(j + 1) % 3], mc->X + 3 * T->v[(j + 2) % 3], T->ref.normal, mj);
                    F->p_col[nz] = 3 * C->nv + T->e[j];
                    F->p_w[nz++] = 0.5 * T->sigma[j] * sb_dot3(mj, mfv);
                }
            }
            F->p_ptr[row + 1] = nz;
        }
    /* columns increasing within each row (sb_galerkin.h reads rows in order) */
    for (int i = 0; i < F->n_dofs; i++)
        for (int k = F->p_ptr[i] + 1; k < F->p_ptr[i + 1]; k++)
            for (int j = k; j > F->p_ptr[i] && F->p_col[j - 1] > F->p_col[j]; j--) {
                const int tc = F->p_col[j];
                const double tw = F->p_w[j];
                F->p_col[j] = F->p_col[j - 1];
                F->p_w[j] = F->p_w[j - 1];
                F->p_col[j - 1] = tc;
                F->p_w[j - 1] = tw;
            }
    return SB_OK;
}

int lf_prolong(const lf_state *S, int lc, const double *xc, double *xf)
{
    const lf_level *F = &S->lv[lc + 1];
    for (int i = 0; i < F->n_dofs; i++) {
        double v = 0.0;
        for (int k = F->p_ptr[i]; k < F->p_ptr[i + 1]; k++) v += F->p_w[k] * xc[F->p_col[k]];
        xf[i] = v;
    }
    return SB_OK;
}

int lf_restrict(const lf_state *S, int lc, const double *gf, double *gc)
{
    const lf_level *F = &S->lv[lc + 1];
    memset(gc, 0, sizeof(double) * (size_t)S->lv[lc].n_dofs);
    for (int i = 0; i < F->n_dofs; i++)
        for (int k = F->p_ptr[i]; k < F->p_ptr[i + 1]; k++) gc[F->p_col[k]] += F->p_w[k] * gf[i];
    return SB_OK;
}

int lf_project(const lf_state *S, int lc, const double *xf, double *xc)
{
    const lf_level *C = &S->lv[lc], *F = &S->lv[lc + 1];
    memcpy(xc, xf, sizeof(double) * 3 * (size_t)C->nv);
    if (S->edge_dofs)
        for (int e = 0; e < C->ne; e++) xc[3 * C->nv + e] = xf[3 * F->nv + F->rf.edge_half[2 * e]];
    return SB_OK;
}

int lf_prolong_matrix(const lf_state *S, int lc, sb_csr *I)
{
    const lf_level *F = &S->lv[lc + 1];
    const long nnz = F->p_ptr[F->n_dofs];
    int rc = sb_csr_alloc(I, F->n_dofs, S->lv[lc].n_dofs, nnz);
    if (rc) return rc;
    for (int i = 0; i <= F->n_dofs; i++) I->rp[i] = F->p_ptr[i];
    memcpy(I->ci, F->p_col, sizeof(int) * (size_t)nnz);
    memcpy(I->v, F->p_w, sizeof(double) * (size_t)nnz);
    return SB_OK;
}
