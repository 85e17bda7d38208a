/* sb_shell.h — Kirchhoff–Love thin-shell kernel shared by every method that
 * writes the midsurface as x(xi) = sum_I N_I(xi) q_I with scalar basis
 * functions N_I and control values q_I in R^3 (subdivision, Hermite).
 *
 * Strains: membrane A = (a - abar)/2, bending B = (b - bbar)/2 in covariant
 * components, transformed to the local orthonormal warp/weft frame; the
 * through-thickness strain E(xi3) = A - 2 xi3 B (BHEM paper Eq. 5-6, C term
 * dropped), integrated by Gauss points through the thickness. */
#ifndef SB_SHELL_H
#define SB_SHELL_H

#include "sb_material.h"
#include "sb_params.h"

#define SB_SHELL_MAX_BASIS 64    /* >= 2n+8 for valence n up to 28 */

typedef enum { SB_HESS_EXACT = 0, SB_HESS_PSEUDO = 1, SB_HESS_PSD = 2 } sb_hess_kind;
extern const char *const sb_hess_kind_names[];   /* "exact", "pseudo", "psd", NULL */

/* Basis at one quadrature point: values and parametric derivatives, each k long. */
typedef struct sb_shell_basis {
    int k;
    const double *N, *N1, *N2, *N11, *N12, *N22;
} sb_shell_basis;

/* Reference quantities at one quadrature point (precomputed once). */
typedef struct sb_shell_ref {
    double abar[3];     /* abar_11, abar_22, abar_12 (covariant metric) */
    double bbar[3];     /* bbar_11, bbar_22, bbar_12 (second fundamental form) */
    double T[9];        /* e_local = T * (E_11, E_22, E_12)_covariant, row-major 3x3 */
    double normal[3];   /* reference unit normal */
    double dA;          /* quadrature weight * sqrt(det abar) */
    /* added by the kernel implementer (additive): */
    double ainv[3];     /* abar^11, abar^22, abar^12 (contravariant metric) */
    double sqrt_a;      /* sqrt(det abar) */
    double weight;      /* quadrature weight in the parameter domain */
    double e1[3], e2[3];/* local orthonormal frame: e1 = warp, e2 = normal x e1 (weft) */
} sb_shell_ref;

/* From the reference surface derivatives X_,1 X_,2 X_,11 X_,12 X_,22.
 * The warp direction is a_1 rotated by warp_angle about the normal.
 * Returns SB_OK, or SB_ERR_INPUT for a degenerate reference (a_1 x a_2 = 0,
 * non-finite input); the struct is then filled with NaN so that any energy
 * computed from it is non-finite.  (Return type changed from void to int:
 * source-compatible with callers that ignore it.) */
int sb_shell_ref_init(sb_shell_ref *r, const double X1[3], const double X2[3],
                      const double X11[3], const double X12[3], const double X22[3],
                      double warp_angle, double weight);
/* Same, from basis and reference control values Xq (k x 3). */
int sb_shell_ref_init_basis(sb_shell_ref *r, const sb_shell_basis *b, const double *Xq,
                            double warp_angle, double weight);

/* The shell "section" law (added, additive): through-thickness Gauss
 * integration of the material for local-frame membrane strain A and bending
 * strain B (Voigt 11, 22, 12; E(xi3) = A - 2 xi3 B).  Returns energy per unit
 * reference area; sA = d/dA, sB = d/dB (3 each) and C = d2/d(A,B)^2 (6 x 6
 * row-major, order A11 A22 A12 B11 B22 B12) when non-NULL.  For triangle
 * elements with a discrete second fundamental form, so that they integrate
 * the same materials the same way. */
double sb_shell_section(const sb_material *m, const double A[3], const double B[3], double sA[3],
                        double sB[3], double C[36]);

/* Scratch space, sized for SB_SHELL_MAX_BASIS; one per thread, never per call. */
typedef struct sb_shell_work sb_shell_work;
sb_shell_work *sb_shell_work_new(void);
void sb_shell_work_free(sb_shell_work *w);

/* Elastic energy of one quadrature point (dA included).  q: k x 3 current
 * control values (row I = q_I).  grad (3k) and hess (3k x 3k, row-major,
 * dof index 3*I + c) are ACCUMULATED when non-NULL.  kind EXACT or PSEUDO
 * (BHEM paper §6.1 / App. B: drop the second derivatives of the bending
 * strains, d2 beta/dq2; the membrane ones, Eq. 51-53, are kept as in the
 * paper); kind PSD evaluates the exact Hessian: the projection is done per
 * element with sb_psd_project().  Bad input (NULL pointers, k out of range,
 * degenerate reference or current surface) gives a NaN / non-finite energy,
 * which the caller records as SB_NONFINITE; never a crash. */
double sb_shell_energy(const sb_material *m, const sb_shell_ref *r, const sb_shell_basis *b,
                       const double *q, double *grad, double *hess, sb_hess_kind kind,
                       sb_shell_work *w);

