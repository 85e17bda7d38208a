/* cc_energy.c — energy, gradient, Hessian and mass of one level of the
 * rmtr method.  Per element (domain face, 16 control points when regular,
 * 2n+8 next to one extraordinary vertex of valence n):
 *   Kirchhoff–Love elastic energy (RMTR paper (3.2)–(3.3), shared kernel
 *   core/shell/sb_shell.h), gravity and pressure (sb_shell_external),
 *   boundary penalty (3.6) and line/point loads (cc_penalty.c).
 * The core adds inertia and damping (DESIGN.md).  Element buffers are
 * allocated once in the method state; nothing is allocated in these loops.
 * The element loop runs on run.threads threads through sb_assemble (a
 * reduction in element order: bit-identical results for any count), with
 * the kernel of method.kernel: fast (sb_shell_element) or reference
 * (sb_shell_energy per point, the arithmetic of the committed records). */
#include "cc_method.h"
#include "sb_assemble.h"

#include <math.h>
#include <string.h>

/* One assembly: what compute() and reduce() share (sb_assemble.h). */
typedef struct cc_asm {
    cc_state *S;
    const cc_level *L;
    double *g;
    sb_matrix *H;
    const double *x;
    double gvec[3];
    int has_g, has_p;
    sb_hess_kind hk;            /* EXACT or PSEUDO: PSD is exact here, projected per element */
    double E;
} cc_asm;

/* The reference kernel, per point: the arithmetic (and the order of the
 * energy terms) of the loop every committed record was made with. */
static int terms_reference(cc_asm *a, sb_elem_scratch *T, int el, int k, double *ge, double *Ke, double *terms)
{
    cc_state *S = a->S;
    const sb_scene *sc = S->scene;
    const cc_quad *Q = &a->L->quad;
    const double *qe = T->qe;
    int nt = 0;
    for (int q = 0; q < Q->nq; q++) {
        sb_shell_basis b = cc_quad_basis(Q, el, q);
        const sb_shell_ref *r = &a->L->ref[(size_t)el * Q->nq + q];
        terms[nt++] = sb_shell_energy(&S->mat, r, &b, qe, ge, Ke, a->hk, T->work);
        if (a->has_g) terms[nt++] = sb_shell_external(&S->mat, r, &b, qe, a->gvec, 0.0, 0, ge, NULL);
        if (a->has_p)
            for (int i = 0; i < sc->n_loads; i++)
                if (sc->loads[i].kind == SB_LOAD_PRESSURE)
                    terms[nt++] = sb_shell_external(&S->mat, r, &b, qe, NULL, S->load_factor[i] * sc->loads[i].value,
                                                    sc->loads[i].follower, ge, Ke);
    }
    terms[nt++] = cc_points_energy(S, a->L, el, qe, ge, Ke);
    if (Ke && S->hess == SB_HESS_PSD) sb_psd_project(3 * k, Ke, T->psd);
    return nt;
}

/* Fast kernel, Hessian not PSD, no pressure and no boundary points on the
 * element: its matrix is the kernel's alone, so the kernel writes it
 * (sb_shell_element_into) and it is not zeroed first (an rmtr element
 * matrix is up to 3k x 3k = 48 x 48 at regular faces). */
static int cc_fast_store(const cc_asm *a, int el)
{
    return a->S->kernel != SB_KERNEL_REFERENCE && a->S->hess != SB_HESS_PSD && !a->has_p &&
           a->L->ept[el + 1] == a->L->ept[el];
}

/* The fast kernel: the element's points batched (sb_shell_element); kind
 * PSD by sb_shell_element_psd (exact where the element Hessian is PSD). */
