/* sb_study_report.c — `shellbench report --study FILE`: report.md and its
 * figures, from the records only (docs/study.md "Reading the report").
 *
 *   1. method selection: per scene with a unique solution and error target,
 *      the cheapest configuration, the runner-up, the cost ratio, and the
 *      configurations that never reach the target
 *   2. work-precision diagrams (error against seconds and work units)
 *   3. performance profiles (Dolan & More 2002) at every error target
 *   4. scenes with several solutions: energy of the minimum found against
 *      the reference's, spread over perturbed starts, convergence and cost
 *      (never ranked by distance to one local minimum)
 *   5. references, per-scene run tables, runs without records, convergence
 *
 * With `deterministic`, wall-clock figures and the machine are left out and
 * costs are work units: the same records give the same bytes. */
#include "sb_study_fig.h"
#include "sb_sysinfo.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct rep {
    const sb_study *st;
    const sb_study_data *d;
    const sb_study_report_options *o;
    FILE *md, *err;
    char dir[1024];
    int n_costs, costs[2];     /* the cost measures shown (seconds first) */
} rep;

static void g3(char *buf, size_t len, double v)
{
    if (!isfinite(v)) snprintf(buf, len, "—");
    else snprintf(buf, len, "%.3g", v);
}

static int unique_ranked(const sb_study *st, int i)
{
    return st->scenes[i].solution == SB_SOLUTION_UNIQUE && st->scenes[i].error != SB_ERRKIND_NONE;
}

static const char *error_words(sb_error_kind e)
{
    switch (e) {
    case SB_ERRKIND_PROBE: return "max probe error, relative to the analytic value";
    case SB_ERRKIND_FIELD_RMS: return "RMS field error against the reference record, / diameter";
    case SB_ERRKIND_FIELD_MAX: return "max field error against the reference record, / diameter";
    default: return "none";
    }
}

/* cost to reach target on scene i for config c; bracket text */
static double reach(const rep *R, int i, int c, int cost, double target, char *how, size_t len)
{
    long lo, hi;
    double best;
    double v = sb_study_reach(R->d, i, c, cost, target, &lo, &hi, &best);
    if (how) {
        if (isfinite(v) && lo == 0) snprintf(how, len, "≤, already at %ld dofs", hi);
        else if (isfinite(v)) snprintf(how, len, "%ld–%ld dofs", lo, hi);
        else if (isfinite(best)) snprintf(how, len, "best %.2g at %ld dofs", best, hi);
        else snprintf(how, len, "no converged run with an error");
    }
    return v;
}

static void selection_table(rep *R, int cost)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    FILE *md = R->md;
    int nc = d->n_configs;
    double *cst = malloc((size_t)nc * sizeof *cst);
    int *ord = malloc((size_t)nc * sizeof *ord);
    char (*how)[128] = malloc((size_t)nc * sizeof *how);
    if (!cst || !ord || !how) goto out;
    fprintf(md, "| scene | error target | cheapest | %s | runner-up | %s | ratio | never reach the target |\n",
            sb_cost_name(cost), sb_cost_name(cost));
    fprintf(md, "|---|--:|---|--:|---|--:|--:|---|\n");
    for (int i = 0; i < st->n_scenes; i++) {
        if (!unique_ranked(st, i)) continue;
        for (int t = 0; t < st->n_targets; t++) {
            int present = 0;
            for (int c = 0; c < nc; c++) {
                cst[c] = reach(R, i, c, cost, st->targets[t], how[c], sizeof how[c]);
                int any = sb_study_has_record(d, i, c);
                if (!any) cst[c] = NAN;   /* no record: not a candidate */
                present += any;
            }
            for (int c = 0; c < nc; c++) if (isnan(cst[c])) cst[c] = INFINITY;
            int nfin = sb_select_order(nc, cst, ord);
            char a[128] = "—", b[128] = "—", ca[64] = "—", cb[64] = "—", ratio[32] = "—", v[32];
            if (nfin >= 1) {
                sb_study_config_label(d, ord[0], a, sizeof a);
                g3(v, sizeof v, cst[ord[0]]);
                snprintf(ca, sizeof ca, "%s (%s)", v, how[ord[0]]);
            }
            if (nfin >= 2) {
                sb_study_config_label(d, ord[1], b, sizeof b);
                g3(v, sizeof v, cst[ord[1]]);
                snprintf(cb, sizeof cb, "%s (%s)", v, how[ord[1]]);
                snprintf(ratio, sizeof ratio, "%.2f", cst[ord[1]] / cst[ord[0]]);
            }
            fprintf(md, "| %s | %g | %s | %s | %s | %s | %s | ", st->scenes[i].name, st->targets[t], a, ca, b, cb, ratio);
            int listed = 0;
            for (int k = nfin; k < nc; k++) {
                int c = ord[k];
                if (!sb_study_has_record(d, i, c)) continue;
                char l[128];
                sb_study_config_label(d, c, l, sizeof l);
                fprintf(md, "%s%s (%s)", listed++ ? "; " : "", l, how[c]);
            }
            fprintf(md, "%s |\n", listed ? "" : (present ? "none" : "no records"));
        }
    }
    fprintf(md, "\n");
