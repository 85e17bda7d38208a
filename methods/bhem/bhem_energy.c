/* bhem_energy.c — E = E_elastic + E_external and its gradient / Hessian,
 * assembled patch by patch through the shared Kirchhoff–Love kernel
 * (BHEM paper Eq. 7-8 energy, App. B derivatives, §6.1 exact / pseudo
 * Hessian), 4x4 Gauss points per patch (App. A).  The patch loop runs on
 * run.threads threads through sb_assemble (reduction in patch order:
 * bit-identical results for any count), with method.kernel's kernel: fast
 * (sb_shell_element) or reference (sb_shell_energy per point). */
#include "bhem.h"
#include "sb_assemble.h"

#include <math.h>
#include <string.h>

/* One assembly: what compute() and reduce() share (sb_assemble.h). */
typedef struct bhem_asm {
    bhem_state *S;
    bhem_level *L;
    const double *x;
    double *g;
    sb_matrix *H;
    double p_follow;
    sb_hess_kind kind;          /* EXACT or PSEUDO: PSD is exact here, projected per patch */
    double E;
} bhem_asm;

static void bhem_compute(void *ctx, int thread, int e, sb_elem_out *o)
{
    bhem_asm *a = ctx;
    bhem_state *S = a->S;
    bhem_level *L = a->L;
    sb_elem_scratch *T = &S->tw[thread];
    const double gzero[3] = { 0.0, 0.0, 0.0 };
    double *qe = T->qe, *ge = o->ge, *Ke = o->Ke;
    bhem_gather(L, e, a->x, qe);
    if (ge) memset(ge, 0, sizeof(double) * BHEM_NED);
    if (Ke) memset(Ke, 0, sizeof(double) * BHEM_NED * BHEM_NED);
    const sb_shell_ref *ref = L->ref + (size_t)e * BHEM_NQP;
    int nt = 0;
    if (S->kernel == SB_KERNEL_REFERENCE) {
        /* per point: the arithmetic and term order of the committed records */
        for (int q = 0; q < BHEM_NQP; q++) {
            const bhem_qp_basis *B = &L->qb[q];
            sb_shell_basis b = { BHEM_NB, B->N, B->N1, B->N2, B->N11, B->N12, B->N22 };
            o->terms[nt++] = sb_shell_energy(&S->mat, &ref[q], &b, qe, ge, Ke, a->kind, T->work);
            if (a->p_follow != 0.0)
                o->terms[nt++] = sb_shell_external(&S->mat, &ref[q], &b, qe, gzero, a->p_follow, 1, ge, Ke);
        }
        if (L->n_mq) o->terms[nt++] = bhem_moment_element(S, L, e, qe, ge, Ke);
        if (Ke && S->hess == SB_HESS_PSD) sb_psd_project(BHEM_NED, Ke, T->psd);
        o->n_terms = nt;
        return;
    }
    /* the fast kernel: the patch's 4 x 4 points batched (sb_shell_element) */
    const int psd = Ke && S->hess == SB_HESS_PSD;
    double *Kt = psd ? T->Kx : Ke, E = 0.0;
    if (psd) memset(Kt, 0, sizeof(double) * BHEM_NED * BHEM_NED);
    for (int q = 0; q < BHEM_NQP; q++) {
        const bhem_qp_basis *B = &L->qb[q];
        sb_shell_basis b = { BHEM_NB, B->N, B->N1, B->N2, B->N11, B->N12, B->N22 };
        T->b[q] = b;
        if (a->p_follow != 0.0) E += sb_shell_external(&S->mat, &ref[q], &b, qe, gzero, a->p_follow, 1, ge, Kt);
    }
    if (L->n_mq) E += bhem_moment_element(S, L, e, qe, ge, Kt);
    o->terms[nt++] = psd ? sb_shell_element_psd(&S->mat, BHEM_NQP, ref, T->b, qe, ge, Ke, Kt,
                                                a->p_follow != 0.0 || L->n_mq, T->batch, T->psd, NULL)
                         : sb_shell_element(&S->mat, BHEM_NQP, ref, T->b, qe, ge, Ke, a->kind, T->batch);
    o->terms[nt++] = E;
    o->n_terms = nt;
}

/* in element order: the energy terms one by one, then gradient and matrix */
static void bhem_reduce(void *ctx, int e, const sb_elem_out *o)
{
    bhem_asm *a = ctx;
    for (int i = 0; i < o->n_terms; i++) a->E += o->terms[i];
    const int *d = a->L->elem_dofs + (size_t)e * BHEM_NED;
    if (a->g)
        for (int i = 0; i < BHEM_NED; i++) a->g[d[i]] += o->ge[i];
    if (a->H) sb_matrix_add_element(a->H, e, o->Ke);
}

int bhem_energy(bhem_state *S, int level, const double *x, double *f, double *g, sb_matrix *H)
{
    bhem_level *L = &S->lv[level];
    int qrc = bhem_level_ensure_quadrature(S, L);
    if (qrc) return qrc;
    const sb_scene *sc = S->scene;
    if (L->rebranch) {
        /* first evaluation of a step: re-centre the end-moment angle branches */
        if (L->n_mq) bhem_moment_rebranch(S, L, x);
        L->rebranch = 0;
    }
    bhem_asm a;
    memset(&a, 0, sizeof a);
    a.S = S;
    a.L = L;
    a.x = x;
    a.g = g;
    a.H = H;
    /* follower pressure: summed over loads, through the kernel's potential */
    for (int k = 0; k < sc->n_loads; k++)
        if (sc->loads[k].kind == SB_LOAD_PRESSURE && sc->loads[k].follower)
            a.p_follow += S->load_factor[k] * sc->loads[k].value;
    a.kind = S->hess == SB_HESS_PSD ? SB_HESS_EXACT : S->hess;
    sb_assemble(S->assembler, L->n_elems, NULL, g || H, H != NULL, bhem_compute, bhem_reduce, &a);
    double E = a.E;
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
    int qrc = bhem_level_ensure_quadrature(S, L);
    if (qrc) return qrc;
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
