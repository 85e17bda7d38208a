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
#include "sb_study_rep.h"
#include "sb_sysinfo.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void sb_rep_g3(char *buf, size_t len, double v)
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
static double reach(const sb_rep *R, int i, int c, int cost, double target, char *how, size_t len)
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

static void selection_table(sb_rep *R, int cost)
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
                sb_rep_g3(v, sizeof v, cst[ord[0]]);
                snprintf(ca, sizeof ca, "%s (%s)", v, how[ord[0]]);
            }
            if (nfin >= 2) {
                sb_study_config_label(d, ord[1], b, sizeof b);
                sb_rep_g3(v, sizeof v, cst[ord[1]]);
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

/* a figure that was not written: a warning, or (a refused output path) an
 * error that makes the report exit 2 */
static void fig_failed(sb_rep *R, int rc, const char *msg)
{
    if (rc == SB_FIG_REFUSED) R->refused++, fprintf(R->err, "shellbench report: %s\n", msg);
    else fprintf(R->err, "shellbench report: warning: %s\n", msg);
}

/* The record drawn for scene i: the finest converged record of the
 * unperturbed start (most dofs; ties: the first in the plan), else the
 * scene's reference record; NULL when there is neither. */
static const char *thumb_record(const sb_rep *R, int i, char *what, size_t len)
{
    const sb_study_data *d = R->d;
    int best = -1;
    for (int k = 0; k < d->plan.n; k++) {
        const sb_study_point *q = &d->pt[k];
        if (d->plan.runs[k].scene != i || d->plan.runs[k].start != 0 || q->state != SB_POINT_RECORDED || q->status) continue;
        if (best < 0 || q->dofs > d->pt[best].dofs) best = k;
    }
    if (best >= 0) {
        char label[128];
        sb_study_config_label(d, d->pt[best].config, label, sizeof label);
        snprintf(what, len, "final state of the finest converged run, %s at %ld dofs", label, d->pt[best].dofs);
        return d->plan.runs[best].out;
    }
    if (d->has_ref[i]) {
        snprintf(what, len, "final state of the reference, %s/%s at %ld dofs (no converged run of the study)",
                 d->ref[i].method, d->ref[i].solver, d->ref[i].dofs);
        return d->ref[i].path;
    }
    return NULL;
}

/* every scene's picture, drawn once into the report's directory */
static void thumbnails(sb_rep *R)
{
    for (int i = 0; i < R->st->n_scenes; i++) {
        char what[300], png[1300], msg[1500];
        const char *rec = thumb_record(R, i, what, sizeof what);
        R->thumb[i] = 0;
        if (!rec) {
            snprintf(R->thumb_caption[i], sizeof R->thumb_caption[i], "no picture: no converged run and no reference record");
            continue;
        }
        snprintf(png, sizeof png, "%s/thumb-%s.png", R->dir, R->st->scenes[i].name);
        int rc = sb_study_thumbnail(rec, png, msg, sizeof msg);
        if (rc == 0) {
            R->thumb[i] = 1;
            snprintf(R->thumb_caption[i], sizeof R->thumb_caption[i], "%s (`shellbench render`, %dx%d, %d samples per pixel)",
                     what, SB_THUMB_W, SB_THUMB_H, SB_THUMB_SPP);
        } else {
            fig_failed(R, rc, msg);
            snprintf(R->thumb_caption[i], sizeof R->thumb_caption[i], "no picture: %s", rc == SB_FIG_REFUSED ? "its path was refused" : "the record cannot be drawn (the report's warnings say why)");
        }
    }
}

void sb_rep_thumb(sb_rep *R, int i)
{
    if (R->thumb[i]) fprintf(R->md, "![%s: final state](thumb-%s.png)  \n*%s: %s.*\n\n", R->st->scenes[i].name,
                             R->st->scenes[i].name, R->st->scenes[i].name, R->thumb_caption[i]);
    else fprintf(R->md, "*%s: %s.*\n\n", R->st->scenes[i].name, R->thumb_caption[i]);
}

static void figure(sb_rep *R, const char *stem_name, const char *alt)
{
    fprintf(R->md, "![%s](%s.png)  \n[SVG](%s.svg)\n\n", alt, stem_name, stem_name);
}

static void work_precision(sb_rep *R)
{
    const sb_study *st = R->st;
    char stem[1300], name[256], msg[1024];
    fprintf(R->md, "## Work-precision diagrams\n\nError against cost, log-log; one curve per method/solver (the "
                   "unperturbed start, converged runs only), one point per resolution labelled by its dofs; the grey "
                   "staircase and circles mark the Pareto front (no other run is both cheaper and more accurate); "
                   "dashed lines are the error targets.\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        if (!unique_ranked(st, i)) continue;
        fprintf(R->md, "### %s — %s\n\n", st->scenes[i].name, error_words(st->scenes[i].error));
        sb_rep_thumb(R, i);
        if (R->d->has_ref[i] && isfinite(R->d->ref_check[i]) && st->scenes[i].error != SB_ERRKIND_PROBE)
            fprintf(R->md, "Reference: %ld dofs; its own run at half the resolution differs by %.2g (RMS / diameter), so field "
                           "errors below about %.1g are not resolved.\n\n", R->d->ref[i].dofs, R->d->ref_check[i], R->d->ref_check[i] / 3);
        for (int k = 0; k < R->n_costs; k++) {
            int cost = R->costs[k];
            snprintf(name, sizeof name, "wp-%s-%s", st->scenes[i].name, cost == SB_COST_SECONDS ? "seconds" : "work");
            snprintf(stem, sizeof stem, "%s/%s", R->dir, name);
            int rc = sb_fig_work_precision(R->d, i, cost, stem, R->o->gnuplot, msg, sizeof msg);
            if (rc == 0) figure(R, name, name);
            else fig_failed(R, rc, msg), fprintf(R->md, "(%s)\n\n", msg);
        }
    }
}

static void profiles(sb_rep *R)
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
            char name[256], stem[1300], title[256], msg[1024];
            snprintf(name, sizeof name, "profile-%s-%g", cost == SB_COST_SECONDS ? "seconds" : "work", st->targets[tg]);
            snprintf(stem, sizeof stem, "%s/%s", R->dir, name);
            snprintf(title, sizeof title, "performance profile: %s to reach error %g (%d scenes)", sb_cost_name(cost), st->targets[tg], np);
            fprintf(R->md, "### %s to reach error %g\n\n", sb_cost_name(cost), st->targets[tg]);
            int rc = sb_fig_profile(np, ns, ratio, labels, cfg, title, stem, R->o->gnuplot, msg, sizeof msg);
            if (rc == 0) figure(R, name, title);
            else fig_failed(R, rc, msg);
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

static void references(sb_rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    fprintf(R->md, "## References\n\n| scene | solution | ranked by | reference |\n|---|---|---|---|\n");
    for (int i = 0; i < st->n_scenes; i++) {
        const sb_study_scene *sc = &st->scenes[i];
        char ref[1400];
        if (d->has_ref[i]) {
            int u = snprintf(ref, sizeof ref, "`%s`: %s/%s, %ld dofs (res %d, %d level%s)", d->ref[i].path, d->ref[i].method,
                             d->ref[i].solver, d->ref[i].dofs, d->ref[i].res, d->ref[i].levels, d->ref[i].levels > 1 ? "s" : "");
            if (isfinite(d->ref_check[i]) && sc->solution == SB_SOLUTION_UNIQUE && u > 0 && (size_t)u < sizeof ref)
                snprintf(ref + u, sizeof ref - u, "; its run at half the resolution differs by %.2g (RMS / diameter): field "
                         "errors below about a third of that are not resolved", d->ref_check[i]);
        }
        else snprintf(ref, sizeof ref, "%s", d->ref_why[i][0] ? d->ref_why[i] : "none");
        fprintf(R->md, "| %s | %s | %s | %s |\n", sc->name, sc->solution == SB_SOLUTION_UNIQUE ? "unique" : "several (not ranked)",
                sc->solution == SB_SOLUTION_UNIQUE ? error_words(sc->error) : "energy, convergence, cost", ref);
    }
    fprintf(R->md, "\nWhy each bundled scene has the reference it has: docs/study.md \"References\".\n\n");
}

static void convergence(sb_rep *R)
{
    const sb_study *st = R->st;
    char name[256], stem[1300], msg[1024];
    fprintf(R->md, "## Convergence\n\nlog10 ‖g‖ of every outer iteration on the finest level over all steps, one line "
                   "per configuration at the resolution nearest the scene's middle dof count.\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        snprintf(name, sizeof name, "convergence-%s", st->scenes[i].name);
        snprintf(stem, sizeof stem, "%s/%s", R->dir, name);
        int rc = sb_fig_convergence(R->d, i, stem, R->o->gnuplot, msg, sizeof msg);
        if (rc == 0) {
            fprintf(R->md, "### %s%s\n\n", st->scenes[i].name,
                    st->scenes[i].solution == SB_SOLUTION_MULTIPLE ? " (several solutions: runs may end in different minima)" : "");
            figure(R, name, name);
        } else {
            fig_failed(R, rc, msg);
        }
    }
}

static void header(sb_rep *R)
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

/* the other reports of the suite that answer related questions (issue 23:
 * the condition-number and penalty studies and the dt study), linked when
 * they exist */
static void related(sb_rep *R)
{
    static const char *const rep[][2] = {
        { "results/dt_stability/report.md", "dt study: the largest time step at which each solver still converges on "
                                            "the four cloth scenes (RMTR paper Fig. 10)" },
        { "results/rmtr/cond.md", "condition numbers of the Hessian against dofs (RMTR paper Fig. 9, left)" },
        { "results/rmtr/cond_sigma.md", "condition numbers against the penalty parameter (RMTR paper Fig. 9, right)" },
        { "results/accuracy/report.md", "the accuracy study: the analytic and unique-solution scenes at 4-5 "
                                        "resolutions per method" },
        { "results/rmtr_report.md", "the RMTR paper's tables reproduced" },
        { "results/bhem_report.md", "the BHEM paper's validation scenes reproduced" },
        { "results/linear_fem_report.md", "the linear triangle FEM baseline" },
    };
    char self[4096], link[4096], path[1300];
    snprintf(path, sizeof path, "%s/report.md", R->dir);
    int have_self = realpath(path, self) != NULL, n = 0;
    for (size_t k = 0; k < sizeof rep / sizeof rep[0]; k++) {
        char real[4096];
        if (!realpath(rep[k][0], real) || (have_self && strcmp(real, self) == 0)) continue;
        if (sb_path_relative(R->dir, rep[k][0], link, sizeof link)) continue;
        if (!n++) fprintf(R->md, "## Related studies and reports\n\n");
        fprintf(R->md, "* [%s](%s): %s\n", rep[k][0], link, rep[k][1]);
    }
    if (n) fprintf(R->md, "\n");
}

int sb_study_report(const sb_study *st, const sb_study_report_options *o, FILE *err)
{
    sb_study_data d;
    if (st->kind == SB_STUDY_DT_STABILITY) return sb_study_dt_report(st, o, err);
    if (sb_study_data_load(st, &d, err)) return SB_EXIT_INPUT;
    sb_rep R;
    memset(&R, 0, sizeof R);
    R.st = st, R.d = &d, R.o = o, R.err = err;
    snprintf(R.dir, sizeof R.dir, "%s", o->out_dir ? o->out_dir : st->records);
    if (o->deterministic) R.costs[R.n_costs++] = SB_COST_WORK;
    else R.costs[R.n_costs++] = SB_COST_SECONDS, R.costs[R.n_costs++] = SB_COST_WORK;
    char path[1200], tmp[1300];
    snprintf(path, sizeof path, "%s/report.md", R.dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    char why[1400];
    if (sb_study_output_ok(path, "report", why, sizeof why)) {
        sb_escape_print(err, "shellbench report: %s", why);
        sb_study_data_free(&d);
        return SB_EXIT_INPUT;
    }
    if (sb_mkdir_p(R.dir) || !(R.md = sb_study_open_tmp(tmp))) {
        sb_escape_print(err, "shellbench report: cannot write %s: %s", path, strerror(errno));
        sb_study_data_free(&d);
        return SB_EXIT_INPUT;
    }
    header(&R);
    thumbnails(&R);
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
    sb_rep_multiple_scenes(&R);
    references(&R);
    sb_rep_run_tables(&R);
    sb_rep_without_records(&R);
    convergence(&R);
    related(&R);
    fprintf(R.md, "## How to read this report\n\nSee docs/study.md: the study file, the reference policy per scene, how the "
                  "cost to reach a target is interpolated, and how to read the diagrams, profiles and the selection table.\n");
    int code = sb_study_commit_report(R.md, tmp, path, R.refused, err);
    sb_study_data_free(&d);
    return code;
}
