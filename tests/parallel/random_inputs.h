// random_inputs.h — the input sizes and seeded random keys on which the CPU and the CUDA
// primitives tests run (test helper, host only).
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace caustica::test {

/// Input lengths of the primitives tests: empty, one element, small and large.
inline constexpr size_t kSizes[] = {0, 1, 1000, 1000000};

/// `n` values uniform in [0, maxValue] from a 64-bit Mersenne Twister seeded with `seed`.
inline std::vector<uint32_t> randomU32(size_t n, uint32_t maxValue, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<uint32_t> dist(0, maxValue);
    std::vector<uint32_t> v(n);
    for (auto& x : v) x = dist(rng);
    return v;
}

}  // namespace caustica::test
