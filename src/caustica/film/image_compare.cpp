// image_compare.cpp — error metrics and false-colour error images.
#include "caustica/film/image_compare.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "caustica/film/colormap.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

void checkSameSize(const Image& test, const Image& reference) {
    if (!test.sameSize(reference))
        throw Error("cannot compare a " + std::to_string(test.width) + " x " +
                    std::to_string(test.height) + " image with a " +
                    std::to_string(reference.width) + " x " + std::to_string(reference.height) +
                    " reference");
}

/// relMse's term per pixel, averaged over the three channels.
std::vector<double> relativeErrorPerPixel(const Image& test, const Image& reference) {
    std::vector<double> err(test.pixelCount());
    for (size_t i = 0; i < err.size(); ++i) {
        double e = 0;
        for (int c = 0; c < 3; ++c) {
            const double a = test.rgb[3 * i + c], b = reference.rgb[3 * i + c], d = a - b;
            e += d * d / (b * b + kRelMseEpsilon);
        }
        err[i] = e / 3;
    }
    return err;
}

/// The fraction of the summed errors that the largest 1% of them (at least one) make up; 0 when
/// they are all 0, NaN when one is not finite.
double worstPercentShare(std::vector<double> err) {
    double total = 0;
    for (double e : err) {
        if (!std::isfinite(e)) return std::nan("");
        total += e;
    }
    if (!(total > 0)) return 0;
    const size_t k = std::max<size_t>(1, (err.size() + 99) / 100);
    std::nth_element(err.begin(), err.begin() + std::ptrdiff_t(k - 1), err.end(), std::greater<>());
    double worst = 0;
    for (size_t i = 0; i < k; ++i) worst += err[i];
    return worst / total;
}

}  // namespace

ErrorMetrics compareImages(const Image& test, const Image& reference) {
    checkSameSize(test, reference);
    ErrorMetrics m;
    m.pixels = test.pixelCount();
    if (m.pixels == 0) return m;
    // Sequential double sums: deterministic, and images are small enough.
    double se = 0, rel = 0, ae = 0, sumTest = 0, sumRef = 0;
    for (size_t i = 0; i < test.rgb.size(); ++i) {
        const double a = test.rgb[i], b = reference.rgb[i], d = a - b;
        se += d * d;
        rel += d * d / (b * b + kRelMseEpsilon);
        ae += std::fabs(d);
        sumTest += a;
        sumRef += b;
    }
    const double n = double(test.rgb.size());
    m.mse = se / n;
    m.rmse = std::sqrt(m.mse);
    m.relMse = rel / n;
    m.mae = ae / n;
    m.meanRatio = sumRef != 0 ? sumTest / sumRef : std::nan("");
    m.relMseWorstShare = worstPercentShare(relativeErrorPerPixel(test, reference));
    return m;
}

ErrorMetrics compareImages(const Image& test, const Image& reference, const Image& referenceVariance) {
    ErrorMetrics m = compareImages(test, reference);
    checkSameSize(referenceVariance, reference);
    double se = 0, rel = 0;
    for (size_t i = 0; i < test.rgb.size(); ++i) {
        const double b = reference.rgb[i], d = double(test.rgb[i]) - b, v = referenceVariance.rgb[i];
        se += d * d - v;
        rel += (d * d - v) / (b * b + kRelMseEpsilon);
    }
    const double n = double(std::max<size_t>(test.rgb.size(), 1));
    m.mseRefNoiseRemoved = se / n;
    m.relMseRefNoiseRemoved = rel / n;
    return m;
}

NonFiniteCount countNonFinite(const Image& image) {
    NonFiniteCount count;
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        size_t bad = 0;
        for (size_t c = 0; c < 3; ++c) bad += !std::isfinite(image.rgb[3 * i + c]);
        count.values += bad;
        count.pixels += bad > 0;
    }
    return count;
}

Image falseColourError(const Image& test, const Image& reference, double scale) {
    checkSameSize(test, reference);
    const size_t n = test.pixelCount();
    const std::vector<double> err = relativeErrorPerPixel(test, reference);
    if (!(scale > 0)) {
        // 99th percentile of the finite errors; their maximum if that is 0; else 1.
        std::vector<double> finite;
        finite.reserve(n);
        for (double e : err)
            if (std::isfinite(e)) finite.push_back(e);
        scale = 0;
        if (!finite.empty()) {
            const size_t k = std::min(finite.size() - 1, size_t(0.99 * double(finite.size())));
            std::nth_element(finite.begin(), finite.begin() + std::ptrdiff_t(k), finite.end());
            scale = finite[k];
            if (!(scale > 0)) scale = *std::max_element(finite.begin(), finite.end());
        }
        if (!(scale > 0)) scale = 1;
    }
    Image out(test.width, test.height);
    for (size_t i = 0; i < n; ++i) {
        const double t = std::isfinite(err[i]) ? std::min(1.0, err[i] / scale) : 1.0;
        const Spectrum s = viridis(Float(t));
        out.rgb[3 * i + 0] = s.r;
        out.rgb[3 * i + 1] = s.g;
        out.rgb[3 * i + 2] = s.b;
    }
    return out;
}

}  // namespace caustica
