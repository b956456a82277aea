// pixel_pass.h — the CPU pass loop shared by the integrators that render by samples per pixel
// (path, direct): each pixel a work item of parallelFor, K samples each with the random stream
// keyed by (pixel, sample index, seed), so images do not depend on the number of threads.
#pragma once

#include <atomic>
#include <cstdint>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/parallel/device.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/scene.h"
#include "caustica/util/rng.h"

namespace caustica {

/// Renders `pass.samplesPerPixel` camera samples for every pixel of `pass`, sample indices
/// starting at `firstSampleIndex`, as the parallelFor launch `name`. Sample s of a pixel jitters
/// its position in the pixel, draws the camera ray and stores
/// `radiance(view, intersector, sampler, ray, rays)` (which adds the rays it traced to `rays`)
/// in the pass's slot pixel * K + s. Returns the number of rays traced.
template <class Radiance>
uint64_t renderPixelPass(const Scene& scene, const Accel& accel, const char* name, uint64_t seed,
                         int firstSampleIndex, SamplePass& pass, const Radiance& radiance) {
    const SceneView view = scene.view();
    const int width = pass.width, k = pass.samplesPerPixel;
    std::atomic<uint64_t> totalRays{0};
    accel.visit([&](const auto& intersector) {
        parallelFor(
            Device::cpu(), name, size_t(width) * size_t(pass.height),
            [&](size_t pixel) {
                const int x = int(pixel % size_t(width)), y = int(pixel / size_t(width));
                uint32_t rays = 0;
                for (int s = 0; s < k; ++s) {
                    IndependentSampler sampler(pixel, uint64_t(firstSampleIndex + s), seed);
                    const Vec2f jitter = sampler.get2D();
                    const Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
                    const Ray ray = sampleCameraRay(view.camera, pos, sampler);
                    const Spectrum L = radiance(view, intersector, sampler, ray, rays);
                    pass.at(x, y, s) = PixelSample{pos, L};
                }
                totalRays.fetch_add(rays, std::memory_order_relaxed);
            },
            16);
    });
    return totalRays.load();
}

}  // namespace caustica
