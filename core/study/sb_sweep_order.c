/* sb_sweep_order.c — the order a distributed sweep hands runs out in:
 * longest expected first (the classic LPT rule, Graham 1969: with runs
 * sorted by decreasing length, greedy scheduling on N workers ends within
 * 4/3 - 1/(3N) of the optimum), so that no rank starts a long run when
 * the others are about to finish.
 *
 * Expected seconds come from the study's own records where there are some:
 * a run of the same scene, method, solver, levels and variant recorded at
 * another resolution or start, scaled by (dofs / recorded dofs)^1.5 (the
 * growth of a sparse direct solve on a 2-D mesh, nested dissection: flops
 * ~ n^1.5, George 1973).  Runs without such a neighbour get c dofs^1.5, c
 * the median of seconds / dofs^1.5 over every record of the study, or
 * 1e-5 s without any (then the order is by dofs alone). */
#include "sb_study_int.h"
#include "sb_gsl.h"
#include "sb_record.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct known {
    double seconds;
    long dofs;
} known;

typedef struct keyed {
    int idx;        /* queue position (stable ties) */
    int run;
    double t;
} keyed;

static int by_time_desc(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    if (x->t != y->t) return x->t < y->t ? 1 : -1;
    return x->idx - y->idx;
}

static int same_config(const sb_plan_run *a, const sb_plan_run *b)
{
    return a->scene == b->scene && a->method == b->method && a->solver == b->solver && a->levels == b->levels &&
           a->variant == b->variant && a->dt == b->dt;
}

void sb_study_order_longest_first(const sb_study *st, const sb_plan *plan, int *queue, int nq, double *expected)
{
    (void)st;
    if (nq <= 0) return;
    known *k = calloc((size_t)plan->n, sizeof *k);
    keyed *q = malloc((size_t)nq * sizeof *q);
    double *c = malloc((size_t)plan->n * sizeof *c);
    if (!k || !q || !c) {
        free(k), free(q), free(c);
        return;   /* plan order: still correct, only less balanced */
    }
    int nc = 0;
    for (int i = 0; i < plan->n; i++) {
        const sb_plan_run *r = &plan->runs[i];
        if (r->state != SB_PLAN_RUN || access(r->out, F_OK) != 0) continue;
        sb_record_summary s;
        char err[512];
        if (sb_record_read_summary(r->out, &s, err, sizeof err) != SB_OK) continue;
        if (s.seconds > 0 && s.dofs > 0) {
            k[i].seconds = s.seconds, k[i].dofs = s.dofs;
            c[nc++] = s.seconds / pow((double)s.dofs, 1.5);
        }
        sb_record_summary_free(&s);
    }
    double cmed = 1e-5;
    if (nc > 0 && sb_median(c, (size_t)nc, &cmed)) cmed = 1e-5;
    for (int j = 0; j < nq; j++) {
        const sb_plan_run *r = &plan->runs[queue[j]];
        double dofs = r->dofs > 0 ? (double)r->dofs : 1.0, t = -1;
        long best = -1;
        /* the recorded neighbour nearest in dofs */
        for (int i = 0; i < plan->n; i++)
            if (k[i].dofs > 0 && same_config(&plan->runs[i], r) &&
                (best < 0 || fabs(log((double)k[i].dofs / dofs)) < fabs(log((double)k[best].dofs / dofs))))
                best = i;
        if (best >= 0) t = k[best].seconds * pow(dofs / (double)k[best].dofs, 1.5);
        else t = cmed * pow(dofs, 1.5);
        q[j].idx = j, q[j].run = queue[j], q[j].t = t;
    }
    qsort(q, (size_t)nq, sizeof *q, by_time_desc);
    for (int j = 0; j < nq; j++) {
        queue[j] = q[j].run;
        if (expected) expected[j] = q[j].t;
    }
    free(k), free(q), free(c);
}

int sb_study_tasks(const sb_plan *plan, int *task)
{
    int n = 0;
    for (int i = 0; i < plan->n; i++)
        if (plan->runs[i].state == SB_PLAN_RUN) task[n++] = i;
    return n;
}

int sb_mpi_launched(void)
{
    /* OpenMPI's mpirun, PMIx launchers (OpenMPI 4/5, Slurm's srun --mpi=pmix), MPICH/Hydra (PMI) */
    static const char *const vars[] = { "OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK" };
    for (size_t k = 0; k < sizeof vars / sizeof *vars; k++)
        if (getenv(vars[k])) return 1;
    return 0;
}
