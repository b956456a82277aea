#include "caustica/render/integrator_registry.h"

#include "caustica/integrators/mlt/mlt_settings.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/integrators/whitted/whitted_settings.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {
std::string runsOnGpu(IntegratorParams&) { return {}; }
const std::vector<IntegratorOption> kNoOptions;
}  // namespace

const std::vector<IntegratorEntry>& integratorRegistry() {
    static const std::vector<IntegratorEntry> entries = {
        {"path", "unidirectional path tracing, next-event estimation + MIS", kNoOptions, runsOnGpu, describePath,
         makePathSession},
        {"direct", "direct illumination (emitter and BSDF sampling, MIS)", kNoOptions, runsOnGpu, describeDirect,
         makeDirectSession},
        {"whitted", "Whitted ray tracing: mirror and glass recursion, direct light from every emitter", whittedOptions(),
         runsOnGpu, describePath, makeWhittedSession},
        {"mlt", "many-chain primary-sample-space Metropolis light transport", mltOptions(), mltGpuRefusal,
         describeMlt, makeMltSession},
        {"sppm", "stochastic progressive photon mapping (Hachisuka & Jensen 2009)", sppmOptions(), runsOnGpu,
         describeSppm, makeSppmSession},
        {"ppm", "progressive photon mapping (Hachisuka et al. 2008): fixed hitpoints, photon passes", ppmOptions(),
         runsOnGpu, describePpm, makePpmSession},
    };
    return entries;
}

IntegratorParams integratorParams(const IntegratorSpec& spec, const std::string& integrator,
                                  const std::vector<IntegratorParam>& commandLine) {
    IntegratorSpec named = spec;
    named.type = integrator;
    return IntegratorParams(named, commandLine);
}

std::string integratorNames() {
    std::string names;
    for (const IntegratorEntry& e : integratorRegistry()) names += (names.empty() ? "" : ", ") + std::string(e.name);
    return names;
}

const IntegratorEntry& findIntegrator(const std::string& name) {
    for (const IntegratorEntry& e : integratorRegistry())
        if (name == e.name) return e;
    throw Error("unknown integrator '" + name + "' (available: " + integratorNames() + ")");
}

}  // namespace caustica
