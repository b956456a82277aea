// image_compare_test.cpp — error metrics on hand-computed arrays, false-colour images, viridis.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "caustica/film/colormap.h"
#include "caustica/film/image_compare.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

Image makeImage(int w, int h, std::vector<float> rgb) {
    Image img(w, h);
    img.rgb = std::move(rgb);
    return img;
}

TEST(ImageCompare, HandComputedMetrics) {
    const Image test = makeImage(2, 1, {1, 2, 3, 0, 0, 0});
    const Image ref = makeImage(2, 1, {1, 1, 1, 1, 0, 2});
    // differences 0, 1, 2, -1, 0, -2
    const ErrorMetrics m = compareImages(test, ref);
    EXPECT_EQ(m.pixels, 2u);
    EXPECT_DOUBLE_EQ(m.mse, 10.0 / 6);
    EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(10.0 / 6));
    EXPECT_DOUBLE_EQ(m.mae, 1.0);
    const double rel = (0 + 1 / 1.01 + 4 / 1.01 + 1 / 1.01 + 0 / 0.01 + 4 / 4.01) / 6;
    EXPECT_NEAR(m.relMse, rel, 1e-15);
    EXPECT_DOUBLE_EQ(m.meanRatio, 6.0 / 6.0);  // both sum to 6
    EXPECT_DOUBLE_EQ(compareImages(makeImage(1, 1, {1, 2, 3}), makeImage(1, 1, {2, 2, 2})).meanRatio, 1.0);
    EXPECT_DOUBLE_EQ(compareImages(makeImage(1, 1, {1, 1, 1}), makeImage(1, 1, {4, 0, 0})).meanRatio, 0.75);
    EXPECT_TRUE(std::isnan(compareImages(test, makeImage(2, 1, {0, 0, 0, 0, 0, 0})).meanRatio));
}

// The share of relMse carried by the worst 1% of pixels (rounded up): one bad pixel among 200 carries
// nearly all of it; even errors over 250 pixels give the worst 3 their 3 / 250.
TEST(ImageCompare, WorstPercentShareOfRelMse) {
    Image ref(20, 10), test(20, 10);
    for (float& v : ref.rgb) v = 0.5f;
    test = ref;
    EXPECT_EQ(compareImages(test, ref).relMseWorstShare, 0.0);  // no error at all
    test.set(3, 4, Spectrum(5.0f));  // the worst 1% of 200 pixels is 2: this one and a small one
    for (int x : {7, 8, 9}) test.set(x, 1, Spectrum(0.51f));
    const ErrorMetrics one = compareImages(test, ref);
    const double big = 4.5 * 4.5, small = 0.01 * 0.01;  // (a - b)^2 over the same b^2 + 0.01
    EXPECT_NEAR(one.relMseWorstShare, (big + small) / (big + 3 * small), 1e-6);
    Image evenRef(25, 10), even(25, 10);
    for (float& v : evenRef.rgb) v = 1.0f;
    for (float& v : even.rgb) v = 1.5f;
    EXPECT_NEAR(compareImages(even, evenRef).relMseWorstShare, 3.0 / 250, 1e-12);
    even.set(0, 0, Spectrum(std::numeric_limits<float>::quiet_NaN()));
    EXPECT_TRUE(std::isnan(compareImages(even, evenRef).relMseWorstShare));
}

TEST(ImageCompare, IdenticalImagesHaveZeroError) {
    const Image a = makeImage(1, 2, {0.5f, 7, 0, 1e3f, 2, 3});
    const ErrorMetrics m = compareImages(a, a);
    EXPECT_EQ(m.mse, 0);
    EXPECT_EQ(m.relMse, 0);
    EXPECT_EQ(m.mae, 0);
}

TEST(ImageCompare, RelMseUsesTheSecondImageAsReference) {
    const Image a = makeImage(1, 1, {1, 1, 1}), b = makeImage(1, 1, {3, 3, 3});
    EXPECT_DOUBLE_EQ(compareImages(a, b).relMse, 4 / 9.01);
    EXPECT_DOUBLE_EQ(compareImages(b, a).relMse, 4 / 1.01);
}

