// The Metropolis chain state (mlt_state.h): fixed-point storage, the symmetry of the small step on
// the 24/16-bit grid, large steps uniform, lazily computed proposals equal to what an accepted
// chain stores, and the memory figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/integrators/mlt/mlt_splat.h"
#include "caustica/integrators/mlt/mlt_state.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

struct CompactFixture {
    uint32_t chains = 3, bounces = 4;
    std::vector<uint8_t> fine;
    std::vector<uint16_t> coarse;
    CompactChainStore store;
    CompactFixture() {
        const size_t fineSlots = kMltCameraDims + 4 * bounces, coarseSlots = 3 * bounces;
        fine.assign(3 * fineSlots * chains, 0);
        coarse.assign(coarseSlots * chains, 0);
        store.fine = fine.data();
        store.coarse = coarse.data();
        store.dims = mltStoredDims(bounces);
        store.fineChainStride = fineSlots;
        store.fineDimStride = 1;
        store.coarseChainStride = coarseSlots;
        store.coarseDimStride = 1;
    }
};

TEST(MltState, DimensionClassesFollowThePathTracersLayout) {
    // Film and lens position fine; per bounce: light choice coarse, light point fine x2, lobe
    // coarse, direction fine x2, roulette coarse.
    const bool coarse[] = {false, false, false, false, true, false, false, true, false, false, true};
    ASSERT_EQ(kMltCameraDims, 4u);
    for (uint32_t d = 0; d < 11; ++d) EXPECT_EQ(isCoarseDim(d), coarse[d]) << d;
    EXPECT_TRUE(isCoarseDim(kMltCameraDims + 7));
    EXPECT_FALSE(isCoarseDim(kMltCameraDims + 7 + 1));
}

TEST(MltState, CompactStoreRoundTripsEveryCoordinateWithoutAliasing) {
    CompactFixture f;
    // Distinct values everywhere, then read back: no two coordinates share storage.
    for (uint32_t c = 0; c < f.chains; ++c)
        for (uint32_t d = 0; d < f.store.dims; ++d) {
            const uint32_t bits = CompactChainStore::bitsOf(d);
            f.store.set(c, d, (c * 977u + d * 131u + 0x5a5a5au) & ((1u << bits) - 1));
        }
    for (uint32_t c = 0; c < f.chains; ++c)
        for (uint32_t d = 0; d < f.store.dims; ++d) {
            const uint32_t bits = CompactChainStore::bitsOf(d);
            EXPECT_EQ(f.store.get(c, d), (c * 977u + d * 131u + 0x5a5a5au) & ((1u << bits) - 1)) << c << " " << d;
        }
}

TEST(MltState, FixedPointValuesMapIntoTheUnitInterval) {
    EXPECT_EQ(CompactChainStore::toFloat(0, 0), 0.0f);
    EXPECT_LT(CompactChainStore::toFloat((1u << 24) - 1, 0), 1.0f);
    EXPECT_LT(CompactChainStore::toFloat((1u << 16) - 1, 2), 1.0f);
    EXPECT_EQ(CompactChainStore::toFloat(1u << 23, 0), 0.5f);
}

// Metropolis needs a symmetric proposal: on the grid, a step of +n units must be exactly as likely
// as a step of -n units. Counted over many draws, the two tails agree within binomial noise.
template <class Store>
void expectSymmetricSmallSteps(uint32_t dim, typename Store::Raw start) {
    MltMutation m;
    const KelemenStep step(m);
    std::map<long, int> counts;
    constexpr int kDraws = 200000;
    const double unit = std::is_same_v<Store, CompactChainStore> ? double(1u << CompactChainStore::bitsOf(dim)) : 1e6;
    for (int i = 0; i < kDraws; ++i) {
        const auto v = Store::small(start, proposalBits(0x1234, uint32_t(i)), dim, step);
        double delta = (double(v) - double(start)) * (std::is_same_v<Store, CompactChainStore> ? 1.0 : unit);
        const double period = std::is_same_v<Store, CompactChainStore> ? unit : unit;
        if (delta > period / 2) delta -= period;
        if (delta < -period / 2) delta += period;
        // Offsets within [s1, s2] of the interval.
        const double frac = std::fabs(delta) / period;
        EXPECT_GE(frac, m.s1 * 0.99 - 1.0 / period);
        EXPECT_LE(frac, m.s2 * 1.01 + 1.0 / period);
        counts[delta > 0 ? 1 : -1]++;
    }
    const double p = double(counts[1]) / kDraws;
    EXPECT_NEAR(p, 0.5, 4 * std::sqrt(0.25 / kDraws));
}

TEST(MltState, SmallStepsAreSymmetricAndSizedByKelemensRange) {
    expectSymmetricSmallSteps<CompactChainStore>(0, 12345);          // fine, near 0: wraps
    expectSymmetricSmallSteps<CompactChainStore>(kMltCameraDims, 40000);  // coarse
    expectSymmetricSmallSteps<FloatChainStore>(0, 0.5f);
}

