/* sb_precond_amg.c — hypre's BoomerAMG (one V-cycle) on the assembled
 * Hessian as the preconditioner of CG (solver.linear = pcg-amg).
 *
 * Build: compiled with hypre when the Makefile finds Debian's libhypre-dev
 * and OpenMPI (SB_HAVE_HYPRE; `make HYPRE=0` leaves it out, and pcg-amg is
 * then refused with a sentence).  Debian's hypre is built against OpenMPI,
 * with no sequential variant, so the library links libmpi; MPI itself is
 * initialized only here, at the set-up of the first pcg-amg solve of the
 * process (MPI_Init_thread as a singleton when no launcher did it, and
 * MPI_Finalize at exit), so runs that do not ask for pcg-amg never start
 * MPI.  Every hypre object lives on MPI_COMM_SELF: one process owns the
 * whole matrix (sequential use, also inside an MPI sweep's ranks).
 *
 * Options (docs/solvers.md "pcg-amg"): systems AMG, the unknown approach
 * with the method's dofs per node as functions (HYPRE_BoomerAMGSetNumFunctions:
 * 3 for positions, 12 for a Hermite node; dof = bs * node + c is hypre's
 * interleaved ordering), so strength is measured only between like
 * components; strength threshold solver.amg_strength (0.5: hypre's advice
 * for 3-D problems, where the default 0.25 makes operator complexities
 * grow); HMIS coarsening with extended+i interpolation truncated to 4
 * entries per row (hypre's defaults, named so a record reads the same with
 * another hypre); symmetric hybrid Gauss–Seidel (relax type 6) down and up,
 * Gaussian elimination on the coarsest level, so the V-cycle is symmetric and
 * CG stays valid.  The rigid-body near-null space (HYPRE_BoomerAMGSetInterpVectors)
 * is not given: it works only with nodal coarsening, and for the Hermite
 * and subdivision dofs the rigid motions are not the positions' six vectors. */
#include "sb_precond.h"
#include "sb_context.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SB_HAVE_HYPRE
#include <mpi.h>
#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>

int sb_precond_have_amg(void) { return 1; }

static int mpi_started_here;

static void amg_finalize(void)
{
    HYPRE_Finalize();
    int fin = 0;
    MPI_Finalized(&fin);
    if (mpi_started_here && !fin) MPI_Finalize();
}

/* MPI and hypre, once per process */
static int amg_init(void)
{
    static int done;
    if (done) return 0;
    int inited = 0;
    MPI_Initialized(&inited);
    if (!inited) {
        int provided;
        if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) return -1;
        mpi_started_here = 1;
    }
    HYPRE_Init();
    atexit(amg_finalize);
    done = 1;
    return 0;
}

typedef struct amg_state {
    int level, n, bs;
    double strength;
    int *ncols, *rows, *cols, *idx;   /* full symmetric CSR of the upper CSC pattern */
    long *vmap;                       /* position in H->val of every full entry */
    double *vals, *xz;
    long nnz_full;
    const sb_pattern *pat;            /* the pattern the structure was built from, */
    long pat_nnz;                     /* and its entries (a new pattern may reuse the address) */
    HYPRE_IJMatrix A;
    HYPRE_IJVector b, x;
    HYPRE_ParCSRMatrix pA;
    HYPRE_ParVector pb, px;
    HYPRE_Solver solver;
    int have_A, have_solver;
} amg_state;

static void amg_release(amg_state *s)
{
    if (s->have_solver) HYPRE_BoomerAMGDestroy(s->solver);
    if (s->have_A) HYPRE_IJMatrixDestroy(s->A);
    s->have_solver = s->have_A = 0;
}

static void amg_free(void *st)
{
    amg_state *s = st;
    amg_release(s);
    if (s->b) HYPRE_IJVectorDestroy(s->b);
    if (s->x) HYPRE_IJVectorDestroy(s->x);
    s->b = s->x = NULL;
    free(s->ncols); free(s->rows); free(s->cols); free(s->idx); free(s->vmap); free(s->vals); free(s->xz);
    s->ncols = s->rows = s->cols = s->idx = NULL;
    s->vmap = NULL;
    s->vals = s->xz = NULL;
}

/* the full symmetric CSR structure of the upper CSC pattern (hypre wants
 * whole rows), built at alloc and again when self-contact replaced the
 * level's pattern */
