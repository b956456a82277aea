// photonPathGroup (integrators/sppm/sppm_passes.h): photon paths traced with their rays in packets
// and lanes handed on from path to path make exactly the photons (and count exactly the rays)
// that the same paths make traced one by one with sppmTracePhoton, for any range length, on a
// small scene built in code with diffuse walls, a glass and a metal sphere and an area light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <tuple>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/sppm/sppm_passes.h"
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

TEST(SppmPhotonGroup, SamePhotonsAndRaysAsPathsTracedOneByOne) {
    const Scene scene = makeLaneTestScene();
    const PathSettings settings;
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        const SceneView& view = accel.sceneView();
        accel.visit([&](const auto& it) {
            // Ranges shorter than, equal to and longer than a packet, starting off a block.
            for (size_t count : {size_t(0), size_t(1), size_t(15), size_t(16), size_t(17), size_t(300)}) {
                const size_t first = 1000;
                const Traced alone = collect([&](uint64_t* rayBlocks, auto&& sink) {
                    for (size_t i = first; i < first + count; ++i)
                        sppm_detail::photonPath(view, it, i, kIteration, kSeed, settings, kMaxDepth, Float(0),
                                                rayBlocks, sink);
                });
                const Traced grouped = collect([&](uint64_t* rayBlocks, auto&& sink) {
                    sppm_detail::photonPathGroup(view, it, first, count, kIteration, kSeed, settings, kMaxDepth,
                                                 Float(0), rayBlocks, sink);
                });
                EXPECT_EQ(grouped.rays, alone.rays) << accelKindName(kind) << " count " << count;
                ASSERT_EQ(grouped.photons.size(), alone.photons.size()) << accelKindName(kind) << " count " << count;
                EXPECT_TRUE(grouped.photons == alone.photons) << accelKindName(kind) << " count " << count;
                if (count >= 300) {
                    EXPECT_GT(alone.photons.size(), count / 4);  // the scene stores photons
                    EXPECT_GT(alone.rays, count);  // and its paths go on past one hit
                }
            }
        });
    }
}

}  // namespace
}  // namespace caustica::test
