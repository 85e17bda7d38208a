/* lf_energy.c — E = E_elastic + E_external of linear_fem with its gradient
 * and Hessian, assembled element by element: the triangle elements
 * (membrane, midedge bending, follower pressure, end moments), then the
 * hinges of the hinge model, then the dead loads.  Optional per-element PSD
 * projection (method.hessian = psd). */
#include "lf.h"

#include <math.h>
#include <string.h>

int lf_energy(lf_state *S, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    lf_level *L = &S->lv[level];
    if (L->rebranch) {
        if (L->n_mq) lf_moment_rebranch(S, L, x);
        L->rebranch = 0;
    }
    const int n = lf_ned(S);
    double *qe = S->qe, *ge = (g || H) ? S->ge : NULL, *Ke = H ? S->Ke : NULL;
    int d[LF_NED_MAX];
    double E = 0.0;
    for (int t = 0; t < L->nt; t++) {
        lf_tri_dofs(S, L, t, d);
        for (int a = 0; a < n; a++) qe[a] = d[a] >= 0 ? x[d[a]] : 0.0;
        if (ge) memset(ge, 0, sizeof(double) * (size_t)n);
        if (Ke) memset(Ke, 0, sizeof(double) * (size_t)n * n);
        E += lf_tri_energy(S, L, t, qe, ge, Ke);
        if (Ke && S->hess == SB_HESS_PSD) sb_psd_project(n, Ke, S->psd_work);
        if (g)
            for (int a = 0; a < n; a++)
                if (d[a] >= 0) g[d[a]] += ge[a];
        if (Ke) sb_matrix_add_element(H, t, Ke);
    }
    for (int h = 0; h < L->n_hinge; h++) {
        const lf_hinge *hg = &L->hinge[h];
        double q[12], g12[12], K12[144];
        for (int s = 0; s < 4; s++)
            for (int c = 0; c < 3; c++) q[3 * s + c] = hg->v[s] >= 0 ? x[3 * hg->v[s] + c] : 0.0;
        if (ge) memset(g12, 0, sizeof g12);
        if (Ke) memset(K12, 0, sizeof K12);
        E += lf_hinge_energy(S, hg, q, ge ? g12 : NULL, Ke ? K12 : NULL);
        if (Ke && S->hess == SB_HESS_PSD) sb_psd_project(12, K12, S->psd_work);
        if (g)
            for (int s = 0; s < 4; s++)
                if (hg->v[s] >= 0)
                    for (int c = 0; c < 3; c++) g[3 * hg->v[s] + c] += g12[3 * s + c];
        if (Ke) sb_matrix_add_element(H, L->nt + h, K12);
    }
    /* dead loads: E_ext = -f_ext . (x - x_ref), measured from the reference (bhem_energy.c) */
    double Eext = 0.0;
    for (int i = 0; i < L->n_dofs; i++) Eext -= L->f_ext[i] * (x[i] - L->x_ref[i]);
    E += Eext;
    if (g) sb_axpy(L->n_dofs, -1.0, L->f_ext, g);
    *f = E;
    if (!isfinite(E)) return SB_NONFINITE;
    if (g && !sb_all_finite(L->n_dofs, g)) return SB_NONFINITE;
    return SB_OK;
}

/* Material state: strains of every triangle (the hinge model's bending
 * strains live on edges and are not included: membrane only). */
int lf_material_state(lf_state *S, int level, const double *x, sb_material_state *ms)
{
    lf_level *L = &S->lv[level];
    sb_material_state_init(ms);
    int status = SB_OK;
    for (int t = 0; t < L->nt; t++) {
        double A[3], B[3];
        lf_gather(S, L, t, x, S->qe);
        int rc = lf_tri_strains(S, L, t, S->qe, A, B);
        if (!rc) rc = sb_material_state_add_strains(ms, &S->mat, L->tri[t].ref.dA, A, B);
        if (rc) status = SB_NONFINITE;
    }
    return status;
}
