// primitives.cpp — CPU (TBB) implementations of the parallel primitives and dispatch to the GPU
// backend. Work is split into fixed-size blocks, never by thread count, so results are identical
// whatever the TBB arena size.
#include "caustica/parallel/primitives.h"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_scan.h>

#include "caustica/parallel/backend.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

constexpr size_t kBlock = size_t(1) << 14;  // elements per CPU work block

size_t blockCount(size_t n) {
    return (n + kBlock - 1) / kBlock;
}

/// Runs f(block, begin, end) over the fixed blocks of [0, n) in parallel.
template <class F>
void forEachBlock(size_t n, F&& f) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blockCount(n), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t b = r.begin(); b != r.end(); ++b)
                              f(b, b * kBlock, std::min(n, (b + 1) * kBlock));
                      });
}

void require(bool ok, const char* what, const std::string& why) {
    if (!ok) throw Error(std::string(what) + ": " + why);
}

uint32_t scanCpu(Span<const uint32_t> in, Span<uint32_t> out) {
    using Range = tbb::blocked_range<size_t>;
    return tbb::parallel_scan(
        Range(0, in.size(), kBlock), uint32_t(0),
        [&](const Range& r, uint32_t sum, bool isFinal) {
            for (size_t i = r.begin(); i != r.end(); ++i) {
                const uint32_t v = in[i];  // read before the write: in place is fine
                if (isFinal) out[i] = sum;
                sum += v;
            }
            return sum;
        },
        std::plus<uint32_t>());
}

/// Parallel LSD radix sort, 8 bits per pass: per-block digit histograms, offsets in
/// (digit, block) order, then a scatter that keeps each block's order — hence stable.
template <class Key>
void radixSortCpu(Span<Key> keys, Span<uint32_t> values, int keyBits) {
    const size_t n = keys.size();
    if (n < 2) return;
    constexpr int kDigitBits = 8;
    constexpr size_t kBuckets = size_t(1) << kDigitBits;
    const size_t blocks = blockCount(n);
    std::vector<Key> keysTmp(n);
    std::vector<uint32_t> valuesTmp(n);
    std::vector<size_t> offsets(blocks * kBuckets);
    Key* srcK = keys.data();
    uint32_t* srcV = values.data();
    Key* dstK = keysTmp.data();
    uint32_t* dstV = valuesTmp.data();
    for (int shift = 0; shift < keyBits; shift += kDigitBits) {
        const Key mask = Key((Key(1) << std::min(kDigitBits, keyBits - shift)) - 1);
        forEachBlock(n, [&](size_t b, size_t begin, size_t end) {
            size_t* count = &offsets[b * kBuckets];
            std::fill(count, count + kBuckets, size_t(0));
            for (size_t i = begin; i < end; ++i) ++count[(srcK[i] >> shift) & mask];
        });
        bool trivial = false;  // all keys share this digit: the pass would not move anything
        size_t running = 0;
        for (size_t d = 0; d < kBuckets; ++d) {
            size_t total = 0;
            for (size_t b = 0; b < blocks; ++b) {
                const size_t c = offsets[b * kBuckets + d];
                offsets[b * kBuckets + d] = running + total;
                total += c;
            }
            trivial = trivial || total == n;
            running += total;
        }
        if (trivial) continue;
        forEachBlock(n, [&](size_t b, size_t begin, size_t end) {
            std::array<size_t, kBuckets> pos;
            std::copy_n(&offsets[b * kBuckets], kBuckets, pos.begin());
            for (size_t i = begin; i < end; ++i) {
                const size_t p = pos[(srcK[i] >> shift) & mask]++;
                dstK[p] = srcK[i];
                dstV[p] = srcV[i];
            }
        });
        std::swap(srcK, dstK);
        std::swap(srcV, dstV);
    }
    if (srcK != keys.data()) {
        forEachBlock(n, [&](size_t, size_t begin, size_t end) {
            std::copy(srcK + begin, srcK + end, keys.data() + begin);
            std::copy(srcV + begin, srcV + end, values.data() + begin);
        });
    }
}

template <class Key>
void radixSortChecked(const Device& device, Span<Key> keys, Span<uint32_t> values, int keyBits) {
    constexpr int maxBits = int(sizeof(Key) * 8);
    require(values.size() == keys.size(), "radixSortPairs",
            std::to_string(keys.size()) + " keys but " + std::to_string(values.size()) + " values");
    require(keyBits >= 1 && keyBits <= maxBits, "radixSortPairs",
            "keyBits " + std::to_string(keyBits) + " outside [1, " + std::to_string(maxBits) + "]");
    if (keys.size() < 2) return;
    if (device.isCpu()) {
        radixSortCpu(keys, values, keyBits);
    } else if constexpr (sizeof(Key) == 8) {
        requireGpuBackend("radixSortPairs")
            .sortPairs64(keys.data(), values.data(), keys.size(), keyBits);
    } else {
        requireGpuBackend("radixSortPairs")
            .sortPairs32(keys.data(), values.data(), keys.size(), keyBits);
    }
}

