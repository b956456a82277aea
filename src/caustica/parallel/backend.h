// backend.h — how the parallel layer reaches a GPU without depending on CUDA.
//
// caustica_parallel is plain C++ (TBB). The CUDA library (cuda/, built only when nvcc exists)
// fills a GpuBackend table with its implementations and installs it with setGpuBackend(), which
// `registerCudaBackend()` from cuda/cuda_backend.h does. Buffer and the primitives dispatch on
// Device::kind: CPU code runs here, CUDA calls go through the table. Arrows point down only:
// caustica_cuda -> caustica_parallel -> caustica_util.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "caustica/parallel/device.h"

namespace caustica {

/// The GPU entry points of the parallel layer. All pointers are device pointers except where a
/// copy names host memory; `copy` infers the direction (unified addressing). Every function
/// throws caustica::Error on failure except `release` and `deviceCount`, which never throw.
/// Counts are element counts; the callers in primitives.cpp have already checked sizes and n > 0.
struct GpuBackend {
    const char* name = nullptr;
    int (*deviceCount)() = nullptr;
    void* (*allocate)(size_t bytes) = nullptr;
    void (*release)(void* ptr) = nullptr;
    void (*copy)(void* dst, const void* src, size_t bytes) = nullptr;
    void (*zero)(void* dst, size_t bytes) = nullptr;
    void (*synchronize)() = nullptr;
    uint32_t (*exclusiveScan)(const uint32_t* in, uint32_t* out, size_t n) = nullptr;
    void (*sortPairs64)(uint64_t* keys, uint32_t* values, size_t n, int keyBits) = nullptr;
    void (*sortPairs32)(uint32_t* keys, uint32_t* values, size_t n, int keyBits) = nullptr;
    uint32_t (*compactIndices)(const uint32_t* flags, uint32_t* out, size_t n) = nullptr;
    double (*reduceSum)(const float* in, size_t n) = nullptr;
    float (*reduceMax)(const float* in, size_t n) = nullptr;
    uint64_t (*reduceSumU32)(const uint32_t* in, size_t n) = nullptr;  // in 64 bits
    /// Free and total memory of the current GPU; false (and zeros) without one. Never throws.
    bool (*memoryInfo)(size_t& freeBytes, size_t& totalBytes) = nullptr;
    /// Bytes held through the backend at most since the last resetPeakBytes. Never throw.
    size_t (*peakBytes)() = nullptr;
    void (*resetPeakBytes)() = nullptr;
    /// "NVIDIA H200 (sm_90, 139.8 GiB)"; "" without a GPU. Never throws.
    std::string (*describe)() = nullptr;
    /// Makes GPU `index` (0 .. deviceCount()-1) the current one of this process (cudaSetDevice):
    /// one GPU per MPI rank. Throws caustica::Error.
    void (*setDevice)(int index) = nullptr;
};

/// Installs (or with nullptr removes) the GPU backend. The table must outlive its use.
void setGpuBackend(const GpuBackend* backend);
/// The installed GPU backend, or nullptr when none is (CPU-only build or not registered).
const GpuBackend* gpuBackend();
/// The installed backend; throws caustica::Error naming `what` when there is none.
const GpuBackend& requireGpuBackend(const char* what);
/// GPUs visible through the installed backend; 0 without one.
int gpuDeviceCount();
/// The backend's memory figures and description (GpuBackend); false, 0 and "" without one.
bool gpuMemoryInfo(size_t& freeBytes, size_t& totalBytes);
size_t gpuPeakBytes();
void resetGpuPeakBytes();
std::string gpuDescription();
/// Makes GPU `index` the one this process renders on, before anything is allocated on a GPU;
/// throws caustica::Error (one line) without a backend or for an index it does not have.
void selectGpu(int index);

namespace detail {
/// Raw memory on a device: 64-byte aligned host memory on the CPU, cudaMalloc on CUDA.
void* allocateOn(const Device& device, size_t bytes);
void releaseOn(const Device& device, void* ptr) noexcept;
/// Copies bytes between host memory and memory of `device` (either direction) or within it.
void copyOn(const Device& device, void* dst, const void* src, size_t bytes);
void zeroOn(const Device& device, void* dst, size_t bytes);
/// Waits for every kernel launched on `device` (a no-op on the CPU, whose launches return done).
void synchronizeOn(const Device& device);
}  // namespace detail

}  // namespace caustica
