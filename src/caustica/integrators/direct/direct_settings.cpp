#include "caustica/integrators/direct/direct_settings.h"

#include <climits>

namespace caustica {

DirectSettings readDirectSettings(IntegratorParams& p) {
    if (p.has("shading_samples") && (p.has("emitter_samples") || p.has("bsdf_samples")))
        p.fail("shading_samples", "cannot be combined with 'emitter_samples' or 'bsdf_samples'");
    auto count = [&](const char* name, int def) { return int(p.getInt(name, def, 0, INT_MAX, "must be >= 0")); };
    const int shading = count("shading_samples", 1);
    DirectSettings s;
    s.emitterSamples = count("emitter_samples", shading);
    s.bsdfSamples = count("bsdf_samples", shading);
    if (s.emitterSamples + s.bsdfSamples == 0)
        p.fail("", "needs at least one emitter or BSDF sample (emitter_samples + bsdf_samples > 0)");
    s.hideEmitters = p.getBool("hide_emitters", false);
    return s;
}

}  // namespace caustica
