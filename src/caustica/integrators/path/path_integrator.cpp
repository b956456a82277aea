#include "caustica/integrators/path/path_integrator.h"

#include "caustica/integrators/pixel_pass.h"

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
    return renderPixelPass(scene, accel, "path.pass", seed, firstSampleIndex, pass,
                           [&](const SceneView& view, const auto& intersector,
                               IndependentSampler& sampler, const Ray& ray, uint32_t& rays) {
                               return pathRadiance(view, intersector, sampler, ray, settings, rays);
                           });
}

}  // namespace caustica
