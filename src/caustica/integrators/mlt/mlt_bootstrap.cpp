#include "caustica/integrators/mlt/mlt_bootstrap.h"

#include <string>

#include "caustica/integrators/mlt/mlt_target.h"
#include "caustica/util/error.h"

namespace caustica {

MltBootstrapPlan planMltBootstrap(std::vector<float>& importance, const std::vector<uint32_t>& pixel,
                                  const MltSettings& settings, int width, int height, uint64_t seed,
                                  int eyeWidth) {
    const uint64_t m = importance.size();
    MltBootstrapPlan plan;
    if (settings.target == MltTarget::Relative && m >= 2) {
        plan.pixelWeight = mltRelativePixelWeights(importance.data(), pixel.data(), (m + 1) / 2, width, height, 2, eyeWidth);
        for (uint64_t i = 0; i < m; ++i) importance[i] = i % 2 == 0 ? 0.0f : importance[i] * plan.pixelWeight[pixel[i]];
        plan.samples = m / 2;
    } else {
        if (settings.target == MltTarget::Relative) plan.pixelWeight.assign(size_t(width) * size_t(height), 1.0f);
        plan.samples = m;
    }
    for (float I : importance) plan.importanceSum += double(I);
    if (!(plan.importanceSum > 0))
        throw Error("MLT: none of the " + std::to_string(plan.samples) +
                    " bootstrap paths that estimate b carries light: the image is black (check the emitters) "
                    "or the bootstrap is too small (--mlt-bootstrap)");
    plan.starts = mltChainStarts(importance.data(), m, settings.chains, settings.start, seed);
    return plan;
}

void adoptMltBootstrap(const MltBootstrapPlan& plan, uint64_t m, MltNormalisation& b, MltStats& stats) {
    b = MltNormalisation{};
    b.add(plan.importanceSum, double(plan.samples));
    b.b0 = b.b();
    stats.bootstrapSamples = m;
    stats.b = b.b();
}

}  // namespace caustica
