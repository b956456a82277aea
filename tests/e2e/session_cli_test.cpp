// `caustica render` as a user meets the render session: an existing checkpoint needs --resume or
// --overwrite, a resume of another render is refused and keeps the checkpoint, interrupts save,
// budgets are totals across resumes, and bad outputs or numbers fail before any rendering.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

class SessionCli : public CliFixture {
protected:
    void SetUp() override {
        CliFixture::SetUp();
        // A copy of the Cornell box that the tests may edit.
        fs::copy_file(sourcePath("scenes/cornell-box/scene.xml"), path("box.xml"));
    }
    std::string read(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
    // Starts a long render of box.xml to out.exr (`extra` options, default --spp-per-pass 2),
    // interrupts it with SIGINT `interrupts` times once its first checkpoint exists, and returns the
    // script's output: "rc=N" (the exit code), then the render's output.
    CliResult interruptedRender(int interrupts, const std::string& extra = "") const {
        std::string script = "$CAUSTICA render " + path("box.xml") + " -D width=48 -D height=48 -q --seed 2 " +
                             "--spp 1000000 --checkpoint-every 0.05 " + (extra.empty() ? "--spp-per-pass 2" : extra) + " -o " +
                             path("out.exr") + " > " + path("log") + " 2>&1 & pid=$!\n" +
                             "for i in $(seq 1500); do [ -f " + path("out.exr.ckpt") + " ] && break; sleep 0.02; done\n";
        for (int i = 0; i < interrupts; ++i) script += "kill -INT $pid; sleep 0.01\n";
        script += "wait $pid; echo rc=$?; cat " + path("log") + "\n";
        return runShell(script);
    }
    const std::string small = " -D width=16 -D height=16 -q --seed 2 ";
};

TEST_F(SessionCli, FirstInterruptFinishesTheStepAndSavesEverything) {
    const CliResult r = interruptedRender(1);
    EXPECT_NE(r.output.find("rc=130"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("continue with --resume"), std::string::npos) << r.output;
    ASSERT_TRUE(fs::exists(path("out.exr.ckpt"))) << r.output;
    const int spp = std::stoi(readImageMetadata(path("out.exr")).entries.at("caustica.spp"));
    EXPECT_GT(spp, 0);
    // It resumes to a budget that counts the samples already rendered.
    const CliResult resumed = runCli("render " + path("box.xml") + " -D width=48 -D height=48 -q --seed 2 --spp " +
                                     std::to_string(spp + 2) + " --resume -o " + path("out.exr"));
    ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
    EXPECT_EQ(std::stoi(readImageMetadata(path("out.exr")).entries.at("caustica.spp")), spp + 2);
}

TEST_F(SessionCli, SecondInterruptQuitsAtOnceAndKeepsTheLastCheckpoint) {
    // Passes of 64 samples per pixel take long enough for the second interrupt to land inside one.
    const CliResult r = interruptedRender(2, "--spp-per-pass 64");
    EXPECT_NE(r.output.find("rc=130"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("is intact"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(path("out.exr.ckpt")), std::string::npos) << r.output;
    const CliResult resumed = runCli("render " + path("box.xml") + " -D width=48 -D height=48 -q --seed 2 --spp 200 " +
                                     "--spp-per-pass 64 --resume -o " + path("out.exr"));
    EXPECT_EQ(resumed.exitCode, 0) << resumed.output;
}

TEST_F(SessionCli, AnExistingCheckpointNeedsResumeOrOverwrite) {
    interruptedRender(1);
    ASSERT_TRUE(fs::exists(path("out.exr.ckpt")));
    const std::string before = read("out.exr.ckpt");
    const CliResult refused = runCli("render " + path("box.xml") + small + "--spp 1 -o " + path("out.exr"));
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_NE(refused.output.find(path("out.exr.ckpt") +
                                  ": a checkpoint of an unfinished render exists; pass --resume to continue it or "
                                  "--overwrite to start over"),
              std::string::npos)
        << refused.output;
    EXPECT_EQ(read("out.exr.ckpt"), before) << "nothing is deleted or changed";
    const CliResult over = runCli("render " + path("box.xml") + small + "--spp 1 --overwrite -o " + path("out.exr"));
    EXPECT_EQ(over.exitCode, 0) << over.output;
    EXPECT_FALSE(fs::exists(path("out.exr.ckpt"))) << "the finished render has nothing left to resume";
}

TEST_F(SessionCli, ResumingAnotherRenderIsRefusedWithTheFirstDifference) {
    interruptedRender(1);
    ASSERT_TRUE(fs::exists(path("out.exr.ckpt")));
    const std::string before = read("out.exr.ckpt");
    auto expectRefused = [&](const std::string& args, const std::string& what) {
        const CliResult r = runCli("render " + path("box.xml") + args + " --resume -o " + path("out.exr"));
        EXPECT_NE(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("caustica: error: " + path("out.exr.ckpt") + ": " + what), std::string::npos)
            << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_EQ(read("out.exr.ckpt"), before) << "a refused resume keeps the checkpoint as it was";
    };
    expectRefused(" -D width=48 -D height=48 -q --seed 3", "seed differs (written for 2; now 3)");
    expectRefused(" -D width=48 -D height=40 -q --seed 2", "-D values differs (written for height=48, width=48; now");
    expectRefused(" -D width=48 -D height=48 -q --seed 2 --integrator mlt", "integrator differs (written for path; now mlt)");
    std::string scene = read("box.xml");
    scene.replace(scene.find("name=\"rr_depth\" value=\"5\""), 25, "name=\"rr_depth\" value=\"6\"");
    std::ofstream(path("box.xml")) << scene;
    expectRefused(" -D width=48 -D height=48 -q --seed 2", "scene file differs (written for " + path("box.xml") + ", sha ");
}

TEST_F(SessionCli, TimeBudgetIsTheWholeRendersTime) {
    // Interrupted at its first checkpoint, then resumed with --time 1.5: the whole render takes
    // about 1.5 s, the resumed run less, and the image and statistics say the whole time.
    const CliResult first = interruptedRender(1, "--spp-per-pass 2 --time 1.5");
    ASSERT_TRUE(fs::exists(path("out.exr.ckpt"))) << first.output;
    const CliResult r = runCli("render " + path("box.xml") + " -D width=48 -D height=48 -q --seed 2 --spp 1000000 " +
                               "--spp-per-pass 2 --time 1.5 --resume --stats-json " + path("s.json") + " -o " +
                               path("out.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string json = read("s.json");
    const double seconds = std::stod(json.substr(json.find("\"seconds\": ") + 11));
    const double run = std::stod(json.substr(json.find("\"run_seconds\": ") + 15));
    EXPECT_GE(seconds, 1.0) << json;
    EXPECT_LT(run, seconds) << json;
    EXPECT_NEAR(std::stod(readImageMetadata(path("out.exr")).entries.at("caustica.renderTime")), seconds, 0.01);
}

// A render killed with SIGKILL at a random moment after its first checkpoint (mid-pass, or while
// a checkpoint is being written) resumes from the last good checkpoint to the image an
// uninterrupted render gives, bit for bit: the path tracer and MLT (sort splats: reproducible).
TEST_F(SessionCli, KilledAtARandomMomentResumesToTheUninterruptedImage) {
    std::random_device entropy;
    const std::string scene = path("box.xml") + " -D width=96 -D height=96 -q --seed 2 --accel bvh ";
    for (const std::string settings : {"--spp 256 --spp-per-pass 2",
                                       "--integrator mlt --spp 256 --splat sort --mlt-chains 256 --mlt-bootstrap 4096"}) {
        SCOPED_TRACE(settings);
        fs::remove(path("out.pfm"));
        const CliResult whole = runCli("render " + scene + settings + " -o " + path("whole.pfm"));
        ASSERT_EQ(whole.exitCode, 0) << whole.output;
        const int delayMs = int(entropy() % 400);
        const CliResult killed = runShell(
            "$CAUSTICA render " + scene + settings + " --checkpoint-every 0.01 -o " + path("out.pfm") +
            " > /dev/null 2>&1 & pid=$!\n" + "for i in $(seq 1500); do [ -f " + path("out.pfm.ckpt") +
            " ] && break; sleep 0.01; done\n" + "sleep " + std::to_string(delayMs / 1000.0) +
            "; kill -KILL $pid; wait $pid; echo rc=$?\n");
        if (!fs::exists(path("out.pfm.ckpt"))) {
            // Finished before the kill: nothing to resume, and it must have finished whole.
            EXPECT_NE(killed.output.find("rc=0"), std::string::npos) << killed.output;
        } else {
            const CliResult resumed = runCli("render " + scene + settings + " --resume -o " + path("out.pfm"));
            ASSERT_EQ(resumed.exitCode, 0) << "killed after " << delayMs << " ms: " << resumed.output;
        }
        EXPECT_TRUE(read("out.pfm") == read("whole.pfm")) << "killed after " << delayMs << " ms";
    }
}

TEST_F(SessionCli, UnwritableOutputsFailBeforeRendering) {
    // --spp 1000000 would take hours: these fail at once, naming the user's path.
    const std::string huge = small + "--spp 1000000 ";
    auto expectRefused = [&](const std::string& args, const std::string& what) {
        const CliResult r = runCli("render " + path("box.xml") + huge + args);
        EXPECT_NE(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find(".tmp"), std::string::npos) << "errors name the user's path: " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    };
    expectRefused("-o " + path("missing/out.exr"), path("missing/out.exr") + ": cannot write the image");
    fs::create_directories(path("folder.exr"));
    expectRefused("-o " + path("folder.exr"), path("folder.exr") + ": cannot write the image: it is a folder");
    expectRefused("-o " + path("a.exr") + " --stats-json " + path("missing/s.json"),
                  path("missing/s.json") + ": cannot write the statistics");
}

TEST_F(SessionCli, NonFiniteAndOutOfRangeNumbersAreRefusedReadably) {
    for (const char* bad : {"--time nan", "--time inf", "--time -1", "--spp inf", "--checkpoint-every nan",
                            "--integrator mlt --mlt-large-step nan", "--integrator mlt --mlt-s1 inf",
                            "--integrator mlt --mlt-chains 0"}) {
        const CliResult r = runCli("render " + path("box.xml") + small + bad + " -o " + path("a.exr"));
        EXPECT_NE(r.exitCode, 0) << bad << ": " << r.output;
        EXPECT_EQ(r.output.find("e+308"), std::string::npos) << bad << ": " << r.output;
        EXPECT_FALSE(fs::exists(path("a.exr"))) << bad;
    }
    const CliResult r = runCli("render " + path("box.xml") + small + "--time 0 -o " + path("a.exr"));
    EXPECT_NE(r.output.find("[0.001, 10000000] seconds"), std::string::npos) << r.output;
}

TEST_F(SessionCli, PrintsThePathsItWrote) {
    const CliResult r = runCli("render " + path("box.xml") + small + "--spp 1 -o " + path("a.exr") + " -o " +
                               path("a.png") + " --stats-json " + path("s.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* name : {"a.exr", "a.png", "s.json"})
        EXPECT_NE(r.output.find("wrote       " + path(name)), std::string::npos) << r.output;
}

}  // namespace
}  // namespace caustica::test
