// Tests of finalizeLights: triangle-area CDFs, areas, the environment's bounding sphere, errors.
#include <gtest/gtest.h>

#include <vector>

#include "caustica/scene/interaction.h"
#include "caustica/scene/light.h"
#include "caustica/scene/light_setup.h"
#include "caustica/util/error.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

TEST(FinalizeLights, MeshCdfAndArea) {
    Scene scene;
    // Triangles of areas 0.5, 2 and 1.5 (right triangles in the z = 0 plane).
    const uint32_t other = test::addMesh(scene, {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}}, {{0, 1, 2}});
    const uint32_t mesh = test::addMesh(
        scene, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 2, 0}, {3, 0, 0}, {0, 1, 0}},
        {{0, 1, 2}, {0, 3, 4}, {0, 5, 6}});
    test::addPointLight(scene, {0, 0, 1}, Spectrum(1.f));
    const uint32_t l = test::addAreaLight(scene, mesh, Spectrum(2.f));
    finalizeLights(scene);
    const Light& light = scene.lights[l];
    EXPECT_FLOAT_EQ(light.area, 4.0f);
    ASSERT_EQ(light.cdfCount, 3u);
    ASSERT_LE(light.cdfOffset + light.cdfCount, scene.lightCdf.size());
    EXPECT_FLOAT_EQ(scene.lightCdf[light.cdfOffset + 0], 0.125f);
    EXPECT_FLOAT_EQ(scene.lightCdf[light.cdfOffset + 1], 0.625f);
    EXPECT_EQ(scene.lightCdf[light.cdfOffset + 2], 1.0f);  // exactly
    EXPECT_EQ(scene.environmentLight, -1);
    (void)other;

    // Idempotent: a second call rebuilds the same CDF instead of appending.
    const size_t n = scene.lightCdf.size();
    finalizeLights(scene);
    EXPECT_EQ(scene.lightCdf.size(), n);
}

/// A rectangle as Mitsuba's rectangle shape is meshed: corners o, o + u, o + u + v, o + v and the
/// triangles (0, 1, 2), (2, 3, 0).
struct TwoTriangleRect {
    std::vector<Vec3f> positions;
    std::vector<Vec3u> triangles = {{0, 1, 2}, {2, 3, 0}};
    TwoTriangleRect(Vec3f o, Vec3f u, Vec3f v) : positions{o, o + u, o + u + v, o + v} {}
};

/// The light on a mesh of `positions` / `triangles` after finalizeLights.
Light meshLight(const std::vector<Vec3f>& positions, const std::vector<Vec3u>& triangles, bool flip = false,
                const std::vector<Vec3f>& normals = {}) {
    Scene scene;
    const uint32_t l =
        test::addAreaLight(scene, test::addMesh(scene, positions, triangles, flip, normals), Spectrum(1.f));
    finalizeLights(scene);
    return scene.lights[l];
}

TEST(FinalizeLights, RectangleLightIsSampledAsAParallelogram) {
    const Vec3f o(1, 2, 3), u(2, 0, 0.5f), v(0, 1.5f, 0);
    const TwoTriangleRect rect(o, u, v);
    Scene scene;
    const uint32_t shape = test::addMesh(scene, rect.positions, rect.triangles);
    const uint32_t l = test::addAreaLight(scene, shape, Spectrum(1.f));
    finalizeLights(scene);
    const Light& light = scene.lights[l];
    ASSERT_TRUE(light.isQuad);
    // The parallelogram's four corners are the rectangle's.
    const Vec3f corners[4] = {light.quadCorner, light.quadCorner + light.quadEdgeU,
                              light.quadCorner + light.quadEdgeV,
                              light.quadCorner + light.quadEdgeU + light.quadEdgeV};
    for (const Vec3f& c : corners) {
        bool found = false;
        for (const Vec3f& p : rect.positions) found = found || length(c - p) < 1e-6f;
        EXPECT_TRUE(found) << c.x << " " << c.y << " " << c.z;
    }
    // Its normal is the one a hit on the light sees; its area the triangles'.
    const SceneView view = scene.view();
    const Vec3f ng = trianglePoint(view, scene.shapes[shape], 0, 0.25f, 0.25f).ng;
    EXPECT_NEAR(dot(light.quadNormal, ng), 1.0f, 1e-6f);
    EXPECT_NEAR(length(cross(light.quadEdgeU, light.quadEdgeV)), light.area, 1e-5f);
    // Samples lie on the rectangle with that normal, and cover it uniformly (quadrant counts).
    int quadrant[4] = {};
    for (int i = 0; i < 4000; ++i) {
        const Vec2f s((i % 64 + 0.5f) / 64, (i / 64 + 0.5f) / 62.5f);
        Vec3f p, n;
        ASSERT_TRUE(sampleAreaLightPosition(view, light, s, p, n));
        EXPECT_EQ(n.x, light.quadNormal.x);
        const Vec3f d = p - o;
        const Float a = dot(d, u) / dot(u, u), b = dot(d, v) / dot(v, v);
        ASSERT_TRUE(a > -1e-5f && a < 1 + 1e-5f && b > -1e-5f && b < 1 + 1e-5f) << a << " " << b;
        EXPECT_NEAR(dot(d, ng), 0.0f, 1e-5f);
        ++quadrant[int(a >= 0.5f) + 2 * int(b >= 0.5f)];
    }
    for (int q = 0; q < 4; ++q) EXPECT_NEAR(quadrant[q], 1000, 40) << q;
}

