// What MLT's bootstrap decides (mlt_bootstrap.h): under the relative target, b must be estimated
// from samples that did not also set the pixel weights, or it comes out low (a bright sample damps
// itself). Checked on synthetic heavy-tailed samples whose exact b for any weights is known.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "caustica/integrators/mlt/mlt_bootstrap.h"
#include "caustica/integrators/mlt/mlt_target.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

// 8 x 1 film, 64 samples per pixel; each sample's luminance is 40 with probability 2%, else 0.5
// (a firefly-ridden pixel: mean 1.29, the same in every pixel).
constexpr int kWidth = 8, kHeight = 1;
constexpr uint64_t kSamples = 64 * kWidth;
constexpr double kBright = 40, kDim = 0.5, kBrightProbability = 0.02;
constexpr double kMeanLuminance = kBrightProbability * kBright + (1 - kBrightProbability) * kDim;

struct Bootstrap {
    std::vector<float> luminance;
    std::vector<uint32_t> pixel;
};

Bootstrap drawBootstrap(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    std::uniform_int_distribution<uint32_t> px(0, kWidth * kHeight - 1);
    Bootstrap s;
    for (uint64_t i = 0; i < kSamples; ++i) {
        s.pixel.push_back(px(rng));
        s.luminance.push_back(float(u(rng) < kBrightProbability ? kBright : kDim));
    }
    return s;
}

/// The exact b = E[luminance x weight(pixel)] for pixel weights w (pixels equally likely).
double exactB(const std::vector<float>& w) {
    double sum = 0;
    for (float x : w) sum += double(x);
    return kMeanLuminance * sum / double(w.size());
}

/// Relative error of b's estimate over many independent bootstraps: its mean and standard error.
template <class Estimate>
std::pair<double, double> relativeBias(Estimate estimate) {
    std::mt19937_64 rng(7);
    constexpr int kTrials = 4000;
    double sum = 0, sum2 = 0;
    for (int t = 0; t < kTrials; ++t) {
        Bootstrap s = drawBootstrap(rng);
        const double e = estimate(s);
        sum += e;
        sum2 += e * e;
    }
    const double mean = sum / kTrials, var = (sum2 / kTrials - mean * mean) / (kTrials - 1);
    return {mean, std::sqrt(var)};
}

MltSettings relativeSettings() {
    MltSettings s;
    s.chains = 16;
    s.target = MltTarget::Relative;
    return s;
}

TEST(MltBootstrap, BIsUnbiasedUnderTheRelativeTarget) {
    const auto [bias, error] = relativeBias([](Bootstrap& s) {
        const MltBootstrapPlan plan = planMltBootstrap(s.luminance, s.pixel, relativeSettings(), kWidth, kHeight, 1);
        return plan.importanceSum / double(plan.samples) / exactB(plan.pixelWeight) - 1;
    });
    std::printf("relative bias of b: %+.4f +- %.4f\n", bias, error);
    EXPECT_LT(std::fabs(bias), 4 * error + 1e-3);
}

TEST(MltBootstrap, TheSameSamplesForWeightsAndBWouldBeCaught) {
    // The estimate the drivers made before: weights and b from all samples. The test above must
    // be able to see its bias.
    const auto [bias, error] = relativeBias([](Bootstrap& s) {
        const std::vector<float> w =
            mltRelativePixelWeights(s.luminance.data(), s.pixel.data(), kSamples, kWidth, kHeight);
        double sum = 0;
        for (uint64_t i = 0; i < kSamples; ++i) sum += double(s.luminance[i]) * w[s.pixel[i]];
        return sum / double(kSamples) / exactB(w) - 1;
    });
    std::printf("relative bias of the same-sample b: %+.4f +- %.4f\n", bias, error);
    EXPECT_GT(std::fabs(bias), 4 * error + 1e-3);
}

TEST(MltBootstrap, ChainsStartOnlyAtSamplesThatEstimateB) {
    std::mt19937_64 rng(3);
    Bootstrap s = drawBootstrap(rng);
    const MltBootstrapPlan plan = planMltBootstrap(s.luminance, s.pixel, relativeSettings(), kWidth, kHeight, 1);
    EXPECT_EQ(plan.samples, kSamples / 2);
    ASSERT_EQ(plan.starts.size(), 16u);
    for (uint64_t start : plan.starts) {
        EXPECT_EQ(start % 2, 1u) << "a chain starts at a sample that set the pixel weights";
        EXPECT_GT(s.luminance[start], 0.0f);
    }
    for (uint64_t i = 0; i < kSamples; i += 2) EXPECT_EQ(s.luminance[i], 0.0f);
}

TEST(MltBootstrap, TheLuminanceTargetUsesEverySample) {
    std::mt19937_64 rng(4);
    Bootstrap s = drawBootstrap(rng);
    const std::vector<float> before = s.luminance;
    MltSettings settings = relativeSettings();
    settings.target = MltTarget::Luminance;
    const MltBootstrapPlan plan = planMltBootstrap(s.luminance, s.pixel, settings, kWidth, kHeight, 1);
    EXPECT_TRUE(plan.pixelWeight.empty());
    EXPECT_EQ(plan.samples, kSamples);
    EXPECT_EQ(s.luminance, before);
    double sum = 0;
    for (float l : before) sum += double(l);
    EXPECT_DOUBLE_EQ(plan.importanceSum, sum);
}

TEST(MltBootstrap, AdoptingAPlanFixesB0AndStartsTheEstimate) {
    MltBootstrapPlan plan;
    plan.importanceSum = 6;
    plan.samples = 4;
    MltNormalisation b;
    MltStats stats;
    adoptMltBootstrap(plan, 8, b, stats);
    EXPECT_DOUBLE_EQ(b.b0, 1.5);
    EXPECT_DOUBLE_EQ(b.b(), 1.5);
    EXPECT_DOUBLE_EQ(b.chainScale(), 1.0);
    EXPECT_EQ(stats.bootstrapSamples, 8u);
    b.add(10, 4);  // large steps brighter than the bootstrap: the chain layer is scaled up
    EXPECT_DOUBLE_EQ(b.chainScale(), 2.0 / 1.5);
}

TEST(MltBootstrap, ABlackBootstrapIsAClearError) {
    Bootstrap s;
    s.luminance.assign(64, 0.0f);
    s.pixel.assign(64, 0);
    try {
        planMltBootstrap(s.luminance, s.pixel, relativeSettings(), kWidth, kHeight, 1);
        ADD_FAILURE() << "a black bootstrap was accepted";
    } catch (const Error& e) {  // both causes named: a black scene, or too few samples
        const std::string what = e.what();
        EXPECT_NE(what.find("none of the 32 bootstrap paths"), std::string::npos) << what;
        EXPECT_NE(what.find("--mlt-bootstrap"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace caustica
