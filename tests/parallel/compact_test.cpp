// compact_test.cpp — compactQueue: the serial pass (SerialExec) and the parallel one (CpuExec:
// compactIndices and a gather) keep the same entries in the same order; SerialExec launches run
// in order in the calling thread; cpuThreadCount follows the task arena.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "caustica/parallel/compact.h"

namespace caustica {
namespace {

std::vector<uint32_t> compacted(auto exec, const std::vector<uint32_t>& flags, const std::vector<uint32_t>& queue) {
    std::vector<uint32_t> selected(queue.size()), out(queue.size());
    const uint32_t kept = compactQueue(exec, flags.data(), queue.data(), queue.size(), selected.data(), out.data());
    out.resize(kept);
    return out;
}

TEST(CompactQueue, SerialAndParallelKeepTheFlaggedEntriesInOrder) {
    std::mt19937 rng(5);
    for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1000), size_t(70000)}) {
        std::vector<uint32_t> flags(n), queue(n), expected;
        for (size_t q = 0; q < n; ++q) {
            queue[q] = uint32_t(rng());
            flags[q] = rng() % 3 == 0 ? 0u : uint32_t(rng() % 5 + 1);  // any non-zero keeps
            if (flags[q]) expected.push_back(queue[q]);
        }
        EXPECT_EQ(compacted(SerialExec{}, flags, queue), expected) << n;
        EXPECT_EQ(compacted(CpuExec{}, flags, queue), expected) << n;
    }
}

TEST(SerialExec, RunsInOrderInTheCallingThread) {
    std::vector<size_t> order;
    const std::thread::id caller = std::this_thread::get_id();
    bool sameThread = true;
    launch(SerialExec{}, "test.serial", 5, [&](size_t i) {
        order.push_back(i);
        sameThread = sameThread && std::this_thread::get_id() == caller;
    });
    EXPECT_EQ(order, (std::vector<size_t>{0, 1, 2, 3, 4}));
    EXPECT_TRUE(sameThread);
}

TEST(CpuThreadCount, FollowsTheTaskArena) {
    tbb::task_arena(1).execute([] { EXPECT_EQ(cpuThreadCount(), 1u); });
    tbb::task_arena(2).execute([] { EXPECT_LE(cpuThreadCount(), 2u); });
    EXPECT_GE(cpuThreadCount(), 1u);
}

}  // namespace
}  // namespace caustica
