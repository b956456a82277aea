// atomic.h — atomic float addition in shared kernel code (hardware atomicAdd on the GPU,
// std::atomic_ref on the CPU).
#pragma once

#include <atomic>

#include "caustica/util/platform.h"

namespace caustica {

CA_HD_INLINE void atomicAddFloat(float* address, float value) {
#if CA_GPU_CODE
    atomicAdd(address, value);
#else
    std::atomic_ref<float>(*address).fetch_add(value, std::memory_order_relaxed);
#endif
}

}  // namespace caustica