out:
    free(cst);
    free(ord);
    free(how);
}

static void figure(rep *R, const char *stem_name, const char *alt)
{
    fprintf(R->md, "![%s](%s.png)  \n[SVG](%s.svg)\n\n", alt, stem_name, stem_name);
}

static void work_precision(rep *R)
{
    const sb_study *st = R->st;
    char stem[1200], name[256], msg[1024];
    fprintf(R->md, "## Work-precision diagrams\n\nError against cost, log-log; one curve per method/solver (the "
                   "unperturbed start, converged runs only), one point per resolution labelled by its dofs; the grey "
                   "staircase and circles mark the Pareto front (no other run is both cheaper and more accurate); "
                   "dashed lines are the error targets.\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        if (!unique_ranked(st, i)) continue;
        fprintf(R->md, "### %s — %s\n\n", st->scenes[i].name, error_words(st->scenes[i].error));
        for (int k = 0; k < R->n_costs; k++) {
            int cost = R->costs[k];
            snprintf(name, sizeof name, "wp-%s-%s", st->scenes[i].name, cost == SB_COST_SECONDS ? "seconds" : "work");
            snprintf(stem, sizeof stem, "%s/%s", R->dir, name);
            if (sb_fig_work_precision(R->d, i, cost, stem, R->o->gnuplot, msg, sizeof msg) == 0) figure(R, name, name);
            else fprintf(R->err, "shellbench report: warning: %s\n", msg), fprintf(R->md, "(%s)\n\n", msg);
        }
    }
}

static void profiles(rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    int np = 0, nc = d->n_configs, scenes[SB_STUDY_MAX_SCENES];
    for (int i = 0; i < st->n_scenes; i++) if (unique_ranked(st, i)) scenes[np++] = i;
    /* configurations with at least one record on those scenes */
    int *cfg = malloc((size_t)nc * sizeof *cfg), ns = 0;
    if (!cfg) return;
    for (int c = 0; c < nc; c++) {
        int any = 0;
        for (int p = 0; p < np; p++) any |= sb_study_has_record(d, scenes[p], c);
        if (any) cfg[ns++] = c;
    }
    fprintf(R->md, "## Performance profiles\n\nDolan & Moré (2002): for each configuration, ρ(τ) is the share of the "
                   "%d scenes with a unique solution on which it reaches the error target at a cost within a factor τ of the "
                   "cheapest configuration on that scene (cost to reach a target: docs/study.md; a scene no configuration "
                   "reaches counts as unsolved for all).  ρ(1): how often it is the cheapest; ρ at the right end: how often "
                   "it reaches the target at all.\n\n", np);
    if (np == 0 || ns == 0) {
        fprintf(R->md, "(no scene with a unique solution and records)\n\n");
        free(cfg);
        return;
    }
    double *t = malloc((size_t)np * ns * sizeof *t), *ratio = malloc((size_t)np * ns * sizeof *ratio);
    char (*labels)[128] = malloc((size_t)ns * sizeof *labels);
    if (!t || !ratio || !labels) goto out;
    for (int s = 0; s < ns; s++) sb_study_config_label(d, cfg[s], labels[s], sizeof labels[s]);
    for (int k = 0; k < R->n_costs; k++)
        for (int tg = 0; tg < st->n_targets; tg++) {
            int cost = R->costs[k];
            for (int p = 0; p < np; p++)
                for (int s = 0; s < ns; s++) t[p * ns + s] = reach(R, scenes[p], cfg[s], cost, st->targets[tg], NULL, 0);
            sb_profile_ratios(np, ns, t, ratio);
            char name[256], stem[1200], title[256], msg[1024];
            snprintf(name, sizeof name, "profile-%s-%g", cost == SB_COST_SECONDS ? "seconds" : "work", st->targets[tg]);
            snprintf(stem, sizeof stem, "%s/%s", R->dir, name);
            snprintf(title, sizeof title, "performance profile: %s to reach error %g (%d scenes)", sb_cost_name(cost), st->targets[tg], np);
            fprintf(R->md, "### %s to reach error %g\n\n", sb_cost_name(cost), st->targets[tg]);
            if (sb_fig_profile(np, ns, ratio, labels, title, stem, R->o->gnuplot, msg, sizeof msg) == 0) figure(R, name, title);
            else fprintf(R->err, "shellbench report: warning: %s\n", msg);
            fprintf(R->md, "| configuration | ρ(1) cheapest | ρ(2) | ρ(4) | ρ(∞) reaches the target |\n|---|--:|--:|--:|--:|\n");
            for (int s = 0; s < ns; s++)
                fprintf(R->md, "| %s | %.2f | %.2f | %.2f | %.2f |\n", labels[s], sb_profile_rho(np, ns, ratio, s, 1.0),
                        sb_profile_rho(np, ns, ratio, s, 2.0), sb_profile_rho(np, ns, ratio, s, 4.0),
                        sb_profile_rho(np, ns, ratio, s, INFINITY));
            fprintf(R->md, "\n");
        }
out:
    free(t);
    free(ratio);
    free(labels);
    free(cfg);
}

