// rectangle_lit_scene.h — the scene of the tests of the shade stage four paths at a time
// (shade_lanes_test.cpp, wavefront_test.cpp): a box of one-sided diffuse walls facing inwards
// (some with uv, so a usable dp/du, some without), lit only by two rectangles of two triangles
// each (Light::isQuad), with a glass and a metal sphere, open towards the camera. `twoSided`:
// the walls are Mitsuba twosided BSDFs over diffuse ones (the red wall's back white), and a
// free-standing twosided panel (red front, white back) inside the box is seen from both sides.
#pragma once

#include "caustica/scene/scene.h"
#include "scene/scene_builder.h"

namespace caustica::test {

inline Scene makeRectangleLitScene(int size, bool twoSided = false) {
    Scene scene;
    Bsdf white, red, glass, metal;
    white.reflectance = Spectrum(0.8f, 0.7f, 0.6f);
    red.reflectance = Spectrum(0.6f, 0.1f, 0.1f);
    glass.type = BsdfType::Dielectric;
    metal.type = BsdfType::Conductor;
    metal.eta = Spectrum(0.2f, 0.9f, 1.1f);
    metal.k = Spectrum(3.9f, 2.4f, 2.2f);
    scene.bsdfs = {white, red, glass, metal};
    if (twoSided) {  // bsdfs 4 and 5: twosided(white, white), twosided(red, white)
        Bsdf t;
        t.type = BsdfType::TwoSided;
        t.front = 0;
        t.back = 0;
        scene.bsdfs.push_back(t);
        t.front = 1;
        scene.bsdfs.push_back(t);
    }
    const uint32_t whiteWall = twoSided ? 4 : 0, redWall = twoSided ? 5 : 1;
    // A wall origin + s u + t v facing cross(u, v); withUv: uv = (s, t), else uv 0 (no dp/du).
    auto wall = [&](Vec3f o, Vec3f u, Vec3f v, uint32_t bsdf, bool withUv) {
        const RectMesh r(o, u, v);
        const size_t first = scene.uvs.size();
        const uint32_t shape = addMesh(scene, r.positions, r.triangles);
        scene.shapes[shape].bsdf = bsdf;
        scene.shapes[shape].hasUVs = withUv;
        if (withUv) {
            const Vec2f uv[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.2f, 0.7f}};
            for (size_t k = 0; k < 5; ++k) scene.uvs[first + k] = uv[k];
        }
    };
    wall({-1, -1, 0}, {0, 0, 3}, {2, 0, 0}, whiteWall, true);   // floor
    wall({-1, 1, 0}, {2, 0, 0}, {0, 0, 3}, whiteWall, false);   // ceiling
    wall({-1, -1, 0}, {0, 2, 0}, {0, 0, 3}, redWall, true);     // left (red)
    wall({1, -1, 0}, {0, 0, 3}, {0, 2, 0}, whiteWall, false);   // right
    wall({-1, -1, 3}, {0, 2, 0}, {2, 0, 0}, whiteWall, true);   // back
    if (twoSided) wall({-0.9f, -1, 1.5f}, {0, 1.2f, 0}, {0.8f, 0, 0}, redWall, true);  // panel, front -z
    // Two rectangles under the ceiling facing down, each two triangles sharing a diagonal.
    auto rectangleLight = [&](Vec3f o, Vec3f u, Vec3f v, Spectrum radiance) {
        const uint32_t shape = addMesh(scene, {o, o + u, o + u + v, o + v}, {{0, 1, 2}, {0, 2, 3}});
        addAreaLight(scene, shape, radiance);
    };
    rectangleLight({-0.6f, 0.99f, 1.0f}, {0.5f, 0, 0}, {0, 0, 0.5f}, Spectrum(8, 7, 6));
    rectangleLight({0.2f, 0.99f, 2.0f}, {0.4f, 0, 0}, {0, 0, 0.6f}, Spectrum(3, 4, 5));
    scene.shapes[addSphere(scene, {0.35f, -0.6f, 1.8f}, 0.4f)].bsdf = 2;
    scene.shapes[addSphere(scene, {-0.45f, -0.7f, 2.3f}, 0.3f)].bsdf = 3;
    finalizeLights(scene);
    setTestCamera(scene, size, size);
    return scene;
}

}  // namespace caustica::test
