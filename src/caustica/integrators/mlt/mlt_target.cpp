#include "caustica/integrators/mlt/mlt_target.h"

#include <algorithm>
#include <cmath>

#include "caustica/film/eye_seam.h"
#include "caustica/util/error.h"

namespace caustica {

MltTarget parseMltTarget(const std::string& name) {
    if (name == "luminance") return MltTarget::Luminance;
    if (name == "relative") return MltTarget::Relative;
    throw Error("unknown MLT target '" + name + "' (use luminance or relative)");
}

namespace {

/// Box blur of `v` (width x height) with radius r, separable, normalised at the borders (and at a
/// stereo film's seam: eye_seam.h).
std::vector<double> boxBlur(const std::vector<double>& v, int width, int height, int r, int eyeWidth) {
    std::vector<double> tmp(v.size()), out(v.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double s = 0;
            int lo, hi;
            eyeColumnRange(x, r, width, eyeWidth, lo, hi);
            for (int i = lo; i <= hi; ++i) s += v[size_t(y) * size_t(width) + size_t(i)];
            tmp[size_t(y) * size_t(width) + size_t(x)] = s / double(hi - lo + 1);
        }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double s = 0;
            const int lo = std::max(0, y - r), hi = std::min(height - 1, y + r);
            for (int i = lo; i <= hi; ++i) s += tmp[size_t(i) * size_t(width) + size_t(x)];
            out[size_t(y) * size_t(width) + size_t(x)] = s / double(hi - lo + 1);
        }
    return out;
}

}  // namespace

std::vector<float> mltRelativePixelWeights(const float* luminance, const uint32_t* pixel, uint64_t count,
                                           int width, int height, uint64_t stride, int eyeWidth) {
    const size_t pixels = size_t(width) * size_t(height);
    std::vector<double> sum(pixels, 0.0);
    for (uint64_t i = 0; i < count * stride; i += stride)
        if (pixel[i] < pixels) sum[pixel[i]] += double(luminance[i]);
    // Samples fall uniformly on the film, so the pixel mean is sum / (count / pixels).
    const double perPixel = double(count) / double(pixels);
    for (double& s : sum) s /= std::max(perPixel, 1e-30);
    // Widen the box until one estimate averages kMltTargetSamplesPerEstimate samples.
    int r = 0;
    while (r < std::max(width, height) && double((2 * r + 1) * (2 * r + 1)) * perPixel < kMltTargetSamplesPerEstimate)
        ++r;
    const std::vector<double> brightness = r > 0 ? boxBlur(sum, width, height, r, eyeWidth) : sum;
    double mean = 0;
    for (double b : brightness) mean += b;
    mean /= double(pixels);
    std::vector<float> weight(pixels, 1.0f);
    if (!(mean > 0) || !std::isfinite(mean)) return weight;
    const double floor = kMltTargetFloor * mean;
    for (size_t p = 0; p < pixels; ++p) weight[p] = float(mean / std::max(brightness[p], floor));
    return weight;
}

}  // namespace caustica
