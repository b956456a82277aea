// mlt_buffers_test.cpp — how many iterations of splats a splat pass takes (mltSplatBatch), and
// where each iteration's splats go in the batch.
#include <gtest/gtest.h>

#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/parallel/device.h"

namespace caustica {
namespace {

MltSettings withChains(uint32_t chains, uint32_t proposals) {
    MltSettings s;
    s.chains = chains;
    s.proposals = proposals;
    return s;
}

// At least one splat per pixel in a batch: the per-pixel work of a splat pass is then no more
// than the splats' own.
TEST(MltSplatBatch, BringsASplatPerPixel) {
    EXPECT_EQ(mltSplatBatch(withChains(1024, 1), 64 * 64), 2u);           // 2048 splats an iteration
    EXPECT_EQ(mltSplatBatch(withChains(1024, 1), 256 * 256), 32u);
    EXPECT_EQ(mltSplatBatch(withChains(1024, 1), 1000 * 1000), 489u);     // rounded up
    EXPECT_EQ(mltSplatBatch(withChains(1024, 3), 256 * 256), 16u);        // k + 1 splats per chain
    EXPECT_EQ(mltSplatBatch(withChains(524288, 1), 1024 * 1024), 1u);     // a GPU's default chains
    EXPECT_EQ(mltSplatBatch(withChains(4096, 1), 16), 1u);                // more splats than pixels
}

TEST(MltSplatBatch, IsBoundedAndCanBeSet) {
    // At most kMltMaxBatchedSplats splats in a batch (one iteration's always fits).
    EXPECT_EQ(mltSplatBatch(withChains(1024, 1), 8192 * 8192), kMltMaxBatchedSplats / 2048);
    EXPECT_EQ(mltSplatBatch(withChains(1u << 23, 1), 8192 * 8192), 1u);
    MltSettings s = withChains(1024, 1);
    s.splatBatch = 7;
    EXPECT_EQ(mltSplatBatch(s, 64 * 64), 7u);
}

// Iteration t writes its n (k + 1) splats to slot t % batch; the buffers hold a whole batch.
TEST(MltSplatBatch, IterationsFillTheirSlots) {
    MltChainBuffers b(Device::cpu(), 10, 2, 100, MltSplatKind::Sort, 4);
    EXPECT_EQ(b.splatsPerIteration, 30u);
    EXPECT_EQ(b.splats.size(), 120u);
    EXPECT_EQ(b.sortKeys.size(), 120u);
    const FloatChainStore store;
    EXPECT_EQ(b.view(store, 0).splats, b.splats.data());
    EXPECT_EQ(b.view(store, 6).splats, b.splats.data() + 60);
    EXPECT_EQ(b.view(store, 7).splats, b.splats.data() + 90);
}

}  // namespace
}  // namespace caustica
