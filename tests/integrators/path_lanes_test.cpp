// pathRadianceLanes (integrators/path/path_lanes.h): paths traced side by side, their rays in
// packet queries, give each path's radiance and ray count bit for bit as pathRadiance (the
// megakernel's loop) does, for any number of lanes, every max_depth / rr_depth / hide_emitters
// variant and both ray-tracing backends; and so do the Metropolis kernels built on it
// (evaluatePrimarySamples against one evaluation per sample).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/mlt/mlt_kernel.h"
#include "caustica/integrators/path/path_lanes.h"
#include "integrators/lane_test_scene.h"
#include "integrators/path_settings_variants.h"

namespace caustica::test {
namespace {

/// Camera-like rays from the box's open middle in directions spread over the sphere.
Ray laneRay(int j) {
    IndependentSampler s(uint64_t(j), 1, 99);
    const Vec2f u = s.get2D();
    const Vec3f o(0.1f * Float(j % 5) - 0.2f, 0.3f, 0.2f + 0.05f * Float(j % 7));
    return Ray{o, sampleUniformSphere(u), kInfinity};
}

bool sameBits(const Spectrum& a, const Spectrum& b) { return std::memcmp(&a, &b, sizeof(Spectrum)) == 0; }

TEST(PathLanes, EachLaneEqualsPathRadiance) {
    const Scene scene = makeLaneTestScene();
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        const SceneView& view = accel.sceneView();
        accel.visit([&](const auto& it) {
            constexpr int L = pathLaneCount<std::decay_t<decltype(it)>>();
            for (const PathSettings& settings : pathSettingsVariants())
                for (int n : {0, 1, 5, L}) {
                    if (n > L) continue;
                    for (int round = 0; round < 8; ++round) {
                        IndependentSampler alone[L], lanes[L];
                        Ray cameraRays[L];
                        Spectrum expected[L], got[L];
                        uint32_t expectedRays[L] = {}, gotRays[L];
                        for (int j = 0; j < n; ++j) {
                            alone[j] = lanes[j] = IndependentSampler(uint64_t(j), uint64_t(round), 5);
                            cameraRays[j] = laneRay(round * L + j);
                            expected[j] = pathRadiance(view, it, alone[j], cameraRays[j], settings, expectedRays[j]);
                        }
                        pathRadianceLanes(view, it, lanes, cameraRays, n, settings, got, gotRays);
                        for (int j = 0; j < n; ++j) {
                            EXPECT_TRUE(sameBits(got[j], expected[j]))
                                << accelKindName(kind) << " n " << n << " lane " << j << " max_depth " << settings.maxDepth;
                            EXPECT_EQ(gotRays[j], expectedRays[j]) << accelKindName(kind) << " n " << n << " lane " << j;
                            EXPECT_EQ(lanes[j].dimension(), alone[j].dimension());
                        }
                    }
                }
        });
    }
}

TEST(PathLanes, PrimarySamplesSideBySideEqualOneByOne) {
    const Scene scene = makeLaneTestScene();
    const Accel accel(scene, AccelKind::Embree);
    const SceneView& view = accel.sceneView();
    accel.visit([&](const auto& it) {
        constexpr int L = pathLaneCount<std::decay_t<decltype(it)>>();
        IndependentSampler lanes[L];
        Vec2f pos[L];
        Spectrum F[L];
        uint32_t rays[L];
        for (int j = 0; j < L; ++j) lanes[j] = IndependentSampler(uint64_t(j), 3, 8);
        evaluatePrimarySamples(view, it, lanes, L, PathSettings{}, 16, 12, pos, F, rays);
        double total = 0;
        for (int j = 0; j < L; ++j) {
            IndependentSampler alone(uint64_t(j), 3, 8);
            Vec2f p;
            Spectrum f;
            uint32_t r = 0;
            evaluatePrimarySamples(view, it, &alone, 1, PathSettings{}, 16, 12, &p, &f, &r);
            EXPECT_EQ(p.x, pos[j].x);
            EXPECT_EQ(p.y, pos[j].y);
            EXPECT_TRUE(sameBits(f, F[j])) << "lane " << j;
            EXPECT_EQ(r, rays[j]);
            total += double(F[j].r + F[j].g + F[j].b);
        }
        EXPECT_GT(total, 0.0);
    });
}

}  // namespace
}  // namespace caustica::test
