#include "caustica/integrators/direct/direct_integrator.h"

#include <string>

#include "caustica/integrators/pixel_pass.h"
#include "caustica/util/error.h"

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
    return renderPixelPass(scene, accel, "direct.pass", seed, firstSampleIndex, pass,
                           [&](const SceneView& view, const auto& intersector,
                               IndependentSampler& sampler, const Ray& ray, uint32_t& rays) {
                               return directRadiance(view, intersector, sampler, ray, settings,
                                                     rays);
                           });
}

}  // namespace caustica
