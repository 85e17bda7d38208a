/* lf_contact.c — contact sample points of the triangle discretization
 * (docs/contact.md): the n-fold barycentric subdivision points of the
 * level's mesh with lumped areas, shared with adaptive_sqrt3
 * (core/contact/sb_contact_mesh.c). */
#include "lf.h"
#include "sb_contact_mesh.h"

int lf_contact_points(void *state, int level, int per_side, sb_contact_points *cp)
{
    const lf_state *S = state;
    return sb_contact_points_mesh(&S->lv[level].mesh, per_side, cp);
}