uint32_t compactCpu(Span<const uint32_t> flags, Span<uint32_t> out) {
    const size_t n = flags.size();
    std::vector<uint32_t> offsets(blockCount(n));
    forEachBlock(n, [&](size_t b, size_t begin, size_t end) {
        uint32_t c = 0;
        for (size_t i = begin; i < end; ++i) c += flags[i] != 0;
        offsets[b] = c;
    });
    uint32_t total = 0;
    for (uint32_t& o : offsets) total += std::exchange(o, total);
    forEachBlock(n, [&](size_t b, size_t begin, size_t end) {
        uint32_t p = offsets[b];
        for (size_t i = begin; i < end; ++i)
            if (flags[i] != 0) out[p++] = uint32_t(i);
    });
    return total;
}

double sumCpu(Span<const float> in) {
    std::vector<double> partial(blockCount(in.size()));
    forEachBlock(in.size(), [&](size_t b, size_t begin, size_t end) {
        double s = 0.0;
        for (size_t i = begin; i < end; ++i) s += double(in[i]);
        partial[b] = s;
    });
    double total = 0.0;
    for (double p : partial) total += p;
    return total;
}

uint64_t sumCpu(Span<const uint32_t> in) {
    std::vector<uint64_t> partial(blockCount(in.size()));
    forEachBlock(in.size(), [&](size_t b, size_t begin, size_t end) {
        uint64_t s = 0;
        for (size_t i = begin; i < end; ++i) s += in[i];
        partial[b] = s;
    });
    uint64_t total = 0;
    for (uint64_t p : partial) total += p;
    return total;
}

Float maxCpu(Span<const float> in) {
    std::vector<float> partial(blockCount(in.size()));
    forEachBlock(in.size(), [&](size_t b, size_t begin, size_t end) {
        float m = -std::numeric_limits<float>::infinity();
        for (size_t i = begin; i < end; ++i) m = in[i] > m ? in[i] : m;
        partial[b] = m;
    });
    float m = -std::numeric_limits<float>::infinity();
    for (float p : partial) m = p > m ? p : m;
    return m;
}

}  // namespace

uint32_t exclusiveScan(const Device& device, Span<const uint32_t> in, Span<uint32_t> out) {
    require(out.size() >= in.size(), "exclusiveScan",
            "output of " + std::to_string(out.size()) + " for " + std::to_string(in.size()) +
                " inputs");
    if (in.empty()) return 0;
    if (device.isCpu()) return scanCpu(in, out);
    return requireGpuBackend("exclusiveScan").exclusiveScan(in.data(), out.data(), in.size());
}

void radixSortPairs(const Device& device, Span<uint64_t> keys, Span<uint32_t> values, int keyBits) {
    radixSortChecked(device, keys, values, keyBits);
}

void radixSortPairs(const Device& device, Span<uint32_t> keys, Span<uint32_t> values, int keyBits) {
    radixSortChecked(device, keys, values, keyBits);
}

uint32_t compactIndices(const Device& device, Span<const uint32_t> flags,
                        Span<uint32_t> outIndices) {
    require(outIndices.size() >= flags.size(), "compactIndices",
            "output of " + std::to_string(outIndices.size()) + " for " +
                std::to_string(flags.size()) + " flags");
    require(flags.size() <= size_t(std::numeric_limits<uint32_t>::max()), "compactIndices",
            "more than 2^32 - 1 flags");
    if (flags.empty()) return 0;
    if (device.isCpu()) return compactCpu(flags, outIndices);
    return requireGpuBackend("compactIndices")
        .compactIndices(flags.data(), outIndices.data(), flags.size());
}

double reduceSum(const Device& device, Span<const float> in) {
    if (in.empty()) return 0.0;
    if (device.isCpu()) return sumCpu(in);
    return requireGpuBackend("reduceSum").reduceSum(in.data(), in.size());
}

uint64_t reduceSum(const Device& device, Span<const uint32_t> in) {
    if (in.empty()) return 0;
    if (device.isCpu()) return sumCpu(in);
    const GpuBackend& backend = requireGpuBackend("reduceSum");
    if (!backend.reduceSumU32) throw Error("reduceSum: the GPU backend has no 32-bit integer sum");
    return backend.reduceSumU32(in.data(), in.size());
}

Float reduceMax(const Device& device, Span<const float> in) {
    if (in.empty()) return -std::numeric_limits<Float>::infinity();
    if (device.isCpu()) return maxCpu(in);
    return requireGpuBackend("reduceMax").reduceMax(in.data(), in.size());
}

}  // namespace caustica
