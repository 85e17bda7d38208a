/* test_regress.c — the nightly regression (core/regress, docs/regression.md):
 * the Mann-Whitney U test against hand-computed values, the verdict rules on
 * made-up samples, the baseline file round trip and its errors, the
 * measurement with an injected clock (known samples: same, 1.5x slower,
 * 2x faster, a confirmed and an unconfirmed timing verdict, a changed
 * count), and the command end to end on a one-case suite: the unchanged
 * build's counts are "same", a changed iteration count is flagged, a
 * baseline whose samples were edited to make this build look 10x slower or
 * faster gives "slower" (confirmed, exit 1) and "faster", and bad input
 * exits 2.  No check here depends on how fast the machine is: time verdicts
 * are asserted only on injected samples or on a 10x effect. */
#include "sb_test.h"
#include "cli_sh.h"
#include "sb_regress_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char tmpdir[256];

SB_TEST(mann_whitney_exact_and_normal)
{
    sb_mwu r;
    const double a[] = { 1, 2, 3 }, b[] = { 4, 5, 6 };
    CHECK_EQ_INT(sb_regress_mwu(a, 3, b, 3, &r), SB_OK);
    CHECK(r.exact);
    CHECK_NEAR(r.u, 0, 0);
    CHECK_NEAR(r.p, 2.0 / 20, 1e-15);   /* one order of 20 in each tail */
    CHECK_EQ_INT(sb_regress_mwu(b, 3, a, 3, &r), SB_OK);
    CHECK_NEAR(r.u, 9, 0);
    CHECK_NEAR(r.p, 2.0 / 20, 1e-15);
    const double x[] = { 1, 2, 3, 4, 5 }, y[] = { 6, 7, 8, 9, 10 };
    CHECK_EQ_INT(sb_regress_mwu(x, 5, y, 5, &r), SB_OK);
    CHECK_NEAR(r.p, 2.0 / 252, 1e-15);
    /* interleaved: x = 1,3,5,7 against y = 2,4,6,8: U = 0+1+2+3 = 6; orders
     * with U <= 6 out of C(8,4) = 70 are 1,1,2,3,5,5,7 for u = 0..6 = 24 */
    const double p[] = { 1, 3, 5, 7 }, q[] = { 2, 4, 6, 8 };
    CHECK_EQ_INT(sb_regress_mwu(p, 4, q, 4, &r), SB_OK);
    CHECK_NEAR(r.u, 6, 0);
    CHECK_NEAR(r.p, 2.0 * 24 / 70, 1e-14);
    /* ties: the normal approximation; identical samples give p = 1 */
    const double t1[] = { 1, 1, 2, 2 }, t2[] = { 1, 1, 2, 2 };
    CHECK_EQ_INT(sb_regress_mwu(t1, 4, t2, 4, &r), SB_OK);
    CHECK(!r.exact);
    CHECK_NEAR(r.p, 1, 1e-12);
    /* large samples: the exact and the normal p agree to a few 1e-3 */
    double u[30], v[30];
    for (int i = 0; i < 30; i++) u[i] = i + 0.25 * (i % 3), v[i] = i + 4.1;
    CHECK_EQ_INT(sb_regress_mwu(u, 30, v, 30, &r), SB_OK);
    CHECK(r.exact);
    double pe = r.p;
    u[0] = u[1];   /* one tie forces the approximation */
    sb_mwu r2;
    CHECK_EQ_INT(sb_regress_mwu(u, 30, v, 30, &r2), SB_OK);
    CHECK(!r2.exact);
    CHECK_MSG(fabs(r2.p - pe) < 0.02, "exact %g, normal %g", pe, r2.p);
    CHECK(sb_regress_mwu(u, 0, v, 3, &r) != SB_OK);
}

static void fill(sb_regress_case *c, double t, int n)
{
    c->ok = 1;
    c->fig.status = 0;
    snprintf(c->fig.reason, sizeof c->fig.reason, "grad_tol");
    c->fig.n[SB_RF_ITERATIONS] = 7;
    c->fig.x[SB_RF_WORK_ASSEMBLY] = 7.25;
    c->fig.has_energy = 1;
    c->fig.energy = -1.5;
    c->fig.n_probes = 1;
    c->fig.probe[0][2] = -0.01;
    c->n_rep = n;
    for (int i = 0; i < n; i++) c->norm[i] = c->cpu[i] = t * (1 + 0.01 * i), c->wall[i] = t;
}

