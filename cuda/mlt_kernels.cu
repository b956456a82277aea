// mlt_kernels.cu — the Metropolis kernels (integrators/mlt/mlt_kernel.h, mlt_splat.h) compiled by
// nvcc as GPU grids: proposal tracing with the own BVH, chain advance, both splat methods and the
// Morton keys. The path-tracing kernels (bootstrap, start, proposals: each holds a whole path
// tracer, minutes of ptxas apiece) are instantiated for the compact store only, the others for
// both stores. The CPU driver (mlt_integrator.cpp) runs the same functions through parallelFor;
// a GPU driver launches these (device pointers only).
#include "caustica/accel/bvh_traversal.h"
#include "caustica/integrators/mlt/mlt_kernel.h"
#include "cuda/mlt_kernels.h"
#include "cuda/parallel_for_cuda.h"

namespace caustica {

template <class Store>
void launchMltProposalsT(const SceneView& scene, const BvhIntersector& accel, const MltChainView<Store>& chains,
                         const MltStepParams& params) {
    parallelForCuda("mlt.propose", size_t(chains.chains) * params.proposals, [=] CA_HD(size_t item) {
        traceProposal(scene, accel, chains, params, uint32_t(item));
    }, 128);
}

template <class Store>
void launchMltAdvanceT(const MltChainView<Store>& chains, const MltStepParams& params) {
    parallelForCuda("mlt.advance", chains.chains, [=] CA_HD(size_t c) { advanceChain(chains, params, uint32_t(c)); });
}

template <class Store>
void launchMltStartT(const SceneView& scene, const BvhIntersector& accel, const MltChainView<Store>& chains,
                     const MltStepParams& params, const uint64_t* bootstrapIndex, uint32_t* rays) {
    parallelForCuda("mlt.start", chains.chains, [=] CA_HD(size_t c) {
        uint32_t r = 0;
        startChain(scene, accel, chains, params, uint32_t(c), bootstrapIndex[c], r);
        rays[c] = r;
    }, 128);
}

template <class Store>
void launchMltMortonKeysT(const MltChainView<Store>& chains, int width, int height, uint64_t* keys, uint32_t* order) {
    parallelForCuda("mlt.morton", chains.chains, [=] CA_HD(size_t c) {
        keys[c] = mltMortonKey(chains, uint32_t(c), width, height);
        order[c] = uint32_t(c);
    });
}

void launchMltBootstrap(const SceneView& scene, const BvhIntersector& accel, const MltStepParams& params,
                        uint64_t count, float* importance, uint32_t* pixel, uint32_t* rays) {
    parallelForCuda("mlt.bootstrap", count, [=] CA_HD(size_t i) {
        uint32_t r = 0;
        importance[i] = bootstrapImportance<CompactChainStore>(scene, accel, params, i, r, pixel[i]);
        rays[i] = r;
    }, 128);
}

void launchMltProposals(const SceneView& s, const BvhIntersector& a, const MltChainView<CompactChainStore>& c,
                        const MltStepParams& p) { launchMltProposalsT(s, a, c, p); }
void launchMltAdvance(const MltChainView<CompactChainStore>& c, const MltStepParams& p) { launchMltAdvanceT(c, p); }
void launchMltAdvance(const MltChainView<FloatChainStore>& c, const MltStepParams& p) { launchMltAdvanceT(c, p); }
void launchMltStart(const SceneView& s, const BvhIntersector& a, const MltChainView<CompactChainStore>& c,
                    const MltStepParams& p, const uint64_t* i, uint32_t* r) { launchMltStartT(s, a, c, p, i, r); }
void launchMltMortonKeys(const MltChainView<CompactChainStore>& c, int w, int h, uint64_t* k, uint32_t* o) {
    launchMltMortonKeysT(c, w, h, k, o);
}
void launchMltMortonKeys(const MltChainView<FloatChainStore>& c, int w, int h, uint64_t* k, uint32_t* o) {
    launchMltMortonKeysT(c, w, h, k, o);
}

void launchMltSplatAtomic(const MltSplatView& v, uint32_t pixels) {
    parallelForCuda("mlt.splat_atomic", v.count, [=] CA_HD(size_t i) { splatAtomic(v, uint32_t(i)); });
    parallelForCuda("mlt.splat_flush", pixels, [=] CA_HD(size_t p) { flushAtomicPixel(v, uint32_t(p)); });
}

void launchMltSplatKeys(const MltSplatView& v, uint32_t* keys, uint32_t* values) {
    parallelForCuda("mlt.splat_keys", v.count, [=] CA_HD(size_t i) {
        keys[i] = splatPixel(v, v.splats[i]);
        values[i] = uint32_t(i);
    });
}

void launchMltSplatGather(const MltSplatView& v, uint32_t* pixelStart, uint32_t pixels) {
    const uint32_t* sorted = v.sortedPixel;
    const uint32_t count = v.count;
    parallelForCuda("mlt.splat_starts", size_t(pixels) + 1, [=] CA_HD(size_t p) {
        findPixelStart(pixelStart, sorted, count, uint32_t(p));
    });
    parallelForCuda("mlt.splat_gather", pixels, [=] CA_HD(size_t p) { gatherSplats(v, uint32_t(p)); });
}

}  // namespace caustica
