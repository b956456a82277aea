// image_compare.h — error metrics between a rendered image and a reference, and a false-colour
// visualisation of where they differ.
#pragma once

#include <cstddef>

#include "caustica/film/image.h"

namespace caustica {

/// Errors of a test image against a reference, averaged over all pixels and RGB channels:
///   mse    = mean (a - b)^2              rmse = sqrt(mse)
///   relMse = mean (a - b)^2 / (b^2 + 0.01)   (b: the reference; Rousselle et al. 2011)
///   mae    = mean |a - b|
/// `pixels` is the number of pixels compared. relMseWorstShare is the fraction of relMse that the
/// worst 1% of pixels carry (at least one pixel): about 0.01-0.05 for even noise, near 1 when a few
/// outliers (fireflies, a Metropolis chain's blotch) make up the error. meanRatio is the test
/// image's mean over all pixels and channels divided by the reference's (NaN for a black
/// reference): an error in overall brightness, which relMse hides among the noise, and a start-up
/// bias of Metropolis chains shows as a ratio away from 1.
/// With the reference's per-pixel variance (the variance of its mean, e.g. REF.var.exr), the
/// expected share of the reference's own noise is subtracted as well: E[(a - b)^2] = (a - r)^2 +
/// var(b) for an exact value r, so mseRefNoiseRemoved and relMseRefNoiseRemoved estimate the test
/// image's error against the exact image (they may be slightly negative when it is tiny).
struct ErrorMetrics {
    double mse = 0, rmse = 0, relMse = 0, mae = 0;
    double relMseWorstShare = 0;
    double meanRatio = 0;
    double mseRefNoiseRemoved = 0, relMseRefNoiseRemoved = 0;  // only with a reference variance
    size_t pixels = 0;
};

/// Offset in relMse's denominator, which keeps dark reference pixels from dominating.
inline constexpr double kRelMseEpsilon = 0.01;

/// Compares `test` against `reference`; throws caustica::Error when their sizes differ. Metrics
/// are NaN when either image holds NaN: a broken render never compares as close.
ErrorMetrics compareImages(const Image& test, const Image& reference);
/// The same, also filling the *RefNoiseRemoved metrics from the reference's variance image.
ErrorMetrics compareImages(const Image& test, const Image& reference, const Image& referenceVariance);

/// How much of an image is NaN or infinite: `values` channels in `pixels` pixels.
struct NonFiniteCount {
    size_t values = 0, pixels = 0;
};
NonFiniteCount countNonFinite(const Image& image);

/// Per-pixel relative squared error (the relMse term averaged over the 3 channels) mapped to
/// viridis, in linear RGB (ready for writeImage's sRGB PNG). `scale` is the error shown as the
/// top of the colormap; 0 (or negative) chooses the 99th percentile of the per-pixel errors (their
/// maximum if that is 0). Non-finite errors map to the top. Throws caustica::Error when the sizes
/// differ.
Image falseColourError(const Image& test, const Image& reference, double scale = 0);

}  // namespace caustica
