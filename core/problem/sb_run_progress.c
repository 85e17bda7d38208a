/* sb_run_progress.c — the run's monitor (sb_context.monitor, called by the
 * shared outer loop after every iteration): checkpoints and the live
 * progress line, chained.
 *
 * Progress: on a terminal one line, rewritten in place at most four times a
 * second ("\r" and erase-to-end-of-line), cleared before any other message
 * and at the end; with --progress off a terminal a plain line at most once a
 * second.  It shows the step, the iteration (and level of a coarse record),
 * f, ||g||, the trust-region radius or the line-search step, the run's
 * iterations so far and the elapsed time.  docs/cli.md "Progress". */
#include "sb_run_state.h"

#include <math.h>
#include <string.h>
#include <unistd.h>

void sb_run_progress_init(run_state *R, const sb_run_request *req)
{
    sb_run_progress *P = &R->progress;
    memset(P, 0, sizeof *P);
    P->tty = isatty(fileno(R->err));
    P->on = req->progress > 0 || (req->progress == 0 && P->tty && !req->quiet);
    P->interval = P->tty ? 0.25 : 1.0;
    P->prefix = req->progress_prefix;
}

void sb_run_progress_clear(run_state *R)
{
    sb_run_progress *P = &R->progress;
    if (!P->shown) return;
    if (P->tty) fputs("\r\033[K", R->err);
    fflush(R->err);
    P->shown = 0;
}

/* "12.3 s", "4 min 05 s", "2 h 03 min" */
static void format_elapsed(double s, char *buf, size_t len)
{
    if (s < 60) snprintf(buf, len, "%.1f s", s);
    else if (s < 3600) snprintf(buf, len, "%d min %02d s", (int)(s / 60), (int)fmod(s, 60));
    else snprintf(buf, len, "%d h %02d min", (int)(s / 3600), (int)fmod(s / 60, 60));
}

static void progress_update(run_state *R, const sb_iter_record *r)
{
    sb_run_progress *P = &R->progress;
    const int F = sb_problem_finest(R->prob);
    double now = sb_now();
    P->iterations += r->level == F && r->iter > 0;   /* outer iterations, as report counts them */
    if (now - P->last < P->interval) return;
    P->last = now;
    char el[32], tr[48] = "", lev[24] = "";
    format_elapsed(now - R->t_start, el, sizeof el);
    if (isfinite(r->delta) && r->delta > 0) snprintf(tr, sizeof tr, ", radius %.2e", r->delta);
    else if (r->rho > 0) snprintf(tr, sizeof tr, ", step %.3g", r->rho);
    if (r->level != F) snprintf(lev, sizeof lev, " (level %d)", r->level);
    fprintf(R->err, "%s%s%s/%s/%s step %d/%d, iteration %d%s: f = %.6g, |g| = %.2e%s; %ld iterations, %s%s",
            P->tty ? "\r" : "", P->prefix ? P->prefix : "", R->scene.name, R->mt->name, R->stype->name, r->step,
            R->scene.time.steps, r->iter, lev, r->f, r->gnorm, tr, P->iterations, el, P->tty ? "\033[K" : "\n");
    fflush(R->err);
    P->shown = P->tty;
}

void sb_run_monitor(void *data, const sb_iter_record *r)
{
    run_state *R = data;
    if (R->checkpoints_on && !R->checkpoint_failed && sb_now() - R->checkpoint_last >= R->checkpoint_every) {
        sb_run_progress_clear(R);   /* a failed checkpoint prints a warning */
        sb_run_write_checkpoint(R);
    }
    if (R->progress.on) {
        double t0 = sb_stats_begin(&R->ctx.stats);
        progress_update(R, r);
        sb_stats_event(&R->ctx.stats, sb_problem_finest(R->prob), SB_EV_PROGRESS, t0);
    }
}
