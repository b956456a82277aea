// sample_pass.h — one entry point for the integrators that render by passes of samples per pixel
// (path, direct): the CLI and the tests call renderSamplePass and never name an integrator's
// driver themselves. (Metropolis renders by chains, not pixel samples: integrators/mlt.)
#pragma once

#include <cstdint>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// Whether `type` renders through renderSamplePass.
bool rendersBySamplePasses(IntegratorType type);

/// Renders `pass.samplesPerPixel` samples for every pixel with the integrator `desc` names, sample
/// indices starting at `firstSampleIndex`. `wavefront` selects the path tracer's CPU execution
/// mode (same image either way). Returns the number of rays traced.
uint64_t renderSamplePass(const Scene& scene, const Accel& accel, const IntegratorDesc& desc,
                          uint64_t seed, int firstSampleIndex, SamplePass& pass, bool wavefront = false);

}  // namespace caustica
