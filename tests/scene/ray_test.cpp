// ray_test.cpp — the bit tricks of ray.h against the standard library.
#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "caustica/scene/ray.h"

namespace caustica {
namespace {

// Embree's open interval (embree_accel.cpp) must be exactly std::nextafter(tMax, 0).
TEST(Ray, NextFloatTowardZeroMatchesNextafter) {
    const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-4f, 123.456f, -7.5e12f,
                             std::numeric_limits<float>::min(), -std::numeric_limits<float>::min(),
                             std::numeric_limits<float>::denorm_min(),
                             -std::numeric_limits<float>::denorm_min(),
                             std::numeric_limits<float>::max(), std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity()};
    auto expectSame = [](float x) {
        const float want = std::nextafter(x, 0.0f), got = nextFloatTowardZero(x);
        EXPECT_EQ(floatAsInt(got), floatAsInt(want)) << "x = " << x;
    };
    for (float x : special) expectSame(x);
    // Every 4099th bit pattern of both signs (NaNs compared as NaN).
    for (uint64_t bits = 0; bits <= 0xffffffffull; bits += 4099) {
        const float x = intAsFloat(int32_t(uint32_t(bits)));
        if (std::isnan(x))
            EXPECT_TRUE(std::isnan(nextFloatTowardZero(x)));
        else
            expectSame(x);
    }
}

}  // namespace
}  // namespace caustica
