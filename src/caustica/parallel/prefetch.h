// prefetch.h — a hint to the CPU's caches that kernel code may give for memory it will read
// soon (a later work item's data); nothing on a GPU, whose warps hide memory latency instead.
#pragma once

#include "caustica/util/platform.h"

namespace caustica {

/// Starts loading the cache line of `p` for reading; never faults (an address past an array is
/// harmless). Compiles to nothing in device code.
CA_HD_INLINE void prefetchRead(const void* p) {
#if !defined(__CUDA_ARCH__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_prefetch(p, 0, 3);
#else
    (void)p;
#endif
}

}  // namespace caustica
