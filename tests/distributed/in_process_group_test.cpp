#include "caustica/distributed/in_process_group.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "caustica/util/error.h"

namespace caustica {
namespace {

TEST(SingleProcess, IsRankZeroOfOneAndLeavesValues) {
    Communicator& comm = singleProcess();
    EXPECT_EQ(comm.rank(), 0);
    EXPECT_EQ(comm.size(), 1);
    double v[2] = {1.5, -2};
    comm.sum(std::span(v));
    EXPECT_EQ(v[0], 1.5);
    EXPECT_EQ(comm.max(3), 3);
    EXPECT_EQ(comm.firstError(""), "");
    EXPECT_EQ(comm.firstError("bad.xml: broken"), "bad.xml: broken");
}

TEST(InProcessGroup, SumsInRankOrderOnEveryRank) {
    InProcessGroup group(3);
    std::vector<std::vector<double>> results(3);
    group.run([&](Communicator& comm) {
        // 1e16 + 1 + -1e16: rank order gives 0 (1 is lost in 1e16 + 1), another order would give 1.
        const double mine[3] = {1e16, 1.0, -1e16};
        std::vector<double> v{mine[comm.rank()], double(comm.rank())};
        comm.sum(std::span(v));
        results[comm.rank()] = v;
    });
    for (const auto& r : results) {
        EXPECT_EQ(r[0], 0.0);
        EXPECT_EQ(r[1], 3.0);
    }
}

TEST(InProcessGroup, GathersBroadcastsAndTakesTheMaximum) {
    InProcessGroup group(3);
    std::atomic<int> checked{0};
    group.run([&](Communicator& comm) {
        const std::string mine(size_t(comm.rank() + 1), char('a' + comm.rank()));
        const auto all = comm.allGather(std::span(reinterpret_cast<const uint8_t*>(mine.data()), mine.size()));
        ASSERT_EQ(all.size(), 3u);
        EXPECT_EQ(std::string(all[2].begin(), all[2].end()), "ccc");
        std::vector<uint8_t> bytes;
        if (comm.rank() == 1) bytes = {7, 8, 9};
        comm.broadcast(bytes, 1);
        EXPECT_EQ(bytes, (std::vector<uint8_t>{7, 8, 9}));
        EXPECT_EQ(comm.max(double(comm.rank())), 2.0);
        EXPECT_TRUE(comm.any(comm.rank() == 2));
        EXPECT_FALSE(comm.any(false));
        uint64_t n[1] = {uint64_t(comm.rank()) + 1};
        comm.sum(std::span(n));
        EXPECT_EQ(n[0], 6u);
        ++checked;
    });
    EXPECT_EQ(checked, 3);
}

TEST(InProcessGroup, FirstErrorNamesTheLowestFailingRank) {
    InProcessGroup group(3);
    group.run([&](Communicator& comm) {
        const std::string message = comm.rank() >= 1 ? "scene" + std::to_string(comm.rank()) + ".xml: bad" : "";
        EXPECT_EQ(comm.firstError(message), "rank 1: scene1.xml: bad");
    });
}

TEST(InProcessGroup, ARankThatThrowsWakesTheOthersAndIsRethrown) {
    InProcessGroup group(2);
    try {
        group.run([&](Communicator& comm) {
            if (comm.rank() == 1) throw Error("rank one failed");
            comm.barrier();  // would wait forever for rank 1 without the wake-up
        });
        FAIL() << "no exception";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "rank one failed");
    }
}

}  // namespace
}  // namespace caustica
