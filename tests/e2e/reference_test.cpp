// End-to-end: caustica's path tracer against reference images rendered by Mitsuba 3 (scalar_rgb;
// glass-caustic: llvm_ad_rgb; made by scripts/make_references.py). Tolerances come from the noise
// of both images: per-pixel z-scores with variances estimated from independent renders, a z-test
// on the image mean, and a relMSE bound of a few times the relMSE the noise alone explains.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "caustica/io/image_io.h"
#include "common/image_stats.h"
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
    const double refSpp = referenceSpp(refPath + ".json");
    ASSERT_GT(refSpp, 0);
    // The statistics and their bounds: tests/common/image_stats.h.
    const ReferenceComparison r = compareToReference(ours, ref, refVar, refSpp, c.runs, c.sppPerRun);
    expectMatches(r);
    std::printf("%s: %s\n", c.scene, r.describe().c_str());
}

TEST(MitsubaReference, CornellBox) {
    checkAgainstReference({"scenes/cornell-box/scene.xml", "scenes/cornell-box/reference/cornell-box-64", 16, 64});
}

TEST(MitsubaReference, CornellWater) {
    checkAgainstReference({"scenes/cornell-water/scene.xml", "scenes/cornell-water/reference/cornell-water-64", 16, 64});
}

TEST(MitsubaReference, DoorGap) {
    // Light only through a narrow gap: the path tracer's noisiest bundled scene.
    checkAgainstReference({"scenes/door-gap/scene.xml", "scenes/door-gap/reference/door-gap-64", 16, 64});
}

TEST(MitsubaReference, GlassCaustic) {
    // A glass ball focuses a small light into a one-pixel caustic (at 64x64) inside its shadow;
    // the small light reaches the rest of the shadow only through the glass (rare paths).
    checkAgainstReference({"scenes/glass-caustic/scene.xml", "scenes/glass-caustic/reference/glass-caustic-64", 16, 64});
}

}  // namespace
}  // namespace caustica::test
