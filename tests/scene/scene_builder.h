// scene_builder.h — builds small scenes (meshes, spheres, cylinders, lights) for the scene,
// accel and integrator tests (test helper, host only).
#pragma once

#include <vector>

#include "caustica/scene/light_setup.h"
#include "caustica/scene/scene.h"

namespace caustica::test {

/// Appends a triangle mesh (positions and index triples local to the mesh) as a new shape.
inline uint32_t addMesh(Scene& scene, const std::vector<Vec3f>& positions,
                        const std::vector<Vec3u>& triangles, bool flipNormals = false,
                        const std::vector<Vec3f>& normals = {}) {
    const uint32_t base = uint32_t(scene.positions.size());
    const uint32_t shapeId = uint32_t(scene.shapes.size());
    Shape shape;
    shape.type = ShapeType::Mesh;
    shape.primOffset = uint32_t(scene.triangles.size());
    shape.primCount = uint32_t(triangles.size());
    shape.flipNormals = flipNormals;
    shape.hasNormals = !normals.empty();
    for (const Vec3f& p : positions) scene.positions.push_back(p);
    for (size_t i = 0; i < positions.size(); ++i) {
        scene.normals.push_back(normals.empty() ? Vec3f(0, 0, 1) : normals[i]);
        scene.uvs.push_back(Vec2f(0, 0));
    }
    for (const Vec3u& t : triangles) {
        scene.triangles.push_back({t.x + base, t.y + base, t.z + base});
        scene.triangleShape.push_back(shapeId);
    }
    scene.shapes.push_back(shape);
    return shapeId;
}

/// Appends a shape of the one primitive `prim` (a Sphere or a Cylinder, stored in `prims`) and
/// returns its shape index.
template <class Prim>
inline uint32_t addPrimitiveShape(Scene& scene, ShapeType type, std::vector<Prim>& prims,
                                  const Prim& prim, bool flipNormals) {
    const uint32_t shapeId = uint32_t(scene.shapes.size());
    Shape shape = appendPrimitiveShape(type, prims, prim, shapeId);
    shape.flipNormals = flipNormals;
    scene.shapes.push_back(shape);
    return shapeId;
}

/// Appends a sphere shape of one sphere and returns its shape index.
inline uint32_t addSphere(Scene& scene, Vec3f center, Float radius, bool flipNormals = false) {
    return addPrimitiveShape(scene, ShapeType::Sphere, scene.spheres, Sphere{center, radius},
                             flipNormals);
}

/// An open cylinder record (Frame's tangent of the axis as xAxis), owned by shape `shape`.
inline Cylinder makeCylinder(Vec3f base, Vec3f axis, Float radius, Float length,
                             uint32_t shape = 0) {
    Cylinder c;
    c.base = base;
    c.axis = normalize(axis);
    c.xAxis = Frame(c.axis).s;
    c.radius = radius;
    c.length = length;
    c.shape = shape;
    return c;
}

/// Appends a cylinder shape of one cylinder and returns its shape index.
inline uint32_t addCylinder(Scene& scene, Vec3f base, Vec3f axis, Float radius, Float length,
                            bool flipNormals = false) {
    return addPrimitiveShape(scene, ShapeType::Cylinder, scene.cylinders,
                             makeCylinder(base, axis, radius, length), flipNormals);
}

/// The camera at the origin looking along +z (the default), its film `width` x `height`, with
/// tan(half the field of view) `tanHalf` on both axes.
inline void setTestCamera(Scene& scene, int width, int height, Float tanHalf = 0.6f) {
    scene.camera.width = scene.film.width = width;
    scene.camera.height = scene.film.height = height;
    scene.camera.tanHalfX = scene.camera.tanHalfY = tanHalf;
}

inline uint32_t addAreaLight(Scene& scene, uint32_t shape, Spectrum radiance) {
    Light l;
    l.type = LightType::Area;
    l.shape = shape;
    l.radiance = radiance;
    scene.shapes[shape].light = int32_t(scene.lights.size());
    scene.lights.push_back(l);
    return uint32_t(scene.lights.size() - 1);
}

inline uint32_t addPointLight(Scene& scene, Vec3f position, Spectrum intensity) {
    Light l;
    l.type = LightType::Point;
    l.position = position;
    l.radiance = intensity;
    scene.lights.push_back(l);
    return uint32_t(scene.lights.size() - 1);
}

inline uint32_t addConstantLight(Scene& scene, Spectrum radiance) {
    Light l;
    l.type = LightType::Constant;
    l.radiance = radiance;
    scene.lights.push_back(l);
    return uint32_t(scene.lights.size() - 1);
}

/// A planar rectangle origin + s·u + t·v, (s, t) ∈ [0, 1]², split into four triangles of unequal
/// area by a fan around the interior point (fs, ft). Winding gives the normal cross(u, v).
struct RectMesh {
    Vec3f origin, u, v;
    std::vector<Vec3f> positions;
    std::vector<Vec3u> triangles;
    RectMesh(Vec3f o, Vec3f u_, Vec3f v_, Float fs = 0.2f, Float ft = 0.7f)
        : origin(o), u(u_), v(v_) {
        positions = {o, o + u, o + u + v, o + v, o + u * fs + v * ft};
        triangles = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    }
    Vec3f at(double s, double t) const { return origin + u * Float(s) + v * Float(t); }
};

/// Appends an envmap light over `w` x `h` texels (row-major, top row first) with to_world `t`.
inline uint32_t addEnvMap(Scene& scene, int w, int h, const std::vector<Spectrum>& texels,
                   const Transform& t = Transform()) {
    Light l;
    l.type = LightType::EnvMap;
    l.radiance = Spectrum(1.0f);
    for (int r = 0; r < 3; ++r) {
        l.localFromWorld[r] = Vec3f(t.mInv.m[r][0], t.mInv.m[r][1], t.mInv.m[r][2]);
        l.worldFromLocal[r] = Vec3f(t.m.m[r][0], t.m.m[r][1], t.m.m[r][2]);
    }
    l.texOffset = uint32_t(scene.lightTexels.size());
    l.texWidth = uint32_t(w);
    l.texHeight = uint32_t(h);
    scene.lightTexels.insert(scene.lightTexels.end(), texels.begin(), texels.end());
    scene.lights.push_back(l);
    return uint32_t(scene.lights.size() - 1);
}

}  // namespace caustica::test
