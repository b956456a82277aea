// Tests of finalizeLights: triangle-area CDFs, areas, the environment's bounding sphere, errors.
#include <gtest/gtest.h>

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