SB_TEST(verdicts)
{
    sb_regress_rules ru;
    sb_regress_rules_default(&ru);
    sb_regress_set base, now;
    memset(&base, 0, sizeof base);
    memset(&now, 0, sizeof now);
    const char *ids[] = { "same", "slower", "faster", "small", "iters", "energy", "failed", "new", "roundoff", "noisy" };
    for (int k = 0; k < 10; k++)
        if (k != 7) fill(sb_regress_set_add(&base, ids[k]), 1.0, 5);   /* "new" is not in the baseline */
    const double scale[] = { 1.0, 2.0, 0.5, 1.05, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0 };
    for (int k = 0; k < 10; k++) fill(sb_regress_set_add(&now, ids[k]), scale[k], 5);
    now.c[4].fig.n[SB_RF_ITERATIONS] = 8;            /* a changed count at equal time */
    now.c[5].fig.energy = -1.5 * (1 + 1e-6);          /* beyond rtol */
    now.c[6].ok = 0, now.c[6].crashed = 1;
    snprintf(now.c[6].failure, sizeof now.c[6].failure, "repeat 1: killed by a signal");
    now.c[8].fig.energy = -1.5 * (1 + 1e-13);         /* round-off: within rtol */
    now.c[8].fig.probe[0][0] = 1e-17;                 /* a zero coordinate off by round-off */
    for (int i = 0; i < 5; i++) now.c[9].norm[i] = i % 2 ? 1.3 : 0.8;   /* large spread, no shift */
    /* a run of 0.02 s slower by 15 % (3 ms, every repeat): below --min-seconds */
    fill(sb_regress_set_add(&base, "short"), 0.02, 5);
    fill(sb_regress_set_add(&now, "short"), 0.023, 5);
    /* 1.5x slower in every repeat: significant (4 vs 4 separated: p = 2/70 < 0.05) and beyond 10 % */
    fill(sb_regress_set_add(&base, "x1.5"), 0.3, 4);
    fill(sb_regress_set_add(&now, "x1.5"), 0.45, 4);
    base.prov.calib_version = now.prov.calib_version = SB_REGRESS_CALIB_VERSION;
    int reg = sb_regress_judge(&now, &base, &ru);
    CHECK_MSG(now.c[11].verdict == SB_VERDICT_SLOWER && fabs(now.c[11].ratio - 1.5) < 1e-12, "x1.5: %s (%s)",
              sb_verdict_name(now.c[11].verdict), now.c[11].detail);
    const sb_verdict want[] = { SB_VERDICT_SAME, SB_VERDICT_SLOWER, SB_VERDICT_FASTER, SB_VERDICT_SAME,
                                SB_VERDICT_CHANGED, SB_VERDICT_CHANGED, SB_VERDICT_FAILED, SB_VERDICT_NEW,
                                SB_VERDICT_SAME, SB_VERDICT_SAME };
    for (int k = 0; k < 10; k++)
        CHECK_MSG(now.c[k].verdict == want[k], "%s: %s (%s)", ids[k], sb_verdict_name(now.c[k].verdict), now.c[k].detail);
    CHECK_MSG(now.c[10].verdict == SB_VERDICT_SAME && strstr(now.c[10].detail, "below the minimum of 10 ms"), "short: %s (%s)",
              sb_verdict_name(now.c[10].verdict), now.c[10].detail);
    ru.min_seconds = 0.001;   /* a finer floor: the same run is slower */
    sb_regress_judge(&now, &base, &ru);
    CHECK_MSG(now.c[10].verdict == SB_VERDICT_SLOWER, "short at 1 ms: %s", now.c[10].detail);
    sb_regress_rules_default(&ru);
    sb_regress_judge(&now, &base, &ru);
    CHECK(strstr(now.c[4].detail, "iterations 7 -> 8") != NULL);
    CHECK(strstr(now.c[5].detail, "energy_final") != NULL);
    CHECK(strstr(now.c[3].detail, "below the minimum effect") != NULL);
    CHECK_EQ_INT(reg, 5);   /* slower, iters, energy, failed, x1.5 */
    /* another calibration kernel: counts still judged, times not */
    base.prov.calib_version = 1;
    CHECK_EQ_INT(sb_regress_judge(&now, &base, &ru), 3);   /* iters, energy, failed */
    CHECK(now.c[11].verdict == SB_VERDICT_SAME);
    CHECK(now.c[1].verdict == SB_VERDICT_SAME && strstr(now.c[1].detail, "calibration kernel"));
    CHECK(now.c[4].verdict == SB_VERDICT_CHANGED);
    /* against no baseline everything is new, nothing a regression */
    CHECK_EQ_INT(sb_regress_judge(&now, NULL, &ru), 1);   /* the failed case still counts */
    CHECK(now.c[0].verdict == SB_VERDICT_NEW);
    CHECK(sb_verdict_is_regression(SB_VERDICT_SLOWER) && !sb_verdict_is_regression(SB_VERDICT_FASTER));
    sb_regress_set_free(&base);
    sb_regress_set_free(&now);
}