static int amg_structure(amg_state *s, const sb_pattern *pat)
{
    const int n = s->n;
    free(s->ncols); free(s->cols); free(s->vmap); free(s->vals);
    s->cols = NULL; s->vmap = NULL; s->vals = NULL;
    s->pat = pat;
    s->pat_nnz = pat->nnz;
    s->ncols = calloc((size_t)n, sizeof *s->ncols);
    if (!s->ncols) return SB_ERR_NOMEM;
    for (int j = 0; j < n; j++)
        for (long k = pat->colptr[j]; k < pat->colptr[j + 1]; k++) {
            const int i = pat->rowind[k];
            s->ncols[i]++;
            if (i != j) s->ncols[j]++;
        }
    long *start = malloc((size_t)(n + 1) * sizeof *start);
    if (!start) return SB_ERR_NOMEM;
    start[0] = 0;
    for (int i = 0; i < n; i++) start[i + 1] = start[i] + s->ncols[i];
    s->nnz_full = start[n];
    s->cols = malloc((size_t)s->nnz_full * sizeof *s->cols);
    s->vmap = malloc((size_t)s->nnz_full * sizeof *s->vmap);
    s->vals = malloc((size_t)s->nnz_full * sizeof *s->vals);
    if (!s->cols || !s->vmap || !s->vals) { free(start); return SB_ERR_NOMEM; }
    /* column j's upper entries (i, j) go to row i as column j, and to row j
     * as column i; row i's columns come out in increasing order */
    long *next = start;
    for (int j = 0; j < n; j++)
        for (long k = pat->colptr[j]; k < pat->colptr[j + 1]; k++) {
            const int i = pat->rowind[k];
            s->cols[next[i]] = j; s->vmap[next[i]++] = k;
            if (i != j) { s->cols[next[j]] = i; s->vmap[next[j]++] = k; }
        }
    free(start);
    return SB_OK;
}

static int amg_alloc(void *st, sb_problem *p, int level, const sb_precond_opts *o)
{
    amg_state *s = st;
    sb_context *ctx = sb_problem_context(p);
    s->level = level;
    s->n = sb_problem_n(p, level);
    s->bs = sb_problem_block_size(p, level);
    if (s->bs < 1 || s->n % s->bs) s->bs = 1;
    s->strength = o ? o->amg_strength : 0.5;
    if (!(s->strength >= 0.0 && s->strength < 1.0))
        return sb_error(ctx, SB_ERR_INPUT, "solver.amg_strength must be in [0, 1) (BoomerAMG's strength threshold), "
                        "got %g", s->strength);
    if (amg_init())
        return sb_error(ctx, SB_ERR_UNSUPPORTED, "solver.linear=pcg-amg: MPI could not be initialized for hypre");
    s->rows = malloc((size_t)s->n * sizeof *s->rows);
    s->idx = malloc((size_t)s->n * sizeof *s->idx);
    s->xz = malloc((size_t)s->n * sizeof *s->xz);
    if (!s->rows || !s->idx || !s->xz) return SB_ERR_NOMEM;
    int rc = amg_structure(s, sb_problem_hessian(p, level)->pat);
    if (rc) return rc;
    const int n = s->n;
    for (int i = 0; i < n; i++) s->rows[i] = s->idx[i] = i;
    memset(s->xz, 0, (size_t)n * sizeof *s->xz);
    if (HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, &s->b) || HYPRE_IJVectorSetObjectType(s->b, HYPRE_PARCSR) ||
        HYPRE_IJVectorInitialize(s->b) || HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, &s->x) ||
        HYPRE_IJVectorSetObjectType(s->x, HYPRE_PARCSR) || HYPRE_IJVectorInitialize(s->x) ||
        HYPRE_IJVectorAssemble(s->b) || HYPRE_IJVectorAssemble(s->x) ||
        HYPRE_IJVectorGetObject(s->b, (void **)&s->pb) || HYPRE_IJVectorGetObject(s->x, (void **)&s->px))
        return sb_error(ctx, SB_ERR_INTERNAL, "hypre: creating vectors of %d rows failed", n);
    return SB_OK;
}

