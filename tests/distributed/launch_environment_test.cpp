// What the launcher's environment says (distributed/launch_environment.h): an MPI launch, the
// number of processes started together, the local rank on a host.
#include "caustica/distributed/launch_environment.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace caustica {
namespace {

// The variables the functions read, cleared for the test and restored after.
class LaunchEnvironment : public ::testing::Test {
protected:
    static constexpr const char* kNames[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK",   "PMI_SIZE",
                                             "PMI_RANK",             "SLURM_STEP_NUM_TASKS",
                                             "OMPI_COMM_WORLD_LOCAL_RANK", "SLURM_LOCALID", "MPI_LOCALRANKID",
                                             "PMI_LOCAL_RANK"};
    void SetUp() override {
        for (const char* name : kNames) {
            const char* v = std::getenv(name);
            saved_.emplace_back(name, v ? std::optional<std::string>(v) : std::nullopt);
            unsetenv(name);
        }
    }
    void TearDown() override {
        for (const auto& [name, value] : saved_) {
            if (value) setenv(name, value->c_str(), 1);
            else unsetenv(name);
        }
    }
    std::vector<std::pair<const char*, std::optional<std::string>>> saved_;
};

TEST_F(LaunchEnvironment, AloneIsOneProcessWithoutALocalRank) {
    EXPECT_FALSE(launchedByMpi());
    EXPECT_EQ(launchedProcessCount(), 1);
    EXPECT_EQ(localRankFromEnvironment(), -1);
}

TEST_F(LaunchEnvironment, OpenMpiAndPmixLaunchesAreRecognised) {
    setenv("OMPI_COMM_WORLD_SIZE", "4", 1);
    setenv("OMPI_COMM_WORLD_LOCAL_RANK", "3", 1);
    EXPECT_TRUE(launchedByMpi());
    EXPECT_EQ(launchedProcessCount(), 4);
    EXPECT_EQ(localRankFromEnvironment(), 3);
    unsetenv("OMPI_COMM_WORLD_SIZE");
    setenv("PMIX_RANK", "0", 1);
    EXPECT_TRUE(launchedByMpi());
}

TEST_F(LaunchEnvironment, SrunWithoutAnMpiPluginIsSeveralProcessesButNoMpiLaunch) {
    setenv("SLURM_STEP_NUM_TASKS", "8", 1);
    setenv("SLURM_LOCALID", "1", 1);
    EXPECT_FALSE(launchedByMpi());
    EXPECT_EQ(launchedProcessCount(), 8);
    EXPECT_EQ(localRankFromEnvironment(), 1);
}

TEST_F(LaunchEnvironment, GarbageIsIgnored) {
    setenv("OMPI_COMM_WORLD_SIZE", "four", 1);
    setenv("OMPI_COMM_WORLD_LOCAL_RANK", "-2", 1);
    EXPECT_FALSE(launchedByMpi());
    EXPECT_EQ(launchedProcessCount(), 1);
    EXPECT_EQ(localRankFromEnvironment(), -1);
}

}  // namespace
}  // namespace caustica
