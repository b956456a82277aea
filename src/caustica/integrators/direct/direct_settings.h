// direct_settings.h — the direct integrator's settings as Mitsuba 3's direct.cpp reads them:
// shading_samples (1) sets both emitter_samples and bsdf_samples and may not be combined with
// them; at least one sample in all; hide_emitters (false).
#pragma once

#include "caustica/integrators/direct/direct_kernel.h"
#include "caustica/integrators/integrator_params.h"

namespace caustica {

DirectSettings readDirectSettings(IntegratorParams& params);

}  // namespace caustica
