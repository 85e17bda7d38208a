/* cc_beta.c — the penalty factor of the rmtr method and how far a state
 * violates the constraints it imposes (RMTR paper (3.6); docs/trust.md).
 *
 * The paper takes beta = h^-sigma with h the mesh size in metres, sigma = 5
 * (§3.1, §7.1), for its 1 m x 1 m denim cloth.  That number has units: on a
 * stiffer or larger scene it is far too soft (a 10 m steel plate at 8 x 8
 * elements gets beta = 0.33 and sags 1e7 times too far), on a softer or
 * smaller one needlessly stiff.  The scaled rule (default) makes it
 * dimensionally consistent,
 *     beta = beta_scale c_p S (l / h)^sigma,   S = k_m / l + D / l^3,
 * with k_m = t C and D = t^3 C / 12 the membrane and bending stiffness of the
 * scene's material (C the largest diagonal entry of its tangent at zero
 * strain, thickness t), l the domain's diameter, and c_p = 1 / (S_p l_p^sigma)
 * calibrated on the paper's cloth (Table 1 denim, the 1 m x 1 m square), so
 * that there beta is the paper's.  In code beta = beta_scale r h^-sigma with
 * r = (S / S_p) (l / l_p)^sigma: on the paper's scenes S == S_p and
 * l == l_p exactly (same inputs, same arithmetic), r = 1.0 and beta is bit
 * for bit the paper's h^-sigma (tests/test_cc_method.c).  S is a boundary
 * stiffness per unit length (N/m^2), beta's own unit. */
#include "cc_method.h"
#include "sb_geometry.h"

#include <math.h>
#include <string.h>

/* S = k_m / l + D / l^3 of a material spec on a domain of diameter l */
static int stiffness_scale(const sb_material_spec *spec, double l, double *out, cc_err *e)
{
    sb_material m;
    char msg[256];
    if (sb_material_init_msg(&m, spec, 0, msg, sizeof msg) != SB_OK)
        return cc_fail(e, SB_ERR_INPUT, "material: %s", msg);
    const double zero[3] = { 0, 0, 0 };
    double d2[9];
    sb_material_psi(&m, zero, NULL, d2);
    double C = fmax(d2[0], d2[4]), t = spec->thickness;
    double km = t * C, D = t * t * t * C / 12.0;
    *out = km / l + D / (l * l * l);
    if (!(*out > 0) || !isfinite(*out))
        return cc_fail(e, SB_ERR_INPUT, "the material has no positive stiffness at zero strain (penalty scale %g)", *out);
    return SB_OK;
}

int cc_beta_factor(const cc_state *S, double *factor, cc_err *e)
{
    *factor = 1.0;
    if (S->beta_paper) return SB_OK;
    sb_material_spec paper;
    sb_material_spec_denim(&paper);                     /* RMTR paper Table 1 */
    sb_domain square;
    memset(&square, 0, sizeof square);
    square.kind = SB_DOMAIN_RECTANGLE;
    square.size[0] = square.size[1] = 1.0;              /* §7: 1 m x 1 m */
    const double lp = sb_domain_diameter(&square), l = sb_domain_diameter(&S->scene->domain);
    double Sp, Ss;
    int rc = stiffness_scale(&paper, lp, &Sp, e);
    if (!rc) rc = stiffness_scale(&S->scene->material, l, &Ss, e);
    if (rc) return rc;
    *factor = (Ss / Sp) * pow(l / lp, S->sigma);
    if (!(*factor > 0) || !isfinite(*factor))
        return cc_fail(e, SB_ERR_INPUT, "penalty factor of the scene is %g (material or domain out of range)", *factor);
    return SB_OK;
}

int cc_penalty_violation(const cc_state *S, int l, const double *x, sb_penalty_report *r)
{
    const cc_level *L = &S->lv[l];
    memset(r, 0, sizeof *r);
    r->beta = L->beta;
    int finite = 1;
    for (int el = 0; el < L->quad.ne; el++) {
        const int *nd = L->quad.enode + L->quad.eoff[el];
        const int k = L->quad.eoff[el + 1] - L->quad.eoff[el];
        for (int i = L->ept[el]; i < L->ept[el + 1]; i++) {
            const cc_pt *p = &L->pt[i];
            if (p->kind != CC_PT_PENALTY && p->kind != CC_PT_SLOPE) continue;
            const double *N = L->ptN + p->off;
            double y[3] = { 0, 0, 0 };
            for (int a = 0; a < k; a++)
                for (int c = 0; c < 3; c++) y[c] += N[a] * x[3 * nd[a] + c];
            r->points++;
            if (p->kind == CC_PT_SLOPE) {
                /* y = dx/dc: theta = (dx/dc . N) / |dX/dc| (cc_penalty.c) */
                double th = fabs(y[0] * p->n[0] + y[1] * p->n[1] + y[2] * p->n[2]) * p->inv_len;
                finite &= isfinite(th);
                r->rotation_max = fmax(r->rotation_max, th);
            } else {
                double d2 = 0;
                for (int c = 0; c < 3; c++)
                    if (p->mask & (1u << c)) d2 += (y[c] - p->b[c]) * (y[c] - p->b[c]);
                finite &= isfinite(d2);
                r->position_max = fmax(r->position_max, sqrt(d2));
            }
        }
    }
    if (!finite) return SB_NONFINITE;
    return SB_OK;
}
