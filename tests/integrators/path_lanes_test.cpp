// tracePathsSideBySide (integrators/path/path_lanes.h, on lanes.h): paths traced side by side,
// their rays in packet queries and lanes handed on from path to path, give each path's radiance
// and ray count bit for bit as pathRadiance (the megakernel's loop) does, for any number of paths,
// every max_depth / rr_depth / hide_emitters variant and both ray-tracing backends; and so do the
// Metropolis bootstrap samples built on it, against the same kernel with single-ray queries.
#include <gtest/gtest.h>

#include <cstring>
#include <type_traits>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/mlt/mlt_kernel.h"
#include "caustica/integrators/path/path_lanes.h"
#include "integrators/lane_test_scene.h"
#include "integrators/path_settings_variants.h"

namespace caustica::test {
namespace {

/// Rays from inside the box in directions spread over the sphere.
Ray laneRay(size_t item) {
    IndependentSampler s(uint64_t(item), 1, 99);
    const Vec2f u = s.get2D();
    const Vec3f o(0.1f * Float(item % 5) - 0.2f, 0.3f, 0.2f + 0.05f * Float(item % 7));
    return Ray{o, sampleUniformSphere(u), kInfinity};
}

bool sameBits(const Spectrum& a, const Spectrum& b) { return std::memcmp(&a, &b, sizeof(Spectrum)) == 0; }

TEST(PathLanes, EachPathEqualsPathRadiance) {
    const Scene scene = makeLaneTestScene();
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        const SceneView& view = accel.sceneView();
        accel.visit([&](const auto& it) {
            for (const PathSettings& settings : pathSettingsVariants())
                for (size_t count : {size_t(0), size_t(1), size_t(5), size_t(16), size_t(17), size_t(200)}) {
                    std::vector<Spectrum> got(count);
                    std::vector<uint32_t> gotRays(count, ~0u), gotDims(count);
                    std::vector<int> finished(count, 0);
                    tracePathsSideBySide<std::decay_t<decltype(it)>, IndependentSampler>(
                        view, it, settings, count,
                        [&](size_t item, IndependentSampler& sampler) {
                            sampler = IndependentSampler(uint64_t(item), 3, 5);
                            return laneRay(item);
                        },
                        [&](size_t item, const IndependentSampler& sampler, const Spectrum& L, uint32_t rays) {
                            got[item] = L;
                            gotRays[item] = rays;
                            gotDims[item] = sampler.dimension();
                            ++finished[item];
                        });
                    for (size_t item = 0; item < count; ++item) {
                        IndependentSampler sampler(uint64_t(item), 3, 5);
                        uint32_t rays = 0;
                        const Spectrum expected = pathRadiance(view, it, sampler, laneRay(item), settings, rays);
                        ASSERT_EQ(finished[item], 1) << accelKindName(kind) << " count " << count << " item " << item;
                        EXPECT_TRUE(sameBits(got[item], expected))
                            << accelKindName(kind) << " count " << count << " item " << item << " max_depth "
                            << settings.maxDepth;
                        EXPECT_EQ(gotRays[item], rays) << accelKindName(kind) << " count " << count << " item " << item;
                        EXPECT_EQ(gotDims[item], sampler.dimension());
                    }
                }
        });
    }
}

TEST(PathLanes, BootstrapSamplesEqualSingleRayOnes) {
    const Scene scene = makeLaneTestScene();
    const Accel accel(scene, AccelKind::Embree);
    const SceneView& view = accel.sceneView();
    MltStepParams p;
    p.seed = 21;
    p.width = scene.camera.width;
    p.height = scene.camera.height;
    accel.visit([&](const auto& it) {
        if constexpr (std::is_same_v<std::decay_t<decltype(it)>, EmbreeIntersector>) {
            const SingleRayEmbree single{it};
            float total = 0;  // the samples see light
            for (uint32_t n : {1u, 16u, 40u, 64u}) {
                std::vector<float> importance(n), importanceAlone(n);
                std::vector<uint32_t> pixel(n), pixelAlone(n), rays(n), raysAlone(n);
                bootstrapImportances<FloatChainStore>(view, it, p, 1000, n, importance.data(), pixel.data(),
                                                      rays.data());
                for (uint32_t l = 0; l < n; ++l)
                    bootstrapImportances<FloatChainStore>(view, single, p, 1000 + l, 1, &importanceAlone[l],
                                                          &pixelAlone[l], &raysAlone[l]);
                EXPECT_EQ(std::memcmp(importance.data(), importanceAlone.data(), n * sizeof(float)), 0) << "n " << n;
                EXPECT_EQ(pixel, pixelAlone) << "n " << n;
                EXPECT_EQ(rays, raysAlone) << "n " << n;
                for (float v : importance) total += v;
            }
            EXPECT_GT(total, 0.0f);
        }
    });
}

}  // namespace
}  // namespace caustica::test
