// shape_geometry.h — what a shape plugin produces (a world-space mesh, an analytic sphere or an
// analytic cylinder) and the checks that turn Mitsuba's transforms into the analytic records.
#pragma once

#include "caustica/io/mesh/triangle_mesh.h"
#include "caustica/io/mitsuba/params.h"
#include "caustica/scene/shape.h"

namespace caustica::mitsuba {

struct ShapeGeometry {
    enum class Kind { Mesh, Sphere, Cylinder };
    Kind kind = Kind::Mesh;
    meshio::TriangleMesh mesh;
    Sphere sphere;
    Cylinder cylinder;
    bool mirrored = false;  // sphere: to_world mirrors, which turns Mitsuba's normals inwards
};

/// Mitsuba 3's sphere under `t` = to_world * translate(center) * scale(radius): `t` must be a
/// similarity (rotation, uniform scale, translation); a mirroring one flips the normals.
ShapeGeometry makeSphereGeometry(const Params& p, const Transform& t);

/// Mitsuba 3's cylinder: to_world * translate(p0) * to_frame(Frame((p1 - p0) / |p1 - p0|)) *
/// scale(radius, radius, |p1 - p0|). `toWorld` may scale, but not shear, mirror or scale the two
/// radial directions differently (Mitsuba only warns there; caustica refuses).
ShapeGeometry makeCylinderGeometry(const Params& p, const Transform& toWorld, Vec3f p0, Vec3f p1,
                                   Float radius);

}  // namespace caustica::mitsuba
