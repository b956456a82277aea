// shape.h — shapes as the kernels see them: flat records pointing into global primitive arrays.
#pragma once

#include <cstdint>

#include "caustica/util/math.h"

namespace caustica {

enum class ShapeType : uint32_t { Mesh, Sphere, Cylinder };

/// One shape of the scene. A mesh owns triangles [primOffset, primOffset + primCount) of the
/// global triangle array; a sphere owns sphere record primOffset (primCount = 1), a cylinder
/// cylinder record primOffset.
struct Shape {
    ShapeType type = ShapeType::Mesh;
    uint32_t primOffset = 0;
    uint32_t primCount = 0;
    uint32_t bsdf = 0;          // index into SceneView::bsdfs
    int32_t light = -1;         // index into SceneView::lights when the shape emits, else -1
    bool hasNormals = false;    // per-vertex shading normals present (mesh)
    bool hasUVs = false;        // per-vertex texture coordinates present (mesh)
    bool flipNormals = false;   // Mitsuba's flip_normals: the surface's outside is the other side
};

/// An analytic sphere (Mitsuba's sphere shape), world space. uv and dp/du, dp/dv are Mitsuba's,
/// taken in object space: the object axes' world directions `objectX/Y/Z` are to_world's linear
/// part divided by the radius (orthonormal; a left-handed triple when to_world mirrors). Normals
/// point outwards unless the shape flips them.
struct Sphere {
    Vec3f center;
    Float radius = 1;
    uint32_t shape = 0;  // index into SceneView::shapes
    Vec3f objectX{1, 0, 0}, objectY{0, 1, 0}, objectZ{0, 0, 1};
};

/// An analytic open cylinder (Mitsuba's cylinder: no caps), world space: the points at distance
/// `radius` from the segment base + [0, length] * axis. uv = (φ / 2π, height / length), φ measured
/// from `xAxis` towards cross(axis, xAxis). Normals point away from the axis unless the shape
/// flips them.
struct Cylinder {
    Vec3f base;
    Float radius = 1;
    Vec3f axis{0, 0, 1};   // unit
    Float length = 1;
    Vec3f xAxis{1, 0, 0};  // unit, perpendicular to axis
    uint32_t shape = 0;    // index into SceneView::shapes
};

}  // namespace caustica
