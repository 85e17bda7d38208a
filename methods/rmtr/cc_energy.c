/* cc_energy.c — energy, gradient, Hessian and mass of one level of the
 * rmtr method.  Per element (domain face, 16 control points when regular,
 * 2n+8 next to one extraordinary vertex of valence n):
 *   Kirchhoff–Love elastic energy (RMTR paper (3.2)–(3.3), shared kernel
 *   core/shell/sb_shell.h), gravity and pressure (sb_shell_external),
 *   boundary penalty (3.6) and line/point loads (cc_penalty.c).
 * The core adds inertia and damping (DESIGN.md).  Element buffers are
 * allocated once in the method state; nothing is allocated in these loops. */
#include "cc_method.h"

#include <math.h>
#include <string.h>

int cc_energy(cc_state *S, int l, const double *x, double *f, double *g, sb_matrix *H)
{
    const sb_scene *sc = S->scene;
    cc_level *L = &S->lv[l];
    const cc_quad *Q = &L->quad;
    double gvec[3] = { 0, 0, 0 };
    int has_g = 0, has_p = 0;
    for (int i = 0; i < sc->n_loads; i++) {
        const sb_load *ld = &sc->loads[i];
        if (ld->kind == SB_LOAD_GRAVITY) {
            for (int c = 0; c < 3; c++) gvec[c] += S->load_factor[i] * ld->vec[c];
            has_g = 1;
        }
        has_p |= ld->kind == SB_LOAD_PRESSURE;
    }
    sb_hess_kind hk = S->hess == SB_HESS_PSD ? SB_HESS_EXACT : S->hess;
    double E = 0;
    for (int el = 0; el < Q->ne; el++) {
        const int *nd = Q->enode + Q->eoff[el];
        int k = Q->eoff[el + 1] - Q->eoff[el], n = 3 * k;
        double *qe = S->qe, *ge = g ? S->ge : NULL, *Ke = H ? S->Ke : NULL;
        for (int a = 0; a < k; a++) memcpy(qe + 3 * a, x + 3 * nd[a], 3 * sizeof(double));
        if (ge) memset(ge, 0, (size_t)n * sizeof *ge);
        if (Ke) memset(Ke, 0, (size_t)n * n * sizeof *Ke);
        for (int q = 0; q < Q->nq; q++) {
            sb_shell_basis b = cc_quad_basis(Q, el, q);
            const sb_shell_ref *r = &L->ref[(size_t)el * Q->nq + q];
            E += sb_shell_energy(&S->mat, r, &b, qe, ge, Ke, hk, S->work);
            if (has_g) E += sb_shell_external(&S->mat, r, &b, qe, gvec, 0.0, 0, ge, NULL);
            if (has_p)
                for (int i = 0; i < sc->n_loads; i++)
                    if (sc->loads[i].kind == SB_LOAD_PRESSURE)
                        E += sb_shell_external(&S->mat, r, &b, qe, NULL, S->load_factor[i] * sc->loads[i].value,
                                               sc->loads[i].follower, ge, Ke);
        }
        E += cc_points_energy(S, L, el, qe, ge, Ke);
        if (ge)
            for (int a = 0; a < k; a++)
                for (int c = 0; c < 3; c++) g[3 * nd[a] + c] += ge[3 * a + c];
        if (Ke) {
            if (S->hess == SB_HESS_PSD) sb_psd_project(n, Ke, S->psd);
            sb_matrix_add_element(H, el, Ke);
        }
    }
    *f = E;
    if (!isfinite(E)) return SB_NONFINITE;
    if (g && !sb_all_finite(3 * L->nv, g)) return SB_NONFINITE;
    return SB_OK;
}

/* M = int rho N_I N_J dA I_3 (consistent; the paper does not state its mass
 * matrix), or its row-sum lumping (subdivision basis functions are >= 0, so
 * the lumped mass is positive). */
int cc_mass(cc_state *S, int l, sb_matrix *M)
{
    cc_level *L = &S->lv[l];
    const cc_quad *Q = &L->quad;
    double rho = S->mat.density;
    for (int el = 0; el < Q->ne; el++) {
        int k = Q->eoff[el + 1] - Q->eoff[el], n = 3 * k;
        double *Me = S->Ke;
        memset(Me, 0, (size_t)n * n * sizeof *Me);
        for (int q = 0; q < Q->nq; q++) {
            sb_shell_basis b = cc_quad_basis(Q, el, q);
            double dA = L->ref[(size_t)el * Q->nq + q].dA;
            for (int a = 0; a < k; a++)
                for (int c = 0; c < k; c++) {
                    double m = rho * b.N[a] * b.N[c] * dA;
                    for (int d = 0; d < 3; d++) Me[(3 * a + d) * n + 3 * c + d] += m;
                }
        }
        if (S->lumped)
            for (int i = 0; i < n; i++) {
                double s = 0;
                for (int j = 0; j < n; j++) {
                    s += Me[i * n + j];
                    if (j != i) Me[i * n + j] = 0;
                }
                Me[i * n + i] = s;
            }
        sb_matrix_add_element(M, el, Me);
    }
    return SB_OK;
}

/* Where x strains the material (sb_material_state): every quadrature point
 * of every element, with the kernel's own strains. */
int cc_material_state(cc_state *S, int l, const double *x, sb_material_state *ms)
{
    cc_level *L = &S->lv[l];
    const cc_quad *Q = &L->quad;
    sb_material_state_init(ms);
    int status = SB_OK;
    for (int el = 0; el < Q->ne; el++) {
        const int *nd = Q->enode + Q->eoff[el];
        int k = Q->eoff[el + 1] - Q->eoff[el];
        for (int a = 0; a < k; a++) memcpy(S->qe + 3 * a, x + 3 * nd[a], 3 * sizeof(double));
        for (int q = 0; q < Q->nq; q++) {
            sb_shell_basis b = cc_quad_basis(Q, el, q);
            const sb_shell_ref *r = &L->ref[(size_t)el * Q->nq + q];
            if (sb_material_state_add(ms, &S->mat, r, &b, S->qe, S->work)) status = SB_NONFINITE;
        }
    }
    return status;
}
