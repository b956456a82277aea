// parallel_for_cuda.h — parallelFor as a CUDA grid, for nvcc translation units (.cu) only.
//
// A kernel is the same lambda over an index as on the CPU, made callable on both sides:
//     parallelForDevice(device, "film_develop", n, [=] CA_HD (size_t i) { ... });
// A lambda with __device__ or __host__ __device__ annotations is an nvcc "extended lambda": the
// caustica_cuda target compiles with --extended-lambda (and propagates it to its users). nvcc
// rejects extended lambdas inside private or protected member functions (such as a gtest
// TEST body): define them in a free function. Captures are by value (device pointers, Spans).
#pragma once

#if !defined(__CUDACC__)
#error "cuda/parallel_for_cuda.h needs nvcc: include it from a .cu file"
#endif

#include <algorithm>
#include <cstddef>
#include <string>

#include <cuda_runtime.h>

#include "caustica/parallel/device.h"
#include "caustica/parallel/kernel_stats.h"
#include "cuda/cuda_check.h"

namespace caustica {

/// The grid behind parallelForCuda: a grid-stride loop over [0, n).
template <class Kernel>
__global__ void parallelForKernel(size_t n, Kernel kernel) {
    const size_t stride = size_t(gridDim.x) * blockDim.x;
    for (size_t i = size_t(blockIdx.x) * blockDim.x + threadIdx.x; i < n; i += stride) kernel(i);
}

/// A CUDA event owned for the duration of one timed launch.
class CudaEvent {
public:
    CudaEvent() { CA_CUDA_CHECK(cudaEventCreate(&event_)); }
    ~CudaEvent() { cudaEventDestroy(event_); }
    CudaEvent(const CudaEvent&) = delete;
    CudaEvent& operator=(const CudaEvent&) = delete;
    cudaEvent_t get() const { return event_; }

private:
    cudaEvent_t event_ = nullptr;
};

/// Launches kernel(i) for i in [0, n) on the current CUDA device (default stream, asynchronous
/// unless KernelStats is enabled: then it is timed with events and waits for the kernel).
/// Launch errors throw caustica::Error naming the kernel.
template <class Kernel>
void parallelForCuda(const char* name, size_t n, const Kernel& kernel, int blockSize = 256) {
    if (n == 0) return;
    const size_t maxBlocks = size_t(1) << 20;  // the grid-stride loop covers the rest
    const unsigned blocks =
        unsigned(std::min((n + size_t(blockSize) - 1) / size_t(blockSize), maxBlocks));
    const std::string what = std::string("launch of kernel '") + name + "'";
    if (!KernelStats::global().enabled()) {
        parallelForKernel<<<blocks, blockSize>>>(n, kernel);
        checkCuda(cudaGetLastError(), what.c_str(), __FILE__, __LINE__);
        return;
    }
    CudaEvent start, stop;
    CA_CUDA_CHECK(cudaEventRecord(start.get()));
    parallelForKernel<<<blocks, blockSize>>>(n, kernel);
    checkCuda(cudaGetLastError(), what.c_str(), __FILE__, __LINE__);
    CA_CUDA_CHECK(cudaEventRecord(stop.get()));
    CA_CUDA_CHECK(cudaEventSynchronize(stop.get()));
    float ms = 0.0f;
    CA_CUDA_CHECK(cudaEventElapsedTime(&ms, start.get(), stop.get()));
    KernelStats::global().record(name, double(ms));
}

/// Single-source launch: a grid on Device::cuda(), the TBB parallelFor on the CPU. The kernel
/// must be callable on host and device ([=] CA_HD (size_t i) { ... }).
template <class Kernel>
void parallelForDevice(const Device& device, const char* name, size_t n, const Kernel& kernel,
                       size_t grain = 64) {
    if (device.kind == DeviceKind::Cuda) {
        parallelForCuda(name, n, kernel);
    } else {
        parallelFor(device, name, n, kernel, grain);
    }
}

}  // namespace caustica
