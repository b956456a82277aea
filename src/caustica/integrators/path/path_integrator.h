// path_integrator.h — host driver of the path tracer on the CPU: one pass = K samples per pixel,
// each pixel a work item of parallelFor; random streams keyed by (pixel, sample index, seed)
// (the pass loop shared with the direct integrator: integrators/pixel_pass.h).
#pragma once

#include <cstdint>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

PathSettings pathSettingsFrom(const IntegratorDesc& desc);

/// Renders `pass.samplesPerPixel` samples for every pixel, with sample indices starting at
/// `firstSampleIndex`. Returns the number of rays traced. Deterministic for any thread count.
uint64_t renderPathPass(const Scene& scene, const Accel& accel, const PathSettings& settings,
                        uint64_t seed, int firstSampleIndex, SamplePass& pass);

}  // namespace caustica
