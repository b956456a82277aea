// buffer_test.cpp — Buffer semantics on the CPU, parallelFor timing and the kernel stats table.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <type_traits>
#include <vector>

#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

static_assert(!std::is_copy_constructible_v<Buffer<int>>);
static_assert(!std::is_copy_assignable_v<Buffer<int>>);
static_assert(std::is_nothrow_move_constructible_v<Buffer<int>>);
static_assert(std::is_nothrow_move_assignable_v<Buffer<int>>);

TEST(Buffer, DefaultIsEmpty) {
    Buffer<float> b;
    EXPECT_EQ(b.size(), 0u);
    EXPECT_TRUE(b.empty());
    EXPECT_EQ(b.data(), nullptr);
    EXPECT_TRUE(b.device().isCpu());
}

TEST(Buffer, AlignedUploadDownload) {
    std::vector<uint32_t> host(1000);
    std::iota(host.begin(), host.end(), 5u);
    Buffer<uint32_t> b(Device::cpu(), host);
    ASSERT_EQ(b.size(), host.size());
    EXPECT_EQ(reinterpret_cast<uintptr_t>(b.data()) % 64, 0u);
    EXPECT_EQ(b.toHost(), host);
    EXPECT_EQ(b.span().data(), b.data());
    EXPECT_EQ(b.constSpan().size(), host.size());

    std::vector<uint32_t> part = {1, 2, 3};
    b.copyFromHost(part, 997);
    std::vector<uint32_t> tail(4);
    b.copyToHost(Span<uint32_t>(tail), 996);
    EXPECT_EQ(tail, (std::vector<uint32_t>{1001u, 1u, 2u, 3u}));
    b.zero();
    EXPECT_EQ(b.toHost(), std::vector<uint32_t>(1000, 0u));
}

TEST(Buffer, RangeChecks) {
    Buffer<int> b(Device::cpu(), 4);
    std::vector<int> five(5);
    EXPECT_THROW(b.copyFromHost(five), Error);
    EXPECT_THROW(b.copyToHost(Span<int>(five.data(), 2), 3), Error);
    EXPECT_NO_THROW(b.copyToHost(Span<int>(five.data(), 0), 4));
}

TEST(Buffer, MoveTransfersOwnership) {
    Buffer<double> a(Device::cpu(), std::vector<double>{1.0, 2.0});
    double* p = a.data();
    Buffer<double> b(std::move(a));
    EXPECT_EQ(b.data(), p);
    EXPECT_EQ(b.size(), 2u);
    EXPECT_EQ(a.data(), nullptr);  // NOLINT(bugprone-use-after-move): moved-from state is defined
    EXPECT_EQ(a.size(), 0u);
    Buffer<double> c(Device::cpu(), 7);
    c = std::move(b);
    EXPECT_EQ(c.data(), p);
    EXPECT_EQ(c.toHost(), (std::vector<double>{1.0, 2.0}));
}

TEST(Buffer, SpanFeedsPrimitivesAndKernels) {
    Buffer<uint32_t> flags(Device::cpu(), 100);
    Span<uint32_t> f = flags.span();
    parallelFor(Device::cpu(), "test.flags", f.size(), [f](size_t i) { f[i] = i % 3 == 0; });
    Buffer<uint32_t> out(Device::cpu(), 100);
    EXPECT_EQ(compactIndices(Device::cpu(), flags.constSpan(), out.span()), 34u);
    EXPECT_EQ(out.toHost()[33], 99u);
}

TEST(KernelStats, ParallelForRecordsLaunchesWhenEnabled) {
    KernelStats& stats = KernelStats::global();
    stats.reset();
    std::vector<int> v(1000);
    parallelFor(Device::cpu(), "test.untimed", v.size(), [&](size_t i) { v[i] = 1; });
    EXPECT_TRUE(stats.snapshot().empty());
    stats.setEnabled(true);
    for (int k = 0; k < 3; ++k)
        parallelFor(Device::cpu(), "test.fill", v.size(), [&](size_t i) { v[i] = k; });
    parallelFor(Device::cpu(), "test.other", v.size(), [&](size_t i) { v[i] = 0; });
    stats.setEnabled(false);
    const auto rows = stats.snapshot();
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].name, "test.fill");
    EXPECT_EQ(rows[0].launches, 3u);
    EXPECT_GE(rows[0].totalMs, 0.0);
    EXPECT_EQ(rows[1].name, "test.other");
    EXPECT_EQ(rows[1].launches, 1u);
    const std::string table = stats.table();
    EXPECT_NE(table.find("kernel"), std::string::npos);
    EXPECT_NE(table.find("test.fill"), std::string::npos);
    EXPECT_NE(table.find("launches"), std::string::npos);
    stats.reset();
    EXPECT_TRUE(stats.snapshot().empty());
}

TEST(Device, HostParallelForOnCudaDeviceThrows) {
    EXPECT_THROW(parallelFor(Device::cuda(), "test.gpu", 4, [](size_t) {}), Error);
    EXPECT_STREQ(deviceName(DeviceKind::Cuda), "cuda");
    EXPECT_EQ(Device::cpu(), Device{});
}

}  // namespace
}  // namespace caustica
