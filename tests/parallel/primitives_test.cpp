// primitives_test.cpp — the CPU primitives against sequential references, stability of the sort
// and independence from the number of threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"
#include "random_inputs.h"

namespace caustica {
namespace {

using test::kSizes;
using test::randomU32;

std::vector<uint64_t> randomU64(size_t n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<uint64_t> v(n);
    for (auto& x : v) x = rng();
    return v;
}

std::vector<float> randomFloats(size_t n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> dist(-100.0f, 100.0f);
    std::vector<float> v(n);
    for (auto& x : v) x = dist(rng);
    return v;
}

template <class Key>
std::vector<std::pair<Key, uint32_t>> stableReference(const std::vector<Key>& keys, int keyBits) {
    const Key mask = keyBits >= int(sizeof(Key) * 8) ? ~Key(0) : Key((Key(1) << keyBits) - 1);
    std::vector<std::pair<Key, uint32_t>> ref(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) ref[i] = {keys[i], uint32_t(i)};
    std::stable_sort(ref.begin(), ref.end(), [mask](const auto& a, const auto& b) {
        return (a.first & mask) < (b.first & mask);
    });
    return ref;
}

template <class Key>
void expectSortedLikeReference(std::vector<Key> keys, int keyBits) {
    const auto ref = stableReference(keys, keyBits);
    std::vector<uint32_t> values(keys.size());
    std::iota(values.begin(), values.end(), 0u);
    radixSortPairs(Device::cpu(), Span<Key>(keys), Span<uint32_t>(values), keyBits);
    for (size_t i = 0; i < keys.size(); ++i) {
        ASSERT_EQ(keys[i], ref[i].first) << "at " << i << " of " << keys.size();
        ASSERT_EQ(values[i], ref[i].second) << "at " << i << " of " << keys.size();
    }
}

TEST(ExclusiveScan, MatchesSequentialReference) {
    for (size_t n : kSizes) {
        const auto in = randomU32(n, 1000, n + 1);
        std::vector<uint32_t> out(n, 7u), ref(n);
        uint32_t total = 0;
        for (size_t i = 0; i < n; ++i) ref[i] = std::exchange(total, total + in[i]);
        EXPECT_EQ(exclusiveScan(Device::cpu(), Span<const uint32_t>(in), Span<uint32_t>(out)),
                  total);
        EXPECT_EQ(out, ref) << "n = " << n;
    }
}

TEST(ExclusiveScan, InPlaceAndWrapsModulo2To32) {
    std::vector<uint32_t> v = {0xffffffffu, 2u, 3u};
    const Span<uint32_t> s(v);
    EXPECT_EQ(exclusiveScan(Device::cpu(), asConst(s), s), 4u);
    EXPECT_EQ(v, (std::vector<uint32_t>{0u, 0xffffffffu, 1u}));
    auto big = randomU32(1000000, 50, 3);
    std::vector<uint32_t> copy = big;
    const uint32_t t1 =
        exclusiveScan(Device::cpu(), Span<const uint32_t>(copy), Span<uint32_t>(copy));
    std::vector<uint32_t> out(big.size());
    const uint32_t t2 =
        exclusiveScan(Device::cpu(), Span<const uint32_t>(big), Span<uint32_t>(out));
    EXPECT_EQ(t1, t2);
    EXPECT_EQ(copy, out);
}

TEST(ExclusiveScan, RejectsShortOutput) {
    std::vector<uint32_t> in(4, 1u), out(3);
    EXPECT_THROW(exclusiveScan(Device::cpu(), Span<const uint32_t>(in), Span<uint32_t>(out)),
                 Error);
}

TEST(RadixSortPairs, Uint64MatchesStableSort) {
    for (size_t n : kSizes) expectSortedLikeReference(randomU64(n, 11 + n), 64);
}

TEST(RadixSortPairs, Uint32MatchesStableSort) {
    for (size_t n : kSizes) expectSortedLikeReference(randomU32(n, 0xffffffffu, 5 + n), 32);
}

TEST(RadixSortPairs, IsStableWithManyEqualKeys) {
    // 16 distinct keys over 1e6 elements: every key repeats; values must stay in input order.
    for (size_t n : kSizes) {
        auto k32 = randomU32(n, 15, 21 + n);
        std::vector<uint64_t> k64(k32.begin(), k32.end());
        expectSortedLikeReference(k32, 32);
        expectSortedLikeReference(k64, 64);
        expectSortedLikeReference(k64, 4);
    }
}

TEST(RadixSortPairs, FewerKeyBitsIgnoreHigherBits) {
    // Morton codes of 30 bits with junk above: ordered by the low 30 bits only, junk preserved.
    auto keys = randomU64(100000, 99);
    expectSortedLikeReference(keys, 30);
    expectSortedLikeReference(randomU32(100000, 0xffffffffu, 98), 13);
}

TEST(RadixSortPairs, RejectsBadArguments) {
    std::vector<uint64_t> keys(4);
    std::vector<uint32_t> values(3), values4(4);
    EXPECT_THROW(radixSortPairs(Device::cpu(), Span<uint64_t>(keys), Span<uint32_t>(values)),
                 Error);
    EXPECT_THROW(radixSortPairs(Device::cpu(), Span<uint64_t>(keys), Span<uint32_t>(values4), 0),
                 Error);
    EXPECT_THROW(radixSortPairs(Device::cpu(), Span<uint64_t>(keys), Span<uint32_t>(values4), 65),
                 Error);
}

TEST(CompactIndices, MatchesSequentialReference) {
    for (size_t n : kSizes) {
        for (uint32_t maxFlag : {1u, 7u}) {  // sparse-ish and dense flags; any non-zero counts
            const auto flags = randomU32(n, maxFlag, 31 + n);
            std::vector<uint32_t> ref;
            for (size_t i = 0; i < n; ++i)
                if (flags[i] != 0) ref.push_back(uint32_t(i));
            std::vector<uint32_t> out(n);
            const uint32_t count =
                compactIndices(Device::cpu(), Span<const uint32_t>(flags), Span<uint32_t>(out));
            ASSERT_EQ(count, ref.size());
            out.resize(count);
            EXPECT_EQ(out, ref) << "n = " << n;
        }
    }
}

TEST(CompactIndices, AllAndNone) {
    std::vector<uint32_t> none(5000, 0u), all(5000, 1u), out(5000);
    EXPECT_EQ(compactIndices(Device::cpu(), Span<const uint32_t>(none), Span<uint32_t>(out)), 0u);
    EXPECT_EQ(compactIndices(Device::cpu(), Span<const uint32_t>(all), Span<uint32_t>(out)), 5000u);
    for (uint32_t i = 0; i < 5000; ++i) ASSERT_EQ(out[i], i);
    std::vector<uint32_t> shortOut(10);
    EXPECT_THROW(compactIndices(Device::cpu(), Span<const uint32_t>(all), Span<uint32_t>(shortOut)),
                 Error);
}

TEST(Reduce, SumAndMaxMatchSequentialReference) {
    for (size_t n : kSizes) {
        const auto in = randomFloats(n, 41 + n);
        double sum = 0.0, absSum = 0.0;
        float mx = -std::numeric_limits<float>::infinity();
        for (float x : in) {
            sum += x;
            absSum += std::abs(x);
            mx = std::max(mx, x);
        }
        EXPECT_NEAR(reduceSum(Device::cpu(), Span<const float>(in)), sum, 1e-12 * absSum + 1e-12);
        EXPECT_EQ(reduceMax(Device::cpu(), Span<const float>(in)), mx) << "n = " << n;
    }
    EXPECT_EQ(reduceSum(Device::cpu(), Span<const float>()), 0.0);
    EXPECT_EQ(reduceMax(Device::cpu(), Span<const float>()),
              -std::numeric_limits<float>::infinity());
}

TEST(Reduce, Uint32SumIsExactIn64Bits) {
    for (size_t n : kSizes) {
        // Values near 2^32: a 32-bit accumulator would wrap after two of them.
        auto in = randomU32(n, 0xffffffffu, 43 + n);
        if (n > 0) in[0] = 0xffffffffu;
        uint64_t sum = 0;
        for (uint32_t x : in) sum += x;
        EXPECT_EQ(reduceSum(Device::cpu(), Span<const uint32_t>(in)), sum) << "n = " << n;
    }
    EXPECT_EQ(reduceSum(Device::cpu(), Span<const uint32_t>()), 0u);
}

struct Results {
    std::vector<uint32_t> scan, sortedValues, compacted;
    std::vector<uint64_t> sortedKeys;
    double sum = 0.0;
    float max = 0.0f;
    bool operator==(const Results&) const = default;
};

Results runAll(int threads) {
    Results r;
    tbb::task_arena arena(threads);
    arena.execute([&] {
        const size_t n = 1000000;
        auto counts = randomU32(n, 100, 1);
        r.scan.resize(n);
        exclusiveScan(Device::cpu(), Span<const uint32_t>(counts), Span<uint32_t>(r.scan));
        r.sortedKeys = randomU64(n, 2);
        r.sortedValues.resize(n);
        std::iota(r.sortedValues.begin(), r.sortedValues.end(), 0u);
        radixSortPairs(Device::cpu(), Span<uint64_t>(r.sortedKeys), Span<uint32_t>(r.sortedValues),
                       40);
        auto flags = randomU32(n, 1, 3);
        r.compacted.resize(n);
        r.compacted.resize(compactIndices(Device::cpu(), Span<const uint32_t>(flags),
                                          Span<uint32_t>(r.compacted)));
        const auto floats = randomFloats(n, 4);
        r.sum = reduceSum(Device::cpu(), Span<const float>(floats));
        r.max = reduceMax(Device::cpu(), Span<const float>(floats));
    });
    return r;
}

TEST(Primitives, DeterministicAcrossThreadCounts) {
    const Results one = runAll(1), two = runAll(2);
    EXPECT_TRUE(one == two);
    EXPECT_EQ(one.sum, two.sum);  // bitwise, not just close
}

TEST(Primitives, CudaDeviceWithoutBackendThrows) {
    if (gpuBackend()) GTEST_SKIP() << "a GPU backend is registered in this process";
    std::vector<uint32_t> v(8, 1u);
    EXPECT_THROW(exclusiveScan(Device::cuda(), Span<const uint32_t>(v), Span<uint32_t>(v)), Error);
    std::vector<float> f(8, 1.0f);
    EXPECT_THROW(reduceSum(Device::cuda(), Span<const float>(f)), Error);
    EXPECT_THROW(reduceSum(Device::cuda(), Span<const uint32_t>(v)), Error);
    EXPECT_THROW(Buffer<float>(Device::cuda(), 8), Error);
}

}  // namespace
}  // namespace caustica
