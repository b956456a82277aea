// primitives_cuda.cu — the CUDA backend of the parallel layer: device memory (cudaMalloc, never
// managed memory) and the primitives on CUB. registerCudaBackend() installs them into the
// GpuBackend table of caustica_parallel (parallel/backend.h). Every call is on the default
// stream; functions that return a value synchronize by copying it back. Scratch memory (CUB
// temporaries, sort double buffers, result slots) comes from one grow-only cache kept between
// calls (ScratchCache). Every CUDA call is checked (caustica::Error on failure).
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

/// The primitives' scratch memory (CUB temporary storage, the sort's alternate buffers, result
/// slots), kept between calls: one grow-only device buffer, reallocated only when a call needs
/// more than it holds. Allocating per call cost a cudaMalloc and a cudaFree (which waits for the
/// device) several times per wavefront bounce. A primitive holds the cache's lock from carving
/// its regions until its last use of them; all work is on the default stream, so the next call's
/// kernels are ordered after the previous call's, and a reallocation's cudaFree waits for them.
/// The buffer is counted by the allocation tracker like any other and lives until exit.
class ScratchCache {
public:
    /// Regions of `bytes[i]` bytes each (256-byte aligned) in the cached buffer, valid while the
    /// returned lock is held.
    template <size_t N>
    std::unique_lock<std::mutex> carve(const size_t (&bytes)[N], void* (&out)[N]) {
        std::unique_lock<std::mutex> lock(mutex_);
        size_t total = 0;
        for (size_t b : bytes) total += align(b);
        if (total > capacity_) {
            trackedFree(ptr_);
            ptr_ = nullptr;
            capacity_ = 0;
            ptr_ = trackedMalloc(total);
            capacity_ = total;
        }
        size_t offset = 0;
        for (size_t i = 0; i < N; ++i) {
            out[i] = static_cast<char*>(ptr_) + offset;
            offset += align(bytes[i]);
        }
        return lock;
    }

private:
    static size_t align(size_t bytes) { return (bytes + 255) / 256 * 256; }
    std::mutex mutex_;
    void* ptr_ = nullptr;
    size_t capacity_ = 0;
};

ScratchCache& scratchCache() {
    // Never destroyed: freeing at exit could run after the CUDA runtime has shut down.
    static ScratchCache* cache = new ScratchCache;
    return *cache;
}

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
    void* temp[1];
    const auto lock = scratchCache().carve({tempBytes}, temp);
    CA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp[0], tempBytes, in, out, n));
    return downloadOne(out + n - 1) + last;
}

template <class Key>
void sortPairs(Key* keys, uint32_t* values, size_t n, int keyBits) {
    size_t tempBytes = 0;
    {
        cub::DoubleBuffer<Key> k(keys, nullptr);
        cub::DoubleBuffer<uint32_t> v(values, nullptr);
        CA_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, tempBytes, k, v, n, 0, keyBits));
    }
    void* region[3];
    const auto lock = scratchCache().carve({n * sizeof(Key), n * sizeof(uint32_t), tempBytes}, region);
    cub::DoubleBuffer<Key> k(keys, static_cast<Key*>(region[0]));
    cub::DoubleBuffer<uint32_t> v(values, static_cast<uint32_t*>(region[1]));
    CA_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(region[2], tempBytes, k, v, n, 0, keyBits));
    if (k.Current() != keys) {
        CA_CUDA_CHECK(cudaMemcpy(keys, k.Current(), n * sizeof(Key), cudaMemcpyDeviceToDevice));
    }
    if (v.Current() != values) {
        CA_CUDA_CHECK(
            cudaMemcpy(values, v.Current(), n * sizeof(uint32_t), cudaMemcpyDeviceToDevice));
    }
}

void sortPairs64(uint64_t* keys, uint32_t* values, size_t n, int keyBits) {
    sortPairs(keys, values, n, keyBits);
}

void sortPairs32(uint32_t* keys, uint32_t* values, size_t n, int keyBits) {
    sortPairs(keys, values, n, keyBits);
}

uint32_t compactIndices(const uint32_t* flags, uint32_t* out, size_t n) {
    const thrust::counting_iterator<uint32_t> indices(0);
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceSelect::Flagged(nullptr, tempBytes, indices, flags, out,
                                             static_cast<uint32_t*>(nullptr), int64_t(n)));
    void* region[2];
    const auto lock = scratchCache().carve({sizeof(uint32_t), tempBytes}, region);
    uint32_t* count = static_cast<uint32_t*>(region[0]);
    CA_CUDA_CHECK(cub::DeviceSelect::Flagged(region[1], tempBytes, indices, flags, out, count,
                                             int64_t(n)));
    return downloadOne(count);
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
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceReduce::TransformReduce(nullptr, tempBytes, in,
                                                     static_cast<double*>(nullptr), n,
                                                     cuda::std::plus<double>(), ToDouble(), 0.0));
    void* region[2];
    const auto lock = scratchCache().carve({sizeof(double), tempBytes}, region);
    double* result = static_cast<double*>(region[0]);
    CA_CUDA_CHECK(cub::DeviceReduce::TransformReduce(region[1], tempBytes, in, result, n,
                                                     cuda::std::plus<double>(), ToDouble(), 0.0));
    return downloadOne(result);
}

/// uint32 -> uint64 before adding: the sum cannot wrap, so it equals the CPU's exactly.
struct ToU64 {
    __host__ __device__ uint64_t operator()(uint32_t x) const { return uint64_t(x); }
};

uint64_t reduceSumU32(const uint32_t* in, size_t n) {
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceReduce::TransformReduce(nullptr, tempBytes, in,
                                                     static_cast<uint64_t*>(nullptr), n,
                                                     cuda::std::plus<uint64_t>(), ToU64(),
                                                     uint64_t(0)));
    void* region[2];
    const auto lock = scratchCache().carve({sizeof(uint64_t), tempBytes}, region);
    uint64_t* result = static_cast<uint64_t*>(region[0]);
    CA_CUDA_CHECK(cub::DeviceReduce::TransformReduce(region[1], tempBytes, in, result, n,
                                                     cuda::std::plus<uint64_t>(), ToU64(),
                                                     uint64_t(0)));
    return downloadOne(result);
}

float reduceMax(const float* in, size_t n) {
    const float init = -std::numeric_limits<float>::infinity();
    size_t tempBytes = 0;
    CA_CUDA_CHECK(cub::DeviceReduce::Reduce(nullptr, tempBytes, in, static_cast<float*>(nullptr), n,
                                            MaxOp(), init));
    void* region[2];
    const auto lock = scratchCache().carve({sizeof(float), tempBytes}, region);
    float* result = static_cast<float*>(region[0]);
    CA_CUDA_CHECK(cub::DeviceReduce::Reduce(region[1], tempBytes, in, result, n, MaxOp(), init));
    return downloadOne(result);
}

size_t peakBytes() {
    return cudaMemoryCounters().peak;
}

void setDevice(int index) {
    CA_CUDA_CHECK(cudaSetDevice(index));
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
    .reduceSumU32 = &reduceSumU32,
    .memoryInfo = &cudaMemoryInfo,
    .peakBytes = &peakBytes,
    .resetPeakBytes = &resetCudaPeakBytes,
    .describe = &cudaDeviceDescription,
    .setDevice = &setDevice,
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
