// cc_osd_shim.cpp — OpenSubdiv behind extern "C" (see cc_osd_shim.h).
// RMTR paper §6: "For the assembly of the global subdivision matrix, we use
// the OpenSubdiv library"; limit stencils serve as an independent check of
// the basis functions of cc_basis.c.
#include "cc_osd_shim.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <vector>

using namespace OpenSubdiv;

namespace {

typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;

Far::TopologyRefiner *make_refiner(int nv, int nf, const int *fv, std::vector<int> &nvpf)
{
    nvpf.assign((size_t)nf, 4);
    Far::TopologyDescriptor desc;
    desc.numVertices = nv;
    desc.numFaces = nf;
    desc.numVertsPerFace = nvpf.data();
    desc.vertIndicesPerFace = fv;
    Sdc::Options opt;
    opt.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    return Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, opt));
}

void msg(char *err, size_t len, const char *text)
{
    if (err && len) std::snprintf(err, len, "OpenSubdiv: %s", text);
}

template <class T> T *cmalloc(size_t n) { return static_cast<T *>(std::malloc((n ? n : 1) * sizeof(T))); }

} // namespace

extern "C" int cc_osd_refine(int nv, int nf, const int *fv, int *nfine, int **kind, int **pa, int **pb,
                             int **rp, int **ci, double **w, char *err, size_t errlen)
{
    *kind = *pa = *pb = *rp = *ci = nullptr;
    *w = nullptr;
    try {
        std::vector<int> nvpf;
        std::unique_ptr<Far::TopologyRefiner> ref(make_refiner(nv, nf, fv, nvpf));
        if (!ref) {
            msg(err, errlen, "cannot build a topology refiner from the cage");
            return -1;
        }
        Far::TopologyRefiner::UniformOptions uo(1);
        uo.orderVerticesFromFacesFirst = true;   // child vertices: faces, edges, vertices
        ref->RefineUniform(uo);
        typedef Far::StencilTableFactoryReal<double> StencilFactory;   // double weights
        StencilFactory::Options so;
        so.interpolationMode = StencilFactory::INTERPOLATE_VERTEX;
        so.generateOffsets = true;
        so.generateControlVerts = false;
        so.generateIntermediateLevels = false;
        so.maxLevel = 1;
        std::unique_ptr<const Far::StencilTableReal<double> > tab(StencilFactory::Create(*ref, so));
        const Far::TopologyLevel &l0 = ref->GetLevel(0);
        int ne = l0.GetNumEdges(), n1 = ref->GetLevel(1).GetNumVertices();
        if (!tab || tab->GetNumStencils() != n1 || n1 != nv + ne + nf) {
            msg(err, errlen, "unexpected stencil table size");
            return -1;
        }
        const std::vector<int> &sz = tab->GetSizes();
        const std::vector<Far::Index> &off = tab->GetOffsets();
        const std::vector<Far::Index> &idx = tab->GetControlIndices();
        const std::vector<double> &wt = tab->GetWeights();
        size_t nnz = idx.size();
        *kind = cmalloc<int>((size_t)n1);
        *pa = cmalloc<int>((size_t)n1);
        *pb = cmalloc<int>((size_t)n1);
        *rp = cmalloc<int>((size_t)n1 + 1);
        *ci = cmalloc<int>(nnz);
        *w = cmalloc<double>(nnz);
        if (!*kind || !*pa || !*pb || !*rp || !*ci || !*w) {
            msg(err, errlen, "out of memory");
            return -1;
        }
        (*rp)[0] = 0;
        for (int i = 0; i < n1; i++) {
            (*rp)[i + 1] = (*rp)[i] + sz[(size_t)i];
            for (int p = 0; p < sz[(size_t)i]; p++) {
                (*ci)[(*rp)[i] + p] = idx[(size_t)off[(size_t)i] + (size_t)p];
                (*w)[(*rp)[i] + p] = wt[(size_t)off[(size_t)i] + (size_t)p];
            }
            if (i < nf) {
                (*kind)[i] = 2;
                (*pa)[i] = i;
                (*pb)[i] = -1;
            } else if (i < nf + ne) {
                Far::ConstIndexArray ev = l0.GetEdgeVertices(i - nf);
                (*kind)[i] = 1;
                (*pa)[i] = ev[0];
                (*pb)[i] = ev[1];
            } else {
                (*kind)[i] = 0;
                (*pa)[i] = i - nf - ne;
                (*pb)[i] = -1;
            }
        }
        *nfine = n1;
        return 0;
    } catch (const std::exception &ex) {
        msg(err, errlen, ex.what());
    } catch (...) {
        msg(err, errlen, "unknown exception");
    }
    return -1;
}

extern "C" int cc_osd_limit(int nv, int nf, const int *fv, int np, const int *face, const double *uv,
                            int approx, double *W, char *err, size_t errlen)
{
    try {
        std::vector<int> nvpf;
        std::unique_ptr<Far::TopologyRefiner> ref(make_refiner(nv, nf, fv, nvpf));
        if (!ref) {
            msg(err, errlen, "cannot build a topology refiner from the cage");
            return -1;
        }
        Bfr::SurfaceFactory::Options fo;
        fo.SetApproxLevelSmooth(approx < 1 ? 1 : approx > 10 ? 10 : approx);
        Bfr::RefinerSurfaceFactory<> factory(*ref, fo);
        Bfr::Surface<double> surf;
        std::vector<int> cv;
        std::vector<double> s;
        std::memset(W, 0, sizeof(double) * (size_t)np * 6 * (size_t)nv);
        for (int p = 0; p < np; p++) {
            if (face[p] < 0 || face[p] >= nf || !factory.InitVertexSurface<double>(face[p], &surf)) {
                msg(err, errlen, "face has no limit surface");
                return -1;
            }
            int k = surf.GetNumControlPoints();
            cv.resize((size_t)k);
            s.assign(6 * (size_t)k, 0.0);
            surf.GetControlPointIndices(cv.data());
            double *d = s.data();
            surf.EvaluateStencil(uv + 2 * p, d, d + k, d + 2 * k, d + 3 * k, d + 4 * k, d + 5 * k);
            for (int r = 0; r < 6; r++)
                for (int a = 0; a < k; a++) W[((size_t)6 * p + r) * nv + cv[(size_t)a]] += s[(size_t)r * k + a];
        }
        return 0;
    } catch (const std::exception &ex) {
        msg(err, errlen, ex.what());
    } catch (...) {
        msg(err, errlen, "unknown exception");
    }
    return -1;
}
