// megakernel_pass.h — the pass driver that traces each camera sample to completion in one work
// item (one thread per pixel sample on a GPU), for any per-sample radiance estimator. Single
// source (launch.h): templates only, instantiated by the driver .cpp files per device.
#pragma once

#include <algorithm>
#include <cstdint>

#include "caustica/accel/device_scene.h"
#include "caustica/integrators/aov/aov_pass.h"
#include "caustica/integrators/first_hit_intersector.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/primitives.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/stereo_rig.h"
#include "caustica/util/error.h"
#include "caustica/util/rng.h"

namespace caustica {

/// The start of every camera sample: sample s of pixel `pixel` (row-major, `width` wide) gets the
/// random stream (pixel, sample index, seed), a jittered film position and a camera ray. On a
/// stereo rig (camera.eyeWidth > 0) the stream is keyed by the pixel within its eye and by
/// stereoEyeSeed(seed, eye), so each eye draws exactly what a mono render of that eye's camera
/// (eyeCamera) draws at that seed.
struct CameraSample {
    IndependentSampler sampler;
    Vec2f pos;
    Ray ray;
};

CA_HD_INLINE CameraSample cameraSample(const Camera& camera, size_t pixel, int width, uint64_t sampleIndex,
                                       uint64_t seed) {
    CameraSample c;
    const DivMod xy = divMod(pixel, uint64_t(width));
    const int x = int(xy.rem), y = int(xy.quot);
    if (camera.eyeWidth > 0) {
        const int eye = x >= camera.eyeWidth ? 1 : 0;
        const size_t eyePixel = size_t(y) * size_t(camera.eyeWidth) + size_t(x - eye * camera.eyeWidth);
        c.sampler = IndependentSampler(eyePixel, sampleIndex, stereoEyeSeed(seed, eye));
    } else {
        c.sampler = IndependentSampler(pixel, sampleIndex, seed);
    }
    const Vec2f jitter = c.sampler.get2D();
    c.pos = Vec2f(Float(x) + jitter.x, Float(y) + jitter.y);
    c.ray = sampleCameraRay(camera, c.pos, c.sampler);  // may draw a lens sample
    return c;
}

namespace megakernel_detail {

/// Where a pass writes AOVs of its camera rays (aov_kernel.h); values null: none.
struct AovOutput {
    AovLayout layout;
    Vec2f* positions = nullptr;
    float* values = nullptr;
};

/// One work item per pass slot: slot = pixel * k + s. WithAovs: the camera ray is traced first,
/// its hit gives the AOVs and answers the radiance estimate's query for it. Two kernels, so that
/// the one without AOVs keeps its registers (a GPU sizes them per kernel).
template <bool WithAovs, class Exec, class Intersector, class Radiance>
void tracePass(Exec exec, const char* name, const SceneView& view, const Intersector& accel,
               const Radiance& radiance, uint64_t seed, int firstSample, int width, int k, size_t slots,
               PixelSample* samples, uint32_t* rays, AovOutput aovs) {
    launch(exec, name, slots, [=] CA_HD(size_t slot) {
        const DivMod ps = divMod(slot, uint64_t(k));  // pixel, sample within the pass
        CameraSample c = cameraSample(view.camera, ps.quot, width, uint64_t(firstSample) + ps.rem, seed);
        uint32_t rayCount = 0;
        Spectrum L;
        if (WithAovs) {  // not `if constexpr`: nvcc's extended lambdas cannot first-capture there
            FirstHitIntersector<Intersector> first{accel};
            first.trace(c.ray);
            aovs.positions[slot] = c.pos;
            aovValues(view, c.ray, first.hit, aovs.layout, aovs.values + slot * size_t(aovs.layout.channels));
            L = radiance(view, first, c.sampler, c.ray, rayCount);
        } else {
            L = radiance(view, accel, c.sampler, c.ray, rayCount);
        }
        samples[slot] = PixelSample{c.pos, L};
        rays[slot] = rayCount;
    }, 16);
}

}  // namespace megakernel_detail

/// Radiance: a copyable functor with
///     template <class I, class S> CA_HD Spectrum operator()(const SceneView&, const I&, S& sampler,
///                                                            const Ray&, uint32_t& rays) const;
template <class Exec, class Radiance>
class MegakernelPass final : public PassDriver {
public:
    MegakernelPass(const Scene& scene, const Accel& accel, const Radiance& radiance, const char* name)
        : scene_(scene, accel, Exec::device()), radiance_(radiance), name_(name) {}

    uint64_t render(uint64_t seed, int firstSampleIndex, SamplePass& pass) override {
        const size_t slots = pass.samples.size();
        if (slots == 0) return 0;
        if (rays_.size() < slots) {
            rays_ = Buffer<uint32_t>(Exec::device(), slots);
            if constexpr (Exec::kind != DeviceKind::Cpu) samples_ = Buffer<PixelSample>(Exec::device(), slots);
        }
        // The CPU's kernels write the host pass directly; a GPU's write device memory, copied after.
        PixelSample* out = Exec::kind == DeviceKind::Cpu ? pass.samples.data() : samples_.data();
        megakernel_detail::AovOutput aovOut{aovLayout_};
        if (aovs_) {
            if (aovs_->slots() != slots || aovs_->channels != aovLayout_.channels)
                throw Error("internal: the AOV pass does not match the sample pass");
            aovTarget_.bind(*aovs_, aovOut.positions, aovOut.values);
        }
        scene_.visit(Exec{}, [&](const auto& intersector) {
            if (aovs_)
                megakernel_detail::tracePass<true>(Exec{}, name_, scene_.view(), intersector, radiance_, seed,
                                                   firstSampleIndex, pass.width, pass.samplesPerPixel, slots,
                                                   out, rays_.data(), aovOut);
            else
                megakernel_detail::tracePass<false>(Exec{}, name_, scene_.view(), intersector, radiance_, seed,
                                                    firstSampleIndex, pass.width, pass.samplesPerPixel, slots,
                                                    out, rays_.data(), aovOut);
        });
        const uint64_t rays = reduceSum(Exec::device(), Span<const uint32_t>(rays_.data(), slots));
        if constexpr (Exec::kind != DeviceKind::Cpu) samples_.copyToHost(pass.span());
        if (aovs_) aovTarget_.copyBack(*aovs_);
        return rays;
    }
    size_t sceneBytes() const override { return scene_.bytes(); }
    bool shareFirstHits(const AovLayout& layout, AovSamplePass* aovs) override {
        aovLayout_ = layout;
        aovs_ = aovs;
        return true;
    }

private:
    DeviceScene scene_;
    Radiance radiance_;
    const char* name_;
    Buffer<uint32_t> rays_;
    Buffer<PixelSample> samples_;  // a GPU's
    AovLayout aovLayout_;
    AovSamplePass* aovs_ = nullptr;  // the caller's, while it shares first hits
    AovPassTarget<Exec> aovTarget_;
};

}  // namespace caustica
