// Tests of the warps in sampling.h: samples lie in their domains, pdfs integrate to 1, and the
// sample distributions match the pdfs (χ²); discrete CDF sampling and the power heuristic.
#include <gtest/gtest.h>

#include <vector>

#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

constexpr int kN = 400000;

Vec2f uniform2D(int i, uint64_t seed) {
    IndependentSampler rng(uint64_t(i), 0, seed);
    return rng.get2D();
}

/// χ² test of a direction warp and its pdf; also checks that the pdf integrates to `mass`.
void checkDirections(const test::SphereGrid& grid, Vec3f (*warp)(Vec2f, Float), Float param,
                     const std::function<double(Vec3f)>& pdf, uint64_t seed, double mass = 1) {
    int outside = 0;
    auto sample = [&](int i, Vec3f& w) {
        w = warp(uniform2D(i, seed), param);
        if (std::fabs(length(w) - 1) > 1e-5f) ++outside;
        return true;
    };
    const test::Chi2Result r = test::chi2Directions(grid, kN, sample, pdf);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(outside, 0);
    const std::vector<double> e = grid.expected(pdf, 1.0, 8);
    EXPECT_NEAR(1 - e.back(), mass, 1e-4);
}

TEST(Sampling, CosineHemisphere) {
    test::SphereGrid grid;
    grid.frame = Frame(Vec3f(0, 0, 1));
    int below = 0;
    for (int i = 0; i < 1000; ++i) below += sampleCosineHemisphere(uniform2D(i, 1)).z < 0;
    EXPECT_EQ(below, 0);
    checkDirections(
        grid, [](Vec2f u, Float) { return sampleCosineHemisphere(u); }, 0,
        [](Vec3f w) { return double(cosineHemispherePdf(w)); }, 2);
}

TEST(Sampling, UniformSphere) {
    test::SphereGrid grid;
    grid.frame = Frame(normalize(Vec3f(1, 2, 3)));
    checkDirections(
        grid, [](Vec2f u, Float) { return sampleUniformSphere(u); }, 0,
        [](Vec3f) { return double(uniformSpherePdf()); }, 3);
}

TEST(Sampling, UniformCone) {
    for (Float cosMax : {0.95f, 0.3f, -0.6f}) {
        test::SphereGrid grid;
        grid.frame = Frame(Vec3f(0, 0, 1));
        grid.thetaMax = std::acos(double(cosMax));
        grid.nTheta = 32;
        checkDirections(grid, sampleUniformCone, cosMax,
                        [&](Vec3f) { return double(uniformConePdf(cosMax)); }, 4);
    }
}

TEST(Sampling, TinyConeStaysPrecise) {
    // A cone of half-angle 1e-4 rad: 1 - cosθmax = 5e-9 is below float resolution near 1, so it
    // is passed directly; directions must stay inside and spread over the whole cone.
    const double thetaMax = 1e-4;
    const Float omc = Float(1 - std::cos(thetaMax));
    double maxTheta = 0;
    for (int i = 0; i < 10000; ++i) {
        const Vec3f w = sampleUniformConeOmc(uniform2D(i, 5), omc);
        const double theta = std::atan2(std::hypot(double(w.x), double(w.y)), double(w.z));
        maxTheta = std::max(maxTheta, theta);
    }
    EXPECT_LE(maxTheta, thetaMax * (1 + 1e-4));
    EXPECT_GE(maxTheta, thetaMax * 0.99);
    EXPECT_NEAR(uniformConePdfOmc(omc), 1 / (2 * M_PI * omc), 1e-3 / omc);
}

TEST(Sampling, ConcentricDisk) {
    constexpr int kR = 16, kPhi = 32;  // equal-area bins in (r², φ)
    std::vector<double> obs(kR * kPhi, 0.0), expected(kR * kPhi, double(kN) / (kR * kPhi));
    int outside = 0;
    for (int i = 0; i < kN; ++i) {
        const Vec2f d = sampleConcentricDisk(uniform2D(i, 6));
        const double r2 = double(d.x) * d.x + double(d.y) * d.y;
        if (r2 > 1 + 1e-6) ++outside;
        double phi = std::atan2(double(d.y), double(d.x));
        if (phi < 0) phi += 2 * M_PI;
        const int a = std::min(int(r2 * kR), kR - 1);
        const int b = std::min(int(phi / (2 * M_PI) * kPhi), kPhi - 1);
        obs[a * kPhi + b] += 1;
    }
    EXPECT_EQ(outside, 0);
    const test::Chi2Result r = test::chi2Test(obs, expected);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_FLOAT_EQ(concentricDiskPdf(), kInvPi);
}

