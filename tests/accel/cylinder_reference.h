// cylinder_reference.h — builders of open cylinders and their ray crossings in double precision,
// the reference of the cylinder intersection and cylinder light tests (test helper, host only).
#pragma once

#include <cmath>
#include <cstdint>

#include "caustica/scene/scene.h"

namespace caustica::test {

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
    const uint32_t shapeId = uint32_t(scene.shapes.size());
    Shape shape;
    shape.type = ShapeType::Cylinder;
    shape.primOffset = uint32_t(scene.cylinders.size());
    shape.primCount = 1;
    shape.flipNormals = flipNormals;
    scene.cylinders.push_back(makeCylinder(base, axis, radius, length, shapeId));
    scene.shapes.push_back(shape);
    return shapeId;
}

/// The line o + t d against the infinite cylinder around c's axis, in double: the roots t of
/// |f + t p|² = r², where f and p are o - base and d with their components along the axis
/// removed, and the heights fa + t da along the axis.
struct CylinderRoots {
    int count = 0;  // 0 (missed, or d along the axis) or 2 (ascending; equal when tangent)
    double t[2] = {0, 0};
    double f[3], p[3];  // o - base and d, off the axis
    double fa = 0, da = 0;

    CylinderRoots(const Cylinder& c, Vec3f o, Vec3f d) {
        const double ax[3] = {c.axis.x, c.axis.y, c.axis.z};
        const double fo[3] = {double(o.x) - c.base.x, double(o.y) - c.base.y,
                              double(o.z) - c.base.z};
        const double dd[3] = {d.x, d.y, d.z};
        fa = fo[0] * ax[0] + fo[1] * ax[1] + fo[2] * ax[2];
        da = dd[0] * ax[0] + dd[1] * ax[1] + dd[2] * ax[2];
        for (int k = 0; k < 3; ++k) {
            f[k] = fo[k] - ax[k] * fa;
            p[k] = dd[k] - ax[k] * da;
        }
        const double a = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        const double b = 2 * (f[0] * p[0] + f[1] * p[1] + f[2] * p[2]);
        const double cc = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - double(c.radius) * c.radius;
        const double disc = b * b - 4 * a * cc;
        if (!(a > 0) || disc < 0) return;
        count = 2;
        t[0] = (-b - std::sqrt(disc)) / (2 * a);
        t[1] = (-b + std::sqrt(disc)) / (2 * a);
    }
    /// Height along the axis of root i.
    double height(int i) const { return fa + da * t[i]; }
};

}  // namespace caustica::test
