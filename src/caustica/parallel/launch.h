// launch.h — single-source drivers: the device as a type, so that one driver text compiles for
// the CPU (g++, caustica_integrators) and for the GPU (nvcc: cuda/*_driver.cu includes the same
// .cpp files, pbrt-v4's way).
//
//     template <class Exec> void shade(Exec exec, float* out, size_t n) {
//         launch(exec, "shade", n, [=] CA_HD (size_t i) { out[i] = 0; });
//     }
//
// A kernel is a lambda over an index that captures by value (spans, views, device pointers).
// `DriverExec` is the device the current compiler builds drivers for: CpuExec under g++, GpuExec
// under nvcc. A driver .cpp defines its factory for DriverExec only; onDevice() picks the one for
// a runtime Device (the GPU's exists when the build has CUDA: CAUSTICA_WITH_CUDA).
//
// nvcc's rules for kernel lambdas (extended lambdas) apply to driver code: define them in named
// functions or public member functions, never inside a generic lambda or a private member.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "caustica/parallel/device.h"
#include "caustica/util/error.h"
#include "caustica/util/platform.h"

#if defined(__CUDACC__)
#include "cuda/parallel_for_cuda.h"
#endif

namespace caustica {

/// Kernels on CPU threads (TBB).
struct CpuExec {
    static constexpr DeviceKind kind = DeviceKind::Cpu;
    static Device device() { return Device::cpu(); }
};

/// Kernels run one after another in the calling CPU thread: for a driver that already spreads
/// independent work over the CPU's threads one level up (the wavefront path tracer traces one
/// chunk of paths per thread this way, each chunk's stages as serial loops).
struct SerialExec {
    static constexpr DeviceKind kind = DeviceKind::Cpu;
    static Device device() { return Device::cpu(); }
};

/// Kernels as CUDA grids on the current GPU (only nvcc-compiled code launches them).
struct GpuExec {
    static constexpr DeviceKind kind = DeviceKind::Cuda;
    static Device device() { return Device::cuda(); }
};

#if defined(__CUDACC__)
using DriverExec = GpuExec;
#else
using DriverExec = CpuExec;
#endif

/// Runs kernel(i) for every i in [0, n) on the CPU's thread pool, `grain` items per task.
template <class Kernel>
void launch(CpuExec, const char* name, size_t n, const Kernel& kernel, size_t grain = 64) {
    parallelFor(Device::cpu(), name, n, kernel, grain);
}

/// Runs kernel(i) for i = 0, 1, ..., n - 1 in order, in the calling thread.
template <class Kernel>
void launch(SerialExec, const char* name, size_t n, const Kernel& kernel, size_t grain = 64) {
    (void)grain;
    KernelTimer timer(name);
    for (size_t i = 0; i < n; ++i) kernel(i);
}

/// The number of CPU threads that kernels launched from here may run on: the current task
/// arena's concurrency, bounded by a tbb::global_control (the --threads option).
inline size_t cpuThreadCount() {
    const size_t arena = size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
    const size_t allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    return std::max<size_t>(1, std::min(arena, allowed));
}

#if defined(__CUDACC__)
/// Runs kernel(i) for every i in [0, n) as a CUDA grid (asynchronous; `grain` is the CPU's).
template <class Kernel>
void launch(GpuExec, const char* name, size_t n, const Kernel& kernel, size_t grain = 64) {
    (void)grain;
    parallelForCuda(name, n, kernel);
}
#endif

/// make(CpuExec{}) or make(GpuExec{}) for `device`: where a runtime device choice meets the
/// drivers compiled per device. Without CUDA in the build a GPU is refused with an Error.
template <class Make>
auto onDevice(const Device& device, Make&& make) {
    if (device.isCpu()) return std::forward<Make>(make)(CpuExec{});
#if defined(CAUSTICA_WITH_CUDA)
    return std::forward<Make>(make)(GpuExec{});
#else
    throw Error("this caustica was built without CUDA: render with --device cpu");
#endif
}

}  // namespace caustica
