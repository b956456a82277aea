// denoise_features.h — the guide images a denoiser may use beside the noisy colour.
#pragma once

#include <optional>

#include "caustica/film/image.h"

namespace caustica {

/// Optional guides, each the colour's size. Depth and variance may be grey (R = G = B); depth
/// uses its first channel. `variance` is the per-pixel, per-channel variance of the colour's
/// mean (what the film's variance AOV holds); without it the NL-means filter estimates one.
struct DenoiseFeatures {
    std::optional<Image> albedo;
    std::optional<Image> normal;
    std::optional<Image> depth;
    std::optional<Image> variance;
};

}  // namespace caustica
