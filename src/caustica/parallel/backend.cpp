// backend.cpp — the GPU backend registry and device memory dispatch.
#include "caustica/parallel/backend.h"

#include <atomic>
#include <cstring>
#include <new>
#include <string>

#include "caustica/util/error.h"

namespace caustica {

namespace {
std::atomic<const GpuBackend*> gBackend{nullptr};
constexpr std::align_val_t kHostAlignment{64};
}  // namespace

const char* deviceName(DeviceKind kind) {
    return kind == DeviceKind::Cuda ? "cuda" : "cpu";
}

void setGpuBackend(const GpuBackend* backend) {
    gBackend.store(backend);
}

const GpuBackend* gpuBackend() {
    return gBackend.load();
}

const GpuBackend& requireGpuBackend(const char* what) {
    const GpuBackend* backend = gBackend.load();
    if (!backend) {
        throw Error(std::string(what) +
                    ": no GPU backend (built without CUDA, or registerCudaBackend() not called)");
    }
    return *backend;
}

int gpuDeviceCount() {
    const GpuBackend* backend = gBackend.load();
    return backend ? backend->deviceCount() : 0;
}

bool gpuMemoryInfo(size_t& freeBytes, size_t& totalBytes) {
    freeBytes = totalBytes = 0;
    const GpuBackend* backend = gpuBackend();
    return backend && backend->memoryInfo(freeBytes, totalBytes);
}

size_t gpuPeakBytes() {
    const GpuBackend* backend = gpuBackend();
    return backend ? backend->peakBytes() : 0;
}

void resetGpuPeakBytes() {
    if (const GpuBackend* backend = gpuBackend()) backend->resetPeakBytes();
}

std::string gpuDescription() {
    const GpuBackend* backend = gpuBackend();
    return backend ? backend->describe() : std::string();
}

void selectGpu(int index) {
    const GpuBackend& backend = requireGpuBackend("--gpu");
    const int count = backend.deviceCount();
    if (index < 0 || index >= count)
        throw Error("--gpu " + std::to_string(index) + ": no such GPU (this host has " + std::to_string(count) + ")");
    if (!backend.setDevice) throw Error("--gpu: the GPU backend cannot choose a GPU");
    backend.setDevice(index);
}

namespace detail {

[[noreturn]] void throwHostLaunchOnGpu(const char* name) {
    throw Error(std::string("parallelFor '") + (name ? name : "?") +
                "': a host-compiled kernel cannot run on a CUDA device; launch it with "
                "launch() (parallel/launch.h) from a driver compiled for the GPU");
}

void* allocateOn(const Device& device, size_t bytes) {
    if (bytes == 0) return nullptr;
    if (device.isCpu()) return ::operator new(bytes, kHostAlignment);
    return requireGpuBackend("Buffer allocation").allocate(bytes);
}

void releaseOn(const Device& device, void* ptr) noexcept {
    if (!ptr) return;
    if (device.isCpu()) {
        ::operator delete(ptr, kHostAlignment);
    } else if (const GpuBackend* backend = gpuBackend()) {
        backend->release(ptr);
    }
}

void copyOn(const Device& device, void* dst, const void* src, size_t bytes) {
    if (bytes == 0) return;
    if (device.isCpu()) {
        std::memmove(dst, src, bytes);
    } else {
        requireGpuBackend("Buffer copy").copy(dst, src, bytes);
    }
}

void zeroOn(const Device& device, void* dst, size_t bytes) {
    if (bytes == 0) return;
    if (device.isCpu()) {
        std::memset(dst, 0, bytes);
    } else {
        requireGpuBackend("Buffer zero").zero(dst, bytes);
    }
}

void synchronizeOn(const Device& device) {
    if (!device.isCpu()) requireGpuBackend("synchronize").synchronize();
}

}  // namespace detail
}  // namespace caustica
