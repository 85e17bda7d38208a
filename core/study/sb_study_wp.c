/* sb_study_wp.c — what work-precision diagrams, performance profiles and the
 * selection table are computed from: Pareto fronts, the cost at which a
 * curve reaches an error target, Dolan & More (2002) profiles, and the
 * order of configurations by cost (sb_study_data.h).  Plain arrays in and
 * out, no I/O: tests/test_study_wp.c checks them on hand-made data. */
#include "sb_study_data.h"

#include <gsl/gsl_sort.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void sb_wp_pareto(int n, const double *cost, const double *err, int *on_front)
{
    for (int i = 0; i < n; i++) {
        on_front[i] = isfinite(cost[i]) && isfinite(err[i]);
        for (int j = 0; j < n && on_front[i]; j++) {
            if (j == i || !isfinite(cost[j]) || !isfinite(err[j])) continue;
            if (cost[j] <= cost[i] && err[j] <= err[i] && (cost[j] < cost[i] || err[j] < err[i])) on_front[i] = 0;
        }
    }
}

double sb_wp_cost_to_reach(int n, const double *cost, const double *err, double target, int *from, int *at_first)
{
    *from = -1;
    *at_first = 0;
    if (n <= 0 || !(err[n - 1] <= target)) return INFINITY;
    int i = n - 1;
    while (i > 0 && err[i - 1] <= target) i--;   /* from i on, every point is below the target */
    *from = i;
    if (i == 0) {
        *at_first = 1;
        return cost[0];
    }
    /* err[i-1] > target >= err[i]: log c linear in log e between them */
    double le0 = log(err[i - 1]), le1 = log(err[i]), lc0 = log(cost[i - 1]), lc1 = log(cost[i]);
    if (!(le0 > le1) || !isfinite(lc0) || !isfinite(lc1)) return cost[i];
    double w = (log(target) - le0) / (le1 - le0);   /* in (0, 1] */
    return exp(lc0 + w * (lc1 - lc0));
}

void sb_profile_ratios(int np, int ns, const double *t, double *ratio)
{
    for (int p = 0; p < np; p++) {
        double best = INFINITY;
        for (int s = 0; s < ns; s++) if (t[p * ns + s] < best) best = t[p * ns + s];
        for (int s = 0; s < ns; s++) {
            double v = t[p * ns + s];
            ratio[p * ns + s] = isfinite(best) && isfinite(v) && best > 0 ? v / best : INFINITY;
        }
    }
}

double sb_profile_rho(int np, int ns, const double *ratio, int s, double tau)
{
    if (np <= 0) return 0;
    int k = 0;
    for (int p = 0; p < np; p++) k += isfinite(ratio[p * ns + s]) && ratio[p * ns + s] <= tau;
    return (double)k / np;
}

int sb_select_order(int n, const double *cost, int *order)
{
    if (n <= 0) return 0;
    /* gsl_sort_index is not stable: sort (cost, index) pairs instead by
     * ordering on the cost with the index as tie-break */
    double *key = malloc((size_t)n * sizeof *key);
    size_t *perm = malloc((size_t)n * sizeof *perm);
    int finite = 0;
    if (!key || !perm) {
        for (int i = 0; i < n; i++) order[i] = i;
        free(key);
        free(perm);
        return 0;
    }
    for (int i = 0; i < n; i++) {
        key[i] = isfinite(cost[i]) ? cost[i] : HUGE_VAL;
        finite += isfinite(cost[i]) != 0;
    }
    gsl_sort_index(perm, key, 1, (size_t)n);
    for (int i = 0; i < n; i++) order[i] = (int)perm[i];
    /* ties (equal keys, e.g. all infinite) by index: insertion sort on the
     * few equal runs */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && key[order[j - 1]] == key[order[j]] && order[j - 1] > order[j]; j--) {
            int tmp = order[j];
            order[j] = order[j - 1];
            order[j - 1] = tmp;
        }
    free(key);
    free(perm);
    return finite;
}
