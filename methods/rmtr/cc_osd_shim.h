/* cc_osd_shim.h — OpenSubdiv (C++) behind a small extern "C" interface.
 * Quad cages only; Catmull–Clark with VTX_BOUNDARY_EDGE_ONLY (smooth
 * boundary curve rules, RMTR paper App. A).  Arrays returned through pointer
 * arguments are malloc'ed; release them with free(). */
#ifndef CC_OSD_SHIM_H
#define CC_OSD_SHIM_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One uniform refinement step (Far::TopologyRefiner + Far::StencilTable).
 * For every fine vertex i (OpenSubdiv's order): its parent kind[i] (0 =
 * vertex pa[i], 1 = edge (pa[i], pb[i]), 2 = face pa[i]) and its stencil
 * (rp[i]..rp[i+1] into ci, w) on the coarse vertices.  Returns 0 or -1 with
 * a message in err. */
int cc_osd_refine(int nv, int nf, const int *fv, int *nfine, int **kind, int **pa, int **pb,
                  int **rp, int **ci, double **w, char *err, size_t errlen);

/* Limit stencils (Bfr::Surface::EvaluateStencil, exact away from extraordinary
 * corners at approximation level `approx`, 1..10) at np points (face[p],
 * uv[2p], uv[2p+1]): W[(6p + r) nv + I], r = P, Du, Dv, Duu, Duv, Dvv. */
int cc_osd_limit(int nv, int nf, const int *fv, int np, const int *face, const double *uv,
                 int approx, double *W, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