/* ---- the fast kernel (issue 30; additive: the functions above are the
 * reference kernel, unchanged, bit-identical to the records made with it) --
 *
 * Energy, gradient and Hessian of a whole element: nq quadrature points
 * with references r[0..nq) and bases b[0..nq) (all with the same k), the
 * same quantities as summing sb_shell_energy() over the points, computed
 * batched over the points (sb_shell_elem.c; round-off differs from the
 * reference).  grad (3k) and hess (3k x 3k, row-major, exactly symmetric)
 * are ACCUMULATED when non-NULL.  kind EXACT and PSEUDO as above; kind PSD
 * is the strain-space projection (section tangent and membrane stress
 * clamped to their PSD parts, bending second derivatives dropped), PSD by
 * construction, for elements whose exact Hessian is not PSD (see
 * sb_psd_check).  Bad input gives NaN, as sb_shell_energy. */
typedef struct sb_shell_batch sb_shell_batch;
/* scratch for elements of up to kmax basis functions and nqmax points; one per thread */
sb_shell_batch *sb_shell_batch_new(int kmax, int nqmax);
void sb_shell_batch_free(sb_shell_batch *w);
double sb_shell_element(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,
                        const double *q, double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w);

/* The vector width of the batch's products (sb_elem_tile.c): the widest
 * the CPU runs is chosen by sb_shell_batch_new.  All widths give the same
 * bits (one lane per output entry, the same operations in the same order,
 * no fused multiply-add; tests/test_shell_isa.c), so the choice changes
 * speed only.  SB_ISA_BASE is the build's own (SSE2 in the default build,
 * whatever -march=native gives in `make NATIVE=1`, which has no others). */
typedef enum { SB_ISA_BASE = 0, SB_ISA_AVX2 = 1, SB_ISA_AVX512 = 2 } sb_shell_isa;
#define SB_ISA_COUNT 3
const char *sb_shell_isa_name(sb_shell_isa isa);   /* "sse2"/"native", "avx2", "avx512" */
int sb_shell_isa_supported(sb_shell_isa isa);      /* built in and run by this CPU? */
sb_shell_isa sb_shell_isa_best(void);
sb_shell_isa sb_shell_batch_isa(const sb_shell_batch *w);
/* SB_OK, or SB_ERR_UNSUPPORTED when this build or CPU lacks isa */
int sb_shell_batch_set_isa(sb_shell_batch *w, sb_shell_isa isa);
/* run.vectors: "auto" (the widest this CPU runs), "sse2", "avx2", "avx512" */
extern const char *const sb_vector_choices[];
/* The width run.vectors asks for (auto when ps is NULL or has no run.vectors):
 * SB_OK, or SB_ERR_INPUT with a sentence in msg when this CPU or build
 * cannot run it. */
int sb_shell_isa_from_params(const sb_paramset *ps, sb_shell_isa *isa, char *msg, size_t len);
/* The same, but hess is OVERWRITTEN (all 3k x 3k entries; grad is still
 * accumulated): for an element matrix with no other terms, which then need
 * not be zeroed first.  Bit-identical to sb_shell_element on a zeroed hess. */
double sb_shell_element_into(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,
                             const double *q, double *grad, double *hess, sb_hess_kind kind, sb_shell_batch *w);

/* The section law of sb_shell_section, evaluated for the fast kernel: the
 * thickness points batched in vectors, denim's powers by vectorized
 * exp/log (sb_vmath.h) instead of libm (agrees with sb_shell_section to a
 * few ulp; tests/test_shell_fast.c). */
double sb_shell_section_fast(const sb_material *m, const double A[3], const double B[3], double sA[3],
                             double sB[3], double C[36]);

/* Which kernel a method assembles with (method.kernel): the fast one, or
 * the reference (per point, sb_shell_energy; the committed records' bits). */
typedef enum { SB_KERNEL_FAST = 0, SB_KERNEL_REFERENCE = 1 } sb_kernel_kind;
extern const char *const sb_kernel_names[];   /* "fast", "reference", NULL */

/* Local-frame membrane strain A and bending strain B (Voigt 11, 22, 12; the
 * E(xi3) = A - 2 xi3 B that sb_shell_energy integrates) at one quadrature
 * point.  Returns SB_OK, SB_ERR_INPUT for bad arguments, SB_NONFINITE for a
 * degenerate current surface. */
int sb_shell_strains(const sb_shell_ref *r, const sb_shell_basis *b, const double *q, sb_shell_work *w,
                     double A[3], double B[3]);

