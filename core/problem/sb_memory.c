/* sb_memory.c — the memory estimate of a run before any allocation, and the
 * refusal of runs that cannot fit or cannot be indexed (sb_memory.h). */
#include "sb_memory.h"
#include "sb_context.h"
#include "sb_linsolve.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* Bytes of the structures of one level of the problem (sb_problem.c,
 * sb_sparse.c): the pattern (row indices, column pointers, diagonal
 * positions), the element node lists and scatter maps (one 1-, 2- or 4-byte
 * offset per ordered node pair a <= b of an element), the value arrays of H (and M and
 * the damping matrix D of dynamic scenes; M by its nonzeros where the method
 * says how many), and the per-dof work vectors. */
static double level_bytes(const sb_method_size *sz, int l, int dynamic, int maps, double *nnz_out)
{
    const double bs = sz->bs, n = sz->nodes[l] * bs, ne = sz->elements[l], k = sz->nodes_per_element;
    const double offdiag = 0.5 * (sz->stencil > 1 ? sz->stencil - 1 : 0);
    /* upper triangle: half the off-diagonal node blocks, the diagonal blocks' upper halves */
    const double nnz = sz->nodes[l] * (offdiag * bs * bs + 0.5 * bs * (bs + 1));
    *nnz_out = nnz;
    double b = nnz * 4.0 + 16.0 * n;                        /* rowind, colptr, diag */
    /* scatter map: one offset a node block in 1, 2 or 4 bytes (sb_sparse.h: the fewest that hold the longest
     * column, at most stencil * bs entries); a coarser level's only when it assembles (the rmtr solver) */
    const double colmax = (sz->stencil > 1 ? sz->stencil : 1) * bs, wmap = colmax <= 256 ? 1 : colmax <= 65536 ? 2 : 4;
    b += ne * k * 4.0 + (maps ? ne * 0.5 * k * (k + 1) * wmap : 0.0);   /* element nodes, scatter map */
    b += nnz * 8.0 * (dynamic ? 2.0 : 1.0);                 /* H (D) */
    if (dynamic) b += sz->mass_nnz[l] > 0 ? sz->mass_nnz[l] * (8.0 + wmap) + 8.0 * n : nnz * 8.0;   /* M (offsets as the map's) */
    b += n * (1.0 + 4.0 * 8.0);                             /* fixed flags, tmp, xhat, xn, spare */
    return b;
}

/* CHOLMOD's factor of level l (nnz upper entries of its matrix): the int
 * pattern copy of A, the supernodal factor's values (sb_linsolve_fill: the
 * zeros supernodes store, measured; 1.3 with CHOLMOD's defaults), its
 * indices and workspaces; nnz(L) = 0.6 nnz(A) log2(nodes) (nested-
 * dissection growth), at most dense. */
static double factor_bytes(const sb_method_size *sz, int l, double nnz, int supernodes, double *lnz_out)
{
    const double n = sz->nodes[l] * sz->bs, nodes = sz->nodes[l];
    double lnz = 0.6 * nnz * (nodes > 2 ? log2(nodes) : 1.0);
    if (lnz > 0.5 * n * (n + 1)) lnz = 0.5 * n * (n + 1);
    *lnz_out = lnz;
    return 4.0 * (nnz + n) + sb_linsolve_fill(supernodes) * 8.0 * lnz + 8.0 * 8.0 * n;
}

int sb_memory_scene_lifts(const sb_scene *scene, const sb_paramset *ps)
{
    if (!scene || (ps && !sb_param_int_or(ps, "run.lifting", 1))) return 0;
    for (int i = 0; i < scene->n_bcs; i++)
        if (scene->bcs[i].kind == SB_BC_MOVING) return 1;
    return 0;
}

