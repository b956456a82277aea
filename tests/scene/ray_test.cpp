// ray_test.cpp — the bit tricks of ray.h against the standard library.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

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

// The scalar form of offsetRayOrigin (Wächter and Binder 2019), the reference for the SSE one
// the host compiles: per coordinate, ulps along n away from the origin, or a tiny absolute step
// next to it.
Vec3f offsetRayOriginScalar(Vec3f p, Vec3f n) {
    Vec3f out;
    for (int i = 0; i < 3; ++i) {
        const int32_t of = int32_t(256.0f * n[i]);
        const float moved = intAsFloat(int32_t(uint32_t(floatAsInt(p[i])) + uint32_t(p[i] < 0 ? -of : of)));
        out[i] = std::fabs(p[i]) < 1.0f / 32.0f ? p[i] + (1.0f / 65536.0f) * n[i] : moved;
    }
    return out;
}

TEST(Ray, OffsetRayOriginMatchesTheScalarFormBitForBit) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-12.0f, 12.0f);
    const float edges[] = {0.0f, -0.0f, 1.0f / 32, -1.0f / 32, std::nextafter(1.0f / 32, 0.0f),
                           std::nextafter(-1.0f / 32, 0.0f), 1e-30f, -1e-30f, 3e7f, -3e7f};
    auto check = [](Vec3f p, Vec3f n) {
        const Vec3f got = offsetRayOrigin(p, n), want = offsetRayOriginScalar(p, n);
        for (int i = 0; i < 3; ++i)
            ASSERT_EQ(floatAsInt(got[i]), floatAsInt(want[i]))
                << "p = " << p[i] << ", n = " << n[i] << ", coordinate " << i;
    };
    for (float a : edges)
        for (float b : edges) check(Vec3f(a, b, -a), normalize(Vec3f(0.3f, -0.9f, 0.1f)));
    for (int k = 0; k < 100000; ++k) {
        const Vec3f p(unit(rng) * std::exp2(exponent(rng)), unit(rng) * std::exp2(exponent(rng)),
                      unit(rng) * std::exp2(exponent(rng)));
        Vec3f n(unit(rng), unit(rng), unit(rng));
        if (k % 2) n = normalize(n);  // unit normals, and any vector (|256 n| < 2^31 either way)
        check(p, n);
    }
}

}  // namespace
}  // namespace caustica
