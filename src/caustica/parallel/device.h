// device.h — where kernels run. A kernel is a callable over an index, launched by name with
// parallelFor(device, "name", n, kernel). On the CPU it runs on the TBB thread pool; the CUDA
// backend (cuda/) launches the same callable as a grid.
#pragma once

#include <cstddef>
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace caustica {

enum class DeviceKind { Cpu, Cuda };

struct Device {
    DeviceKind kind = DeviceKind::Cpu;
    static Device cpu() { return Device{DeviceKind::Cpu}; }
};

/// Runs kernel(i) for every i in [0, n). Work is chunked by `grain` on the CPU. `name` identifies
/// the launch (for timing and for debug checks on the GPU).
template <class Kernel>
void parallelFor(const Device& device, const char* name, size_t n, Kernel&& kernel, size_t grain = 64) {
    (void)name;
    (void)device;  // the CPU path; DeviceKind::Cuda dispatches in the CUDA backend
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) kernel(i);
    });
}

}  // namespace caustica