static void status_words(const sb_study_point *q, char *buf, size_t len)
{
    if (q->status == 0) snprintf(buf, len, "converged");
    else snprintf(buf, len, "**not converged** (%s, %d of %d steps)", q->reason, q->steps, q->steps_planned);
}

/* distance between two starts' final surfaces / diameter (RMS) */
static double start_distance(const sb_study_data *d, int i, const sb_study_point *a, const sb_study_point *b)
{
    if (!a->pos || !b->pos || a->n_samples != b->n_samples || a->n_samples == 0) return NAN;
    double rms, mx;
    sb_field_error(a->n_samples, a->pos, b->pos, d->diameter[i], &rms, &mx);
    return mx;
}

static void multiple_scenes(rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    int any = 0;
    for (int i = 0; i < st->n_scenes; i++) any |= st->scenes[i].n_seeds > 0 || st->scenes[i].solution == SB_SOLUTION_MULTIPLE;
    if (!any) return;
    fprintf(R->md, "## Scenes with several solutions, and perturbed starts\n\n"
                   "The buckled, nonconvex cloth scenes have many local minima: a method that lands in another minimum "
                   "than the reference has not made an error, so these scenes are **not ranked by distance to the "
                   "reference** and take no part in the selection table or the profiles.  What is compared instead: "
                   "whether the run converged and at what cost, the energy E of the minimum it found against the "
                   "reference's (ΔE = (E − E_ref)/|E_ref|, negative: a lower minimum than the reference's), and the "
                   "spread over perturbed starts (`run.perturb`, `run.seed`): how far apart in energy (ΔE spread) and in "
                   "shape (max |x_a − x_b| / diameter between the starts' final surfaces) the minima reached from nearby "
                   "starts are.  On a scene with a unique solution the same columns check uniqueness: the starts should "
                   "agree to the solver tolerance.\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        const sb_study_scene *sc = &st->scenes[i];
        if (!(sc->n_seeds > 0 || sc->solution == SB_SOLUTION_MULTIPLE)) continue;
        double eref = d->has_ref[i] ? d->ref[i].energy : NAN;
        char v[32];
        g3(v, sizeof v, eref);
        fprintf(R->md, "### %s (%s solution%s)\n\nE_ref = %s J%s.  Starts: the unperturbed one", sc->name,
                sc->solution == SB_SOLUTION_UNIQUE ? "unique" : "several", sc->solution == SB_SOLUTION_UNIQUE ? "" : "s", v,
                d->has_ref[i] ? "" : " (no reference record: ΔE is left out)");
        if (sc->n_seeds) fprintf(R->md, " and %d perturbed by ±%g per dof (seeds", sc->n_seeds, sc->perturb);
        for (int k = 0; k < sc->n_seeds; k++) fprintf(R->md, "%s%ld", k ? ", " : " ", sc->seeds[k]);
        fprintf(R->md, "%s.\n\n", sc->n_seeds ? ")" : "");
        fprintf(R->md, "| configuration | dofs | unperturbed start | iterations | %s WU | E (J) | ΔE | starts converged | ΔE spread | max shape distance between starts |\n",
                R->o->deterministic ? "" : "seconds |");
        fprintf(R->md, "|---|--:|---|--:|%s--:|--:|--:|--:|--:|--:|\n", R->o->deterministic ? "" : "--:|");
        for (int k = 0; k < d->plan.n; k++) {
            const sb_plan_run *r = &d->plan.runs[k];
            const sb_study_point *q = &d->pt[k];
            if (r->scene != i || r->start != 0 || q->state != SB_POINT_RECORDED) continue;
            char label[128], stw[128], sec[32], wu[32], e[32], de[32], spread[32], dist[32];
            sb_study_config_label(d, q->config, label, sizeof label);
            status_words(q, stw, sizeof stw);
            g3(sec, sizeof sec, q->seconds);
            g3(wu, sizeof wu, q->work);
            snprintf(e, sizeof e, isfinite(q->energy) ? "%.6g" : "—", q->energy);
            g3(de, sizeof de, isfinite(eref) && q->status == 0 ? (q->energy - eref) / fabs(eref) : NAN);
            /* the other starts of this configuration and resolution */
            int conv = q->status == 0, total = 1;
            double emin = q->status == 0 ? q->energy : INFINITY, emax = q->status == 0 ? q->energy : -INFINITY, dmax = 0;
            int have_d = 0;
            for (int j = 0; j < d->plan.n; j++) {
                const sb_plan_run *rj = &d->plan.runs[j];
                if (rj->scene != i || rj->start == 0 || d->pt[j].config != q->config || rj->res != r->res) continue;
                total++;
                if (d->pt[j].state != SB_POINT_RECORDED || d->pt[j].status != 0) continue;
                conv++;
                emin = fmin(emin, d->pt[j].energy), emax = fmax(emax, d->pt[j].energy);
                if (q->status == 0) {
                    double dd = start_distance(d, i, q, &d->pt[j]);
                    if (isfinite(dd)) dmax = fmax(dmax, dd), have_d = 1;
                }
            }
            double scale = isfinite(eref) ? fabs(eref) : fabs(q->energy);
            g3(spread, sizeof spread, total > 1 && conv > 1 ? (emax - emin) / scale : NAN);
            g3(dist, sizeof dist, have_d ? dmax : NAN);
            fprintf(R->md, "| %s | %ld | %s | %d | %s%s%s | %s | %s | %d of %d | %s | %s |\n", label, q->dofs, stw,
                    q->iterations, R->o->deterministic ? "" : sec, R->o->deterministic ? "" : " | ", wu, e, de, conv, total, spread, dist);
        }
        fprintf(R->md, "\n");
    }
}

