/* sb_regress_judge.c — one verdict per case of the nightly regression
 * (docs/regression.md "Verdicts"), in this order:
 *
 *   failed   no repeat left a readable record (internal error, crash)
 *   changed  a deterministic figure differs from the baseline's (counts,
 *            work units, nnz, flops, status and reason exactly; energy and
 *            probe positions beyond rtol), or differs between the repeats
 *            of this invocation; judged before time, so a changed count is
 *            flagged even when the time is equal
 *   new      the baseline has no such case
 *   slower / faster  the normalized CPU times (cpu / calibration median)
 *            differ from the baseline's by a two-sided Mann-Whitney U test
 *            at level alpha AND the medians differ by at least min_effect
 *            AND the change is at least min_seconds of this run's CPU time
 *            (the test alone calls a 1 % change significant once samples
 *            are large; the effect alone would call noise a change; runs of
 *            a few hundredths of a second move by more than 10 % between
 *            invocations of the same build)
 *   same     otherwise (also when the baseline's calibration kernel is
 *            another version: its normalized times mean something else).
 * slower, changed and failed are regressions (exit code 1). */
#include "sb_regress.h"
#include "sb_gsl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const names[SB_VERDICT_COUNT] = { "same", "faster", "slower", "changed", "failed", "new" };

const char *sb_verdict_name(sb_verdict v) { return v >= 0 && v < SB_VERDICT_COUNT ? names[v] : "?"; }

int sb_verdict_is_regression(sb_verdict v)
{
    return v == SB_VERDICT_SLOWER || v == SB_VERDICT_CHANGED || v == SB_VERDICT_FAILED;
}

void sb_regress_rules_default(sb_regress_rules *r)
{
    r->alpha = 0.05;
    r->min_effect = 0.10;
    r->min_seconds = 0.01;
    r->rtol = 1e-9;
}

void sb_regress_set_free(sb_regress_set *s)
{
    free(s->c);
    s->c = NULL;
    s->n = s->cap = 0;
}

sb_regress_case *sb_regress_set_add(sb_regress_set *s, const char *id)
{
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 32;
        sb_regress_case *c = realloc(s->c, (size_t)cap * sizeof *c);
        if (!c) return NULL;
        s->c = c, s->cap = cap;
    }
    sb_regress_case *c = &s->c[s->n++];
    memset(c, 0, sizeof *c);
    snprintf(c->id, sizeof c->id, "%s", id);
    c->ratio = NAN, c->p = NAN;
    return c;
}

const sb_regress_case *sb_regress_set_find(const sb_regress_set *s, const char *id)
{
    for (int k = 0; s && k < s->n; k++)
        if (!strcmp(s->c[k].id, id)) return &s->c[k];
    return NULL;
}

static double median(const double *x, int n)
{
    double m = NAN;
    if (n > 0 && sb_median(x, (size_t)n, &m)) m = NAN;
    return m;
}

static void judge_time(sb_regress_case *c, const sb_regress_case *b, const sb_regress_rules *ru)
{
    double mn = median(c->norm, c->n_rep), mb = median(b->norm, b->n_rep);
    c->ratio = mn / mb;
    sb_mwu t;
    if (sb_regress_mwu(c->norm, c->n_rep, b->norm, b->n_rep, &t)) {
        c->verdict = SB_VERDICT_SAME;
        snprintf(c->detail, sizeof c->detail, "no U test (no samples)");
        return;
    }
    c->p = t.p;
    /* the change in this run's seconds: its median CPU time times |ratio - 1| */
    const double dsec = fabs(c->ratio - 1) * median(c->cpu, c->n_rep);
    int significant = t.p < ru->alpha, large = fabs(c->ratio - 1) >= ru->min_effect;
    int long_enough = !(dsec < ru->min_seconds);
    c->verdict = significant && large && long_enough ? (c->ratio > 1 ? SB_VERDICT_SLOWER : SB_VERDICT_FASTER)
                                                     : SB_VERDICT_SAME;
    char why[96] = "";
    if (c->verdict == SB_VERDICT_SAME) {
        if (!significant) snprintf(why, sizeof why, ": not significant");
        else if (!large) snprintf(why, sizeof why, ": below the minimum effect");
        else snprintf(why, sizeof why, ": a change of %.1f ms, below the minimum of %.0f ms", 1e3 * dsec, 1e3 * ru->min_seconds);
    }
    snprintf(c->detail, sizeof c->detail, "median x%.3f, p = %.3g (%s, %d vs %d)%s", c->ratio, t.p,
             t.exact ? "exact" : "normal approx.", c->n_rep, b->n_rep, why);
}

int sb_regress_judge(sb_regress_set *now, const sb_regress_set *base, const sb_regress_rules *ru)
{
    int regressions = 0;
    for (int k = 0; k < now->n; k++) {
        sb_regress_case *c = &now->c[k];
        const sb_regress_case *b = sb_regress_set_find(base, c->id);
        char what[400];
        if (!c->ok || c->crashed) {
            c->verdict = SB_VERDICT_FAILED;
            snprintf(c->detail, sizeof c->detail, "%s", c->failure);
        } else if (c->failure[0]) {   /* repeats disagree: not reproducible */
            c->verdict = SB_VERDICT_CHANGED;
            snprintf(c->detail, sizeof c->detail, "%s", c->failure);
        } else if (!b || !b->ok) {
            c->verdict = SB_VERDICT_NEW;
            snprintf(c->detail, sizeof c->detail, "%s", b ? "the baseline has no figures of this case" : "not in the baseline");
        } else if (sb_regress_figures_differ(&b->fig, &c->fig, ru->rtol, what, sizeof what)) {
            c->verdict = SB_VERDICT_CHANGED;
            snprintf(c->detail, sizeof c->detail, "%s", what);
            c->ratio = median(c->norm, c->n_rep) / median(b->norm, b->n_rep);
        } else if (base->prov.calib_version != now->prov.calib_version) {
            c->verdict = SB_VERDICT_SAME;
            snprintf(c->detail, sizeof c->detail, "figures agree; times not compared: the baseline's calibration kernel "
                     "is version %d, this one %d (update the baseline)", base->prov.calib_version, now->prov.calib_version);
        } else {
            judge_time(c, b, ru);
        }
        regressions += sb_verdict_is_regression(c->verdict);
    }
    return regressions;
}
