// mlt_kernels.h — host entry points of cuda/mlt_kernels.cu: the Metropolis kernels as CUDA grids
// (all pointers in the views are device pointers). Launches are asynchronous on the default stream.
#pragma once

#include <cstdint>

#include "caustica/accel/intersector.h"
#include "caustica/integrators/mlt/mlt_kernel.h"

namespace caustica {

void launchMltBootstrap(const SceneView& scene, const BvhIntersector& accel, const MltStepParams& params,
                        uint64_t count, float* importance, uint32_t* pixel, uint32_t* rays);
void launchMltStart(const SceneView& scene, const BvhIntersector& accel, const MltChainView<CompactChainStore>& chains,
                    const MltStepParams& params, const uint64_t* bootstrapIndex, uint32_t* rays);
void launchMltProposals(const SceneView& scene, const BvhIntersector& accel,
                        const MltChainView<CompactChainStore>& chains, const MltStepParams& params);
void launchMltAdvance(const MltChainView<CompactChainStore>& chains, const MltStepParams& params);
void launchMltAdvance(const MltChainView<FloatChainStore>& chains, const MltStepParams& params);
void launchMltMortonKeys(const MltChainView<CompactChainStore>& chains, int width, int height, uint64_t* keys,
                         uint32_t* order);
void launchMltMortonKeys(const MltChainView<FloatChainStore>& chains, int width, int height, uint64_t* keys,
                         uint32_t* order);
void launchMltSplatAtomic(const MltSplatView& view, uint32_t pixels);
void launchMltSplatKeys(const MltSplatView& view, uint32_t* keys, uint32_t* values);
/// After radixSortPairs of the keys: per-pixel starts (binary search) and the gather.
void launchMltSplatGather(const MltSplatView& view, uint32_t* pixelStart, uint32_t pixels);

}  // namespace caustica