TEST(MltState, SmallStepDistributionIsExactlyMirrorSymmetricOnTheGrid) {
    // The rounded offset has the same distribution for +n and -n: compare the histogram of
    // |offset| for the two signs bucket by bucket (chi-square-like bound on the difference).
    const KelemenStep step{MltMutation{}};
    std::map<long, long> pos, neg;
    constexpr int kDraws = 400000;
    for (int i = 0; i < kDraws; ++i) {
        const uint32_t v = CompactChainStore::small(1u << 15, proposalBits(77, uint32_t(i)), kMltCameraDims, step);
        const long delta = long(v) - long(1u << 15);
        const long bucket = std::labs(delta) / 64;
        (delta >= 0 ? pos : neg)[bucket]++;
    }
    for (const auto& [bucket, n] : pos) {
        const double a = double(n), b = double(neg[bucket]);
        EXPECT_LE(std::fabs(a - b), 5 * std::sqrt(a + b) + 1) << "bucket " << bucket;
    }
}

// The step sizes are log-uniform in [s1, s2]: log2(|offset|) is uniform over [log2 s1, log2 s2].
TEST(MltState, SmallStepSizesAreLogUniform) {
    const MltMutation m{1.0f / 4096.0f, 1.0f / 16.0f};
    const KelemenStep step(m);
    const test::Chi2Result r = test::chi2UniformOnUnitInterval(16, 160000, [&](int i) {
        const double size = step.magnitude(proposalBits(31, uint32_t(i)));
        EXPECT_GE(size, m.s1 * (1 - 1e-6));
        EXPECT_LE(size, m.s2 * (1 + 1e-6));
        const double t = std::log2(size / m.s1) / std::log2(m.s2 / m.s1);
        return std::clamp(t, 0.0, std::nextafter(1.0, 0.0));  // the ends are checked just above
    });
    EXPECT_TRUE(r.passed()) << r.describe();
}

TEST(MltState, LargeStepsAreUniformOnTheGrid) {
    for (uint32_t dim : {0u, kMltCameraDims}) {
        const test::Chi2Result r = test::chi2UniformOnUnitInterval(16, 160000, [&](int i) {
            return double(CompactChainStore::toFloat(CompactChainStore::large(proposalBits(9, uint32_t(i)), dim), dim));
        });
        EXPECT_TRUE(r.passed()) << "dim " << dim << ": " << r.describe();
    }
}

// The proposal is lazy: the path tracer reads coordinates through the sampler, the chain writes
// them through raw() when it accepts. Both must be the same numbers, and coordinates past the
// stored ones must still be valid uniform numbers.
TEST(MltState, ProposalSamplerReadsWhatAnAcceptedChainStores) {
    CompactFixture f;
    for (uint32_t d = 0; d < f.store.dims; ++d)
        f.store.set(1, d, CompactChainStore::large(proposalBits(5, d), d));
    for (bool large : {false, true}) {
        MltProposalSampler<CompactChainStore> sampler(&f.store, 1, f.store.dims, 4242, large, MltMutation{});
        std::vector<Float> read;
        for (uint32_t d = 0; d < f.store.dims + 5; ++d) read.push_back(sampler.get1D());
        for (uint32_t d = 0; d < f.store.dims; ++d)
            EXPECT_EQ(read[d], CompactChainStore::toFloat(sampler.raw(d), d)) << d;
        for (uint32_t d = f.store.dims; d < read.size(); ++d) {
            EXPECT_GE(read[d], 0.0f);
            EXPECT_LT(read[d], 1.0f);
        }
        // Another chain's storage is untouched by reading.
        for (uint32_t d = 0; d < f.store.dims; ++d) EXPECT_EQ(f.store.get(0, d), 0u);
    }
}

TEST(MltState, CompactStateUsesFewerBytesPerChainThanFloat) {
    // Max depth 24 stores 23 bounces of 7 coordinates plus the film and lens position.
    const uint32_t bounces = mltStoredBounces(PathSettings{24, 5, false});
    EXPECT_EQ(bounces, 23u);
    const size_t compact = mltBytesPerChain(MltStateKind::Compact, bounces);
    const size_t flt = mltBytesPerChain(MltStateKind::Float, bounces);
    EXPECT_EQ(compact, size_t(4 * 3 + 23 * (4 * 3 + 3 * 2) + 26));
    EXPECT_EQ(flt, size_t(4 * (4 + 23 * 7) + 26));
    EXPECT_LT(double(compact) / double(flt), 0.7);
    EXPECT_EQ(mltStoredBounces(PathSettings{-1, 5, false}), kMltUnboundedStoredBounces);
    EXPECT_EQ(mltStoredBounces(PathSettings{1, 5, false}), 0u);
}

TEST(MltSplat, SplatPixelSkipsZeroInvalidAndOutsideSplats) {
    MltSplatView v;
    v.width = 4;
    v.height = 3;
    EXPECT_EQ(splatPixel(v, MltSplat{{1.5f, 2.5f}, Spectrum(1), Spectrum(0)}), 2u * 4u + 1u);
    EXPECT_EQ(splatPixel(v, MltSplat{{1.5f, 2.5f}, Spectrum(0), Spectrum(1)}), 2u * 4u + 1u);  // large step only
    EXPECT_EQ(splatPixel(v, MltSplat{{1.5f, 2.5f}, Spectrum(0), Spectrum(0)}), kNoPixel);
    EXPECT_EQ(splatPixel(v, MltSplat{{4.0f, 0.5f}, Spectrum(1), Spectrum(0)}), kNoPixel);
    EXPECT_EQ(splatPixel(v, MltSplat{{0.5f, 0.5f}, Spectrum(std::nanf("")), Spectrum(0)}), kNoPixel);
    EXPECT_EQ(splatPixel(v, MltSplat{{0.5f, 0.5f}, Spectrum(1), Spectrum(std::nanf(""))}), kNoPixel);
}

}  // namespace
}  // namespace caustica
