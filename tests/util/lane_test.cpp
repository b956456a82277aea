// Tests of the lane types (float4.h, lane.h) and of the code generic over them: run on Float4,
// every lane must hold the bits the float instantiation gives that lane's inputs — random
// inputs and the edge cases of each function (the disk's centre and diagonals, normals along
// ±z, infinite and zero pdfs, NaN).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "caustica/scene/light.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"

namespace caustica {
namespace {

constexpr int kRandomCases = 100000;

uint32_t bitsOf(float f) { return std::bit_cast<uint32_t>(f); }

/// Inputs four at a time: lane k of the Float4 is element i + k.
Float4 gather(const std::vector<float>& v, size_t i) { return Float4::loadUnaligned(v.data() + i); }

std::vector<float> randomFloats(int n, uint64_t seed, float lo, float hi) {
    std::vector<float> v(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        IndependentSampler rng(uint64_t(i), 1, seed);
        v[size_t(i)] = lo + (hi - lo) * rng.get1D();
    }
    return v;
}

/// Appends the pairs `cases` to (a, b), then (pad, pad) until both hold whole groups of four.
template <size_t N>
void appendCases(std::vector<float>& a, std::vector<float>& b, const float (&cases)[N][2], float pad) {
    for (const auto& c : cases) {
        a.push_back(c[0]);
        b.push_back(c[1]);
    }
    while (a.size() % 4 != 0) {
        a.push_back(pad);
        b.push_back(pad);
    }
}

/// Random u in [0, 1)² followed by the warps' edge cases.
void unitSquareCases(std::vector<float>& ux, std::vector<float>& uy) {
    ux = randomFloats(kRandomCases, 7, 0, 1);
    uy = randomFloats(kRandomCases, 8, 0, 1);
    const float edges[][2] = {{0.5f, 0.5f}, {0, 0}, {0.25f, 0.25f}, {0.75f, 0.25f}, {0.5f, 0},
                              {0, 0.5f},    {kOneMinusEpsilon, kOneMinusEpsilon}, {0.5f, 0.75f}};
    appendCases(ux, uy, edges, 0.5f);
}

TEST(Lanes, Float4OperationsRoundAsTheirScalarForms) {
    const std::vector<float> a = randomFloats(4096, 1, -4, 4), b = randomFloats(4096, 2, -4, 4);
    for (size_t i = 0; i < a.size(); i += 4) {
        const Float4 x = gather(a, i), y = gather(b, i);
        const Float4 sum = x + y, diff = x - y, prod = x * y, quot = x / y, neg = -x, root = lane::sqrt(lane::abs(x)),
                     sign = lane::copysign(y, x), lo = lane::min(x, y), hi = lane::max(x, y);
        const uint32_t less = (x < y).bits();
        const Float4 picked = lane::select(x < y, y, x);
        for (int k = 0; k < 4; ++k) {
            const float p = a[i + k], q = b[i + k];
            EXPECT_EQ(bitsOf(sum[k]), bitsOf(p + q));
            EXPECT_EQ(bitsOf(diff[k]), bitsOf(p - q));
            EXPECT_EQ(bitsOf(prod[k]), bitsOf(p * q));
            EXPECT_EQ(bitsOf(quot[k]), bitsOf(p / q));
            EXPECT_EQ(bitsOf(neg[k]), bitsOf(-p));
            EXPECT_EQ(bitsOf(root[k]), bitsOf(std::sqrt(std::fabs(p))));
            EXPECT_EQ(bitsOf(sign[k]), bitsOf(std::copysign(q, p)));
            EXPECT_EQ(bitsOf(lo[k]), bitsOf(min(p, q)));
            EXPECT_EQ(bitsOf(hi[k]), bitsOf(max(p, q)));
            EXPECT_EQ((less >> k) & 1u, uint32_t(p < q));
            EXPECT_EQ(bitsOf(picked[k]), bitsOf(p < q ? q : p));
        }
    }
    // NaN: min/max yield the second operand, as caustica::min/max; comparisons are false.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Float4 n = Float4::broadcast(nan), one = Float4::broadcast(1);
    EXPECT_EQ(bitsOf(lane::min(n, one)[0]), bitsOf(min(nan, 1.0f)));
    EXPECT_EQ(bitsOf(lane::max(one, n)[2]), bitsOf(max(1.0f, nan)));
    EXPECT_EQ((n < one).bits() | (n >= one).bits() | (n == n).bits(), 0u);
    EXPECT_EQ((n != n).bits(), 0xfu);
    EXPECT_EQ(lane::isInf(Float4::broadcast(-INFINITY)).bits(), 0xfu);
    EXPECT_EQ(lane::isInf(n).bits(), 0u);
    EXPECT_TRUE(lane::any(one > Float4::broadcast(0.5f)));
    EXPECT_FALSE(lane::all(one > Float4::broadcast(1)));
}

TEST(Lanes, MaskOfFourFlagsSetsExactlyTheirLanes) {
    for (uint32_t pattern = 0; pattern < 16; ++pattern) {
        const bool flags[4] = {(pattern & 1u) != 0, (pattern & 2u) != 0, (pattern & 4u) != 0, (pattern & 8u) != 0};
        EXPECT_EQ(lane::maskOf(flags).bits(), pattern);
    }
}

// Per-path structs and their lane forms (LaneOf).
static_assert(std::is_same_v<SpectrumOf<float>, Spectrum>);
static_assert(std::is_same_v<SpectrumOf<Float4>, SpectrumF4>);
static_assert(std::is_same_v<LightSampleOf<float>, LightSample>);
static_assert(std::is_same_v<BsdfSampleOf<float>, BsdfSample>);

TEST(Lanes, CosineHemisphereAndDiskMatchTheScalarWarpsBitForBit) {
    std::vector<float> ux, uy;
    unitSquareCases(ux, uy);
    for (size_t i = 0; i < ux.size(); i += 4) {
        const Vec2F4 u{gather(ux, i), gather(uy, i)};
        const Vec2F4 d = sampleConcentricDisk<Float4>(u);
        const Vec3F4 w = sampleCosineHemisphere<Float4>(u);
        const Float4 pdf = cosineHemispherePdf<Float4>(w);
        for (int k = 0; k < 4; ++k) {
            const Vec2f u1(ux[i + k], uy[i + k]);
            const Vec2f d1 = sampleConcentricDisk(u1);
            const Vec3f w1 = sampleCosineHemisphere(u1);
            ASSERT_EQ(bitsOf(d.x[k]), bitsOf(d1.x)) << "u = " << u1.x << ", " << u1.y;
            ASSERT_EQ(bitsOf(d.y[k]), bitsOf(d1.y)) << "u = " << u1.x << ", " << u1.y;
            ASSERT_EQ(bitsOf(w.z[k]), bitsOf(w1.z));
            ASSERT_EQ(bitsOf(pdf[k]), bitsOf(cosineHemispherePdf(w1)));
        }
    }
    // The centre of the square maps to the disk's centre, not to 0 / 0.
    const Vec2f centre = sampleConcentricDisk(Vec2f(0.5f, 0.5f));
    EXPECT_EQ(bitsOf(centre.x), 0u);
    EXPECT_EQ(bitsOf(centre.y), 0u);
    EXPECT_EQ(sampleCosineHemisphere(Vec2f(0.5f, 0.5f)).z, 1.0f);
}

TEST(Lanes, FrameMatchesTheScalarFrameBitForBit) {
    const std::vector<float> ux = randomFloats(kRandomCases, 3, 0, 1), uy = randomFloats(kRandomCases, 4, 0, 1);
    const std::vector<float> vx = randomFloats(kRandomCases, 5, -1, 1), vy = randomFloats(kRandomCases, 6, -1, 1),
                             vz = randomFloats(kRandomCases, 9, -1, 1);
    std::vector<float> nx, ny, nz;
    for (int i = 0; i < kRandomCases; ++i) {
        // Unit normals over the whole sphere, then those along the axes (n.z = ±1, ±0).
        const float z = 1 - 2 * ux[size_t(i)], r = std::sqrt(std::fmax(0.0f, 1 - z * z));
        nx.push_back(r * std::cos(2 * kPi * uy[size_t(i)]));
        ny.push_back(r * std::sin(2 * kPi * uy[size_t(i)]));
        nz.push_back(z);
    }
    const float axes[][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, -0.0f}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -0.0f}, {1, 0, 0}};
    for (size_t a = 0; a < 8; ++a) {
        nx[a] = axes[a][0];
        ny[a] = axes[a][1];
        nz[a] = axes[a][2];
    }
    for (size_t i = 0; i + 4 <= nx.size(); i += 4) {
        const Vec3F4 n{gather(nx, i), gather(ny, i), gather(nz, i)};
        const Vec3F4 v{gather(vx, i), gather(vy, i), gather(vz, i)};
        Vec3F4 s, t;
        orthonormalBasis<Float4>(n, s, t);
        const Vec3F4 world = frameToWorld<Float4>(s, t, n, v), local = frameToLocal<Float4>(s, t, n, v);
        for (int k = 0; k < 4; ++k) {
            const Frame f(Vec3f(nx[i + k], ny[i + k], nz[i + k]));
            const Vec3f v1(vx[i + k], vy[i + k], vz[i + k]);
            const Vec3f s1 = lane::extract(s, k), t1 = lane::extract(t, k), w1 = lane::extract(world, k),
                        l1 = lane::extract(local, k);
            const Vec3f ws = f.toWorld(v1), ls = f.toLocal(v1);
            for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(bitsOf(s1[c]), bitsOf(f.s[c])) << "normal " << i + size_t(k);
                ASSERT_EQ(bitsOf(t1[c]), bitsOf(f.t[c])) << "normal " << i + size_t(k);
                ASSERT_EQ(bitsOf(w1[c]), bitsOf(ws[c]));
                ASSERT_EQ(bitsOf(l1[c]), bitsOf(ls[c]));
            }
        }
    }
}

