/* sb_memory.h — the memory a run will take, estimated before anything is
 * allocated, and the limit it must fit in.  A run whose estimate exceeds
 * run.max_memory (or, by default, the machine's physical memory) is refused
 * up front with one sentence (exit 2), and a request whose counts exceed
 * what the data structures can index (int dofs, CHOLMOD's int entries) is
 * refused whatever the memory.  docs/cli.md "Sizes and memory". */
#ifndef SB_MEMORY_H
#define SB_MEMORY_H

#include "sb_linsolve.h"   /* SB_SUPERNODES_* */
#include "sb_method.h"

#include <stddef.h>

typedef struct sb_memory_estimate {
    double bytes;                       /* total */
    double method, matrices, factor, vectors, record;   /* its parts */
    double dofs;                        /* finest level */
    double nnz;                         /* upper triangle of the finest Hessian */
    double factor_nnz;                  /* estimated nnz(L) of the finest level */
} sb_memory_estimate;

/* What the run needs besides the method: the scene's time stepping, probes
 * and the sample grid. */
typedef struct sb_memory_run {
    int dynamic;                        /* mass and damping matrices per level */
    int steps, n_probes;
    int sample_n;                       /* sample grid per side */
    int multilevel;                     /* the solver factors only the coarsest level (rmtr) */
    int supernodes;                     /* run.supernodes (0: CHOLMOD's defaults) */
    int lifts;                          /* moving boundaries lifted by a CHOLMOD solve on the finest level
                                           (sb_problem_lift): a multilevel solver holds that factor too;
                                           sb_memory_check_method sets it from the scene */
    int krylov_mg;                      /* solver.linear = pcg-mg (lsnewton, tr, damped, linearized): no
                                           finest factor (the lifting solves by CG too); the coarsest
                                           level's, the lean Galerkin weights and the smoother's blocks */
} sb_memory_run;

/* The estimate of a discretization of size sz run as r.  The Cholesky
 * factor of the level the solver factors is counted (the finest for tr,
 * lsnewton, damped and linearized, an upper bound when tr uses CG; the
 * coarsest for rmtr, whose finer levels have Galerkin matrices of their
 * Hessian's size instead) with nnz(L) = 0.6 nnz(A) log2(nodes), the
 * nested-dissection growth measured on the bundled scenes (bhem and rmtr,
 * 1e3..2e5 dofs: 0.38..0.56).  Measured against the peak resident size of
 * runs of 1e4..2e5 dofs (bhem and rmtr, tr, lsnewton and rmtr): within 10 %
 * (docs/cli.md "Sizes and memory"). */
void   sb_memory_estimate_run(const sb_method_size *sz, const sb_memory_run *r, sb_memory_estimate *est);
/* Physical memory of the machine in bytes (sysconf), 0 when unknown. */
double sb_memory_physical(void);
/* SB_OK when the estimate fits in limit_bytes (0: the machine's physical
 * memory; unknown: only the index limits apply) and every count can be
 * indexed; else SB_ERR_INPUT with one sentence in err naming `what` (e.g.
 * "bhem at --res 4096") and how to proceed. */
int    sb_memory_check(const sb_method_size *sz, const sb_memory_estimate *est, double limit_bytes,
                       const char *what, char *err, size_t errlen);
/* The method's estimate op (when it has one) and sb_memory_check in one:
 * SB_OK (also for a method without the op: nothing to measure before
 * create), or SB_ERR_INPUT with a sentence; *bytes gets the estimate (0
 * when none). */
int    sb_memory_check_method(const sb_method_type *mt, const sb_scene *scene, const sb_method_config *cfg,
                              const sb_memory_run *r, double limit_bytes, const char *what, double *bytes,
                              char *err, size_t errlen);
/* "1.2 GB", "340 MB", "12 kB" (decimal units) */
void   sb_memory_format(double bytes, char *buf, size_t len);

/* 1 when a run of the scene lifts boundary motion (a moving boundary part and
 * run.lifting on, the default): sb_memory_run.lifts */
struct sb_scene;
struct sb_paramset;
int sb_memory_scene_lifts(const struct sb_scene *scene, const struct sb_paramset *ps);

#endif
