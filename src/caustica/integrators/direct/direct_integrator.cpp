#include "caustica/integrators/direct/direct_integrator.h"

#include <atomic>
#include <string>

#include "caustica/parallel/device.h"
#include "caustica/scene/camera.h"
#include "caustica/util/error.h"
#include "caustica/util/rng.h"

namespace caustica {

DirectSettings directSettingsFrom(const IntegratorDesc& desc) {
    DirectSettings s;
    s.emitterSamples = desc.emitterSamples;
    s.bsdfSamples = desc.bsdfSamples;
    s.hideEmitters = desc.hideEmitters;
    if (s.emitterSamples < 0 || s.bsdfSamples < 0 || s.emitterSamples + s.bsdfSamples == 0)
        throw Error("direct integrator: needs at least one emitter or BSDF sample (got " +
                    std::to_string(s.emitterSamples) + " and " + std::to_string(s.bsdfSamples) +
                    ")");
    return s;
}

uint64_t renderDirectPass(const Scene& scene, const Accel& accel, const DirectSettings& settings,
                          uint64_t seed, int firstSampleIndex, SamplePass& pass) {
    const SceneView view = scene.view();
    const int width = pass.width, k = pass.samplesPerPixel;
    std::atomic<uint64_t> totalRays{0};
    accel.visit([&](const auto& intersector) {
        parallelFor(
            Device::cpu(), "direct.pass", size_t(width) * size_t(pass.height),
            [&](size_t pixel) {
                const int x = int(pixel % size_t(width)), y = int(pixel / size_t(width));
                uint32_t rays = 0;
                for (int s = 0; s < k; ++s) {
                    IndependentSampler sampler(pixel, uint64_t(firstSampleIndex + s), seed);
                    const Vec2f jitter = sampler.get2D();
                    const Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
                    const Ray ray = sampleCameraRay(view.camera, pos, sampler);
                    const Spectrum L =
                        directRadiance(view, intersector, sampler, ray, settings, rays);
                    pass.at(x, y, s) = PixelSample{pos, L};
                }
                totalRays.fetch_add(rays, std::memory_order_relaxed);
            },
            16);
    });
    return totalRays.load();
}

}  // namespace caustica
