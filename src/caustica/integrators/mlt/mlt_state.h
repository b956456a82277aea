// mlt_state.h — the primary-sample vectors of many Markov chains, stored compactly, and the
// proposals made from them on the fly (Frolov & Galaktionov 2017, sec. 3.2).
//
// A chain keeps only its current state: the primary samples (uniform numbers in [0, 1)) that the
// path tracer consumed to build its current path, and how many it consumed (U). A proposal is
// never stored: coordinate d of proposal j at iteration t is a pure function of (current value,
// d, hash(seed, chain, t, j)), so it is computed when the path tracer asks for it (lazily, per
// coordinate), and the accepted proposal's used coordinates are recomputed into the state.
// Coordinates at or past U play no part in the current path; under the target distribution they
// are uniform given the used ones (U is a stopping time of the path tracer's reads), so they are
// refreshed by drawing them anew — a Gibbs step composed with Kelemen's symmetric perturbation of
// the used ones (Kelemen et al. 2002) — and need not be stored. The work per step is then
// proportional to the path's length, not to the maximum depth.
//
// Layout of a path's primary samples (path_kernel.h draws a fixed number per bounce):
//   0, 1            film position (x / width, y / height)
//   2, 3            lens position (thin lens; drawn for every camera so the layout is fixed)
//   4 + 7 b + ...   bounce b: light choice, light point (2), BSDF lobe, BSDF direction (2), roulette
// Continuous choices (film and lens position, light point, BSDF direction) need the full 24 bits a float in
// [0, 1) carries; discrete ones (light and lobe selection, roulette) are stored in 16 bits.
// Coordinates past the stored bounces are likewise drawn anew at each proposal.
#pragma once

#include <cmath>
#include <cstdint>

#include "caustica/util/math.h"
#include "caustica/util/rng.h"

namespace caustica {

inline constexpr uint32_t kMltCameraDims = 4;
inline constexpr uint32_t kMltDimsPerBounce = 7;
/// Coarse (16-bit) coordinates inside a bounce: light choice, BSDF lobe, roulette.
CA_HD_INLINE bool isCoarseDim(uint32_t dim) {
    if (dim < kMltCameraDims) return false;
    const uint32_t k = (dim - kMltCameraDims) % kMltDimsPerBounce;
    return k == 0 || k == 3 || k == 6;
}
/// Primary dimensions a chain stores for `bounces` bounces.
CA_HD_INLINE constexpr uint32_t mltStoredDims(uint32_t bounces) { return kMltCameraDims + kMltDimsPerBounce * bounces; }

/// Kelemen's small-step perturbation: |offset| = s2 exp(-ln(s2 / s1) u), sign random
/// (Kelemen et al. 2002, sec. 4.1). Sizes are fractions of the unit interval.
struct MltMutation {
    Float s1 = 1.0f / 1024.0f;
    Float s2 = 1.0f / 64.0f;
};

/// Kelemen's step sizes ready to draw from: log2(s2 / s1) computed once per proposal.
struct KelemenStep {
    float s2 = 0, log2Ratio = 0;
    KelemenStep() = default;
    CA_HD explicit KelemenStep(const MltMutation& m) : s2(float(m.s2)), log2Ratio(log2f(float(m.s2 / m.s1))) {}
    /// |offset| = s2 (s1 / s2)^u, u from bits 39..62 of `bits` (bit 63 is the sign).
    CA_HD float magnitude(uint64_t bits) const {
        const float u = float(uint32_t(bits >> 39) & 0xffffffu) * 0x1p-24f;
        return s2 * exp2Approx(-log2Ratio * u);
    }
    CA_HD static bool negative(uint64_t bits) { return (bits >> 63) != 0; }
};

/// The random bits behind coordinate `dim` of the proposal stream `key`.
CA_HD_INLINE uint64_t proposalBits(uint64_t key, uint32_t dim) {
    return mix64(key + 0x9e3779b97f4a7c15ull * (uint64_t(dim) + 1));
}

/// Chain states in fixed point: 24 bits per continuous coordinate (3 bytes), 16 bits per discrete
/// one. Values v stand for v / 2^bits. A small step moves by the offset rounded to the grid
/// (round-to-nearest keeps the step symmetric), modulo 1; a large step draws a grid value.
/// Coordinate d of chain c lives at c * chainStride + d * dimStride (fine and coarse coordinates
/// are numbered separately): chain-major on the CPU, dimension-major for coalescing on a GPU.
struct CompactChainStore {
    using Raw = uint32_t;
    uint8_t* fine = nullptr;     // 3 bytes per continuous coordinate, little endian
    uint16_t* coarse = nullptr;  // discrete coordinates
    uint32_t dims = 0;           // stored coordinates per chain
    size_t fineChainStride = 0, fineDimStride = 0;      // in 3-byte units
    size_t coarseChainStride = 0, coarseDimStride = 0;  // in uint16 units

    /// Index of `dim` among the fine (or coarse) coordinates of a chain.
    CA_HD static uint32_t slotOf(uint32_t dim) {
        if (dim < kMltCameraDims) return dim;
        const uint32_t b = (dim - kMltCameraDims) / kMltDimsPerBounce;
        const uint32_t k = (dim - kMltCameraDims) % kMltDimsPerBounce;
        // fine: 1, 2, 4, 5 -> 0..3; coarse: 0, 3, 6 -> 0..2
        const uint32_t fineRank = k < 3 ? k - 1 : k - 2;
        return isCoarseDim(dim) ? b * 3 + k / 3 : kMltCameraDims + b * 4 + fineRank;
    }
    static constexpr size_t bytesPerDims(uint32_t bounces) { return kMltCameraDims * 3 + bounces * (4 * 3 + 3 * 2); }

