// filter_test.cpp — reconstruction filters against Mitsuba 3's formulas.
#include <gtest/gtest.h>

#include <cmath>

#include "caustica/film/filter.h"

namespace caustica {
namespace {

// Midpoint rule over [-r, r] with many steps: the filters are piecewise smooth, so this is exact
// to ~1e-7 relative, far below the tolerance used.
double numericIntegral(const Filter& f) {
    const int n = 200000;
    const double r = f.radius, h = 2 * r / n;
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += f.eval(Float(-r + (i + 0.5) * h));
    return sum * h;
}

TEST(Filter, BoxIsHalfOpenUnitInterval) {
    const Filter f = Filter::box();
    EXPECT_EQ(f.radius, 0.5f);
    EXPECT_EQ(f.eval(0.0f), 1.0f);
    EXPECT_EQ(f.eval(-0.5f), 1.0f);  // Mitsuba: x >= -0.5 && x < 0.5
    EXPECT_EQ(f.eval(0.49999f), 1.0f);
    EXPECT_EQ(f.eval(0.5f), 0.0f);
    EXPECT_EQ(f.eval(-0.50001f), 0.0f);
    EXPECT_EQ(f.eval(3.0f), 0.0f);
    EXPECT_NEAR(numericIntegral(f), f.integral(), 1e-4);
}

TEST(Filter, TentShape) {
    const Filter f = Filter::tent();
    EXPECT_EQ(f.radius, 1.0f);
    EXPECT_EQ(f.eval(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(f.eval(0.25f), 0.75f);
    EXPECT_FLOAT_EQ(f.eval(-0.5f), 0.5f);
    EXPECT_EQ(f.eval(1.0f), 0.0f);
    EXPECT_EQ(f.eval(-1.5f), 0.0f);
    const Filter wide = Filter::tent(2.0f);
    EXPECT_FLOAT_EQ(wide.eval(1.0f), 0.5f);
    EXPECT_EQ(wide.eval(2.0f), 0.0f);
    EXPECT_NEAR(numericIntegral(f), 1.0, 1e-6);
    EXPECT_NEAR(numericIntegral(wide), 2.0, 1e-6);
    EXPECT_DOUBLE_EQ(wide.integral(), 2.0);
}

TEST(Filter, GaussianMatchesMitsubaFormula) {
    for (float stddev : {0.5f, 1.0f, 0.3f}) {
        const Filter f = Filter::gaussian(stddev);
        EXPECT_FLOAT_EQ(f.radius, 4 * stddev);
        const double s = stddev, r = 4 * s, bias = std::exp(-r * r / (2 * s * s));
        for (double x : {0.0, 0.1, -0.25, 0.5, 0.9, -1.3, 1.99}) {
            if (std::fabs(x) >= r) continue;
            const double expected = std::max(0.0, std::exp(-x * x / (2 * s * s)) - bias);
            EXPECT_NEAR(f.eval(Float(x)), expected, 1e-6) << "stddev " << s << " x " << x;
        }
        EXPECT_EQ(f.eval(f.radius), 0.0f);
        EXPECT_EQ(f.eval(-f.radius * 1.01f), 0.0f);
        EXPECT_EQ(f.eval(0.3f), f.eval(-0.3f));
        EXPECT_NEAR(numericIntegral(f), f.integral(), 1e-6 * f.integral());
        // sigma sqrt(2 pi) erf(2 sqrt 2) - 8 sigma exp(-8), by hand.
        const double analytic =
            s * std::sqrt(2 * M_PI) * std::erf(2 * std::sqrt(2.0)) - 8 * s * std::exp(-8.0);
        EXPECT_NEAR(f.integral(), analytic, 1e-6);
    }
}

TEST(Filter, TwoDimensionalWeightIsProduct) {
    for (const Filter& f : {Filter::box(), Filter::tent(), Filter::gaussian()}) {
        for (float dx : {-0.7f, -0.2f, 0.0f, 0.3f, 0.45f})
            for (float dy : {-0.4f, 0.1f, 0.6f}) EXPECT_EQ(f.eval(dx, dy), f.eval(dx) * f.eval(dy));
        EXPECT_EQ(f.eval(Vec2f(0.1f, -0.2f)), f.eval(0.1f, -0.2f));
    }
}

TEST(Filter, FromDescFollowsMitsubaRadii) {
    FilterDesc desc;
    desc.type = FilterType::Box;
    desc.radius = 3.0f;
    EXPECT_EQ(Filter::fromDesc(desc).radius, 0.5f);
    desc.type = FilterType::Tent;
    desc.radius = 1.5f;
    EXPECT_EQ(Filter::fromDesc(desc).radius, 1.5f);
    desc.type = FilterType::Gaussian;
    desc.stddev = 0.25f;
    EXPECT_EQ(Filter::fromDesc(desc).radius, 1.0f);
    desc.stddev = 0.0f;
    EXPECT_THROW(Filter::fromDesc(desc), Error);
    desc.type = FilterType::Tent;
    desc.radius = -1.0f;
    EXPECT_THROW(Filter::fromDesc(desc), Error);
}

}  // namespace
}  // namespace caustica