void sb_memory_estimate_run(const sb_method_size *sz, const sb_memory_run *r, sb_memory_estimate *est)
{
    const int F = sz->levels > 0 ? sz->levels - 1 : 0;
    /* a coarser level's own energy is evaluated by the rmtr solver alone
     * (its coarse models and nested start); Galerkin products never read it */
    est->method = sz->method_bytes - (r->multilevel ? 0.0 : sz->coarse_energy_bytes);
    est->matrices = 0;
    const int C = r->multilevel || r->krylov_mg ? 0 : F;   /* the level whose factor is counted */
    double nnz_c = 0;
    for (int l = 0; l <= F; l++) {
        double nnz;
        est->matrices += level_bytes(sz, l, r->dynamic, l == F || r->multilevel, &nnz);
        if (r->multilevel && l > 0) est->matrices += nnz * 8.0;   /* Galerkin coarse model I^T H I */
        if (l == F) est->nnz = nnz;
        if (l == C) nnz_c = nnz;
    }
    /* the rmtr solver's own structures on each finer level of a pair (l-1, l),
     * counted since issue 42 measured a 1.2e6-dof bhem run at twice its old
     * estimate: the Galerkin product's index of the fine pattern's strictly
     * lower part (a row and a 4-byte offset per off-diagonal entry), its
     * accumulators and marks (sb_galerkin.c), the prolongation
     * and its transpose (sb_csr, int column + double value), and the additive
     * Schwarz smoother's packed element factors (sb_schwarz.c, the default
     * smoother_precond) with their dof lists */
    if (r->multilevel)
        for (int l = 1; l <= F; l++) {
            double nnz_l;
            (void)level_bytes(sz, l, 0, 1, &nnz_l);
            const double nf = sz->nodes[l] * sz->bs, nc = sz->nodes[l - 1] * sz->bs;
            const double ps = (sz->prolong_per_dof > 0 ? sz->prolong_per_dof : 1.0) * nf;
            const double m = (double)sz->nodes_per_element * sz->bs;
            est->matrices += (nnz_l - nf > 0 ? nnz_l - nf : 0) * 8.0 + nf * (8.0 + 8.0 + 4.0 + 1.0) + nc * (8.0 + 4.0 + 2.0);
            est->matrices += 2.0 * ps * 12.0 + (nf + nc) * 8.0;
            est->matrices += sz->elements[l] * (0.5 * m * (m + 1.0) * 8.0 + m * 4.0 + 17.0);
        }
    /* pcg-mg (issue 38, sb_precond_mg.c, sb_galerkin.c lean products): per
     * finer level of a pair, 8 bytes per off-diagonal entry of its pattern
     * (docs/solvers.md, "lean" products), the smoother's inverted node blocks
     * and five work vectors; the coarse levels' values are their matrices
     * (counted above).  The penalty band's factors (rmtr: O(sqrt n) dofs)
     * are left out. */
    if (r->krylov_mg && !r->multilevel)
        for (int l = 1; l <= F; l++) {
            double nnz_l;
            (void)level_bytes(sz, l, 0, 1, &nnz_l);
            const double nf = sz->nodes[l] * sz->bs;
            est->matrices += (nnz_l - nf > 0 ? nnz_l - nf : 0) * 8.0 + nf * (sz->bs + 5.0) * 8.0;
        }
    est->dofs = sz->nodes[F] * sz->bs;
    est->factor = factor_bytes(sz, C, nnz_c, r->supernodes, &est->factor_nnz);
    if (r->multilevel && r->lifts && C != F) {
        /* the lifting's CHOLMOD factor of the finest level, kept for the run
         * (issue 42: a bhem drape run with the rmtr solver at 311,052 dofs
         * peaked at 1.5 times its estimate without it) */
        double lnz_f;
        est->factor += factor_bytes(sz, F, est->nnz, r->supernodes, &lnz_f);
    }
    /* the run's and the solver's vectors on the finest level (x, x_n, v,
     * reference, resume point, gradient, trial point, steps ...) */
    est->vectors = 24.0 * 8.0 * est->dofs;
    /* the record: probe trajectories and the sample grid with its triangles */
    const double ns = (double)r->sample_n * r->sample_n, nt = 2.0 * (r->sample_n - 1.0) * (r->sample_n - 1.0);
    est->record = ((double)r->steps + 1.0) * (r->n_probes > 0 ? r->n_probes : 1) * 3.0 * 8.0 + ns * 8.0 * 8.0 +
                  nt * 3.0 * 4.0;
    /* the process itself: code and libraries (HDF5, CHOLMOD, OpenBLAS), measured 15 MB */
    est->bytes = 16e6 + est->method + est->matrices + est->factor + est->vectors + est->record;
}

