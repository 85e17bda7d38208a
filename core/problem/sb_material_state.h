/* sb_material_state.h — how far a configuration strains its material: the
 * figure a method's optional material_state op fills (sb_method.h), that a
 * run records as /final/material and `shellbench inspect` prints. */
#ifndef SB_MATERIAL_STATE_H
#define SB_MATERIAL_STATE_H

/* Where a configuration strains the material (optional method op
 * material_state; recorded as /final/material).  Counts over the level's
 * quadrature points; "soft": the thickness-integrated tangent has a negative
 * eigenvalue (sb_shell_section_stability), i.e. the law is not convex in the
 * strain there (strain softening). */
typedef struct sb_material_state {
    long points;                /* quadrature points evaluated */
    long soft_membrane;         /* membrane tangent d2e/dA2 indefinite */
    long soft_section;          /* membrane + bending tangent indefinite */
    double area;                /* reference area of all points (m^2) */
    double soft_area;           /* reference area of the soft_membrane points (m^2) */
    long below_reference;       /* section energy below the reference state's (0): the
                                 * denim law's wells beyond about 2.5 % strain (docs/denim.md) */
    double below_reference_area;/* reference area of those points (m^2) */
    double max_strain[3];       /* max |E11|, |E22|, |E12|, local frame, midsurface */
    double min_rel_eig;         /* smallest relative eigenvalue of a membrane tangent */
    /* not recorded: the membrane eigenvalue and the section's softness of a
     * law whose tangent is the same at every strain (StVK), computed at its
     * first point (sb_stability.c) */
    const void *const_tangent_of;
    double const_tangent_lm;
    int const_tangent_soft;
} sb_material_state;

#endif
