// whitted_settings.h — the whitted integrator's command-line options. Its settings are the path
// tracer's (max_depth -1, rr_depth 5, hide_emitters false; whitted_kernel.h), read by
// readPathSettings.
#pragma once

#include <vector>

#include "caustica/integrators/integrator_params.h"

namespace caustica {

/// --whitted-max-depth, --whitted-rr-depth, --whitted-hide-emitters.
const std::vector<IntegratorOption>& whittedOptions();

}  // namespace caustica