TEST(Sampling, UniformTriangle) {
    // n² congruent sub-triangles of the reference triangle, each with probability 1 / n².
    constexpr int n = 16;
    std::vector<double> obs(n * n, 0.0), expected(n * n, double(kN) / (n * n));
    int outside = 0;
    for (int i = 0; i < kN; ++i) {
        const Vec2f b = sampleUniformTriangle(uniform2D(i, 7));
        if (b.x < 0 || b.y < 0 || b.x + b.y > 1 + 1e-6f) {
            ++outside;
            continue;
        }
        const double x = b.x * n, y = b.y * n;
        const int cx = std::min(int(x), n - 1), cy = std::min(int(y), n - 1 - cx);
        const bool upper = (x - cx) + (y - cy) >= 1 && cx + cy < n - 1;
        // Row cx holds 2 (n - cx) - 1 cells: lower ones at 2 cy, upper ones at 2 cy + 1.
        int index = 0;
        for (int k = 0; k < cx; ++k) index += 2 * (n - k) - 1;
        obs[index + 2 * cy + (upper ? 1 : 0)] += 1;
    }
    EXPECT_EQ(outside, 0);
    const test::Chi2Result r = test::chi2Test(obs, expected);
    EXPECT_TRUE(r.passed()) << r.describe();
}

TEST(Sampling, DiscreteCdf) {
    const std::vector<float> probs = {0.0f, 0.1f, 0.0f, 0.3f, 0.6f, 0.0f};
    std::vector<float> cdf;
    float sum = 0;
    for (float p : probs) cdf.push_back(sum += p);
    cdf.back() = 1;
    const Span<const float> span(cdf);
    std::vector<double> obs(probs.size(), 0.0), expected;
    for (float p : probs) expected.push_back(double(p) * kN);
    for (int i = 0; i < kN; ++i) {
        IndependentSampler rng(uint64_t(i), 0, 8);
        Float pmf;
        const uint32_t k = sampleDiscreteCdf(span, rng.get1D(), &pmf);
        ASSERT_LT(k, probs.size());
        ASSERT_GT(pmf, 0.0f) << "zero-probability entry " << k << " chosen";
        ASSERT_NEAR(pmf, probs[k], 1e-6f);
        ASSERT_NEAR(discreteCdfPmf(span, k), probs[k], 1e-6f);
        obs[k] += 1;
    }
    const test::Chi2Result r = test::chi2Test(obs, expected);
    EXPECT_TRUE(r.passed()) << r.describe();
    // Ends of [0, 1) and exact boundaries (u = cdf[i] belongs to the next interval).
    EXPECT_EQ(sampleDiscreteCdf(span, 0.0f, nullptr), 1u);
    EXPECT_EQ(sampleDiscreteCdf(span, kOneMinusEpsilon, nullptr), 4u);
    EXPECT_EQ(sampleDiscreteCdf(span, 0.1f, nullptr), 3u);
    Float pmf = -1;
    EXPECT_EQ(sampleDiscreteCdf(Span<const float>(), 0.5f, &pmf), 0u);
    EXPECT_EQ(pmf, 0.0f);
}

TEST(Sampling, PowerHeuristic) {
    EXPECT_FLOAT_EQ(powerHeuristic(1, 1), 0.5f);
    EXPECT_FLOAT_EQ(powerHeuristic(2, 1), 0.8f);
    EXPECT_FLOAT_EQ(powerHeuristic(1, 2), 0.2f);
    EXPECT_EQ(powerHeuristic(kInfinity * 2, 1), 1.0f);  // +inf: a delta strategy
    EXPECT_EQ(powerHeuristic(1, kInfinity * 2), 0.0f);
    EXPECT_EQ(powerHeuristic(kInfinity * 2, kInfinity * 2), 0.5f);
    EXPECT_EQ(powerHeuristic(0, 0), 0.0f);
    EXPECT_EQ(powerHeuristic(0, 1), 0.0f);
    EXPECT_EQ(powerHeuristic(1, 0), 1.0f);
    EXPECT_FLOAT_EQ(powerHeuristic(1e30f, 1e30f), 0.5f);  // no overflow to NaN
    EXPECT_FLOAT_EQ(powerHeuristic(1e-30f, 1e-30f), 0.5f);
    EXPECT_FLOAT_EQ(powerHeuristic(1e30f, 1e-30f), 1.0f);
    for (Float a : {0.1f, 3.0f, 1e5f})
        for (Float b : {0.2f, 7.0f, 1e-3f})
            EXPECT_NEAR(powerHeuristic(a, b) + powerHeuristic(b, a), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace caustica
