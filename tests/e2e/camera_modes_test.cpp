// camera_modes_test.cpp — the thin lens draws its aperture sample from the pixel's sampler in
// both path-tracer execution modes, so the wavefront renders a thin-lens (and a cropped) scene to
// the megakernel's image; a pinhole scene does not draw it (its random numbers are unchanged).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render_helpers.h"

namespace caustica::test {
namespace {

double maxRelDiff(const Image& a, const Image& b) {
    double worst = 0;
    for (size_t j = 0; j < a.rgb.size(); ++j) {
        const double x = a.rgb[j], y = b.rgb[j], s = std::max(std::fabs(x), std::fabs(y));
        if (s > 0) worst = std::max(worst, std::fabs(x - y) / s);
    }
    return worst;
}

TEST(CameraModes, WavefrontMatchesMegakernelWithThinLensAndCrop) {
    for (const char* name : {"thinlens", "crop", "orthographic"}) {
        const Scene scene = loadScene(sourcePath("tests/compat/scenes/" + std::string(name) + ".xml"));
        const Image mega = renderImage(scene, {4, 5, AccelKind::Bvh, 0, false});
        const Image wave = renderImage(scene, {4, 5, AccelKind::Bvh, 0, true});
        ASSERT_EQ(mega.rgb.size(), wave.rgb.size());
        EXPECT_EQ(mega.width, scene.film.width);
        EXPECT_LE(maxRelDiff(mega, wave), 1e-5) << name;
    }
}

TEST(CameraModes, ClosedThinLensRendersThePinholeImage) {
    // aperture_radius 0 draws no lens sample: the same random numbers as the perspective camera.
    Scene lens = loadScene(sourcePath("tests/compat/scenes/thinlens.xml"));
    lens.camera.apertureRadius = 0;
    Scene pin = lens;
    pin.camera.type = CameraType::Perspective;
    const Image a = renderImage(lens, {2, 3, AccelKind::Bvh, 0, false});
    const Image b = renderImage(pin, {2, 3, AccelKind::Bvh, 0, false});
    EXPECT_LE(maxRelDiff(a, b), 1e-6);
}

}  // namespace
}  // namespace caustica::test
