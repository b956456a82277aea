// prefetch.h — a hint to the CPU's caches that kernel code may give for memory it will read
// soon (a later work item's data); nothing on a GPU, whose warps hide memory latency instead.
#pragma once

#include "caustica/util/platform.h"

namespace caustica {

/// Starts loading the cache line of `p` for reading; never faults (an address past an array is
/// harmless). Compiles to nothing in device code.
///
/// The empty volatile asm gives the prefetch a side effect the optimiser must keep: g++ otherwise
/// finds a helper made only of prefetches (prefetchVertices, hit_prefetch.h) free of side effects,
/// marks it pure and deletes every call to it that it does not inline first (g++ 12, -O3).
CA_HD_INLINE void prefetchRead(const void* p) {
#if !defined(__CUDA_ARCH__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_prefetch(p, 0, 3);
    asm volatile("" : : "r"(p));
#else
    (void)p;
#endif
}

}  // namespace caustica
