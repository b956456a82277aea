// The shade stage four paths at a time (integrators/path/shade_lanes.h): shadeDiffuseQuad4 gives
// each of its four paths what shadeHit gives that path alone, bit for bit (its state, its
// sampler's position, its shadow ray and contribution, whether it continues), at every bounce of
// paths traced through a box lit by rectangles, for every settings variant and both ray-tracing
// backends. Which vertices and scenes it takes: diffuseQuadEligible, allLightsAreQuads.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/path/shade_lanes.h"
#include "integrators/lane_test_scene.h"
#include "integrators/path_settings_variants.h"
#include "integrators/rectangle_lit_scene.h"

#if CA_FLOAT4_SSE
namespace caustica::test {
namespace {

template <class T>
bool sameBits(const T& a, const T& b) {  // Vec3f, Spectrum, Ray: floats without padding
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

bool samePath(const PathState& a, const PathState& b) {
    return sameBits(a.ray, b.ray) && sameBits(a.throughput, b.throughput) && sameBits(a.radiance, b.radiance) &&
           sameBits(a.prevP, b.prevP) && sameBits(a.etaScale, b.etaScale) && sameBits(a.prevBsdfPdf, b.prevBsdfPdf) &&
           a.depth == b.depth && a.prevBsdfDelta == b.prevBsdfDelta;
}

/// One path as the test traces it: its state, sampler and the NEE sample of its last vertex.
struct TestPath {
    PathState state;
    IndependentSampler sampler;
    ShadowRay shadow;
    bool hasShadow = false;
    bool alive = false;
};

/// Traces the camera's paths bounce by bounce; at each bounce the eligible vertices are shaded
/// four at a time by shadeDiffuseQuad4 and, on copies, one at a time by shadeHit, and the two
/// compared. Returns the number of groups of four compared (and mismatches in `failures`).
template <class Intersector>
size_t compareGroups(const Scene& scene, const SceneView& view, const Intersector& it, const PathSettings& settings,
                     size_t& failures, double& radiance) {
    const size_t pixels = size_t(scene.film.width) * size_t(scene.film.height);
    std::vector<TestPath> paths(pixels);
    for (size_t p = 0; p < pixels; ++p) {
        const CameraSample c = cameraSample(scene.camera, p, scene.film.width, 3, 41);
        paths[p].sampler = c.sampler;
        paths[p].alive = startPath(paths[p].state, c.ray, settings);
    }
    size_t groups = 0;
    for (bool any = true; any;) {
        any = false;
        std::vector<size_t> eligible;
        std::vector<Hit> hits(pixels);
        for (size_t p = 0; p < pixels; ++p) {
            TestPath& t = paths[p];
            t.hasShadow = false;
            if (!t.alive) continue;
            if (!it.intersect(t.state.ray, hits[p])) {
                missPath(view, t.state, settings);
                t.alive = false;
            } else if (diffuseQuadEligible(view, t.state, hits[p], settings)) {
                eligible.push_back(p);
            } else {
                t.alive = shadeHit(view, t.state, hits[p], t.sampler, settings, t.shadow, t.hasShadow);
            }
        }
        for (size_t g = 0; g + 4 <= eligible.size(); g += 4) {
            TestPath reference[4];
            PathState* state[4];
            const Hit* hit4[4];
            IndependentSampler* sampler[4];
            ShadowRay* shadow[4];
            bool hasShadow[4];
            for (int k = 0; k < 4; ++k) {
                TestPath& t = paths[eligible[g + k]];
                const Hit& hit = hits[eligible[g + k]];
                reference[k] = t;
                reference[k].alive = shadeHit(view, reference[k].state, hit, reference[k].sampler, settings,
                                              reference[k].shadow, reference[k].hasShadow);
                state[k] = &t.state;
                hit4[k] = &hit;
                sampler[k] = &t.sampler;
                shadow[k] = &t.shadow;
            }
            const uint32_t alive = shadeDiffuseQuad4(view, state, hit4, sampler, settings, shadow, hasShadow);
            for (int k = 0; k < 4; ++k) {
                TestPath& t = paths[eligible[g + k]];
                t.alive = (alive >> k) & 1u;
                t.hasShadow = hasShadow[k];
                const TestPath& r = reference[k];
                const bool same = t.alive == r.alive && t.hasShadow == r.hasShadow && samePath(t.state, r.state) &&
                                  t.sampler.dimension() == r.sampler.dimension() &&
                                  (!r.hasShadow || (sameBits(t.shadow.ray, r.shadow.ray) &&
                                                    sameBits(t.shadow.contribution, r.shadow.contribution)));
                if (!same) {
                    ++failures;
                    if (failures < 4)
                        ADD_FAILURE() << "alive " << t.alive << r.alive << " shadow " << t.hasShadow << r.hasShadow
                                      << " path " << samePath(t.state, r.state) << " dim " << t.sampler.dimension()
                                      << " " << r.sampler.dimension() << " depth " << t.state.depth << " "
                                      << r.state.depth << " ray " << sameBits(t.state.ray, r.state.ray) << " tp "
                                      << sameBits(t.state.throughput, r.state.throughput) << " L "
                                      << sameBits(t.state.radiance, r.state.radiance) << " prevP "
                                      << sameBits(t.state.prevP, r.state.prevP) << " shadowray "
                                      << sameBits(t.shadow.ray, r.shadow.ray) << " contribution "
                                      << sameBits(t.shadow.contribution, r.shadow.contribution);
                }
            }
            ++groups;
        }
        for (size_t g = eligible.size() / 4 * 4; g < eligible.size(); ++g) {
            TestPath& t = paths[eligible[g]];
            t.alive = shadeHit(view, t.state, hits[eligible[g]], t.sampler, settings, t.shadow, t.hasShadow);
        }
        for (TestPath& t : paths) {
            if (t.hasShadow) addShadowContribution(t.state, t.shadow, it.occluded(t.shadow.ray));
            any = any || t.alive;
        }
    }
    for (const TestPath& t : paths) radiance += double(t.state.radiance.r) + t.state.radiance.g + t.state.radiance.b;
    return groups;
}

/// The box of one-sided walls, and the same with twosided walls and a panel seen from both sides.
class ShadeLanesScenes : public ::testing::TestWithParam<bool> {};

TEST_P(ShadeLanesScenes, FourPathsGetTheBitsOfEachPathShadedAlone) {
    const Scene scene = makeRectangleLitScene(24, GetParam());
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        ASSERT_TRUE(allLightsAreQuads(accel.sceneView()));
        accel.visit([&](const auto& it) {
            for (const PathSettings& settings : pathSettingsVariants()) {
                size_t failures = 0;
                double radiance = 0;
                const size_t groups = compareGroups(scene, accel.sceneView(), it, settings, failures, radiance);
                const std::string what = std::string(accelKindName(kind)) + " max_depth " +
                                         std::to_string(settings.maxDepth) + " rr_depth " +
                                         std::to_string(settings.rrDepth);
                EXPECT_EQ(failures, 0u) << what;
                if (settings.maxDepth == 0 || settings.maxDepth == 1) {
                    EXPECT_EQ(groups, 0u) << what;  // no vertex below the maximum depth
                } else {
                    EXPECT_GT(groups, 50u) << what;
                    EXPECT_GT(radiance, 0.0) << what;
                }
            }
        });
    }
}

INSTANTIATE_TEST_SUITE_P(Walls, ShadeLanesScenes, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "TwoSided" : "OneSided"; });

TEST(ShadeLanes, TakesTwoSidedDiffuseVerticesBothWays) {
    // Both sides of the twosided panel and walls are hit, and every such vertex is eligible.
    const Scene scene = makeRectangleLitScene(24, true);
    const Accel accel(scene, AccelKind::Bvh);
    const SceneView view = accel.sceneView();
    PathSettings settings;
    settings.maxDepth = 16;
    size_t front = 0, back = 0;
    accel.visit([&](const auto& it) {
        const size_t pixels = size_t(scene.film.width) * size_t(scene.film.height);
        for (size_t p = 0; p < pixels; ++p) {
            const CameraSample c = cameraSample(scene.camera, p, scene.film.width, 3, 41);
            PathState path;
            IndependentSampler sampler = c.sampler;
            if (!startPath(path, c.ray, settings)) continue;
            for (int bounce = 0; bounce < 6; ++bounce) {
                Hit hit;
                if (!it.intersect(path.ray, hit)) break;
                if (hit.primId < view.numTriangles() &&
                    view.bsdfs[view.shapes[view.triangleShape[hit.primId]].bsdf].type == BsdfType::TwoSided) {
                    EXPECT_TRUE(diffuseQuadEligible(view, path, hit, settings));
                    const SurfaceInteraction si = computeInteraction(view, path.ray, hit);
                    (dot(-path.ray.d, si.ns) < 0 ? back : front) += 1;
                }
                ShadowRay shadow;
                bool hasShadow = false;
                if (!shadeHit(view, path, hit, sampler, settings, shadow, hasShadow)) break;
            }
        }
    });
    EXPECT_GT(front, 100u);
    EXPECT_GT(back, 20u);
}

TEST(ShadeLanes, TakesSceneWhoseLightsAreAllRectangles) {
    EXPECT_TRUE(allLightsAreQuads(Accel(makeRectangleLitScene(4), AccelKind::Bvh).sceneView()));
    // Point and environment lights, and an area light of four triangles: shaded one path at a time.
    EXPECT_FALSE(allLightsAreQuads(Accel(makeLaneTestScene(), AccelKind::Bvh).sceneView()));
}

}  // namespace
}  // namespace caustica::test
#endif  // CA_FLOAT4_SSE
