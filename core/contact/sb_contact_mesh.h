/* sb_contact_mesh.h — contact sample points of a triangle mesh (docs/contact.md),
 * shared by the triangle methods (linear_fem, adaptive_sqrt3). */
#ifndef SB_CONTACT_MESH_H
#define SB_CONTACT_MESH_H

#include "sb_contact_points.h"
#include "sb_mesh.h"

/* The points of the per_side-fold barycentric subdivision of every triangle
 * of m (vertex v's dofs at 3 v): vertices, per_side - 1 points per edge, the
 * interior points of each triangle, with the lumped areas of the
 * sub-triangulation (they sum to the reference area).  per_side = 1: the
 * vertices alone.  SB_OK or SB_ERR_NOMEM. */
int sb_contact_points_mesh(const sb_mesh *m, int per_side, sb_contact_points *cp);

#endif
