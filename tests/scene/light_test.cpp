// Light evaluation and the deterministic parts of light sampling: point lights, selection,
// one-sided emission and its normal convention (flip_normals, shading normals), environment.
#include <gtest/gtest.h>

#include <vector>

#include "caustica/scene/light.h"
#include "caustica/util/rng.h"
#include "scene/chi2.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

TEST(Light, NoLightsNoSample) {
    Scene scene;
    test::addSphere(scene, {0, 0, 0}, 1);
    finalizeLights(scene);
    const SceneView view = scene.view();
    LightSample ls;
    EXPECT_FALSE(sampleLight(view, Vec3f(0, 0, 3), 0.5f, Vec2f(0.5f, 0.5f), ls));
    EXPECT_EQ(pdfEnvironmentLight(view, Vec3f(0, 0, 1)), 0.0f);
    EXPECT_TRUE(environmentRadiance(view, Vec3f(0, 0, 1)).isBlack());
}

TEST(Light, PointLightIsDelta) {
    Scene scene;
    test::addPointLight(scene, {1, 2, 3}, Spectrum(4, 8, 12));
    finalizeLights(scene);
    LightSample ls;
    ASSERT_TRUE(sampleLight(scene.view(), Vec3f(1, 2, 1), 0.3f, Vec2f(0.1f, 0.9f), ls));
    EXPECT_TRUE(ls.delta);
    EXPECT_EQ(ls.pdf, 1.0f);
    EXPECT_EQ(ls.light, 0u);
    EXPECT_FLOAT_EQ(ls.dist, 2.0f);
    EXPECT_NEAR(ls.wi.z, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(ls.Le.r, 1.0f);  // intensity / dist²
    EXPECT_FLOAT_EQ(ls.Le.b, 3.0f);
    EXPECT_EQ(ls.n, Vec3f(0));
}

TEST(Light, EnvironmentRadianceAndPdf) {
    Scene scene;
    test::addPointLight(scene, {0, 0, 5}, Spectrum(1.f));
    test::addConstantLight(scene, Spectrum(0.5f, 0.25f, 1));
    finalizeLights(scene);
    const SceneView view = scene.view();
    EXPECT_FLOAT_EQ(environmentRadiance(view, Vec3f(0, 1, 0)).g, 0.25f);
    EXPECT_FLOAT_EQ(pdfEnvironmentLight(view, Vec3f(0, 1, 0)), kInv4Pi / 2);
    LightSample ls;
    ASSERT_TRUE(sampleLight(view, Vec3f(0, 0, 0), 0.75f, Vec2f(0.3f, 0.6f), ls));
    EXPECT_EQ(ls.light, 1u);
    EXPECT_FALSE(ls.delta);
    EXPECT_EQ(ls.dist, kInfinity);
    EXPECT_FLOAT_EQ(ls.pdf, kInv4Pi / 2);
    EXPECT_FLOAT_EQ(ls.Le.b, 1.0f);
}

// Lights are chosen uniformly (χ² over the light index) and the pdf includes 1 / #lights.
TEST(Light, UniformSelection) {
    Scene scene;
    const test::RectMesh rect({-1, -1, 3}, {0, 2, 0}, {2, 0, 0});  // faces -z
    test::addAreaLight(scene, test::addMesh(scene, rect.positions, rect.triangles), Spectrum(1.f));
    test::addAreaLight(scene, test::addSphere(scene, {4, 0, 0}, 1), Spectrum(1.f));
    test::addPointLight(scene, {0, 0, -4}, Spectrum(1.f));
    test::addConstantLight(scene, Spectrum(1.f));
    finalizeLights(scene);
    const SceneView view = scene.view();
    constexpr int kN = 100000;
    std::vector<double> counts(5, 0.0);  // 4 lights + "no sample"
    for (int i = 0; i < kN; ++i) {
        IndependentSampler rng(uint64_t(i), 0, 9);
        const Float uSel = rng.get1D();
        LightSample ls;
        if (!sampleLight(view, Vec3f(0, 0, 0), uSel, rng.get2D(), ls)) {
            counts[4] += 1;
            continue;
        }
        counts[ls.light] += 1;
        if (ls.light == 2) {
            EXPECT_EQ(ls.pdf, 0.25f);
        } else if (ls.light == 3) {
            EXPECT_FLOAT_EQ(ls.pdf, 0.25f * kInv4Pi);
        }
    }
    const test::Chi2Result r =
        test::chi2Test(counts, {kN / 4.0, kN / 4.0, kN / 4.0, kN / 4.0, 0.0});
    EXPECT_TRUE(r.passed()) << r.describe();
}

/// Hits the mesh with a ray from `o` along `d` (the test knows which triangle) and returns the
/// interaction computeInteraction builds.
SurfaceInteraction hitTriangle(const SceneView& view, uint32_t tri, Float b1, Float b2, Vec3f o) {
    const Vec3u t = view.triangles[tri];
    const Vec3f p = view.positions[t.x] * (1 - b1 - b2) + view.positions[t.y] * b1 +
                    view.positions[t.z] * b2;
    Hit hit;
    hit.primId = tri;
    hit.b1 = b1;
    hit.b2 = b2;
    hit.t = length(p - o);
    return computeInteraction(view, Ray{o, normalize(p - o), kInfinity}, hit);
}

// One-sided emission follows the normal computeInteraction reports, including flip_normals and
// meshes whose shading normals disagree with the winding; sampling agrees with evaluation.
TEST(Light, OneSidedEmissionFollowsInteractionNormal) {
    struct Case {
        bool flip, normals;
    };
    for (Case c : {Case{false, false}, Case{true, false}, Case{false, true}, Case{true, true}}) {
        Scene scene;
        const test::RectMesh rect({-1, -1, 0}, {2, 0, 0}, {0, 2, 0});  // winding normal +z
        // Vertex normals pointing to -z: Mitsuba (and computeInteraction) orient ng by them.
        const std::vector<Vec3f> normals(c.normals ? rect.positions.size() : 0, Vec3f(0, 0, -1));
        const uint32_t shape =
            test::addMesh(scene, rect.positions, rect.triangles, c.flip, normals);
        test::addAreaLight(scene, shape, Spectrum(2.f));
        finalizeLights(scene);
        const SceneView view = scene.view();
        const bool frontUp = (c.flip == c.normals);  // each of the two flips the front
        for (Float side : {1.0f, -1.0f}) {
            const Vec3f o(0.2f, 0.1f, 2 * side);
            const SurfaceInteraction si = hitTriangle(view, 1, 0.3f, 0.3f, o);
            const bool lit = (side > 0) == frontUp;
            const Spectrum le = emittedRadiance(view, si, normalize(o - si.p));
            EXPECT_EQ(le.r, lit ? 2.0f : 0.0f) << c.flip << c.normals << side;
            EXPECT_EQ(pdfAreaLight(view, 0, o, si) > 0, lit);
            LightSample ls;
            const bool sampled = sampleLight(view, o, 0.5f, Vec2f(0.4f, 0.6f), ls);
            EXPECT_EQ(sampled, lit) << c.flip << c.normals << side;
            if (sampled) {
                EXPECT_GT(dot(ls.n, o - ls.p), 0.0f);
                // pdf = dist² / (cosθ_l · area) with area 4.
                const Float cosL = std::fabs(dot(ls.n, ls.wi));
                EXPECT_NEAR(ls.pdf, ls.dist * ls.dist / (cosL * 4), 1e-5f);
            }
        }
    }
}

TEST(Light, EmittedRadianceOfNonEmittersIsBlack) {
    Scene scene;
    const uint32_t s = test::addSphere(scene, {0, 0, 0}, 1);
    test::addPointLight(scene, {0, 0, 5}, Spectrum(1.f));
    finalizeLights(scene);
    SurfaceInteraction si;
    si.p = Vec3f(0, 0, 1);
    si.ng = si.ns = Vec3f(0, 0, 1);
    si.shape = s;
    EXPECT_TRUE(emittedRadiance(scene.view(), si, Vec3f(0, 0, 1)).isBlack());
    EXPECT_EQ(pdfAreaLight(scene.view(), 0, Vec3f(0, 0, 3), si), 0.0f);  // a point light
}

// A sphere light's pdf from outside is the visible cone's, 1 / (2π (1 - cosθmax)).
TEST(Light, SphereConePdf) {
    Scene scene;
    test::addAreaLight(scene, test::addSphere(scene, {0, 0, 0}, 1), Spectrum(1.f));
    finalizeLights(scene);
    const SceneView view = scene.view();
    const Vec3f ref(0, 0, 2);
    const double cosMax = std::sqrt(1 - 0.25);
    SurfaceInteraction si;
    si.p = Vec3f(0, 0, 1);
    si.ng = si.ns = Vec3f(0, 0, 1);
    EXPECT_NEAR(pdfAreaLight(view, 0, ref, si), 1 / (2 * M_PI * (1 - cosMax)), 1e-4);
    LightSample ls;
    ASSERT_TRUE(sampleLight(view, ref, 0.5f, Vec2f(0.7f, 0.2f), ls));
    EXPECT_NEAR(ls.pdf, 1 / (2 * M_PI * (1 - cosMax)), 1e-4);
    EXPECT_NEAR(length(ls.p), 1.0f, 1e-6f);
    EXPECT_GE(dot(ls.wi, Vec3f(0, 0, -1)), cosMax - 1e-6);  // inside the cone
}

}  // namespace
}  // namespace caustica
