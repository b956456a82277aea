#include "caustica/scene/scene.h"

namespace caustica {

/// The smallest box around the cylinder's two end circles (Mitsuba's Cylinder::bbox): a circle
/// of radius r around unit axis a extends r * sqrt(1 - a_i²) along axis i.
Bounds3f cylinderBounds(const Cylinder& c) {
    const Vec3f a = c.axis;
    const Vec3f ext(c.radius * safeSqrt(1 - a.x * a.x), c.radius * safeSqrt(1 - a.y * a.y),
                    c.radius * safeSqrt(1 - a.z * a.z));
    const Vec3f top = c.base + a * c.length;
    Bounds3f b;
    b.extend(c.base - ext);
    b.extend(c.base + ext);
    b.extend(top - ext);
    b.extend(top + ext);
    return b;
}

Bounds3f Scene::primitiveBounds(uint32_t primId) const {
    Bounds3f b;
    if (primId < triangles.size()) {
        const Vec3u& t = triangles[primId];
        b.extend(positions[t.x]);
        b.extend(positions[t.y]);
        b.extend(positions[t.z]);
    } else if (primId < triangles.size() + spheres.size()) {
        const Sphere& s = spheres[primId - triangles.size()];
        b.extend(s.center - Vec3f(s.radius));
        b.extend(s.center + Vec3f(s.radius));
    } else {
        b = cylinderBounds(cylinders[primId - triangles.size() - spheres.size()]);
    }
    return b;
}

Bounds3f Scene::bounds() const {
    Bounds3f b;
    for (const Vec3f& p : positions) b.extend(p);
    for (const Sphere& s : spheres) {
        b.extend(s.center - Vec3f(s.radius));
        b.extend(s.center + Vec3f(s.radius));
    }
    for (const Cylinder& c : cylinders) {
        const Bounds3f cb = cylinderBounds(c);
        b.extend(cb.lo);
        b.extend(cb.hi);
    }
    return b;
}

void reserveVertexPadding(Scene& scene) {
    if (scene.positions.capacity() <= scene.positions.size())
        scene.positions.reserve(scene.positions.size() + 1);
}

}  // namespace caustica
