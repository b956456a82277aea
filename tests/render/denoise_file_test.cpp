// denoise_file_test.cpp — `caustica denoise` of files (render/denoise_file.h): a multi-view
// (stereo) EXR denoised view by view with each view's own layers into a multi-view EXR, a
// single-view file as before, and the refusals (views other than left/right, guide files or a
// non-EXR output for a multi-view input, the input as output).
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiView.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>

#include <filesystem>
#include <string>
#include <vector>

#include "caustica/io/exr_feature_layers.h"
#include "caustica/io/exr_multiview.h"
#include "caustica/io/image_io.h"
#include "caustica/render/denoise_file.h"
#include "caustica/util/error.h"
#include "io/scene_test_util.h"

namespace caustica::test {
namespace {

constexpr int kW = 24, kH = 16;

/// A two-region image (left half dark, right half bright) with deterministic noise of `seed`.
Image noisyImage(uint32_t seed) {
    Image image(kW, kH);
    uint32_t s = seed * 2654435761u + 1;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) {
                s = s * 1664525u + 1013904223u;
                image.pixel(x, y)[c] = (x < kW / 2 ? 0.2f : 0.8f) + 0.3f * (float(s >> 8) / 16777216.0f - 0.5f);
            }
    return image;
}

/// Albedo, normal, depth and variance layers: the edge at column `edge`.
AovImage guides(int edge, float variance) {
    AovImage a;
    a.width = kW;
    a.height = kH;
    a.spec = parseAovSpec("a:albedo,n:sh_normal,d:depth,v:variance", "test");
    a.channels = a.spec.channelNames();
    const size_t C = a.channels.size();
    a.values.assign(size_t(kW) * kH * C, 0.0f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float* v = &a.values[(size_t(y) * kW + size_t(x)) * C];
            const float side = x < edge ? 0.2f : 0.9f;
            v[0] = v[1] = v[2] = side;            // albedo
            v[5] = 1;                             // normal +z
            v[6] = x < edge ? 2.0f : 5.0f;        // depth
            v[7] = v[8] = v[9] = variance;        // variance
        }
    return a;
}

DenoiseSettings nlm() { return DenoiseSettings{}; }

TEST(DenoiseFile, MultiViewIsDenoisedViewByViewWithItsOwnGuides) {
    TempDir dir;
    const Image left = noisyImage(1), right = noisyImage(2);
    const AovImage leftGuides = guides(kW / 2, 1e-3f), rightGuides = guides(kW / 3, 4e-3f);
    const std::string in = dir.path("pair.exr"), out = dir.path("pair.denoised.exr");
    writeMultiViewExr(in, left, right, {}, leftGuides, rightGuides);
    const DenoiseFileResult r = denoiseFile(DenoiseFileRequest{.input = in, .output = out}, nlm());
    EXPECT_EQ(r.views, 2);
    EXPECT_EQ(r.width, kW);
    EXPECT_TRUE(r.albedo && r.normal && r.depth && r.variance);
    EXPECT_EQ(exrViews(out), (std::vector<std::string>{"left", "right"}));
    const StereoImagePair got = readMultiViewExr(out);
    EXPECT_TRUE(got.leftAovs.empty());  // the output holds the colour only
    EXPECT_TRUE(got.left.rgb == denoise(left, featuresFromAovs(leftGuides), nlm()).rgb);
    EXPECT_TRUE(got.right.rgb == denoise(right, featuresFromAovs(rightGuides), nlm()).rgb);
    // The right view's own guides matter: the left view's give another image.
    EXPECT_FALSE(got.right.rgb == denoise(right, featuresFromAovs(leftGuides), nlm()).rgb);
    EXPECT_EQ(readImageMetadata(out).entries.at("caustica.denoiser"), "nlm");
    // --ignore-layers: no guides in either view.
    DenoiseFileRequest bare{.input = in, .output = dir.path("bare.exr")};
    bare.ignoreLayers = true;
    EXPECT_FALSE(denoiseFile(bare, nlm()).albedo);
    EXPECT_TRUE(readMultiViewExr(dir.path("bare.exr")).right.rgb == denoise(right, DenoiseFeatures{}, nlm()).rgb);
}

TEST(DenoiseFile, SingleViewFileIsDenoisedAsBefore) {
    TempDir dir;
    const Image noisy = noisyImage(3);
    writeImage(dir.path("a.exr"), noisy);
    writeImage(dir.path("albedo.exr"), noisy);
    DenoiseFileRequest req{.input = dir.path("a.exr"), .output = dir.path("b.exr")};
    req.albedo = dir.path("albedo.exr");
    const DenoiseFileResult r = denoiseFile(req, nlm());
    EXPECT_EQ(r.views, 1);
    EXPECT_TRUE(r.albedo);
    EXPECT_TRUE(exrViews(dir.path("b.exr")).empty());
    DenoiseFeatures f;
    f.albedo = noisy;
    EXPECT_TRUE(readImage(dir.path("b.exr")).rgb == denoise(noisy, f, nlm()).rgb);
}

/// A multi-view EXR of `views` (each with R, G, B; the first unprefixed), black.
void writeViews(const std::string& path, const std::vector<std::string>& views) {
    Imf::Header header(kW, kH);
    std::vector<std::string> names;
    for (size_t v = 0; v < views.size(); ++v)
        for (const char* c : {"R", "G", "B"}) names.push_back(v == 0 ? std::string(c) : views[v] + "." + c);
    for (const std::string& n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
    Imf::addMultiView(header, Imf::StringVector(views.begin(), views.end()));
    std::vector<float> zeros(size_t(kW) * kH, 0.0f);
    Imf::FrameBuffer fb;
    for (const std::string& n : names)
        fb.insert(n, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(zeros.data()), sizeof(float), sizeof(float) * kW));
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(kH);
}

void expectRefused(const DenoiseFileRequest& req, const std::string& part) {
    try {
        denoiseFile(req, nlm());
        ADD_FAILURE() << "accepted; expected: " << part;
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(part), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
    }
    if (req.output != req.input) {
        EXPECT_FALSE(std::filesystem::exists(req.output)) << req.output;
    }
}

TEST(DenoiseFile, RefusesOtherViewsGuideFilesAndNonExrOutputsForMultiView) {
    TempDir dir;
    writeViews(dir.path("three.exr"), {"left", "right", "center"});
    expectRefused({dir.path("three.exr"), dir.path("o1.exr")}, "expected the views left and right");
    writeViews(dir.path("swapped.exr"), {"right", "left"});
    expectRefused({dir.path("swapped.exr"), dir.path("o2.exr")}, "expected the views left and right");
    writeMultiViewExr(dir.path("pair.exr"), noisyImage(1), noisyImage(2));
    DenoiseFileRequest withAlbedo{.input = dir.path("pair.exr"), .output = dir.path("o3.exr")};
    withAlbedo.albedo = dir.path("pair.exr");
    expectRefused(withAlbedo, "--albedo");
    expectRefused({dir.path("pair.exr"), dir.path("o4.png")}, "multi-view EXR");
    expectRefused({dir.path("pair.exr"), dir.path("pair.exr")}, "overwrite the noisy input");
}

}  // namespace
}  // namespace caustica::test
