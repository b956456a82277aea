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
#include "caustica/parallel/buffer.h"
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

/// Where a kernel of `Exec`'s device writes an AovSamplePass: on the CPU the pass itself, on a GPU
/// device buffers (kept across passes) that copyBack() copies into the pass.
template <class Exec>
class AovPassTarget {
public:
    /// Pointers the kernel writes positions (pass.slots()) and values (slots x channels) to.
    void bind(AovSamplePass& pass, Vec2f*& positions, float*& values) {
        positions = pass.positions.data();
        values = pass.values.data();
        if constexpr (Exec::kind != DeviceKind::Cpu) {
            if (positions_.size() != pass.slots() || values_.size() != pass.values.size()) {
                positions_ = Buffer<Vec2f>(Exec::device(), pass.slots());
                values_ = Buffer<float>(Exec::device(), pass.values.size());
            }
            positions = positions_.data();
            values = values_.data();
        }
    }
    void copyBack(AovSamplePass& pass) const {
        if constexpr (Exec::kind != DeviceKind::Cpu) {
            positions_.copyToHost(Span<Vec2f>(pass.positions.data(), pass.slots()));
            values_.copyToHost(Span<float>(pass.values.data(), pass.values.size()));
        }
    }

private:
    Buffer<Vec2f> positions_;  // a GPU's
    Buffer<float> values_;
};

/// The AOV pass on the device of `Exec`; scene and accel (a Bvh one for a GPU) outlive it.
/// Defined per device by aov_pass.cpp.
template <class Exec>
std::unique_ptr<AovPassDriver> makeAovPass(const Scene& scene, const Accel& accel,
                                           const AovLayout& layout);

}  // namespace caustica
