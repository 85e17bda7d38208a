/* sb_validation.h — a run judged against its scene's expected probe values,
 * separate from solver convergence (docs/trust.md "Validation"). */
#ifndef SB_VALIDATION_H
#define SB_VALIDATION_H

#include "sb_record.h"

/* Judge one expected value against the displacement u = x - X of its probe
 * (rel_error, signed_error, passed); row->probe is left to the caller. */
void sb_check_eval(const sb_probe_check *c, const double u[3], sb_check_row *row);

#endif
