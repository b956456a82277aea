// denoise_test.cpp — the feature-guided NL-means denoiser (film/denoise_nlm*.h) and the run-time
// loaded Open Image Denoise (film/oidn_denoiser.h).
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>

#include "caustica/film/denoise_nlm_pass.h"
#include "caustica/film/oidn_denoiser.h"
#include "caustica/parallel/launch.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

constexpr int kW = 40, kH = 32;

Image constantImage(float r, float g, float b, int w = kW, int h = kH) {
    Image image(w, h);
    image.fill({r, g, b});
    return image;
}

/// Gaussian noise of standard deviation `sigma` on every channel (Box-Muller on mt19937 bits, so
/// the same on every standard library).
Image addNoise(const Image& clean, float sigma, uint32_t seed) {
    std::mt19937 rng(seed);
    auto uniform = [&] { return (float(rng() >> 8) + 0.5f) * (1.0f / 16777216.0f); };
    Image out = clean;
    for (float& v : out.rgb) {
        const float u1 = uniform(), u2 = uniform();
        v += sigma * std::sqrt(-2.0f * std::log(u1)) * std::cos(6.2831853f * u2);
    }
    return out;
}

/// Mean and variance of channel `ch` over the pixels with x in [x0, x1).
std::pair<double, double> stats(const Image& image, int ch, int x0 = 0, int x1 = kW) {
    double sum = 0, sum2 = 0;
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = x0; x < x1; ++x) {
            const double v = image.pixel(x, y)[ch];
            sum += v, sum2 += v * v, ++n;
        }
    const double mean = sum / n;
    return {mean, sum2 / n - mean * mean};
}

/// A vertical step at x = kW / 2 in colour and in every guide.
DenoiseFeatures stepFeatures() {
    DenoiseFeatures f;
    f.albedo = Image(kW, kH);
    f.normal = Image(kW, kH);
    f.depth = Image(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const bool right = x >= kW / 2;
            f.albedo->set(x, y, right ? Spectrum{0.8f, 0.8f, 0.8f} : Spectrum{0.6f, 0.1f, 0.1f});
            f.normal->set(x, y, right ? Spectrum{0, 0, 1} : Spectrum{1, 0, 0});
            f.depth->set(x, y, right ? Spectrum{3, 3, 3} : Spectrum{2, 2, 2});
        }
    return f;
}

Image stepColor() {
    Image c(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) c.set(x, y, x >= kW / 2 ? Spectrum{1.5f, 1.4f, 1.3f} : Spectrum{0.2f, 0.1f, 0.05f});
    return c;
}

Image nlm(const Image& color, const DenoiseFeatures& features = {}, const NlmParams& params = {}) {
    return denoiseNlm(CpuExec{}, color, features, params);
}

TEST(DenoiseNlm, ConstantImageComesBackBitExact) {
    const Image c = constantImage(0.25f, 1.5f, 3.0e-3f);
    // Accumulated as differences from the centre pixel: exact, with or without guides/variance.
    EXPECT_EQ(nlm(c).rgb, c.rgb);
    EXPECT_EQ(nlm(c, stepFeatures()).rgb, c.rgb);
    DenoiseFeatures withVariance;
    withVariance.variance = constantImage(0.01f, 0.01f, 0.01f);
    EXPECT_EQ(nlm(c, withVariance).rgb, c.rgb);
}

TEST(DenoiseNlm, NonFinitePixelsAreFilledFromTheirNeighbours) {
    Image c = constantImage(0.5f, 0.5f, 0.5f);
    c.pixel(3, 4)[0] = std::numeric_limits<float>::quiet_NaN();
    c.pixel(10, 10)[1] = std::numeric_limits<float>::infinity();
    c.pixel(0, 0)[2] = -std::numeric_limits<float>::infinity();
    DenoiseFeatures f = stepFeatures();
    f.albedo->pixel(5, 5)[0] = std::numeric_limits<float>::quiet_NaN();
    f.variance = constantImage(0.01f, 0.01f, 0.01f);
    f.variance->pixel(7, 7)[0] = std::numeric_limits<float>::quiet_NaN();
    for (const Image& out : {nlm(c), nlm(c, f), nlm(addNoise(c, 0.1f, 3), f)}) EXPECT_TRUE(out.allFinite());
    const Image out = nlm(c);
    for (const auto& [x, y] : {std::pair{3, 4}, std::pair{10, 10}, std::pair{0, 0}})
        for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(out.pixel(x, y)[ch], 0.5f) << x << "," << y;
}

TEST(DenoiseNlm, AllNonFiniteGivesBlackNotNaN) {
    Image c = constantImage(std::nanf(""), 1, 1, 4, 4);
    const Image out = nlm(c);
    EXPECT_TRUE(out.allFinite());
    for (float v : out.rgb) EXPECT_EQ(v, 0.0f);
}