static void references(rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    fprintf(R->md, "## References\n\n| scene | solution | ranked by | reference |\n|---|---|---|---|\n");
    for (int i = 0; i < st->n_scenes; i++) {
        const sb_study_scene *sc = &st->scenes[i];
        char ref[1400];
        if (d->has_ref[i]) snprintf(ref, sizeof ref, "`%s`: %s/%s, %ld dofs (res %d, %d level%s)", d->ref[i].path, d->ref[i].method,
                                    d->ref[i].solver, d->ref[i].dofs, d->ref[i].res, d->ref[i].levels, d->ref[i].levels > 1 ? "s" : "");
        else snprintf(ref, sizeof ref, "%s", d->ref_why[i][0] ? d->ref_why[i] : "none");
        fprintf(R->md, "| %s | %s | %s | %s |\n", sc->name, sc->solution == SB_SOLUTION_UNIQUE ? "unique" : "several (not ranked)",
                sc->solution == SB_SOLUTION_UNIQUE ? error_words(sc->error) : "energy, convergence, cost", ref);
    }
    fprintf(R->md, "\nWhy each bundled scene has the reference it has: docs/study.md \"References\".\n\n");
}

static void run_tables(rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    fprintf(R->md, "## Runs\n\nEvery record of the study (the unperturbed start); errors as defined per scene above "
                   "(probe: relative to the analytic value or, with a reference record, distance / diameter).\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        fprintf(R->md, "### %s\n\n| configuration | res | dofs | status | steps | iterations | %sassembly WU | probe error | RMS field error | max field error |\n"
                       "|---|--:|--:|---|--:|--:|%s--:|--:|--:|--:|\n", st->scenes[i].name, R->o->deterministic ? "" : "seconds | ",
                R->o->deterministic ? "" : "--:|");
        for (int k = 0; k < d->plan.n; k++) {
            const sb_plan_run *r = &d->plan.runs[k];
            const sb_study_point *q = &d->pt[k];
            if (r->scene != i || r->start != 0 || q->state != SB_POINT_RECORDED) continue;
            char label[128], stw[160], sec[32], wu[32], ep[32], er[32], em[32];
            sb_study_config_label(d, q->config, label, sizeof label);
            status_words(q, stw, sizeof stw);
            g3(sec, sizeof sec, q->seconds);
            g3(wu, sizeof wu, q->work);
            g3(ep, sizeof ep, q->err_probe);
            g3(er, sizeof er, q->err_rms);
            g3(em, sizeof em, q->err_max);
            fprintf(R->md, "| %s | %d | %ld | %s | %d | %d | %s%s%s | %s | %s | %s |\n", label, r->res, q->dofs, stw, q->steps,
                    q->iterations, R->o->deterministic ? "" : sec, R->o->deterministic ? "" : " | ", wu, ep, er, em);
        }
        fprintf(R->md, "\n");
    }
}

