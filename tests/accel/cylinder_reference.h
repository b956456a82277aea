// cylinder_reference.h — ray crossings of open cylinders in double precision, the reference of
// the cylinder intersection and cylinder light tests (test helper, host only; the cylinders
// themselves are built by scene/scene_builder.h).
#pragma once

#include <cmath>

#include "caustica/scene/scene.h"

namespace caustica::test {

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
