// mlt_target.h — the relative target function of MLT: I(x) = luminance(F(x)) / B(pixel of x),
// B a smoothed estimate of each pixel's brightness from the bootstrap samples.
//
// Plain PSSMLT (target = luminance) spends effort in proportion to brightness, so bright regions
// (a visible light, its reflections) draw most mutations. Dividing by B damps them: inside a pixel
// the chains still follow the paths that carry its light (caustics, small lights) — "arbitrary
// importance functions" for MLT (Hoberock and Hart 2010). Any positive B leaves the estimate
// unbiased (the splats divide by I) as long as b is estimated from other samples than B
// (mlt_bootstrap.h); a poor B only costs efficiency. B is blurred until each
// estimate rests on enough samples and is never less than the image mean: pixels darker than
// average keep the luminance target's weight. A lower floor (5% of the mean was the first
// default) sends the chains after pixels whose bootstrap samples happened to be dark — rare
// caustics the chains then cannot find in time — which on cornell-water left the upper part of
// the image 30-40% too bright and the caustic-lit floor 40-60% too dark after 512 mutations per
// pixel (docs/PERFORMANCE.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace caustica {

enum class MltTarget { Luminance, Relative };
MltTarget parseMltTarget(const std::string& name);  // "luminance" | "relative"

/// Bootstrap samples with at least this many per blurred pixel estimate.
inline constexpr double kMltTargetSamplesPerEstimate = 64;
/// B is at least this fraction of its image mean (1: weights never exceed 1).
inline constexpr double kMltTargetFloor = 1.0;

/// Per-pixel weights 1 / B from `count` bootstrap samples (luminance and pixel index each, the
/// i-th at index i x stride) on a width x height film. Every weight is finite and positive; a
/// black bootstrap gives weights 1. On a stereo film (eyeWidth > 0) the blur stays in each eye.
std::vector<float> mltRelativePixelWeights(const float* luminance, const uint32_t* pixel, uint64_t count,
                                           int width, int height, uint64_t stride = 1, int eyeWidth = 0);

}  // namespace caustica