static void without_records(rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    int any = 0;
    for (int k = 0; k < d->plan.n; k++) {
        const sb_study_point *q = &d->pt[k];
        const sb_plan_run *r = &d->plan.runs[k];
        if (q->state == SB_POINT_RECORDED) continue;
        if (!any++) fprintf(R->md, "## Runs without a record\n\n| scene | configuration | res | start | state | why |\n|---|---|--:|--:|---|---|\n");
        char label[128];
        sb_study_config_label(d, q->config, label, sizeof label);
        static const char *const words[] = { "recorded", "refused", "missing", "skipped", "not applicable" };
        char res[16] = "—";
        if (r->res) snprintf(res, sizeof res, "%d", r->res);
        fprintf(R->md, "| %s | %s | %s | %d | %s | %s |\n", st->scenes[r->scene].name, label, res, r->start,
                words[q->state], q->why);
    }
    if (any) fprintf(R->md, "\nRefused: the method or solver cannot honour the scene (the sentence is its own); "
                            "missing: not run yet or failed without a record (run the sweep again).\n\n");
}

static void convergence(rep *R)
{
    const sb_study *st = R->st;
    char name[256], stem[1200], msg[1024];
    fprintf(R->md, "## Convergence\n\nlog10 ‖g‖ of every outer iteration on the finest level over all steps, one line "
                   "per configuration at the resolution nearest the scene's middle dof count.\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        snprintf(name, sizeof name, "convergence-%s", st->scenes[i].name);
        snprintf(stem, sizeof stem, "%s/%s", R->dir, name);
        if (sb_fig_convergence(R->d, i, stem, R->o->gnuplot, msg, sizeof msg) == 0) {
            fprintf(R->md, "### %s%s\n\n", st->scenes[i].name,
                    st->scenes[i].solution == SB_SOLUTION_MULTIPLE ? " (several solutions: runs may end in different minima)" : "");
            figure(R, name, name);
        } else {
            fprintf(R->err, "shellbench report: warning: %s\n", msg);
        }
    }
}

