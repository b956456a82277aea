#include "caustica/integrators/path/path_integrator.h"

#include <atomic>

#include "caustica/parallel/device.h"
#include "caustica/scene/camera.h"
#include "caustica/util/rng.h"

namespace caustica {

PathSettings pathSettingsFrom(const IntegratorDesc& desc) {
    PathSettings s;
    s.maxDepth = desc.maxDepth;
    s.rrDepth = desc.rrDepth;
    s.hideEmitters = desc.hideEmitters;
    return s;
}

uint64_t renderPathPass(const Scene& scene, const Accel& accel, const PathSettings& settings,
                        uint64_t seed, int firstSampleIndex, SamplePass& pass) {
    const SceneView view = scene.view();
    const int width = pass.width, k = pass.samplesPerPixel;
    std::atomic<uint64_t> totalRays{0};
    accel.visit([&](const auto& intersector) {
        parallelFor(Device::cpu(), "path.pass", size_t(width) * size_t(pass.height), [&](size_t pixel) {
            const int x = int(pixel % size_t(width)), y = int(pixel / size_t(width));
            uint32_t rays = 0;
            for (int s = 0; s < k; ++s) {
                IndependentSampler sampler(pixel, uint64_t(firstSampleIndex + s), seed);
                Vec2f jitter = sampler.get2D();
                Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
                Ray ray = sampleCameraRay(view.camera, pos, sampler);
                Spectrum L = pathRadiance(view, intersector, sampler, ray, settings, rays);
                pass.at(x, y, s) = PixelSample{pos, L};
            }
            totalRays.fetch_add(rays, std::memory_order_relaxed);
        }, 16);
    });
    return totalRays.load();
}

}  // namespace caustica
