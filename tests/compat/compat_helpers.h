// compat_helpers.h — shared by the compatibility tests (tests/compat/*_test.cpp): renders a scene
// of tests/compat/scenes with its own integrator as an ensemble of independent runs and compares
// it with its Mitsuba 3 reference (tests/compat/reference, scripts/make_compat_references.py) by
// the statistics of tests/common/image_stats.h.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "caustica/io/image_io.h"
#include "common/image_stats.h"
#include "e2e/render_helpers.h"

namespace caustica::test {

/// Each comparison renders kRuns independent runs (the image-mean z-test needs that many run
/// means). A matching case takes kMatchSppPerRun samples per pixel per run (2048 in all, against
/// the references' 8192); a case with a wrong parameter only needs enough to fail with margin:
/// kWrongSppPerRun by default, more for the few subtle wrong parameters (their tests pass a
/// budget). Halving the budget roughly halves a bias's block z² and relMSE excess.
constexpr int kRuns = 16, kMatchSppPerRun = 128, kWrongSppPerRun = 32;

/// Renders tests/compat/scenes/<name>.xml with `defines` (kRuns runs of `sppPerRun`) and
/// compares it with its reference; prints the statistics as a `compat ...` line.
inline ReferenceComparison compareScene(const std::string& name,
                                        const std::map<std::string, std::string>& defines = {},
                                        int sppPerRun = kMatchSppPerRun) {
    const std::string ref = sourcePath("tests/compat/reference/" + name);
    if (!std::filesystem::exists(ref + ".exr")) {
        ADD_FAILURE() << "missing reference " << ref << ".exr";
        return {};
    }
    const Image mean = readImage(ref + ".exr"), var = readImage(ref + ".var.exr");
    const double refSpp = referenceSpp(ref + ".json");
    EXPECT_GT(refSpp, 0);
    Scene scene = loadScene(sourcePath("tests/compat/scenes/" + name + ".xml"), defines);
    RenderEnsemble ours = renderEnsemble(scene, kRuns, sppPerRun);
    EXPECT_EQ(ours.mean.rgb.size(), mean.rgb.size());
    if (ours.mean.rgb.size() != mean.rgb.size()) return {};
    const ReferenceComparison r = compareToReference(ours, mean, var, refSpp, kRuns, sppPerRun);
    std::string d;
    for (const auto& [k, v] : defines) d += " " + k + "=" + v;
    std::printf("compat %s%s (%d spp): %s\n", name.c_str(), d.c_str(), kRuns * sppPerRun,
                r.describe().c_str());
    return r;
}

/// The scene matches its reference; with `wrong` defines (rendered with `wrongSppPerRun`) it
/// must not.
inline void checkPlugin(const std::string& name, const std::map<std::string, std::string>& wrong,
                        int wrongSppPerRun = kWrongSppPerRun) {
    expectMatches(compareScene(name));
    const ReferenceComparison bad = compareScene(name, wrong, wrongSppPerRun);
    EXPECT_FALSE(bad.passed()) << name << " with a wrong parameter still matches: " << bad.describe();
}

}  // namespace caustica::test
