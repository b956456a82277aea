// direct_integrator.h — host driver of the direct-illumination integrator (direct_kernel.h) on
// the CPU: one pass = K samples per pixel, each pixel a work item of parallelFor; random streams
// keyed by (pixel, sample index, seed) as the path tracer's, so images do not depend on threads
// (the pass loop both share: integrators/pixel_pass.h).
#pragma once

#include <cstdint>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/integrators/direct/direct_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

DirectSettings directSettingsFrom(const IntegratorDesc& desc);

/// Renders `pass.samplesPerPixel` samples for every pixel, with sample indices starting at
/// `firstSampleIndex`. Returns the number of rays traced. Deterministic for any thread count.
uint64_t renderDirectPass(const Scene& scene, const Accel& accel, const DirectSettings& settings,
                          uint64_t seed, int firstSampleIndex, SamplePass& pass);

}  // namespace caustica