/* Stability of the shell section at strains (A, B) (sb_stability.c): the
 * smallest eigenvalue of the membrane tangent d2e/dA2 (3 x 3, integrated
 * through the thickness) and of the whole section tangent d2e/d(A,B)2
 * (6 x 6, B scaled by sqrt(3)/thickness so both blocks weigh alike; a
 * congruence, so the signs of the eigenvalues are unchanged), each divided
 * by the largest |eigenvalue| of its matrix.  A negative value means the
 * material law softens there: the energy is not convex in the strain
 * (strain softening), so the minimization problem of a fine mesh can
 * localize.  Returns SB_OK, SB_ERR_INPUT or SB_NONFINITE. */
int sb_shell_section_stability(const sb_material *m, const double A[3], const double B[3],
                               double *rel_min_membrane, double *rel_min_section);

/* Accumulate one quadrature point of configuration q into a material state
 * (sb_material_state, sb_method.h): strains, stability, area.  Init first. */
struct sb_material_state;
void sb_material_state_init(struct sb_material_state *ms);
int sb_material_state_add(struct sb_material_state *ms, const sb_material *m, const sb_shell_ref *r,
                          const sb_shell_basis *b, const double *q, sb_shell_work *w);
/* The same from a point's strains (A, B) and reference area dA (methods
 * with strains of their own, e.g. linear_fem's triangles). */
int sb_material_state_add_strains(struct sb_material_state *ms, const sb_material *m, double dA, const double A[3],
                                  const double B[3]);

/* External potential of one quadrature point: gravity (dead, density * g)
 * and pressure p along the normal.  follower = 0: dead load on the reference
 * normal (linear potential); follower = 1: follows the deformed normal,
 * made conservative by the enclosed-volume potential E = -p/3 x.(x_,1 x x_,2) w
 * (exact p n da on closed surfaces and fixed boundaries; see sb_shell_ext.c).
 * Returns energy, accumulates grad / hess (hess only for follower). */
double sb_shell_external(const sb_material *m, const sb_shell_ref *r, const sb_shell_basis *b,
                         const double *q, const double gvec[3], double pressure, int follower,
                         double *grad, double *hess);

/* Clamp the eigenvalues of a symmetric n x n (row-major) matrix at >= 0, in place.
 * Uses LAPACK dsyev; work must hold sb_psd_work_size(n) doubles.  An already
 * PSD matrix comes back unchanged.  Returns SB_OK, SB_ERR_INPUT, or
 * SB_NONFINITE (NaN/Inf entries, or dsyev failed to converge). */
size_t sb_psd_work_size(int n);
int sb_psd_project(int n, double *H, double *work);

/* Is the symmetric n x n H (row-major) positive semidefinite up to
 * round-off?  LDL^T with diagonal pivoting (sb_psd.c): 1 when every pivot
 * above the tolerance tol = 64 n eps max|H_ii| is positive and the Schur
 * complement left below it is within the tolerance; 0 otherwise (also for
 * NaN/Inf, and for n > SB_PSD_CHECK_MAX_N).  work: n*n doubles.  About
 * n^3/6 multiply-adds, against the ~9 n^3 of a full eigendecomposition. */
#define SB_PSD_CHECK_MAX_N (3 * SB_SHELL_MAX_BASIS)
int sb_psd_check(int n, const double *H, double *work);

/* Hessian kind PSD with the fast kernel, for one element: as
 * sb_shell_element (energy returned, grad and hess accumulated; hess must
 * hold zeros or other terms of no concern here), hess then plus Kx, the
 * element's other terms (penalty, loads; ignored unless kx_used).  The sum
 * is kept when it is PSD (sb_psd_check): exact where the element Hessian
 * already is.  Otherwise, if Kx is PSD, the shell part is replaced by the
 * strain-space projection (kind PSD above, computed as the exact Hessian
 * minus the difference: bending second derivatives, negative membrane
 * stress and, where a section tangent is clamped, its clamped part), and
 * else the eigenvalues of the sum are clamped
 * (sb_psd_project).  *path (may be NULL) = 0, 1 or 2 for the three cases.
 * work: sb_psd_work_size(3k) doubles. */
double sb_shell_element_psd(const sb_material *m, int nq, const sb_shell_ref *r, const sb_shell_basis *b,
                            const double *q, double *grad, double *hess, const double *Kx, int kx_used,
                            sb_shell_batch *w, double *work, int *path);

/* Per-thread element scratch of a method: both kernels' work spaces,
 * control values qe (3 kmax), the other terms' matrix Kx ((3 kmax)^2), PSD
 * work and nqmax bases.  init returns SB_OK or SB_ERR_NOMEM (then free). */
typedef struct sb_elem_scratch {
    sb_shell_work *work;
    sb_shell_batch *batch;
    double *qe, *Kx, *psd;
    sb_shell_basis *b;
} sb_elem_scratch;
/* isa: the vector width of its batch (sb_shell_isa_from_params) */
int sb_elem_scratch_init(sb_elem_scratch *s, int kmax, int nqmax, sb_shell_isa isa);
void sb_elem_scratch_free(sb_elem_scratch *s);

#endif
