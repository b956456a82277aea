// interaction.h — what a ray hit: position, normals, uv and the shape's material and emitter.
#pragma once

#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"

namespace caustica {

struct SurfaceInteraction {
    Vec3f p;
    Vec3f ng;        // geometric normal, on the shape's outside (flip_normals applied)
    Vec3f ns;        // shading normal, same hemisphere as ng
    Vec2f uv;
    uint32_t primId = kNoPrimitive;
    uint32_t shape = 0;
};

/// Fills the interaction for a valid hit of `ray`.
CA_HD_INLINE SurfaceInteraction computeInteraction(const SceneView& scene, const Ray& ray, const Hit& hit) {
    SurfaceInteraction si;
    si.primId = hit.primId;
    si.p = ray.o + ray.d * hit.t;
    if (hit.primId < scene.numTriangles()) {
        const Vec3u tri = scene.triangles[hit.primId];
        const Vec3f p0 = scene.positions[tri.x], p1 = scene.positions[tri.y], p2 = scene.positions[tri.z];
        const Float b0 = 1 - hit.b1 - hit.b2;
        si.p = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;  // on the surface, not ray-distance rounded
        si.shape = scene.triangleShape[hit.primId];
        const Shape& shape = scene.shapes[si.shape];
        si.ng = normalize(cross(p1 - p0, p2 - p0));
        si.ns = si.ng;
        if (shape.hasNormals) {
            Vec3f n = scene.normals[tri.x] * b0 + scene.normals[tri.y] * hit.b1 + scene.normals[tri.z] * hit.b2;
            if (lengthSquared(n) > 0) {
                si.ns = normalize(n);
                // Mitsuba orients the geometric normal by the shading normal for meshes with normals.
                si.ng = faceForward(si.ng, si.ns);
            }
        }
        if (shape.hasUVs) {
            Vec2f uv = scene.uvs[tri.x] * b0 + scene.uvs[tri.y] * hit.b1 + scene.uvs[tri.z] * hit.b2;
            si.uv = uv;
        } else {
            si.uv = Vec2f(hit.b1, hit.b2);
        }
        if (shape.flipNormals) {
            si.ng = -si.ng;
            si.ns = -si.ns;
        }
    } else {
        const Sphere& s = scene.spheres[hit.primId - scene.numTriangles()];
        si.shape = s.shape;
        Vec3f n = normalize(si.p - s.center);
        si.p = s.center + n * s.radius;  // reproject onto the surface
        Float phi = std::atan2(n.y, n.x);
        if (phi < 0) phi += 2 * kPi;
        si.uv = Vec2f(phi * kInv2Pi, std::acos(clamp(n.z, Float(-1), Float(1))) * kInvPi);
        if (scene.shapes[s.shape].flipNormals) n = -n;
        si.ng = si.ns = n;
    }
    return si;
}

}  // namespace caustica
