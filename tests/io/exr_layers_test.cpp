// exr_layers_test.cpp — the layered EXR (io/exr_layers.h): image and AOV channels round trip
// bit for bit with the caustica.aovs attribute and the metadata; refusals.
#include <gtest/gtest.h>

#include "caustica/io/exr_layers.h"
#include "caustica/io/image_io.h"
#include "caustica/util/error.h"
#include "io/scene_test_util.h"

namespace caustica::test {
namespace {

TEST(ExrLayers, RoundTripOfImageLayersAndAttribute) {
    TempDir dir;
    Image image(5, 3);
    for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(i) * 0.25f;
    AovImage aovs;
    aovs.width = 5;
    aovs.height = 3;
    aovs.spec = parseAovSpec("dd.y:depth,nn:sh_normal,uv:uv", "test");
    aovs.channels = aovs.spec.channelNames();
    for (size_t i = 0; i < 15 * aovs.channels.size(); ++i) aovs.values.push_back(float(i) - 7.5f);
    ImageMetadata meta;
    meta.entries["caustica.spp"] = "16";
    writeExrLayers(dir.path("a.exr"), image, aovs, meta);

    const ExrLayers read = readExrLayers(dir.path("a.exr"));
    EXPECT_TRUE(read.image.rgb == image.rgb);
    EXPECT_EQ(read.metadata.entries.at("caustica.aovs"), "dd.y:depth,nn:sh_normal,uv:uv");
    EXPECT_EQ(read.metadata.entries.at("caustica.spp"), "16");
    EXPECT_EQ(read.aovs.channels, aovs.channels);
    EXPECT_TRUE(read.aovs.values == aovs.values);
    EXPECT_EQ(read.aovs.firstChannelOf(AovType::ShNormal), 1);
    EXPECT_EQ(read.aovs.firstChannelOf(AovType::Albedo), -1);
    // Any EXR reader sees the image: readImage takes R, G, B.
    EXPECT_TRUE(readImage(dir.path("a.exr")).rgb == image.rgb);
}

TEST(ExrLayers, PlainExrHasNoLayersAndBadInputIsRefused) {
    TempDir dir;
    Image image(2, 2);
    writeImage(dir.path("plain.exr"), image);
    EXPECT_TRUE(readExrLayers(dir.path("plain.exr")).aovs.empty());
    AovImage aovs;
    aovs.width = 2;
    aovs.height = 2;
    aovs.spec = parseAovSpec("d:depth", "test");
    aovs.channels = aovs.spec.channelNames();
    aovs.values.assign(3, 0.0f);  // one short
    EXPECT_THROW(writeExrLayers(dir.path("b.exr"), image, aovs), Error);
    aovs.values.assign(4, 0.0f);
    ImageMetadata clash;
    clash.entries["caustica.aovs"] = "x";
    EXPECT_THROW(writeExrLayers(dir.path("c.exr"), image, aovs, clash), Error);
}

}  // namespace
}  // namespace caustica::test