    CA_HD Raw get(uint32_t chain, uint32_t dim) const {
        const uint32_t s = slotOf(dim);
        if (isCoarseDim(dim)) return coarse[chain * coarseChainStride + s * coarseDimStride];
        const uint8_t* p = fine + 3 * (chain * fineChainStride + s * fineDimStride);
        return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16);
    }
    CA_HD void set(uint32_t chain, uint32_t dim, Raw v) const {
        const uint32_t s = slotOf(dim);
        if (isCoarseDim(dim)) {
            coarse[chain * coarseChainStride + s * coarseDimStride] = uint16_t(v);
            return;
        }
        uint8_t* p = fine + 3 * (chain * fineChainStride + s * fineDimStride);
        p[0] = uint8_t(v);
        p[1] = uint8_t(v >> 8);
        p[2] = uint8_t(v >> 16);
    }
    CA_HD static int bitsOf(uint32_t dim) { return isCoarseDim(dim) ? 16 : 24; }
    CA_HD static Float toFloat(Raw v, uint32_t dim) { return Float(v) * (isCoarseDim(dim) ? 0x1p-16f : 0x1p-24f); }
    CA_HD static Raw large(uint64_t bits, uint32_t dim) { return uint32_t(bits >> (64 - bitsOf(dim))); }
    CA_HD static Raw small(Raw v, uint64_t bits, uint32_t dim, const KelemenStep& step) {
        const int n = bitsOf(dim);
        // The magnitude is rounded, then signed: exactly mirror-symmetric on the grid.
        const uint32_t delta = uint32_t(step.magnitude(bits) * float(1u << n) + 0.5f);
        const uint32_t moved = KelemenStep::negative(bits) ? v - delta : v + delta;
        return moved & ((1u << n) - 1);
    }
};

/// Chain states as plain float32 per coordinate: the baseline the compact store is measured against.
/// A small step is the float sum wrapped to [0, 1).
struct FloatChainStore {
    using Raw = float;
    float* values = nullptr;
    uint32_t dims = 0;
    size_t chainStride = 0, dimStride = 0;

    static constexpr size_t bytesPerDims(uint32_t bounces) { return sizeof(float) * mltStoredDims(bounces); }
    CA_HD Raw get(uint32_t chain, uint32_t dim) const { return values[chain * chainStride + dim * dimStride]; }
    CA_HD void set(uint32_t chain, uint32_t dim, Raw v) const { values[chain * chainStride + dim * dimStride] = v; }
    CA_HD static Float toFloat(Raw v, uint32_t) { return v; }
    CA_HD static Raw large(uint64_t bits, uint32_t) { return uniformFloat(bits); }
    CA_HD static Raw small(Raw v, uint64_t bits, uint32_t, const KelemenStep& step) {
        const double offset = double(step.magnitude(bits));  // below s2 < 1: one wrap is enough
        double x = KelemenStep::negative(bits) ? double(v) - offset : double(v) + offset;
        x = x < 0 ? x + 1 : (x >= 1 ? x - 1 : x);
        const float f = float(x);
        return f < 1.0f ? f : 0.0f;  // x just below 1 may round up to 1
    }
};

/// One proposal of one chain as a sampler for the path tracer (the get1D/get2D interface of
/// IndependentSampler): coordinate d is the current value perturbed by the proposal's stream when
/// the current path used it (d < `currentDims`), else — and for a large step — a fresh value,
/// computed when asked for. `store == nullptr` (or currentDims = 0) makes every coordinate fresh
/// (bootstrap). dimension() afterwards is U of the proposal's path.
template <class Store>
class MltProposalSampler {
public:
    /// A sampler to assign to (the lanes of a work item that traces several proposals).
    MltProposalSampler() = default;
    CA_HD MltProposalSampler(const Store* store, uint32_t chain, uint32_t currentDims, uint64_t key,
                             bool largeStep, const MltMutation& mutation)
        : store_(store), chain_(chain), current_(store ? min(currentDims, store->dims) : 0), key_(key),
          large_(largeStep), step_(largeStep ? KelemenStep{} : KelemenStep(mutation)) {}

    /// Coordinate `dim` of this proposal in the store's representation.
    CA_HD typename Store::Raw raw(uint32_t dim) const {
        const uint64_t bits = proposalBits(key_, dim);
        if (large_ || dim >= current_) return Store::large(bits, dim);
        return Store::small(store_->get(chain_, dim), bits, dim, step_);
    }
    CA_HD Float get1D() {
        const uint32_t d = dim_++;
        return Store::toFloat(raw(d), d);
    }
    CA_HD Vec2f get2D() {
        const Float a = get1D();
        return {a, get1D()};
    }
    CA_HD uint32_t dimension() const { return dim_; }

private:
    const Store* store_ = nullptr;
    uint32_t chain_ = 0;
    uint32_t current_ = 0;  // coordinates of the current state that may be perturbed
    uint64_t key_ = 0;
    bool large_ = true;
    KelemenStep step_;
    uint32_t dim_ = 0;
};

}  // namespace caustica
