/* sb_precond.h — preconditioners of the Krylov linear solvers (solver.linear,
 * docs/solvers.md "Linear solvers"), one constant type table each (GSL
 * multimin style), for the Hessian of one level of an sb_problem:
 *
 *   alloc  once per run: workspaces for the level's size, and every check of
 *          what cannot work (a sentence in the context's error, SB_ERR_INPUT
 *          or SB_ERR_UNSUPPORTED), so that a bad request is refused before
 *          any work;
 *   setup  once per Newton iteration, after the level's Hessian was
 *          assembled (coarse operators, block inverses, factorizations);
 *          allocates nothing;
 *   apply  z = M^{-1} r, M symmetric positive definite whenever the Hessian
 *          is (CG stays valid); allocates nothing.
 *
 * Nothing is counted here except through the sb_problem wrappers
 * (transfers, Galerkin products, factorizations); CG iterations are counted
 * once by the Krylov solver (sb_krylov.c). */
#ifndef SB_PRECOND_H
#define SB_PRECOND_H

#include "sb_problem.h"

typedef struct sb_precond_opts {
    int mg_sweeps;          /* pcg-mg: smoothing sweeps before and after the coarse correction */
    int mg_lag;             /* pcg-mg: coarse levels rebuilt every mg_lag-th setup and at each step's first (0, 1: every setup) */
    int mg_cycle;           /* pcg-mg: SB_MG_CYCLE_V (0) or SB_MG_CYCLE_W (each coarse level but the coarsest
                               visited twice) */
    double amg_strength;    /* pcg-amg: BoomerAMG strength threshold */
} sb_precond_opts;

enum { SB_MG_CYCLE_V = 0, SB_MG_CYCLE_W = 1 };
extern const char *const sb_mg_cycle_names[];      /* v, w (the order of the enum) */
int sb_mg_cycle_kind(const char *name);            /* SB_MG_CYCLE_*; V for NULL or an unknown name */
#define SB_MG_CYCLE_HELP "pcg-mg: v (V-cycle) or w (W-cycle: each coarse level but the coarsest visited " \
    "twice, about one more finest-level cycle of work; keeps linear_fem's CG counts from growing with the " \
    "levels, docs/krylov.md)"

typedef struct sb_precond_type {
    const char *name;
    size_t state_size;
    int  (*alloc)(void *state, sb_problem *p, int level, const sb_precond_opts *o);
    /* SB_OK, SB_NOT_POSDEF (the preconditioner could not be made positive
     * definite: the caller treats it as an indefinite Hessian), or an error */
    int  (*setup)(void *state, sb_problem *p);
    int  (*apply)(void *state, sb_problem *p, const double *r, double *z);
    void (*free)(void *state);
    /* optional: one line on the configuration (levels, options) */
    void (*describe)(const void *state, char *buf, size_t len);
} sb_precond_type;

extern const sb_precond_type sb_precond_jacobi;  /* node-block Jacobi (sb_precond_jacobi.c) */
extern const sb_precond_type sb_precond_mg;      /* one symmetric V-cycle of the method's hierarchy */
extern const sb_precond_type sb_precond_amg;     /* hypre BoomerAMG, one V-cycle (when built with hypre) */

/* 1 when this build has hypre (pcg-amg usable). */
int sb_precond_have_amg(void);

/* The inverse of the symmetric bs x bs node block A (row-major) in place,
 * through Cholesky; when the block is not positive definite it is replaced
 * by the diagonal matrix of 1/|a_ii| (1 where a_ii = 0), which keeps the
 * preconditioner positive definite.  Returns 1 when the block was positive
 * definite, else 0.  bs <= 12. */
int sb_block_inverse_spd(int bs, double *A);
/* the same without the fallback: 0, A unchanged, when A is not SPD */
int sb_spd_block_inverse(int bs, double *A);

#endif
