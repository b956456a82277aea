// The photon mappers' passes with paths side by side (integrators/sppm/sppm_passes.h, lanes.h):
// photonPathGroup's photon paths, their rays in packets and lanes handed on from path to path, make
// exactly the photons (and count exactly the rays) that the same paths make traced one by one
// with sppmTracePhoton, for any range length; the eye pass gives every entry the radiance, visible
// point, flag and ray count that it gives with single-ray queries (one path per work item).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/sppm/sppm_passes.h"
#include "caustica/parallel/buffer.h"
#include "caustica/scene/emitter_boxes.h"
#include "integrators/lane_test_scene.h"

namespace caustica::test {
namespace {

using PhotonRecord = std::tuple<Float, Float, Float, Float, Float, Float, Float, Float, Float, Float, uint32_t>;

struct Traced {
    std::vector<PhotonRecord> photons;  // sorted
    uint64_t rays = 0;
};

constexpr uint64_t kIteration = 3, kSeed = 11;
constexpr uint32_t kMaxDepth = 12;

template <class Trace>
Traced collect(Trace&& trace) {
    Traced out;
    std::vector<uint64_t> rayBlocks(64, 0);
    trace(rayBlocks.data(), [&](const SurfaceInteraction& si, Vec3f wo, const Spectrum& flux, uint32_t k) {
        out.photons.emplace_back(si.p.x, si.p.y, si.p.z, wo.x, wo.y, wo.z, si.ng.x, flux.r, flux.g, flux.b, k);
    });
    for (uint64_t r : rayBlocks) out.rays += r;
    std::sort(out.photons.begin(), out.photons.end());
    return out;
}

TEST(SppmLanes, PhotonGroupMakesThePhotonsOfPathsTracedOneByOne) {
    const Scene scene = makeLaneTestScene();
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        const SceneView& view = accel.sceneView();
        accel.visit([&](const auto& it) {
            // Ranges shorter than, equal to and longer than a packet, starting off a block.
            for (size_t count : {size_t(0), size_t(1), size_t(15), size_t(16), size_t(17), size_t(300)})
            for (PhotonRoulette roulette : {PhotonRoulette::Albedo, PhotonRoulette::Throughput}) {
                const SppmPhotonRules rules{PathSettings{}, kMaxDepth, Float(0), roulette};
                const size_t first = 1000;
                const Traced alone = collect([&](uint64_t* rayBlocks, auto&& sink) {
                    for (size_t i = first; i < first + count; ++i)
                        sppm_detail::photonPath(view, it, i, kIteration, kSeed, rules, rayBlocks, sink);
                });
                const Traced grouped = collect([&](uint64_t* rayBlocks, auto&& sink) {
                    sppm_detail::photonPathGroup(view, it, first, count, kIteration, kSeed, rules, rayBlocks,
                                                 sink);
                });
                SCOPED_TRACE(std::string(accelKindName(kind)) + " count " + std::to_string(count) + " roulette " +
                             photonRouletteName(roulette));
                EXPECT_EQ(grouped.rays, alone.rays);
                ASSERT_EQ(grouped.photons.size(), alone.photons.size());
                EXPECT_TRUE(grouped.photons == alone.photons);
                if (count >= 300) {
                    EXPECT_GT(alone.photons.size(), count / 4);  // the scene stores photons
                    EXPECT_GT(alone.rays, count);  // and its paths go on past one hit
                }
            }
        });
    }
}

struct EyeResult {
    std::vector<Spectrum> radiance;
    std::vector<SppmVisiblePoint> points;
    std::vector<uint32_t> flags, rays;
};

template <class Intersector>
EyeResult eyePassOf(const SceneView& view, const Intersector& accel, const EmitterBoxes& emitters, size_t entries,
                    uint32_t perPixel, const PathSettings& settings) {
    const Device cpu = Device::cpu();
    Buffer<SppmPixel> stats(cpu, entries);
    Buffer<SppmVisiblePoint> points(cpu, entries);
    Buffer<uint32_t> flags(cpu, entries), rays(cpu, entries);
    Buffer<Spectrum> radiance(cpu, entries);
    sppm_detail::EyeSampling sampling;
    sampling.perPixel = perPixel;
    sampling.iteration = 2;
    sampling.fixedHitpoints = perPixel > 1;
    sampling.radiance = radiance.data();
    sppm_detail::eyePass(CpuExec{}, view, accel, settings, Float(0), emitters, 13, sampling, view.camera.width,
                         entries, stats.data(), points.data(), flags.data(), rays.data());
    return {radiance.toHost(), points.toHost(), flags.toHost(), rays.toHost()};
}

TEST(SppmLanes, EyePassEqualsSingleRayEyePass) {
    const Scene scene = makeLaneTestScene();
    const Accel accel(scene, AccelKind::Embree);
    const SceneView& view = accel.sceneView();
    const EmitterBoxes emitters = buildEmitterBoxes(scene);
    accel.visit([&](const auto& it) {
        if constexpr (std::is_same_v<std::decay_t<decltype(it)>, EmbreeIntersector>) {
            const SingleRayEmbree single{it};
            PathSettings shallow;
            shallow.maxDepth = 2;
            for (const PathSettings& settings : {PathSettings{}, shallow})
                for (uint32_t perPixel : {1u, 3u}) {
                    const size_t entries = size_t(scene.camera.width) * size_t(scene.camera.height) * perPixel;
                    const EyeResult lanes = eyePassOf(view, it, emitters, entries, perPixel, settings);
                    const EyeResult alone = eyePassOf(view, single, emitters, entries, perPixel, settings);
                    size_t points = 0;
                    for (size_t s = 0; s < entries; ++s) {
                        EXPECT_EQ(std::memcmp(&lanes.radiance[s], &alone.radiance[s], sizeof(Spectrum)), 0) << s;
                        EXPECT_EQ(lanes.flags[s], alone.flags[s]) << s;
                        EXPECT_EQ(lanes.rays[s], alone.rays[s]) << s;
                        EXPECT_EQ(lanes.points[s].stat, alone.points[s].stat) << s;
                        if (!alone.flags[s]) continue;
                        ++points;
                        const SppmVisiblePoint &a = lanes.points[s], &b = alone.points[s];
                        EXPECT_EQ(std::memcmp(&a.si.p, &b.si.p, sizeof(Vec3f)), 0) << s;
                        EXPECT_EQ(std::memcmp(&a.beta, &b.beta, sizeof(Spectrum)), 0) << s;
                        EXPECT_EQ(std::memcmp(&a.wo, &b.wo, sizeof(Vec3f)), 0) << s;
                        EXPECT_EQ(a.depth, b.depth) << s;
                        EXPECT_EQ(a.bsdf, b.bsdf) << s;
                    }
                    EXPECT_GT(points, entries / 2);
                }
        }
    });
}

}  // namespace
}  // namespace caustica::test
