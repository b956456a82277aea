// shape_geometry.cpp — analytic sphere and cylinder records from Mitsuba's parameters.
#include "caustica/io/mitsuba/shape_geometry.h"

#include <cmath>

namespace caustica::mitsuba {

ShapeGeometry makeSphereGeometry(const Params& p, const Transform& t) {
    Vec3f col[3];
    for (int c = 0; c < 3; ++c) col[c] = Vec3f(t.m.m[0][c], t.m.m[1][c], t.m.m[2][c]);
    const Float s = length(col[0]);
    const Float tol = 1e-4f * s * s;
    for (int c = 1; c < 3; ++c)
        if (std::fabs(lengthSquared(col[c]) - s * s) > tol)
            p.fail("to_world must scale uniformly (a sphere cannot become an ellipsoid)");
    if (std::fabs(dot(col[0], col[1])) > tol || std::fabs(dot(col[0], col[2])) > tol ||
        std::fabs(dot(col[1], col[2])) > tol)
        p.fail("to_world must not shear a sphere");
    if (t.m.m[3][0] != 0 || t.m.m[3][1] != 0 || t.m.m[3][2] != 0 || t.m.m[3][3] != 1)
        p.fail("to_world must be affine for a sphere");
    ShapeGeometry g;
    g.kind = ShapeGeometry::Kind::Sphere;
    g.sphere.center = t.applyPoint(Vec3f(0));
    g.sphere.radius = s;
    if (!isFinite(g.sphere.center) || !std::isfinite(s) || !(s > 0))
        p.fail("sphere is not finite or has zero radius");
    g.sphere.objectX = col[0] / s;  // to_object's rows: the uv frame
    g.sphere.objectY = col[1] / s;
    g.sphere.objectZ = col[2] / s;
    g.mirrored = dot(cross(col[0], col[1]), col[2]) < 0;
    return g;
}

ShapeGeometry makeCylinderGeometry(const Params& p, const Transform& toWorld, Vec3f p0, Vec3f p1,
                                   Float radius) {
    const Vec3f d = p1 - p0;
    const Float len = length(d);
    if (!(len > 0) || !std::isfinite(len)) p.fail("p0 and p1 must differ (the cylinder's axis)");
    const Frame frame(d / len);
    const Transform& t = toWorld;
    if (t.m.m[3][0] != 0 || t.m.m[3][1] != 0 || t.m.m[3][2] != 0 || t.m.m[3][3] != 1)
        p.fail("to_world must be affine for a cylinder");
    // The images of the local frame's radial and axial edges.
    const Vec3f x = t.applyVector(frame.s * radius), y = t.applyVector(frame.t * radius);
    const Vec3f z = t.applyVector(d);
    const Float r = length(x), tol = 1e-4f;
    if (std::fabs(length(y) - r) > tol * r)
        p.fail("to_world must scale the cylinder's cross-section uniformly (no ellipses)");
    const Float lz = length(z);
    if (std::fabs(dot(x, y)) > tol * r * r || std::fabs(dot(x, z)) > tol * r * lz ||
        std::fabs(dot(y, z)) > tol * r * lz)
        p.fail("to_world must not shear a cylinder");
    if (dot(cross(x, y), z) < 0)
        p.fail("to_world must not mirror a cylinder (Mitsuba's result is ill-defined there)");
    ShapeGeometry g;
    g.kind = ShapeGeometry::Kind::Cylinder;
    Cylinder& c = g.cylinder;
    c.base = t.applyPoint(p0);
    c.radius = r;
    c.length = lz;
    c.axis = z / lz;
    c.xAxis = x / r;
    if (!isFinite(c.base) || !std::isfinite(r) || !std::isfinite(lz) || !(r > 0) || !(lz > 0))
        p.fail("cylinder is not finite or has zero size after to_world");
    return g;
}

}  // namespace caustica::mitsuba
