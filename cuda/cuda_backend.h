// cuda_backend.h — the host entry of the CUDA backend (plain C++: includable without nvcc).
#pragma once

#include <cstddef>
#include <string>

namespace caustica {

/// Installs the CUDA implementations of device memory and the parallel primitives
/// (cuda/primitives_cuda.cu) as the parallel layer's GPU backend (see parallel/backend.h), so
/// that Buffer<T> and the primitives accept Device::cuda(). Idempotent; call it once at start-up
/// from a program that links caustica_cuda. It does not touch the GPU.
void registerCudaBackend();

/// The number of CUDA devices; 0 when there is no GPU or no driver. Never throws.
int cudaDeviceCountOrZero();

/// Device memory held through the backend: Buffer<T> allocations and the primitives' scratch
/// (CUB temporaries), in bytes. `peak` is the high-water mark since the last resetCudaPeakBytes().
struct CudaMemoryCounters {
    size_t current = 0;
    size_t peak = 0;
};
CudaMemoryCounters cudaMemoryCounters();
/// Sets the peak to the current figure.
void resetCudaPeakBytes();

/// Free and total memory of the current device (cudaMemGetInfo); false (and zeros) without a GPU.
/// Never throws. Creates the CUDA context if there is none yet.
bool cudaMemoryInfo(size_t& freeBytes, size_t& totalBytes);

/// "NVIDIA H200 (sm_90, 139.8 GiB)" for the current device; "" without a GPU. Never throws.
std::string cudaDeviceDescription();
}  // namespace caustica
