// kernel_check.h — host entry points of the CUDA translation units (device pointers only).
#pragma once

#include <cstdint>

#include "caustica/accel/intersector.h"
#include "caustica/film/film.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// One path-traced sample per pixel on the GPU (all pointers are device pointers).
void launchPathMegakernel(const SceneView& scene, const BvhIntersector& accel, const PathSettings& settings,
                          uint64_t seed, int firstSample, int width, int height, Vec2f* positions,
                          Spectrum* radiance, uint32_t* rays);
/// Filters one pass of samples into the film sums on the GPU (device pointers in `view`).
void launchFilmSplat(const FilmSplatView& view);

}  // namespace caustica
