// device.h — where kernels run. A kernel is a callable over an index, launched by name with
// parallelFor(device, "name", n, kernel). On the CPU it runs on the TBB thread pool; the CUDA
// backend (cuda/parallel_for_cuda.h, nvcc only) launches the same callable as a grid.
#pragma once

#include <cstddef>
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "caustica/parallel/kernel_stats.h"

namespace caustica {

enum class DeviceKind { Cpu, Cuda };

/// A place where kernels run and Buffers live. CUDA means the current CUDA device of the calling
/// thread; it is usable only when the CUDA backend is registered (see parallel/backend.h).
struct Device {
    DeviceKind kind = DeviceKind::Cpu;
    static Device cpu() { return Device{DeviceKind::Cpu}; }
    static Device cuda() { return Device{DeviceKind::Cuda}; }
    bool isCpu() const { return kind == DeviceKind::Cpu; }
    bool operator==(const Device&) const = default;
};

/// "cpu" or "cuda".
const char* deviceName(DeviceKind kind);

namespace detail {
/// Throws caustica::Error: a host-compiled parallelFor cannot launch on a GPU.
[[noreturn]] void throwHostLaunchOnGpu(const char* name);
}  // namespace detail

/// Runs kernel(i) for every i in [0, n). Work is chunked by `grain` on the CPU. `name` identifies
/// the launch for KernelStats (timed when enabled). A CUDA device throws caustica::Error here:
/// GPU launches go through launch(GpuExec, ...) (parallel/launch.h) in nvcc-compiled driver code.
template <class Kernel>
void parallelFor(const Device& device, const char* name, size_t n, Kernel&& kernel,
                 size_t grain = 64) {
    if (device.kind != DeviceKind::Cpu) detail::throwHostLaunchOnGpu(name);
    KernelTimer timer(name);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t i = r.begin(); i != r.end(); ++i) kernel(i);
                      });
}

}  // namespace caustica
