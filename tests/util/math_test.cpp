// Scalar helpers of util/math.h that approximate libm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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
