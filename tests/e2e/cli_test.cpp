// The `caustica` command line: outputs, statistics, errors on bad input, checkpoints and resume.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

using Result = CliResult;
inline Result run(const std::string& args) { return runCli(args); }

class Cli : public CliFixture {
protected:
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path(name)) << text;
        return path(name);
    }
    const std::string box = sourcePath("scenes/cornell-box/scene.xml");

    // A render killed (SIGKILL, no chance to clean up) after it wrote a checkpoint, resumed to
    // `target` samples (or mutations) per pixel, gives the uninterrupted render's image bit for bit.
    // The resume runs with `resumeArgs` when given (settings a resume may leave out), else `args`.
    void expectKilledRenderResumes(const std::string& scene, const std::string& args, int target,
                                   const std::string& resumeArgs = "") {
        std::string cmd = std::string(CAUSTICA_BINARY) + " render " + scene + args +
                          "--spp 100000 --checkpoint-every 0.05 -o " + path("part.exr") + " >/dev/null 2>&1 & echo $!";
        FILE* p = popen(cmd.c_str(), "r");
        ASSERT_NE(p, nullptr);
        int pid = 0;
        ASSERT_EQ(fscanf(p, "%d", &pid), 1);
        pclose(p);
        const std::string ckpt = path("part.exr") + ".ckpt";
        for (int i = 0; i < 600 && !fs::exists(ckpt); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        std::system(("kill -9 " + std::to_string(pid)).c_str());
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        ASSERT_TRUE(fs::exists(ckpt)) << "no checkpoint was written";
        // The image written with the checkpoint is a valid image holding the finished work.
        const int partial = std::stoi(readImageMetadata(path("part.exr")).entries.at("caustica.spp"));
        if (partial >= target) GTEST_SKIP() << "the killed render was already at " << partial << " per pixel";

        Result resumed = run("render " + scene + (resumeArgs.empty() ? args : resumeArgs) + "--spp " +
                             std::to_string(target) + " --resume -o " + path("part.exr"));
        ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
        EXPECT_NE(resumed.output.find("resuming from"), std::string::npos) << resumed.output;
        EXPECT_FALSE(fs::exists(ckpt)) << "a finished render removes its checkpoint";
        ASSERT_EQ(run("render " + scene + args + "--spp " + std::to_string(target) + " -o " + path("full.exr")).exitCode, 0);
        Image a = readImage(path("full.exr")), b = readImage(path("part.exr"));
        ASSERT_EQ(a.rgb.size(), b.rgb.size());
        EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)))
            << "the resumed render differs from the uninterrupted one (killed at " << partial << " per pixel)";
    }
};

TEST_F(Cli, RendersAllFormatsWithStatistics) {
    Result r = run("render " + box + " -D width=16 -D height=12 --spp 2 -q -o " + path("a.exr") + " -o " +
                   path("a.png") + " -o " + path("a.pfm") + " --stats-json " + path("stats.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* f : {"a.exr", "a.png", "a.pfm"}) {
        Image im = readImage(path(f));
        EXPECT_EQ(im.width, 16);
        EXPECT_EQ(im.height, 12);
    }
    EXPECT_EQ(readImageMetadata(path("a.exr")).entries.at("caustica.spp"), "2");
    std::ifstream js(path("stats.json"));
    std::string json((std::istreambuf_iterator<char>(js)), {});
    EXPECT_NE(json.find("\"rays_per_second\""), std::string::npos);
    EXPECT_NE(r.output.find("samples/s"), std::string::npos);
    EXPECT_NE(r.output.find("rays/s"), std::string::npos);
}

// --embree-isa caps Embree's instruction set; the statistics say which cap and packet width ran
// (the default, auto, resolves to widest or sse4.2 by the CPU: embree_isa.h).
TEST_F(Cli, EmbreeInstructionSetIsChosenAndReported) {
    auto statsOf = [&](const std::string& extra) {
        Result r = run("render " + box + " -D width=8 -D height=8 --spp 1 -q -o " + path("e.pfm") + " --stats-json " +
                       path("e.json") + extra);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        std::ifstream js(path("e.json"));
        return std::string((std::istreambuf_iterator<char>(js)), {});
    };
    EXPECT_NE(statsOf(" --embree-isa sse4.2").find("\"accel_description\": \"embree (sse4.2, 4-ray packets)\""),
              std::string::npos);
    const std::string automatic = statsOf("");
    EXPECT_TRUE(automatic.find("\"embree (widest, ") != std::string::npos ||
                automatic.find("\"embree (sse4.2, 4-ray packets)\"") != std::string::npos)
        << automatic;
    EXPECT_NE(statsOf(" --accel bvh").find("\"accel_description\": \"bvh\""), std::string::npos);
    Result bad = run("render " + box + " --embree-isa avx2 -q -o " + path("e.pfm"));
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("--embree-isa"), std::string::npos) << bad.output;
}