TEST(Lanes, PowerHeuristicMatchesTheScalarFormBitForBit) {
    std::vector<float> a = randomFloats(kRandomCases, 10, 0, 50), b = randomFloats(kRandomCases, 11, 0, 50);
    const float inf = INFINITY, nan = std::numeric_limits<float>::quiet_NaN();
    const float special[][2] = {{inf, 1}, {1, inf}, {inf, inf}, {0, 1}, {0, 0}, {1, 0}, {-1, 2}, {nan, 1},
                                {1, nan}, {1e30f, 1e-30f}, {1e-30f, 1e30f}, {0, inf}};
    appendCases(a, b, special, 1.0f);
    for (size_t i = 0; i < a.size(); i += 4) {
        const Float4 w = powerHeuristic<Float4>(gather(a, i), gather(b, i));
        for (int k = 0; k < 4; ++k)
            ASSERT_EQ(bitsOf(w[k]), bitsOf(powerHeuristic(a[i + k], b[i + k]))) << a[i + k] << ", " << b[i + k];
    }
    // The scalar form's documented values.
    EXPECT_EQ(powerHeuristic(inf, 1.0f), 1.0f);
    EXPECT_EQ(powerHeuristic(1.0f, inf), 0.0f);
    EXPECT_EQ(powerHeuristic(inf, inf), 0.5f);
    EXPECT_EQ(powerHeuristic(0.0f, 1.0f), 0.0f);
    EXPECT_EQ(powerHeuristic(2.0f, 2.0f), 0.5f);
}

