// rng.h — counter-based random numbers: every value is a pure function of its coordinates
// (pixel or chain, sample index, dimension, seed), never of the thread that asks for it.
#pragma once

#include <cstdint>

#include "caustica/util/math.h"

namespace caustica {

/// 64-bit finaliser of SplitMix64 / MurmurHash3: a bijective, well-mixing hash.
CA_HD_INLINE uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// Hash of several 64-bit words, order-sensitive.
CA_HD_INLINE uint64_t hashCombine(uint64_t seed, uint64_t v) {
    return mix64(seed ^ (v + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2)));
}

/// Uniform float in [0, 1) from the top 24 bits of a 64-bit word.
CA_HD_INLINE Float uniformFloat(uint64_t bits) {
    return Float(uint32_t(bits >> 40)) * 0x1p-24f;
}

/// A sampler that draws independent uniform numbers for one sample of one pixel (or one chain):
/// value k of the stream is hash(streamKey, k). This is the interface every sampling routine
/// takes its numbers from (get1D/get2D), so that Metropolis can substitute its own sampler.
class IndependentSampler {
public:
    IndependentSampler() = default;
    /// `stream` identifies the pixel (or chain), `sampleIndex` the sample within it.
    CA_HD IndependentSampler(uint64_t stream, uint64_t sampleIndex, uint64_t seed)
        : key_(hashCombine(hashCombine(mix64(seed + 0x632be59bd9b4e019ull), stream), sampleIndex)) {}

    CA_HD Float get1D() { return uniformFloat(mix64(key_ + 0x9e3779b97f4a7c15ull * ++dimension_)); }
    CA_HD Vec2f get2D() {
        Float a = get1D();
        return {a, get1D()};
    }
    CA_HD uint32_t dimension() const { return dimension_; }

private:
    uint64_t key_ = 0;
    uint32_t dimension_ = 0;
};

}  // namespace caustica
