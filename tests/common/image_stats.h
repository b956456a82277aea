// image_stats.h — statistics comparing caustica's renders with Mitsuba 3 references (mean and
// variance-of-the-mean EXRs from independent batches): per-pixel z-scores (median |z|), z² of
// 8x8-pixel block means, a z-test on the image mean, and a relMSE bound of a few times the
// relMSE the noise alone explains. Shared by tests/e2e/reference_test.cpp and
// tests/compat/compat_test.cpp (test helper, host only).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "caustica/film/image.h"
#include "e2e/render_helpers.h"

namespace caustica::test {

/// The "spp" entry of a reference's JSON sidecar.
inline double referenceSpp(const std::string& jsonPath) {
    std::ifstream f(jsonPath);
    std::string text((std::istreambuf_iterator<char>(f)), {});
    size_t at = text.rfind("\"spp\":");
    return at == std::string::npos ? 0 : std::atof(text.c_str() + at + 6);
}

/// Per-pixel z = (a - b) / sqrt(var_a + var_b) over all channels with noise.
struct ZScores {
    std::vector<double> pixel;  // one per channel value with noise
    double blockZ2Mean = 0;     // mean z² of 8x8-pixel block means
};

inline ZScores zScores(const Image& ours, const Image& oursVar, const Image& ref, const Image& refVar) {
    ZScores z;
    for (size_t j = 0; j < ref.rgb.size(); ++j) {
        const double var = double(oursVar.rgb[j]) + double(refVar.rgb[j]);
        if (var > 0) z.pixel.push_back((double(ours.rgb[j]) - ref.rgb[j]) / std::sqrt(var));
        else EXPECT_NEAR(ours.rgb[j], ref.rgb[j], 1e-5) << "noise-free value " << j;
    }
    // The box filter keeps pixels independent, so a block's variance is the sum of its pixels'.
    constexpr int kBlock = 8;
    int blocks = 0;
    for (int by = 0; by + kBlock <= ref.height; by += kBlock)
        for (int bx = 0; bx + kBlock <= ref.width; bx += kBlock)
            for (int c = 0; c < 3; ++c) {
                double d = 0, var = 0;
                for (int y = by; y < by + kBlock; ++y)
                    for (int x = bx; x < bx + kBlock; ++x) {
                        size_t j = (size_t(y) * ref.width + x) * 3 + c;
                        d += double(ours.rgb[j]) - ref.rgb[j];
                        var += double(oursVar.rgb[j]) + refVar.rgb[j];
                    }
                if (var <= 0) continue;
                z.blockZ2Mean += d * d / var;
                ++blocks;
            }
    z.blockZ2Mean /= std::max(1, blocks);
    return z;
}

inline double medianAbs(std::vector<double> v) {
    for (double& x : v) x = std::fabs(x);
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

/// The statistics of one comparison and the bounds they must meet.
struct ReferenceComparison {
    size_t noisyValues = 0, values = 0;
    double medianZ = 0, blockZ2Mean = 0, zMean = 0, relMse = 0, expectedRelMse = 0;
    double ourMean = 0, refMean = 0;

    bool enoughNoisy() const { return noisyValues > values / 2; }
    bool medianOk() const { return medianZ < 0.85; }
    bool blocksOk() const { return blockZ2Mean < 2.5; }
    bool meanOk() const { return std::fabs(zMean) < 4.0; }
    bool relMseOk() const { return relMse < 3 * expectedRelMse + 1e-6; }
    bool passed() const { return enoughNoisy() && medianOk() && blocksOk() && meanOk() && relMseOk(); }
    std::string describe() const {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "median |z| %.3f, block z² %.3f, image-mean z %.2f, relMSE %.3g (noise explains %.3g)",
                      medianZ, blockZ2Mean, zMean, relMse, expectedRelMse);
        return buf;
    }
};

/// Compares our ensemble (`runs` renders of `sppPerRun`) with a reference of `refSpp` samples.
/// Heavy tails (rare caustic paths) make a variance estimated from a few runs too small in most
/// pixels. Both renderers are path tracers with NEE and MIS, so their per-sample variances are
/// alike: our variance is the larger of our estimate and the reference's scaled to our sample
/// count (this modifies `ours.varianceOfMean`).
inline ReferenceComparison compareToReference(RenderEnsemble& ours, const Image& ref,
                                              const Image& refVar, double refSpp, int runs,
                                              int sppPerRun) {
    ReferenceComparison r;
    const double sppRatio = refSpp / double(runs * sppPerRun);
    for (size_t j = 0; j < ref.rgb.size(); ++j)
        ours.varianceOfMean.rgb[j] = float(std::max(double(ours.varianceOfMean.rgb[j]), refVar.rgb[j] * sppRatio));

    // Caustic paths make both estimators heavy-tailed, so the per-pixel test is the median |z|
    // (0.674 for unbiased normal noise, robust to fireflies; a bias of one sigma per pixel
    // raises it to about 1.0); block means are closer to normal and get a z² test.
    ZScores z = zScores(ours.mean, ours.varianceOfMean, ref, refVar);
    r.values = ref.rgb.size();
    r.noisyValues = z.pixel.size();
    if (!z.pixel.empty()) r.medianZ = medianAbs(z.pixel);
    r.blockZ2Mean = z.blockZ2Mean;

    double relMse = 0, expectedRelMse = 0, refMean = 0, refMeanVar = 0;
    for (size_t j = 0; j < ref.rgb.size(); ++j) {
        const double a = ours.mean.rgb[j], b = ref.rgb[j];
        relMse += (a - b) * (a - b) / (b * b + 0.01);
        expectedRelMse += (double(ours.varianceOfMean.rgb[j]) + refVar.rgb[j]) / (b * b + 0.01);
        refMean += b;
        refMeanVar += refVar.rgb[j];
    }
    const double P = double(ref.rgb.size());
    r.relMse = relMse / P;
    r.expectedRelMse = expectedRelMse / P;
    r.refMean = refMean / P;
    refMeanVar /= P * P;
    r.ourMean = meanOf(ours.runImageMeans);
    r.zMean = (r.ourMean - r.refMean) / std::sqrt(varianceOfMeanOf(ours.runImageMeans) + refMeanVar);
    return r;
}

/// The gtest expectations of a comparison, each with its own message.
inline void expectMatches(const ReferenceComparison& r) {
    ASSERT_TRUE(r.enoughNoisy()) << r.noisyValues << " of " << r.values << " values have noise";
    EXPECT_TRUE(r.medianOk()) << "per-pixel disagreement beyond the noise: " << r.describe();
    EXPECT_TRUE(r.blocksOk()) << "8x8 block means disagree beyond the noise: " << r.describe();
    EXPECT_TRUE(r.meanOk()) << "image mean " << r.ourMean << " vs reference " << r.refMean << ": "
                            << r.describe();
    EXPECT_TRUE(r.relMseOk()) << "relMSE " << r.relMse << " expected ~" << r.expectedRelMse;
}

}  // namespace caustica::test
