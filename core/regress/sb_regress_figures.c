/* sb_regress_figures.c — the deterministic figures of one record, what the
 * nightly regression compares exactly (docs/regression.md): the summary
 * (status, reason, steps, iterations, dofs, work units, energy_final) and,
 * from /stats and /probes (layout: docs/recorded_figures.md), event counts
 * summed over levels, CHOLMOD nnz(L) and flops, Hessian nnz, and the probes'
 * positions after the last step.  Reads through the recording module's
 * HDF5 helpers (sb_record_io.h) so that every failure names the file. */
#include "sb_regress.h"
#include "sb_record.h"
#include "sb_record_io.h"

#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const int_names[SB_RF_COUNT_INT] = {
    "steps", "iterations", "dofs", "energy_calls", "gradient_calls", "hessian_calls", "factorize_calls", "solve_calls",
    "cg_iters"
};
static const char *const exact_names[SB_RF_COUNT_EXACT] = {
    "work_assembly", "work_qp", "factor_nnz", "factor_flops", "matrix_nnz"
};

const char *sb_regress_int_name(int k) { return k >= 0 && k < SB_RF_COUNT_INT ? int_names[k] : "?"; }
const char *sb_regress_exact_name(int k) { return k >= 0 && k < SB_RF_COUNT_EXACT ? exact_names[k] : "?"; }

/* column of an event in /stats/events_count, by name (-1: absent) */
static int event_column(hid_t f, const char *name, hsize_t ncols)
{
    hid_t a = H5Aopen_by_name(f, "/stats", "event_names", H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) return -1;
    hid_t t = H5Aget_type(a);
    size_t w = t < 0 ? 0 : H5Tget_size(t);
    int col = -1;
    char *buf = w > 0 && H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t) ? calloc(ncols + 1, w + 1) : NULL;
    if (buf && H5Aread(a, t, buf) >= 0)
        for (hsize_t c = 0; c < ncols && col < 0; c++)
            if (strlen(name) <= w && !strncmp(buf + c * w, name, w) && (strlen(name) == w || buf[c * w + strlen(name)] == 0))
                col = (int)c;
    free(buf);
    if (t >= 0) H5Tclose(t);
    H5Aclose(a);
    return col;
}

static int read_stats(sb_h5r *r, hid_t f, sb_regress_figures *g)
{
    static const struct { int fig; const char *event; } ev[] = {
        { SB_RF_ENERGY_CALLS, "energy" }, { SB_RF_GRADIENT_CALLS, "gradient" }, { SB_RF_HESSIAN_CALLS, "hessian" },
        { SB_RF_FACTORIZE_CALLS, "factorize" }, { SB_RF_SOLVE_CALLS, "solve" }, { SB_RF_CG_ITERS, "cg_iter" },
    };
    hsize_t d2[2], d1;
    long *cnt = NULL;
    double *nnz = NULL, *flops = NULL;
    long *mnnz = NULL;
    int rc = sb_h5r_dset(r, f, "/stats/events_count", 2, H5T_NATIVE_LONG, sizeof(long), d2, (void **)&cnt);
    for (size_t k = 0; !rc && k < sizeof ev / sizeof *ev; k++) {
        int c = event_column(f, ev[k].event, d2[1]);
        if (c < 0) { rc = sb_h5r_fail(r, SB_ERR_INPUT, "no such event in", "/stats/event_names"); break; }
        for (hsize_t l = 0; l < d2[0]; l++) g->n[ev[k].fig] += cnt[l * d2[1] + (hsize_t)c];
    }
    if (!rc) rc = sb_h5r_dset(r, f, "/stats/chol_nnz_l", 1, H5T_NATIVE_DOUBLE, sizeof(double), &d1, (void **)&nnz);
    for (hsize_t l = 0; !rc && l < d1; l++) g->x[SB_RF_CHOL_NNZ] += nnz[l];
    if (!rc) rc = sb_h5r_dset(r, f, "/stats/chol_flops", 1, H5T_NATIVE_DOUBLE, sizeof(double), &d1, (void **)&flops);
    for (hsize_t l = 0; !rc && l < d1; l++) g->x[SB_RF_CHOL_FLOPS] += flops[l];
    if (!rc) rc = sb_h5r_dset(r, f, "/stats/matrix_nnz", 1, H5T_NATIVE_LONG, sizeof(long), &d1, (void **)&mnnz);
    for (hsize_t l = 0; !rc && l < d1; l++) g->x[SB_RF_MATRIX_NNZ] += (double)mnnz[l];
    free(cnt), free(nnz), free(flops), free(mnnz);
    return rc;
}

