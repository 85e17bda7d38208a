/* a3_energy.c — assembly of adaptive_sqrt3: the corotational membrane of
 * every triangle (Eq. 16-17), the isometric bending of every interior edge
 * (Eq. 18), the dead loads, and the lumped mass (Alg. 1, Eq. 3).  What E, g
 * and H mean for the lagged rotation: a3.h.  Element blocks go in the
 * pattern's order: triangles, then interior edges (a3_method.c). */
#include "a3.h"

#include <math.h>
#include <string.h>

int a3_energy(a3_state *S, const double *x, double *f, double *g, sb_matrix *H)
{
    double E = 0.0;
    for (int t = 0; t < S->nt; t++) {
        const a3_tri *T = &S->tri[t];
        double q[9], ge[9] = { 0 }, Ke[81];
        for (int i = 0; i < 3; i++) memcpy(q + 3 * i, x + 3 * T->v[i], 3 * sizeof(double));
        if (H) memset(Ke, 0, sizeof Ke);
        E += a3_membrane(T, q, NULL, NULL, g ? ge : NULL, H ? Ke : NULL);
        if (g)
            for (int i = 0; i < 3; i++)
                for (int c = 0; c < 3; c++) g[3 * T->v[i] + c] += ge[3 * i + c];
        if (H) sb_matrix_add_element(H, t, Ke);
    }
    for (int k = 0; k < S->n_edge; k++) {
        const a3_edge *e = &S->edge[k];
        double q[12], ge[12] = { 0 }, Ke[144];
        for (int i = 0; i < 4; i++) memcpy(q + 3 * i, x + 3 * e->v[i], 3 * sizeof(double));
        if (H) memset(Ke, 0, sizeof Ke);
        E += a3_bend(e, q, g ? ge : NULL, H ? Ke : NULL);
        if (g)
            for (int i = 0; i < 4; i++)
                for (int c = 0; c < 3; c++) g[3 * e->v[i] + c] += ge[3 * i + c];
        if (H) sb_matrix_add_element(H, S->nt + k, Ke);
    }
    /* dead loads: E_ext = -f_ext . (x - x_ref) */
    for (int i = 0; i < S->n_dofs; i++) E -= S->f_ext[i] * (x[i] - S->x_ref[i]);
    if (g) sb_axpy(S->n_dofs, -1.0, S->f_ext, g);
    *f = E;
    if (!isfinite(E)) return SB_NONFINITE;
    if (g && !sb_all_finite(S->n_dofs, g)) return SB_NONFINITE;
    return SB_OK;
}

int a3_mass(a3_state *S, sb_matrix *M)
{
    for (int v = 0; v < S->nv; v++)
        for (int c = 0; c < 3; c++) {
            int rc = sb_matrix_add(M, 3 * v + c, 3 * v + c, S->mass[v]);
            if (rc) return rc;
        }
    return SB_OK;
}
