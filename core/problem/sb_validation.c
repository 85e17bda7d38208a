/* sb_validation.c — expected probe values judged (docs/trust.md
 * "Validation"): each check's relative error against its tolerance, its
 * signed error (too soft and too stiff are different findings), and the
 * run's verdict passed / failed / none, recorded apart from the solver's
 * reason and turned into an exit code by --strict. */
#include "sb_validation.h"
#include "sb_run_state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sb_check_eval(const sb_probe_check *c, const double u[3], sb_check_row *row)
{
    row->component = c->component;
    row->tol = c->tol;
    for (int k = 0; k < 3; k++) row->expected[k] = row->measured[k] = NAN;
    if (c->component < 0) {
        double num = 0, den = 0, along = 0;
        for (int k = 0; k < 3; k++) {
            row->expected[k] = c->value[k];
            row->measured[k] = u[k];
            num += (u[k] - c->value[k]) * (u[k] - c->value[k]);
            den += c->value[k] * c->value[k];
            along += u[k] * c->value[k];
        }
        row->rel_error = sqrt(num) / fmax(sqrt(den), 1e-300);
        row->signed_error = along / fmax(den, 1e-300) - 1.0;   /* projection on the expected vector */
    } else {
        double v = c->component == 3 ? sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) : u[c->component];
        double e = c->value[0];
        row->expected[0] = e;
        row->measured[0] = v;
        row->rel_error = fabs(v - e) / fmax(fabs(e), 1e-300);
        row->signed_error = v / e - 1.0;                          /* e != 0 (sb_scene_probes.c) */
    }
    row->passed = row->rel_error <= c->tol;                       /* NaN fails */
}

/* Every check of every probe at the final state; probe_rel_error[p] becomes
 * the largest relative error of the probe's checks.  The verdict is none
 * when there is nothing to check or the run stopped before its final step
 * (the expected values are those of the final step). */
int sb_run_validate(run_state *R)
{
    sb_run *rec = &R->rec;
    const sb_scene *sc = &R->scene;
    int n = 0;
    for (int p = 0; p < rec->n_probes; p++) n += sc->probes[p].n_checks;
    free(rec->checks);
    rec->checks = n ? calloc((size_t)n, sizeof *rec->checks) : NULL;
    rec->n_checks = 0;
    rec->validation = SB_VALIDATION_NONE;
    if (n && !rec->checks) return SB_ERR_NOMEM;
    int failed = 0;
    for (int p = 0; p < rec->n_probes; p++) {
        const double *pos = rec->probe_traj + ((size_t)rec->steps_done * rec->n_probes + p) * 3;
        const double *ref = rec->probe_traj + (size_t)p * 3;
        const double u[3] = { pos[0] - ref[0], pos[1] - ref[1], pos[2] - ref[2] };
        double worst = NAN;
        int nan = 0;
        for (int k = 0; k < sc->probes[p].n_checks; k++) {
            sb_check_row *row = &rec->checks[rec->n_checks++];
            sb_check_eval(&sc->probes[p].checks[k], u, row);
            row->probe = p;
            failed += !row->passed;
            nan |= isnan(row->rel_error);
            if (!(row->rel_error <= worst)) worst = row->rel_error;
        }
        rec->probe_rel_error[p] = nan ? NAN : worst;
    }
    if (rec->n_checks > 0 && rec->steps_done == rec->steps_planned)
        rec->validation = failed ? SB_VALIDATION_FAILED : SB_VALIDATION_PASSED;
    return SB_OK;
}
