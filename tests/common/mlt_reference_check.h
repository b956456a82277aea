// mlt_reference_check.h — what the CPU (tests/e2e/mlt_test.cpp) and GPU
// (tests/gpu/gpu_mlt_test.cpp) MLT tests share: small test settings, R renders of a bundled scene
// against its Mitsuba 3 reference with the block statistics of block_agreement.h (and the power to
// reject a brighter image), and the scene, settings and image difference with which sort and atomic
// splats are compared.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/film/filter.h"
#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/io/image_io.h"
#include "caustica/io/scene_loader.h"
#include "common/block_agreement.h"
#include "e2e/render_helpers.h"

namespace caustica::test {

/// 4096 chains and 2^17 bootstrap samples, the rest default: small enough for tests.
inline MltSettings smallMltSettings() {
    MltSettings s;
    s.chains = 4096;
    s.bootstrapSamples = 1 << 17;
    return s;
}

/// A bundled scene and its reference (paths relative to the source tree; the reference without
/// ".exr", REF.var.exr beside it), the mutations per pixel of a run, and the relative brightness
/// error the statistics must reject when the power is checked.
struct MltCase {
    const char* scene;
    const char* reference;
    double mutationsPerPixel;
    double detectableError;
};

/// `runs` renders of `c.scene` at its reference's size, `render(scene, accel, settings, seed,
/// mutationsPerPixel)` for seeds 100, 101, ..., must agree with the reference; with `checkPower`
/// the same statistics must reject them made brighter by `c.detectableError`. `driver` names the
/// renderer on the printed line.
template <class Render>
void checkMltAgainstReference(const MltCase& c, const MltSettings& settings, AccelKind accelKind,
                              const char* driver, bool checkPower, int runs, Render&& render) {
    const std::string refPath = sourcePath(c.reference);
    const Image ref = readImage(refPath + ".exr"), refVar = readImage(refPath + ".var.exr");
    const Scene scene = loadScene(sourcePath(c.scene), {{"width", std::to_string(ref.width)},
                                                        {"height", std::to_string(ref.height)}});
    const Accel accel(scene, accelKind);
    std::vector<Image> images;
    for (int r = 0; r < runs; ++r)
        images.push_back(render(scene, accel, settings, 100 + uint64_t(r), c.mutationsPerPixel));
    const BlockStats ours = blocksOfRuns(images), theirs = blocksOfReference(ref, refVar);
    const Agreement a = compare(ours, theirs);
    std::printf(
        "%s %s (k=%u, %s, %s, sort every %u): block mean z^2 %.2f, image-mean z %.2f, bias "
        "%+.2f%%\n",
        c.scene, driver, settings.proposals,
        settings.state == MltStateKind::Compact ? "compact" : "float",
        settings.splat == MltSplatKind::Atomic ? "atomic" : "sort", settings.sortEvery, a.meanZ2,
        a.imageZ, 100 * a.relBias);
    EXPECT_TRUE(a.passed(runs)) << "block mean z^2 " << a.meanZ2 << ", image-mean z " << a.imageZ;
    if (!checkPower) return;
    // Power: the same statistics reject a brighter image.
    const Agreement wrong = compare(ours, theirs, 1 + c.detectableError);
    EXPECT_FALSE(wrong.passed(runs))
        << "an error of " << 100 * c.detectableError << "% is not detected: mean z^2 "
        << wrong.meanZ2 << ", image-mean z " << wrong.imageZ;
}

/// Where sort and atomic splats are compared: cornell-box at 24 x 16 through a wide Gaussian filter
/// (a splat lands on many pixels), 512 chains, Morton sorting every 3 iterations, sort splats.
inline Scene splatComparisonScene() {
    Scene scene =
        loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "24"}, {"height", "16"}});
    scene.film.filter = FilterDesc{FilterType::Gaussian, 2.0f, 0.5f};
    return scene;
}

inline MltSettings splatComparisonSettings() {
    MltSettings s = smallMltSettings();
    s.chains = 512;
    s.bootstrapSamples = 4096;
    s.splat = MltSplatKind::Sort;
    s.sortEvery = 3;
    return s;
}

/// The largest |a - b| / (|b| + 1e-3) over all samples of two images of the same size.
inline double maxRelativeDifference(const Image& a, const Image& b) {
    double maxRel = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        maxRel = std::max(
            maxRel, std::fabs(double(a.rgb[i]) - b.rgb[i]) / (std::fabs(double(b.rgb[i])) + 1e-3));
    return maxRel;
}

}  // namespace caustica::test
