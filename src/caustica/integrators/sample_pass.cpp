#include "caustica/integrators/sample_pass.h"

#include "caustica/integrators/direct/direct_integrator.h"
#include "caustica/integrators/path/path_integrator.h"
#include "caustica/integrators/path/wavefront.h"
#include "caustica/util/error.h"

namespace caustica {

bool rendersBySamplePasses(IntegratorType type) {
    switch (type) {
        case IntegratorType::Path:
        case IntegratorType::Direct: return true;
        default: return false;
    }
}

uint64_t renderSamplePass(const Scene& scene, const Accel& accel, const IntegratorDesc& desc,
                          uint64_t seed, int firstSampleIndex, SamplePass& pass, bool wavefront) {
    switch (desc.type) {
        case IntegratorType::Path: {
            const PathSettings settings = pathSettingsFrom(desc);
            if (wavefront) return renderPathPassWavefront(scene, accel, settings, seed, firstSampleIndex, pass);
            return renderPathPass(scene, accel, settings, seed, firstSampleIndex, pass);
        }
        case IntegratorType::Direct:  // one execution mode: `wavefront` is the path tracer's
            return renderDirectPass(scene, accel, directSettingsFrom(desc), seed, firstSampleIndex, pass);
        default: break;
    }
    throw Error(std::string("integrator ") + integratorTypeName(desc.type) + " does not render by pixel samples");
}

}  // namespace caustica
