/* fd_check.h — finite-difference checks of a problem's gradient and Hessian,
 * shared by the fixture and method tests.  Central differences at several
 * step sizes; the error must fall as the step shrinks (O(h^2)) until round-off. */
#ifndef FD_CHECK_H
#define FD_CHECK_H

#include "sb_problem.h"

typedef struct fd_report {
    double grad_err[4];    /* relative errors for h = h0, h0/4, h0/16, h0/64 */
    double hess_err[4];
    double best_grad, best_hess;
} fd_report;

/* x: point (finest level or `level`); dir: direction (free dofs only).
 * Compares the directional derivative g.dir with (f(x+h dir)-f(x-h dir))/2h and
 * H dir with (g(x+h dir)-g(x-h dir))/2h over free dofs. */
int fd_check_problem(sb_problem *p, int level, const double *x, const double *dir, double h0, fd_report *r);

#endif
