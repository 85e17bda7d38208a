/* test_cc_plate.c — physical checks of the rmtr discretization: simply
 * supported and clamped square Kirchhoff plates under uniform pressure (positions held by
 * the penalty (3.6), rotations free), one Newton step from the flat
 * reference, centre deflection against the Navier series
 * w = 0.00406235 q a^4 / D (Timoshenko & Woinowsky-Krieger, Table 8), the
 * same numbers as bench/scenes/plate_simply_supported.json. */
#include "sb_test.h"
#include "sb_method.h"
#include "sb_geometry.h"

#include <stdlib.h>
#include <string.h>

extern const sb_method_type sb_method_subdiv;
extern void dposv_(const char *uplo, const int *n, const int *nrhs, double *a, const int *lda, double *b,
                   const int *ldb, int *info);

static double center_deflection(sb_test_state *T, int res, sb_bc_kind edge_bc)
{
    sb_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.domain.kind = SB_DOMAIN_RECTANGLE;
    sc.domain.size[0] = sc.domain.size[1] = 1.0;
    sc.chart.kind = SB_CHART_PLANE;
    sc.material.kind = SB_MAT_STVK;
    sc.material.young = 1e7;
    sc.material.poisson = 0.3;
    sc.material.thickness = 0.01;
    sc.material.density = 10;
    sc.n_loads = 1;
    sc.loads[0].kind = SB_LOAD_PRESSURE;
    sc.loads[0].value = 0.002;
    sc.n_bcs = 1;
    sc.bcs[0].kind = edge_bc;
    sc.bcs[0].components = 7;
    sc.bcs[0].n_parts = 4;
    static const char *edges[4] = { "left", "right", "bottom", "top" };
    for (int i = 0; i < 4; i++) sb_domain_edge_part(&sc.domain, edges[i], &sc.bcs[0].parts[i]);
    void *st = calloc(1, sb_method_subdiv.state_size);
    sb_method_config cfg = { res, 1, NULL, NULL, 0 };
    int rc = sb_method_subdiv.create(st, &sc, &cfg);
    CHECK(rc == SB_OK);
    if (rc) {
        free(st);
        return NAN;
    }
    sb_step_info si;
    memset(&si, 0, sizeof si);
    si.step = si.n_steps = 1;
    si.load_factor[0] = 1.0;
    sb_method_subdiv.set_step(st, &si);
    int n = sb_method_subdiv.n_dofs(st, 0);
    sb_pattern_builder *pb = sb_pattern_builder_new(n / 3, 3);
    sb_pattern *pat = NULL;
    sb_method_subdiv.pattern(st, 0, pb);
    CHECK(sb_pattern_builder_finish(pb, &pat) == SB_OK);
    sb_matrix H;
    sb_matrix_init(&H, pat);
    sb_matrix_zero(&H);
    double *x = malloc(sizeof(double) * 2 * n), *g = x + n, f;
    double *A = calloc((size_t)n * n, sizeof *A);
    sb_method_subdiv.initial(st, 0, x);
    memset(g, 0, sizeof(double) * n);
    CHECK(sb_method_subdiv.energy(st, 0, x, &f, g, &H) == SB_OK);
    for (int j = 0; j < n; j++)                      /* upper CSC -> dense (column-major, upper) */
        for (long p = pat->colptr[j]; p < pat->colptr[j + 1]; p++) A[(size_t)j * n + pat->rowind[p]] = H.val[p];
    for (int i = 0; i < n; i++) g[i] = -g[i];
    int one = 1, info = 0;
    dposv_("U", &n, &one, A, &n, g, &n, &info);      /* Newton step from the flat plate */
    CHECK_EQ_INT(info, 0);
    for (int i = 0; i < n; i++) x[i] += g[i];
    double c[2] = { 0.5, 0.5 }, pos[3] = { 0, 0, 0 };
    CHECK(sb_method_subdiv.eval_points(st, 0, x, 1, c, pos) == SB_OK);
    free(A);
    free(x);
    sb_matrix_free(&H);
    sb_pattern_free(pat);
    sb_method_subdiv.destroy(st);
    free(st);
    return pos[2];
}

SB_TEST(navier_plate_converges)
{
    const double D = 1e7 * 1e-6 / (12 * (1 - 0.09)), w = 0.00406235 * 0.002 / D;
    double e8 = fabs(center_deflection(T, 8, SB_BC_FIXED) / w - 1), e16 = fabs(center_deflection(T, 16, SB_BC_FIXED) / w - 1);
    printf("    centre deflection rel. error: 8x8 %.2e, 16x16 %.2e (Navier w = %.6e)\n", e8, e16, w);
    CHECK(e8 < 1e-2);
    CHECK(e16 < 1e-3);
    CHECK(e16 < e8 / 8);
}

/* Clamped edges: positions and the slope across the edge by penalty (see
 * cc_penalty.c); w = 0.00126532 q a^4 / D (Timoshenko & Woinowsky-Krieger,
 * Table 35), as bench/scenes/plate_clamped.json.  Measured: 2.5e-2 at 8x8,
 * 2.1e-3 at 16x16. */
SB_TEST(clamped_plate_converges)
{
    const double D = 1e7 * 1e-6 / (12 * (1 - 0.09)), w = 0.00126532 * 0.002 / D;
    double e8 = fabs(center_deflection(T, 8, SB_BC_CLAMPED) / w - 1);
    double e16 = fabs(center_deflection(T, 16, SB_BC_CLAMPED) / w - 1);
    printf("    clamped centre deflection rel. error: 8x8 %.2e, 16x16 %.2e (w = %.6e)\n", e8, e16, w);
    CHECK(e8 < 4e-2);
    CHECK(e16 < 4e-3);
    CHECK(e16 < e8 / 6);
}

int main(int argc, char **argv)
{
    static const sb_test_case cases[] = {
        SB_CASE(navier_plate_converges), SB_CASE(clamped_plate_converges),
        SB_END
    };
    return sb_test_main(argc, argv, cases);
}