static void header(rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    int planned = 0, rec = 0, conv = 0, refused = 0, missing = 0;
    double secs = 0;
    char builds[512] = "";
    for (int k = 0; k < d->plan.n; k++) {
        const sb_study_point *q = &d->pt[k];
        planned += d->plan.runs[k].state == SB_PLAN_RUN || q->state == SB_POINT_REFUSED;
        rec += q->state == SB_POINT_RECORDED;
        conv += q->state == SB_POINT_RECORDED && q->status == 0;
        refused += q->state == SB_POINT_REFUSED;
        missing += q->state == SB_POINT_MISSING;
        if (q->state == SB_POINT_RECORDED) {
            secs += q->seconds;
            if (!strstr(builds, q->build) && strlen(builds) + strlen(q->build) + 3 < sizeof builds)
                snprintf(builds + strlen(builds), sizeof builds - strlen(builds), "%s%s", builds[0] ? ", " : "", q->build);
        }
    }
    fprintf(R->md, "# Study `%s`: which method and solver reach an error budget fastest\n\n", st->name);
    if (st->description[0]) fprintf(R->md, "%s\n\n", st->description);
    fprintf(R->md, "Study file `%s`, records under `%s`.  %d runs: %d recorded (%d converged), %d refused, %d not run.  "
                   "Generated by `shellbench report --study %s` from the records only.\n\n",
            st->path, st->records, planned, rec, conv, refused, missing, st->path);
    if (!R->o->deterministic) {
        char cpu[128];
        sb_sysinfo_cpu_model(cpu, sizeof cpu);
        fprintf(R->md, "Builds of the records: %s.  Sum of the recorded run times: %.0f s.  Seconds are wall clock of one "
                       "run on one core (OPENBLAS_NUM_THREADS=1); runs of a sweep with several jobs ran side by side on a "
                       "shared machine, so compare seconds as ratios and trust work units for small differences.\n\n",
                builds[0] ? builds : "—", secs);
    } else {
        fprintf(R->md, "(Deterministic report: wall-clock figures left out, costs in assembly work units.)\n\n");
    }
}

static int mkdir_p(const char *dir)
{
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s/", dir);
    for (char *p = tmp + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0777) && errno != EEXIST) return -1;
            *p = '/';
        }
    return 0;
}

int sb_study_report(const sb_study *st, const sb_study_report_options *o, FILE *err)
{
    sb_study_data d;
    if (st->kind == SB_STUDY_DT_STABILITY) return sb_study_dt_report(st, o, err);
    if (sb_study_data_load(st, &d, err)) return SB_EXIT_INPUT;
    rep R = { st, &d, o, NULL, err, "", 0, { 0, 0 } };
    snprintf(R.dir, sizeof R.dir, "%s", o->out_dir ? o->out_dir : st->records);
    if (o->deterministic) R.costs[R.n_costs++] = SB_COST_WORK;
    else R.costs[R.n_costs++] = SB_COST_SECONDS, R.costs[R.n_costs++] = SB_COST_WORK;
    char path[1200], tmp[1300];
    snprintf(path, sizeof path, "%s/report.md", R.dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    if (mkdir_p(R.dir) || !(R.md = fopen(tmp, "w"))) {
        fprintf(err, "shellbench report: cannot write %s: %s\n", path, strerror(errno));
        sb_study_data_free(&d);
        return SB_EXIT_INPUT;
    }
    header(&R);
    fprintf(R.md, "## Method selection\n\nPer scene with a unique solution and error target: the configuration "
                  "(method/solver) that reaches the target cheapest, the runner-up and the ratio of their costs.  The cost "
                  "to reach a target is interpolated log-log between the two resolutions that bracket it, never "
                  "extrapolated (\"≤, already at N dofs\": the coarsest run is below the target already); configurations "
                  "whose finest converged run misses the target are listed with their best error.  Scenes with several "
                  "solutions are not in this table (see below).\n\n");
    for (int k = 0; k < R.n_costs; k++) {
        if (R.n_costs > 1) fprintf(R.md, "### By %s%s\n\n", sb_cost_name(R.costs[k]),
                                   R.costs[k] == SB_COST_WORK ? " (one WU = one fine-level assembly of that method: compare solvers of one method)" : "");
        selection_table(&R, R.costs[k]);
    }
    work_precision(&R);
    profiles(&R);
    multiple_scenes(&R);
    references(&R);
    run_tables(&R);
    without_records(&R);
    convergence(&R);
    fprintf(R.md, "## How to read this report\n\nSee docs/study.md: the study file, the reference policy per scene, how the "
                  "cost to reach a target is interpolated, and how to read the diagrams, profiles and the selection table.\n");
    int bad = ferror(R.md);
    if (fclose(R.md) || bad || rename(tmp, path)) {
        fprintf(err, "shellbench report: cannot write %s\n", path);
        unlink(tmp);
        sb_study_data_free(&d);
        return SB_EXIT_INTERNAL;
    }
    fprintf(err, "shellbench report: %s\n", path);
    sb_study_data_free(&d);
    return 0;
}
