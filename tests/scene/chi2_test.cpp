// Self-tests of the χ² helper: the incomplete gamma function against tabulated values, the
// pooling of small cells, and the quadrature of SphereGrid.
#include <gtest/gtest.h>

#include <numeric>

#include "scene/chi2.h"

namespace caustica {
namespace {

TEST(Chi2Helper, PValuesMatchTables) {
    // Critical values of the χ² distribution at upper-tail probability 0.05 and 0.01.
    EXPECT_NEAR(test::chi2PValue(3.841459, 1), 0.05, 1e-6);
    EXPECT_NEAR(test::chi2PValue(6.634897, 1), 0.01, 1e-6);
    EXPECT_NEAR(test::chi2PValue(18.307038, 10), 0.05, 1e-6);
    EXPECT_NEAR(test::chi2PValue(124.342113, 100), 0.05, 1e-6);
    EXPECT_NEAR(test::chi2PValue(135.806723, 100), 0.01, 1e-6);
    // Two degrees of freedom: Q = exp(-x / 2) exactly.
    for (double x : {0.5, 3.0, 40.0}) EXPECT_NEAR(test::chi2PValue(x, 2), std::exp(-x / 2), 1e-12);
    // Large dof: the median is close to k (1 - 2 / (9k))³ (Wilson–Hilferty).
    const double k = 4000, median = k * std::pow(1 - 2 / (9 * k), 3);
    EXPECT_NEAR(test::chi2PValue(median, int(k)), 0.5, 1e-3);
    EXPECT_EQ(test::chi2PValue(0, 5), 1.0);
    EXPECT_LT(test::chi2PValue(1e4, 100), 1e-100);
}

TEST(Chi2Helper, NormalQuantile) {
    EXPECT_NEAR(test::normalUpperQuantile(0.05), 1.644854, 1e-5);
    EXPECT_NEAR(test::normalUpperQuantile(0.0001), 3.719016, 1e-5);
}

TEST(Chi2Helper, PoolsSmallCellsAndRejectsImpossibleSamples) {
    // Exact agreement: χ² = 0.
    test::Chi2Result r = test::chi2Test({10, 20, 30, 1, 2}, {10, 20, 30, 1, 2});
    EXPECT_EQ(r.chi2, 0.0);
    // The two small cells pool into one of expectation 3 < 5, which joins the smallest regular
    // cell: 3 cells remain.
    EXPECT_EQ(r.cells, 3);
    EXPECT_EQ(test::chi2Test({10, 20, 30, 3, 3}, {10, 20, 30, 3, 3}).cells, 4);
    r = test::chi2Test({0, 100}, {0, 100});
    EXPECT_TRUE(r.passed());
    r = test::chi2Test({1, 99}, {0, 100});  // a sample where the pdf is zero
    EXPECT_FALSE(r.passed());
    EXPECT_FALSE(r.error.empty());
}

TEST(Chi2Helper, GridQuadratureIsExactForSmoothPdfs) {
    test::SphereGrid grid;
    grid.frame = Frame(normalize(Vec3f(1, 1, 1)));
    // Uniform: every bin's expectation is its solid angle; the total is 1.
    auto binned = [](const std::vector<double>& v) {  // all but the "no sample" bin
        return std::accumulate(v.begin(), v.end() - 1, 0.0);
    };
    const std::vector<double> e = grid.expected([](Vec3f) { return kInv4Pi; }, 1.0);
    EXPECT_NEAR(binned(e), 1.0, 1e-6);  // directions and pdfs are floats
    // Cosine lobe around the frame's axis, zero below: the horizon is a bin edge.
    const Vec3f n = grid.frame.n;
    const std::vector<double> c =
        grid.expected([&](Vec3f w) { return std::max(0.0, double(dot(w, n))) / M_PI; }, 1.0);
    EXPECT_NEAR(binned(c), 1.0, 1e-6);
}

}  // namespace
}  // namespace caustica
