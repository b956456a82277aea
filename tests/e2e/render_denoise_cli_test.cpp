// render_denoise_cli_test.cpp — `caustica render --denoise`: the denoised copy beside the kept
// noisy output, the guide AOVs in the noisy EXR, bad combinations refused before rendering.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_helpers.h"
#include "render_helpers.h"
#include "caustica/io/exr_feature_layers.h"
#include "caustica/io/exr_layers.h"
#include "caustica/io/image_io.h"

namespace caustica::test {
namespace {

class RenderDenoiseCli : public CliFixture {
protected:
    const std::string box = sourcePath("scenes/cornell-box/scene.xml");
};

TEST_F(RenderDenoiseCli, WritesTheDenoisedCopyBesideTheNoisyImage) {
    const CliResult r = runCli("render " + box + " --res 32x24 --spp 4 -q --denoise nlm -o " + path("a.exr") +
                               " -o " + path("a.png"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Image noisy = readImage(path("a.exr")), denoised = readImage(path("a.denoised.exr"));
    ASSERT_TRUE(denoised.sameSize(noisy));
    EXPECT_TRUE(denoised.allFinite());
    EXPECT_NE(denoised.rgb, noisy.rgb);
    EXPECT_TRUE(std::filesystem::exists(path("a.denoised.png")));
    EXPECT_EQ(readImageMetadata(path("a.denoised.exr")).entries.at("caustica.denoiser"), "nlm");
    // The noisy EXR carries the guides the filter used, variance included (path renders passes).
    const std::string aovs = readImageMetadata(path("a.exr")).entries.at("caustica.aovs");
    for (const char* guide : {"denoise.albedo:albedo", "denoise.normal:sh_normal", "denoise.depth:depth",
                              "denoise.variance:variance"})
        EXPECT_NE(aovs.find(guide), std::string::npos) << aovs;
}

// sppm's variance guide is by batch means over its iterations (docs/AOV.md): 2 iterations, 2 batches.
TEST_F(RenderDenoiseCli, PhotonMappingGetsTheBatchVarianceGuide) {
    const CliResult r = runCli("render " + box + " --integrator sppm --res 24x16 --spp 2 -q --denoise nlm -o " +
                               path("s.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(readImage(path("s.denoised.exr")).allFinite());
    const std::string aovs = readImageMetadata(path("s.exr")).entries.at("caustica.aovs");
    EXPECT_NE(aovs.find("denoise.variance:variance"), std::string::npos) << aovs;
    EXPECT_TRUE(readFeatureLayers(path("s.exr")).variance.has_value());  // finite: used
}

TEST_F(RenderDenoiseCli, BadCombinationsAreRefusedBeforeRendering) {
    CliResult r = runCli("render " + box + " --res 8x8 --spp 1 -q --denoise fancy -o " + path("b.exr"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--denoise"), std::string::npos) << r.output;
    r = runCli("render " + box + " --res 8x8 --spp 1 -q --oidn-library /x.so -o " + path("b.exr"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--oidn-library needs --denoise oidn"), std::string::npos) << r.output;
    r = runCli("render " + box + " --res 8x8 --spp 1 -q --denoise oidn --oidn-library " + path("none.so") + " -o " +
               path("b.exr"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("none.so"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("b.exr")));
}

TEST_F(RenderDenoiseCli, StereoRendersAreDenoisedEyeByEye) {
    const CliResult r = runCli("render " + box + " --res 8x8 --spp 2 -q --denoise nlm --stereo off-axis "
                               "--stereo-output separate -o " + path("s.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* eye : {"left", "right"}) {
        EXPECT_TRUE(readImage(path(std::string("s.denoised.") + eye + ".exr")).allFinite()) << eye;
        EXPECT_FALSE(readExrLayers(path(std::string("s.") + eye + ".exr")).aovs.empty()) << eye;
    }
}

}  // namespace
}  // namespace caustica::test
