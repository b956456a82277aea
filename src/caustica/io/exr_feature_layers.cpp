// exr_feature_layers.cpp — denoiser guides from AOV layers, by type.
#include "caustica/io/exr_feature_layers.h"

#include <cmath>

#include "caustica/io/exr_layers.h"

namespace caustica {

namespace {

/// Layer `type`'s channels as an RGB image: 3 channels map to R, G, B; 1 fills all three.
std::optional<Image> layerImage(const AovImage& aovs, AovType type) {
    const int first = aovs.firstChannelOf(type);
    if (first < 0) return std::nullopt;
    const int n = aovChannelCount(type);
    Image image(aovs.width, aovs.height);
    for (int y = 0; y < aovs.height; ++y)
        for (int x = 0; x < aovs.width; ++x)
            for (int c = 0; c < 3; ++c)
                image.pixel(x, y)[c] = aovs.at(x, y, size_t(first + (n == 1 ? 0 : c)));
    return image;
}

}  // namespace

DenoiseFeatures featuresFromAovs(const AovImage& aovs) {
    DenoiseFeatures features;
    if (aovs.empty()) return features;
    features.albedo = layerImage(aovs, AovType::Albedo);
    features.normal = layerImage(aovs, AovType::ShNormal);
    if (!features.normal) features.normal = layerImage(aovs, AovType::GeoNormal);
    features.depth = layerImage(aovs, AovType::Depth);
    features.variance = layerImage(aovs, AovType::Variance);
    // An undefined variance (NaN: batch means of fewer than 2 steps, docs/AOV.md) is no guide:
    // the NL-means filter then estimates its own.
    if (features.variance)
        for (float v : features.variance->rgb)
            if (!std::isfinite(v)) {
                features.variance.reset();
                break;
            }
    return features;
}

DenoiseFeatures readFeatureLayers(const std::string& path) {
    return featuresFromAovs(readExrLayers(path).aovs);
}

}  // namespace caustica
