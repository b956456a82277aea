// mlt_target.h — the relative target function of MLT: I(x) = luminance(F(x)) / B(pixel of x),
// B a smoothed estimate of each pixel's brightness from the bootstrap samples.
//
// Plain PSSMLT (target = luminance) spends effort in proportion to brightness, so dark pixels get
// few mutations and a high relative error. Dividing by B makes every pixel draw about the same
// number of mutations while the chains still concentrate, inside a pixel, on the paths that carry
// its light (caustics, small lights) — "arbitrary importance functions" for MLT (Hoberock and Hart
// 2010). Any positive B leaves the estimate unbiased (the splats divide by I); a poor B only costs
// efficiency, so B is blurred until each estimate rests on enough samples and floored at a
// fraction of its mean.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace caustica {

enum class MltTarget { Luminance, Relative };
MltTarget parseMltTarget(const std::string& name);  // "luminance" | "relative"

/// Bootstrap samples with at least this many per blurred pixel estimate.
inline constexpr double kMltTargetSamplesPerEstimate = 64;
/// B is at least this fraction of its image mean.
inline constexpr double kMltTargetFloor = 0.05;

/// Per-pixel weights 1 / B from `count` bootstrap samples (luminance and pixel index each) on a
/// width x height film. Every weight is finite and positive; a black bootstrap gives weights 1.
std::vector<float> mltRelativePixelWeights(const float* luminance, const uint32_t* pixel, uint64_t count,
                                           int width, int height);

}  // namespace caustica
