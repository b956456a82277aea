// The wavefront path tracer (one kernel per bounce stage, compacted queues) renders the bundled
// scenes to the same image as the megakernel, for both ray-tracing backends, and its image does
// not depend on the thread count; `caustica render --path-mode wavefront` writes the same file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "render_helpers.h"

namespace caustica::test {
namespace {

Scene smallScene(const std::string& name, int size = 32) {
    return loadScene(sourcePath("scenes/" + name + "/scene.xml"),
                     {{"width", std::to_string(size)}, {"height", std::to_string(size)}});
}

/// Largest |a - b| / max(|a|, |b|) over all channels (0 where both are 0).
double maxRelativeDifference(const Image& a, const Image& b) {
    double worst = 0;
    for (size_t j = 0; j < a.rgb.size(); ++j) {
        double x = a.rgb[j], y = b.rgb[j], scale = std::max(std::fabs(x), std::fabs(y));
        if (scale > 0) worst = std::max(worst, std::fabs(x - y) / scale);
    }
    return worst;
}

TEST(Wavefront, MatchesTheMegakernelOnTheBundledScenes) {
    for (const char* name : {"cornell-box", "cornell-water", "glass-caustic"}) {
        Scene scene = smallScene(name);
        for (AccelKind accel : {AccelKind::Embree, AccelKind::Bvh}) {
            Image mega = renderImage(scene, {4, 5, accel, 0, false});
            Image wave = renderImage(scene, {4, 5, accel, 0, true});
            ASSERT_EQ(mega.rgb.size(), wave.rgb.size());
            EXPECT_LE(maxRelativeDifference(mega, wave), 1e-5)
                << name << ", " << accelKindName(accel);
            double sum = 0;
            for (float v : wave.rgb) sum += v;
            EXPECT_GT(sum, 0) << name << ": the image must not be black";
        }
    }
}

TEST(Wavefront, OneAndTwoThreadsGiveBitIdenticalImages) {
    Scene scene = smallScene("cornell-water", 24);
    Image one = renderImage(scene, {4, 9, AccelKind::Bvh, 1, true});
    Image two = renderImage(scene, {4, 9, AccelKind::Bvh, 2, true});
    ASSERT_EQ(one.rgb.size(), two.rgb.size());
    EXPECT_EQ(0, std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)));
}

TEST(Wavefront, CommandLineModesWriteTheSameFile) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "caustica_wavefront_cli";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string scene = sourcePath("scenes/cornell-water/scene.xml");
    auto render = [&](const std::string& mode) {
        const std::string out = (dir / (mode + ".pfm")).string();
        const std::string cmd = std::string(CAUSTICA_BINARY) + " render " + scene +
                                " --res 16x16 --spp 3 --seed 4 -q --checkpoint-every 0" +
                                " --path-mode " + mode + " -o " + out + " > /dev/null 2>&1";
        EXPECT_EQ(0, std::system(cmd.c_str())) << cmd;
        std::ifstream in(out, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const std::string mega = render("megakernel"), wave = render("wavefront");
    EXPECT_FALSE(mega.empty());
    EXPECT_EQ(mega, wave);
    EXPECT_NE(0, std::system((std::string(CAUSTICA_BINARY) + " render " + scene +
                              " --path-mode sideways -q > /dev/null 2>&1").c_str()));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace caustica::test
