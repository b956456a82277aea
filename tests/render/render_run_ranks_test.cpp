// runRender over several ranks (render/render_run.h), the ranks as threads (InProcessGroup): the
// ranks agree on stopping (time budget, a cancel on one rank), rank 0 writes, the checkpoint of an
// interrupted render resumes to the single-process image, and refusals reach every rank.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "caustica/distributed/agreed_error.h"
#include "caustica/distributed/in_process_group.h"
#include "caustica/io/image_io.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/render_run.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-box/scene.xml";

class RenderRunRanks : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("caustica_run_ranks_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    static RenderRequest request(int spp, double seconds = 0) {
        RenderRequest r;
        r.integrator = "path";
        r.samplesPerPixel = spp;
        r.timeLimit = seconds;
        r.samplesPerPass = 1;
        r.seed = 5;
        r.device = "cpu";
        r.resolution = std::make_pair(16, 12);
        return r;
    }
    RunControl control(const std::string& output) const {
        RunControl c;
        c.outputs = {path(output)};
        c.checkpoint = path(output) + ".ckpt";
        c.checkpointEvery = 0;
        c.quiet = true;
        c.catchInterrupts = false;  // the tests cancel through RunControl::cancel
        return c;
    }
    /// runRender on every rank; returns each rank's samples per pixel at the end.
    static std::vector<double> run(int ranks, const RenderRequest& r, const std::vector<RunControl>& controls) {
        InProcessGroup group(ranks);
        std::vector<double> spp(static_cast<size_t>(ranks), 0.0);
        group.run([&](Communicator& comm) {
            const RunControl& c = controls[size_t(comm.rank())];
            const std::optional<CheckpointHeader> resume = prepareRun(c, comm);
            Renderer renderer(loadScene(kScene), r, resume ? &*resume : nullptr, comm);
            runRender(renderer, c);
            spp[size_t(comm.rank())] = renderer.progress().samplesPerPixel;
        });
        return spp;
    }
    static std::string readFile(const std::string& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    fs::path dir_;
};

TEST_F(RenderRunRanks, ATimeBudgetStopsEveryRankAfterTheSameStep) {
    RunControl c = control("time.pfm");
    c.statsJson = path("time.json");
    const std::vector<double> spp = run(2, request(0, 0.2), {c, c});
    EXPECT_GT(spp[0], 0);
    EXPECT_EQ(spp[0], spp[1]);
    EXPECT_TRUE(fs::exists(path("time.pfm")));
    const std::string stats = readFile(path("time.json"));
    EXPECT_NE(stats.find("\"ranks\": 2"), std::string::npos) << stats;
    EXPECT_NE(stats.find("\"per_rank\": [{\"rank\": 0"), std::string::npos) << stats;
    EXPECT_NE(stats.find("\"bytes_sent_per_iteration\""), std::string::npos) << stats;
}

TEST_F(RenderRunRanks, ACancelOnOneRankStopsAllAndTheCheckpointResumesToTheSingleProcessImage) {
    // Rank 1 alone is cancelled (as by Ctrl-C on its host) while the budget is far away.
    std::atomic<bool> cancelRank1{false};
    std::vector<RunControl> controls{control("cut.pfm"), control("cut.pfm")};
    controls[1].cancel = &cancelRank1;
    std::thread canceller([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(150));
        cancelRank1 = true;
    });
    const std::vector<double> cut = run(2, request(1 << 20), controls);
    canceller.join();
    ASSERT_EQ(cut[0], cut[1]);
    ASSERT_LT(cut[0], 1 << 20);
    ASSERT_TRUE(fs::exists(path("cut.pfm.ckpt")));

    // Another number of ranks is refused on every rank, naming both counts.
    for (RunControl& c : controls) {
        c.cancel = nullptr;
        c.resume = true;
    }
    const int total = int(cut[0]) + 3;
    try {
        run(3, request(total), {controls[0], controls[0], controls[0]});
        FAIL() << "a resume with 3 ranks of a 2-rank checkpoint ran";
    } catch (const AgreedError& e) {
        EXPECT_NE(std::string(e.what()).find("written by a render over 2 MPI ranks, resumed with 3 MPI ranks"),
                  std::string::npos)
            << e.what();
    }
    // The same number resumes, to the image one process renders without interruption.
    run(2, request(total), controls);
    EXPECT_FALSE(fs::exists(path("cut.pfm.ckpt")));  // finished: nothing left to resume
    Renderer alone(loadScene(kScene), request(total));
    while (!alone.finished()) alone.step();
    const Image resumed = readImage(path("cut.pfm"));
    const Image expected = alone.develop();
    ASSERT_EQ(resumed.rgb.size(), expected.rgb.size());
    EXPECT_EQ(std::memcmp(resumed.rgb.data(), expected.rgb.data(), expected.rgb.size() * sizeof(float)), 0);
}

TEST_F(RenderRunRanks, AnOutputRank0CannotWriteFailsOnEveryRank) {
    RunControl c = control("image.pfm");
    c.outputs = {path("missing-folder/image.pfm")};
    c.checkpoint = c.outputs[0] + ".ckpt";
    InProcessGroup group(2);
    std::atomic<int> refused{0};
    try {
        group.run([&](Communicator& comm) {
            try {
                prepareRun(c, comm);
            } catch (const AgreedError& e) {
                EXPECT_NE(std::string(e.what()).find("rank 0: "), std::string::npos) << e.what();
                ++refused;
            }
        });
    } catch (...) {
        FAIL() << "a rank failed on its own";
    }
    EXPECT_EQ(refused, 2);
}

}  // namespace
}  // namespace caustica::test
