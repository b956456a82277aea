// aov_pass.h — the AOV pass: for every pixel sample, the same camera sample as the integrators
// (megakernel_pass.h cameraSample: stream (pixel, sample index, seed), jittered film position,
// camera ray), one closest-hit ray and the geometric AOVs of its hit (aov_kernel.h), into an
// AovSamplePass. Written once against launch.h: g++ compiles aov_pass.cpp for the CPU, nvcc
// (cuda/aov_driver.cu) for the GPU.
#pragma once

#include <cstdint>
#include <memory>

#include "caustica/accel/accel.h"
#include "caustica/film/aov_film.h"
#include "caustica/integrators/aov/aov_kernel.h"
#include "caustica/parallel/launch.h"
#include "caustica/scene/scene.h"

namespace caustica {

class AovPassDriver {
public:
    virtual ~AovPassDriver() = default;
    /// Fills every slot (pixel * K + s) of `pass` with sample index firstSampleIndex + s: its film
    /// position and layout.channels values. Returns the rays traced.
    virtual uint64_t render(uint64_t seed, uint64_t firstSampleIndex, AovSamplePass& pass) = 0;
};

/// The AOV pass on the device of `Exec`; scene and accel (a Bvh one for a GPU) outlive it.
/// Defined per device by aov_pass.cpp.
template <class Exec>
std::unique_ptr<AovPassDriver> makeAovPass(const Scene& scene, const Accel& accel,
                                           const AovLayout& layout);

}  // namespace caustica
