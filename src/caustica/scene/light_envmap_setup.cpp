// light_envmap_setup.cpp — the envmap's piecewise-constant 2-D distribution (light_envmap.h):
// patch weights = mean luminance of the patch's four texels × mean sinθ over its rows.
#include "caustica/scene/light_envmap_setup.h"

#include <cmath>
#include <vector>

#include "caustica/util/error.h"

namespace caustica {

namespace {

/// Appends the normalised running sums of `w` to `cdf` (uniform when they sum to zero: such a
/// row is never chosen by the marginal), the last entry exactly 1.
void appendCdf(std::vector<float>& cdf, const std::vector<double>& w) {
    double total = 0;
    for (double v : w) total += v;
    double sum = 0;
    for (size_t i = 0; i < w.size(); ++i) {
        sum += total > 0 ? w[i] : 1.0;
        cdf.push_back(float(sum / (total > 0 ? total : double(w.size()))));
    }
    cdf.back() = 1.0f;
}

}  // namespace

void setupEnvMapDistribution(Scene& scene, Light& light) {
    const uint32_t W = light.texWidth, H = light.texHeight;
    if (W < 2 || H < 3) throw Error("environment map must be at least 2x3 texels (as Mitsuba)");
    if (size_t(light.texOffset) + size_t(W) * H > scene.lightTexels.size())
        throw Error("environment map references texels out of range");
    const Spectrum* t = scene.lightTexels.data() + light.texOffset;
    const double dTheta = M_PI / double(H - 1);

    std::vector<double> rowWeight(H - 1), patch(size_t(W) * (H - 1));
    for (uint32_t j = 0; j + 1 < H; ++j) {
        // Mean of sinθ over the patch's θ range [j, j+1]·dθ.
        const double sinMean = (std::cos(j * dTheta) - std::cos((j + 1) * dTheta)) / dTheta;
        double sum = 0;
        for (uint32_t i = 0; i < W; ++i) {
            const uint32_t i1 = i + 1 == W ? 0 : i + 1;
            const double lum = double(t[j * W + i].luminance()) + t[j * W + i1].luminance() +
                               t[(j + 1) * W + i].luminance() + t[(j + 1) * W + i1].luminance();
            const double w = std::max(0.0, 0.25 * lum) * sinMean;
            patch[size_t(j) * W + i] = w;
            sum += w;
        }
        rowWeight[j] = sum;
    }
    double total = 0;
    for (double w : rowWeight) total += w;
    if (!(total > 0)) light.radiance = Spectrum(0.0f);  // a black map: nothing to sample
    light.cdfOffset = uint32_t(scene.lightCdf.size());
    appendCdf(scene.lightCdf, rowWeight);
    for (uint32_t j = 0; j + 1 < H; ++j)
        appendCdf(scene.lightCdf, std::vector<double>(patch.begin() + size_t(j) * W,
                                                      patch.begin() + size_t(j + 1) * W));
    light.cdfCount = uint32_t(scene.lightCdf.size()) - light.cdfOffset;
}

}  // namespace caustica
