// mlt_gpu_memory_test.cpp — the GPU MLT driver's memory estimate (mlt_gpu_memory.h) is a pure
// function of the settings: checked on the CPU, its chain-buffer term against what
// MltChainBuffers really allocates.
#include <gtest/gtest.h>

#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_gpu_memory.h"
#include "caustica/parallel/device.h"

namespace caustica {
namespace {

MltSettings someSettings(uint32_t chains) {
    MltSettings s;
    s.chains = chains;
    s.proposals = 3;
    s.bootstrapSamples = 5000;
    return s;
}

template <class T>
size_t bytesOf(const Buffer<T>& b) {
    return b.size() * sizeof(T);
}

size_t allocatedBytes(const MltChainBuffers& b) {
    return bytesOf(b.pos) + bytesOf(b.proposalPos) + bytesOf(b.value) + bytesOf(b.proposalValue) +
           bytesOf(b.importance) + bytesOf(b.proposalImportance) + bytesOf(b.largeStepSum) +
           bytesOf(b.accum) + bytesOf(b.usedDims) + bytesOf(b.proposalDims) +
           bytesOf(b.proposalRays) + bytesOf(b.largeSteps) + bytesOf(b.accepted) +
           bytesOf(b.sortKeys) + bytesOf(b.sortValues) + bytesOf(b.pixelStart) + bytesOf(b.splats) +
           bytesOf(b.image);
}

// The chain buffers' per-chain state (film position, F, I, U) is part of mltBytesPerChain; the
// rest is the scratch term, in both splat modes.
TEST(MltGpuMemory, ChainBuffersAreWhatMltChainBuffersAllocates) {
    const uint32_t pixels = 20 * 10, bounces = 5;
    for (MltSplatKind splat : {MltSplatKind::Atomic, MltSplatKind::Sort}) {
        MltSettings s = someSettings(37);
        s.splat = splat;
        // 37 x 4 splats per iteration on 200 pixels: batches of 2 iterations.
        ASSERT_EQ(mltSplatBatch(s, pixels), 2u);
        const MltChainBuffers buffers(Device::cpu(), s.chains, s.proposals, pixels, splat, mltSplatBatch(s, pixels));
        const MltGpuMemoryEstimate e = estimateMltGpuMemory(s, bounces, pixels);
        const size_t perChainState =
            sizeof(Vec2f) + sizeof(Spectrum) + sizeof(float) + sizeof(uint16_t);
        EXPECT_EQ(allocatedBytes(buffers), e.chainScratch + s.chains * perChainState) << int(splat);
        EXPECT_EQ(e.chainState, s.chains * mltBytesPerChain(MltStateKind::Compact, bounces));
    }
}

TEST(MltGpuMemory, GrowsLinearlyWithChains) {
    for (uint32_t sortEvery : {0u, 4u}) {
        auto total = [&](uint32_t chains) {
            MltSettings s = someSettings(chains);
            s.splat = MltSplatKind::Sort;
            s.sortEvery = sortEvery;
            return estimateMltGpuMemory(s, 6, 64 * 48).total();
        };
        const size_t one = total(1000), two = total(2000), three = total(3000);
        EXPECT_GT(two, one);
        EXPECT_EQ(three - two, two - one) << "sort every " << sortEvery;
    }
}

TEST(MltGpuMemory, BootstrapIsMTimesBytesPerSample) {
    EXPECT_EQ(kMltBootstrapBytesPerSample, 12u);  // importance, pixel, rays
    MltSettings s = someSettings(256);
    s.bootstrapSamples = 1000;
    const MltGpuMemoryEstimate small = estimateMltGpuMemory(s, 4, 32 * 32);
    s.bootstrapSamples = 1000 + 4096;
    const MltGpuMemoryEstimate large = estimateMltGpuMemory(s, 4, 32 * 32);
    EXPECT_EQ(large.bootstrap - small.bootstrap, 4096 * kMltBootstrapBytesPerSample);
    EXPECT_EQ(large.total() - small.total(), 4096 * kMltBootstrapBytesPerSample);
    s.bootstrapSamples = 0;  // the default M
    EXPECT_EQ(estimateMltGpuMemory(s, 4, 32 * 32).bootstrap,
              mltDefaultBootstrapSamples(256, 32 * 32) * kMltBootstrapBytesPerSample +
                  256 * (sizeof(uint64_t) + sizeof(uint32_t)));
}

TEST(MltGpuMemory, OptionalTermsFollowTheSettings) {
    MltSettings s = someSettings(100);
    s.target = MltTarget::Luminance;
    s.sortEvery = 0;
    const MltGpuMemoryEstimate plain = estimateMltGpuMemory(s, 4, 30 * 20);
    EXPECT_EQ(plain.pixelWeights, 0u);
    EXPECT_EQ(plain.chainSort, 0u);
    EXPECT_EQ(plain.primitives, kMltCubTemporaryBytes);  // atomic splats, no sort
    s.target = MltTarget::Relative;
    s.sortEvery = 8;
    const MltGpuMemoryEstimate full = estimateMltGpuMemory(s, 4, 30 * 20);
    EXPECT_EQ(full.pixelWeights, 30 * 20 * sizeof(float));
    EXPECT_EQ(full.chainSort,
              100 * (sizeof(uint64_t) + sizeof(uint32_t)) + mltGpuPermuteScratchBytes(100, 4));
    EXPECT_EQ(full.primitives, 100 * (sizeof(uint64_t) + sizeof(uint32_t)) + kMltCubTemporaryBytes +
                                   100 * kMltCubTemporaryBytesPerSortedElement);
    // Sorted splats: a batch of 2 iterations (600 pixels, chains x (k + 1) = 400 splats an
    // iteration), 800 keys and values, and CUB's storage grows with them.
    s.splat = MltSplatKind::Sort;
    s.sortEvery = 0;
    EXPECT_EQ(estimateMltGpuMemory(s, 4, 30 * 20).primitives,
              800 * 2 * sizeof(uint32_t) + kMltCubTemporaryBytes + 800 * kMltCubTemporaryBytesPerSortedElement);
    s.splatBatch = 5;  // set, not chosen
    EXPECT_EQ(estimateMltGpuMemory(s, 4, 30 * 20).primitives,
              2000 * 2 * sizeof(uint32_t) + kMltCubTemporaryBytes + 2000 * kMltCubTemporaryBytesPerSortedElement);
    // The permutation scratch holds the largest per-chain array: the fine store here.
    EXPECT_EQ(mltGpuPermuteScratchBytes(100, 4), 3 * (kMltCameraDims + 4 * 4) * 100u);
}

}  // namespace
}  // namespace caustica