TEST_F(Cli, TimeBudgetStopsTheRender) {
    Result r = run("render " + box + " -D width=16 -D height=16 --time 0.5 -q -o " + path("t.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_GE(std::stoi(readImageMetadata(path("t.exr")).entries.at("caustica.spp")), 1);
}

TEST_F(Cli, ResolutionOverrideAndSeed) {
    ASSERT_EQ(run("render " + box + " --res 20x10 --spp 1 --seed 5 -q -o " + path("r.exr")).exitCode, 0);
    Image im = readImage(path("r.exr"));
    EXPECT_EQ(im.width, 20);
    EXPECT_EQ(im.height, 10);
}

TEST_F(Cli, CompareAndInfo) {
    ASSERT_EQ(run("render " + box + " -D width=8 -D height=8 --spp 1 -q -o " + path("c.exr")).exitCode, 0);
    Result c = run("compare " + path("c.exr") + " " + path("c.exr") + " --json -e " + path("err.png"));
    ASSERT_EQ(c.exitCode, 0) << c.output;
    EXPECT_NE(c.output.find("\"mse\": 0"), std::string::npos) << c.output;
    EXPECT_NE(c.output.find("\"relmse_worst_1pct_share\": 0"), std::string::npos) << c.output;
    EXPECT_NE(c.output.find("\"mean_ratio\": 1"), std::string::npos) << c.output;
    writeImage(path("black.exr"), Image(8, 8));  // no mean to divide by: null, JSON has no NaN
    Result black = run("compare " + path("c.exr") + " " + path("black.exr") + " --json");
    ASSERT_EQ(black.exitCode, 0) << black.output;
    EXPECT_NE(black.output.find("\"mean_ratio\": null"), std::string::npos) << black.output;
    EXPECT_TRUE(fs::exists(path("err.png")));
    Result i = run("info " + box);
    ASSERT_EQ(i.exitCode, 0) << i.output;
    EXPECT_NE(i.output.find("triangles"), std::string::npos);
    EXPECT_NE(i.output.find("bvh"), std::string::npos);
    for (const char* cmd : {"render --help", "compare --help", "info --help", "--help"})
        EXPECT_EQ(run(cmd).exitCode, 0) << cmd;
}

/// Bad input: non-zero exit, one line "caustica: error: ..." naming what is wrong.
void expectOneLineError(const Result& r, const std::string& mustContain) {
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("caustica: error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(mustContain), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST_F(Cli, BadInputIsRefusedWithOneLine) {
    std::string malformed = write("malformed.xml", "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n</scene>\n");
    expectOneLineError(run("render " + malformed + " -q -o " + path("x.exr")), "malformed.xml:");
    std::string unknown = write("unknown.xml", "<scene version=\"3.0.0\">\n\n<shape type=\"teapot\"/>\n</scene>\n");
    expectOneLineError(run("render " + unknown + " -q -o " + path("x.exr")), "unknown.xml:3");
    std::string missing = write("missing.xml",
        "<scene version=\"3.0.0\">\n<shape type=\"obj\"><string name=\"filename\" value=\"nope.obj\"/></shape>\n</scene>\n");
    expectOneLineError(run("render " + missing + " -q -o " + path("x.exr")), "nope.obj");
    expectOneLineError(run("render " + box + " --res 0x0 -q -o " + path("x.exr")), "absurd resolution");
    expectOneLineError(run("render " + box + " -q -o " + path("x.bmp")), "x.bmp");
    expectOneLineError(run("compare " + path("none.exr") + " " + path("none.exr")), "none.exr");
}

TEST_F(Cli, KilledRenderResumesToTheSameImage) {
    expectKilledRenderResumes(box, " -D width=64 -D height=64 --spp-per-pass 1 -q --seed 3 ", 200);
}

// MLT keeps its chains, splat sums, b and counters (sort splats: the image is bit-reproducible).
// The resume gives no --mlt-chains and takes the checkpoint's 64, not the default 1024 (a render
// started on a GPU, whose default differs, resumes on the CPU so).
TEST_F(Cli, KilledMltRenderResumesToTheSameImage) {
    const std::string common = " -D width=32 -D height=32 --integrator mlt --mlt-bootstrap 4096 --splat sort -q --seed 3 ";
    expectKilledRenderResumes(box, common + "--mlt-chains 64 ", 60, common);
}

TEST_F(Cli, ResumingWithAnotherIntegratorsCheckpointIsRefused) {
    const std::string args = " -D width=8 -D height=8 -q --seed 1 --checkpoint-every 0 ";
    // A path checkpoint is left by an interrupted render; make one by hand from a finished one.
    ASSERT_EQ(run("render " + box + args + "--spp 1 -o " + path("p.exr")).exitCode, 0);
    std::ofstream(path("p.exr.ckpt")) << "CAUSCKP1 not an MLT checkpoint";
    expectOneLineError(run("render " + box + args + "--integrator mlt --mlt-chains 16 --spp 1 --resume -o " +
                           path("p.exr")),
                       "p.exr.ckpt");
}

TEST_F(Cli, ResumeWithoutCheckpointIsRefused) {
    expectOneLineError(run("render " + box + " -D width=8 -D height=8 --resume -q -o " + path("nope.exr")),
                       "nope.exr.ckpt");
}

}  // namespace
}  // namespace caustica::test
