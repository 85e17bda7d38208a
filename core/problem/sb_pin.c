/* sb_pin.c — sliding pins as a penalty (sb_pin.h). */
#include "sb_pin.h"

#include "sb_context.h"
#include "sb_geometry.h"
#include "sb_vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct pin {
    int bc;                          /* scene boundary condition */
    unsigned mask;                   /* held components */
    double k;                        /* stiffness (N/m) */
    int nt;                          /* terms at the current point */
    int dof[SB_POINT_TERMS_MAX];
    double w[SB_POINT_TERMS_MAX];
    double target[3];                /* p(f) */
} pin;

struct sb_pins {
    const sb_method_type *mt;
    void *ms;
    const sb_scene *sc;
    int level, n;
    pin p[SB_SCENE_MAX_BCS];
    double *xref;                    /* the method's reference state of the level */
};

int sb_pins_count(const sb_pins *P) { return P ? P->n : 0; }

int sb_pins_create(sb_context *ctx, const sb_method_type *mt, void *ms, const sb_scene *sc, int level, sb_pins **out)
{
    *out = NULL;
    int n = 0, first = -1;
    for (int b = 0; b < sc->n_bcs; b++)
        if (sc->bcs[b].kind == SB_BC_MOVING && sc->bcs[b].slide) {
            if (first < 0) first = b;
            n++;
        }
    if (!n) return SB_OK;
    if (!mt->point_terms)
        return sb_error(ctx, SB_ERR_UNSUPPORTED, "scene %s: boundary[%d] has a sliding pin (\"slide\"), which needs a "
                        "point held between the nodes of the discretization; method %s can only constrain its "
                        "nodes or vertices", sc->name, first, mt->name);
    sb_pins *P = calloc(1, sizeof *P);
    if (!P) return sb_error(ctx, SB_ERR_NOMEM, "out of memory (sliding pins)");
    P->mt = mt;
    P->ms = ms;
    P->sc = sc;
    P->level = level;
    const int nd = mt->n_dofs(ms, level);
    P->xref = malloc((size_t)nd * sizeof *P->xref);
    int rc = P->xref ? mt->initial(ms, level, P->xref) : SB_ERR_NOMEM;
    if (rc) {
        sb_pins_free(P);
        return rc < 0 ? sb_error(ctx, rc, "method %s: reference state for the sliding pins failed", mt->name) : rc;
    }
    for (int b = 0; b < sc->n_bcs; b++) {
        const sb_bc *bc = &sc->bcs[b];
        if (bc->kind != SB_BC_MOVING || !bc->slide) continue;
        pin *q = &P->p[P->n++];
        q->bc = b;
        q->mask = bc->components ? bc->components : 7u;
        q->k = bc->slide_stiffness;
    }
    sb_step_info si;
    memset(&si, 0, sizeof si);            /* factor 0: the start points (checks the op once) */
    if ((rc = sb_pins_set_step(P, &si))) {
        sb_pins_free(P);
        return sb_error(ctx, SB_ERR_INPUT, "scene %s: method %s cannot evaluate a sliding pin's start point",
                        sc->name, mt->name);
    }
    *out = P;
    return SB_OK;
}

void sb_pins_free(sb_pins *P)
{
    if (!P) return;
    free(P->xref);
    free(P);
}

int sb_pins_set_step(sb_pins *P, const sb_step_info *si)
{
    if (!P) return SB_OK;
    for (int i = 0; i < P->n; i++) {
        pin *q = &P->p[i];
        const sb_bc *bc = &P->sc->bcs[q->bc];
        const double f = si->motion_factor[q->bc];
        /* the pinned point: st(f) = st_0 + f (st_1 - st_0), clamped to the
           segment (factors outside [0, 1] would leave the checked path) */
        const double fs = fmin(1.0, fmax(0.0, f));
        const double st[2] = { bc->parts[0].st[0] + fs * (bc->slide_st[0] - bc->parts[0].st[0]),
                               bc->parts[0].st[1] + fs * (bc->slide_st[1] - bc->parts[0].st[1]) };
        const int nt = P->mt->point_terms(P->ms, P->level, st, q->dof, q->w);
        if (nt <= 0 || nt > SB_POINT_TERMS_MAX) return nt < 0 ? nt : SB_ERR_INTERNAL;
        q->nt = nt;
        double X[3] = { 0, 0, 0 };
        for (int a = 0; a < nt; a++)
            for (int c = 0; c < 3; c++) X[c] += q->w[a] * P->xref[q->dof[a] + c];
        /* p(f) = c + R(f angle)(X - c) + f translation (as a moving condition) */
        double an = sqrt(sb_dot3(bc->rot_axis, bc->rot_axis));
        double y[3];
        if (an > 0.0 && bc->rot_angle != 0.0) {
            double ax[3] = { bc->rot_axis[0] / an, bc->rot_axis[1] / an, bc->rot_axis[2] / an }, R[9], d[3];
            sb_rotation(ax, f * bc->rot_angle, R);
            for (int c = 0; c < 3; c++) d[c] = X[c] - bc->rot_center[c];
            for (int r = 0; r < 3; r++) y[r] = bc->rot_center[r] + R[3 * r] * d[0] + R[3 * r + 1] * d[1] + R[3 * r + 2] * d[2];
        } else {
            for (int c = 0; c < 3; c++) y[c] = X[c];
        }
        for (int c = 0; c < 3; c++) q->target[c] = y[c] + f * bc->translation[c];
    }
    return SB_OK;
}

static void residual(const pin *q, const double *x, double r[3])
{
    for (int c = 0; c < 3; c++) r[c] = -q->target[c];
    for (int a = 0; a < q->nt; a++)
        for (int c = 0; c < 3; c++) r[c] += q->w[a] * x[q->dof[a] + c];
    for (int c = 0; c < 3; c++)
        if (!(q->mask & (1u << c))) r[c] = 0.0;
}

int sb_pins_energy(const sb_pins *P, const double *x, double *e, double *g, sb_matrix *H)
{
    if (!P) return SB_OK;
    for (int i = 0; i < P->n; i++) {
        const pin *q = &P->p[i];
        double r[3];
        residual(q, x, r);
        *e += 0.5 * q->k * sb_dot3(r, r);                        /* E_pin = k/2 |r|^2 */
        if (g)
            for (int a = 0; a < q->nt; a++)
                for (int c = 0; c < 3; c++) g[q->dof[a] + c] += q->k * q->w[a] * r[c];   /* k w_a r */
        if (H)
            for (int a = 0; a < q->nt; a++)
                for (int b = a; b < q->nt; b++) {
                    const double v = q->k * q->w[a] * q->w[b];           /* k w_a w_b on held components */
                    if (v == 0.0) continue;
                    for (int c = 0; c < 3; c++) {
                        if (!(q->mask & (1u << c))) continue;
                        const int i0 = q->dof[a] + c, j0 = q->dof[b] + c;
                        /* a term repeated on one dof (identified seam nodes) adds twice on the diagonal */
                        if (sb_matrix_add(H, i0, j0, (a == b || i0 != j0) ? v : 2.0 * v)) return SB_ERR_INTERNAL;
                    }
                }
    }
    return SB_OK;
}

double sb_pins_violation(const sb_pins *P, const double *x)
{
    double v = 0.0;
    for (int i = 0; P && i < P->n; i++) {
        double r[3];
        residual(&P->p[i], x, r);
        v = fmax(v, sqrt(sb_dot3(r, r)));
    }
    return v;
}
