// pass_driver.h — the drivers of the integrators that render by passes of K samples per pixel
// (path, direct, whitted). Each is written once against launch.h and compiled per device: g++ builds the
// CPU's, nvcc (cuda/*_driver.cu) the GPU's, from the same .cpp. A pass's samples end in host
// memory, where the Film accumulates them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "caustica/accel/accel.h"
#include "caustica/film/aov_film.h"
#include "caustica/film/film.h"
#include "caustica/integrators/aov/aov_kernel.h"
#include "caustica/integrators/direct/direct_kernel.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/integrators/whitted/whitted_kernel.h"
#include "caustica/parallel/launch.h"
#include "caustica/scene/scene.h"

namespace caustica {

class PassDriver {
public:
    virtual ~PassDriver() = default;
    /// Renders pass.samplesPerPixel samples for every pixel of `pass` (the film's size), sample
    /// indices from `firstSampleIndex`, random streams keyed by (pixel, sample index, seed), into
    /// slot pixel * K + s of `pass`. Returns the rays traced (closest hit + shadow).
    virtual uint64_t render(uint64_t seed, int firstSampleIndex, SamplePass& pass) = 0;
    /// From the next render() on, also writes the AOVs of `layout` (aov_kernel.h) of every
    /// sample's camera ray into `aovs` (the caller sizes it like each pass; null stops it): the
    /// radiance estimate takes the first hit of that same query (first_hit_intersector.h), so the
    /// camera ray is traced once for both. False, and nothing written, for a driver that cannot
    /// (the wavefront path tracer).
    virtual bool shareFirstHits(const AovLayout& layout, AovSamplePass* aovs) { return false; }
    /// Device bytes of the scene copy the driver holds (0 on the CPU).
    virtual size_t sceneBytes() const = 0;
};

/// Default bound on the number of paths the wavefront keeps in flight: a pass with more samples
/// is traced in consecutive chunks, which bounds its memory to wavefrontBytesPerPath()
/// (gpu_memory.h) times this.
inline constexpr size_t kWavefrontMaxPaths = size_t(1) << 20;

/// The path tracer (megakernel or wavefront) on the device of `Exec`; the scene, the accel (a
/// Bvh one for a GPU) outlive the driver. Defined per device by path_pass.cpp.
template <class Exec>
std::unique_ptr<PassDriver> makePathPass(const Scene& scene, const Accel& accel, const PathSettings& settings,
                                         PathMode mode, size_t maxPathsInFlight = kWavefrontMaxPaths);
/// The direct-lighting integrator on the device of `Exec`. Defined per device by direct_pass.cpp.
template <class Exec>
std::unique_ptr<PassDriver> makeDirectPass(const Scene& scene, const Accel& accel, const DirectSettings& settings);
/// Whitted ray tracing on the device of `Exec`. Defined per device by whitted_pass.cpp.
template <class Exec>
std::unique_ptr<PassDriver> makeWhittedPass(const Scene& scene, const Accel& accel, const WhittedSettings& settings);

}  // namespace caustica
