#include "caustica/scene/scene.h"

namespace caustica {

Bounds3f Scene::primitiveBounds(uint32_t primId) const {
    Bounds3f b;
    if (primId < triangles.size()) {
        const Vec3u& t = triangles[primId];
        b.extend(positions[t.x]);
        b.extend(positions[t.y]);
        b.extend(positions[t.z]);
    } else {
        const Sphere& s = spheres[primId - triangles.size()];
        b.extend(s.center - Vec3f(s.radius));
        b.extend(s.center + Vec3f(s.radius));
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
    return b;
}

}  // namespace caustica
