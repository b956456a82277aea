// primitives_cuda.cu — the CUDA backend of the parallel layer: device memory (cudaMalloc, never
// managed memory) and the primitives on CUB. registerCudaBackend() installs them into the
// GpuBackend table of caustica_parallel (parallel/backend.h). Every call is on the default
// stream; functions that return a value synchronize by copying it back. Scratch memory is
// allocated per call. Every CUDA call is checked (caustica::Error on failure).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>
#include <unordered_map>

#include <thrust/iterator/counting_iterator.h>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>

#include "caustica/parallel/backend.h"
#include "cuda/cuda_backend.h"
#include "cuda/cuda_check.h"

namespace caustica {
namespace {

/// Every cudaMalloc of the backend goes through trackedMalloc/trackedFree, which keep the bytes
/// held and their high-water mark (cudaMemoryCounters()).
struct AllocationTracker {
    std::mutex mutex;
    std::unordered_map<const void*, size_t> sizes;
    size_t current = 0, peak = 0;
};

AllocationTracker& tracker() {
    static AllocationTracker t;  // never destroyed before the last Buffer (function-local static)
    return t;
}

/// cudaMalloc that throws caustica::Error (never a crash) on failure, out of memory included, and
/// clears the (non-sticky) error state so that the process can go on, e.g. on the CPU.
void* trackedMalloc(size_t bytes) {
    void* ptr = nullptr;
    const cudaError_t status = cudaMalloc(&ptr, bytes);
    if (status != cudaSuccess) {
        (void)cudaGetLastError();
        checkCuda(status, ("cudaMalloc of " + std::to_string(bytes) + " bytes").c_str(), __FILE__,
                  __LINE__);
    }
    AllocationTracker& t = tracker();
    std::lock_guard<std::mutex> lock(t.mutex);
    t.sizes[ptr] = bytes;
    t.current += bytes;
    t.peak = std::max(t.peak, t.current);
    return ptr;
}

/// cudaFree; never throws (destructors call it): failures are reported on stderr and cleared.
void trackedFree(void* ptr) {
    if (!ptr) return;
    {
        AllocationTracker& t = tracker();
        std::lock_guard<std::mutex> lock(t.mutex);
        auto it = t.sizes.find(ptr);
        if (it != t.sizes.end()) {
            t.current -= it->second;
            t.sizes.erase(it);
        }
    }
    const cudaError_t status = cudaFree(ptr);
    if (status != cudaSuccess) {
        std::fprintf(stderr, "caustica: cudaFree failed: %s\n", cudaGetErrorString(status));
        (void)cudaGetLastError();
    }
}

/// Device memory released when the scope ends (CUB temporary storage, alternate sort buffers).
class DeviceScratch {
public:
    explicit DeviceScratch(size_t bytes) {
        if (bytes > 0) ptr_ = trackedMalloc(bytes);
    }
    ~DeviceScratch() { trackedFree(ptr_); }
    DeviceScratch(const DeviceScratch&) = delete;
    DeviceScratch& operator=(const DeviceScratch&) = delete;
    void* get() const { return ptr_; }
    template <class T>
    T* as() const {
        return static_cast<T*>(ptr_);
    }

private:
    void* ptr_ = nullptr;
};

template <class T>
T downloadOne(const T* devicePtr) {
    T value{};
    CA_CUDA_CHECK(cudaMemcpy(&value, devicePtr, sizeof(T), cudaMemcpyDeviceToHost));
    return value;
}

int deviceCount() {
    return cudaDeviceCountOrZero();
}

void* allocate(size_t bytes) {
    return trackedMalloc(bytes);
}

void release(void* ptr) {
    trackedFree(ptr);
}

void copy(void* dst, const void* src, size_t bytes) {
    CA_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyDefault));
}

void zero(void* dst, size_t bytes) {
    CA_CUDA_CHECK(cudaMemset(dst, 0, bytes));
}

void synchronize() {
    CA_CUDA_CHECK(cudaDeviceSynchronize());
}

uint32_t exclusiveScan(const uint32_t* in, uint32_t* out, size_t n) {
    const uint32_t last = downloadOne(in + n - 1);  // read before an in-place scan overwrites it
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, tempBytes, in, out, n));
    DeviceScratch temp(tempBytes);
    CA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.get(), tempBytes, in, out, n));
    return downloadOne(out + n - 1) + last;
}

template <class Key>
void sortPairs(Key* keys, uint32_t* values, size_t n, int keyBits) {
    DeviceScratch keysAlt(n * sizeof(Key)), valuesAlt(n * sizeof(uint32_t));
    cub::DoubleBuffer<Key> k(keys, keysAlt.as<Key>());
    cub::DoubleBuffer<uint32_t> v(values, valuesAlt.as<uint32_t>());
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, tempBytes, k, v, n, 0, keyBits));
    DeviceScratch temp(tempBytes);
    CA_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp.get(), tempBytes, k, v, n, 0, keyBits));
    if (k.Current() != keys) {
        CA_CUDA_CHECK(cudaMemcpy(keys, k.Current(), n * sizeof(Key), cudaMemcpyDeviceToDevice));
    }
    if (v.Current() != values) {
        CA_CUDA_CHECK(
            cudaMemcpy(values, v.Current(), n * sizeof(uint32_t), cudaMemcpyDeviceToDevice));
    }
    // The scratch is freed on return; cudaFree waits for the sort to finish first.
}

