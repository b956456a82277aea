// direct_check.h — host entry of cuda/direct_check.cu (device pointers only).
#pragma once

#include <cstdint>

#include "caustica/accel/intersector.h"
#include "caustica/film/film.h"
#include "caustica/integrators/direct/direct_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// One direct-illumination sample per pixel on the GPU, the CPU driver's layout and random
/// streams (renderDirectPass with one sample per pixel); all pointers are device pointers.
void launchDirectMegakernel(const SceneView& scene, const BvhIntersector& accel,
                            const DirectSettings& settings, uint64_t seed, int firstSample,
                            int width, int height, PixelSample* samples, uint32_t* rays);

}  // namespace caustica