TEST(DenoiseNlm, DeterministicAndIndependentOfThreadCount) {
    const Image noisy = addNoise(stepColor(), 0.2f, 7);
    const DenoiseFeatures f = stepFeatures();
    const Image a = nlm(noisy, f);
    EXPECT_EQ(nlm(noisy, f).rgb, a.rgb);
    Image one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = nlm(noisy, f);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = nlm(noisy, f);
    }
    EXPECT_EQ(one.rgb, a.rgb);
    EXPECT_EQ(two.rgb, a.rgb);
}

TEST(DenoiseNlm, StepInTheGuidesIsKept) {
    // Noise-free step, guides with the same step: every pixel keeps its side's value.
    const Image c = stepColor();
    const Image out = nlm(c, stepFeatures());
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(out.pixel(x, y)[ch], c.pixel(x, y)[ch], 1e-4f) << x << "," << y;
    // Noisy: each side's mean stays its own (no bleeding across the edge), also next to it.
    const Image noisy = addNoise(c, 0.1f, 11);
    const Image d = nlm(noisy, stepFeatures());
    for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(stats(d, ch, kW / 2 - 2, kW / 2).first, c.pixel(0, 0)[ch], 0.03);
        EXPECT_NEAR(stats(d, ch, kW / 2, kW / 2 + 2).first, c.pixel(kW - 1, 0)[ch], 0.03);
    }
}

TEST(DenoiseNlm, StepInTheColourAloneIsKeptByTheColourWeight) {
    // A caustic's edge on a flat floor: no guide sees it, the variance-aware colour weight must.
    const Image c = stepColor();
    DenoiseFeatures flat;
    flat.albedo = constantImage(0.5f, 0.5f, 0.5f);
    flat.variance = constantImage(1e-4f, 1e-4f, 1e-4f);
    const Image out = nlm(c, flat);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(out.pixel(x, y)[ch], c.pixel(x, y)[ch], 1e-3f) << x << "," << y;
}

TEST(DenoiseNlm, NoiseOnAConstantRegionIsReduced) {
    const float sigma = 0.1f;
    const Image noisy = addNoise(constantImage(0.5f, 0.5f, 0.5f), sigma, 5);
    DenoiseFeatures given;
    given.variance = constantImage(sigma * sigma, sigma * sigma, sigma * sigma);
    for (const DenoiseFeatures& f : {DenoiseFeatures{}, given}) {
        const Image out = nlm(noisy, f);
        for (int ch = 0; ch < 3; ++ch) {
            const auto [meanIn, varIn] = stats(noisy, ch);
            const auto [meanOut, varOut] = stats(out, ch);
            EXPECT_GT(varIn / varOut, 20.0) << "channel " << ch << (f.variance ? " (variance given)" : "");
            EXPECT_NEAR(meanOut, 0.5, 0.01);
        }
    }
}

TEST(DenoiseNlm, RefusesGuidesOfAnotherSizeAndBadParameters) {
    const Image c = constantImage(1, 1, 1);
    DenoiseFeatures f;
    f.normal = constantImage(0, 0, 1, kW + 1, kH);
    EXPECT_THROW(nlm(c, f), Error);
    NlmParams p;
    p.kColor = 0;
    EXPECT_THROW(nlm(c, {}, p), Error);
    p = NlmParams{};
    p.radius = -1;
    EXPECT_THROW(nlm(c, {}, p), Error);
}

TEST(Oidn, AbsentLibraryPathIsRefusedClearly) {
    try {
        OidnOptions o;
        o.library = "/nonexistent/libOpenImageDenoise.so.2";
        denoiseOidn(constantImage(1, 1, 1), {}, o);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/libOpenImageDenoise.so.2"), std::string::npos) << e.what();
    }
}

TEST(Oidn, NotALibraryIsRefused) {
    OidnOptions o;
    o.library = std::string(CAUSTICA_SOURCE_DIR) + "/README.md";
    EXPECT_THROW(denoiseOidn(constantImage(1, 1, 1), {}, o), Error);
}

TEST(Oidn, DenoisesWhenTheLibraryIsFound) {
    const std::string lib = findOidnLibrary();
    if (lib.empty()) GTEST_SKIP() << kOidnNotFound << " (set CAUSTICA_OIDN_LIBRARY to run this test)";
    const float sigma = 0.1f;
    const Image noisy = addNoise(constantImage(0.5f, 0.5f, 0.5f, 64, 64), sigma, 9);
    DenoiseFeatures f;
    f.albedo = constantImage(0.7f, 0.7f, 0.7f, 64, 64);
    f.normal = constantImage(0, 0, 1, 64, 64);
    const Image out = denoiseOidn(noisy, f, OidnOptions{});
    ASSERT_TRUE(out.allFinite());
    const auto [meanOut, varOut] = stats(out, 0, 0, 64);
    EXPECT_GT(sigma * sigma / varOut, 10.0);
    EXPECT_NEAR(meanOut, 0.5, 0.05);
    DenoiseFeatures normalOnly;
    normalOnly.normal = f.normal;
    EXPECT_THROW(denoiseOidn(noisy, normalOnly, OidnOptions{}), Error);
}

}  // namespace
}  // namespace caustica
