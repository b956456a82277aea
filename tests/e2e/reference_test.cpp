// End-to-end: caustica's path tracer against reference images rendered by Mitsuba 3 (scalar_rgb,
// made by scripts/make_references.py). Tolerances come from the noise of both images: per-pixel
// z-scores with variances estimated from independent renders, a z-test on the image mean, and a
// relMSE bound of a few times the relMSE the noise alone explains.
#include <gtest/gtest.h>

#include <filesystem>

#include "caustica/io/image_io.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

struct ReferenceCase {
    const char* scene;
    const char* reference;  // without extension; REF.exr is the mean, REF.var.exr its variance
    int runs, sppPerRun;
};

void checkAgainstReference(const ReferenceCase& c) {
    const std::string refPath = sourcePath(c.reference);
    ASSERT_TRUE(std::filesystem::exists(refPath + ".exr")) << refPath;
    Image ref = readImage(refPath + ".exr");
    Image refVar = readImage(refPath + ".var.exr");
    Scene scene = loadScene(sourcePath(c.scene), {{"width", std::to_string(ref.width)},
                                                  {"height", std::to_string(ref.height)}});
    RenderEnsemble ours = renderEnsemble(scene, c.runs, c.sppPerRun);
    ASSERT_EQ(ours.mean.rgb.size(), ref.rgb.size());

    double z2Sum = 0, relMse = 0, expectedRelMse = 0, refMean = 0, refMeanVar = 0;
    size_t n = 0;
    for (size_t j = 0; j < ref.rgb.size(); ++j) {
        const double a = ours.mean.rgb[j], b = ref.rgb[j];
        const double var = double(ours.varianceOfMean.rgb[j]) + double(refVar.rgb[j]);
        relMse += (a - b) * (a - b) / (b * b + 0.01);
        expectedRelMse += var / (b * b + 0.01);
        refMean += b;
        refMeanVar += refVar.rgb[j];
        if (var <= 0) {
            EXPECT_NEAR(a, b, 1e-5) << "noise-free pixel value " << j;
            continue;
        }
        z2Sum += (a - b) * (a - b) / var;
        ++n;
    }
    const double P = double(ref.rgb.size());
    relMse /= P;
    expectedRelMse /= P;
    refMean /= P;
    // Pixels of the reference are correlated only through its own filter (box here): treat them
    // as independent but allow a factor 4 in variance for safety.
    refMeanVar = 4 * refMeanVar / (P * P);
    const double ourMean = meanOf(ours.runImageMeans);
    const double z = (ourMean - refMean) / std::sqrt(varianceOfMeanOf(ours.runImageMeans) + refMeanVar);

    // Mean of z² is ~1 for unbiased agreement (~1.1 with variances estimated from few runs).
    EXPECT_LT(z2Sum / double(n), 1.6) << "per-pixel disagreement beyond the noise";
    EXPECT_LT(std::fabs(z), 4.0) << "image mean " << ourMean << " vs reference " << refMean;
    EXPECT_LT(relMse, 3 * expectedRelMse + 1e-6) << "relMSE " << relMse << " expected ~" << expectedRelMse;
    RecordProperty("mean_z2", std::to_string(z2Sum / double(n)));
    RecordProperty("image_mean_z", std::to_string(z));
}

TEST(MitsubaReference, CornellBox) {
    checkAgainstReference({"scenes/cornell-box/scene.xml", "scenes/cornell-box/reference/cornell-box-64", 16, 64});
}

}  // namespace
}  // namespace caustica::test