TEST(ImageCompare, CountsNonFiniteValuesAndPixels) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const NonFiniteCount n = countNonFinite(makeImage(3, 1, {1, nan, inf, 0, 0, 0, -inf, 2, 3}));
    EXPECT_EQ(n.values, 3u);
    EXPECT_EQ(n.pixels, 2u);
    const NonFiniteCount none = countNonFinite(makeImage(1, 1, {1e30f, -2, 0}));
    EXPECT_EQ(none.values, 0u);
    EXPECT_EQ(none.pixels, 0u);
}

TEST(ImageCompare, SizeMismatchThrows) {
    EXPECT_THROW(compareImages(Image(2, 3), Image(3, 2)), Error);
    EXPECT_THROW(falseColourError(Image(2, 3), Image(2, 2)), Error);
}

TEST(ImageCompare, FalseColourSizeAndFiniteness) {
    Image test(16, 9), ref(16, 9);
    for (size_t i = 0; i < ref.rgb.size(); ++i) {
        ref.rgb[i] = float(i % 7) * 0.3f;
        test.rgb[i] = ref.rgb[i] + float(i % 5) * 0.1f;
    }
    test.rgb[5] = std::numeric_limits<float>::quiet_NaN();
    test.rgb[9] = std::numeric_limits<float>::infinity();
    for (double scale : {0.0, 0.5, 1e-9}) {
        const Image fc = falseColourError(test, ref, scale);
        EXPECT_EQ(fc.width, 16);
        EXPECT_EQ(fc.height, 9);
        EXPECT_TRUE(fc.allFinite());
        for (float v : fc.rgb) {
            EXPECT_GE(v, 0.0f);
            EXPECT_LE(v, 1.0f);
        }
    }
    // Identical images: the bottom of the colormap everywhere.
    const Image same = falseColourError(ref, ref);
    const Spectrum bottom = viridis(0);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 16; ++x) EXPECT_EQ(same.at(x, y).g, bottom.g);
}

TEST(ImageCompare, FalseColourAutoScaleSaturatesAtPercentile) {
    // 200 pixels with error growing with the index: the top 1% saturate, the smallest is dark.
    Image test(200, 1), ref(200, 1);
    for (int x = 0; x < 200; ++x) test.set(x, 0, Spectrum(0.1f * float(x)));
    const Image fc = falseColourError(test, ref);
    EXPECT_EQ(fc.at(199, 0).g, viridis(1).g);
    EXPECT_EQ(fc.at(0, 0).g, viridis(0).g);
    EXPECT_LT(fc.at(100, 0).g, fc.at(150, 0).g);  // viridis' green grows monotonically
}

TEST(Colormap, ViridisMatchesMatplotlibAnchors) {
    // matplotlib's _viridis_data at t = 0, 0.25, 0.5, 0.75, 1 (sRGB).
    const float anchors[5][3] = {{0.267004f, 0.004874f, 0.329415f},
                                 {0.229739f, 0.322361f, 0.545706f},
                                 {0.127568f, 0.566949f, 0.550556f},
                                 {0.369214f, 0.788888f, 0.382914f},
                                 {0.993248f, 0.906157f, 0.143936f}};
    for (int i = 0; i < 5; ++i) {
        const Spectrum s = viridisSrgb(0.25f * float(i));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s[c], anchors[i][c], 0.02) << i << " " << c;
        const Spectrum lin = viridis(0.25f * float(i));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(linearToSrgb(lin[c]), s[c], 1e-5);
    }
    EXPECT_EQ(viridisSrgb(-1).r, viridisSrgb(0).r);
    EXPECT_EQ(viridisSrgb(std::numeric_limits<float>::quiet_NaN()).r, viridisSrgb(0).r);
    EXPECT_EQ(viridisSrgb(5).g, viridisSrgb(1).g);
}

TEST(Colormap, SrgbTransferRoundTrips) {
    for (float v = 0; v <= 1.0f; v += 1.0f / 64)
        EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-6);
    EXPECT_EQ(linearToSrgb(2.0f), 1.0f);
    EXPECT_EQ(linearToSrgb(-1.0f), 0.0f);
    EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5);
}

}  // namespace
}  // namespace caustica
