// path_settings.h — the path tracer's settings from the scene's <integrator> (and the command
// line): Mitsuba's max_depth (-1 = unbounded), rr_depth (5) and hide_emitters (false).
#pragma once

#include "caustica/integrators/integrator_params.h"
#include "caustica/integrators/path/path_kernel.h"

namespace caustica {

PathSettings readPathSettings(IntegratorParams& params);

}  // namespace caustica
