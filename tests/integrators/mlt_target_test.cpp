// The relative MLT target's pixel weights (mlt_target.h): inverse brightness where the bootstrap
// sees enough samples, blurred where it does not, floored at the mean, and harmless on a black bootstrap.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/integrators/mlt/mlt_target.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

struct Samples {
    std::vector<float> luminance;
    std::vector<uint32_t> pixel;
    void add(uint32_t p, float l, int n) {
        for (int i = 0; i < n; ++i) {
            pixel.push_back(p);
            luminance.push_back(l);
        }
    }
};

TEST(MltTarget, BrightPixelsAreDampedByTheirBrightness) {
    // 3 x 1 film, 64 samples per pixel: no blur; brightness 1, 2 and 6, mean 3: the bright pixel
    // is damped by mean / B, the others keep weight 1.
    Samples s;
    s.add(0, 1.0f, 64);
    s.add(1, 2.0f, 64);
    s.add(2, 6.0f, 64);
    const std::vector<float> w = mltRelativePixelWeights(s.luminance.data(), s.pixel.data(), s.luminance.size(), 3, 1);
    ASSERT_EQ(w.size(), 3u);
    EXPECT_NEAR(w[0], 1.0f, 1e-5f);
    EXPECT_NEAR(w[1], 1.0f, 1e-5f);
    EXPECT_NEAR(w[2], 0.5f, 1e-5f);
}

TEST(MltTarget, DarkPixelsKeepTheLuminanceWeight) {
    Samples s;
    s.add(0, 0.0f, 64);
    s.add(1, 2.0f, 64);
    const std::vector<float> w = mltRelativePixelWeights(s.luminance.data(), s.pixel.data(), s.luminance.size(), 2, 1);
    EXPECT_NEAR(w[0], 1.0f, 1e-5f);  // mean 1: a black pixel's brightness is floored at the mean
    EXPECT_NEAR(w[1], 0.5f, 1e-5f);
    for (float x : w) EXPECT_TRUE(std::isfinite(x) && x > 0);
}

TEST(MltTarget, FewSamplesAreBlurredOverNeighbours) {
    // 9 x 1 film, 8 samples per pixel: the box widens to 64 samples per estimate (radius 1 in 2D
    // covers 9 pixels = 72 samples), so a single bright pixel spreads to its neighbours.
    Samples s;
    for (uint32_t p = 0; p < 9; ++p) s.add(p, p == 4 ? 9.0f : 0.0f, 8);
    const std::vector<float> w = mltRelativePixelWeights(s.luminance.data(), s.pixel.data(), s.luminance.size(), 9, 1);
    EXPECT_NEAR(w[3], w[4], 1e-5f);
    EXPECT_NEAR(w[5], w[4], 1e-5f);
    EXPECT_NEAR(w[4], 1.0f / 3.0f, 1e-5f);  // blurred brightness 3, mean 1
    EXPECT_NEAR(w[0], 1.0f, 1e-5f);         // far from the light: floored at the mean
}

TEST(MltTarget, ABlackBootstrapGivesUnitWeights) {
    Samples s;
    s.add(0, 0.0f, 10);
    const std::vector<float> w = mltRelativePixelWeights(s.luminance.data(), s.pixel.data(), s.luminance.size(), 3, 2);
    for (float x : w) EXPECT_EQ(x, 1.0f);
}

TEST(MltBootstrap, DefaultSizeIs64PerPixelCappedAndAtLeast4PerChain) {
    EXPECT_EQ(mltDefaultBootstrapSamples(1024, 64 * 64), 64u * 64 * 64);
    EXPECT_EQ(mltDefaultBootstrapSamples(1024, 4096 * 4096), uint64_t(1) << 24);
    EXPECT_EQ(mltDefaultBootstrapSamples(1u << 20, 16 * 16), uint64_t(4) << 20);
}

TEST(MltChains, DefaultIsFixedOnTheCpuAndHalfAChainPerPixelOnAGpu) {
    EXPECT_EQ(mltDefaultChains(false, 64 * 64), kMltDefaultChains);
    EXPECT_EQ(mltDefaultChains(false, 4096 * 4096), kMltDefaultChains);
    EXPECT_EQ(mltDefaultChains(true, 640 * 480), 640u * 480 / 2);
    EXPECT_EQ(mltDefaultChains(true, 1024 * 1024), 1u << 19);  // the founding paper's count
    EXPECT_EQ(mltDefaultChains(true, 4096 * 4096), 1u << 19);
    EXPECT_EQ(mltDefaultChains(true, 64 * 64), 4096u);
}

TEST(MltTarget, ParsesItsNames) {
    EXPECT_EQ(parseMltTarget("luminance"), MltTarget::Luminance);
    EXPECT_EQ(parseMltTarget("relative"), MltTarget::Relative);
    EXPECT_THROW(parseMltTarget("bright"), Error);
}

}  // namespace
}  // namespace caustica
