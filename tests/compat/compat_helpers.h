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

constexpr int kRuns = 16, kSppPerRun = 256;

inline ReferenceComparison compareScene(const std::string& name,
                                 const std::map<std::string, std::string>& defines = {}) {
    const std::string ref = sourcePath("tests/compat/reference/" + name);
    if (!std::filesystem::exists(ref + ".exr")) {
        ADD_FAILURE() << "missing reference " << ref << ".exr";
        return {};
    }
    const Image mean = readImage(ref + ".exr"), var = readImage(ref + ".var.exr");
    const double refSpp = referenceSpp(ref + ".json");
    EXPECT_GT(refSpp, 0);
    Scene scene = loadScene(sourcePath("tests/compat/scenes/" + name + ".xml"), defines);
    RenderEnsemble ours = renderEnsemble(scene, kRuns, kSppPerRun);
    EXPECT_EQ(ours.mean.rgb.size(), mean.rgb.size());
    if (ours.mean.rgb.size() != mean.rgb.size()) return {};
    const ReferenceComparison r = compareToReference(ours, mean, var, refSpp, kRuns, kSppPerRun);
    std::string d;
    for (const auto& [k, v] : defines) d += " " + k + "=" + v;
    std::printf("compat %s%s: %s\n", name.c_str(), d.c_str(), r.describe().c_str());
    return r;
}

/// The scene matches its reference; with `wrong` defines it must not.
inline void checkPlugin(const std::string& name, const std::map<std::string, std::string>& wrong) {
    expectMatches(compareScene(name));
    const ReferenceComparison bad = compareScene(name, wrong);
    EXPECT_FALSE(bad.passed()) << name << " with a wrong parameter still matches: " << bad.describe();
}

}  // namespace caustica::test
