// mlt_device_cli_test.cpp — `caustica render --integrator mlt --device cpu|cuda|auto`. Passes on
// any machine: with or without the CUDA backend in the binary, with or without a GPU (where the
// outcome depends on that, each possibility is checked for being the right one).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

class MltDeviceCli : public CliFixture {
protected:
    std::string small() const {
        return "render " + sourcePath("scenes/cornell-box/scene.xml") +
               " -D width=16 -D height=12 --spp 2 --integrator mlt --mlt-chains 64 --mlt-bootstrap 1024 "
               "--checkpoint-every 0 ";
    }
    /// A failed run: exit 1, one line "caustica: error: ...".
    static void expectOneLineError(const CliResult& r) {
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_EQ(r.output.rfind("caustica: error: ", 0), 0u) << r.output;
    }
    static bool noGpuError(const CliResult& r) {
        return r.output.rfind("caustica: error: --device cuda: ", 0) == 0 &&
               (r.output.find("no CUDA GPU found") != std::string::npos ||
                r.output.find("built without the CUDA backend") != std::string::npos);
    }
};

TEST_F(MltDeviceCli, CpuNamesTheDevice) {
    const CliResult r = runCli(small() + "--device cpu -o " + path("c.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("device: cpu; integrator mlt"), std::string::npos) << r.output;
}

TEST_F(MltDeviceCli, CudaRendersOrFailsWithOneClearLine) {
    const CliResult r = runCli(small() + "--device cuda -o " + path("g.exr"));
    if (r.exitCode == 0) {  // a CUDA binary on a machine with a GPU
        EXPECT_NE(r.output.find("device: cuda, "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("GPU memory: peak"), std::string::npos) << r.output;
        EXPECT_EQ(readImage(path("g.exr")).width, 16);
        return;
    }
    expectOneLineError(r);
    EXPECT_TRUE(noGpuError(r)) << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("g.exr")));
}

TEST_F(MltDeviceCli, AutoAlwaysRenders) {
    const CliResult r = runCli(small() + "--device auto -o " + path("a.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const bool cpu = r.output.find("device: cpu") != std::string::npos;
    const bool cuda = r.output.find("device: cuda") != std::string::npos;
    EXPECT_TRUE(cpu != cuda) << r.output;
}

TEST_F(MltDeviceCli, FloatStateRunsOnTheCpuOnly) {
    // auto falls back to the CPU; cuda refuses it in one line (or has no GPU at all).
    const CliResult a = runCli(small() + "--mlt-state float --device auto -o " + path("f.exr"));
    ASSERT_EQ(a.exitCode, 0) << a.output;
    EXPECT_NE(a.output.find("device: cpu"), std::string::npos) << a.output;
    const CliResult g = runCli(small() + "--mlt-state float --device cuda -o " + path("g.exr"));
    expectOneLineError(g);
    EXPECT_TRUE(noGpuError(g) || g.output.find("--mlt-state float") != std::string::npos) << g.output;
}

}  // namespace
}  // namespace caustica::test