SB_TEST(baseline_round_trip_and_errors)
{
    sb_regress_set s, r;
    memset(&s, 0, sizeof s);
    snprintf(s.prov.build, sizeof s.prov.build, "v1-2-gabc");
    snprintf(s.prov.date, sizeof s.prov.date, "2026-12-04T00:00:00Z");
    snprintf(s.prov.blas_core, sizeof s.prov.blas_core, "Prescott");
    s.prov.repeat = 3, s.prov.n_calib = 3, s.prov.calib_median = 0.1, s.prov.load_max = 2.5, s.prov.cores = 2;
    s.prov.calib_version = SB_REGRESS_CALIB_VERSION;
    for (int i = 0; i < 3; i++) s.prov.calib[i] = 0.1 + 0.001 * i;
    sb_regress_case *c = sb_regress_set_add(&s, "plate/bhem-tr-r4.h5");
    fill(c, 0.123456789012345678, 3);
    c->fig.x[SB_RF_CHOL_FLOPS] = 123456789.0;
    c->fig.energy = -1.0 / 3.0;
    char path[400], err[1024];
    snprintf(path, sizeof path, "%s/base.json", tmpdir);
    CHECK_EQ_INT(sb_regress_baseline_write(&s, path, err, sizeof err), SB_OK);
    CHECK_EQ_INT(sb_regress_baseline_read(path, &r, err, sizeof err), SB_OK);
    CHECK_EQ_INT(r.n, 1);
    if (r.n == 1) {
        char what[400];
        CHECK_MSG(!sb_regress_figures_differ(&c->fig, &r.c[0].fig, 0.0, what, sizeof what), "%s", what);
        CHECK_EQ_INT(r.c[0].n_rep, 3);
        CHECK(r.c[0].norm[1] == c->norm[1]);   /* 17 digits: exactly */
        CHECK(!strcmp(r.prov.build, "v1-2-gabc"));
        CHECK(r.prov.calib[2] == s.prov.calib[2]);
        CHECK(r.prov.load_max == 2.5 && r.prov.cores == 2 && r.prov.calib_version == SB_REGRESS_CALIB_VERSION);
    }
    sb_regress_set_free(&r);
    /* damaged files: the file and the member are named */
    FILE *f = fopen(path, "w");
    fprintf(f, "{\"format\": \"shellbench-nightly-baseline\", \"version\": 1, \"provenance\": {\"build\": \"x\"}, \"cases\": []}\n");
    fclose(f);
    CHECK_EQ_INT(sb_regress_baseline_read(path, &r, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, path) && strstr(err, "/provenance/date"), "%s", err);
    f = fopen(path, "w");
    fprintf(f, "{\"format\": \"something else\"}\n");
    fclose(f);
    CHECK_EQ_INT(sb_regress_baseline_read(path, &r, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, "/format"), "%s", err);
    f = fopen(path, "w");
    fprintf(f, "{\"format\": \n");
    fclose(f);
    CHECK_EQ_INT(sb_regress_baseline_read(path, &r, err, sizeof err), SB_ERR_INPUT);
    CHECK_MSG(strstr(err, path) && strstr(err, ":2:"), "%s", err);
    sb_regress_set_free(&s);
}

static int count(const char *hay, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(hay, needle); p; p = strstr(p + 1, needle)) n++;
    return n;
}

/* ---- the measurement with an injected clock -------------------------------- */

/* Known samples: every calibration pass takes 0.1 s; a run of case id takes
 * 0.3 s x (1 + 0.01 rep) x the scale the test sets for that case and
 * measurement (the measurement counted by calibration passes of round 0). */
typedef struct fake_clock {
    int measurement;          /* 0 before the first */
    double scale[4][3];       /* [measurement - 1][case: r4, r6, r8] */
    int runs;
} fake_clock;

static double fake_calibrate(void *ctx, int round)
{
    fake_clock *f = ctx;
    if (round == 0) f->measurement++;
    return 0.1;
}