double sb_memory_physical(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    return pages > 0 && size > 0 ? (double)pages * (double)size : 0.0;
}

void sb_memory_format(double bytes, char *buf, size_t len)
{
    static const char *const unit[] = { "bytes", "kB", "MB", "GB", "TB", "PB", "EB" };
    int u = 0;
    while (bytes >= 1000.0 && u < 6) bytes /= 1000.0, u++;
    if (u == 0) snprintf(buf, len, "%.0f bytes", bytes);
    else if (bytes >= 1000.0) snprintf(buf, len, "%.3g %s", bytes, unit[u]);   /* beyond exabytes */
    else snprintf(buf, len, "%.*f %s", bytes < 10.0 ? 1 : 0, bytes, unit[u]);
}

int sb_memory_check(const sb_method_size *sz, const sb_memory_estimate *est, double limit_bytes,
                    const char *what, char *err, size_t errlen)
{
    char need[32], have[32];
    const int F = sz->levels > 0 ? sz->levels - 1 : 0;
    double limit = limit_bytes > 0 ? limit_bytes : sb_memory_physical();
    if (limit > 0 && est->bytes > limit) {
        sb_memory_format(est->bytes, need, sizeof need);
        sb_memory_format(limit, have, sizeof have);
        snprintf(err, errlen, "%s needs about %s of memory (%.3g dofs, %.3g Hessian entries, a Cholesky factor of "
                 "about %.3g entries), more than the %s %s: choose a smaller resolution, or raise the limit with "
                 "--set run.max_memory=GB", what, need, est->dofs, est->nnz, est->factor_nnz,
                 limit_bytes > 0 ? "run.max_memory of" : "machine's physical memory of", have);
        return SB_ERR_INPUT;
    }
    /* index limits: dofs and element dof lists are int, CHOLMOD's entries int */
    if (!(est->dofs <= INT_MAX) || !(sz->elements[F] * sz->nodes_per_element * sz->bs <= INT_MAX)) {
        snprintf(err, errlen, "%s would have %.3g dofs (%.3g elements); this build indexes dofs and element dof "
                 "lists with int, at most %d: choose a smaller resolution", what, est->dofs, sz->elements[F], INT_MAX);
        return SB_ERR_INPUT;
    }
    if (!(est->nnz <= INT_MAX)) {
        snprintf(err, errlen, "%s would have a Hessian of %.3g stored entries; the sparse Cholesky factorization "
                 "(CHOLMOD's int interface) takes at most %d: choose a smaller resolution", what, est->nnz, INT_MAX);
        return SB_ERR_INPUT;
    }
    return SB_OK;
}

int sb_memory_check_method(const sb_method_type *mt, const sb_scene *scene, const sb_method_config *cfg,
                           const sb_memory_run *r, double limit_bytes, const char *what, double *bytes,
                           char *err, size_t errlen)
{
    sb_method_size sz;
    sb_memory_estimate est;
    *bytes = 0;
    if (!mt->estimate) return SB_OK;
    memset(&sz, 0, sizeof sz);
    if (cfg->ctx) cfg->ctx->err[0] = 0;
    if (mt->estimate(scene, cfg, &sz)) {
        snprintf(err, errlen, "%s: %s", what,
                 cfg->ctx && cfg->ctx->err[0] ? cfg->ctx->err : "the discretization cannot be built at this size");
        return SB_ERR_INPUT;
    }
    sb_memory_run rl = *r;
    /* penalty methods have no constrained dofs: nothing to lift (sb_problem_lift) */
    if (!rl.lifts && !(mt->flags & SB_METHOD_PENALTY_BCS)) rl.lifts = sb_memory_scene_lifts(scene, cfg->params);
    sb_memory_estimate_run(&sz, &rl, &est);
    *bytes = est.bytes;
    return sb_memory_check(&sz, &est, limit_bytes, what, err, errlen);
}