void sortPairs64(uint64_t* keys, uint32_t* values, size_t n, int keyBits) {
    sortPairs(keys, values, n, keyBits);
}

void sortPairs32(uint32_t* keys, uint32_t* values, size_t n, int keyBits) {
    sortPairs(keys, values, n, keyBits);
}

uint32_t compactIndices(const uint32_t* flags, uint32_t* out, size_t n) {
    const thrust::counting_iterator<uint32_t> indices(0);
    DeviceScratch count(sizeof(uint32_t));
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceSelect::Flagged(nullptr, tempBytes, indices, flags, out,
                                             count.as<uint32_t>(), int64_t(n)));
    DeviceScratch temp(tempBytes);
    CA_CUDA_CHECK(cub::DeviceSelect::Flagged(temp.get(), tempBytes, indices, flags, out,
                                             count.as<uint32_t>(), int64_t(n)));
    return downloadOne(count.as<uint32_t>());
}

/// float -> double before adding, as the CPU does.
struct ToDouble {
    __host__ __device__ double operator()(float x) const { return double(x); }
};

/// The larger of two floats (the CPU's comparison).
struct MaxOp {
    __host__ __device__ float operator()(float a, float b) const { return b > a ? b : a; }
};

double reduceSum(const float* in, size_t n) {
    DeviceScratch result(sizeof(double));
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceReduce::TransformReduce(nullptr, tempBytes, in, result.as<double>(), n,
                                                     cuda::std::plus<double>(), ToDouble(), 0.0));
    DeviceScratch temp(tempBytes);
    CA_CUDA_CHECK(cub::DeviceReduce::TransformReduce(temp.get(), tempBytes, in, result.as<double>(),
                                                     n, cuda::std::plus<double>(), ToDouble(),
                                                     0.0));
    return downloadOne(result.as<double>());
}

float reduceMax(const float* in, size_t n) {
    DeviceScratch result(sizeof(float));
    const float init = -std::numeric_limits<float>::infinity();
    size_t tempBytes = 0;
    CA_CUDA_CHECK(
        cub::DeviceReduce::Reduce(nullptr, tempBytes, in, result.as<float>(), n, MaxOp(), init));
    DeviceScratch temp(tempBytes);
    CA_CUDA_CHECK(
        cub::DeviceReduce::Reduce(temp.get(), tempBytes, in, result.as<float>(), n, MaxOp(), init));
    return downloadOne(result.as<float>());
}

const GpuBackend kCudaBackend = {
    .name = "CUDA",
    .deviceCount = &deviceCount,
    .allocate = &allocate,
    .release = &release,
    .copy = &copy,
    .zero = &zero,
    .synchronize = &synchronize,
    .exclusiveScan = &exclusiveScan,
    .sortPairs64 = &sortPairs64,
    .sortPairs32 = &sortPairs32,
    .compactIndices = &compactIndices,
    .reduceSum = &reduceSum,
    .reduceMax = &reduceMax,
};

}  // namespace

void registerCudaBackend() {
    setGpuBackend(&kCudaBackend);
}

CudaMemoryCounters cudaMemoryCounters() {
    AllocationTracker& t = tracker();
    std::lock_guard<std::mutex> lock(t.mutex);
    return CudaMemoryCounters{t.current, t.peak};
}

void resetCudaPeakBytes() {
    AllocationTracker& t = tracker();
    std::lock_guard<std::mutex> lock(t.mutex);
    t.peak = t.current;
}

bool cudaMemoryInfo(size_t& freeBytes, size_t& totalBytes) {
    freeBytes = totalBytes = 0;
    if (cudaDeviceCountOrZero() == 0) return false;
    if (cudaMemGetInfo(&freeBytes, &totalBytes) != cudaSuccess) {
        (void)cudaGetLastError();
        freeBytes = totalBytes = 0;
        return false;
    }
    return true;
}

std::string cudaDeviceDescription() {
    if (cudaDeviceCountOrZero() == 0) return "";
    int device = 0;
    cudaDeviceProp prop{};
    if (cudaGetDevice(&device) != cudaSuccess ||
        cudaGetDeviceProperties(&prop, device) != cudaSuccess) {
        (void)cudaGetLastError();
        return "";
    }
    char text[700];
    std::snprintf(text, sizeof text, "%s (sm_%d%d, %.1f GiB)", prop.name, prop.major, prop.minor,
                  double(prop.totalGlobalMem) / double(size_t(1) << 30));
    return text;
}

int cudaDeviceCountOrZero() {
    int count = 0;
    if (cudaGetDeviceCount(&count) != cudaSuccess) {
        (void)cudaGetLastError();  // no driver or no device: not an error for the caller
        return 0;
    }
    return count;
}

}  // namespace caustica