/// Four Vec3f from three coordinate arrays at i.
Vec3F4 gather3(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z, size_t i) {
    return {gather(x, i), gather(y, i), gather(z, i)};
}

TEST(Lanes, DiffuseBsdfMatchesTheScalarLeafBitForBit) {
    // Directions on both sides of the surface (z of either sign, and exactly 0), random reflectances.
    std::vector<float> ox = randomFloats(kRandomCases, 20, -1, 1), oy = randomFloats(kRandomCases, 21, -1, 1),
                       oz = randomFloats(kRandomCases, 22, -1, 1), ix = randomFloats(kRandomCases, 23, -1, 1),
                       iy = randomFloats(kRandomCases, 24, -1, 1), iz = randomFloats(kRandomCases, 25, -1, 1),
                       rr = randomFloats(kRandomCases, 26, 0, 1), ux = randomFloats(kRandomCases, 27, 0, 1),
                       uy = randomFloats(kRandomCases, 28, 0, 1);
    oz[0] = 0;
    iz[1] = 0;
    oz[2] = -0.0f;
    iz[3] = std::numeric_limits<float>::quiet_NaN();
    ux[4] = uy[4] = 0.5f;  // the disk's centre: wi = +z
    Bsdf diffuse;
    diffuse.type = BsdfType::Diffuse;
    for (size_t i = 0; i < ox.size(); i += 4) {
        const Vec3F4 wo = gather3(ox, oy, oz, i), wi = gather3(ix, iy, iz, i);
        const Float4 r = gather(rr, i);
        const SpectrumF4 refl{r, r * 0.5f, r * 0.25f};
        const SpectrumF4 f = bsdf_detail::diffuseEvalLocal<Float4>(refl, wo, wi);
        const Float4 pdf = bsdf_detail::diffusePdfLocal<Float4>(wo, wi);
        Vec3F4 sampled;
        Float4 sampledPdf;
        const uint32_t ok = bsdf_detail::diffuseSampleLocal<Float4>(wo, Vec2F4{gather(ux, i), gather(uy, i)}, sampled,
                                                                     sampledPdf).bits();
        for (int k = 0; k < 4; ++k) {
            diffuse.reflectance = lane::extract(refl, k);
            const Vec3f wo1 = lane::extract(wo, k), wi1 = lane::extract(wi, k);
            const Spectrum f1 = bsdf_detail::evalLocal(diffuse, wo1, wi1);
            ASSERT_EQ(bitsOf(f.r[k]), bitsOf(f1.r)) << i + size_t(k);
            ASSERT_EQ(bitsOf(f.g[k]), bitsOf(f1.g));
            ASSERT_EQ(bitsOf(f.b[k]), bitsOf(f1.b));
            ASSERT_EQ(bitsOf(pdf[k]), bitsOf(bsdf_detail::pdfLocal(diffuse, wo1, wi1)));
            BsdfSample bs;
            const bool ok1 = bsdf_detail::sampleLocal(diffuse, wo1, 0.5f, Vec2f(ux[i + k], uy[i + k]), bs);
            ASSERT_EQ((ok >> k) & 1u, uint32_t(ok1)) << i + size_t(k);
            if (ok1) {
                const Vec3f s1 = lane::extract(sampled, k);
                for (int c = 0; c < 3; ++c) ASSERT_EQ(bitsOf(s1[c]), bitsOf(bs.wi[c]));
                ASSERT_EQ(bitsOf(sampledPdf[k]), bitsOf(bs.pdf));
            }
        }
    }
}