static int amg_setup(void *st, sb_problem *p)
{
    amg_state *s = st;
    sb_context *ctx = sb_problem_context(p);
    const sb_matrix *H = sb_problem_hessian(p, s->level);
    const int n = s->n;
    if (H->pat != s->pat || H->pat->nnz != s->pat_nnz) {
        int rc = amg_structure(s, H->pat);
        if (rc) return rc;
    }
    for (long k = 0; k < s->nnz_full; k++) s->vals[k] = H->val[s->vmap[k]];
    amg_release(s);
    if (HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &s->A))
        return sb_error(ctx, SB_ERR_INTERNAL, "hypre: creating a %d x %d matrix failed", n, n);
    s->have_A = 1;
    HYPRE_IJMatrixSetObjectType(s->A, HYPRE_PARCSR);
    HYPRE_IJMatrixSetRowSizes(s->A, s->ncols);
    if (HYPRE_IJMatrixInitialize(s->A) || HYPRE_IJMatrixSetValues(s->A, n, s->ncols, s->rows, s->cols, s->vals) ||
        HYPRE_IJMatrixAssemble(s->A) || HYPRE_IJMatrixGetObject(s->A, (void **)&s->pA))
        return sb_error(ctx, SB_ERR_INTERNAL, "hypre: assembling the %d x %d Hessian failed", n, n);
    HYPRE_BoomerAMGCreate(&s->solver);
    s->have_solver = 1;
    int bad = 0;
    bad |= HYPRE_BoomerAMGSetPrintLevel(s->solver, 0);
    bad |= HYPRE_BoomerAMGSetMaxIter(s->solver, 1);           /* one V-cycle per application */
    bad |= HYPRE_BoomerAMGSetTol(s->solver, 0.0);
    bad |= HYPRE_BoomerAMGSetNumFunctions(s->solver, s->bs);  /* systems AMG, unknown approach */
    bad |= HYPRE_BoomerAMGSetStrongThreshold(s->solver, s->strength);
    bad |= HYPRE_BoomerAMGSetCoarsenType(s->solver, 10);      /* HMIS */
    bad |= HYPRE_BoomerAMGSetInterpType(s->solver, 6);        /* extended+i */
    bad |= HYPRE_BoomerAMGSetPMaxElmts(s->solver, 4);
    bad |= HYPRE_BoomerAMGSetCycleRelaxType(s->solver, 6, 1); /* symmetric hybrid Gauss-Seidel down */
    bad |= HYPRE_BoomerAMGSetCycleRelaxType(s->solver, 6, 2); /* ... and up */
    bad |= HYPRE_BoomerAMGSetCycleRelaxType(s->solver, 9, 3); /* Gaussian elimination, coarsest */
    bad |= HYPRE_BoomerAMGSetNumSweeps(s->solver, 1);
    if (bad) {
        HYPRE_ClearAllErrors();
        return sb_error(ctx, SB_ERR_INPUT, "hypre rejected the BoomerAMG options (solver.amg_strength=%g, %d functions)",
                        s->strength, s->bs);
    }
    if (HYPRE_BoomerAMGSetup(s->solver, s->pA, s->pb, s->px)) {
        HYPRE_ClearAllErrors();
        return SB_NOT_POSDEF;   /* a zero pivot or worse: treated as an indefinite Hessian */
    }
    return SB_OK;
}

static int amg_apply(void *st, sb_problem *p, const double *r, double *z)
{
    (void)p;
    amg_state *s = st;
    HYPRE_IJVectorSetValues(s->b, s->n, s->idx, r);
    HYPRE_IJVectorSetValues(s->x, s->n, s->idx, s->xz);
    if (HYPRE_BoomerAMGSolve(s->solver, s->pA, s->pb, s->px)) HYPRE_ClearAllErrors();  /* max_iter 1 "not converged" */
    HYPRE_IJVectorGetValues(s->x, s->n, s->idx, z);
    return SB_OK;
}

static void amg_describe(const void *st, char *buf, size_t len)
{
    const amg_state *s = st;
    snprintf(buf, len, "hypre %s BoomerAMG V-cycle: %d functions (systems, unknown approach), strength %g, HMIS, "
             "ext+i interpolation (Pmax 4), symmetric hybrid Gauss-Seidel", HYPRE_RELEASE_VERSION, s->bs, s->strength);
}

#else

int sb_precond_have_amg(void) { return 0; }

typedef struct amg_state { int unused; } amg_state;

static int amg_alloc(void *st, sb_problem *p, int level, const sb_precond_opts *o)
{
    (void)st; (void)level; (void)o;
    return sb_error(sb_problem_context(p), SB_ERR_UNSUPPORTED, "solver.linear=pcg-amg needs hypre, and this build "
                    "has none (install libhypre-dev and OpenMPI, then rebuild without HYPRE=0)");
}
static int amg_setup(void *st, sb_problem *p) { (void)st; (void)p; return SB_ERR_UNSUPPORTED; }
static int amg_apply(void *st, sb_problem *p, const double *r, double *z)
{
    (void)st; (void)p; (void)r; (void)z;
    return SB_ERR_UNSUPPORTED;
}
static void amg_free(void *st) { (void)st; }
static void amg_describe(const void *st, char *buf, size_t len) { (void)st; snprintf(buf, len, "no hypre"); }

#endif

const sb_precond_type sb_precond_amg = {
    "pcg-amg", sizeof(amg_state), amg_alloc, amg_setup, amg_apply, amg_free, amg_describe,
};
