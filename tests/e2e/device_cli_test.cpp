// device_cli_test.cpp — `caustica render --device cpu|cuda|auto`, `--gpu-mode` and
// `--kernel-stats` through the command line. Passes on any machine: with or without the CUDA
// backend in the binary, with or without a GPU (where the outcome depends on that, each
// possibility is checked for being the right one).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

using Result = CliResult;
inline Result run(const std::string& args) { return runCli(args); }

class DeviceCli : public CliFixture {
protected:
    std::string small() const { return box + " -D width=16 -D height=12 --spp 2 "; }
    const std::string box = sourcePath("scenes/cornell-box/scene.xml");
};

TEST_F(DeviceCli, CpuRendersAndNamesTheDevice) {
    Result r = run("render " + small() + "--device cpu -o " + path("c.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("device: cpu"), std::string::npos) << r.output;
    EXPECT_EQ(readImage(path("c.exr")).width, 16);
}

TEST_F(DeviceCli, AutoAlwaysRenders) {
    // A binary without CUDA, or a machine without a GPU, falls back to the CPU.
    Result r = run("render " + small() + "--device auto -o " + path("a.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const bool cpu = r.output.find("device: cpu") != std::string::npos;
    const bool cuda = r.output.find("device: cuda") != std::string::npos;
    EXPECT_TRUE(cpu != cuda) << r.output;
    EXPECT_EQ(readImage(path("a.exr")).height, 12);
}

TEST_F(DeviceCli, CudaRendersOrFailsWithOneClearLine) {
    Result r = run("render " + small() + "--device cuda -o " + path("g.exr"));
    if (r.exitCode == 0) {  // a CUDA binary on a machine with a GPU
        EXPECT_NE(r.output.find("device: cuda"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("GPU memory needed"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("peak"), std::string::npos) << r.output;
        return;
    }
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("caustica: error: --device cuda: ", 0), 0u) << r.output;
    const bool noGpu = r.output.find("no CUDA GPU found") != std::string::npos;
    const bool noBackend = r.output.find("built without the CUDA backend") != std::string::npos;
    EXPECT_TRUE(noGpu || noBackend) << r.output;
    EXPECT_FALSE(fs::exists(path("g.exr")));
}

TEST_F(DeviceCli, UnknownDeviceOrGpuModeIsRefused) {
    Result bad = run("render " + small() + "--device tpu -o " + path("x.exr"));
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("--device"), std::string::npos) << bad.output;
    Result mode = run("render " + small() + "--gpu-mode fast -o " + path("y.exr"));
    EXPECT_NE(mode.exitCode, 0);
    EXPECT_NE(mode.output.find("--gpu-mode"), std::string::npos) << mode.output;
}

TEST_F(DeviceCli, KernelStatsTableOnTheCpu) {
    for (const char* mode : {"megakernel", "wavefront"}) {
        Result r = run("render " + small() + "--device cpu -q --kernel-stats --path-mode " + mode +
                       " -o " + path("k.exr"));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("kernel statistics (cpu)"), std::string::npos) << r.output;
        const char* kernel = std::string(mode) == "wavefront" ? "wavefront.extend" : "path.megakernel";
        EXPECT_NE(r.output.find(kernel), std::string::npos) << r.output;
    }
}

// Without --path-mode the CPU runs the wavefront (render_request.h: its default).
TEST_F(DeviceCli, CpuPathTracerDefaultsToTheWavefront) {
    Result r = run("render " + small() + "--device cpu -q --kernel-stats -o " + path("d.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("wavefront.extend"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("path.megakernel"), std::string::npos) << r.output;
}

TEST_F(DeviceCli, GpuModeDoesNotChangeACpuRender) {
    // --gpu-mode governs the GPU only: a CPU render is the same image whatever it says.
    ASSERT_EQ(run("render " + small() + "--device cpu -q --gpu-mode megakernel -o " + path("m.exr")).exitCode, 0);
    ASSERT_EQ(run("render " + small() + "--device cpu -q --gpu-mode wavefront -o " + path("w.exr")).exitCode, 0);
    EXPECT_EQ(readImage(path("m.exr")).rgb, readImage(path("w.exr")).rgb);
}

}  // namespace
}  // namespace caustica::test
