// mlt_bootstrap.h — what MLT's bootstrap samples decide, on the host (both drivers): the relative
// target's pixel weights, the samples b is estimated from, and the chains' starts.
//
// Under the relative target the samples that estimate the pixel brightness B must not also
// estimate b = E[I]: a sample that is bright for its pixel raises its own B and so damps its own
// I, and the mean of I over the same samples falls short of E[I] — by 5-10% on cornell-water with
// 64 samples per pixel, which left MLT's images that much too dark (docs/PERFORMANCE.md). So the
// even-numbered samples estimate B, the odd-numbered ones b and the starts.
#pragma once

#include <cstdint>
#include <vector>

#include "caustica/integrators/mlt/mlt_impl.h"

namespace caustica {

struct MltBootstrapPlan {
    std::vector<float> pixelWeight;  // relative target: 1 / B per pixel; empty for luminance
    double importanceSum = 0;        // sum of I over the samples that estimate b
    uint64_t samples = 0;            // their number
    std::vector<uint64_t> starts;    // the bootstrap sample each chain starts at
};

/// `importance` holds the luminance of each of the M bootstrap samples, `pixel` the pixel each
/// fell in (read under the relative target only; may be empty under the luminance target); on return `importance` holds I under the settings' target, 0 for samples that only
/// estimated B (so no chain starts there). Throws caustica::Error if no sample carries light.
MltBootstrapPlan planMltBootstrap(std::vector<float>& importance, const std::vector<uint32_t>& pixel,
                                  const MltSettings& settings, int width, int height, uint64_t seed,
                                  int eyeWidth = 0);

/// Starts the estimate of b from the plan (b0 = the plan's mean, fixed in the splat weights) and
/// records it in `stats` with the bootstrap size m.
void adoptMltBootstrap(const MltBootstrapPlan& plan, uint64_t m, MltNormalisation& b, MltStats& stats);

}  // namespace caustica
