// mlt_settings.h — Metropolis light transport's settings from the scene's <integrator type="mlt">
// (or Mitsuba 0.6's "pssmlt") and the command line's --mlt-* options, which set the same
// parameters:
//
// | parameter         | option            | meaning (default)                                      |
// |-------------------|-------------------|--------------------------------------------------------|
// | chains            | --mlt-chains      | chains in lock step (CPU 1024; GPU: mltDefaultChains)  |
// | luminance_samples | --mlt-bootstrap   | bootstrap samples M (64 per pixel, <= 2^24)            |
// | p_large           | --mlt-large-step  | large-step probability (0.1)                           |
// | proposals         | --mlt-proposals   | k split-transition proposals per step (1)              |
// | target            | --mlt-target      | relative or luminance (relative)                       |
// | s1, s2            | --mlt-s1, -s2     | small-step sizes (1/1024, 1/64)                        |
// | state             | --mlt-state       | compact (24/16-bit) or float chain state (compact)     |
// | splat             | --splat           | atomic or sort splats (atomic)                         |
// | sort_every        | --mlt-sort-every  | Morton-sort the chains every N iterations (0 = never)  |
// | start             | --mlt-start       | bootstrap or uniform chain starts (bootstrap)          |
//
// plus the path tracer's max_depth, rr_depth, hide_emitters (path_settings.h).
#pragma once

#include <vector>

#include "caustica/integrators/integrator_params.h"
#include "caustica/integrators/mlt/mlt_integrator.h"

namespace caustica {

/// `defaultChains`: the chain count when none is given (it depends on the device and the image).
MltSettings readMltSettings(IntegratorParams& params, uint32_t defaultChains);
/// The command-line options of the table above.
const std::vector<IntegratorOption>& mltOptions();

}  // namespace caustica
