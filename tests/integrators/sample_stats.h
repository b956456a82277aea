// sample_stats.h — per-pixel statistics of a SamplePass's independent samples and z-tests
// between two estimators of the same image (test helper for the integrator tests).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "caustica/film/film.h"

namespace caustica::test {

/// Per pixel and channel, mean and variance of the mean over the pass's independent samples.
struct PixelStats {
    std::vector<double> mean, varOfMean;
    double imageMean = 0, imageVarOfMean = 0;
};

inline PixelStats statsOf(const SamplePass& pass) {
    PixelStats s;
    const int k = pass.samplesPerPixel;
    const size_t pixels = size_t(pass.width) * size_t(pass.height);
    for (size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) {
            double sum = 0, sum2 = 0;
            for (int j = 0; j < k; ++j) {
                const double v = pass.samples[p * size_t(k) + size_t(j)].L[c];
                sum += v;
                sum2 += v * v;
            }
            const double m = sum / k, var = std::max(0.0, (sum2 - k * m * m) / (k - 1));
            s.mean.push_back(m);
            s.varOfMean.push_back(var / k);
            s.imageMean += m;
            s.imageVarOfMean += var / k;
        }
    const double n = double(s.mean.size());
    s.imageMean /= n;
    s.imageVarOfMean /= n * n;
    return s;
}

struct Agreement {
    double imageZ = 0;          // z of the difference of the image means
    double fractionAbove4 = 0;  // fraction of pixel channels with |z| > 4
};

inline Agreement compare(const PixelStats& a, const PixelStats& b) {
    Agreement r;
    r.imageZ = (a.imageMean - b.imageMean) / std::sqrt(a.imageVarOfMean + b.imageVarOfMean);
    size_t above = 0, tested = 0;
    for (size_t i = 0; i < a.mean.size(); ++i) {
        const double var = a.varOfMean[i] + b.varOfMean[i];
        if (!(var > 0)) {
            above += a.mean[i] != b.mean[i];  // noiseless: must agree exactly
            ++tested;
            continue;
        }
        above += std::abs(a.mean[i] - b.mean[i]) / std::sqrt(var) > 4;
        ++tested;
    }
    r.fractionAbove4 = double(above) / double(tested);
    return r;
}

// Under agreement |z| > 4 has probability 6e-5 per pixel channel (normal tails; the sample
// variances of heavy-tailed pixels are underestimated, hence an allowance of 1 %), and the image
// mean's |z| stays below 4.
constexpr double kMaxImageZ = 4, kMaxFractionAbove4 = 0.01;

}  // namespace caustica::test