static double fake_run_seconds(void *ctx, const char *id, int rep, const struct rusage *ru)
{
    fake_clock *f = ctx;
    (void)ru;
    int c = strstr(id, "-r4.h5") ? 0 : strstr(id, "-r6.h5") ? 1 : 2, m = f->measurement - 1;
    f->runs++;
    return 0.3 * (1 + 0.01 * rep) * f->scale[m < 0 ? 0 : m > 3 ? 3 : m][c];
}

static const sb_regress_case *find(const sb_regress_set *s, const char *res)
{
    char id[64];
    snprintf(id, sizeof id, "trampoline/bhem-lsnewton-%s.h5", res);
    return sb_regress_set_find(s, id);
}

SB_TEST(measure_with_injected_clock)
{
    char suite[400], err[2048];
    snprintf(suite, sizeof suite, "%s/suite3.json", tmpdir);
    FILE *f = fopen(suite, "w");
    fprintf(f, "{\"study\": \"three\", \"records\": \"%s/rec3\", \"scenes\": [{\"scene\": \"trampoline\", \"solution\": \"unique\"}],"
               " \"methods\": [\"bhem\"],\n \"solvers\": [\"lsnewton\"], \"res\": [4, 6, 8]}\n", tmpdir);
    fclose(f);
    sb_study *st = calloc(1, sizeof *st);
    CHECK(st != NULL);
    if (!st) return;
    if (sb_study_load(suite, NULL, st, err, sizeof err)) {
        CHECK_MSG(0, "%s", err);
        free(st);
        return;
    }
    fake_clock fc;
    memset(&fc, 0, sizeof fc);
    const double scale[4][3] = { { 1, 1, 1 },        /* the baseline */
                                 { 1, 1.5, 0.5 },    /* now: r4 unchanged, r6 1.5x slower, r8 2x faster */
                                 { 1, 1.5, 1 },      /* the confirmation: r6 still slower, r8 was a passing disturbance */
                                 { 1, 1, 1 } };      /* the changed count (r4 with another gradient tolerance) */
    memcpy(fc.scale, scale, sizeof scale);
    sb_regress_clock clk = { fake_calibrate, fake_run_seconds, &fc };
    sb_regress_run_options o;
    memset(&o, 0, sizeof o);
    o.repeat = 4, o.jobs = 1, o.quiet = 1, o.clock = &clk;
    sb_regress_rules ru;
    sb_regress_rules_default(&ru);
    sb_regress_set base, now, chg;
    memset(&base, 0, sizeof base);
    memset(&now, 0, sizeof now);
    memset(&chg, 0, sizeof chg);
    CHECK_EQ_INT(sb_regress_measure(st, &o, &base, stdout, stderr), 0);
    CHECK_EQ_INT(base.n, 3);
    CHECK_EQ_INT(fc.runs, 12);
    /* the samples are the clock's, normalized by its calibration */
    CHECK(base.prov.n_calib == 4 && base.prov.calib_median == 0.1);
    const sb_regress_case *b4 = find(&base, "r4");
    CHECK(b4 && b4->ok && b4->n_rep == 4);
    if (b4 && b4->n_rep == 4)
        for (int i = 0; i < 4; i++)
            CHECK_MSG(fabs(b4->cpu[i] - 0.3 * (1 + 0.01 * i)) < 1e-15 && fabs(b4->norm[i] - 3 * (1 + 0.01 * i)) < 1e-12,
                      "repeat %d: %g s, normalized %g", i, b4->cpu[i], b4->norm[i]);
    CHECK_EQ_INT(sb_regress_judge(&base, NULL, &ru), 0);
    CHECK_EQ_INT(sb_regress_measure(st, &o, &now, stdout, stderr), 0);
    int regressions = sb_regress_judge(&now, &base, &ru);
    const sb_regress_case *n4 = find(&now, "r4"), *n6 = find(&now, "r6"), *n8 = find(&now, "r8");
    CHECK(n4 && n6 && n8);
    if (!n4 || !n6 || !n8) goto done;
    CHECK_MSG(n4->verdict == SB_VERDICT_SAME, "r4: %s (%s)", sb_verdict_name(n4->verdict), n4->detail);
    CHECK_MSG(n6->verdict == SB_VERDICT_SLOWER && fabs(n6->ratio - 1.5) < 1e-12, "r6: %s (%s)", sb_verdict_name(n6->verdict), n6->detail);
    CHECK_MSG(n8->verdict == SB_VERDICT_FASTER && fabs(n8->ratio - 0.5) < 1e-12, "r8: %s (%s)", sb_verdict_name(n8->verdict), n8->detail);
    CHECK_EQ_INT(regressions, 1);
    /* the confirmation measures r6 and r8 again (8 runs): r6 stays slower,
     * r8's second measurement agrees with the baseline */
    fc.runs = 0;
    CHECK_EQ_INT(sb_regress_confirm(st, &o, &now, &base, &ru, &regressions, stdout, stderr), 0);
    CHECK_EQ_INT(fc.runs, 8);
    n4 = find(&now, "r4"), n6 = find(&now, "r6"), n8 = find(&now, "r8");
    CHECK_MSG(n4->verdict == SB_VERDICT_SAME, "r4: %s", n4->detail);
    CHECK_MSG(n6->verdict == SB_VERDICT_SLOWER && strstr(n6->detail, "; confirmed"), "r6: %s (%s)",
              sb_verdict_name(n6->verdict), n6->detail);
    CHECK_MSG(n8->verdict == SB_VERDICT_SAME && strstr(n8->detail, "not confirmed (first measurement faster"),
              "r8: %s (%s)", sb_verdict_name(n8->verdict), n8->detail);
    CHECK_EQ_INT(regressions, 1);
    /* a changed count at equal (injected) times: changed, judged before time */
    {
        const char *only[] = { "trampoline/bhem-lsnewton-r4.h5" };
        sb_regress_run_options o2 = o;
        o2.n_only = 1, o2.only = only, o2.n_sets = 1, o2.sets[0] = "run.gtol=1e-4";
        CHECK_EQ_INT(sb_regress_measure(st, &o2, &chg, stdout, stderr), 0);
        CHECK_EQ_INT(chg.n, 1);
        CHECK_EQ_INT(sb_regress_judge(&chg, &base, &ru), 1);
        CHECK_MSG(chg.n == 1 && chg.c[0].verdict == SB_VERDICT_CHANGED && fabs(chg.c[0].ratio - 1) < 1e-12,
                  "%s (%s)", sb_verdict_name(chg.c[0].verdict), chg.c[0].detail);
    }
done:
    sb_regress_set_free(&base);
    sb_regress_set_free(&now);
    sb_regress_set_free(&chg);
    sb_study_free(st);
    free(st);
}