static int terms_fast(cc_asm *a, sb_elem_scratch *T, int el, int k, double *ge, double *Ke, double *terms)
{
    cc_state *S = a->S;
    const sb_scene *sc = S->scene;
    const cc_quad *Q = &a->L->quad;
    const double *qe = T->qe;
    const int n = 3 * k, psd = Ke && S->hess == SB_HESS_PSD;
    const sb_shell_ref *r = &a->L->ref[(size_t)el * Q->nq];
    for (int q = 0; q < Q->nq; q++) T->b[q] = cc_quad_basis(Q, el, q);
    /* the other terms: gravity, pressure, penalty and loads (into Kx first for PSD) */
    double *Kt = psd ? T->Kx : Ke, E = 0.0;
    if (psd) memset(Kt, 0, (size_t)n * n * sizeof *Kt);
    int kx_used = 0;
    for (int q = 0; q < Q->nq; q++) {
        if (a->has_g) E += sb_shell_external(&S->mat, &r[q], &T->b[q], qe, a->gvec, 0.0, 0, ge, NULL);
        if (a->has_p)
            for (int i = 0; i < sc->n_loads; i++)
                if (sc->loads[i].kind == SB_LOAD_PRESSURE) {
                    E += sb_shell_external(&S->mat, &r[q], &T->b[q], qe, NULL, S->load_factor[i] * sc->loads[i].value,
                                           sc->loads[i].follower, ge, Kt);
                    kx_used |= sc->loads[i].follower;
                }
    }
    kx_used |= a->L->ept[el + 1] > a->L->ept[el];
    E += cc_points_energy(S, a->L, el, qe, ge, Kt);
    /* Ke with no other terms (no pressure, no boundary points: cc_fast_store)
     * was not zeroed: the kernel overwrites it (the same bits) */
    terms[0] = psd ? sb_shell_element_psd(&S->mat, Q->nq, r, T->b, qe, ge, Ke, Kt, kx_used, T->batch, T->psd, NULL)
               : Ke && cc_fast_store(a, el) ? sb_shell_element_into(&S->mat, Q->nq, r, T->b, qe, ge, Ke, a->hk, T->batch)
                                            : sb_shell_element(&S->mat, Q->nq, r, T->b, qe, ge, Ke, a->hk, T->batch);
    terms[1] = E;
    return 2;
}

static void cc_compute(void *ctx, int thread, int el, sb_elem_out *o)
{
    cc_asm *a = ctx;
    cc_state *S = a->S;
    const cc_quad *Q = &a->L->quad;
    sb_elem_scratch *T = &S->tw[thread];
    const int *nd = Q->enode + Q->eoff[el];
    const int k = Q->eoff[el + 1] - Q->eoff[el], n = 3 * k;
    double *ge = a->g ? o->ge : NULL, *Ke = o->Ke;
    for (int i = 0; i < k; i++) memcpy(T->qe + 3 * i, a->x + 3 * nd[i], 3 * sizeof(double));
    if (ge) memset(ge, 0, (size_t)n * sizeof *ge);
    if (Ke && !cc_fast_store(a, el)) memset(Ke, 0, (size_t)n * n * sizeof *Ke);
    o->n_terms = S->kernel == SB_KERNEL_REFERENCE ? terms_reference(a, T, el, k, ge, Ke, o->terms)
                                                 : terms_fast(a, T, el, k, ge, Ke, o->terms);
}

/* in element order: the energy terms one by one, then gradient and matrix */
static void cc_reduce(void *ctx, int el, const sb_elem_out *o)
{
    cc_asm *a = ctx;
    for (int i = 0; i < o->n_terms; i++) a->E += o->terms[i];
    const cc_quad *Q = &a->L->quad;
    const int *nd = Q->enode + Q->eoff[el];
    const int k = Q->eoff[el + 1] - Q->eoff[el];
    if (a->g)
        for (int i = 0; i < k; i++)
            for (int c = 0; c < 3; c++) a->g[3 * nd[i] + c] += o->ge[3 * i + c];
    if (a->H) sb_matrix_add_element(a->H, el, o->Ke);
}

static int cc_dim(void *ctx, int el)
{
    const cc_quad *Q = &((cc_asm *)ctx)->L->quad;
    return 3 * (Q->eoff[el + 1] - Q->eoff[el]);
}

int cc_energy(cc_state *S, int l, const double *x, double *f, double *g, sb_matrix *H)
{
    const sb_scene *sc = S->scene;
    cc_level *L = &S->lv[l];
    int rc = cc_level_ref(S, l);
    if (rc) return rc;
    cc_asm a;
    memset(&a, 0, sizeof a);
    a.S = S;
    a.L = L;
    a.g = g;
    a.H = H;
    a.x = x;
    for (int i = 0; i < sc->n_loads; i++) {
        const sb_load *ld = &sc->loads[i];
        if (ld->kind == SB_LOAD_GRAVITY) {
            for (int c = 0; c < 3; c++) a.gvec[c] += S->load_factor[i] * ld->vec[c];
            a.has_g = 1;
        }
        a.has_p |= ld->kind == SB_LOAD_PRESSURE;
    }
    a.hk = S->hess == SB_HESS_PSD ? SB_HESS_EXACT : S->hess;
    sb_assemble(S->assembler, L->quad.ne, cc_dim, g != NULL, H != NULL, cc_compute, cc_reduce, &a);
    *f = a.E;
    if (!isfinite(a.E)) return SB_NONFINITE;
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
    int rc = cc_level_ref(S, l);
    if (rc) return rc;
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
    int status = cc_level_ref(S, l);
    if (status) return status;
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
