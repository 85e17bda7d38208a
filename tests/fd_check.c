#include "fd_check.h"
#include "sb_sparse.h"

#include <math.h>
#include <stdlib.h>

int fd_check_problem(sb_problem *p, int level, const double *x, const double *dir, double h0, fd_report *r)
{
    int n = sb_problem_n(p, level);
    double *g = malloc((size_t)n * sizeof(double)), *gp = malloc((size_t)n * sizeof(double));
    double *gm = malloc((size_t)n * sizeof(double)), *xp = malloc((size_t)n * sizeof(double));
    double *Hd = malloc((size_t)n * sizeof(double));
    if (!g || !gp || !gm || !xp || !Hd) return -1;
    double f;
    sb_problem_eval(p, level, x, &f, g, sb_problem_hessian(p, level));
    sb_problem_hess_mult(p, level, dir, Hd);
    sb_problem_constrain(p, level, Hd);
    double gd = sb_dot(n, g, dir), hdn = sb_problem_norm(p, level, Hd);
    r->best_grad = r->best_hess = INFINITY;
    double h = h0;
    for (int k = 0; k < 4; k++, h /= 4) {
        double fp, fm;
        for (int i = 0; i < n; i++) xp[i] = x[i] + h * dir[i];
        sb_problem_eval(p, level, xp, &fp, gp, NULL);
        for (int i = 0; i < n; i++) xp[i] = x[i] - h * dir[i];
        sb_problem_eval(p, level, xp, &fm, gm, NULL);
        double fd = (fp - fm) / (2 * h);
        r->grad_err[k] = fabs(fd - gd) / fmax(fabs(gd), 1e-300);
        double e2 = 0;
        for (int i = 0; i < n; i++) {
            double d = (gp[i] - gm[i]) / (2 * h) - Hd[i];
            e2 += d * d;
        }
        r->hess_err[k] = sqrt(e2) / fmax(hdn, 1e-300);
        r->best_grad = fmin(r->best_grad, r->grad_err[k]);
        r->best_hess = fmin(r->best_hess, r->hess_err[k]);
    }
    free(g); free(gp); free(gm); free(xp); free(Hd);
    return 0;
}
