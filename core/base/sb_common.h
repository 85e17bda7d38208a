/* sb_common.h — status codes, outcome reasons and small shared helpers.
 *
 * Status convention (CHOLMOD style): 0 = ok, negative = error (the run could
 * not be carried out), positive = an outcome or warning of an algorithm that
 * is recorded as a result of the run, never a crash. */
#ifndef SB_COMMON_H
#define SB_COMMON_H

#include <stddef.h>
#include <stdio.h>

enum {
    SB_OK = 0,
    /* errors (< 0) */
    SB_ERR_INPUT = -1,       /* malformed or out-of-range input (scene, option) */
    SB_ERR_NOMEM = -2,
    SB_ERR_INTERNAL = -3,
    SB_ERR_UNSUPPORTED = -4, /* impossible combination (solver needs an op the method lacks) */
    SB_ERR_IO = -5,
    /* outcomes / warnings (> 0) */
    SB_NOT_POSDEF = 1,       /* factorization found a non-positive-definite matrix */
    SB_NONFINITE = 2,        /* NaN or Inf met in an energy, gradient or Hessian */
    SB_DIVERGED = 3,
    SB_NOT_CONVERGED = 4     /* an iterative library routine (GSL) stopped short of its tolerance */
};

/* Why an outer solve stopped.  Recorded per step; names in sb_reason_name(). */
typedef enum {
    SB_REASON_NONE = 0,
    SB_REASON_GRAD_TOL,      /* ||g|| < gtol                                   (RMTR paper Eq. 7.1) */
    SB_REASON_F_TOL,         /* |f_{i-1}-f_i| < ftol while Delta > delta_big   (Eq. 7.1) */
    SB_REASON_X_TOL,         /* ||x_{i-1}-x_i|| < xtol while Delta > delta_big (Eq. 7.1) */
    SB_REASON_SINGLE_STEP,   /* linearized solver: one Newton step by design */
    SB_REASON_MAX_ITER,      /* iteration cap reached */
    SB_REASON_NONFINITE,     /* NaN/Inf in f, g or H */
    SB_REASON_DIVERGED,      /* f or ||x|| blew past the divergence limit */
    SB_REASON_NOT_POSDEF,    /* a solver that needs a PD Hessian met an indefinite one */
    SB_REASON_LINESEARCH,    /* line search could not find sufficient decrease */
    SB_REASON_RADIUS,        /* trust-region radius collapsed below delta_min */
    SB_REASON_LINEAR_SOLVER, /* linear solver failed beyond recovery */
    SB_REASON_STALLED,       /* run.stall_iter iterations in a row with accepted steps below
                                xtol changing f by less than ftol (or rejections with a radius
                                below xtol): the limiting accuracy; NOT counted as converged */
    SB_REASON_CHECKPOINT,    /* not an outcome: the run was still going when this checkpoint record
                                was written (record status SB_STATUS_UNFINISHED) */
    /* added by issue 27 (appended: the codes above are in committed records) */
    SB_REASON_ROUNDOFF,      /* run.stop=scaled: a correction not limited by a radius or a line search
                                was below run.xtol_rel ||x||, the round-off of the state: the limiting
                                accuracy reached (counted as converged; docs/trust.md) */
    SB_REASON_PENALTY,       /* constraints imposed by penalty are violated beyond run.penalty_tol
                                relative to the displacement scale (NOT converged) */
    SB_REASON_STRAIN,        /* the state strains the material beyond run.strain_max: not a
                                physical solution (NOT converged) */
    SB_REASON_SINGLE_STEP_RESIDUAL, /* linearized: the single step left ||g|| above
                                run.single_step_rtol times the step's force scale (NOT converged) */
    /* added by issue 37 */
    SB_REASON_OBSTACLE_SWEPT, /* a moving obstacle's motion over the step sweeps through a contact
                                sample point (or overruns it): the barrier, which sees the obstacle at
                                the step's end only, cannot keep the cloth on its side; the step is
                                not solved (NOT converged; docs/contact.md) */
    SB_REASON_CONTACT_UNRESOLVED, /* contact.model = impulse: more than run.contact_unresolved_max steps
                                ended with a collision the response could not resolve (the cloth
                                crosses itself or an obstacle in the state recorded; NOT converged) */
    SB_REASON_COUNT
} sb_reason;

const char *sb_reason_name(sb_reason r);
/* 1 when the reason counts as convergence (grad/f/x tolerances, round-off
 * limit, a judged single step). */
int sb_reason_converged(sb_reason r);

/* Rewrite the NUL-terminated message s (buffer of cap bytes) so that it is
 * safe to print on a terminal and stays one line: control characters
 * become \n, \r, \t or \xNN, C1 controls (U+0080..U+009F) and the
 * invisible byte-order mark \uNNNN, the bidirectional embeddings, overrides
 * and isolates (U+202A..U+202E, U+2066..U+2069, which reorder what follows
 * them on the line) \uNNNN, invalid UTF-8 bytes \xNN; truncated to
 * cap.  Returns the number of characters escaped.  Every message that can
 * carry text from a scene file or a command line passes through it. */
size_t sb_escape_controls(char *s, size_t cap);
/* s copied into buf (len bytes) and escaped likewise; returns buf. */
const char *sb_escape_copy(const char *s, char *buf, size_t len);
/* One message line: the printf-formatted text escaped as a whole (so every
 * piece of input it echoes is), then a newline, on f.  For messages that
 * are meant to be one line (not usage texts); at most 4095 bytes. */
void sb_escape_print(FILE *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#define SB_MAX_LEVELS 8
#define SB_NAME_LEN 64

/* The path of `target` (relative to the current directory) as seen from the
 * directory `dir`, into buf: a relative link.  0, or -1 when either path
 * does not exist. */
int sb_path_relative(const char *dir, const char *target, char *buf, size_t len);
/* mkdir -p DIR: 0, or -1 with errno (core/base/sb_path.c) */
int sb_mkdir_p(const char *dir);

#endif
