// The image depends only on the seed, never on the thread count; the two ray-tracing backends
// agree within noise; different seeds give different noise.
#include <gtest/gtest.h>

#include <cstring>

#include "render_helpers.h"

namespace caustica::test {
namespace {

Scene smallCornell(int size = 32) {
    return loadScene(sourcePath("scenes/cornell-box/scene.xml"),
                     {{"width", std::to_string(size)}, {"height", std::to_string(size)}});
}

TEST(Determinism, OneAndTwoThreadsGiveBitIdenticalImages) {
    Scene scene = smallCornell();
    for (AccelKind accel : {AccelKind::Embree, AccelKind::Bvh}) {
        Image one = renderImage(scene, {8, 7, accel, 1});
        Image two = renderImage(scene, {8, 7, accel, 2});
        ASSERT_EQ(one.rgb.size(), two.rgb.size());
        EXPECT_EQ(0, std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)))
            << "accel " << accelKindName(accel);
    }
}

TEST(Determinism, WaterSceneIsThreadIndependentToo) {
    Scene scene = loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "24"}, {"height", "24"}});
    Image one = renderImage(scene, {4, 3, AccelKind::Bvh, 1});
    Image two = renderImage(scene, {4, 3, AccelKind::Bvh, 2});
    EXPECT_EQ(0, std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)));
}

TEST(Determinism, SeedChangesTheNoise) {
    Scene scene = smallCornell(16);
    Image a = renderImage(scene, {2, 1, AccelKind::Embree, 0});
    Image b = renderImage(scene, {2, 2, AccelKind::Embree, 0});
    EXPECT_NE(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)));
}

TEST(Backends, OwnBvhAndEmbreeConvergeToTheSameImage) {
    Scene scene = smallCornell(24);
    RenderEnsemble bvh = renderEnsemble(scene, 8, 16, AccelKind::Bvh);
    RenderEnsemble embree = renderEnsemble(scene, 8, 16, AccelKind::Embree);
    double z2 = 0;
    size_t n = 0;
    for (size_t j = 0; j < bvh.mean.rgb.size(); ++j) {
        double var = double(bvh.varianceOfMean.rgb[j]) + embree.varianceOfMean.rgb[j];
        double d = double(bvh.mean.rgb[j]) - embree.mean.rgb[j];
        if (var > 0) {
            z2 += d * d / var;
            ++n;
        }
    }
    EXPECT_LT(z2 / double(n), 1.6);
    double z = (meanOf(bvh.runImageMeans) - meanOf(embree.runImageMeans)) /
               std::sqrt(varianceOfMeanOf(bvh.runImageMeans) + varianceOfMeanOf(embree.runImageMeans));
    EXPECT_LT(std::fabs(z), 4.0);
}

}  // namespace
}  // namespace caustica::test
