/* sb_study_report_runs.c — the study report's sections on runs rather than
 * rankings: the scenes with several solutions (energy of the minimum found,
 * spread over perturbed starts, convergence and cost; never ranked by
 * distance to one minimum), every record per scene, and the runs without a
 * record (refused, missing, skipped, not applicable). */
#include "sb_study_rep.h"

#include <math.h>
#include <string.h>

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

void sb_rep_multiple_scenes(sb_rep *R)
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
                   "agree to the solver tolerance.  *Below rest*: the share of the cloth's area whose energy is below "
                   "the flat, unstrained sheet's (the denim law's wells beyond about 2.5 %% strain, docs/denim.md): "
                   "a minimum there is set by the material law's fit rather than by the loads.\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        const sb_study_scene *sc = &st->scenes[i];
        if (!(sc->n_seeds > 0 || sc->solution == SB_SOLUTION_MULTIPLE)) continue;
        double eref = d->has_ref[i] ? d->ref[i].energy : NAN;
        char v[32];
        sb_rep_g3(v, sizeof v, eref);
        fprintf(R->md, "### %s (%s solution%s)\n\nE_ref = %s J%s.  Starts: the unperturbed one", sc->name,
                sc->solution == SB_SOLUTION_UNIQUE ? "unique" : "several", sc->solution == SB_SOLUTION_UNIQUE ? "" : "s", v,
                d->has_ref[i] ? "" : " (no reference record: ΔE is left out)");
        if (sc->n_seeds) fprintf(R->md, " and %d perturbed by ±%g per dof (seeds", sc->n_seeds, sc->perturb);
        for (int k = 0; k < sc->n_seeds; k++) fprintf(R->md, "%s%ld", k ? ", " : " ", sc->seeds[k]);
        fprintf(R->md, "%s.\n\n", sc->n_seeds ? ")" : "");
        fprintf(R->md, "| configuration | dofs | unperturbed start | iterations | %s WU | E (J) | ΔE | below rest | starts converged | ΔE spread | max shape distance between starts |\n",
                R->o->deterministic ? "" : "seconds |");
        fprintf(R->md, "|---|--:|---|--:|%s--:|--:|--:|--:|--:|--:|--:|\n", R->o->deterministic ? "" : "--:|");
        for (int k = 0; k < d->plan.n; k++) {
            const sb_plan_run *r = &d->plan.runs[k];
            const sb_study_point *q = &d->pt[k];
            if (r->scene != i || r->start != 0 || q->state != SB_POINT_RECORDED) continue;
            char label[128], stw[128], sec[32], wu[32], e[32], de[32], spread[32], dist[32], below[32];
            sb_study_config_label(d, q->config, label, sizeof label);
            status_words(q, stw, sizeof stw);
            sb_rep_g3(sec, sizeof sec, q->seconds);
            sb_rep_g3(wu, sizeof wu, q->work);
            snprintf(e, sizeof e, isfinite(q->energy) ? "%.6g" : "—", q->energy);
            sb_rep_g3(de, sizeof de, isfinite(eref) && q->status == 0 ? (q->energy - eref) / fabs(eref) : NAN);
            sb_rep_g3(below, sizeof below, q->below_reference);
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
            sb_rep_g3(spread, sizeof spread, total > 1 && conv > 1 ? (emax - emin) / scale : NAN);
            sb_rep_g3(dist, sizeof dist, have_d ? dmax : NAN);
            fprintf(R->md, "| %s | %ld | %s | %d | %s%s%s | %s | %s | %s | %d of %d | %s | %s |\n", label, q->dofs, stw,
                    q->iterations, R->o->deterministic ? "" : sec, R->o->deterministic ? "" : " | ", wu, e, de, below, conv,
                    total, spread, dist);
        }
        fprintf(R->md, "\n");
    }
}

void sb_rep_run_tables(sb_rep *R)
{
    const sb_study *st = R->st;
    const sb_study_data *d = R->d;
    fprintf(R->md, "## Runs\n\nEvery record of the study (the unperturbed start); errors as defined per scene above "
                   "(probe: relative to the analytic value or, with a reference record, distance / diameter).\n\n");
    for (int i = 0; i < st->n_scenes; i++) {
        /* several solutions: a run ending in another minimum than the
         * reference's has made no error, so the columns say "distance" */
        const int several = st->scenes[i].solution == SB_SOLUTION_MULTIPLE;
        fprintf(R->md, "### %s\n\n", st->scenes[i].name);
        /* the picture: here for the scenes without a work-precision diagram (which shows it for the others) */
        if (st->scenes[i].solution == SB_SOLUTION_MULTIPLE || st->scenes[i].error == SB_ERRKIND_NONE) sb_rep_thumb(R, i);
        if (several)
            fprintf(R->md, "Several solutions: the last three columns are distances (/ diameter) to the minimum the "
                           "reference found, not errors; a run in another minimum can be as good (compare energies "
                           "under *Scenes with several solutions*).\n\n");
        fprintf(R->md, "| configuration | res | dofs | status | steps | iterations | %sassembly WU | %s |\n"
                       "|---|--:|--:|---|--:|--:|%s--:|--:|--:|--:|\n", R->o->deterministic ? "" : "seconds | ",
                several ? "probe distance to the reference's minimum | RMS distance to it | max distance to it"
                        : "probe error | RMS field error | max field error",
                R->o->deterministic ? "" : "--:|");
        for (int k = 0; k < d->plan.n; k++) {
            const sb_plan_run *r = &d->plan.runs[k];
            const sb_study_point *q = &d->pt[k];
            if (r->scene != i || r->start != 0 || q->state != SB_POINT_RECORDED) continue;
            char label[128], stw[160], sec[32], wu[32], ep[32], er[32], em[32];
            sb_study_config_label(d, q->config, label, sizeof label);
            status_words(q, stw, sizeof stw);
            sb_rep_g3(sec, sizeof sec, q->seconds);
            sb_rep_g3(wu, sizeof wu, q->work);
            sb_rep_g3(ep, sizeof ep, q->err_probe);
            sb_rep_g3(er, sizeof er, q->err_rms);
            sb_rep_g3(em, sizeof em, q->err_max);
            fprintf(R->md, "| %s | %d | %ld | %s | %d | %d | %s%s%s | %s | %s | %s |\n", label, r->res, q->dofs, stw, q->steps,
                    q->iterations, R->o->deterministic ? "" : sec, R->o->deterministic ? "" : " | ", wu, ep, er, em);
        }
        fprintf(R->md, "\n");
    }
}

void sb_rep_without_records(sb_rep *R)
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

