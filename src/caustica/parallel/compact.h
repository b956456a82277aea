// compact.h — stream compaction of a queue by flags, single source (launch.h): the kept entries
// in order. A GPU (and a parallel CPU launch) compacts the flags with compactIndices and then
// gathers; a SerialExec caller, already one of many CPU threads, does both in one serial pass.
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"

namespace caustica {

/// Writes queue[q] for every q in [0, count) with flags[q] != 0 to `out`, in order, and returns
/// how many. `selected` is scratch of `count` entries (unused by SerialExec); `out` must not
/// overlap `queue`.
template <class Exec>
uint32_t compactQueue(Exec exec, const uint32_t* flags, const uint32_t* queue, size_t count, uint32_t* selected,
                      uint32_t* out) {
    if (count == 0) return 0;
    const uint32_t kept = compactIndices(Exec::device(), Span<const uint32_t>(flags, count),
                                         Span<uint32_t>(selected, count));
    launch(exec, "compact.gather", kept, [=] CA_HD(size_t q) { out[q] = queue[selected[q]]; }, 256);
    return kept;
}

inline uint32_t compactQueue(SerialExec, const uint32_t* flags, const uint32_t* queue, size_t count,
                             uint32_t* /*selected*/, uint32_t* out) {
    uint32_t kept = 0;
    for (size_t q = 0; q < count; ++q) {  // branch-free: the flags are unpredictable
        out[kept] = queue[q];
        kept += flags[q] != 0;
    }
    return kept;
}

}  // namespace caustica
