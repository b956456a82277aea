// wavefront.h — host driver of the path tracer in wavefront form: one kernel per stage of a
// bounce (generate, extend, shade, shadow), with the queue of live paths compacted after every
// bounce ("active thread compaction"). The stages call the same step functions as the megakernel
// (path_kernel.h), so both modes give bit-identical images; only this launcher differs per device.
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// Default bound on the number of paths in flight: a pass with more samples than this is traced
/// in consecutive chunks of this many paths, which bounds the memory to
/// wavefrontBytesPerPath() * kWavefrontMaxPaths.
inline constexpr size_t kWavefrontMaxPaths = size_t(1) << 20;

/// Bytes of per-path state the wavefront keeps in flight (path state, sampler, hit, pending
/// shadow ray, queue entries and flags).
size_t wavefrontBytesPerPath();

/// Renders `pass.samplesPerPixel()` samples for every pixel, with sample indices starting at
/// `firstSampleIndex`, at most `maxPathsInFlight` paths at a time. Returns the number of rays
/// traced. The image is bit-identical to renderPathPass's for the same seed, for any thread count
/// and any `maxPathsInFlight`.
uint64_t renderPathPassWavefront(const Scene& scene, const Accel& accel,
                                 const PathSettings& settings, uint64_t seed, int firstSampleIndex,
                                 SamplePass& pass, size_t maxPathsInFlight = kWavefrontMaxPaths);

}  // namespace caustica
