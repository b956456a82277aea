// gpu_primitives_test.cu — the CUDA backend against the CPU: Buffer round trips, the primitives
// on random inputs, and parallelForDevice. Built only with the CUDA backend (target
// caustica_cuda_tests); every GPU test skips when cudaGetDeviceCount finds no GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"
#include "tests/common/gpu_test_setup.h"
#include "cuda/cuda_backend.h"
#include "cuda/cuda_check.h"
#include "cuda/parallel_for_cuda.h"
#include "random_inputs.h"

namespace caustica {
namespace {

using test::kSizes;
using test::randomU32;

class Gpu : public ::testing::Test {
protected:
    void SetUp() override {
        test::skipWithoutGpu("GPU primitives");
    }
    const Device gpu = Device::cuda();
    const Device cpu = Device::cpu();
};

TEST(CudaCheck, ErrorNamesCallLocationAndReason) {
    try {
        checkCuda(cudaErrorMemoryAllocation, "cudaMalloc(&p, n)", "buffer.cu", 42);
        FAIL() << "no exception";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("buffer.cu:42:"), std::string::npos) << what;
        EXPECT_NE(what.find("cudaMalloc(&p, n) failed"), std::string::npos) << what;
        EXPECT_NE(what.find(cudaGetErrorString(cudaErrorMemoryAllocation)), std::string::npos);
    }
}

TEST(CudaBackend, RegistersAndFailsCleanlyWithoutGpu) {
    registerCudaBackend();
    ASSERT_NE(gpuBackend(), nullptr);
    EXPECT_EQ(gpuDeviceCount(), cudaDeviceCountOrZero());
    if (cudaDeviceCountOrZero() > 0) GTEST_SKIP() << "a GPU is present";
    EXPECT_THROW(Buffer<float>(Device::cuda(), 16), Error);  // cudaMalloc fails, checked
}

TEST_F(Gpu, BufferRoundTrip) {
    std::vector<uint32_t> host(10000);
    std::iota(host.begin(), host.end(), 3u);
    Buffer<uint32_t> b(gpu, host);
    EXPECT_EQ(b.toHost(), host);
    Buffer<uint32_t> moved(std::move(b));
    EXPECT_EQ(moved.toHost(), host);
    moved.zero();
    EXPECT_EQ(moved.toHost(), std::vector<uint32_t>(host.size(), 0u));
}

TEST_F(Gpu, ExclusiveScanMatchesCpu) {
    for (size_t n : kSizes) {
        const auto in = randomU32(n, 1000, n);
        std::vector<uint32_t> ref(n);
        const uint32_t total = exclusiveScan(cpu, Span<const uint32_t>(in), Span<uint32_t>(ref));
        Buffer<uint32_t> d(gpu, in), out(gpu, n);
        EXPECT_EQ(exclusiveScan(gpu, d.constSpan(), out.span()), total);
        EXPECT_EQ(out.toHost(), ref);
        EXPECT_EQ(exclusiveScan(gpu, d.constSpan(), d.span()), total);  // in place
        EXPECT_EQ(d.toHost(), ref);
    }
}

template <class Key>
void expectGpuSortMatchesCpu(std::vector<Key> keys, int keyBits) {
    std::vector<uint32_t> values(keys.size());
    std::iota(values.begin(), values.end(), 0u);
    Buffer<Key> dk(Device::cuda(), keys);
    Buffer<uint32_t> dv(Device::cuda(), values);
    radixSortPairs(Device::cpu(), Span<Key>(keys), Span<uint32_t>(values), keyBits);
    radixSortPairs(Device::cuda(), dk.span(), dv.span(), keyBits);
    EXPECT_EQ(dk.toHost(), keys);
    EXPECT_EQ(dv.toHost(), values);  // stable on both: identical permutations
}

TEST_F(Gpu, RadixSortMatchesCpu) {
    for (size_t n : kSizes) {
        const auto k32 = randomU32(n, 0xffffffffu, n + 7);
        const auto few = randomU32(n, 15, n + 8);
        expectGpuSortMatchesCpu(k32, 32);
        expectGpuSortMatchesCpu(few, 32);
        std::vector<uint64_t> k64(n);
        std::mt19937_64 rng(n + 9);
        for (auto& k : k64) k = rng();
        expectGpuSortMatchesCpu(k64, 64);
        expectGpuSortMatchesCpu(k64, 30);
    }
}

TEST_F(Gpu, CompactIndicesMatchesCpu) {
    for (size_t n : kSizes) {
        const auto flags = randomU32(n, 3, n + 11);
        std::vector<uint32_t> ref(n);
        ref.resize(compactIndices(cpu, Span<const uint32_t>(flags), Span<uint32_t>(ref)));
        Buffer<uint32_t> d(gpu, flags), out(gpu, n);
        const uint32_t count = compactIndices(gpu, d.constSpan(), out.span());
        ASSERT_EQ(count, ref.size());
        auto got = out.toHost();
        got.resize(count);
        EXPECT_EQ(got, ref);
    }
}

TEST_F(Gpu, ReductionsMatchCpu) {
    for (size_t n : kSizes) {
        std::mt19937_64 rng(n + 13);
        std::uniform_real_distribution<float> dist(-100.0f, 100.0f);
        std::vector<float> in(n);
        for (auto& x : in) x = dist(rng);
        Buffer<float> d(gpu, in);
        const double sum = reduceSum(cpu, Span<const float>(in));
        EXPECT_NEAR(reduceSum(gpu, d.constSpan()), sum, 1e-9 * (1.0 + 100.0 * double(n)));
        EXPECT_EQ(reduceMax(gpu, d.constSpan()), reduceMax(cpu, Span<const float>(in)));
    }
}

TEST_F(Gpu, Uint32SumMatchesCpuExactly) {
    for (size_t n : kSizes) {
        auto in = randomU32(n, 0xffffffffu, n + 17);  // a 32-bit accumulator would wrap
        Buffer<uint32_t> d(gpu, in);
        EXPECT_EQ(reduceSum(gpu, d.constSpan()), reduceSum(cpu, Span<const uint32_t>(in))) << "n = " << n;
    }
}

/// Extended lambdas may not live in a TEST body (a private member function): a free function.
void squareOn(const Device& device, Span<uint32_t> out) {
    parallelForDevice(device, "test.square", out.size(),
                      [out] CA_HD(size_t i) { out[i] = uint32_t(i * i); });
}

TEST_F(Gpu, ParallelForDeviceRunsTheSameLambdaOnBoth) {
    const size_t n = 100000;
    Buffer<uint32_t> d(gpu, n), h(cpu, n);
    KernelStats::global().reset();
    KernelStats::global().setEnabled(true);
    squareOn(gpu, d.span());
    squareOn(cpu, h.span());
    KernelStats::global().setEnabled(false);
    CA_CUDA_CHECK(cudaDeviceSynchronize());
    EXPECT_EQ(d.toHost(), h.toHost());
    const auto stats = KernelStats::global().snapshot();
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_EQ(stats[0].launches, 2u);
}

}  // namespace
}  // namespace caustica
