// primitives.h — data-parallel building blocks with one API on the CPU (TBB) and CUDA (CUB).
//
// Used by the wavefront path tracer (compaction of active paths), Metropolis (sorting splats by
// pixel, Morton-sorting chains, prefix sums) and photon mapping (counting sort into hash grids).
// Spans are memory of `device` (Buffer<T>::span()); every call is synchronous with respect to
// the returned value. CPU results do not depend on the number of threads.
#pragma once

#include <cstdint>

#include "caustica/parallel/buffer.h"
#include "caustica/parallel/device.h"
#include "caustica/util/math.h"
#include "caustica/util/span.h"

namespace caustica {

/// A read-only view of the same elements.
template <class T>
Span<const T> asConst(Span<T> s) {
    return Span<const T>(s.data(), s.size());
}

/// out[i] = in[0] + ... + in[i-1] (modulo 2^32); returns the sum of all of `in`. `out` may be
/// `in` (in place) and needs at least in.size() elements.
uint32_t exclusiveScan(const Device& device, Span<const uint32_t> in, Span<uint32_t> out);

/// Sorts (keys[i], values[i]) by key, ascending and stable, in place. Only key bits
/// [0, keyBits) are compared (higher bits are kept but ignored); fewer bits means fewer passes.
/// values.size() must equal keys.size(). Scratch memory of the size of the input is allocated
/// inside each call.
void radixSortPairs(const Device& device, Span<uint64_t> keys, Span<uint32_t> values,
                    int keyBits = 64);
void radixSortPairs(const Device& device, Span<uint32_t> keys, Span<uint32_t> values,
                    int keyBits = 32);

/// Writes the indices i with flags[i] != 0, in increasing order, to outIndices and returns how
/// many there are. outIndices needs at least flags.size() elements (the worst case);
/// flags.size() must be below 2^32.
uint32_t compactIndices(const Device& device, Span<const uint32_t> flags,
                        Span<uint32_t> outIndices);

/// The sum of `in`, accumulated in double (0 when empty). The CPU sums fixed blocks, so the
/// result is reproducible; the GPU agrees up to rounding.
double reduceSum(const Device& device, Span<const float> in);
/// The sum of `in` in 64 bits (0 when empty): exact, so CPU and GPU agree bit for bit (counters
/// such as rays or accepted moves; CUB DeviceReduce on the GPU).
uint64_t reduceSum(const Device& device, Span<const uint32_t> in);

/// The largest element of `in` (-infinity when empty; NaNs give an unspecified result).
Float reduceMax(const Device& device, Span<const float> in);

}  // namespace caustica
