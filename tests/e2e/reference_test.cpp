// End-to-end: caustica's path tracer against reference images rendered by Mitsuba 3 (scalar_rgb,
// made by scripts/make_references.py). Tolerances come from the noise of both images: per-pixel
// z-scores with variances estimated from independent renders, a z-test on the image mean, and a
// relMSE bound of a few times the relMSE the noise alone explains.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "caustica/io/image_io.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

struct ReferenceCase {
    const char* scene;
    const char* reference;  // without extension; REF.exr is the mean, REF.var.exr its variance
    int runs, sppPerRun;
};

/// The "spp" entry of a reference's JSON sidecar.
double referenceSpp(const std::string& jsonPath) {
    std::ifstream f(jsonPath);
    std::string text((std::istreambuf_iterator<char>(f)), {});
    size_t at = text.rfind("\"spp\":");
    return at == std::string::npos ? 0 : std::atof(text.c_str() + at + 6);
}

/// Per-pixel z = (a - b) / sqrt(var_a + var_b) over all channels with noise.
struct ZScores {
    std::vector<double> pixel;  // one per channel value with noise
    double blockZ2Mean = 0;     // mean z² of 8x8-pixel block means
};

ZScores zScores(const Image& ours, const Image& oursVar, const Image& ref, const Image& refVar) {
    ZScores z;
    for (size_t j = 0; j < ref.rgb.size(); ++j) {
        const double var = double(oursVar.rgb[j]) + double(refVar.rgb[j]);
        if (var > 0) z.pixel.push_back((double(ours.rgb[j]) - ref.rgb[j]) / std::sqrt(var));
        else EXPECT_NEAR(ours.rgb[j], ref.rgb[j], 1e-5) << "noise-free value " << j;
    }
    // The box filter keeps pixels independent, so a block's variance is the sum of its pixels'.
    constexpr int kBlock = 8;
    int blocks = 0;
    for (int by = 0; by + kBlock <= ref.height; by += kBlock)
        for (int bx = 0; bx + kBlock <= ref.width; bx += kBlock)
            for (int c = 0; c < 3; ++c) {
                double d = 0, var = 0;
                for (int y = by; y < by + kBlock; ++y)
                    for (int x = bx; x < bx + kBlock; ++x) {
                        size_t j = (size_t(y) * ref.width + x) * 3 + c;
                        d += double(ours.rgb[j]) - ref.rgb[j];
                        var += double(oursVar.rgb[j]) + refVar.rgb[j];
                    }
                if (var <= 0) continue;
                z.blockZ2Mean += d * d / var;
                ++blocks;
            }
    z.blockZ2Mean /= std::max(1, blocks);
    return z;
}

double medianAbs(std::vector<double> v) {
    for (double& x : v) x = std::fabs(x);
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

void checkAgainstReference(const ReferenceCase& c) {
    const std::string refPath = sourcePath(c.reference);
    ASSERT_TRUE(std::filesystem::exists(refPath + ".exr")) << refPath;
    Image ref = readImage(refPath + ".exr");
    Image refVar = readImage(refPath + ".var.exr");
    Scene scene = loadScene(sourcePath(c.scene), {{"width", std::to_string(ref.width)},
                                                  {"height", std::to_string(ref.height)}});
    RenderEnsemble ours = renderEnsemble(scene, c.runs, c.sppPerRun);
    ASSERT_EQ(ours.mean.rgb.size(), ref.rgb.size());
    // Heavy tails (rare caustic paths) make a variance estimated from a few runs too small in
    // most pixels. Both renderers are path tracers with NEE and MIS, so their per-sample variances
    // are alike: take the larger of our estimate and the reference's scaled to our sample count.
    const double refSpp = referenceSpp(refPath + ".json");
    ASSERT_GT(refSpp, 0);
    const double sppRatio = refSpp / double(c.runs * c.sppPerRun);
    for (size_t j = 0; j < ref.rgb.size(); ++j)
        ours.varianceOfMean.rgb[j] = float(std::max(double(ours.varianceOfMean.rgb[j]), refVar.rgb[j] * sppRatio));

    // Caustic paths make both estimators heavy-tailed, so the per-pixel test is the median |z|
    // (0.674 for unbiased normal noise, robust to fireflies; a bias of one sigma per pixel
    // raises it to about 1.0); block means are closer to normal and get a z² test.
    ZScores z = zScores(ours.mean, ours.varianceOfMean, ref, refVar);
    ASSERT_GT(z.pixel.size(), ref.rgb.size() / 2);
    const double medianZ = medianAbs(z.pixel);
    EXPECT_LT(medianZ, 0.85) << "per-pixel disagreement beyond the noise";
    EXPECT_LT(z.blockZ2Mean, 2.5) << "8x8 block means disagree beyond the noise";

    double relMse = 0, expectedRelMse = 0, refMean = 0, refMeanVar = 0;
    for (size_t j = 0; j < ref.rgb.size(); ++j) {
        const double a = ours.mean.rgb[j], b = ref.rgb[j];
        relMse += (a - b) * (a - b) / (b * b + 0.01);
        expectedRelMse += (double(ours.varianceOfMean.rgb[j]) + refVar.rgb[j]) / (b * b + 0.01);
        refMean += b;
        refMeanVar += refVar.rgb[j];
    }
    const double P = double(ref.rgb.size());
    relMse /= P;
    expectedRelMse /= P;
    refMean /= P;
    refMeanVar /= P * P;
    const double ourMean = meanOf(ours.runImageMeans);
    const double zMean = (ourMean - refMean) / std::sqrt(varianceOfMeanOf(ours.runImageMeans) + refMeanVar);
    EXPECT_LT(std::fabs(zMean), 4.0) << "image mean " << ourMean << " vs reference " << refMean;
    EXPECT_LT(relMse, 3 * expectedRelMse + 1e-6) << "relMSE " << relMse << " expected ~" << expectedRelMse;
    std::printf("%s: median |z| %.3f, block z² %.3f, image-mean z %.2f, relMSE %.3g (noise explains %.3g)\n",
                c.scene, medianZ, z.blockZ2Mean, zMean, relMse, expectedRelMse);
}

TEST(MitsubaReference, CornellBox) {
    checkAgainstReference({"scenes/cornell-box/scene.xml", "scenes/cornell-box/reference/cornell-box-64", 16, 64});
}

TEST(MitsubaReference, CornellWater) {
    checkAgainstReference({"scenes/cornell-water/scene.xml", "scenes/cornell-water/reference/cornell-water-64", 16, 64});
}

}  // namespace
}  // namespace caustica::test
