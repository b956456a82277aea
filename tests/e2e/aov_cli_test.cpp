// aov_cli_test.cpp — `caustica render --aov`: the .exr output holds the image and the AOV layers
// with the caustica.aovs attribute, the .png the image only; a bad list is one line.
#include <gtest/gtest.h>

#include <algorithm>

#include "caustica/io/exr_layers.h"
#include "cli_helpers.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

using AovCli = CliFixture;

TEST_F(AovCli, RenderWritesTheLayersIntoTheExr) {
    const std::string box = sourcePath("scenes/cornell-box/scene.xml");
    const CliResult r = runCli(
        "render " + box + " --res 16x12 --spp 2 -q --aov dd.y:depth,nn:sh_normal,var:variance -o " +
        path("a.exr") + " -o " + path("a.png"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const ExrLayers read = readExrLayers(path("a.exr"));
    EXPECT_EQ(read.metadata.entries.at("caustica.aovs"), "dd.y:depth,nn:sh_normal,var:variance");
    const std::vector<std::string> channels = {"dd.y.T", "nn.X",  "nn.Y", "nn.Z",
                                               "var.R",  "var.G", "var.B"};
    EXPECT_EQ(read.aovs.channels, channels);
    // The camera at z = 3.9 sees the boxes (depth ~1.6) and walls (up to ~5.1), and past the open
    // front beside them (0: a miss).
    int hits = 0;
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 16; ++x) {
            const float d = read.aovs.at(x, y, 0);
            EXPECT_TRUE(d >= 0 && d < 5.2f) << d;
            hits += d > 1.0f;
        }
    EXPECT_GT(hits, 150);
    EXPECT_TRUE(readExrLayers(path("a.png")).aovs.empty());

    const CliResult bad =
        runCli("render " + box + " --res 16x12 --spp 1 -q --aov dd.y -o " + path("b.exr"));
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("caustica: error: --aov: aov 'dd.y' is not a NAME:TYPE pair"),
              std::string::npos)
        << bad.output;
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
}

}  // namespace
}  // namespace caustica::test
