/* sb_pin.h — sliding pins (docs/scene_format.md "Sliding pins"): a moving
 * point condition with "slide" holds a material point that runs along a
 * straight segment of the grid parameter (s, t) as its motion factor f runs
 * from 0 to 1, at that point's reference position moved by the condition's
 * rigid motion,
 *
 *     E_pin = k/2 sum_{c in components} (x_c(st(f)) - p_c(f))^2,
 *     st(f) = st_0 + f (st_1 - st_0),   p(f) = c + R(f angle)(X(st(f)) - c) + f translation,
 *
 * a penalty (the point moves between nodes, so no dof can be eliminated).
 * x(st) = sum_a w_a x[dof_a .. dof_a+2] through the method's optional op
 * point_terms; X(st) through the same terms on the method's reference state.
 * One sb_pins per level, owned by the problem (sb_problem.c). */
#ifndef SB_PIN_H
#define SB_PIN_H

#include "sb_method.h"

typedef struct sb_pins sb_pins;

/* The pins of `level` (NULL in *out when the scene has none).  SB_OK, or
 * SB_ERR_UNSUPPORTED with a sentence in ctx when the method has no
 * point_terms op. */
int  sb_pins_create(struct sb_context *ctx, const sb_method_type *mt, void *ms, const sb_scene *sc, int level,
                    sb_pins **out);
void sb_pins_free(sb_pins *P);
/* The pins' points and targets for a step (motion factors of si). */
int  sb_pins_set_step(sb_pins *P, const sb_step_info *si);
/* e += E_pin(x); g += dE/dx; H += d2E/dx2 (each when non-NULL).  SB_OK, or
 * SB_ERR_INTERNAL when a pin couples dofs outside the pattern. */
int  sb_pins_energy(const sb_pins *P, const double *x, double *e, double *g, sb_matrix *H);
/* max over pins of |x(st(f)) - p(f)| over the held components (m) */
double sb_pins_violation(const sb_pins *P, const double *x);
int  sb_pins_count(const sb_pins *P);

#endif
