// The host's four-triangle SSE test (triangle4.h) against the scalar intersectTriangle, lane by
// lane and bit for bit, plus the small vector helpers of simd4.h.
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/primitive_intersect.h"
#include "caustica/accel/simd4.h"
#include "caustica/accel/triangle4.h"

namespace caustica {
namespace {

TEST(Simd4, LowestBit) {
    EXPECT_EQ(lowestBit(1u), 0);
    EXPECT_EQ(lowestBit(0x80u), 7);
    EXPECT_EQ(lowestBit(0x80000000u), 31);
    EXPECT_EQ(lowestBit(0b10100u), 2);
}

TEST(Simd4, MinMaxFollowTheScalarOperandRule) {
    // min(a, b) = a < b ? a : b and max(a, b) = a > b ? a : b, NaN operands included.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    alignas(16) const float a[4] = {1, nan, 2, -0.0f}, b[4] = {2, 3, nan, 0.0f};
    alignas(16) float lo[4], hi[4];
    min(Float4::load(a), Float4::load(b)).store(lo);
    max(Float4::load(a), Float4::load(b)).store(hi);
    for (int k = 0; k < 4; ++k) {
        const float wantLo = a[k] < b[k] ? a[k] : b[k], wantHi = a[k] > b[k] ? a[k] : b[k];
        EXPECT_EQ(std::memcmp(&lo[k], &wantLo, 4), 0) << k;
        EXPECT_EQ(std::memcmp(&hi[k], &wantHi, 4), 0) << k;
    }
    EXPECT_EQ(lessEqualMask(Float4::load(a), Float4::load(b)), 0b1001u);
}

#if CA_BVH_SSE
bool sameBits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Runs the four triangles prims[g..g+3] against the ray (o, d, tMax) with intersectTriangle4 and
/// expects each lane to equal the scalar intersectTriangle bit for bit; returns the lanes hit.
uint32_t expectLanesMatchScalar(const std::vector<BvhPrimitive>& prims, uint32_t g, Vec3f o,
                                Vec3f d, float tMax) {
    const uint32_t index[4] = {g, g + 1, g + 2, g + 3};
    const bvh_detail::Triangle4 tri = bvh_detail::Triangle4::load(prims.data(), index);
    float t[4], b1[4], b2[4];
    const uint32_t mask = bvh_detail::intersectTriangle4(bvh_detail::broadcast3(o),
                                                         makeWatertightRay(d), tMax, tri, t, b1, b2);
    for (int l = 0; l < 4; ++l) {
        const BvhPrimitive& p = prims[g + l];
        Float tRef = 0, b1Ref = 0, b2Ref = 0;
        const bool hit = intersectTriangle(o, d, tMax, p.p0, p.p1, p.p2, tRef, b1Ref, b2Ref);
        EXPECT_EQ(bool(mask & (1u << l)), hit) << "group " << g << " lane " << l;
        if (!hit || !(mask & (1u << l))) continue;
        EXPECT_TRUE(sameBits(t[l], tRef));
        EXPECT_TRUE(sameBits(b1[l], b1Ref));
        EXPECT_TRUE(sameBits(b2[l], b2Ref));
    }
    return mask;
}

TEST(Triangle4, EveryLaneMatchesTheScalarTestBitForBit) {
    // Small random triangles around the origin (with some degenerate ones), rays from random
    // points towards random points near them: hits, misses, grazing and back-facing cases.
    test::TestRng rng(77);
    std::vector<BvhPrimitive> prims(4 * 2000);
    for (size_t i = 0; i < prims.size(); ++i) {
        BvhPrimitive& p = prims[i];
        p.p0 = rng.inBox(Vec3f(-1, -1, -1), Vec3f(1, 1, 1));
        p.p1 = rng.inBox(Vec3f(-1, -1, -1), Vec3f(1, 1, 1));
        p.p2 = i % 17 == 0 ? p.p0 + (p.p1 - p.p0) * 2.0f : rng.inBox(Vec3f(-1, -1, -1), Vec3f(1, 1, 1));
        p.primId = uint32_t(i);
    }
    uint32_t hits = 0;
    for (uint32_t g = 0; g < prims.size(); g += 4) {
        const Vec3f o = rng.inBox(Vec3f(-4, -4, -4), Vec3f(4, 4, 4));
        const Vec3f d = rng.inBox(Vec3f(-0.5f, -0.5f, -0.5f), Vec3f(0.5f, 0.5f, 0.5f)) - o;
        const float tMax = g % 8 == 0 ? kInfinity : rng.uniform(0.5f, 1.5f);
        const uint32_t index[4] = {g, g + 1, g + 2, g + 3};
        EXPECT_EQ(bvh_detail::Triangle4::load(prims.data(), index).triangleLanes(g + 2), 0b0011u);
        hits += uint32_t(__builtin_popcount(expectLanesMatchScalar(prims, g, o, d, tMax)));
    }
    EXPECT_GT(hits, 200u);  // the rays do hit
}

TEST(Triangle4, RaysThroughVerticesMatchTheScalarTest) {
    // Rays aimed exactly at a vertex shared by the four lanes' triangles: edge functions come out
    // exactly 0 in some lanes and are redone in double precision, as in the scalar test. Axis-
    // aligned and random rays, so that both exact zeros and tiny values occur.
    test::TestRng rng(78);
    uint32_t hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3f v = i % 2 ? rng.inBox(Vec3f(-1, -1, -1), Vec3f(1, 1, 1))
                              : Vec3f(Float(i % 5) * 0.25f, 0.5f, -0.75f);
        std::vector<BvhPrimitive> prims(4);
        for (uint32_t l = 0; l < 4; ++l) {
            prims[l].p0 = l % 2 ? rng.inBox(Vec3f(-1, -1, -1), Vec3f(1, 1, 1)) : v;
            prims[l].p1 = l % 2 ? v : rng.inBox(Vec3f(-1, -1, -1), Vec3f(1, 1, 1));
            prims[l].p2 = rng.inBox(Vec3f(-1, -1, -1), Vec3f(1, 1, 1));
            if (i % 2 == 0) prims[l].p2[l % 3] = v[l % 3];  // an edge in an axis plane
            prims[l].primId = l;
        }
        const Vec3f o = i % 4 == 0 ? v + Vec3f(0, 0, 3) : rng.inBox(Vec3f(-4, -4, -4), Vec3f(4, 4, 4));
        hits += uint32_t(__builtin_popcount(expectLanesMatchScalar(prims, 0, o, v - o, kInfinity)));
    }
    EXPECT_GT(hits, 100u);
}
#endif

}  // namespace
}  // namespace caustica
