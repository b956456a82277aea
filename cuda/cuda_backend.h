// cuda_backend.h — the host entry of the CUDA backend (plain C++: includable without nvcc).
#pragma once

namespace caustica {

/// Installs the CUDA implementations of device memory and the parallel primitives
/// (cuda/primitives_cuda.cu) as the parallel layer's GPU backend (see parallel/backend.h), so
/// that Buffer<T> and the primitives accept Device::cuda(). Idempotent; call it once at start-up
/// from a program that links caustica_cuda. It does not touch the GPU.
void registerCudaBackend();

/// The number of CUDA devices; 0 when there is no GPU or no driver. Never throws.
int cudaDeviceCountOrZero();

}  // namespace caustica