TEST(Lanes, AreaLightPiecesMatchTheScalarFormsBitForBit) {
    // Reference points around a parallelogram light, some behind it, one on it, one at its corner.
    const Vec3f corner(-0.5f, 1.9f, -0.4f), edgeU(1, 0, 0), edgeV(0, 0, 0.8f), normal(0, -1, 0);
    std::vector<float> px = randomFloats(kRandomCases, 30, -2, 2), py = randomFloats(kRandomCases, 31, -1, 3),
                       pz = randomFloats(kRandomCases, 32, -2, 2), ux = randomFloats(kRandomCases, 33, 0, 1),
                       uy = randomFloats(kRandomCases, 34, 0, 1), area = randomFloats(kRandomCases, 35, 0, 2);
    px[0] = corner.x, py[0] = corner.y, pz[0] = corner.z, ux[0] = uy[0] = 0;  // refP is the sampled point
    py[1] = corner.y;                                                          // in the light's plane
    area[2] = 0;
    area[3] = INFINITY;
    const Vec3F4 c4{Float4::broadcast(corner.x), Float4::broadcast(corner.y), Float4::broadcast(corner.z)};
    const Vec3F4 u4{Float4::broadcast(edgeU.x), Float4::broadcast(edgeU.y), Float4::broadcast(edgeU.z)};
    const Vec3F4 v4{Float4::broadcast(edgeV.x), Float4::broadcast(edgeV.y), Float4::broadcast(edgeV.z)};
    const Vec3F4 n4{Float4::broadcast(normal.x), Float4::broadcast(normal.y), Float4::broadcast(normal.z)};
    const Float4 selPdf = Float4::broadcast(0.5f);
    for (size_t i = 0; i < px.size(); i += 4) {
        const Vec3F4 refP = gather3(px, py, pz, i);
        const Vec3F4 p = light_detail::parallelogramPoint<Float4>(c4, u4, v4, Vec2F4{gather(ux, i), gather(uy, i)});
        const Float4 pdf = light_detail::areaToSolidAngle<Float4>(refP, p, n4, gather(area, i));
        Vec3F4 wi;
        Float4 dist, pdfOut;
        const uint32_t ok = light_detail::areaLightDirection<Float4>(refP, p, pdf, selPdf, wi, dist, pdfOut).bits();
        for (int k = 0; k < 4; ++k) {
            const Vec3f refP1 = lane::extract(refP, k);
            const Vec3f p1 = light_detail::parallelogramPoint<float>(corner, edgeU, edgeV, Vec2f(ux[i + k], uy[i + k]));
            const Vec3f p4 = lane::extract(p, k);
            for (int c = 0; c < 3; ++c) ASSERT_EQ(bitsOf(p4[c]), bitsOf(p1[c]));
            const float pdf1 = light_detail::areaToSolidAngle(refP1, p1, normal, area[i + k]);
            ASSERT_EQ(bitsOf(pdf[k]), bitsOf(pdf1)) << i + size_t(k);
            Vec3f wi1;
            float dist1, pdfOut1;
            const bool ok1 = light_detail::areaLightDirection<float>(refP1, p1, pdf1, 0.5f, wi1, dist1, pdfOut1);
            ASSERT_EQ((ok >> k) & 1u, uint32_t(ok1)) << i + size_t(k);
            if (ok1) {
                const Vec3f w4 = lane::extract(wi, k);
                for (int c = 0; c < 3; ++c) ASSERT_EQ(bitsOf(w4[c]), bitsOf(wi1[c]));
                ASSERT_EQ(bitsOf(dist[k]), bitsOf(dist1));
                ASSERT_EQ(bitsOf(pdfOut[k]), bitsOf(pdfOut1));
            }
        }
    }
    // The documented zeros: behind the light, area 0, the reference point on the light.
    EXPECT_EQ(light_detail::areaToSolidAngle(Vec3f(0, 3, 0), Vec3f(0, 1.9f, 0), normal, 1.0f), 0.0f);
    EXPECT_EQ(light_detail::areaToSolidAngle(Vec3f(0, 0, 0), Vec3f(0, 1.9f, 0), normal, 0.0f), 0.0f);
    EXPECT_EQ(light_detail::areaToSolidAngle(corner, corner, normal, 1.0f), 0.0f);
}

}  // namespace
}  // namespace caustica