TEST(FinalizeLights, QuadFollowsFlipAndConstantNormals) {
    const TwoTriangleRect rect({0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // winding normal +z
    const Light plain = meshLight(rect.positions, rect.triangles);
    ASSERT_TRUE(plain.isQuad);
    EXPECT_NEAR(plain.quadNormal.z, 1.0f, 1e-6f);
    const Light flipped = meshLight(rect.positions, rect.triangles, true);
    ASSERT_TRUE(flipped.isQuad);
    EXPECT_NEAR(flipped.quadNormal.z, -1.0f, 1e-6f);
    // Constant shading normals against the winding: Mitsuba orients the front side by them.
    const Light byNormals = meshLight(rect.positions, rect.triangles, false, std::vector<Vec3f>(4, Vec3f(0, 0, -1)));
    ASSERT_TRUE(byNormals.isQuad);
    EXPECT_NEAR(byNormals.quadNormal.z, -1.0f, 1e-6f);
}

TEST(FinalizeLights, OtherMeshesKeepTheTriangleCdf) {
    const TwoTriangleRect rect({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    // Shading normals that vary across the rectangle.
    EXPECT_FALSE(meshLight(rect.positions, rect.triangles, false,
                           {{0, 0, 1}, {0, 0.1f, 1}, {0, 0, 1}, {0, 0, 1}})
                     .isQuad);
    // A kite: two triangles on a diagonal, not a parallelogram.
    EXPECT_FALSE(meshLight({{0, 0, 0}, {1, 0, 0}, {1.5f, 1.5f, 0}, {0, 1, 0}}, {{0, 1, 2}, {2, 3, 0}}).isQuad);
    // The two halves wound opposite ways: they emit to different sides.
    EXPECT_FALSE(meshLight(rect.positions, {{0, 1, 2}, {0, 3, 2}}).isQuad);
    // Two triangles that share one vertex only, and a rectangle of four triangles.
    EXPECT_FALSE(meshLight({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}).isQuad);
    const test::RectMesh four({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    EXPECT_FALSE(meshLight(four.positions, four.triangles).isQuad);
}

TEST(FinalizeLights, TwoMeshLightsGetDisjointCdfs) {
    Scene scene;
    const test::RectMesh a({0, 0, 0}, {1, 0, 0}, {0, 3, 0});
    const test::RectMesh b({0, 0, 2}, {2, 0, 0}, {0, 0.5f, 0}, 0.9f, 0.1f);
    const uint32_t la = test::addAreaLight(scene, test::addMesh(scene, a.positions, a.triangles),
                                           Spectrum(1.f));
    const uint32_t lb = test::addAreaLight(scene, test::addMesh(scene, b.positions, b.triangles),
                                           Spectrum(1.f));
    finalizeLights(scene);
    EXPECT_FLOAT_EQ(scene.lights[la].area, 3.0f);
    EXPECT_FLOAT_EQ(scene.lights[lb].area, 1.0f);
    EXPECT_EQ(scene.lights[la].cdfOffset + scene.lights[la].cdfCount, scene.lights[lb].cdfOffset);
    for (uint32_t l : {la, lb}) {
        const Light& light = scene.lights[l];
        float prev = 0;
        for (uint32_t i = 0; i < light.cdfCount; ++i) {
            const float c = scene.lightCdf[light.cdfOffset + i];
            EXPECT_GT(c, prev);  // the fan's triangles all have positive area
            prev = c;
        }
        EXPECT_EQ(prev, 1.0f);
    }
    // The fan around (0.9, 0.1) has unequal triangles: first = 0.5 * 0.1 / 1 of the area.
    EXPECT_NEAR(scene.lightCdf[scene.lights[lb].cdfOffset], 0.05f, 1e-6f);
}

TEST(FinalizeLights, SphereArea) {
    Scene scene;
    const uint32_t l = test::addAreaLight(scene, test::addSphere(scene, {1, 2, 3}, 0.5f),
                                          Spectrum(1.f));
    finalizeLights(scene);
    EXPECT_NEAR(scene.lights[l].area, 4 * kPi * 0.25f, 1e-6f);
    EXPECT_EQ(scene.lights[l].cdfCount, 0u);
}

TEST(FinalizeLights, EnvironmentBoundingSphere) {
    Scene scene;
    test::addSphere(scene, {0, 0, 0}, 1);
    test::addMesh(scene, {{4, 0, 0}, {4, 1, 0}, {4, 0, 1}}, {{0, 1, 2}});
    const uint32_t env = test::addConstantLight(scene, Spectrum(0.5f));
    finalizeLights(scene);
    EXPECT_EQ(scene.environmentLight, int32_t(env));
    const Light& l = scene.lights[env];
    // Bounds [-1, 4] x [-1, 1] x [-1, 1]: centre (1.5, 0, 0), half-diagonal sqrt(25 + 4 + 4) / 2.
    EXPECT_NEAR(l.sceneCenter.x, 1.5f, 1e-6f);
    EXPECT_NEAR(l.sceneCenter.y, 0.0f, 1e-6f);
    EXPECT_NEAR(l.sceneCenter.z, 0.0f, 1e-6f);
    EXPECT_GE(l.sceneRadius, 0.5f * std::sqrt(33.0f));
    EXPECT_NEAR(l.sceneRadius, 0.5f * std::sqrt(33.0f), 1e-3f);
}

TEST(FinalizeLights, EnvironmentInEmptySceneHasPositiveRadius) {
    Scene scene;
    const uint32_t env = test::addConstantLight(scene, Spectrum(1.f));
    finalizeLights(scene);
    EXPECT_EQ(scene.environmentLight, int32_t(env));
    EXPECT_GT(scene.lights[env].sceneRadius, 0.0f);
    EXPECT_TRUE(std::isfinite(scene.lights[env].sceneRadius));
}

TEST(FinalizeLights, EnvironmentOfAPointSceneHasPositiveRadius) {
    Scene scene;
    test::addMesh(scene, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, {{0, 1, 2}});
    const uint32_t env = test::addConstantLight(scene, Spectrum(1.f));
    finalizeLights(scene);
    EXPECT_GT(scene.lights[env].sceneRadius, 0.0f);
}

TEST(FinalizeLights, TwoEnvironmentsAreRefused) {
    Scene scene;
    test::addConstantLight(scene, Spectrum(1.f));
    test::addConstantLight(scene, Spectrum(2.f));
    EXPECT_THROW(finalizeLights(scene), Error);
}

TEST(FinalizeLights, ZeroAreaEmittersAreRefused) {
    {
        Scene scene;  // degenerate (collinear) triangles
        const uint32_t s = test::addMesh(scene, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}});
        test::addAreaLight(scene, s, Spectrum(1.f));
        try {
            finalizeLights(scene);
            ADD_FAILURE() << "no error";
        } catch (const Error& e) {
            EXPECT_EQ(e.reason(), "area emitter on a shape with zero area");
        }
    }
    {
        Scene scene;  // a mesh without triangles
        const uint32_t s = test::addMesh(scene, {}, {});
        test::addAreaLight(scene, s, Spectrum(1.f));
        EXPECT_THROW(finalizeLights(scene), Error);
    }
    {
        Scene scene;  // a sphere of radius 0
        test::addAreaLight(scene, test::addSphere(scene, {0, 0, 0}, 0), Spectrum(1.f));
        EXPECT_THROW(finalizeLights(scene), Error);
    }
}

TEST(FinalizeLights, BadShapeIndexIsRefused) {
    Scene scene;
    Light l;
    l.type = LightType::Area;
    l.shape = 3;
    scene.lights.push_back(l);
    EXPECT_THROW(finalizeLights(scene), Error);
}

}  // namespace
}  // namespace caustica
