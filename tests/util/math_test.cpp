// Scalar helpers of util/math.h that approximate libm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "caustica/util/math.h"

namespace caustica {
namespace {

TEST(Math, Exp2ApproxMatchesLibm) {
    // Over the whole range MLT's small-step sizes use (and beyond, down to the clamp).
    double worst = 0;
    for (int i = 0; i <= 1000000; ++i) {
        const float x = 0.5f - 125.5f * float(i) / 1e6f;
        worst = std::max(worst, std::fabs(double(exp2Approx(x)) / std::exp2(double(x)) - 1));
    }
    EXPECT_LT(worst, 5e-7);
    EXPECT_FLOAT_EQ(exp2Approx(-1000.0f), std::exp2(-125.0f));  // clamped, never denormal or zero
}

/// Distance in units in the last place between two finite floats of the same sign (or zero).
int64_t ulpDistance(float a, float b) {
    auto key = [](float f) {
        int32_t i;
        std::memcpy(&i, &f, 4);
        return i < 0 ? int64_t(INT32_MIN) - i : int64_t(i);  // monotonic in f
    };
    return std::llabs(key(a) - key(b));
}

TEST(Math, SinCosQuarterPiWithinTwoUlp) {
    int64_t worstSin = 0, worstCos = 0;
    const int n = 2000000;
    for (int i = 0; i <= n; ++i) {
        float a = float(-M_PI / 4 + (M_PI / 2) * double(i) / n);
        a = std::clamp(a, -float(M_PI / 4), float(M_PI / 4));
        float s, c;
        sinCosQuarterPi(a, s, c);
        worstSin = std::max(worstSin, ulpDistance(s, float(std::sin(double(a)))));
        worstCos = std::max(worstCos, ulpDistance(c, float(std::cos(double(a)))));
    }
    EXPECT_LE(worstSin, 2);
    EXPECT_LE(worstCos, 2);
    float s, c;
    sinCosQuarterPi(0.0f, s, c);
    EXPECT_EQ(s, 0.0f);
    EXPECT_EQ(c, 1.0f);
    sinCosQuarterPi(-0.5f, s, c);  // odd and even
    float s2, c2;
    sinCosQuarterPi(0.5f, s2, c2);
    EXPECT_EQ(s, -s2);
    EXPECT_EQ(c, c2);
}

TEST(Math, SinCosTwoPiMatchesLibm) {
    // Every quarter turn, the turns' boundaries (ties), negative and beyond one turn.
    double worst = 0;
    const int n = 1000000;
    for (int i = -n; i <= 2 * n; ++i) {
        const float u = float(i) / n;
        float s, c;
        sinCosTwoPi(u, s, c);
        const double phi = 2 * M_PI * double(u);
        worst = std::max({worst, std::fabs(s - std::sin(phi)), std::fabs(c - std::cos(phi))});
    }
    EXPECT_LT(worst, 3e-7);
    for (float u : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f, 0.125f, 0.375f, 0.625f, 0.875f, -0.25f}) {
        float s, c;
        sinCosTwoPi(u, s, c);
        EXPECT_NEAR(s, std::sin(2 * M_PI * u), 2e-7) << u;
        EXPECT_NEAR(c, std::cos(2 * M_PI * u), 2e-7) << u;
    }
}

}  // namespace
}  // namespace caustica

namespace caustica {
namespace {

TEST(DivMod, MatchesSixtyFourBitDivision) {
    const uint64_t ns[] = {0, 1, 7, 255, 65535, 0xffffffffull, 0x100000000ull, 0x123456789abcull,
                           ~0ull};
    const uint64_t ds[] = {1, 3, 256, 1000, 0xffffffffull, 0x100000001ull};
    for (uint64_t n : ns)
        for (uint64_t d : ds) {
            const DivMod r = divMod(n, d);
            EXPECT_EQ(r.quot, n / d) << n << " / " << d;
            EXPECT_EQ(r.rem, n % d) << n << " % " << d;
        }
}

}  // namespace
}  // namespace caustica
