// denoise_cli_test.cpp — `caustica denoise`: output written beside the kept input, bad options
// refused with one clear line and a non-zero exit.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "caustica/io/exr_multiview.h"
#include "caustica/io/image_io.h"
#include "common/layered_exr.h"

namespace caustica::test {
namespace {

class DenoiseCli : public CliFixture {
protected:
    void SetUp() override {
        CliFixture::SetUp();
        Image noisy(16, 12);
        for (int y = 0; y < noisy.height; ++y)
            for (int x = 0; x < noisy.width; ++x) {
                const float n = float((x * 7 + y * 13) % 5) * 0.05f;  // a fixed pattern of "noise"
                noisy.set(x, y, {0.5f + n, 0.4f + n, 0.3f + n});
            }
        writeImage(path("in.exr"), noisy);
        Image albedo(16, 12);
        albedo.fill({0.7f, 0.7f, 0.7f});
        writeImage(path("albedo.exr"), albedo);
        writeImage(path("small.exr"), Image(8, 8));
    }
};

TEST_F(DenoiseCli, WritesANewFileAndKeepsTheInput) {
    const auto before = std::filesystem::last_write_time(path("in.exr"));
    const CliResult r = runCli("denoise " + path("in.exr") + " -o " + path("out.exr") + " --albedo " + path("albedo.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("guides: albedo"), std::string::npos) << r.output;
    const Image in = readImage(path("in.exr")), out = readImage(path("out.exr"));
    EXPECT_EQ(std::filesystem::last_write_time(path("in.exr")), before);
    EXPECT_TRUE(out.sameSize(in) && out.allFinite());
    EXPECT_NE(out.rgb, in.rgb);
    EXPECT_EQ(readImageMetadata(path("out.exr")).entries.at("caustica.denoiser"), "nlm");
}

TEST_F(DenoiseCli, UsesTheInputsAovLayers) {
    // Colour: a step at x = 8 plus a fixed pattern; albedo layer with the same step.
    auto value = [](int channel, int x, int y) {
        const float step = x >= 8 ? 1.0f : 0.1f;
        if (channel < 3) return step + float((x * 7 + y * 13) % 5) * 0.02f;
        return channel < 6 ? step * 0.5f : 0.0f;  // alb.R/G/B; the other layer's channels 0
    };
    writeLayeredExr(path("layered.exr"), 16, 12, {"alb.R", "alb.G", "alb.B", "nn.X", "nn.Y", "nn.Z"},
                    "alb:albedo,nn:sh_normal", value);
    CliResult r = runCli("denoise " + path("layered.exr") + " -o " + path("out.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("guides: albedo normal)"), std::string::npos) << r.output;
    EXPECT_EQ(readImageMetadata(path("out.exr")).entries.count("caustica.aovs"), 0u);
    r = runCli("denoise " + path("layered.exr") + " -o " + path("out2.exr") + " --ignore-layers");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("guides: none)"), std::string::npos) << r.output;
}

TEST_F(DenoiseCli, DenoisesAStereoPairViewByViewIntoAMultiViewExr) {
    writeMultiViewExr(path("pair.exr"), readImage(path("in.exr")), readImage(path("albedo.exr")));
    CliResult r = runCli("denoise " + path("pair.exr") + " -o " + path("pair.denoised.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("views left and right"), std::string::npos) << r.output;
    EXPECT_EQ(exrViews(path("pair.denoised.exr")), (std::vector<std::string>{"left", "right"}));
    r = runCli("denoise " + path("pair.exr") + " -o " + path("pair.png"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("multi-view EXR"), std::string::npos) << r.output;
}

TEST_F(DenoiseCli, RefusesToOverwriteTheInput) {
    const CliResult r = runCli("denoise " + path("in.exr") + " -o " + path("in.exr"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("overwrite the noisy input"), std::string::npos) << r.output;
}

TEST_F(DenoiseCli, RefusesAnUnknownMethod) {
    const CliResult r = runCli("denoise " + path("in.exr") + " -o " + path("out.exr") + " --method magic");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("unknown denoiser 'magic'"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("out.exr")));
}

TEST_F(DenoiseCli, RefusesAMissingFeatureFile) {
    const CliResult r = runCli("denoise " + path("in.exr") + " -o " + path("out.exr") + " --normal " + path("nope.exr"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("nope.exr"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("out.exr")));
}

TEST_F(DenoiseCli, RefusesAFeatureOfAnotherSize) {
    const CliResult r = runCli("denoise " + path("in.exr") + " -o " + path("out.exr") + " --depth " + path("small.exr"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("depth image is 8 x 8"), std::string::npos) << r.output;
}

TEST_F(DenoiseCli, RefusesOidnFromABogusLibraryPath) {
    const CliResult r = runCli("denoise " + path("in.exr") + " -o " + path("out.exr") +
                               " --method oidn --oidn-library " + path("libOpenImageDenoise.so.2"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("libOpenImageDenoise.so.2"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("out.exr")));
}

TEST_F(DenoiseCli, SaysOidnIsNotFoundWhenNothingIsThere) {
    // An empty environment: no PATH python, no HOME, no CAUSTICA_OIDN_LIBRARY.
    const CliResult r = runCliCommand("env -i " + std::string(CAUSTICA_BINARY) + " denoise " + path("in.exr") +
                                      " -o " + path("out.exr") + " --method oidn 2>&1");
    if (r.exitCode == 0) GTEST_SKIP() << "an OIDN library is on the system library path";
    EXPECT_NE(r.output.find("OIDN not found: give --oidn-library or install pyoidn"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace caustica::test
