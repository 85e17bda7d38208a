/* bhem_energy.c — E = E_elastic + E_external and its gradient / Hessian,
 * assembled patch by patch through the shared Kirchhoff–Love kernel
 * (BHEM paper Eq. 7-8 energy, App. B derivatives, §6.1 exact / pseudo
 * Hessian), 4x4 Gauss points per patch (App. A). */
#include "bhem.h"

#include <math.h>
#include <string.h>

int bhem_energy(bhem_state *S, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    bhem_level *L = &S->lv[level];
    const sb_scene *sc = S->scene;
    if (L->rebranch) {
        /* first evaluation of a step: re-centre the end-moment angle branches */
        if (L->n_mq) bhem_moment_rebranch(S, L, x);
        L->rebranch = 0;
    }
    /* follower pressure: summed over loads, through the kernel's potential */
    double p_follow = 0.0;
    for (int k = 0; k < sc->n_loads; k++)
        if (sc->loads[k].kind == SB_LOAD_PRESSURE && sc->loads[k].follower)
            p_follow += S->load_factor[k] * sc->loads[k].value;
    const double gzero[3] = { 0.0, 0.0, 0.0 };
    sb_hess_kind kind = S->hess == SB_HESS_PSD ? SB_HESS_EXACT : S->hess;
    double *ge = (g || H) ? S->ge : NULL, *Ke = H ? S->Ke : NULL;
    double *qe = S->qe;
    double E = 0.0;
    for (int e = 0; e < L->n_elems; e++) {
        bhem_gather(L, e, x, qe);
        if (ge) memset(ge, 0, sizeof S->ge);
        if (Ke) memset(Ke, 0, sizeof(double) * BHEM_NED * BHEM_NED);
        const sb_shell_ref *ref = L->ref + (size_t)e * BHEM_NQP;
        for (int q = 0; q < BHEM_NQP; q++) {
            const bhem_qp_basis *B = &L->qb[q];
            sb_shell_basis b = { BHEM_NB, B->N, B->N1, B->N2, B->N11, B->N12, B->N22 };
            E += sb_shell_energy(&S->mat, &ref[q], &b, qe, ge, Ke, kind, S->work);
            if (p_follow != 0.0) E += sb_shell_external(&S->mat, &ref[q], &b, qe, gzero, p_follow, 1, ge, Ke);
        }
        if (L->n_mq) E += bhem_moment_element(S, L, e, qe, ge, Ke);
        if (Ke && S->hess == SB_HESS_PSD) sb_psd_project(BHEM_NED, Ke, S->psd_work);
        const int *d = L->elem_dofs + (size_t)e * BHEM_NED;
        if (g)
            for (int a = 0; a < BHEM_NED; a++) g[d[a]] += ge[a];
        if (Ke) sb_matrix_add_element(H, e, Ke);
    }
    /* dead loads: E_ext = -f_ext . (x - x_ref) (BHEM Eq. 19 and 21); measured
     * from the reference so that f carries no large constant (the f-tests of
     * RMTR Eq. 7.1 compare energy differences) */
    double Eext = 0.0;
    for (int i = 0; i < L->n_dofs; i++) Eext -= L->f_ext[i] * (x[i] - L->x_ref[i]);
    E += Eext;
    if (g) sb_axpy(L->n_dofs, -1.0, L->f_ext, g);
    *f = E;
    if (!isfinite(E)) return SB_NONFINITE;
    if (g && !sb_all_finite(L->n_dofs, g)) return SB_NONFINITE;
    return SB_OK;
}

/* Where x strains the material (sb_material_state): every Gauss point of
 * every patch, with the kernel's own strains. */
int bhem_material_state(bhem_state *S, int level, const double *x, sb_material_state *ms)
{
    bhem_level *L = &S->lv[level];
    sb_material_state_init(ms);
    int status = SB_OK;
    for (int e = 0; e < L->n_elems; e++) {
        bhem_gather(L, e, x, S->qe);
        const sb_shell_ref *ref = L->ref + (size_t)e * BHEM_NQP;
        for (int q = 0; q < BHEM_NQP; q++) {
            const bhem_qp_basis *B = &L->qb[q];
            sb_shell_basis b = { BHEM_NB, B->N, B->N1, B->N2, B->N11, B->N12, B->N22 };
            if (sb_material_state_add(ms, &S->mat, &ref[q], &b, S->qe, S->work)) status = SB_NONFINITE;
        }
    }
    return status;
}
