// mlt_gpu_memory.h — what the GPU MLT driver (mlt_driver.h on a GPU) allocates on the device, estimated
// from the settings alone before anything is allocated, so that a render that does not fit is
// refused with one line instead of failing halfway. Plain C++: checked by CPU tests.
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/integrators/mlt/mlt_integrator.h"

namespace caustica {

/// Bytes by use. The scene and BVH come on top (estimateGpuMemory in path/gpu_memory.h). An
/// upper bound: the bootstrap's arrays are counted although they are freed before the first
/// iteration.
struct MltGpuMemoryEstimate {
    size_t chainState = 0;    // chains x mltBytesPerChain: primary samples, film position, F, I, U
    size_t chainScratch = 0;  // the rest of MltChainBuffers: proposals, splats, counters, splat
                              // sums, and the splat mode's arrays (atomic accumulators, or sort
                              // keys, values and pixel starts)
    size_t pixelWeights = 0;  // relative target: one float per pixel
    size_t bootstrap = 0;     // M x kMltBootstrapBytesPerSample, plus each chain's start and rays
    size_t chainSort = 0;     // Morton sorting (sortEvery > 0): keys, order, permutation scratch
    size_t primitives = 0;    // the primitives' cached scratch: the largest radix sort's
                              // alternate arrays plus CUB's temporary storage
    size_t total() const {
        return chainState + chainScratch + pixelWeights + bootstrap + chainSort + primitives;
    }
};

/// Per bootstrap sample: its importance, pixel and ray count.
inline constexpr size_t kMltBootstrapBytesPerSample = sizeof(float) + 2 * sizeof(uint32_t);
/// Allowance for CUB's temporary storage: a fixed part (reductions, scans, small sorts) plus a
/// part per element of the largest radix sort. CUB's one-sweep sort keeps a 256-bin histogram
/// per tile of a few thousand elements and per 8-bit pass; 8 bytes per element bounds that for
/// 64-bit keys (past a few million splats the fixed part alone would not).
inline constexpr size_t kMltCubTemporaryBytes = size_t(1) << 20;
inline constexpr size_t kMltCubTemporaryBytesPerSortedElement = 8;

/// The estimate for `settings` (compact state) with `storedBounces` stored bounces
/// (mltStoredBounces) on a film of `pixels` pixels.
MltGpuMemoryEstimate estimateMltGpuMemory(const MltSettings& settings, uint32_t storedBounces,
                                          uint32_t pixels);

/// Refuses (one line naming what to lower) an MLT render on a GPU whose estimate, scene and BVH
/// included, exceeds the GPU's free memory; without a GPU to ask, the allocation reports the error.
void checkGpuMltMemory(const Scene& scene, const Bvh& bvh, const PathSettings& path, const MltSettings& settings);

/// The Morton sort's permutation scratch: as large as the largest per-chain array of the
/// compact store and the chain buffers.
size_t mltGpuPermuteScratchBytes(uint32_t chains, uint32_t storedBounces);

}  // namespace caustica
