// exr_multiview_test.cpp — the multi-view EXR with AOV layers (io/exr_multiview.h): channel
// names after OpenEXR's multi-view convention (checked with OpenEXR's own viewFromChannelName),
// a bit-exact round trip of both views' images and layers, and refusals.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiView.h>
#include <OpenEXR/ImfStandardAttributes.h>

#include <set>

#include "caustica/io/exr_multiview.h"
#include "caustica/util/error.h"
#include "io/scene_test_util.h"

namespace caustica::test {
namespace {

AovImage testAovs(int w, int h, float offset) {
    AovImage aovs;
    aovs.width = w;
    aovs.height = h;
    aovs.spec = parseAovSpec("dd.y:depth,nn:sh_normal", "test");
    aovs.channels = aovs.spec.channelNames();
    for (size_t i = 0; i < size_t(w * h) * aovs.channels.size(); ++i) aovs.values.push_back(float(i) * 0.5f + offset);
    return aovs;
}

Image testImage(int w, int h, float offset) {
    Image image(w, h);
    for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(i) * 0.25f + offset;
    return image;
}

TEST(ExrMultiView, ChannelNamesFollowOpenExrsConvention) {
    EXPECT_EQ(multiViewChannelName("R", 0), "R");
    EXPECT_EQ(multiViewChannelName("R", 1), "right.R");
    EXPECT_EQ(multiViewChannelName("nn.X", 0), "nn.left.X");
    EXPECT_EQ(multiViewChannelName("dd.y.T", 1), "dd.y.right.T");

    TempDir dir;
    writeMultiViewExr(dir.path("a.exr"), testImage(4, 3, 0), testImage(4, 3, 100), {}, testAovs(4, 3, 0),
                      testAovs(4, 3, 1000));
    Imf::InputFile file(dir.path("a.exr").c_str());
    const Imf::StringVector views = Imf::multiView(file.header());
    std::set<std::string> names;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
        names.insert(it.name());
        // Every channel belongs to a view: none is "in no view" for Nuke or Blender.
        const std::string view = Imf::viewFromChannelName(it.name(), views);
        EXPECT_EQ(view, std::string(it.name()).find("right") != std::string::npos ? "right" : "left") << it.name();
    }
    EXPECT_EQ(names, (std::set<std::string>{"R", "G", "B", "right.R", "right.G", "right.B", "dd.y.left.T",
                                            "dd.y.right.T", "nn.left.X", "nn.left.Y", "nn.left.Z", "nn.right.X",
                                            "nn.right.Y", "nn.right.Z"}));
    EXPECT_EQ(Imf::channelsInView("right", file.header().channels(), views).begin().name(), std::string("dd.y.right.T"));
}

TEST(ExrMultiView, ViewsAndLayersRoundTripBitForBit) {
    TempDir dir;
    const AovImage left = testAovs(5, 2, 0), right = testAovs(5, 2, -50);
    writeMultiViewExr(dir.path("a.exr"), testImage(5, 2, 0), testImage(5, 2, 7), {}, left, right);
    const StereoImagePair read = readMultiViewExr(dir.path("a.exr"));
    EXPECT_TRUE(read.left.rgb == testImage(5, 2, 0).rgb);
    EXPECT_TRUE(read.right.rgb == testImage(5, 2, 7).rgb);
    EXPECT_EQ(read.leftAovs.spec.text(), "dd.y:depth,nn:sh_normal");
    EXPECT_EQ(read.rightAovs.channels, right.channels);
    EXPECT_TRUE(read.leftAovs.values == left.values);
    EXPECT_TRUE(read.rightAovs.values == right.values);
    // Without AOVs: no layers, no attribute.
    writeMultiViewExr(dir.path("b.exr"), testImage(5, 2, 0), testImage(5, 2, 7));
    EXPECT_TRUE(readMultiViewExr(dir.path("b.exr")).leftAovs.empty());
}

TEST(ExrMultiView, MismatchedLayersAreRefused) {
    TempDir dir;
    AovImage other = testAovs(5, 2, 0);
    other.spec = parseAovSpec("dd.y:depth,mm:sh_normal", "test");
    other.channels = other.spec.channelNames();
    EXPECT_THROW(writeMultiViewExr(dir.path("a.exr"), testImage(5, 2, 0), testImage(5, 2, 0), {}, testAovs(5, 2, 0),
                                   other),
                 Error);
    EXPECT_THROW(writeMultiViewExr(dir.path("a.exr"), testImage(5, 2, 0), testImage(5, 2, 0), {}, testAovs(4, 2, 0),
                                   testAovs(4, 2, 0)),
                 Error);
    EXPECT_THROW(writeMultiViewExr(dir.path("a.exr"), testImage(5, 2, 0), testImage(5, 2, 0), {}, testAovs(5, 2, 0)),
                 Error);
    // A single-view EXR is not a stereo pair.
    writeImage(dir.path("mono.exr"), testImage(5, 2, 0));
    EXPECT_THROW(readMultiViewExr(dir.path("mono.exr")), Error);
}

}  // namespace
}  // namespace caustica::test