/* a copy of the baseline `from` with every time multiplied by factor */
static int scaled_baseline(const char *from, const char *to, double factor)
{
    sb_regress_set s;
    char err[1024];
    if (sb_regress_baseline_read(from, &s, err, sizeof err)) return -1;
    for (int k = 0; k < s.n; k++)
        for (int i = 0; i < s.c[k].n_rep; i++) s.c[k].cpu[i] *= factor, s.c[k].norm[i] *= factor, s.c[k].wall[i] *= factor;
    int rc = sb_regress_baseline_write(&s, to, err, sizeof err);
    sb_regress_set_free(&s);
    return rc;
}

SB_TEST(regress_command_end_to_end)
{
    static char out[200000], err[20000];
    const char *bin = sb_test_bin();
    char suite[400], common[2000], base[400], slow[400], fast[400];
    snprintf(suite, sizeof suite, "%s/suite.json", tmpdir);
    FILE *f = fopen(suite, "w");
    fprintf(f, "{\"study\": \"tiny\", \"records\": \"%s/rec\", \"scenes\": [{\"scene\": \"trampoline\", \"solution\": \"unique\"}], \"methods\": [\"bhem\"],\n"
               " \"solvers\": [\"lsnewton\"], \"res\": [8]}\n", tmpdir);
    fclose(f);
    snprintf(base, sizeof base, "%s/b/base.json", tmpdir);
    snprintf(slow, sizeof slow, "%s/b/base_x0.1.json", tmpdir);
    snprintf(fast, sizeof fast, "%s/b/base_x10.json", tmpdir);
    snprintf(common, sizeof common, "cd %s && %s regress --suite %s --history %s/h/hist.csv --out %s/out --repeat 4 --quiet",
             sb_test_root(), bin, suite, tmpdir, tmpdir);
    int rc, invocations = 0;
    /* no baseline yet: an input error */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s", common, base), 2);
    CHECK_MSG(strstr(err, "--update-baseline"), "%s", err);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --update-baseline", common, base), 0);
    CHECK_MSG(strstr(out, "baseline written"), "%s%s", out, err);
    /* The unchanged build: its counts are "same".  Its times are those of a
     * shared machine, which a test of the harness must not judge (a 1.5x
     * threshold was crossed by chance here): --min-effect 10 asks for an
     * 11-fold change before a time verdict, which no scheduler noise reaches,
     * so the verdict is decided by the deterministic figures alone. */
    rc = sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --min-effect 10", common, base);
    invocations++;
    CHECK_MSG(rc == 0 && strstr(out, "| same |") && !strstr(out, "**changed**") && !strstr(out, "**slower**"),
              "rc %d: %s%s", rc, out, err);
    /* a changed count (the gradient test loosened): flagged whatever the time */
    rc = sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --set run.gtol=1e-4 --min-effect 10", common, base);
    invocations++;
    CHECK_MSG(rc == 1 && strstr(out, "**changed**"), "rc %d: %s%s", rc, out, err);
    /* Time verdicts end to end, on an effect no noise reaches: the baseline's
     * recorded samples scaled by 0.1 (this build looks 10x slower: every one
     * of its samples would have to run 10x faster than the baseline's to
     * overlap) and by 10 (10x faster). */
    CHECK_EQ_INT(scaled_baseline(base, slow, 0.1), 0);
    CHECK_EQ_INT(scaled_baseline(base, fast, 10), 0);
    rc = sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s", common, slow);
    invocations++;
    CHECK_MSG(rc == 1 && strstr(out, "**slower**") && strstr(out, "confirmed"), "rc %d: %s%s", rc, out, err);
    rc = sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --no-confirm", common, fast);
    invocations++;
    CHECK_MSG(rc == 0 && strstr(out, "| faster |"), "rc %d: %s%s", rc, out, err);
    /* bad input: exit 2 with the parameter named */
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --set method.nonsense=1", common, base), 2);
    CHECK_MSG(strstr(err, "method.nonsense"), "%s", err);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --repeat 1", common, base), 2);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --min-seconds -1", common, base), 2);
    CHECK_MSG(strstr(err, "--min-seconds"), "%s", err);
    CHECK_EQ_INT(sb_sh(out, sizeof out, err, sizeof err, "%s --baseline %s --frobnicate", common, base), 2);
    /* the history: one line per case per completed invocation, plus the header */
    char hist[400];
    snprintf(hist, sizeof hist, "%s/h/hist.csv", tmpdir);
    f = fopen(hist, "r");
    CHECK(f != NULL);
    if (f) {
        size_t n = fread(out, 1, sizeof out - 1, f);
        out[n] = 0;
        fclose(f);
        /* the baseline's own invocation and every comparison above */
        CHECK_MSG(count(out, "\n") == 2 + invocations && count(out, "trampoline/bhem-lsnewton-r8.h5") == 1 + invocations,
                  "%d invocations: %s", invocations, out);
        CHECK(strstr(out, ",same,") && strstr(out, ",slower,") && strstr(out, ",faster,") && strstr(out, ",changed,") &&
              strstr(out, ",new,"));
    }
    char report[400];
    snprintf(report, sizeof report, "%s/out/report.md", tmpdir);
    CHECK(access(report, R_OK) == 0);
    /* the picture of the scene's final state, drawn from its record and
       linked under "Final states" with a caption naming the case */
    char png[400];
    snprintf(png, sizeof png, "%s/out/final-trampoline.png", tmpdir);
    f = fopen(png, "rb");
    CHECK_MSG(f != NULL, "%s not drawn", png);
    if (f) {
        unsigned char sig[8];
        CHECK(fread(sig, 1, 8, f) == 8 && !memcmp(sig, "\x89PNG\r\n\x1a\n", 8));
        fclose(f);
    }
    f = fopen(report, "r");
    if (f) {
        size_t n = fread(out, 1, sizeof out - 1, f);
        out[n] = 0;
        fclose(f);
        CHECK_MSG(strstr(out, "## Final states") && strstr(out, "](final-trampoline.png)") &&
                  strstr(out, "`trampoline/bhem-lsnewton-r8.h5`, final state"), "%s", out);
    }
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sb_test_regress_XXXXXX");
    if (!mkdtemp(tmpdir)) return 1;
    /* the suites name bundled scenes: resolved from the project root */
    if (chdir(sb_test_root())) return 1;
    static const sb_test_case cases[] = {
        SB_CASE(mann_whitney_exact_and_normal), SB_CASE(verdicts), SB_CASE(baseline_round_trip_and_errors),
        SB_CASE(measure_with_injected_clock), SB_CASE(regress_command_end_to_end), SB_END,
    };
    int rc = sb_test_main(argc, argv, cases);
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    if (system(cmd)) { /* best effort */ }
    return rc;
}
