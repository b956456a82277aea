// lane_test_scene.h — the scene of the tests of paths traced side by side (path_lanes_test.cpp,
// sppm_lanes_test.cpp): a diffuse box (its walls one-sided) under a ceiling area light, with
// a glass and a metal sphere, a point light and a constant environment.
#pragma once

#include "caustica/accel/embree_accel.h"
#include "caustica/scene/scene.h"
#include "scene/scene_builder.h"

namespace caustica::test {

/// The six walls of the box x, y in [-1, 1], z in [0, 2], each made by rect(origin, u, v) (the
/// rectangle origin + s u + t v, normal cross(u, v)).
template <class Rect>
void addBoxWalls(Rect&& rect) {
    rect(Vec3f(-1, -1, 0), Vec3f(2, 0, 0), Vec3f(0, 0, 2));  // floor
    rect(Vec3f(-1, 1, 0), Vec3f(0, 0, 2), Vec3f(2, 0, 0));   // ceiling
    rect(Vec3f(-1, -1, 0), Vec3f(0, 2, 0), Vec3f(0, 0, 2));  // left
    rect(Vec3f(1, -1, 0), Vec3f(0, 0, 2), Vec3f(0, 2, 0));   // right
    rect(Vec3f(-1, -1, 2), Vec3f(2, 0, 0), Vec3f(0, 2, 0));  // back
    rect(Vec3f(-1, -1, 0), Vec3f(0, 2, 0), Vec3f(2, 0, 0));  // front
}

/// A box x, y in [-1, 1], z in [0, 2]: area, point and environment light, glass and metal sphere.
inline Scene makeLaneTestScene() {
    Scene scene;
    Bsdf white, glass, metal;
    white.reflectance = Spectrum(0.8f, 0.7f, 0.6f);
    glass.type = BsdfType::Dielectric;
    metal.type = BsdfType::Conductor;
    metal.eta = Spectrum(0.2f, 0.9f, 1.1f);
    metal.k = Spectrum(3.9f, 2.4f, 2.2f);
    scene.bsdfs = {white, glass, metal};
    auto rect = [&](Vec3f o, Vec3f u, Vec3f v) {
        RectMesh r(o, u, v);
        return addMesh(scene, r.positions, r.triangles);
    };
    addBoxWalls(rect);
    addAreaLight(scene, rect({-0.2f, 0.99f, 0.8f}, {0.4f, 0, 0}, {0, 0, 0.4f}), Spectrum(10, 9, 8));
    scene.shapes[addSphere(scene, {0.3f, -0.5f, 1.0f}, 0.4f)].bsdf = 1;
    scene.shapes[addSphere(scene, {-0.5f, -0.7f, 1.4f}, 0.3f)].bsdf = 2;
    addPointLight(scene, {0.5f, 0.5f, 1.5f}, Spectrum(0.5f));
    addConstantLight(scene, Spectrum(0.3f, 0.4f, 0.6f));
    finalizeLights(scene);
    scene.camera.width = scene.film.width = 16;  // at the origin, looking along +z into the box
    scene.camera.height = scene.film.height = 12;
    scene.camera.tanHalfX = scene.camera.tanHalfY = 0.6f;
    return scene;
}

/// Embree answering single rays only: a packet of one, so the kernels that trace paths side by
/// side trace them one by one (their reference in the tests).
struct SingleRayEmbree {
    EmbreeIntersector embree;
    bool intersect(const Ray& ray, Hit& hit) const { return embree.intersect(ray, hit); }
    bool occluded(const Ray& ray) const { return embree.occluded(ray); }
};

}  // namespace caustica::test
