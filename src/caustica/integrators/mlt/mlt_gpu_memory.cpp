#include "caustica/integrators/mlt/mlt_gpu_memory.h"

#include <algorithm>

#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_impl.h"
#include "caustica/integrators/mlt/mlt_splat.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/parallel/backend.h"
#include "caustica/util/error.h"

namespace caustica {

void checkGpuMltMemory(const Scene& scene, const Bvh& bvh, const PathSettings& path, const MltSettings& settings) {
    size_t freeBytes = 0, totalBytes = 0;
    if (!gpuMemoryInfo(freeBytes, totalBytes)) return;
    const GpuMemoryEstimate sceneBytes = estimateGpuMemory(gpuRenderSizes(scene, bvh, 1, PathMode::Megakernel));
    const uint32_t pixels = uint32_t(scene.film.width) * uint32_t(scene.film.height);
    const MltGpuMemoryEstimate mlt = estimateMltGpuMemory(settings, mltStoredBounces(path), pixels);
    const size_t need = sceneBytes.scene + sceneBytes.bvh + mlt.total();
    if (need <= freeBytes) return;
    throw Error("GPU memory: MLT needs about " + formatBytes(need) + " (scene and BVH " +
                formatBytes(sceneBytes.scene + sceneBytes.bvh) + ", chains " +
                formatBytes(mlt.chainState + mlt.chainScratch + mlt.chainSort) + ", bootstrap " +
                formatBytes(mlt.bootstrap) + ") but only " + formatBytes(freeBytes) + " is free on " +
                gpuDescription() + "; lower --mlt-chains or --mlt-bootstrap, or use --device cpu");
}

size_t mltGpuPermuteScratchBytes(uint32_t chains, uint32_t storedBounces) {
    const size_t n = chains;
    const size_t fine = 3 * (kMltCameraDims + 4 * size_t(storedBounces)) * n;  // 3-byte slots
    const size_t coarse = 3 * size_t(storedBounces) * n * sizeof(uint16_t);
    return std::max({fine, coarse, n * sizeof(Spectrum), n * sizeof(Vec2f)});
}

MltGpuMemoryEstimate estimateMltGpuMemory(const MltSettings& s, uint32_t storedBounces,
                                          uint32_t pixels) {
    const size_t n = s.chains, proposals = n * s.proposals;
    const size_t splats = size_t(mltSplatBatch(s, pixels)) * n * (size_t(s.proposals) + 1);  // a whole batch
    MltGpuMemoryEstimate e;
    e.chainState = n * mltBytesPerChain(MltStateKind::Compact, storedBounces);
    e.chainScratch =
        proposals * (sizeof(Vec2f) + sizeof(Spectrum) + sizeof(float) + sizeof(uint16_t) +
                     sizeof(uint32_t)) +
        n * (sizeof(float) + 2 * sizeof(uint32_t)) +  // large-step sums, large steps, accepted
        splats * sizeof(MltSplat) + size_t(kMltValuesPerPixel) * pixels * sizeof(double);
    size_t largestSort = 0, largestSortElements = 0;  // a radix sort's alternate keys and values
    if (s.splat == MltSplatKind::Atomic) {
        e.chainScratch += size_t(kMltValuesPerPixel) * pixels * sizeof(float);
    } else {
        e.chainScratch += splats * 2 * sizeof(uint32_t) + (size_t(pixels) + 1) * sizeof(uint32_t);
        largestSort = splats * 2 * sizeof(uint32_t);
        largestSortElements = splats;
    }
    if (s.target == MltTarget::Relative) e.pixelWeights = size_t(pixels) * sizeof(float);
    e.bootstrap = mltBootstrapCount(s, pixels) * kMltBootstrapBytesPerSample +
                  n * (sizeof(uint64_t) + sizeof(uint32_t));
    if (s.sortEvery > 0) {
        e.chainSort = n * (sizeof(uint64_t) + sizeof(uint32_t)) +
                      mltGpuPermuteScratchBytes(s.chains, storedBounces);
        largestSort = std::max(largestSort, n * (sizeof(uint64_t) + sizeof(uint32_t)));
        largestSortElements = std::max(largestSortElements, n);
    }
    e.primitives = largestSort + kMltCubTemporaryBytes + largestSortElements * kMltCubTemporaryBytesPerSortedElement;
    return e;
}

}  // namespace caustica