/* positions of the probes after the last recorded step */
static int read_probes(sb_h5r *r, hid_t f, sb_regress_figures *g)
{
    if (H5Lexists(f, "/probes", H5P_DEFAULT) <= 0 || H5Lexists(f, "/probes/trajectory", H5P_DEFAULT) <= 0) return SB_OK;
    hsize_t d[3];
    double *tr = NULL;
    int rc = sb_h5r_dset(r, f, "/probes/trajectory", 3, H5T_NATIVE_DOUBLE, sizeof(double), d, (void **)&tr);
    if (!rc && d[0] > 0 && d[2] == 3) {
        g->n_probes = d[1] < SB_REGRESS_MAX_PROBES ? (int)d[1] : SB_REGRESS_MAX_PROBES;
        for (int p = 0; p < g->n_probes; p++)
            for (int c = 0; c < 3; c++) g->probe[p][c] = tr[((d[0] - 1) * d[1] + (hsize_t)p) * 3 + (hsize_t)c];
    }
    free(tr);
    return rc;
}

int sb_regress_figures_read(const char *path, sb_regress_figures *g, char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    sb_record_summary s;
    int rc = sb_record_read_summary(path, &s, err, errlen);
    if (rc) return rc;
    g->status = s.status;
    snprintf(g->reason, sizeof g->reason, "%s", s.reason_name);
    g->n[SB_RF_STEPS] = s.steps;
    g->n[SB_RF_ITERATIONS] = s.iterations;
    g->n[SB_RF_DOFS] = s.dofs;
    g->x[SB_RF_WORK_ASSEMBLY] = s.work_assembly;
    g->x[SB_RF_WORK_QP] = s.work_qp;
    g->has_energy = isfinite(s.energy_final);
    g->energy = g->has_energy ? s.energy_final : 0;
    sb_record_summary_free(&s);
    sb_h5r r = { path, err, errlen, NULL, NULL };
    hid_t f;
    rc = sb_h5r_open(&r, &f);
    if (rc) return rc;
    rc = read_stats(&r, f, g);
    if (!rc) rc = read_probes(&r, f, g);
    sb_h5r_close(&r, f);
    return rc;
}

/* |a - b| <= rtol max(|a|, |b|) (and equal non-finite values agree) */
static int near(double a, double b, double rtol)
{
    if (a == b) return 1;
    return fabs(a - b) <= rtol * fmax(fabs(a), fabs(b));
}

int sb_regress_figures_differ(const sb_regress_figures *a, const sb_regress_figures *b, double rtol, char *what,
                              size_t len)
{
    /* work units are sums of n^l/n^L in a fixed order, nnz and flops whole
     * numbers: the same run computes the same double; 1e-12 only absorbs a
     * decimal round trip through the baseline file (written with 17 digits) */
    const double exact_rtol = 1e-12;
    what[0] = 0;
    if (a->status != b->status) snprintf(what, len, "status %s -> %s", sb_record_status_name(a->status), sb_record_status_name(b->status));
    else if (strcmp(a->reason, b->reason)) snprintf(what, len, "reason %s -> %s", a->reason, b->reason);
    for (int k = 0; !what[0] && k < SB_RF_COUNT_INT; k++)
        if (a->n[k] != b->n[k]) snprintf(what, len, "%s %ld -> %ld", int_names[k], a->n[k], b->n[k]);
    for (int k = 0; !what[0] && k < SB_RF_COUNT_EXACT; k++)
        if (!near(a->x[k], b->x[k], exact_rtol)) snprintf(what, len, "%s %.17g -> %.17g", exact_names[k], a->x[k], b->x[k]);
    if (!what[0] && a->has_energy != b->has_energy) snprintf(what, len, "energy_final %s", a->has_energy ? "no longer recorded" : "now recorded");
    if (!what[0] && a->has_energy && !near(a->energy, b->energy, rtol))
        snprintf(what, len, "energy_final %.12g -> %.12g J (rel %.2g > %.2g)", a->energy, b->energy,
                 fabs(a->energy - b->energy) / fmax(fabs(a->energy), fabs(b->energy)), rtol);
    if (!what[0] && a->n_probes != b->n_probes) snprintf(what, len, "probes %d -> %d", a->n_probes, b->n_probes);
    for (int p = 0; !what[0] && p < a->n_probes; p++) {
        /* relative to the probe's distance from the origin, so that a
         * coordinate that is zero on a symmetry line is not held to 0 */
        double scale = fmax(hypot(hypot(a->probe[p][0], a->probe[p][1]), a->probe[p][2]), 1e-300);
        for (int c = 0; !what[0] && c < 3; c++)
            if (!(fabs(a->probe[p][c] - b->probe[p][c]) <= rtol * scale))
                snprintf(what, len, "probe %d component %c %.12g -> %.12g m", p, "xyz"[c], a->probe[p][c], b->probe[p][c]);
    }
    return what[0] != 0;
}
