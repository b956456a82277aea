// exr_feature_layers_test.cpp — denoiser guides read by type from an EXR's AOV layers.
#include <gtest/gtest.h>


#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "caustica/io/exr_feature_layers.h"
#include "common/layered_exr.h"
#include "caustica/io/image_io.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

constexpr int kW = 5, kH = 3;

/// Value of channel number `channelIndex` at pixel (x, y) in the test file: distinct per channel and pixel.
float valueOf(int channelIndex, int x, int y) { return float(channelIndex) * 100.0f + float(y * kW + x); }

std::string writeLayeredExr(const std::string& name, const std::vector<std::string>& channels,
                            const std::string& aovs) {
    const std::string path = (std::filesystem::temp_directory_path() / name).string();
    test::writeLayeredExr(path, kW, kH, channels, aovs, valueOf);
    return path;
}

TEST(ExrFeatureLayers, ReadsLayersByType) {
    // Channel order in the file: R G B (0-2), then the AOVs' channels from index 3 on.
    const std::vector<std::string> channels = {"alb.R", "alb.G", "alb.B", "nn.X", "nn.Y", "nn.Z",
                                               "dd.y.T", "var.R", "var.G", "var.B", "uv.U", "uv.V"};
    const std::string path =
        writeLayeredExr("caustica_feature_layers.exr", channels, "alb:albedo,nn:sh_normal,dd.y:depth,var:variance,uv:uv");
    const DenoiseFeatures f = readFeatureLayers(path);
    ASSERT_TRUE(f.albedo && f.normal && f.depth && f.variance);
    // Each channel's values come from its position in the list the file was written from.
    std::vector<std::string> written = {"R", "G", "B"};
    written.insert(written.end(), channels.begin(), channels.end());
    auto index = [&](const std::string& c) { return int(std::find(written.begin(), written.end(), c) - written.begin()); };
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            EXPECT_EQ(f.albedo->pixel(x, y)[1], valueOf(index("alb.G"), x, y));
            EXPECT_EQ(f.normal->pixel(x, y)[2], valueOf(index("nn.Z"), x, y));
            for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(f.depth->pixel(x, y)[ch], valueOf(index("dd.y.T"), x, y));
            EXPECT_EQ(f.variance->pixel(x, y)[0], valueOf(index("var.R"), x, y));
        }
    // The colour itself still reads as R, G, B.
    EXPECT_EQ(readImage(path).pixel(1, 1)[2], valueOf(2, 1, 1));
    std::filesystem::remove(path);
}

TEST(ExrFeatureLayers, GeometricNormalWhenNoShadingNormal) {
    const std::string path = writeLayeredExr("caustica_feature_layers_gn.exr", {"gn.X", "gn.Y", "gn.Z"}, "gn:geo_normal");
    const DenoiseFeatures f = readFeatureLayers(path);
    EXPECT_TRUE(f.normal && !f.albedo && !f.depth && !f.variance);
    std::filesystem::remove(path);
}

TEST(ExrFeatureLayers, NoAttributeMeansNoGuides) {
    const std::string path = writeLayeredExr("caustica_feature_layers_none.exr", {"nn.X"}, "");
    const DenoiseFeatures f = readFeatureLayers(path);
    EXPECT_FALSE(f.albedo || f.normal || f.depth || f.variance);
    std::filesystem::remove(path);
}

TEST(ExrFeatureLayers, MissingChannelIsNamed) {
    const std::string path = writeLayeredExr("caustica_feature_layers_bad.exr", {"nn.X", "nn.Y"}, "nn:sh_normal");
    try {
        readFeatureLayers(path);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("nn.Z"), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace caustica
